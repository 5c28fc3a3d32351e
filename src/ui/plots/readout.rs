//! The plots' legend and numbers in one table below them (a legend inside
//! a plot covers data): per material its colour, its name, the
//! directional albedo at the current ω_i with its error bound, and the
//! gloss meter's readings (ISO 2813 / ASTM D523, gloss units) with the
//! sample turned to φ_i. A value still being recomputed is shown greyed.

use super::{Integrals, Series, Settings, colour};
use crate::explore::albedo::AlbedoEstimate;
use crate::explore::slice::Slice;

/// Longest name shown in full (the whole name is the hover text).
const NAME_CHARS: usize = 26;

pub fn show(
    ui: &mut egui::Ui,
    s: &Settings,
    series: &[Series],
    slices: &[&Slice],
    points: &[Option<(&AlbedoEstimate, bool)>],
    curves: &[Option<(&Integrals, bool)>],
) {
    egui::Grid::new("readout")
        .striped(true)
        .num_columns(5)
        .show(ui, |ui| {
            ui.label("");
            ui.label(format!("ρ(θ_i={:.0}°)", s.theta_i_deg))
                .on_hover_text("directional albedo at the plots' ω_i, ± its error bound");
            for g in crate::explore::gloss::GEOMETRIES {
                ui.label(format!("{:.0}° GU", g.angle_deg))
                    .on_hover_text("specular gloss, ISO 2813 / ASTM D523, gloss units");
            }
            ui.end_row();
            for (i, one) in series.iter().enumerate() {
                let name: String = if one.label.chars().count() > NAME_CHARS {
                    let short: String = one.label.chars().take(NAME_CHARS - 1).collect();
                    format!("{short}…")
                } else {
                    one.label.clone()
                };
                ui.label(egui::RichText::new(format!("— {name}")).color(colour(i)))
                    .on_hover_text(&one.label);
                value(
                    ui,
                    points[i].map(|(a, fresh)| {
                        let (v, e) = (s.channel.of(a.value), s.channel.of(a.error_bound));
                        (format!("{v:.4} ± {e:.0e}"), fresh)
                    }),
                );
                for k in 0..3 {
                    value(
                        ui,
                        curves[i]
                            .map(|(c, fresh)| (format!("{:.1}", c.gloss[k].gloss_units), fresh)),
                    );
                }
                ui.end_row();
            }
        });
    for (one, sl) in series.iter().zip(slices) {
        if let Some(d) = sl.dirac {
            ui.small(format!(
                "{}: a Dirac lobe in the mirror direction of reflectance {d:.4} (its f_r is infinite; the dot marks its reflectance)",
                one.label
            ));
        }
    }
}

/// A number, greyed while stale; "…" before the first result.
fn value(ui: &mut egui::Ui, v: Option<(String, bool)>) {
    match v {
        Some((text, true)) => ui.label(text),
        Some((text, false)) => ui.weak(text),
        None => ui.weak("…"),
    };
}
