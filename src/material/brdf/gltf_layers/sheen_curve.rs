//! The sheen's directional albedo `E(μ)` at one sheen `α`, as a curve read
//! instead of the exact integral at every direction.
//!
//! Why: the layered `f_r` scales the base by `1 − max₃(C) E(μ)` at both
//! directions ([`super::stack`]), and the exact `E` is an adaptive
//! quadrature of its own ([`super::sheen_albedo`], about a millisecond).
//! An image of the reference asks for it at every light sample of every
//! pixel (a 200 × 150 image with a 256-sample area light: 7.7 million
//! integrals, hours), an albedo or a plot of the explorer at every
//! direction it evaluates. Here `E` is computed exactly at `2 ×` [`NODES`]
//! values of `μ ≥` [`MU_LOW`] once per `α` and read by cubic
//! interpolation in between; below [`MU_LOW`] (θ > 89.994°)
//! [`SheenCurve::at`] computes it exactly, as there the specified `V_sh`
//! makes `E` rise to a cusp near `μ ≈ 10⁻⁶` (E ≈ 2.7 at `r_sh = 0.1`)
//! that no table resolves, and few directions fall there.
//!
//! This stays the contract's exact `E` (pinned choice 6: "the exact
//! directional albedo of the specified `D_sh V_sh`, not a table"): the
//! curve's error is measured against the integral when it is built and a
//! curve is read only when that error is below [`CURVE_ERROR_LIMIT`],
//! under the f32 rounding of `E` — unlike the GPU's fitted table
//! ([`super::sheen_albedo::SHEEN_ALBEDO_TABLE_ERROR`]), whose error is
//! part of what the GPU gets wrong.
//!
//! The curve is two pieces that meet at `μ = ½`, where `E` has a kink
//! (the fit of Charlie's `Λ` changes branch there, `sheen::sheen_lambda`),
//! so that no cubic spans it. Below, the nodes are equally spaced in
//! `u = μ^¼`, as the GPU's table
//! ([`SHEEN_ALBEDO_TABLE_SIZE`](super::sheen_albedo::SHEEN_ALBEDO_TABLE_SIZE))
//! spreads the steep rise of `E` near grazing (it varies with `log μ`);
//! above, in `θ = acos μ`, in which `E` is smooth at normal incidence (in
//! `μ` or `u` it goes as `√(1 − μ)` there).
//! The interpolation is the cubic through the four nearest nodes
//! (Lagrange, one-sided at the ends). Its error is measured when the
//! curve is built, at the midpoint of every interval against the exact
//! integral: [`SheenCurve::error`] is twice the largest difference (an
//! a-posteriori estimate; for a smooth `E` a cubic's error peaks near an
//! interval's middle). The explorer adds `max₃(C) · error` to an albedo's
//! error bound: the base's albedo, which the scaling multiplies, is at
//! most 1.

use super::sheen_albedo::sheen_albedo;
use rayon::prelude::*;
use std::cell::RefCell;
use std::f64::consts::FRAC_PI_3;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
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

/// Exact evaluations a [`SheenAlbedo`] answers before it builds its curve:
/// the curve's own cost in exact integrals (`4 ×` [`NODES`], with its
/// check). So an `α` asked for fewer times than that (a printed value, a
/// probe, one pixel of a sheen roughness texture) never pays for a curve,
/// and one asked for more (an image, an albedo, a plot) pays at most
/// twice what the exact integrals alone would have cost.
pub const EXACT_CALLS: u32 = 4 * NODES as u32;

/// The largest measured [`SheenCurve::error`] that is read; a coarser curve
/// is dropped and `E` stays exact. A sixth of the f32 rounding of `E ≈ 1`
/// (6·10⁻⁸), so no comparison with the GPU can see the curve; the
/// `sheen_roughness` values measured are inside it (the test below).
pub const CURVE_ERROR_LIMIT: f64 = 1e-8;

/// `E(μ)` at one sheen `α`: exact for the first [`EXACT_CALLS`]
/// directions asked, from the curve after, which the call past them
/// builds. Never blocks: while one thread builds the curve, the others
/// (and that thread itself, should a nested parallel loop hand it another
/// pixel) go on with the exact integral, so a build inside a parallel
/// render cannot wait on itself.
#[derive(Debug)]
pub struct SheenAlbedo {
    alpha: f64,
    calls: AtomicU32,
    building: AtomicBool,
    /// The curve once built; `None` inside when its error exceeded
    /// [`CURVE_ERROR_LIMIT`].
    curve: OnceLock<Option<SheenCurve>>,
}

impl SheenAlbedo {
    pub fn new(alpha: f64) -> SheenAlbedo {
        SheenAlbedo {
            alpha,
            calls: AtomicU32::new(0),
            building: AtomicBool::new(false),
            curve: OnceLock::new(),
        }
    }

    /// `E(μ)` (`μ` clamped to [0, 1]): the exact integral or the curve
    /// (the type's doc).
    pub fn at(&self, mu: f64) -> f64 {
        let mu = mu.clamp(0.0, 1.0);
        match self.curve.get() {
            Some(Some(curve)) => return curve.at(mu),
            Some(None) => return sheen_albedo(mu, self.alpha),
            None => {}
        }
        if self.calls.load(Ordering::Relaxed) < EXACT_CALLS {
            self.calls.fetch_add(1, Ordering::Relaxed);
        } else if !self.building.swap(true, Ordering::AcqRel) {
            let curve = SheenCurve::new(self.alpha);
            let usable = curve.error <= CURVE_ERROR_LIMIT;
            let _ = self.curve.set(usable.then_some(curve));
            return self.at(mu);
        }
        sheen_albedo(mu, self.alpha)
    }

    /// The error of what [`SheenAlbedo::at`] returns: the curve's once
    /// it is built, 0 before.
    pub fn error(&self) -> f64 {
        match self.curve.get() {
            Some(Some(curve)) => curve.error,
            _ => 0.0,
        }
    }
}

/// Sheen `α`s whose [`SheenAlbedo`] is kept, most recently used last: a
/// scene's few sheen roughnesses, a viewer's slider; a sheen roughness
/// texture, filtered, asks for a new `α` at every pixel, none of which
/// reaches [`EXACT_CALLS`].
pub const KEPT: usize = 64;

static KEPT_ALBEDOS: Mutex<Vec<Arc<SheenAlbedo>>> = Mutex::new(Vec::new());

thread_local! {
    /// The last one this thread asked for, without the lock.
    static LAST: RefCell<Option<Arc<SheenAlbedo>>> = const { RefCell::new(None) };
}

/// The [`SheenAlbedo`] of sheen `α`, made on first use and kept for the
/// next [`KEPT`] distinct `α` asked for. Every caller of one `α` (the
/// reference's pixels on all threads, the explorer's plots) shares it, so
/// the curve is built once.
pub fn sheen_albedo_of(alpha: f64) -> Arc<SheenAlbedo> {
    let same = |a: &Arc<SheenAlbedo>| a.alpha.to_bits() == alpha.to_bits();
    if let Some(a) = LAST.with(|l| l.borrow().as_ref().filter(|a| same(a)).cloned()) {
        return a;
    }
    let albedo = {
        let mut kept = KEPT_ALBEDOS.lock().unwrap_or_else(|e| e.into_inner());
        let albedo = match kept.iter().position(same) {
            Some(i) => kept.remove(i),
            None => Arc::new(SheenAlbedo::new(alpha)),
        };
        if kept.len() >= KEPT {
            kept.remove(0);
        }
        kept.push(albedo.clone());
        albedo
    };
    LAST.with(|l| *l.borrow_mut() = Some(albedo.clone()));
    albedo
}

#[cfg(test)]
mod tests {
    use super::super::sheen::sheen_alpha;
    use super::*;

    /// The curve is the exact `E` within its stated error at points
    /// between the nodes other than the midpoints it was measured at, and
    /// that error is small against the explorer's own tolerances (the
    /// albedo's outer panels stop at 10⁻⁸ of the integral).
    #[test]
    fn the_curve_is_the_exact_albedo_within_its_error() {
        for r in [0.02, 0.05, 0.1, 0.25, 0.4, 0.7, 1.0] {
            let alpha = sheen_alpha(r);
            let start = std::time::Instant::now();
            let curve = SheenCurve::new(alpha);
            eprintln!(
                "r_sh {r}: error {:.2e}, built in {:.2} s",
                curve.error,
                start.elapsed().as_secs_f64()
            );
            // Usable wherever E stays moderate near grazing; at r_sh = 0.02
            // (E = 3.0 at 89°) its steep rise keeps E exact.
            if r >= 0.05 {
                assert!(
                    curve.error <= CURVE_ERROR_LIMIT,
                    "r_sh {r}: {}",
                    curve.error
                );
            }
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
