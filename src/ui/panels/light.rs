//! The lights section: one `[[lights]]` entry, edited as its typed value.

use super::triple_array;
use crate::base::ColorValue;
use crate::scene::scene_file::LightEntry;
use crate::scene::{ShadowFilter, ShadowSettings, area_light};

/// Edits one `[[lights]]` entry of the scene file in place; `effective`
/// is the shadow settings it renders with (its own keys over `[shadows]`
/// over the defaults), shown where the entry sets no key. Returns whether
/// anything changed.
pub fn light_editor(
    ui: &mut egui::Ui,
    index: usize,
    entry: &mut LightEntry,
    effective: ShadowSettings,
) -> bool {
    let mut changed = false;
    let id = |k: &str| format!("light{index}.{k}");
    egui::Grid::new(id("grid")).num_columns(2).show(ui, |ui| {
        ui.label("kind");
        ui.label(entry.kind());
        ui.end_row();
        changed |= placement_and_power(ui, entry);
        changed |= kind_specific(ui, entry);
        changed |= shadow_keys(ui, &id, entry, effective);
    });
    changed
}

/// Position and direction (or normal), and the emitted power.
fn placement_and_power(ui: &mut egui::Ui, entry: &mut LightEntry) -> bool {
    let (vectors, power_key, power): (Vec<(&str, &mut [f64; 3])>, &str, &mut ColorValue) =
        match entry {
            LightEntry::Point(e) => (
                vec![("position", &mut e.position)],
                "intensity",
                &mut e.intensity,
            ),
            LightEntry::Directional(e) => (
                vec![("direction", &mut e.direction)],
                "irradiance",
                &mut e.irradiance,
            ),
            LightEntry::Spot(e) => (
                vec![
                    ("position", &mut e.position),
                    ("direction", &mut e.direction),
                ],
                "intensity",
                &mut e.intensity,
            ),
            LightEntry::Area(e) => (
                vec![("position", &mut e.position), ("normal", &mut e.normal)],
                "radiance",
                &mut e.radiance,
            ),
        };
    let mut changed = false;
    for (key, v) in vectors {
        ui.label(key);
        changed |= triple_array(ui, v, 0.02);
        ui.end_row();
    }
    ui.label(power_key);
    let mut p = power.rgb().to_array();
    if triple_array(ui, &mut p, 0.05) {
        *power = ColorValue::Rgb(p.map(|c| c.max(0.0)));
        changed = true;
    }
    ui.end_row();
    changed
}

/// A spot light's cones, an area light's sample count.
fn kind_specific(ui: &mut egui::Ui, entry: &mut LightEntry) -> bool {
    let mut changed = false;
    match entry {
        LightEntry::Spot(e) => {
            // glTF's defaults: inner 0, outer π/4.
            for (key, cone, default) in [
                ("inner_cone_deg", &mut e.inner_cone_deg, 0.0),
                ("outer_cone_deg", &mut e.outer_cone_deg, 45.0),
            ] {
                ui.label(key);
                let mut v = cone.unwrap_or(default);
                if ui.add(egui::Slider::new(&mut v, 0.0..=90.0)).changed() {
                    *cone = Some(v);
                    changed = true;
                }
                ui.end_row();
            }
        }
        LightEntry::Area(e) => {
            ui.label("samples N");
            let mut n = e.samples.unwrap_or(area_light::DEFAULT_SAMPLES);
            if ui
                .add(egui::Slider::new(&mut n, 1..=256).logarithmic(true))
                .changed()
            {
                e.samples = Some(n);
                changed = true;
            }
            ui.end_row();
        }
        LightEntry::Point(_) | LightEntry::Directional(_) => {}
    }
    changed
}

/// `shadows` and the shadow-map keys (written into the entry's own keys).
fn shadow_keys(
    ui: &mut egui::Ui,
    id: &dyn Fn(&str) -> String,
    entry: &mut LightEntry,
    effective: ShadowSettings,
) -> bool {
    let mut changed = false;
    ui.label("shadows");
    let mut on = entry.shadows();
    if ui.checkbox(&mut on, "").changed() {
        entry.set_shadows(on);
        changed = true;
    }
    ui.end_row();
    if !on {
        return changed;
    }
    let mut keys = entry.shadow_keys();
    let before = keys.clone();
    ui.label("map size");
    egui::ComboBox::from_id_salt(id("map"))
        .selected_text(effective.map_size.to_string())
        .show_ui(ui, |ui| {
            for s in [256, 512, 1024, 2048, 4096] {
                if ui
                    .selectable_label(s == effective.map_size, s.to_string())
                    .clicked()
                {
                    keys.map_size = Some(s);
                }
            }
        });
    ui.end_row();
    ui.label("filter");
    let filter = effective.filter.name();
    egui::ComboBox::from_id_salt(id("filter"))
        .selected_text(filter)
        .show_ui(ui, |ui| {
            for f in ["none", "pcf"] {
                if ui.selectable_label(f == filter, f).clicked() {
                    keys.filter = Some(f.into());
                }
            }
        });
    ui.end_row();
    if let ShadowFilter::Pcf { mut kernel } = effective.filter {
        ui.label("PCF kernel");
        if ui
            .add(egui::Slider::new(&mut kernel, 1..=9).step_by(2.0))
            .changed()
        {
            keys.pcf_kernel = Some(kernel);
        }
        ui.end_row();
    }
    ui.label("bias (m)");
    let mut b = effective.bias;
    if ui
        .add(egui::DragValue::new(&mut b).speed(1e-4).range(0.0..=1.0))
        .changed()
    {
        keys.bias = Some(b);
    }
    ui.end_row();
    ui.label("slope bias (texels)");
    let mut b = effective.slope_bias;
    if ui
        .add(egui::DragValue::new(&mut b).speed(0.05).range(0.0..=100.0))
        .changed()
    {
        keys.slope_bias = Some(b);
    }
    ui.end_row();
    if keys != before {
        entry.set_shadow_keys(keys);
        changed = true;
    }
    changed
}
