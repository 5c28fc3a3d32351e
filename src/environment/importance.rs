//! Importance sampling of a map by its texels: directions drawn with a
//! density proportional to the radiance they bring, so a small bright
//! source (a sun) is found by a few samples where cosine or BRDF-lobe
//! directions rarely hit it (the third strategy of
//! `environment.specular = "sampled"`, `crate::reference::environment::sampled`).
//!
//! The density is piecewise constant over a grid of the map's texels
//! (the map itself, box-filtered by 2 × 2 until it has at most
//! [`MAX_TEXELS`], as the quadrature does, so the table stays small for
//! any map): texel `t` of weight `w_t` (the mean of its R, G and B, so
//! every texel that brings light has a weight) and solid angle `Ω_t` is
//! drawn with probability `w_t Ω_t / Σ w Ω`, and within it uniformly in
//! solid angle (uniform in `φ` across its column and in `cos θ` across
//! its row). So the density of a direction in texel `t` is
//! `p(ω) = w_t / Σ w Ω` [1/sr] (pbrt-v4's `PiecewiseConstant2D` over the
//! lat-long image, with the `sin θ` of its solid angle folded into the
//! weights; Pharr, Jakob & Humphreys, *Physically Based Rendering* 4th
//! ed., §A.5 and §12.5.2).
//!
//! A direction is drawn from two variates by inverting the cumulative
//! distributions continuously: `u₁` picks the row by the marginal CDF and
//! its fraction within the row's probability places `cos θ`; `u₂` picks
//! the column by the row's conditional CDF and its fraction places `φ`.
//! The inversion is continuous in `(u₁, u₂)`, so a variate on a bin's
//! boundary gives the same direction on either side of it, and the f32
//! twin draws the directions of the f64 one up to rounding.
//!
//! The sampled mode draws map directions only where the map's light is
//! concentrated ([`ImportanceTable::concentrated`]: somewhere at least
//! [`CONCENTRATION`] times as dense as on average). Directions of a
//! uniform map are uniform over the sphere, half of them below any
//! surface: cosine and lobe directions use those samples better, and a
//! white map then keeps the cosine estimate's exact furnace. A black map
//! has no distribution at all ([`ImportanceTable::usable`] false).
//!
//! WGSL twin: `importance_direction` and `importance_pdf` in
//! shaders/environment_sampled.wgsl (the GPU reads this table, rounded to
//! f32, [`ImportanceTable::gpu_entries`]).

use super::{latlong, quadrature};
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// Texels of the largest grid the table is built on (1024 × 512): a
/// 2.5° sun covers about 50 of them, and the f32 table is 8 MiB.
pub const MAX_TEXELS: usize = 1024 * 512;

/// How much denser than the uniform `1/(4π)` the densest texel must be
/// for the sampled mode to draw map directions: with half of uniform
/// directions below the surface, drawing by the map pays from about 2.
pub const CONCENTRATION: f64 = 2.0;

/// The distribution of a map's directions.
#[derive(Debug, PartialEq)]
pub struct ImportanceTable {
    pub width: u32,
    pub height: u32,
    /// `rows[r]`: the probability of rows `0..=r` (the last is exactly 1;
    /// all 0 for a black map).
    pub rows: Vec<f64>,
    /// `columns[r·W + c]`: the probability of columns `0..=c` within row
    /// `r` (each row's last is exactly 1; a row without light is uniform).
    pub columns: Vec<f64>,
    /// `density[r·W + c]`: the density of a direction in texel `(c, r)`,
    /// `w_t / Σ w Ω` [1/sr].
    pub density: Vec<f64>,
    /// The largest density.
    pub peak: f64,
}

impl ImportanceTable {
    /// The table of a `width × height` map (row-major, row 0 at +Y).
    pub fn new(width: u32, height: u32, texels: &[[f32; 3]]) -> ImportanceTable {
        let (w, h, grid) = quadrature::reduced_grid(width, height, texels, MAX_TEXELS);
        let weight = |t: Rgb| (t.x + t.y + t.z) / 3.0;
        let mut row_sums = Vec::with_capacity(h as usize);
        let mut columns = Vec::with_capacity(grid.len());
        for r in 0..h as usize {
            let row = &grid[r * w as usize..(r + 1) * w as usize];
            let sum: f64 = row.iter().map(|&t| weight(t)).sum();
            let mut running = 0.0;
            for (c, &t) in row.iter().enumerate() {
                running += weight(t);
                columns.push(if c + 1 == w as usize {
                    1.0
                } else if sum > 0.0 {
                    running / sum
                } else {
                    (c + 1) as f64 / w as f64
                });
            }
            row_sums.push(sum);
        }
        // Σ w Ω: a row's texels share Ω = (2π/W)(cos θ_top − cos θ_bottom).
        let row_power: Vec<f64> = row_sums
            .iter()
            .enumerate()
            .map(|(r, &s)| s * texel_solid_angle(r as u32, w, h))
            .collect();
        let total: f64 = row_power.iter().sum();
        let mut rows = Vec::with_capacity(h as usize);
        let mut running = 0.0;
        for (r, p) in row_power.iter().enumerate() {
            running += p;
            rows.push(if total <= 0.0 {
                0.0
            } else if r + 1 == h as usize {
                1.0
            } else {
                running / total
            });
        }
        let density: Vec<f64> = grid
            .iter()
            .map(|&t| if total > 0.0 { weight(t) / total } else { 0.0 })
            .collect();
        let peak = density.iter().fold(0.0f64, |m, &p| m.max(p));
        ImportanceTable {
            width: w,
            height: h,
            rows,
            columns,
            density,
            peak,
        }
    }

    /// Whether the map brings any light to draw directions by.
    pub fn usable(&self) -> bool {
        self.rows.last() == Some(&1.0)
    }

    /// Whether the sampled mode draws directions by this map: it has
    /// light, and its densest texel is at least [`CONCENTRATION`] times
    /// the uniform density `1/(4π)`.
    pub fn concentrated(&self) -> bool {
        self.usable() && self.peak * 4.0 * PI >= CONCENTRATION
    }

    /// The direction (the map's frame) of the variates `u₁, u₂ ∈ [0, 1)`.
    /// Twin: `importance_direction`.
    pub fn direction(&self, u1: f64, u2: f64) -> DVec3 {
        let (row, fr) = invert(|r| self.rows[r as usize], self.height, u1);
        let start = (row * self.width) as usize;
        let (col, fc) = invert(|c| self.columns[start + c as usize], self.width, u2);
        let (top, bottom) = latlong::row_cos_bounds(row, self.height);
        let cos_theta = top + (bottom - top) * fr;
        let phi = TAU * (col as f64 + fc) / self.width as f64;
        latlong::direction_phi_cos(phi, cos_theta)
    }

    /// The density [1/sr] of direction `d` (the map's frame, unit).
    /// Twin: `importance_pdf`.
    pub fn pdf(&self, d: DVec3) -> f64 {
        let (u, v) = latlong::uv(d);
        let col = ((u * self.width as f64) as u32).min(self.width - 1);
        let row = ((v * self.height as f64) as u32).min(self.height - 1);
        self.density[(row * self.width + col) as usize]
    }

    /// The table as the GPU reads it (`EnvironmentImportance` in
    /// shaders/environment_sampled.wgsl): per texel `(columns, density,
    /// rows of its row, 0)` in f32, row-major.
    pub fn gpu_entries(&self) -> Vec<[f32; 4]> {
        (0..self.columns.len())
            .map(|k| {
                let row = k / self.width as usize;
                [
                    self.columns[k] as f32,
                    self.density[k] as f32,
                    self.rows[row] as f32,
                    0.0,
                ]
            })
            .collect()
    }
}

/// The solid angle of a texel of row `row` of a `width × height` grid.
fn texel_solid_angle(row: u32, width: u32, height: u32) -> f64 {
    let (top, bottom) = latlong::row_cos_bounds(row, height);
    TAU / width as f64 * (top - bottom)
}

/// The bin of `u` under the cumulative distribution `cdf(0..n)` (its
/// first entry above `u`) and `u`'s fraction within that bin's
/// probability. Twin: `importance_invert`.
fn invert(cdf: impl Fn(u32) -> f64, n: u32, u: f64) -> (u32, f64) {
    // The first i with cdf(i) > u, by bisection (as the twin).
    let (mut lo, mut hi) = (0u32, n);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if cdf(mid) <= u {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    let i = lo.min(n - 1);
    let below = if i == 0 { 0.0 } else { cdf(i - 1) };
    let width = cdf(i) - below;
    let f = if width > 0.0 {
        ((u - below) / width).clamp(0.0, 1.0)
    } else {
        0.5
    };
    (i, f)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::test_maps;

    /// The density integrates to 1 over the sphere (it is constant on
    /// each texel: `Σ p_t Ω_t = Σ w_t Ω_t / Σ w Ω`).
    #[test]
    fn the_density_integrates_to_one() {
        for map in [test_maps::blobs(), crate::environment::sky::map()] {
            let t = ImportanceTable::new(map.width, map.height, &map.texels);
            let mut sum = 0.0;
            for r in 0..t.height {
                for c in 0..t.width {
                    sum += t.density[(r * t.width + c) as usize]
                        * texel_solid_angle(r, t.width, t.height);
                }
            }
            assert!((sum - 1.0).abs() < 1e-12, "{}: {sum}", map.name);
        }
    }

    /// Every direction drawn lies in the texel its variates chose, and
    /// the density there is the one the table gives that texel: the
    /// estimator's weights `f L cos / (… + n_m p)` use `pdf` of the
    /// direction, so the two must agree. Under the sky, the sun's texels
    /// are drawn in proportion to their power: the fraction of 4096
    /// stratified directions within 3° of the sun is the sun's share of
    /// `Σ w Ω`, to the stratification's 1/4096.
    #[test]
    fn directions_fall_where_the_power_is() {
        let map = crate::environment::sky::map();
        let t = ImportanceTable::new(map.width, map.height, &map.texels);
        let sun = crate::environment::sky::sun_direction();
        let near_sun = |d: DVec3| d.dot(sun) > 3f64.to_radians().cos();
        let n = 4096;
        let mut hits = 0;
        for k in 0..n {
            let u1 = (k as f64 + 0.5) / n as f64;
            let u2 = (k as u32).reverse_bits() as f64 / 4_294_967_296.0;
            let d = t.direction(u1, u2);
            assert!((d.length() - 1.0).abs() < 1e-12);
            assert!(t.pdf(d) > 0.0, "a direction where the density is 0: {d}");
            hits += near_sun(d) as u32;
        }
        // The share of Σ w Ω within 3° of the sun, by the texels' centres.
        let mut share = 0.0;
        for r in 0..t.height {
            for c in 0..t.width {
                if near_sun(latlong::texel_direction(c, r, t.width, t.height)) {
                    share += t.density[(r * t.width + c) as usize]
                        * texel_solid_angle(r, t.width, t.height);
                }
            }
        }
        let got = hits as f64 / n as f64;
        // The share counts whole texels by their centres, the hits by the
        // directions: they differ by the power of the texels the 3° circle
        // cuts, at most the ring's (the sun's edge is inside 2.5°, so the
        // ring holds only the glow): a 5 % margin.
        assert!(share > 0.5, "the sun's share {share}");
        assert!(
            (got - share).abs() < 0.05 * share,
            "{got} of the directions near the sun, {share} of the power"
        );
    }

    /// Continuity at a bin's boundary: `u` just below and at a row's
    /// cumulative value give the same direction (to rounding).
    #[test]
    fn the_inversion_is_continuous() {
        let map = test_maps::blobs();
        let t = ImportanceTable::new(map.width, map.height, &map.texels);
        for r in (0..t.height - 1).step_by(5) {
            let u = t.rows[r as usize];
            // (A row without light between two is skipped by the
            // inversion: its edges are not shared.)
            if u <= 0.0 || u >= 1.0 || t.rows[r as usize + 1] == u {
                continue;
            }
            let a = t.direction(u - 1e-12, 0.3);
            let b = t.direction(u, 0.3);
            // Same cos θ at the shared edge; φ may differ (another row's
            // columns), so compare the heights.
            assert!((a.y - b.y).abs() < 1e-9, "row {r}: {a} vs {b}");
        }
    }

    #[test]
    fn a_black_map_has_no_distribution_and_a_white_one_is_not_drawn_by() {
        let map = test_maps::uniform(16, Rgb::ZERO);
        let t = ImportanceTable::new(map.width, map.height, &map.texels);
        assert!(!t.usable());
        let lit = test_maps::uniform(16, Rgb::ONE);
        let t = ImportanceTable::new(lit.width, lit.height, &lit.texels);
        // Uniform radiance: a uniform density 1/(4π), not concentrated.
        assert!(t.usable() && !t.concentrated());
        let p = t.pdf(DVec3::new(0.3, 0.5, -0.2).normalize());
        assert!((p - 1.0 / (4.0 * PI)).abs() < 1e-12, "{p}");
        let sky = crate::environment::sky::map();
        assert!(ImportanceTable::new(sky.width, sky.height, &sky.texels).concentrated());
    }
}
