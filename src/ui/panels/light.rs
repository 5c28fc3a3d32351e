//! The lights section: one `[[lights]]` entry's keys.

use super::triple_array;
use toml::Value;

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_values_read_scalars_and_triples() {
        let t: toml::Table = "a = [1, 2.5, 3]\nb = 2.0\n".parse().unwrap();
        assert_eq!(read_vec(t.get("a"), [0.0; 3]), [1.0, 2.5, 3.0]);
        assert_eq!(read_vec(t.get("b"), [0.0; 3]), [2.0; 3]);
        assert_eq!(read_vec(t.get("c"), [7.0; 3]), [7.0; 3]);
        assert_eq!(format_vec([1.0, 0.5, -2.0]), "[1.0, 0.5, -2.0]");
    }
}
