//! The material section: the selected material's model, terms and
//! parameters.

use super::{color, combo, log_slider, triple};
use crate::material::presets::PRESETS;
use crate::material::terms::{Denominator, Distribution, Fresnel, Geometry};
use crate::material::{Material, ReflectanceModel};

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
