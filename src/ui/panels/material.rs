//! The material section: the selected material's model, terms and
//! parameters, one row per entry of the model's row in the table of
//! models ([`crate::material::table`]).

use super::widgets::{color, combo, log_slider, triple};
use crate::material::param::{Param, Scale, Value, Widget};
use crate::material::presets::PRESETS;
use crate::material::table::{self, Terms};
use crate::material::terms::{Denominator, Distribution, Fresnel, Geometry};
use crate::material::{Material, ReflectanceModel, measured};

/// Edits `m` in place; returns whether anything changed.
pub fn material_editor(ui: &mut egui::Ui, m: &mut Material) -> bool {
    let mut changed = false;
    // Weights at their defaults follow a change of model, preset or term
    // (as `--set` of that key in a scene file would have them).
    let before = (m.model.row().weights)(m);
    egui::Grid::new("material").num_columns(2).show(ui, |ui| {
        ui.label("model");
        changed |= combo(ui, "model", &mut m.model, ReflectanceModel::ALL, |v| {
            v.name()
        });
        ui.end_row();
        let row = m.model.row();
        changed |= terms(ui, m, row.terms);
        for &p in table::COMMON.iter().chain(row.params) {
            ui.label(p.label);
            changed |= param(ui, p, m);
            ui.end_row();
        }
        if row.energy_compensation {
            // Multiple scattering, the scene key
            // `energy_compensation`; off by default.
            ui.label("energy compensation");
            changed |= ui.checkbox(&mut m.energy_compensation, "").changed();
            ui.end_row();
        }
        if m.model == ReflectanceModel::Measured {
            ui.label("measured");
            changed |= measured_choice(ui, m);
            ui.end_row();
        }
        if row.terms.fresnel {
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
    if changed {
        m.follow_default_weights(before);
    }
    changed
}

/// The built-in measured materials (a file's table stays selected until
/// another is picked).
fn measured_choice(ui: &mut egui::Ui, m: &mut Material) -> bool {
    let current = m.measured_brdf().map_or("", |b| b.name.as_str());
    let mut changed = false;
    egui::ComboBox::from_id_salt("measured")
        .selected_text(current)
        .height(400.0)
        .show_ui(ui, |ui| {
            for b in measured::library::all() {
                if ui.selectable_label(b.name == current, &b.name).clicked() {
                    m.measured = Some(b);
                    changed = true;
                }
            }
        });
    changed
}

/// A combo box per term the model selects.
fn terms(ui: &mut egui::Ui, m: &mut Material, terms: Terms) -> bool {
    let mut changed = false;
    if terms.distribution {
        ui.label("distribution D");
        changed |= combo(ui, "dist", &mut m.distribution, Distribution::ALL, |v| {
            v.name()
        });
        ui.end_row();
    }
    if terms.geometry {
        ui.label("geometry G");
        changed |= combo(ui, "geom", &mut m.geometry, Geometry::ALL, |v| v.name());
        ui.end_row();
    }
    if terms.denominator {
        ui.label("denominator");
        changed |= combo(ui, "denom", &mut m.denominator, Denominator::ALL, |v| {
            v.name()
        });
        ui.end_row();
    }
    if terms.fresnel {
        ui.label("Fresnel F");
        changed |= combo(ui, "fresnel", &mut m.fresnel, Fresnel::ALL, |v| v.name());
        ui.end_row();
    }
    changed
}

/// The widget of parameter `p`, editing `m` through the parameter's binding.
fn param(ui: &mut egui::Ui, p: &Param, m: &mut Material) -> bool {
    let mut value = p.read(m);
    let changed = match (&mut value, p.widget) {
        (Value::Color(c), Widget::ColorPicker) => color(ui, c),
        (Value::Color(c), Widget::Drag { speed, min, max }) => triple(ui, c, speed, min..=max),
        (Value::Scalar(v), Widget::Slider { min, max, scale }) => match scale {
            Scale::Log => log_slider(ui, v, min..=max),
            Scale::Linear => ui.add(egui::Slider::new(v, min..=max)).changed(),
        },
        (Value::Scalar(v), Widget::Drag { speed, min, max }) => ui
            .add(egui::DragValue::new(v).speed(speed).range(min..=max))
            .changed(),
        // A colour with a slider or a number with a colour picker: the
        // table's tests rule it out.
        _ => false,
    };
    if changed {
        p.write(m, value);
    }
    changed
}

/// One line per texture of `m`: what it multiplies, the image (by its
/// name in `images`), the channel it reads, its UV set and its
/// `KHR_texture_transform` (the panel once showed only the factors of
/// textured parameters, with no sign that a texture multiplies them).
pub fn texture_lines(m: &Material, images: &[&str]) -> Vec<String> {
    use crate::material::texture::TextureTarget;
    m.textures
        .iter()
        .map(|t| {
            let image = images.get(t.image).copied().unwrap_or("?");
            let what = match t.target {
                TextureTarget::Param(key) => {
                    let colour = table::all_params()
                        .iter()
                        .any(|p| p.key == key && p.kind == crate::material::param::Kind::Color);
                    let channel = if colour {
                        "RGB".to_string()
                    } else {
                        ["R", "G", "B", "A"][t.channel.min(3)].to_string()
                    };
                    format!("{key} × texture ({channel})")
                }
                TextureTarget::Normal { scale } => format!("normal map (scale {scale})"),
                TextureTarget::Occlusion { strength } => {
                    format!("occlusion map (R, strength {strength})")
                }
                TextureTarget::ClearcoatNormal { scale } => {
                    format!("clearcoat normal map (scale {scale})")
                }
                TextureTarget::Anisotropy => {
                    "anisotropy map (RG direction, B strength)".to_string()
                }
            };
            let mut line = format!("{what}: {image}, UV {}", t.tex_coord);
            let tr = t.transform;
            if tr != Default::default() {
                line += &format!(
                    "; offset ({}, {}), rotation {:.1}°, scale ({}, {})",
                    tr.offset.x,
                    tr.offset.y,
                    tr.rotation.to_degrees(),
                    tr.scale.x,
                    tr.scale.y
                );
            }
            line
        })
        .collect()
}

/// [`texture_lines`] under the material's parameters, when it has any.
pub fn texture_notes(ui: &mut egui::Ui, m: &Material, images: &[&str]) {
    let lines = texture_lines(m, images);
    if lines.is_empty() {
        return;
    }
    ui.label(egui::RichText::new("textures (each multiplies the factor above)").small());
    for line in lines {
        ui.label(egui::RichText::new(line).small().monospace());
    }
}

#[cfg(test)]
mod texture_tests {
    use super::*;
    use crate::material::texture::{MaterialTexture, TextureTarget, UvTransform};

    #[test]
    fn each_texture_is_listed_with_its_channel_and_transform() {
        let mut m = Material::new("m", ReflectanceModel::GltfPbr);
        m.textures.push(MaterialTexture {
            target: TextureTarget::Param("roughness"),
            image: 1,
            channel: 1,
            tex_coord: 0,
            transform: UvTransform {
                rotation: std::f64::consts::FRAC_PI_2,
                ..Default::default()
            },
            sampler: Default::default(),
        });
        m.textures.push(MaterialTexture {
            target: TextureTarget::Param("base_color"),
            image: 0,
            channel: 0,
            tex_coord: 1,
            transform: Default::default(),
            sampler: Default::default(),
        });
        let lines = texture_lines(&m, &["albedo.png", "orm.png"]);
        assert_eq!(
            lines,
            [
                "roughness × texture (G): orm.png, UV 0; offset (0, 0), rotation 90.0°, scale (1, 1)",
                "base_color × texture (RGB): albedo.png, UV 1",
            ]
        );
    }
}
