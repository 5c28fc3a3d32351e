//! The polar slice (the lecture's "2D polar plot, intensity as length of
//! vector from origin") of every plotted material, drawn as `gonio brdf`
//! draws it: the normal up, signed θ_o with the light's side right
//! (`crate::explore::slice::polar`). A real polar frame instead of x/y
//! axes: rings at round values of the radius (linear or log,
//! [`super::radius`]) labelled along the horizon, spokes every 30°
//! labelled with θ_o, the light direction (solid) and the mirror
//! direction (dashed) as lines from the origin. A material that lets
//! light through draws its transmitted lobe below the surface, beside
//! the straight line through it (dotted), as `gonio brdf` does.

use super::radius::Radius;
use super::{Settings, colour};
use crate::explore::slice::{Slice, light_marker, mirror_marker, polar};
use egui_plot::{Line, LineStyle, Plot, PlotPoint, PlotPoints, Points, Text};

/// The frame's grey.
const FRAME: egui::Color32 = egui::Color32::from_gray(90);
const LABEL: egui::Color32 = egui::Color32::from_gray(170);

/// The radius scale for `slices`: their largest finite value (Dirac
/// reflectances included).
pub fn scale(s: &Settings, slices: &[&Slice]) -> Radius {
    let peak = slices
        .iter()
        .flat_map(|sl| {
            sl.points
                .iter()
                .chain(&sl.transmitted)
                .map(|p| p.1)
                .chain(sl.dirac)
        })
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    Radius::new(peak, s.log, s.decades)
}

pub fn show(ui: &mut egui::Ui, s: &Settings, slices: &[&Slice]) {
    let radius = scale(s, slices);
    let outer = radius.outer();
    let theta_i = s.theta_i_deg.to_radians();
    let scale_name = match radius {
        Radius::Linear { .. } => "linear radius".to_string(),
        Radius::Log { decades, .. } => format!("log radius, {decades} decades"),
    };
    ui.label(format!(
        "Polar slice at θ_i = {:.1}°, φ_i = {:.0}°: {} [1/sr], {}, {scale_name}",
        s.theta_i_deg,
        s.phi_i_deg,
        match s.quantity {
            crate::explore::slice::Quantity::ProjectedFr => "f_r·cos θ_o",
            crate::explore::slice::Quantity::Fr => "f_r",
        },
        s.channel.describe(),
    ));
    // The whole circle where some lobe lies below the surface.
    let below = slices.iter().any(|sl| !sl.transmitted.is_empty());
    let (half_turn, bottom) = if below { (180, -1.1) } else { (90, -0.1) };
    let width = ui.available_width() - 8.0;
    let aspect = if below { 1.0 } else { 0.56 };
    Plot::new("slice")
        .width(width)
        .height(width * aspect)
        .data_aspect(1.0)
        .show_axes(false)
        .show_grid(false)
        .allow_scroll(false)
        .allow_zoom(false)
        .allow_drag(false)
        .allow_boxed_zoom(false)
        .include_x(-1.12 * outer)
        .include_x(1.12 * outer)
        .include_y(bottom * outer)
        .include_y(1.1 * outer)
        .show(ui, |p| {
            for (r, label) in radius.rings() {
                let ring: Vec<[f64; 2]> = (0..=half_turn)
                    .map(|k| polar(r, (k as f64 * 2.0 - half_turn as f64).to_radians()))
                    .collect();
                p.line(
                    Line::new("", PlotPoints::from(ring))
                        .color(FRAME)
                        .width(0.5),
                );
                p.text(
                    Text::new("", PlotPoint::new(r, 0.0), label)
                        .color(LABEL)
                        .anchor(egui::Align2::CENTER_TOP),
                );
            }
            let spokes: &[i32] = if below {
                &[-150, -120, -90, -60, -30, 0, 30, 60, 90, 120, 150, 180]
            } else {
                &[-90, -60, -30, 0, 30, 60, 90]
            };
            for &deg in spokes {
                let t = (deg as f64).to_radians();
                let spoke = vec![[0.0, 0.0], polar(outer, t)];
                p.line(
                    Line::new("", PlotPoints::from(spoke))
                        .color(FRAME)
                        .width(0.5),
                );
                // ±90° sit above the horizon, clear of the rings' labels.
                let (at, anchor) = match deg {
                    90 => ([1.02 * outer, 0.0], egui::Align2::LEFT_BOTTOM),
                    -90 => ([-1.02 * outer, 0.0], egui::Align2::RIGHT_BOTTOM),
                    _ => (polar(1.06 * outer, t), egui::Align2::CENTER_CENTER),
                };
                p.text(
                    Text::new("", PlotPoint::new(at[0], at[1]), format!("{deg}°"))
                        .color(LABEL)
                        .anchor(anchor),
                );
            }
            let light = vec![[0.0, 0.0], light_marker(theta_i, outer)];
            p.line(
                Line::new("light ω_i", PlotPoints::from(light))
                    .color(egui::Color32::from_rgb(255, 230, 120))
                    .width(1.5),
            );
            if below {
                let through = vec![[0.0, 0.0], polar(outer, theta_i - std::f64::consts::PI)];
                p.line(
                    Line::new("straight through", PlotPoints::from(through))
                        .color(LABEL)
                        .style(LineStyle::dotted_loose()),
                );
            }
            let mirror = vec![[0.0, 0.0], mirror_marker(theta_i, outer)];
            p.line(
                Line::new("mirror direction", PlotPoints::from(mirror))
                    .color(LABEL)
                    .style(LineStyle::dashed_loose()),
            );
            // A lobe (reflected above, transmitted below) on the radius scale.
            let lobe = |points: &[(f64, f64)], i: usize| {
                let mapped: Vec<[f64; 2]> = points
                    .iter()
                    .filter(|(_, v)| v.is_finite())
                    .map(|&(t, v)| polar(radius.map(v), t))
                    .collect();
                Line::new("", PlotPoints::from(mapped))
                    .color(colour(i))
                    .width(1.8)
            };
            for (i, sl) in slices.iter().enumerate() {
                p.line(lobe(&sl.points, i));
                if !sl.transmitted.is_empty() {
                    p.line(lobe(&sl.transmitted, i));
                }
                if let Some(d) = sl.dirac {
                    p.points(
                        Points::new("", vec![mirror_marker(theta_i, radius.map(d))])
                            .color(colour(i))
                            .radius(4.0),
                    );
                }
            }
        });
    if below {
        ui.small("yellow: light ω_i · dashed: mirror direction · dotted: straight through · below the surface: transmitted · dot: a Dirac lobe's reflectance");
    } else {
        ui.small("yellow: light ω_i · dashed: mirror direction · dot: a Dirac lobe's reflectance");
    }
}
