//! The sheen's directional albedo `E(μ)` at one sheen `α`, as a curve the
//! explorer reads instead of the exact integral at every outgoing
//! direction.
//!
//! Why: the layered `f_r` scales the base by `1 − max₃(C) E(μ_o)`
//! (`brdf::gltf_layers::stack`), and the exact `E` is an adaptive
//! quadrature of its own (`sheen_albedo`). An albedo, a gloss value or a
//! plot of a material with sheen asks for `E` at every outgoing
//! direction it evaluates, each a new `μ_o`, so a directional albedo
//! took minutes. Here `E` is computed exactly at `2 ×` [`NODES`] values
//! of `μ ≥` [`MU_LOW`] once per `α` and read by cubic interpolation in
//! between; below [`MU_LOW`] (θ > 89.994°) [`SheenCurve::at`] computes
//! it exactly, as there the specified `V_sh` makes `E` rise to a cusp
//! near `μ ≈ 10⁻⁶` (E ≈ 2.7 at `r_sh = 0.1`) that no table resolves,
//! and an albedo's quadrature asks for few such directions.
//!
//! The curve is two pieces that meet at `μ = ½`, where `E` has a kink
//! (the fit of Charlie's `Λ` changes branch there, `sheen::sheen_lambda`),
//! so that no cubic spans it. Below, the nodes are equally spaced in
//! `u = μ^¼`, as the GPU's table
//! ([`SHEEN_ALBEDO_TABLE_SIZE`](crate::material::brdf::gltf_layers::sheen_albedo::SHEEN_ALBEDO_TABLE_SIZE))
//! spreads the steep rise of `E` near grazing (it varies with `log μ`);
//! above, in `θ = acos μ`, in which `E` is smooth at normal incidence (in
//! `μ` or `u` it goes as `√(1 − μ)` there).
//! The interpolation is the cubic through the four nearest nodes
//! (Lagrange, one-sided at the ends). Its error is measured when the
//! curve is built, at the midpoint of every interval against the exact
//! integral: [`SheenCurve::error`] is twice the largest difference (an
//! a-posteriori estimate, as the albedo's own bound is; for a smooth `E`
//! a cubic's error peaks near an interval's middle). The explorer adds
//! `max₃(C) · error` to an albedo's error bound: the base's albedo, which
//! the scaling multiplies, is at most 1.

use crate::material::brdf::gltf_layers::sheen_albedo::sheen_albedo;
use rayon::prelude::*;
use std::f64::consts::FRAC_PI_3;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Nodes on each side of `μ = ½`.
pub const NODES: usize = 1025;

/// Below this `μ` the curve is the exact integral (the module doc).
pub const MU_LOW: f64 = 1e-4;

/// The pieces' ends in their coordinates: `u = μ^¼` from [`MU_LOW`] to
/// `½`, `θ = acos μ` from `π/3` (`μ = ½`) to 0.
const PIECES: [(f64, f64); 2] = [(0.1, 0.840_896_415_253_714_6), (FRAC_PI_3, 0.0)];

/// `E(μ)` at one sheen `α` ([`SheenCurve::at`]), and the bound on its
/// interpolation error.
#[derive(Debug)]
pub struct SheenCurve {
    alpha: f64,
    values: Vec<f64>,
    /// `|E_exact(μ) − at(μ)|` is below this (measured, see the module
    /// doc).
    pub error: f64,
}

impl SheenCurve {
    /// The curve of sheen `α` (`α_sh = r_sh²`): `2 ×` [`NODES`] exact
    /// integrals and as many checks, in parallel.
    pub fn new(alpha: f64) -> SheenCurve {
        let last = (NODES - 1) as f64;
        let values: Vec<f64> = (0..2 * NODES)
            .into_par_iter()
            .map(|i| sheen_albedo(mu_at(i / NODES, (i % NODES) as f64 / last), alpha))
            .collect();
        let mut curve = SheenCurve {
            alpha,
            values,
            error: 0.0,
        };
        let largest = (0..2 * (NODES - 1))
            .into_par_iter()
            .map(|i| {
                let t = ((i % (NODES - 1)) as f64 + 0.5) / last;
                let mu = mu_at(i / (NODES - 1), t);
                (curve.at(mu) - sheen_albedo(mu, alpha)).abs()
            })
            .reduce(|| 0.0, f64::max);
        curve.error = 2.0 * largest;
        curve
    }

    /// `E(μ)` by cubic interpolation in the piece's coordinate (`μ`
    /// clamped to [0, 1]), exact below [`MU_LOW`].
    pub fn at(&self, mu: f64) -> f64 {
        if mu < MU_LOW {
            return sheen_albedo(mu.max(0.0), self.alpha);
        }
        let mu = mu.min(1.0);
        let piece = usize::from(mu >= 0.5);
        let (lo, hi) = PIECES[piece];
        let coordinate = if piece == 0 {
            mu.sqrt().sqrt()
        } else {
            mu.acos()
        };
        let last = NODES - 1;
        let x = ((coordinate - lo) / (hi - lo)).clamp(0.0, 1.0) * last as f64;
        // The four nodes around x, kept inside the piece.
        let first = (x.floor() as usize).saturating_sub(1).min(last - 3);
        let t = x - first as f64;
        let start = piece * NODES + first;
        let v = &self.values[start..start + 4];
        // Lagrange through nodes 0, 1, 2, 3 at t.
        let (a, b, c, d) = (t, t - 1.0, t - 2.0, t - 3.0);
        -v[0] * b * c * d / 6.0 + v[1] * a * c * d / 2.0 - v[2] * a * b * d / 2.0
            + v[3] * a * b * c / 6.0
    }
}

/// `μ` at position `t` ∈ [0, 1] of piece `piece`.
fn mu_at(piece: usize, t: f64) -> f64 {
    let (lo, hi) = PIECES[piece];
    let x = lo + (hi - lo) * t;
    if piece == 0 {
        let s = x * x;
        s * s
    } else {
        x.cos()
    }
}

/// Curves kept, most recently used last: a viewer dragging the sheen's
/// roughness asks for a new `α` every frame, and builds each once.
pub const KEPT: usize = 8;

static CURVES: Mutex<Vec<Arc<SheenCurve>>> = Mutex::new(Vec::new());

/// The curve of sheen `α`, built on first use and kept for the next
/// [`KEPT`] distinct `α` asked for.
pub fn sheen_curve(alpha: f64) -> Arc<SheenCurve> {
    let found = {
        let mut kept = CURVES.lock().unwrap_or_else(|e| e.into_inner());
        let at = kept
            .iter()
            .position(|c| c.alpha.to_bits() == alpha.to_bits());
        at.map(|i| {
            let c = kept.remove(i);
            kept.push(c.clone());
            c
        })
    };
    if let Some(c) = found {
        return c;
    }
    let curve = Arc::new(SheenCurve::new(alpha));
    let mut kept = CURVES.lock().unwrap_or_else(|e| e.into_inner());
    if kept.len() >= KEPT {
        kept.remove(0);
    }
    kept.push(curve.clone());
    curve
}

/// Exact evaluations a [`SheenAlbedo`] answers before it builds its curve.
pub const EXACT_CALLS: u32 = 256;

/// `E(μ)` at one sheen `α` for the explorer: exact for the first
/// [`EXACT_CALLS`] directions asked (a printed value, a probe), from the
/// curve after (an albedo, a gloss reading, a plot), which is then built
/// once, in [`sheen_curve`]'s store.
#[derive(Debug)]
pub struct SheenAlbedo {
    alpha: f64,
    calls: AtomicU32,
    curve: OnceLock<Arc<SheenCurve>>,
}

impl SheenAlbedo {
    pub fn new(alpha: f64) -> SheenAlbedo {
        SheenAlbedo {
            alpha,
            calls: AtomicU32::new(0),
            curve: OnceLock::new(),
        }
    }

    /// `E(μ)`: the exact integral or the curve (the type's doc).
    pub fn at(&self, mu: f64) -> f64 {
        if let Some(curve) = self.curve.get() {
            return curve.at(mu);
        }
        if self.calls.fetch_add(1, Ordering::Relaxed) < EXACT_CALLS {
            return sheen_albedo(mu.clamp(0.0, 1.0), self.alpha);
        }
        self.curve.get_or_init(|| sheen_curve(self.alpha)).at(mu)
    }

    /// The error of what [`SheenAlbedo::at`] returned so far: the curve's
    /// once it is read, 0 before.
    pub fn error(&self) -> f64 {
        self.curve.get().map_or(0.0, |c| c.error)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::brdf::gltf_layers::sheen::sheen_alpha;

    /// The curve is the exact `E` within its stated error at points
    /// between the nodes other than the midpoints it was measured at, and
    /// that error is small against the explorer's own tolerances (the
    /// albedo's outer panels stop at 10⁻⁸ of the integral).
    #[test]
    fn the_curve_is_the_exact_albedo_within_its_error() {
        for r in [0.1, 0.4] {
            let alpha = sheen_alpha(r);
            let start = std::time::Instant::now();
            let curve = SheenCurve::new(alpha);
            eprintln!(
                "r_sh {r}: error {:.2e}, built in {:.2} s",
                curve.error,
                start.elapsed().as_secs_f64()
            );
            assert!(curve.error < 1e-8, "r_sh {r}: {}", curve.error);
            for k in 0..200 {
                let mu = mu_at(k % 2, (k as f64 + 0.37) / 200.0);
                let d = (curve.at(mu) - sheen_albedo(mu, alpha)).abs();
                assert!(
                    d <= curve.error,
                    "r_sh {r} μ {mu}: {d:e} > {:e}",
                    curve.error
                );
            }
            for mu in [0.0, 1e-6, 0.5 * MU_LOW, MU_LOW, 0.5, 1.0] {
                let d = (curve.at(mu) - sheen_albedo(mu, alpha)).abs();
                assert!(d < 1e-12, "r_sh {r} μ {mu}: {d:e} at a node or below it");
            }
        }
    }
}
