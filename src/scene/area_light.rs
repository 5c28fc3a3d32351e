//! Area lights: a rectangle or a disk that emits with a cosine
//! distribution about its normal (constant radiance `L`, a Lambertian
//! emitter), rendered as N point lights (lecture: "Area light sources ...
//! replacing it with some point light sources").
//!
//! The N points are a deterministic stratified pattern: the centres of the
//! cells of an `nx × ny` grid with `nx · ny = N` (the divisor pair whose
//! cells are closest to square) on the rectangle, or the same grid on the
//! unit square carried to the disk by Shirley and Chiu's concentric mapping
//! (which preserves area, so every sample stands for `A/N`). Sample k emits
//! `I(ω) = L · (A/N) · max(0, n_l · ω)` (ω from the sample towards the
//! surface): the N samples' irradiance is the midpoint rule for the exact
//! integral, so it converges to it as N grows.
//!
//! The exact irradiance on a receiver, for measuring the error of N
//! samples, is Lambert's polygon formula ([`AreaLight::exact_irradiance`]).

use crate::scene::Light;
use crate::scene::Rgb;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// Samples an area light gets when the scene does not say.
pub const DEFAULT_SAMPLES: u32 = 16;
/// Most samples one area light may have.
pub const MAX_SAMPLES: u32 = 4096;
/// Edges of the polygon that stands in for a disk in the exact formula
/// (its radius is scaled so that its area is the disk's; the remaining
/// error is below 10⁻⁶ relative).
const DISK_EDGES: usize = 1024;

/// The emitting shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AreaShape {
    /// `width` along `tangent`, `height` along `normal × tangent`.
    Rect {
        width: f64,
        height: f64,
    },
    Disk {
        radius: f64,
    },
}

/// An area light of the scene file (`kind = "area"`).
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    pub shape: AreaShape,
    /// Centre of the shape.
    pub position: DVec3,
    /// Unit normal of the emitting side.
    pub normal: DVec3,
    /// Unit tangent, orthogonal to `normal`: the direction of a rectangle's
    /// width (for a disk, the orientation of the sample pattern).
    pub tangent: DVec3,
    /// Emitted radiance `L` [W/(m²·sr)] per channel, the same in every
    /// direction of the emitting side.
    pub radiance: Rgb,
    /// N: how many point lights stand in for it.
    pub samples: u32,
    pub shadows: bool,
    /// GPU shadows: one cube map per sample (exact up to the map's
    /// resolution, 6N layers) instead of one at the centre shared by all
    /// samples (a hard shadow, 6 layers). The reference always traces one
    /// ray per sample.
    pub shadow_per_sample: bool,
}

impl AreaLight {
    /// Area `A` in m².
    pub fn area(&self) -> f64 {
        match self.shape {
            AreaShape::Rect { width, height } => width * height,
            AreaShape::Disk { radius } => PI * radius * radius,
        }
    }

    /// `normal × tangent`: the direction of a rectangle's height.
    pub fn bitangent(&self) -> DVec3 {
        self.normal.cross(self.tangent)
    }

    /// The `n` sample positions, in a fixed order.
    pub fn sample_positions(&self, n: u32) -> Vec<DVec3> {
        let n = n.max(1);
        let (t, b) = (self.tangent, self.bitangent());
        let cell_aspect = match self.shape {
            AreaShape::Rect { width, height } => width / height,
            AreaShape::Disk { .. } => 1.0,
        };
        let (nx, ny) = grid(n, cell_aspect);
        let mut out = Vec::with_capacity(n as usize);
        for j in 0..ny {
            for i in 0..nx {
                let u = (i as f64 + 0.5) / nx as f64;
                let v = (j as f64 + 0.5) / ny as f64;
                let offset = match self.shape {
                    AreaShape::Rect { width, height } => {
                        t * (width * (u - 0.5)) + b * (height * (v - 0.5))
                    }
                    AreaShape::Disk { radius } => {
                        let (x, y) = concentric(u, v);
                        (t * x + b * y) * radius
                    }
                };
                out.push(self.position + offset);
            }
        }
        out
    }

    /// The `n` point lights that stand in for this light; `index` is its
    /// place in [`crate::scene::Scene::area_lights`].
    pub fn point_lights(&self, index: usize, n: u32) -> Vec<Light> {
        let intensity = self.radiance * (self.area() / n.max(1) as f64);
        self.sample_positions(n)
            .into_iter()
            .map(|position| Light::AreaSample {
                position,
                normal: self.normal,
                intensity,
                area: index,
                center: self.position,
                shadows: self.shadows,
            })
            .collect()
    }

    /// The outline as a polygon, counter-clockwise seen from the emitting
    /// side; a disk becomes a regular polygon of the same area.
    pub fn outline(&self) -> Vec<DVec3> {
        let (t, b) = (self.tangent, self.bitangent());
        match self.shape {
            AreaShape::Rect { width, height } => {
                [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                    .iter()
                    .map(|&(x, y)| self.position + t * (0.5 * width * x) + b * (0.5 * height * y))
                    .collect()
            }
            AreaShape::Disk { radius } => {
                let step = 2.0 * PI / DISK_EDGES as f64;
                // Area of the inscribed polygon: ½ n r² sin(2π/n).
                let scale = (PI / (0.5 * DISK_EDGES as f64 * step.sin())).sqrt();
                (0..DISK_EDGES)
                    .map(|k| {
                        let a = step * k as f64;
                        self.position + (t * a.cos() + b * a.sin()) * (radius * scale)
                    })
                    .collect()
            }
        }
    }

    /// The exact irradiance `E` at `x` on a surface with unit normal `n`
    /// from the whole light, unoccluded: `E = L · ∫ cosθ dω` over the part
    /// of the light above the surface, by Lambert's formula for the
    /// projected solid angle of a polygon,
    /// `∫ cosθ dω = ½ |Σ_i γ_i · (n · ĉ_i)|`, with `γ_i` the angle the edge
    /// `v_i v_{i+1}` subtends at x and `ĉ_i` the unit normal of the plane
    /// through x and that edge. The polygon is first clipped to the
    /// half-space above the surface; points behind the emitting side get
    /// nothing.
    pub fn exact_irradiance(&self, x: DVec3, n: DVec3) -> Rgb {
        if self.normal.dot(x - self.position) <= 0.0 {
            return Rgb::ZERO;
        }
        let polygon: Vec<DVec3> = self.outline().into_iter().map(|v| v - x).collect();
        let clipped = clip_above(&polygon, n);
        if clipped.len() < 3 {
            return Rgb::ZERO;
        }
        let mut sum = 0.0;
        for (i, a) in clipped.iter().enumerate() {
            let b = clipped[(i + 1) % clipped.len()];
            let c = a.cross(b);
            let len = c.length();
            if len == 0.0 {
                continue;
            }
            let gamma = len.atan2(a.dot(b));
            sum += gamma * n.dot(c) / len;
        }
        self.radiance * (0.5 * sum.abs())
    }
}

/// The divisor pair `(nx, ny)`, `nx · ny = n`, whose cells on a shape of
/// aspect `width / height` are closest to square (ties: the larger nx).
pub fn grid(n: u32, aspect: f64) -> (u32, u32) {
    let n = n.max(1);
    let mut best = (n, 1);
    let mut best_cost = f64::INFINITY;
    for nx in 1..=n {
        if !n.is_multiple_of(nx) {
            continue;
        }
        let ny = n / nx;
        // Cell aspect (width/nx) / (height/ny), compared on a log scale.
        let cost = (aspect * ny as f64 / nx as f64).ln().abs();
        if cost <= best_cost + 1e-12 {
            best = (nx, ny);
            best_cost = cost;
        }
    }
    best
}

/// Shirley and Chiu's concentric map from the unit square to the unit disk
/// ("A Low Distortion Map Between Disk and Square", 1997): squares around
/// the centre go to rings, and areas are preserved.
pub fn concentric(u: f64, v: f64) -> (f64, f64) {
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, FRAC_PI_2 - FRAC_PI_4 * (a / b))
    };
    (r * phi.cos(), r * phi.sin())
}

/// Sutherland–Hodgman: the part of `polygon` (points relative to the
/// receiver) with `n · p ≥ 0`.
fn clip_above(polygon: &[DVec3], n: DVec3) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(polygon.len() + 2);
    for (i, &a) in polygon.iter().enumerate() {
        let b = polygon[(i + 1) % polygon.len()];
        let (da, db) = (n.dot(a), n.dot(b));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let s = da / (da - db);
            out.push(a + (b - a) * s);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(samples: u32) -> AreaLight {
        AreaLight {
            shape: AreaShape::Rect {
                width: 2.0,
                height: 0.5,
            },
            position: DVec3::new(0.0, 2.0, 0.0),
            normal: DVec3::NEG_Y,
            tangent: DVec3::X,
            radiance: Rgb::new(1.0, 2.0, 3.0),
            samples,
            shadows: false,
            shadow_per_sample: false,
        }
    }

    fn sampled_irradiance(light: &AreaLight, n: u32, x: DVec3, normal: DVec3) -> Rgb {
        light
            .point_lights(0, n)
            .iter()
            .map(|l| {
                let inc = l.incidence(x);
                inc.irradiance * normal.dot(inc.wi).max(0.0)
            })
            .sum()
    }

    #[test]
    fn grids_have_exactly_n_cells_close_to_square() {
        assert_eq!(grid(16, 1.0), (4, 4));
        assert_eq!(grid(16, 4.0), (8, 2));
        assert_eq!(grid(7, 1.0), (7, 1));
        assert_eq!(grid(1, 3.0), (1, 1));
        for n in 1..300 {
            let (nx, ny) = grid(n, 1.7);
            assert_eq!(nx * ny, n);
        }
    }

    #[test]
    fn samples_lie_on_the_shape_and_are_centred() {
        let light = rect(16);
        let points = light.sample_positions(16);
        assert_eq!(points.len(), 16);
        let mean: DVec3 = points.iter().sum::<DVec3>() / 16.0;
        assert!((mean - light.position).length() < 1e-12);
        for p in &points {
            let d = *p - light.position;
            assert!(d.dot(light.normal).abs() < 1e-12);
            assert!(d.x.abs() < 1.0 && d.z.abs() < 0.25);
        }
        let disk = AreaLight {
            shape: AreaShape::Disk { radius: 0.3 },
            ..rect(64)
        };
        for p in disk.sample_positions(64) {
            assert!((p - disk.position).length() < 0.3);
        }
    }

    #[test]
    fn concentric_map_preserves_area() {
        // Equal cells map to equal areas: the fraction of a fine grid that
        // lands within radius r is r².
        let n = 200;
        let mut inside = 0;
        for i in 0..n {
            for j in 0..n {
                let (x, y) = concentric((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                if x * x + y * y < 0.25 {
                    inside += 1;
                }
            }
        }
        let fraction = inside as f64 / (n * n) as f64;
        assert!((fraction - 0.25).abs() < 0.01, "{fraction}");
    }

    #[test]
    fn exact_irradiance_matches_the_far_field_and_many_samples() {
        let light = rect(1);
        // Far away the light is a point of intensity L·A·cos.
        let x = DVec3::new(0.3, -200.0, 0.1);
        let d = light.position - x;
        let far = light.radiance * light.area() / d.length_squared() * (d.normalize().y).powi(2);
        let e = light.exact_irradiance(x, DVec3::Y);
        assert!(((e - far) / far).abs().max_element() < 1e-3, "{e} vs {far}");
        // Close by, many samples converge to it (midpoint rule: O(1/N)).
        let x = DVec3::new(0.7, 0.5, -0.4);
        let exact = light.exact_irradiance(x, DVec3::Y);
        let many = sampled_irradiance(&light, 256 * 64, x, DVec3::Y);
        assert!(
            ((many - exact) / exact).abs().max_element() < 1e-4,
            "{many} vs {exact}"
        );
        // A tilted receiver sees part of the light below its horizon.
        let n = DVec3::new(1.0, 0.2, 0.0).normalize();
        let x = DVec3::new(0.0, 1.0, 0.0);
        let exact = light.exact_irradiance(x, n);
        let many = sampled_irradiance(&light, 512 * 128, x, n);
        assert!(
            ((many - exact) / exact).abs().max_element() < 1e-3,
            "{many} vs {exact}"
        );
        // Behind the emitter: nothing.
        assert_eq!(
            light.exact_irradiance(DVec3::new(0.0, 3.0, 0.0), DVec3::NEG_Y),
            Rgb::ZERO
        );
    }

    #[test]
    fn disk_exact_irradiance_matches_the_on_axis_formula() {
        // On the axis of a disk of radius R at height h: E = L·π·R²/(R²+h²).
        let (r, h) = (0.5, 1.5);
        let light = AreaLight {
            shape: AreaShape::Disk { radius: r },
            position: DVec3::new(0.0, h, 0.0),
            ..rect(1)
        };
        let e = light.exact_irradiance(DVec3::ZERO, DVec3::Y);
        let want = light.radiance * (PI * r * r / (r * r + h * h));
        assert!(
            ((e - want) / want).abs().max_element() < 1e-6,
            "{e} vs {want}"
        );
    }

    #[test]
    fn sampled_error_falls_with_n() {
        let light = rect(1);
        let x = DVec3::new(0.5, 0.0, 0.3);
        let exact = light.exact_irradiance(x, DVec3::Y);
        let mut last = f64::INFINITY;
        for n in [1, 4, 16, 64, 256] {
            let e = sampled_irradiance(&light, n, x, DVec3::Y);
            let err = ((e - exact) / exact).abs().max_element();
            assert!(err < last, "N = {n}: {err} ≥ {last}");
            last = err;
        }
    }
}
