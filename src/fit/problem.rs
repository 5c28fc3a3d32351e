//! One fit: a model's free numbers searched to minimize a metric against
//! the samples of a measured material, by Nelder-Mead (argmin) from
//! several starts.
//!
//! Bounds are a change of variables (MINUIT's, F. James, "MINUIT
//! Tutorial", CERN 2004, §1.3.1): the searched `x` is unbounded and the
//! number is `lo + (hi − lo)(1 + sin x)/2` (in `ln` for a log-scaled one),
//! so every point the simplex visits is a valid material.
//!
//! The stopping rule is argmin's: the standard deviation of the cost at
//! the simplex's vertices below [`SD_TOLERANCE`] (costs are relative:
//! `E²/E₀²` for `ngan`, see `metric.rs`), or [`MAX_ITERS`] iterations.
//! Multi-start: a scan over the lobe's width (exponent, slope or
//! roughness: the number whose wrong value leaves a highlight between the
//! samples, a plateau a simplex cannot leave) picks the starts; the other
//! shape numbers start mid-interval, colours at 0.3. The best run is
//! then restarted from its end with a fresh simplex until a restart no
//! longer improves by more than the tolerance (a simplex can collapse
//! before the minimum: Lagarias et al. 1998; restarting is the usual cure).
//!
//! Under the `ngan` metric the numbers `f_r` is linear in (`k_d`, `k_s`,
//! abc's `A`) are not searched but solved at every point (`linear.rs`,
//! variable projection): the simplex moves the lobe's shape alone.

use super::linear::Linear;
use super::metric::Metric;
use super::models::FitModel;
use super::samples::Sample;
use super::terms::Terms;
use crate::base::Rgb;
use crate::base::frame::SurfaceFrame;
use crate::material::Material;
use crate::material::brdf;
use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use glam::DVec3;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The stopping tolerance on the simplex's cost spread (relative cost).
pub const SD_TOLERANCE: f64 = 1e-9;
/// Iterations per Nelder-Mead run.
pub const MAX_ITERS: u64 = 4000;
/// Starts: the lobe's width is scanned at [`SCAN`] + 1 fractions of its
/// (log-)interval, the others held at their start; the [`STARTS`] best
/// local minima of the scan start a search each.
pub const SCAN: usize = 24;
pub const STARTS: usize = 3;
/// Where the other shape numbers (indices, metallic) start (fraction).
const SHAPE_START: f64 = 0.5;
/// Where colours start (fraction of [0, 1]).
const COLOUR_START: f64 = 0.3;
/// The initial simplex's edge in `x` (radians of the sine map).
const STEP: f64 = 0.4;
/// Restarts of the best run at most.
const MAX_RESTARTS: usize = 4;

/// What a fit found.
#[derive(Clone, Debug)]
pub struct FitResult {
    pub material: Material,
    /// The free numbers, as [`FitModel::free`] lists them.
    pub values: Vec<f64>,
    /// The metric's reported error (`E` in 1/sr for `ngan`).
    pub error: f64,
    /// The error relative to that of `f = 0` (`E/E₀`; for `log` its ratio
    /// to the log error of `f = 0`).
    pub relative: f64,
    /// Cost evaluations used.
    pub evaluations: usize,
}

/// The cost of a point `x` of the search.
struct Problem<'a> {
    model: &'a FitModel,
    samples: &'a [Sample],
    metric: Metric,
    /// [`Metric::mean`] of `f = 0`: costs are relative to it.
    norm: f64,
    /// The samples' cosines and groups: the inner loop (`terms.rs`).
    terms: Terms,
    /// The numbers solved, not searched (`ngan` only).
    linear: Option<Linear>,
    /// The numbers the simplex searches (indices into the model's free
    /// numbers): `x` has one entry per index here.
    search: Vec<usize>,
    /// The model's scans over searched numbers only.
    scans: Vec<(Vec<usize>, Vec<f64>)>,
    evaluations: AtomicUsize,
}

impl Problem<'_> {
    /// The free numbers at `x` (the searched ones from `x`, the linear
    /// ones solved) and, when solved, the metric's mean there.
    fn point(&self, x: &[f64]) -> (Vec<f64>, Option<f64>) {
        let free = &self.model.free;
        let mut v: Vec<f64> = free.iter().map(|f| f.at(0.5)).collect();
        for (&k, &x) in self.search.iter().zip(x) {
            v[k] = free[k].at((1.0 + x.sin()) / 2.0);
        }
        let mean = self
            .linear
            .as_ref()
            .map(|l| l.solve(self.model, &mut v, self.samples, &self.terms));
        (v, mean)
    }

    fn values(&self, x: &[f64]) -> Vec<f64> {
        self.point(x).0
    }

    /// The metric's mean at `values`, by [`Terms`] (equal to [`mean_of`]
    /// to rounding).
    fn mean(&self, values: &[f64]) -> f64 {
        let mut f = Vec::with_capacity(self.samples.len());
        self.terms
            .f_r(&self.model.material(values), self.samples, &mut f);
        self.metric.mean(self.samples, |i| f[i])
    }
}

/// How many numbers the simplex searches for `model` under `metric` (the
/// `n` of the stopping rule; the others are solved, `linear.rs`).
pub fn searched(model: &FitModel, metric: Metric) -> usize {
    let linear = Linear::of(model, metric);
    (0..model.free.len())
        .filter(|&k| !linear.as_ref().is_some_and(|l| l.contains(k)))
        .count()
}

/// `metric`'s mean of `m` against `samples`.
pub fn mean_of(m: &Material, samples: &[Sample], metric: Metric) -> f64 {
    let b = m.brdf();
    let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
    metric.mean(samples, |i| {
        let s = &samples[i];
        brdf::eval(&b, s.wi, s.wo, &frame)
    })
}

/// The error of a given material `m` (no search): how the published ABC
/// parameters are scored, on the same samples and metric as a fit.
pub fn score(m: &Material, samples: &[Sample], metric: Metric) -> FitResult {
    let norm = metric.mean(samples, |_| Rgb::ZERO).max(f64::MIN_POSITIVE);
    let mean = mean_of(m, samples, metric);
    FitResult {
        material: m.clone(),
        values: Vec::new(),
        error: metric.reported(mean),
        relative: metric.reported(mean) / metric.reported(norm),
        evaluations: 1,
    }
}

impl CostFunction for &Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Self::Param) -> Result<f64, argmin::core::Error> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let (values, mean) = self.point(x);
        let c = mean.unwrap_or_else(|| self.mean(&values)) / self.norm;
        // A model that overflows somewhere is a bad point, not an error.
        Ok(if c.is_finite() { c } else { f64::MAX })
    }
}

/// Fits `model` to `samples` under `metric`.
pub fn fit(model: &FitModel, samples: &[Sample], metric: Metric) -> FitResult {
    fit_from(model, samples, metric, None)
}

/// [`fit`] with one more start: the free numbers of `also` (clamped into
/// their bounds). `abc,start=published` starts from the published ABC
/// parameters besides gonio's own starts.
pub fn fit_from(
    model: &FitModel,
    samples: &[Sample],
    metric: Metric,
    also: Option<&Material>,
) -> FitResult {
    let norm = metric.mean(samples, |_| Rgb::ZERO).max(f64::MIN_POSITIVE);
    let linear = Linear::of(model, metric);
    let solved = |k: usize| linear.as_ref().is_some_and(|l| l.contains(k));
    let problem = Problem {
        model,
        samples,
        metric,
        norm,
        search: (0..model.free.len()).filter(|&k| !solved(k)).collect(),
        scans: model
            .scans
            .iter()
            .filter(|(idx, _)| !idx.iter().any(|&k| solved(k)))
            .cloned()
            .collect(),
        terms: Terms::new(samples),
        linear,
        evaluations: AtomicUsize::new(0),
    };
    let x_of = |t: f64| (2.0 * t - 1.0).clamp(-1.0, 1.0).asin();
    let start_at = |(width, extra): (f64, &[f64])| -> Vec<f64> {
        problem
            .search
            .iter()
            .map(|&k| {
                let f = &model.free[k];
                let scanned = problem
                    .scans
                    .iter()
                    .zip(extra)
                    .find(|((ks, _), _)| ks.contains(&k));
                x_of(if Some(k) == model.width {
                    width
                } else if let Some((_, &t)) = scanned {
                    t
                } else if f.shape {
                    SHAPE_START
                } else {
                    COLOUR_START
                })
            })
            .collect()
    };
    let mut best: Option<(Vec<f64>, f64)> = None;
    for (w, extra) in starts(model.width, &problem.scans, |w, e| {
        (&problem).cost(&start_at((w, e))).unwrap_or(f64::MAX)
    }) {
        let run = run(&problem, start_at((w, &extra)));
        if best.as_ref().is_none_or(|b| run.1 < b.1) {
            best = Some(run);
        }
    }
    if let Some(m) = also {
        let x0: Vec<f64> = problem
            .search
            .iter()
            .map(|&k| x_of(model.free[k].fraction(model.free[k].read(m))))
            .collect();
        let run = run(&problem, x0);
        if best.as_ref().is_none_or(|b| run.1 < b.1) {
            best = Some(run);
        }
    }
    let (mut x, mut cost) = best.expect("at least one start");
    for _ in 0..MAX_RESTARTS {
        let (x2, c2) = run(&problem, x.clone());
        let improved = c2 < cost - SD_TOLERANCE;
        if c2 < cost {
            (x, cost) = (x2, c2);
        }
        if !improved {
            break;
        }
    }
    let values = problem.values(&x);
    // Reported by `brdf::eval` itself, the truth `Terms` is tested against.
    let mean = mean_of(&model.material(&values), samples, metric);
    FitResult {
        material: model.material(&values),
        values,
        error: metric.reported(mean),
        relative: metric.reported(mean) / metric.reported(norm),
        evaluations: problem.evaluations.load(Ordering::Relaxed),
    }
}

/// The starts: the width's fraction and the fractions of the
/// [`FitModel::scans`], at the best local minima of `cost` over the
/// width's scan, repeated at every combination of the other scans' fractions
/// (abc: `A` and `C`, whose trades with `B` make valleys the width scan
/// alone misses: a bright needle between the samples costs as little as
/// no lobe); one start at ½ for a model without a width.
fn starts(
    width: Option<usize>,
    scans: &[(Vec<usize>, Vec<f64>)],
    cost: impl Fn(f64, &[f64]) -> f64,
) -> Vec<(f64, Vec<f64>)> {
    let mut combos: Vec<Vec<f64>> = vec![Vec::new()];
    for (_, fractions) in scans {
        combos = combos
            .into_iter()
            .flat_map(|c| {
                fractions.iter().map(move |&t| {
                    let mut c = c.clone();
                    c.push(t);
                    c
                })
            })
            .collect();
    }
    if width.is_none() {
        return combos.into_iter().map(|c| (0.5, c)).collect();
    }
    let t: Vec<f64> = (0..=SCAN).map(|k| k as f64 / SCAN as f64).collect();
    let mut minima: Vec<((f64, Vec<f64>), f64)> = Vec::new();
    for extra in &combos {
        let c: Vec<f64> = t.iter().map(|&t| cost(t, extra)).collect();
        minima.extend(
            (0..t.len())
                .filter(|&k| (k == 0 || c[k] <= c[k - 1]) && (k + 1 == t.len() || c[k] <= c[k + 1]))
                .map(|k| ((t[k], extra.clone()), c[k])),
        );
    }
    minima.sort_by(|a, b| a.1.total_cmp(&b.1));
    minima.into_iter().take(STARTS).map(|(t, _)| t).collect()
}

/// One Nelder-Mead run from `x0`: its best point and cost.
fn run(problem: &Problem, x0: Vec<f64>) -> (Vec<f64>, f64) {
    if x0.is_empty() {
        // Everything solved (Lambert under `ngan`): nothing to search.
        let c = problem.cost(&x0).unwrap_or(f64::MAX);
        return (x0, c);
    }
    let mut simplex = vec![x0.clone()];
    for i in 0..x0.len() {
        let mut v = x0.clone();
        // Step towards the interval's interior (x ∈ [−π/2, π/2] covers it).
        v[i] += if v[i] > 0.0 { -STEP } else { STEP };
        simplex.push(v);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(SD_TOLERANCE)
        .expect("a positive tolerance");
    let result = Executor::new(problem, solver)
        .configure(|s| s.max_iters(MAX_ITERS))
        .timer(false)
        .run();
    match result {
        Ok(r) => {
            let s = r.state();
            let x = s.best_param.clone().unwrap_or(x0);
            (x, s.best_cost)
        }
        // Only argmin's "unreachable" branch errs (NaN-free costs).
        Err(_) => {
            let c = problem.cost(&x0).unwrap_or(f64::MAX);
            (x0, c)
        }
    }
}
