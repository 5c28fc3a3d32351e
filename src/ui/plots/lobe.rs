//! The 3D lobe: `f_r · cos θ_o` (or `f_r`, as the slice's radius setting
//! says) over the whole hemisphere of outgoing directions for the current
//! ω_i, each direction drawn at the radius its value maps to (linear or
//! log, the slice's scale), as a wireframe of rings of constant θ_o and
//! meridians of constant φ_o. Drag to turn it. The values come from the
//! f64 reference (`Material::f_r`) on a worker thread ([`super::worker`]),
//! one mesh per material; the drawing is an orthographic projection by
//! egui's painter.

use super::radius::Radius;
use super::{Settings, colour};
use crate::explore::slice::Quantity;
use crate::explore::{direction, frame};
use crate::material::Material;
use glam::DVec3;

/// Rings (θ_o from 0 to 90°) and meridians (φ_o around) of the mesh.
const RINGS: usize = 31;
const MERIDIANS: usize = 72;

/// The lobe's values: `values[ring][meridian]`, ring k at
/// θ_o = 90°·k/(RINGS − 1), meridian m at φ_o = 360°·m/MERIDIANS.
pub struct Mesh {
    pub values: Vec<Vec<f64>>,
}

/// The values of `m`'s lobe for `s`'s ω_i, quantity and channel.
pub fn mesh(m: &Material, s: &Settings) -> Mesh {
    let wi = direction(s.theta_i_deg.to_radians(), s.phi_i_deg.to_radians());
    let f = frame();
    let values = (0..RINGS)
        .map(|k| {
            let theta = ring_theta(k);
            (0..MERIDIANS)
                .map(|j| {
                    let wo = direction(theta, meridian_phi(j));
                    let mut v = s.channel.of(m.f_r(wi, wo, &f));
                    if s.quantity == Quantity::ProjectedFr {
                        v *= wo.z.max(0.0);
                    }
                    v
                })
                .collect()
        })
        .collect();
    Mesh { values }
}

fn ring_theta(k: usize) -> f64 {
    // The last ring a hair above the horizon, where one-sided models are
    // still defined.
    (k as f64 / (RINGS - 1) as f64 * 89.9).to_radians()
}

fn meridian_phi(j: usize) -> f64 {
    j as f64 / MERIDIANS as f64 * std::f64::consts::TAU
}

impl Mesh {
    /// The largest finite value.
    pub fn peak(&self) -> f64 {
        self.values
            .iter()
            .flatten()
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |a, &b| a.max(b))
    }
}

/// The view's turn: yaw about the normal, pitch towards the viewer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turn {
    pub yaw: f64,
    pub pitch: f64,
}

impl Default for Turn {
    fn default() -> Self {
        Turn {
            yaw: -0.6,
            pitch: 0.45,
        }
    }
}

impl Turn {
    /// Screen coordinates (right, up) of the point `p` (explore frame:
    /// n = +Z up on the screen at pitch 0).
    pub fn project(&self, p: DVec3) -> (f64, f64) {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        // Yaw about Z, then view along −Y' tilted by the pitch.
        let x = cy * p.x - sy * p.y;
        let y = sy * p.x + cy * p.y;
        (x, cp * p.z + sp * y)
    }
}

/// Draws the meshes (one per material, in its colour) into a square as
/// wide as the panel; dragging turns it.
pub fn show(ui: &mut egui::Ui, s: &Settings, turn: &mut Turn, meshes: &[Option<(&Mesh, bool)>]) {
    let stale = meshes.iter().any(|m| !matches!(m, Some((_, true))));
    ui.label(format!(
        "3D lobe at θ_i = {:.1}°, φ_i = {:.0}° (drag to turn){}",
        s.theta_i_deg,
        s.phi_i_deg,
        if stale { " (updating…)" } else { "" }
    ));
    let side = ui.available_width() - 8.0;
    let (rect, response) =
        ui.allocate_exact_size(egui::vec2(side, side * 0.8), egui::Sense::drag());
    if response.dragged() {
        let d = response.drag_delta();
        turn.yaw += d.x as f64 * 0.01;
        turn.pitch = (turn.pitch + d.y as f64 * 0.01).clamp(-0.2, 1.5);
    }
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_gray(18));
    let peak = meshes
        .iter()
        .flatten()
        .map(|(m, _)| m.peak())
        .fold(0.0_f64, f64::max);
    let radius = Radius::new(peak, s.log, s.decades);
    let outer = radius.outer();
    let scale = 0.45 * rect.width().min(rect.height() / 0.8) as f64 / outer;
    let centre = rect.center() + egui::vec2(0.0, 0.25 * rect.height());
    let to_screen = |p: DVec3| {
        let (x, y) = turn.project(p);
        egui::pos2(centre.x + (x * scale) as f32, centre.y - (y * scale) as f32)
    };
    let grey = egui::Stroke::new(1.0, egui::Color32::from_gray(80));
    // The surface: the outer ring on the horizon, the normal, ω_i.
    let horizon: Vec<egui::Pos2> = (0..=MERIDIANS)
        .map(|j| to_screen(outer * direction(std::f64::consts::FRAC_PI_2, meridian_phi(j))))
        .collect();
    painter.add(egui::Shape::line(horizon, grey));
    painter.line_segment([to_screen(DVec3::ZERO), to_screen(outer * DVec3::Z)], grey);
    let wi = direction(s.theta_i_deg.to_radians(), s.phi_i_deg.to_radians());
    painter.line_segment(
        [to_screen(DVec3::ZERO), to_screen(outer * wi)],
        egui::Stroke::new(1.5, egui::Color32::from_rgb(255, 230, 120)),
    );
    for (i, m) in meshes.iter().enumerate() {
        let Some((mesh, _)) = m else { continue };
        let stroke = egui::Stroke::new(1.0, colour(i).gamma_multiply(0.85));
        let point = |k: usize, j: usize| {
            let v = mesh.values[k][j % MERIDIANS];
            let r = if v.is_finite() { radius.map(v) } else { 0.0 };
            to_screen(r * direction(ring_theta(k), meridian_phi(j)))
        };
        for k in (0..RINGS).step_by(3) {
            let ring: Vec<egui::Pos2> = (0..=MERIDIANS).map(|j| point(k, j)).collect();
            painter.add(egui::Shape::line(ring, stroke));
        }
        for j in (0..MERIDIANS).step_by(3) {
            let meridian: Vec<egui::Pos2> = (0..RINGS).map(|k| point(k, j)).collect();
            painter.add(egui::Shape::line(meridian, stroke));
        }
    }
    painter.text(
        rect.left_top() + egui::vec2(6.0, 4.0),
        egui::Align2::LEFT_TOP,
        match radius {
            Radius::Linear { outer, .. } => format!("horizon ring: radius {outer:.3}"),
            Radius::Log { top, decades } => {
                format!("log radius: {decades} decades up to {top:e} at the horizon ring")
            }
        },
        egui::FontId::proportional(11.0),
        egui::Color32::from_gray(170),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;

    /// Lambert's f_r·cos θ_o is (k_d/π) cos θ_o on every meridian; the
    /// mesh's first ring is the normal.
    #[test]
    fn a_lambert_lobe_is_its_cosine() {
        let m = Material::new("l", ReflectanceModel::Lambert);
        let mesh = mesh(&m, &Settings::default());
        for (k, ring) in mesh.values.iter().enumerate() {
            for v in ring {
                let want = 0.8 / std::f64::consts::PI * ring_theta(k).cos();
                assert!((v - want).abs() < 1e-14, "{v} vs {want}");
            }
        }
        // Seen from the side (no turn), the normal points up the screen.
        let t = Turn {
            yaw: 0.0,
            pitch: 0.0,
        };
        assert_eq!(t.project(DVec3::Z), (0.0, 1.0));
    }
}
