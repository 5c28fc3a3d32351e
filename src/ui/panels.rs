//! The side panel's sections: material, lights, view. Each edits a copy
//! and hands back what changed; the caller validates and applies it, so a
//! value the renderer rejects becomes a message, never a crash.

use crate::material::presets::PRESETS;
use crate::material::terms::{Denominator, Distribution, Fresnel, Geometry};
use crate::material::{Material, ReflectanceModel};
use crate::scene::{Rgb, ShadingMode};
use toml::Value;

/// Edits `m` in place; returns whether anything changed.
pub fn material_editor(ui: &mut egui::Ui, m: &mut Material) -> bool {
    let mut changed = false;
    egui::Grid::new("material").num_columns(2).show(ui, |ui| {
        ui.label("model");
        changed |= combo(ui, "model", &mut m.model, ReflectanceModel::ALL, |v| {
            v.name()
        });
        ui.end_row();
        if m.model == ReflectanceModel::CookTorrance {
            ui.label("distribution D");
            changed |= combo(
                ui,
                "dist",
                &mut m.distribution,
                Distribution::ALL.iter().copied(),
                |v| v.name(),
            );
            ui.end_row();
            ui.label("geometry G");
            changed |= combo(
                ui,
                "geom",
                &mut m.geometry,
                Geometry::ALL.iter().copied(),
                |v| v.name(),
            );
            ui.end_row();
            ui.label("denominator");
            changed |= combo(
                ui,
                "denom",
                &mut m.denominator,
                Denominator::ALL.iter().copied(),
                |v| v.name(),
            );
            ui.end_row();
        }
        if matches!(
            m.model,
            ReflectanceModel::CookTorrance | ReflectanceModel::Mirror
        ) {
            ui.label("Fresnel F");
            changed |= combo(
                ui,
                "fresnel",
                &mut m.fresnel,
                Fresnel::ALL.iter().copied(),
                |v| v.name(),
            );
            ui.end_row();
        }
        for (label, value) in [
            ("k_a", &mut m.k_a),
            ("k_d", &mut m.k_d),
            ("k_s", &mut m.k_s),
        ] {
            ui.label(label);
            changed |= color(ui, value);
            ui.end_row();
        }
        let lobe = |model| {
            matches!(
                model,
                ReflectanceModel::Phong
                    | ReflectanceModel::PhongNormalized
                    | ReflectanceModel::BlinnPhong
                    | ReflectanceModel::BlinnPhongNormalized
            )
        };
        if lobe(m.model) {
            ui.label("k_e");
            changed |= log_slider(ui, &mut m.k_e, 1e-2..=1e6);
            ui.end_row();
        }
        if m.model == ReflectanceModel::CookTorrance {
            ui.label("roughness m");
            changed |= log_slider(ui, &mut m.roughness, 1e-4..=1.0);
            ui.end_row();
        }
        if matches!(
            m.model,
            ReflectanceModel::Ward | ReflectanceModel::WardAnisotropic
        ) {
            ui.label("σ_x");
            changed |= log_slider(ui, &mut m.sigma_x, 1e-4..=1.0);
            ui.end_row();
            if m.model == ReflectanceModel::WardAnisotropic {
                ui.label("σ_y");
                changed |= log_slider(ui, &mut m.sigma_y, 1e-4..=1.0);
                ui.end_row();
            } else if m.sigma_y != m.sigma_x {
                m.sigma_y = m.sigma_x;
                changed = true;
            }
        }
        if matches!(
            m.model,
            ReflectanceModel::CookTorrance | ReflectanceModel::Mirror
        ) {
            ui.label("η (R G B)");
            changed |= triple(ui, &mut m.eta, 0.005, 0.0..=50.0);
            ui.end_row();
            ui.label("κ (R G B)");
            changed |= triple(ui, &mut m.kappa, 0.005, 0.0..=50.0);
            ui.end_row();
            ui.label("η_i, η_t");
            ui.horizontal(|ui| {
                changed |= ui
                    .add(
                        egui::DragValue::new(&mut m.eta_i)
                            .speed(0.005)
                            .range(0.01..=10.0),
                    )
                    .changed();
                changed |= ui
                    .add(
                        egui::DragValue::new(&mut m.eta_t)
                            .speed(0.005)
                            .range(0.01..=10.0),
                    )
                    .changed();
            });
            ui.end_row();
            ui.label("preset");
            egui::ComboBox::from_id_salt("preset")
                .selected_text("apply…")
                .show_ui(ui, |ui| {
                    for (name, preset) in PRESETS {
                        if ui.selectable_label(false, *name).clicked() {
                            preset.apply(m);
                            changed = true;
                        }
                    }
                });
            ui.end_row();
        }
    });
    changed
}

/// A light-entry edit: `(key, TOML value)` for `lights.N.key`.
pub type LightEdit = (String, String);

/// Edits one `[[lights]]` entry of the scene file; returns the first
/// change as a key and its new value.
pub fn light_editor(ui: &mut egui::Ui, index: usize, entry: &toml::Table) -> Option<LightEdit> {
    let mut edit = None;
    let kind = entry.get("kind").and_then(Value::as_str).unwrap_or("?");
    let id = |k: &str| format!("light{index}.{k}");
    egui::Grid::new(id("grid")).num_columns(2).show(ui, |ui| {
        ui.label("kind");
        ui.label(kind);
        ui.end_row();
        let vector_keys: &[&str] = match kind {
            "point" => &["position"],
            "directional" => &["direction"],
            "spot" => &["position", "direction"],
            "area" => &["position", "normal"],
            _ => &[],
        };
        for key in vector_keys {
            ui.label(*key);
            let mut v = read_vec(entry.get(*key), [0.0; 3]);
            if triple_array(ui, &mut v, 0.02) {
                edit = Some((key.to_string(), format_vec(v)));
            }
            ui.end_row();
        }
        let power_key = match kind {
            "directional" => "irradiance",
            "area" => "radiance",
            _ => "intensity",
        };
        ui.label(power_key);
        let mut p = read_vec(entry.get(power_key), [1.0; 3]);
        if triple_array(ui, &mut p, 0.05) {
            edit = Some((power_key.into(), format_vec(p.map(|c| c.max(0.0)))));
        }
        ui.end_row();
        if kind == "spot" {
            for key in ["inner_cone_deg", "outer_cone_deg"] {
                ui.label(key);
                let mut v = read_f64(
                    entry.get(key),
                    if key == "inner_cone_deg" { 0.0 } else { 45.0 },
                );
                if ui.add(egui::Slider::new(&mut v, 0.0..=90.0)).changed() {
                    edit = Some((key.into(), format!("{v}")));
                }
                ui.end_row();
            }
        }
        if kind == "area" {
            ui.label("samples N");
            let mut n = entry
                .get("samples")
                .and_then(Value::as_integer)
                .unwrap_or(16);
            if ui
                .add(egui::Slider::new(&mut n, 1..=256).logarithmic(true))
                .changed()
            {
                edit = Some(("samples".into(), n.to_string()));
            }
            ui.end_row();
        }
        ui.label("shadows");
        let mut on = entry
            .get("shadows")
            .and_then(Value::as_bool)
            .unwrap_or(false);
        if ui.checkbox(&mut on, "").changed() {
            edit = Some(("shadows".into(), on.to_string()));
        }
        ui.end_row();
        if on {
            ui.label("map size");
            let size = entry
                .get("shadow_map_size")
                .and_then(Value::as_integer)
                .unwrap_or(2048);
            egui::ComboBox::from_id_salt(id("map"))
                .selected_text(size.to_string())
                .show_ui(ui, |ui| {
                    for s in [256, 512, 1024, 2048, 4096] {
                        if ui.selectable_label(s == size, s.to_string()).clicked() {
                            edit = Some(("shadow_map_size".into(), s.to_string()));
                        }
                    }
                });
            ui.end_row();
            ui.label("filter");
            let filter = entry
                .get("shadow_filter")
                .and_then(Value::as_str)
                .unwrap_or("pcf");
            egui::ComboBox::from_id_salt(id("filter"))
                .selected_text(filter)
                .show_ui(ui, |ui| {
                    for f in ["none", "pcf"] {
                        if ui.selectable_label(f == filter, f).clicked() {
                            edit = Some(("shadow_filter".into(), format!("\"{f}\"")));
                        }
                    }
                });
            ui.end_row();
            if filter == "pcf" {
                ui.label("PCF kernel");
                let mut k = entry
                    .get("shadow_pcf_kernel")
                    .and_then(Value::as_integer)
                    .unwrap_or(3);
                if ui
                    .add(egui::Slider::new(&mut k, 1..=9).step_by(2.0))
                    .changed()
                {
                    edit = Some(("shadow_pcf_kernel".into(), k.to_string()));
                }
                ui.end_row();
            }
            ui.label("bias (m)");
            let mut b = read_f64(entry.get("shadow_bias"), 0.0);
            if ui
                .add(egui::DragValue::new(&mut b).speed(1e-4).range(0.0..=1.0))
                .changed()
            {
                edit = Some(("shadow_bias".into(), format!("{b}")));
            }
            ui.end_row();
            ui.label("slope bias (texels)");
            let mut b = read_f64(entry.get("shadow_slope_bias"), 0.0);
            if ui
                .add(egui::DragValue::new(&mut b).speed(0.05).range(0.0..=100.0))
                .changed()
            {
                edit = Some(("shadow_slope_bias".into(), format!("{b}")));
            }
            ui.end_row();
        }
    });
    edit
}

/// Shading mode selector.
pub fn shading_mode(ui: &mut egui::Ui, mode: &mut ShadingMode) -> bool {
    combo(ui, "shading", mode, ShadingMode::ALL, |m| m.name())
}

/// A radiance triple with non-negative components.
pub fn radiance(ui: &mut egui::Ui, value: &mut Rgb) -> bool {
    triple(ui, value, 0.005, 0.0..=1e6)
}

fn combo<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    id: &str,
    value: &mut T,
    all: impl IntoIterator<Item = T>,
    name: impl Fn(T) -> &'static str,
) -> bool {
    let mut changed = false;
    egui::ComboBox::from_id_salt(id)
        .selected_text(name(*value))
        .show_ui(ui, |ui| {
            for v in all {
                if ui.selectable_label(v == *value, name(v)).clicked() && v != *value {
                    *value = v;
                    changed = true;
                }
            }
        });
    changed
}

/// A logarithmic slider for a positive parameter.
fn log_slider(ui: &mut egui::Ui, value: &mut f64, range: std::ops::RangeInclusive<f64>) -> bool {
    ui.add(egui::Slider::new(value, range).logarithmic(true))
        .changed()
}

/// A linear RGB reflectance: colour picker (shown in sRGB) and exact values.
fn color(ui: &mut egui::Ui, value: &mut Rgb) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        let mut srgb = value
            .to_array()
            .map(|c| crate::output::write::srgb_encode(c.clamp(0.0, 1.0)) as f32);
        if ui.color_edit_button_rgb(&mut srgb).changed() {
            *value = Rgb::from_array(srgb.map(|c| srgb_decode(c as f64)));
            changed = true;
        }
        changed |= triple(ui, value, 0.005, 0.0..=1.0);
    });
    changed
}

fn triple(
    ui: &mut egui::Ui,
    value: &mut Rgb,
    speed: f64,
    range: std::ops::RangeInclusive<f64>,
) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        for c in [&mut value.x, &mut value.y, &mut value.z] {
            changed |= ui
                .add(
                    egui::DragValue::new(c)
                        .speed(speed)
                        .range(range.clone())
                        .max_decimals(4),
                )
                .changed();
        }
    });
    changed
}

fn triple_array(ui: &mut egui::Ui, value: &mut [f64; 3], speed: f64) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        for c in value.iter_mut() {
            changed |= ui
                .add(egui::DragValue::new(c).speed(speed).max_decimals(4))
                .changed();
        }
    });
    changed
}

fn read_vec(v: Option<&Value>, default: [f64; 3]) -> [f64; 3] {
    let num = |v: &Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
    match v {
        Some(Value::Array(a)) if a.len() == 3 => {
            let mut out = default;
            for (o, x) in out.iter_mut().zip(a) {
                *o = num(x).unwrap_or(*o);
            }
            out
        }
        Some(x) => num(x).map(|g| [g; 3]).unwrap_or(default),
        None => default,
    }
}

fn read_f64(v: Option<&Value>, default: f64) -> f64 {
    v.and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        .unwrap_or(default)
}

fn format_vec(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

/// Inverse of the sRGB transfer function.
fn srgb_decode(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips() {
        for v in [0.0, 0.001, 0.2, 0.5, 1.0] {
            let back = srgb_decode(crate::output::write::srgb_encode(v));
            assert!((back - v).abs() < 1e-12, "{v} → {back}");
        }
    }

    #[test]
    fn light_values_read_scalars_and_triples() {
        let t: toml::Table = "a = [1, 2.5, 3]\nb = 2.0\n".parse().unwrap();
        assert_eq!(read_vec(t.get("a"), [0.0; 3]), [1.0, 2.5, 3.0]);
        assert_eq!(read_vec(t.get("b"), [0.0; 3]), [2.0; 3]);
        assert_eq!(read_vec(t.get("c"), [7.0; 3]), [7.0; 3]);
        assert_eq!(format_vec([1.0, 0.5, -2.0]), "[1.0, 0.5, -2.0]");
    }
}
