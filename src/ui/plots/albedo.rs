//! The directional albedo `ρ(θ_i) = ∫ f_r cos θ_o dω_o` against θ_i in
//! the plane φ_i, one curve per material (a stale curve, still being
//! recomputed, dashed), the line `ρ = 1` of energy conservation and the
//! current θ_i. Labelled axes with a tick every 15° and every 0.1–0.2 of ρ.
//! A material that lets light through also draws `ρ + τ`, reflected plus
//! transmitted (dotted), which energy conservation keeps below 1.

use super::{Integrals, Settings, colour};
use egui_plot::{HLine, Line, LineStyle, Plot, PlotPoints, VLine, uniform_grid_spacer};

/// `[θ_i, ρ + τ]` in `channel` of a material that lets light through;
/// empty otherwise.
fn through(c: &Integrals, channel: crate::explore::Channel) -> Vec<[f64; 2]> {
    c.albedo
        .iter()
        .zip(&c.transmitted)
        .map(|((deg, a), (_, t))| [*deg, channel.of(a.value + t.value)])
        .collect()
}

pub fn show(ui: &mut egui::Ui, s: &Settings, curves: &[Option<(&Integrals, bool)>]) {
    let stale = curves.iter().any(|c| !matches!(c, Some((_, true))));
    ui.label(format!(
        "Directional albedo ρ(θ_i) at φ_i = {:.0}°, {}{}",
        s.phi_i_deg,
        s.channel.describe(),
        if stale { " (updating…)" } else { "" }
    ));
    let top = curves
        .iter()
        .flatten()
        .flat_map(|(c, _)| {
            c.albedo
                .iter()
                .map(|(_, a)| s.channel.of(a.value))
                .chain(through(c, s.channel).into_iter().map(|p| p[1]))
        })
        .filter(|v| v.is_finite())
        .fold(1.0_f64, f64::max);
    let width = ui.available_width() - 8.0;
    let shown = Plot::new("albedo")
        .width(width)
        .height(width * 0.55)
        .include_x(0.0)
        .include_x(90.0)
        .include_y(0.0)
        .include_y(top * 1.05)
        .allow_scroll(false)
        .allow_zoom(false)
        .allow_drag(false)
        .allow_boxed_zoom(false)
        .x_axis_label("θ_i (°)")
        .y_axis_label("ρ")
        .x_grid_spacer(uniform_grid_spacer(|_| [5.0, 15.0, 45.0]))
        .x_axis_formatter(|mark, _| format!("{:.0}", mark.value))
        .y_axis_formatter(|mark, _| {
            let text = format!("{:.2}", mark.value);
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        })
        .y_grid_spacer(uniform_grid_spacer(move |_| {
            if top > 2.0 {
                [0.1, 0.5, 1.0]
            } else {
                [0.05, 0.1, 0.5]
            }
        }))
        .show(ui, |p| {
            let mut any_through = false;
            p.hline(
                HLine::new("ρ = 1", 1.0)
                    .color(egui::Color32::from_gray(120))
                    .style(LineStyle::dashed_loose()),
            );
            p.vline(VLine::new("θ_i", s.theta_i_deg).color(egui::Color32::from_rgb(255, 230, 120)));
            for (i, c) in curves.iter().enumerate() {
                let Some((c, fresh)) = c else { continue };
                let points: Vec<[f64; 2]> = c
                    .albedo
                    .iter()
                    .map(|(deg, a)| [*deg, s.channel.of(a.value)])
                    .collect();
                let mut line = Line::new("", PlotPoints::from(points))
                    .color(colour(i))
                    .width(1.8);
                if !fresh {
                    line = line.style(LineStyle::dashed_dense());
                }
                p.line(line);
                let sum = through(c, s.channel);
                if !sum.is_empty() {
                    any_through = true;
                    p.line(
                        Line::new("", PlotPoints::from(sum))
                            .color(colour(i))
                            .width(1.4)
                            .style(LineStyle::dotted_dense()),
                    );
                }
            }
            any_through
        });
    if shown.inner {
        ui.small("dotted: ρ + τ, reflected plus transmitted (at most 1)");
    }
}
