//! The widgets every section draws with: combo boxes over a closed set of
//! names, logarithmic sliders, colours (edited in sRGB, stored linear) and
//! number triples.

use crate::scene::{Rgb, ShadingMode};

/// Shading mode selector.
pub fn shading_mode(ui: &mut egui::Ui, mode: &mut ShadingMode) -> bool {
    combo(ui, "shading", mode, ShadingMode::ALL, |m| m.name())
}

/// A radiance triple with non-negative components.
pub fn radiance(ui: &mut egui::Ui, value: &mut Rgb) -> bool {
    triple(ui, value, 0.005, 0.0..=1e6)
}

pub fn combo<T: Copy + PartialEq>(
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
pub fn log_slider(
    ui: &mut egui::Ui,
    value: &mut f64,
    range: std::ops::RangeInclusive<f64>,
) -> bool {
    ui.add(egui::Slider::new(value, range).logarithmic(true))
        .changed()
}

/// A linear RGB reflectance: colour picker (shown in sRGB) and exact values.
pub(super) fn color(ui: &mut egui::Ui, value: &mut Rgb) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        let mut srgb = value
            .to_array()
            .map(|c| crate::output::srgb8::srgb_encode(c.clamp(0.0, 1.0)) as f32);
        if ui.color_edit_button_rgb(&mut srgb).changed() {
            *value = Rgb::from_array(srgb.map(|c| srgb_decode(c as f64)));
            changed = true;
        }
        changed |= triple(ui, value, 0.005, 0.0..=1.0);
    });
    changed
}

pub(super) fn triple(
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

pub fn triple_array(ui: &mut egui::Ui, value: &mut [f64; 3], speed: f64) -> bool {
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
            let back = srgb_decode(crate::output::srgb8::srgb_encode(v));
            assert!((back - v).abs() < 1e-12, "{v} → {back}");
        }
    }
}
