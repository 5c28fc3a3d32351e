//! The integrated truth: a quadrature of the map over the sphere.
//!
//! Each texel is taken as constant radiance over its patch of the sphere
//! (`φ` in its column, `cos θ` in its row, solid angle
//! `(2π/W)(cos θ_top − cos θ_bottom)`); the patch is integrated with the
//! midpoint rule in `φ` and 3-point Gauss–Legendre in `cos θ`. For a
//! polynomial of degree ≤ 4 in the direction (the SH bands gonio uses)
//! this is exact: the midpoint sum of a trigonometric polynomial of
//! degree < W over a full period is exact, and 3 Gauss points integrate
//! degree 5 in `cos θ`. So a constant map projects to band 0 alone, to
//! f64 rounding, and the white furnace holds exactly.
//!
//! The clamped cosine's kink at the horizon is what a texel quadrature
//! integrates worst (about 10⁻³ of `E` on a 32 × 16 map). So [`Truth`]
//! uses the map's own band-0–4 projection as a control variate: the
//! projected part is integrated exactly by the Funk–Hecke theorem
//! ([`super::sh`]), and only the residual `L − L_≤4` goes through the
//! quadrature. A constant map has no residual: its irradiance is exact
//! (the white furnace), and smooth skies leave a small one.
//!
//! Maps larger than [`MAX_TEXELS`] are box-filtered by 2 × 2 (weighted by
//! solid angle, so the power `∫ L dω` is unchanged) until they fit, to
//! bound the reference's per-pixel cost; the filter changes only
//! frequencies far above band 4 and the irradiance (a cosine-weighted
//! integral) by less than the kernel's curvature over two texels.

use super::latlong;
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::TAU;

/// Texels of the largest grid the quadrature runs on (128 × 64: 24 576
/// nodes, the reference's cost per shading point).
pub const MAX_TEXELS: usize = 128 * 64;

/// Gauss–Legendre nodes and weights on [−1, 1], 3 points.
const GAUSS_3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// One node: direction, weight (solid angle, sr) and radiance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    pub direction: DVec3,
    pub weight: f64,
    pub radiance: Rgb,
}

/// The nodes of a `width × height` map's texels (row-major, row 0 at
/// +Y), box-filtered to at most [`MAX_TEXELS`].
pub fn nodes(width: u32, height: u32, texels: &[[f32; 3]]) -> Vec<Node> {
    let (w, h, grid) = reduced_grid(width, height, texels, MAX_TEXELS);
    let mut out = Vec::with_capacity(3 * grid.len());
    for row in 0..h {
        let (top, bottom) = latlong::row_cos_bounds(row, h);
        let (mid, half) = (0.5 * (top + bottom), 0.5 * (top - bottom));
        for col in 0..w {
            let radiance = grid[(row * w + col) as usize];
            let phi = TAU * (col as f64 + 0.5) / w as f64;
            for (x, g) in GAUSS_3 {
                out.push(Node {
                    direction: latlong::direction_phi_cos(phi, mid + half * x),
                    weight: g * half * TAU / w as f64,
                    radiance,
                });
            }
        }
    }
    out
}

/// A `width × height` map's texels in f64, box-filtered by 2 × 2 (each
/// texel the solid-angle weighted mean of the 2 × 2 it covers, which
/// keeps the power `∫ L dω`) while they are more than `max_texels` and
/// both sides even: `(width, height, texels)`.
pub fn reduced_grid(
    width: u32,
    height: u32,
    texels: &[[f32; 3]],
    max_texels: usize,
) -> (u32, u32, Vec<Rgb>) {
    let (mut w, mut h) = (width, height);
    let too_many = |w: u32, h: u32| {
        (w as usize) * (h as usize) > max_texels && w.is_multiple_of(2) && h.is_multiple_of(2)
    };
    let texel = |i: usize| Rgb::from(texels[i].map(f64::from));
    // The first halving reads the f32 texels directly: a full-size f64
    // copy of a large map (24 bytes a texel, twice the texels' own) would
    // be the load's peak.
    let mut grid: Vec<Rgb> = if too_many(w, h) {
        let half = halve(w, h, texel);
        w /= 2;
        h /= 2;
        half
    } else {
        (0..texels.len()).map(texel).collect()
    };
    while too_many(w, h) {
        grid = halve(w, h, |i| grid[i]);
        w /= 2;
        h /= 2;
    }
    (w, h, grid)
}

/// A map of half the width and height: each texel the solid-angle
/// weighted mean of the 2 × 2 it covers.
fn halve(w: u32, h: u32, grid: impl Fn(usize) -> Rgb) -> Vec<Rgb> {
    let solid = |row: u32| {
        let (top, bottom) = latlong::row_cos_bounds(row, h);
        top - bottom
    };
    let mut out = Vec::with_capacity((w as usize / 2) * (h as usize / 2));
    for row in 0..h / 2 {
        let (a, b) = (solid(2 * row), solid(2 * row + 1));
        for col in 0..w / 2 {
            let at = |r: u32, c: u32| grid((r * w + c) as usize);
            let upper = at(2 * row, 2 * col) + at(2 * row, 2 * col + 1);
            let lower = at(2 * row + 1, 2 * col) + at(2 * row + 1, 2 * col + 1);
            out.push((upper * a + lower * b) / (2.0 * (a + b)));
        }
    }
    out
}

/// `E(n) = ∫ L(ω) max(0, n·ω) dω` over `nodes`.
pub fn irradiance(nodes: &[Node], n: DVec3) -> Rgb {
    nodes.iter().fold(Rgb::ZERO, |sum, node| {
        let cos = n.dot(node.direction);
        if cos > 0.0 {
            sum + node.radiance * (cos * node.weight)
        } else {
            sum
        }
    })
}

/// The integrated irradiance of a map: its band-0–4 projection, exact,
/// plus the quadrature of the residual (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Truth {
    /// Radiance coefficients `L_lm`, bands 0–4.
    pub radiance_sh: Vec<Rgb>,
    /// `Â_l · L_lm`: the projected part's irradiance.
    irradiance_sh: [Rgb; super::sh::COUNT],
    /// The nodes with the residual radiance `L − Σ L_lm Y_lm`.
    residual: Vec<Node>,
}

impl Truth {
    /// The truth of a `width × height` map (row-major, row 0 at +Y).
    pub fn new(width: u32, height: u32, texels: &[[f32; 3]]) -> Truth {
        let mut nodes = nodes(width, height, texels);
        let radiance_sh = project(&nodes);
        let irradiance_sh = super::sh::irradiance_coefficients(&radiance_sh, super::sh::MAX_ORDER);
        let low: [Rgb; super::sh::COUNT] = std::array::from_fn(|i| radiance_sh[i]);
        for node in &mut nodes {
            node.radiance -= super::sh::evaluate(&low, node.direction);
        }
        nodes.retain(|n| n.radiance != Rgb::ZERO);
        Truth {
            radiance_sh,
            irradiance_sh,
            residual: nodes,
        }
    }

    /// `E(n) = ∫ L(ω) max(0, n·ω) dω` (unscaled).
    pub fn irradiance(&self, n: DVec3) -> Rgb {
        super::sh::evaluate(&self.irradiance_sh, n) + irradiance(&self.residual, n)
    }
}

/// The radiance's SH coefficients `L_lm = ∫ L(ω) Y_lm(ω) dω`, bands 0–4.
pub fn project(nodes: &[Node]) -> Vec<Rgb> {
    let mut out = vec![Rgb::ZERO; super::sh::COUNT];
    for node in nodes {
        for (c, y) in out.iter_mut().zip(super::sh::basis(node.direction)) {
            *c += node.radiance * (y * node.weight);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_constant_map_is_a_furnace() {
        let (w, h) = (32, 16);
        let nodes = nodes(w, h, &vec![[1.0; 3]; (w * h) as usize]);
        let total: f64 = nodes.iter().map(|n| n.weight).sum();
        assert!((total - 4.0 * PI).abs() < 1e-12);
        for n in [DVec3::Y, DVec3::new(0.6, -0.48, 0.64)] {
            let e = irradiance(&nodes, n.normalize());
            // The kink of max(0, cos) at the horizon is not integrated
            // exactly: about 1e-3 at 32 × 16.
            assert!((e.x - PI).abs() < 5e-3 * PI, "{e}");
        }
        let c = project(&nodes);
        assert!((c[0].x - (4.0 * PI).sqrt()).abs() < 1e-12);
        for (i, c) in c.iter().enumerate().skip(1) {
            assert!(c.abs().max_element() < 1e-12, "L_{i} = {c}");
        }
    }

    #[test]
    fn the_truth_of_a_constant_map_is_exact() {
        let (w, h) = (32, 16);
        let truth = Truth::new(w, h, &vec![[0.5; 3]; (w * h) as usize]);
        for n in [DVec3::Y, DVec3::new(0.6, -0.48, 0.64)] {
            let e = truth.irradiance(n.normalize());
            assert!(
                (e - Rgb::splat(0.5 * PI)).abs().max_element() < 1e-12,
                "{e}"
            );
        }
    }

    #[test]
    fn the_control_variate_does_not_change_the_integral() {
        // One bright texel: the truth and the plain quadrature agree away
        // from the texel's horizon (where the plain one is worst).
        let (w, h) = (16, 8);
        let mut texels = vec![[0.0f32; 3]; (w * h) as usize];
        texels[(2 * w + 5) as usize] = [10.0, 10.0, 10.0];
        let truth = Truth::new(w, h, &texels);
        let plain = nodes(w, h, &texels);
        let d = latlong::texel_direction(5, 2, w, h);
        for n in [d, (d + DVec3::Y).normalize()] {
            let (a, b) = (truth.irradiance(n).x, irradiance(&plain, n).x);
            assert!((a - b).abs() < 1e-3 * b, "{a} vs {b}");
        }
    }

    #[test]
    fn halving_keeps_the_power() {
        let (w, h) = (8, 4);
        let texels: Vec<[f32; 3]> = (0..w * h).map(|i| [i as f32, 1.0, 0.0]).collect();
        let full = nodes(w, h, &texels);
        let grid: Vec<Rgb> = texels.iter().map(|t| Rgb::from(t.map(f64::from))).collect();
        let half = halve(w, h, |i| grid[i]);
        let power = |g: &[Rgb], w: u32, h: u32| -> Rgb {
            (0..h)
                .flat_map(|r| (0..w).map(move |c| (r, c)))
                .map(|(r, c)| {
                    let (top, bottom) = latlong::row_cos_bounds(r, h);
                    g[(r * w + c) as usize] * (TAU / w as f64 * (top - bottom))
                })
                .sum()
        };
        let p: Rgb = full.iter().map(|n| n.radiance * n.weight).sum();
        assert!((power(&half, w / 2, h / 2) - p).abs().max_element() < 1e-9);
    }
}
