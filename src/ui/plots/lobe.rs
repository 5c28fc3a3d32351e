//! The 3D lobe: `f_r · cos θ_o` (or `f_r`, as the slice's radius setting
//! says) over the whole hemisphere of outgoing directions for the current
//! ω_i, each direction drawn at the radius its value maps to (linear or
//! log, the slice's scale), as a wireframe of rings of constant θ_o and
//! meridians of constant φ_o. Drag to turn it. The values come from the
//! f64 reference (`Material::f_r`) on a worker thread ([`super::worker`]),
//! one mesh per material; the drawing is an orthographic projection by
//! egui's painter.
//!
//! Hidden lines: the surface is cut into patches (the cells between
//! neighbouring drawn rings and meridians), each filled with the
//! background (85 % opaque, tinted with its material's colour) and
//! outlined, drawn back to front by the depth of its centre (the
//! painter's algorithm, all materials' patches in one order). Lines behind
//! the surface show through at 15 %: dimmed, so the lobe reads as a
//! solid, while a lobe inside another stays visible. A material that lets
//! light through also has its transmitted lobe, below the surface
//! (`MaterialPart`'s far side, mirrored back down).

use super::radius::Radius;
use super::{Settings, colour};
use crate::explore::slice::Quantity;
use crate::explore::{MaterialPart, direction, frame};
use glam::DVec3;

/// Rings (θ_o from 0 to 90°) and meridians (φ_o around) of the mesh.
const RINGS: usize = 31;
const MERIDIANS: usize = 72;

/// The lobe's values: `values[ring][meridian]`, ring k at
/// θ_o = 90°·k/(RINGS − 1), meridian m at φ_o = 360°·m/MERIDIANS.
pub struct Mesh {
    pub values: Vec<Vec<f64>>,
    /// The transmitted lobe's values at the same rings mirrored below
    /// the surface (θ_o → 180° − θ_o), for a material that lets light
    /// through.
    pub transmitted: Option<Vec<Vec<f64>>>,
}

/// The values of `m`'s lobe for `s`'s ω_i, quantity and channel.
pub fn mesh<'a>(m: impl Into<MaterialPart<'a>>, s: &Settings) -> Mesh {
    let m = m.into();
    let wi = direction(s.theta_i_deg.to_radians(), s.phi_i_deg.to_radians());
    let f = frame();
    let grid = |part: MaterialPart| -> Vec<Vec<f64>> {
        (0..RINGS)
            .map(|k| {
                let theta = ring_theta(k);
                (0..MERIDIANS)
                    .map(|j| {
                        let wo = direction(theta, meridian_phi(j));
                        let mut v = s.channel.of(part.f_r(wi, wo, &f));
                        if s.quantity == Quantity::ProjectedFr {
                            v *= wo.z.max(0.0);
                        }
                        v
                    })
                    .collect()
            })
            .collect()
    };
    Mesh {
        values: grid(m),
        transmitted: m.transmits().then(|| grid(m.transmitted())),
    }
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
    /// The largest finite value (of either lobe).
    pub fn peak(&self) -> f64 {
        self.values
            .iter()
            .chain(self.transmitted.iter().flatten())
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

    /// How far towards the viewer `p` is (larger is nearer): the view's
    /// third axis, so that (right, up, towards) is right-handed.
    pub fn depth(&self, p: DVec3) -> f64 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let y = sy * p.x + cy * p.y;
        sp * p.z - cp * y
    }
}

/// Rings and meridians between drawn lines: the patch size.
const STEP: usize = 3;

/// The background of the view.
const BACKGROUND: egui::Color32 = egui::Color32::from_gray(18);

/// One patch: rings `k0..=k0 + STEP`, meridians `j0..=j0 + STEP` of
/// series `series`, and its centre's depth.
struct Patch {
    depth: f64,
    series: usize,
    k0: usize,
    j0: usize,
}

/// Every patch of every mesh (`(series, points)`), farthest first;
/// `Patch::series` indexes `meshes`.
fn patches(meshes: &[(usize, Vec<Vec<DVec3>>)], turn: &Turn) -> Vec<Patch> {
    let mut all = Vec::new();
    for (series, (_, p)) in meshes.iter().enumerate() {
        for k0 in (0..RINGS - 1).step_by(STEP) {
            for j0 in (0..MERIDIANS).step_by(STEP) {
                let (k1, j1) = (k0 + STEP, (j0 + STEP) % MERIDIANS);
                let centre = (p[k0][j0] + p[k0][j1] + p[k1][j0] + p[k1][j1]) / 4.0;
                all.push(Patch {
                    depth: turn.depth(centre),
                    series,
                    k0,
                    j0,
                });
            }
        }
    }
    all.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    all
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
    painter.rect_filled(rect, 2.0, BACKGROUND);
    let peak = meshes
        .iter()
        .flatten()
        .map(|(m, _)| m.peak())
        .fold(0.0_f64, f64::max);
    let radius = Radius::new(peak, s.log, s.decades);
    let outer = radius.outer();
    // A lobe below the surface: the origin at the middle, room both ways.
    let below = meshes
        .iter()
        .flatten()
        .any(|(m, _)| m.transmitted.is_some());
    let (fill, lift) = if below { (0.36, 0.0) } else { (0.45, 0.25) };
    let scale = fill * rect.width().min(rect.height() / 0.8) as f64 / outer;
    let centre = rect.center() + egui::vec2(0.0, lift * rect.height());
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
    // Each lobe's points with its material's index: the reflected lobe,
    // and the transmitted one mirrored below the surface.
    let placed = |values: &Vec<Vec<f64>>, side: f64| -> Vec<Vec<DVec3>> {
        (0..RINGS)
            .map(|k| {
                (0..MERIDIANS)
                    .map(|j| {
                        let v = values[k][j];
                        let r = if v.is_finite() { radius.map(v) } else { 0.0 };
                        let d = direction(ring_theta(k), meridian_phi(j));
                        r * DVec3::new(d.x, d.y, side * d.z)
                    })
                    .collect()
            })
            .collect()
    };
    let mut points: Vec<(usize, Vec<Vec<DVec3>>)> = Vec::new();
    for (i, m) in meshes.iter().enumerate() {
        let Some((mesh, _)) = m else { continue };
        points.push((i, placed(&mesh.values, 1.0)));
        if let Some(below) = &mesh.transmitted {
            points.push((i, placed(below, -1.0)));
        }
    }
    for patch in patches(&points, turn) {
        let (material, p) = &points[patch.series];
        let at = |k: usize, j: usize| to_screen(p[k][j % MERIDIANS]);
        let tint = colour(*material);
        let mix = |b: u8, c: u8| (0.85 * b as f32 + 0.15 * c as f32) as u8;
        let fill = egui::Color32::from_rgba_unmultiplied(
            mix(BACKGROUND.r(), tint.r()),
            mix(BACKGROUND.g(), tint.g()),
            mix(BACKGROUND.b(), tint.b()),
            217,
        );
        let mut cells = egui::Mesh::default();
        for k in patch.k0..patch.k0 + STEP {
            for j in patch.j0..patch.j0 + STEP {
                let base = cells.vertices.len() as u32;
                for (a, b) in [(k, j), (k + 1, j), (k + 1, j + 1), (k, j + 1)] {
                    cells.colored_vertex(at(a, b), fill);
                }
                cells.add_triangle(base, base + 1, base + 2);
                cells.add_triangle(base, base + 2, base + 3);
            }
        }
        painter.add(egui::Shape::mesh(cells));
        let (k0, j0, k1, j1) = (patch.k0, patch.j0, patch.k0 + STEP, patch.j0 + STEP);
        let outline: Vec<egui::Pos2> = (j0..=j1)
            .map(|j| at(k0, j))
            .chain((k0..=k1).map(|k| at(k, j1)))
            .chain((j0..=j1).rev().map(|j| at(k1, j)))
            .chain((k0..=k1).rev().map(|k| at(k, j0)))
            .collect();
        painter.add(egui::Shape::line(
            outline,
            egui::Stroke::new(1.0, tint.gamma_multiply(0.85)),
        ));
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
    use crate::material::{Material, ReflectanceModel};

    /// A material that lets light through has its transmitted lobe:
    /// Lambert on the far side is `D c_dt (1 − F(H)) / π · |cos θ_o|`,
    /// between `(1 − F(0°))` and 0 times `D c_dt/π` on every ring, and
    /// the largest at the straight-down ring; an opaque one has none.
    #[test]
    fn a_transmissive_lobe_has_its_far_side() {
        let mut m = Material::new("t", ReflectanceModel::GltfPbr);
        m.layers.diffuse_transmission = 1.0;
        let mesh = mesh(&m, &Settings::default());
        let below = mesh.transmitted.expect("a far side");
        let lambert = 1.0 / std::f64::consts::PI;
        for (k, ring) in below.iter().enumerate() {
            for &v in ring {
                assert!(v <= lambert * ring_theta(k).cos() + 1e-15, "{k}: {v}");
            }
        }
        assert!(below[0][0] > 0.9 * lambert, "{}", below[0][0]);
        let opaque = Material::new("l", ReflectanceModel::Lambert);
        assert!(
            super::mesh(&opaque, &Settings::default())
                .transmitted
                .is_none()
        );
    }

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

    /// The view's axes (right, up, towards the viewer) are orthonormal and
    /// right-handed for any turn, so the depth order is the one seen: from
    /// above (pitch > 0) the top of the lobe is nearer than the horizon
    /// behind it.
    #[test]
    fn depth_is_the_third_axis_of_the_view() {
        for (yaw, pitch) in [(-0.6, 0.45), (1.3, -0.2), (2.9, 1.5)] {
            let t = Turn { yaw, pitch };
            let axis = |f: &dyn Fn(DVec3) -> f64| DVec3::new(f(DVec3::X), f(DVec3::Y), f(DVec3::Z));
            let right = axis(&|p| t.project(p).0);
            let up = axis(&|p| t.project(p).1);
            let towards = axis(&|p| t.depth(p));
            for (a, b) in [(right, up), (up, towards), (towards, right)] {
                assert!(a.dot(b).abs() < 1e-12);
            }
            assert!((right.cross(up) - towards).length() < 1e-12);
        }
        let t = Turn::default();
        let far_horizon = (0..MERIDIANS)
            .map(|j| direction(ring_theta(RINGS - 1), meridian_phi(j)))
            .min_by(|a, b| t.depth(*a).total_cmp(&t.depth(*b)))
            .unwrap();
        assert!(t.depth(DVec3::Z) > t.depth(far_horizon));
        // And the patches come farthest first.
        let m = Material::new("l", ReflectanceModel::Lambert);
        let mesh = mesh(&m, &Settings::default());
        let pts: Vec<Vec<DVec3>> = (0..RINGS)
            .map(|k| {
                (0..MERIDIANS)
                    .map(|j| mesh.values[k][j] * direction(ring_theta(k), meridian_phi(j)))
                    .collect()
            })
            .collect();
        let order = patches(&[(0, pts)], &t);
        assert_eq!(order.len(), (RINGS - 1) / STEP * MERIDIANS / STEP);
        assert!(order.windows(2).all(|w| w[0].depth <= w[1].depth));
    }
}
