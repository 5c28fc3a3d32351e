//! The fixed set of direction pairs a fit compares model and measurement
//! on: a grid over MERL's own half/difference parametrisation (θ_h in
//! MERL's square-root spacing, θ_d linear, φ_d over [0, π): isotropy fixes
//! φ_h, reciprocity folds φ_d by π), thinned to [`GRID`] cells, each cell
//! centre weighted by the solid-angle measure of its cell.
//!
//! The measure: `dω_i dω_o = 4 cos θ_d dω_h dω_d` (Rusinkiewicz 1998), so
//! a cell of the `(θ_h, θ_d, φ_d)` grid (φ_h integrated out) has weight
//! `cos θ_d sin θ_d sin θ_h Δθ_h Δθ_d Δφ_d`; constants cancel in the
//! metrics. Pairs with `θ_i` or `θ_o` beyond [`MAX_THETA_DEG`] are left
//! out, as Ngan et al. 2005 do ("measurements beyond 80° are unreliable").

use crate::base::Rgb;
use crate::material::measured::MeasuredBrdf;
use crate::material::measured::coords::{directions, half_diff_of_angles};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// Cells along `(θ_h, θ_d, φ_d)`: MERL's `(90, 90, 180)` thinned by
/// `(3, 6, 12)`. Enough to resolve chrome's highlight (the first θ_h cell
/// centre sits at 0.016°, the second at 0.14°) at a cost a fit of 100
/// materials × 15 models on two cores can afford (docs/fit/ranking.md).
pub const GRID: [usize; 3] = [30, 15, 15];

/// Largest `θ_i`, `θ_o` sampled (Ngan et al. 2005's cut-off).
pub const MAX_THETA_DEG: f64 = 80.0;

/// One direction pair: where the model is evaluated (frame `t, b, n` =
/// `x, y, z`), the measurement there, and the pair's weight.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub wi: DVec3,
    pub wo: DVec3,
    /// `f_r` measured [1/sr], per channel (`max(0, ·)` of the source).
    pub measured: Rgb,
    /// The cell's solid-angle weight, normalized so that all sum to 1.
    pub weight: f64,
}

/// The grid's cell centres and weights, without measurements: the same
/// for every material.
fn grid() -> Vec<(f64, f64, f64, f64)> {
    let [n_h, n_d, n_p] = GRID;
    let cos_max = MAX_THETA_DEG.to_radians().cos();
    let mut cells = Vec::with_capacity(n_h * n_d * n_p);
    for i in 0..n_h {
        // MERL's θ_h axis: θ_h = (π/2) u², u uniform; the cell's width in
        // θ_h is (π/2) 2u Δu.
        let u = (i as f64 + 0.5) / n_h as f64;
        let theta_h = FRAC_PI_2 * u * u;
        let d_theta_h = FRAC_PI_2 * 2.0 * u / n_h as f64;
        for j in 0..n_d {
            let theta_d = (j as f64 + 0.5) / n_d as f64 * FRAC_PI_2;
            let d_theta_d = FRAC_PI_2 / n_d as f64;
            for k in 0..n_p {
                let phi_d = (k as f64 + 0.5) / n_p as f64 * PI;
                let d_phi_d = PI / n_p as f64;
                let (wi, wo) = directions(theta_h, theta_d, phi_d);
                if wi.z < cos_max || wo.z < cos_max {
                    continue;
                }
                let w =
                    theta_d.cos() * theta_d.sin() * theta_h.sin() * d_theta_h * d_theta_d * d_phi_d;
                cells.push((theta_h, theta_d, phi_d, w));
            }
        }
    }
    cells
}

/// The samples of `brdf`: every grid cell above the cut-off with its
/// measured value.
pub fn samples(brdf: &MeasuredBrdf) -> Vec<Sample> {
    samples_of(|theta_h, theta_d, phi_d, _, _| {
        brdf.f_r_half_diff(&half_diff_of_angles(theta_h, theta_d, phi_d))
            .max(Rgb::ZERO)
    })
}

/// The samples of any `f_r(θ_h, θ_d, φ_d, ω_i, ω_o)` (a synthetic
/// "measurement" made from a model, for tests).
pub fn samples_of(f_r: impl Fn(f64, f64, f64, DVec3, DVec3) -> Rgb) -> Vec<Sample> {
    let cells = grid();
    let total: f64 = cells.iter().map(|c| c.3).sum();
    cells
        .into_iter()
        .map(|(theta_h, theta_d, phi_d, w)| {
            let (wi, wo) = directions(theta_h, theta_d, phi_d);
            Sample {
                wi,
                wo,
                measured: f_r(theta_h, theta_d, phi_d, wi, wo),
                weight: w / total,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weights are the measure of the pairs: for a constant `f_r` the
    /// weighted sum of `cos θ_i` over all pairs (no cut-off) would be the
    /// mean of `cos θ_i` over the 4-D domain; here we check the simpler
    /// facts that hold with the cut-off: positive weights summing to 1, and
    /// every pair above the cut-off.
    #[test]
    fn the_grid_is_above_the_cut_off_and_normalized() {
        let s = samples_of(|_, _, _, _, _| Rgb::ONE);
        let cos_max = MAX_THETA_DEG.to_radians().cos();
        assert!(s.len() > GRID.iter().product::<usize>() / 3, "{}", s.len());
        assert!(
            s.iter()
                .all(|s| s.weight > 0.0 && s.wi.z >= cos_max && s.wo.z >= cos_max)
        );
        let sum: f64 = s.iter().map(|s| s.weight).sum();
        assert!((sum - 1.0).abs() < 1e-12);
    }
}
