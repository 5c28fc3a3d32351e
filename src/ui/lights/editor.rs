//! One `[[lights]]` entry, edited as its typed value: every key of its
//! kind (the contract's table, plus `range` and the shadow-map keys).
//!
//! No widget clamps: a value typed or dragged out of range reaches the
//! caller, which validates the entry as the scene file does and shows the
//! file's message instead of applying it: a bad value is refused with a
//! message, never silently clamped.

use super::kinds;
use crate::base::ColorValue;
use crate::scene::scene_file::LightEntry;
use crate::scene::scene_file::schema::AreaEntry;
use crate::scene::{ShadowFilter, ShadowSettings, area_light};
use crate::ui::panels::widgets::triple_array;
use egui::SliderClamping;
use glam::DVec3;

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
        changed |= placement_and_power(ui, entry);
        changed |= kind_specific(ui, &id, entry);
        changed |= shadow_keys(ui, &id, entry, effective);
    });
    changed
}

/// Position and direction (or normal), and the emitted power with its
/// unit.
fn placement_and_power(ui: &mut egui::Ui, entry: &mut LightEntry) -> bool {
    let (vectors, power_key, power): (Vec<(&str, &mut [f64; 3])>, &str, &mut ColorValue) =
        match entry {
            LightEntry::Point(e) => (
                vec![("position", &mut e.position)],
                "intensity W/sr",
                &mut e.intensity,
            ),
            LightEntry::Directional(e) => (
                vec![("direction", &mut e.direction)],
                "irradiance W/m²",
                &mut e.irradiance,
            ),
            LightEntry::Spot(e) => (
                vec![
                    ("position", &mut e.position),
                    ("direction", &mut e.direction),
                ],
                "intensity W/sr",
                &mut e.intensity,
            ),
            LightEntry::Area(e) => (
                vec![("position", &mut e.position), ("normal", &mut e.normal)],
                "radiance W/(m²·sr)",
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
        *power = ColorValue::Rgb(p);
        changed = true;
    }
    ui.end_row();
    changed
}

/// A point or spot light's range, a spot's cones, an area light's shape,
/// size, tangent and sample count.
fn kind_specific(ui: &mut egui::Ui, id: &dyn Fn(&str) -> String, entry: &mut LightEntry) -> bool {
    let mut changed = false;
    match entry {
        LightEntry::Point(e) => changed |= range(ui, &mut e.range),
        LightEntry::Spot(e) => {
            // glTF's defaults: inner 0, outer π/4.
            for (key, cone, default) in [
                ("inner_cone_deg", &mut e.inner_cone_deg, 0.0),
                ("outer_cone_deg", &mut e.outer_cone_deg, 45.0),
            ] {
                ui.label(key);
                let mut v = cone.unwrap_or(default);
                let slider = egui::Slider::new(&mut v, 0.0..=90.0).clamping(SliderClamping::Never);
                if ui.add(slider).changed() {
                    *cone = Some(v);
                    changed = true;
                }
                ui.end_row();
            }
            changed |= range(ui, &mut e.range);
        }
        LightEntry::Area(e) => changed |= area_keys(ui, id, e),
        LightEntry::Directional(_) => {}
    }
    changed
}

/// `range` (glTF's cut-off distance): unset means none.
fn range(ui: &mut egui::Ui, range: &mut Option<f64>) -> bool {
    let mut changed = false;
    ui.label("range m");
    ui.horizontal(|ui| {
        let mut on = range.is_some();
        if ui
            .checkbox(&mut on, "")
            .on_hover_text("beyond it the light gives nothing (glTF's range window); off: none")
            .changed()
        {
            *range = on.then_some(10.0);
            changed = true;
        }
        if let Some(r) = range {
            changed |= ui
                .add(egui::DragValue::new(r).speed(0.05).max_decimals(4))
                .changed();
        }
    });
    ui.end_row();
    changed
}

fn area_keys(ui: &mut egui::Ui, id: &dyn Fn(&str) -> String, e: &mut AreaEntry) -> bool {
    let mut changed = false;
    ui.label("shape");
    let mut shape = e.shape.clone();
    egui::ComboBox::from_id_salt(id("shape"))
        .selected_text(shape.clone())
        .show_ui(ui, |ui| {
            for s in ["rect", "disk"] {
                ui.selectable_value(&mut shape, s.to_string(), s);
            }
        })
        .response
        .on_hover_text("changing the shape keeps the area, so the emitted power");
    if shape != e.shape {
        kinds::reshape(e, &shape);
        changed = true;
    }
    ui.end_row();
    if e.shape == "disk" {
        ui.label("radius m");
        let mut r = e.radius.unwrap_or(0.5);
        if ui
            .add(egui::DragValue::new(&mut r).speed(0.01).max_decimals(4))
            .changed()
        {
            e.radius = Some(r);
            changed = true;
        }
    } else {
        ui.label("size m (w, h)");
        let mut size = e.size.unwrap_or([1.0, 1.0]);
        let mut edited = false;
        ui.horizontal(|ui| {
            for v in size.iter_mut() {
                edited |= ui
                    .add(egui::DragValue::new(v).speed(0.01).max_decimals(4))
                    .changed();
            }
        });
        if edited {
            e.size = Some(size);
            changed = true;
        }
    }
    ui.end_row();
    ui.label("tangent").on_hover_text(
        "direction of the rectangle's width (of a disk's sample pattern); unset: any direction across the normal",
    );
    let normal = DVec3::from_array(e.normal);
    let mut t = e
        .tangent
        .unwrap_or_else(|| crate::base::any_tangent(normal.normalize_or_zero()).to_array());
    if triple_array(ui, &mut t, 0.02) {
        e.tangent = Some(t);
        changed = true;
    }
    ui.end_row();
    ui.label("samples N")
        .on_hover_text("point lights that stand in for it");
    let mut n = e.samples.unwrap_or(area_light::DEFAULT_SAMPLES);
    let slider = egui::Slider::new(&mut n, 1..=area_light::MAX_SAMPLES)
        .logarithmic(true)
        .clamping(SliderClamping::Never);
    if ui.add(slider).changed() {
        e.samples = Some(n);
        changed = true;
    }
    ui.end_row();
    changed
}

/// `shadows` and the shadow-map keys (written into the entry's own keys);
/// an area light's `shadow_per_sample`.
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
    if let LightEntry::Area(e) = entry {
        ui.label("shadow per sample").on_hover_text(
            "GPU: one shadow cube map per sample (soft, 6N layers) instead of one at the centre shared by all (hard)",
        );
        changed |= ui.checkbox(&mut e.shadow_per_sample, "").changed();
        ui.end_row();
    }
    let mut keys = entry.shadow_keys();
    let before = keys.clone();
    ui.label("map size");
    egui::ComboBox::from_id_salt(id("map"))
        .selected_text(effective.map_size.to_string())
        .show_ui(ui, |ui| {
            for s in [256, 512, 1024, 2048, 4096, 8192] {
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
        let slider = egui::Slider::new(&mut kernel, 1..=ShadowSettings::MAX_PCF_KERNEL)
            .step_by(2.0)
            .clamping(SliderClamping::Never);
        if ui.add(slider).changed() {
            keys.pcf_kernel = Some(kernel);
        }
        ui.end_row();
    }
    for (label, key, value, speed, hover) in [
        (
            "bias m",
            &mut keys.bias,
            effective.bias,
            1e-4,
            "constant depth bias along the light ray",
        ),
        (
            "slope bias texels",
            &mut keys.slope_bias,
            effective.slope_bias,
            0.05,
            "adds slope_bias · texel · tanθ",
        ),
        (
            "normal offset texels",
            &mut keys.normal_offset,
            effective.normal_offset,
            0.05,
            "the map is read this many texels along the normal (default k/√2 + ½ for a k × k kernel: docs/shadows.md)",
        ),
    ] {
        ui.label(label).on_hover_text(hover);
        let mut v = value;
        if ui
            .add(egui::DragValue::new(&mut v).speed(speed).max_decimals(5))
            .changed()
        {
            *key = Some(v);
        }
        ui.end_row();
    }
    if keys != before {
        entry.set_shadow_keys(keys);
        changed = true;
    }
    changed
}
