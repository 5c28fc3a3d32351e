//! Variable projection: the numbers that enter `f_r` linearly are solved,
//! not searched.
//!
//! Every fitted model is `f_r = k_d/π + k_s · f_spec` (the contract), and
//! abc's `A` scales its distribution; so at fixed lobe shape (exponent,
//! width, roughness, η, κ, …) the `ngan` cost is a quadratic in `k_d`,
//! `k_s` and `A`, whose minimum over their bounds is found exactly. The
//! search then runs over the shape numbers alone: Golub & Pereyra, "The
//! Differentiation of Pseudo-Inverses and Nonlinear Least Squares Problems
//! Whose Variables Separate", SIAM J. Numer. Anal. 10(2), 1973. This takes
//! the Phong family's and Ward's simplex from 7 numbers to 1, the
//! dielectric Cook-Torrance's from 8 to 2 and abc's from 9 to 3; the
//! conductor Cook-Torrance keeps its full search (see [`Linear::of`]).
//! `docs/measured.md` gives the run times before and after.
//!
//! The quadratic's minimum over the box: every linear number is either
//! free or held at one of its bounds; for each of the `3ⁿ` patterns the
//! free ones solve their normal equations, and the cheapest pattern whose
//! solution lies in the box is the minimum (the box minimum of a convex
//! quadratic is the unconstrained minimum over the numbers not at a bound).
//! The quadratic splits into one block per channel (a channel's `k_d` and
//! `k_s` or `A` reach that channel alone), `n = 2` each: 3 × 9 small
//! solves per point. (One block of all 6 numbers, 729 patterns, cost as
//! much as evaluating the samples.)
//!
//! Only the `ngan` metric is a quadratic in these numbers; the `log`
//! metric searches every number (`problem.rs`).

use super::metric::Metric;
use super::models::{FitModel, Free};
use super::samples::Sample;
use super::terms::Terms;
use crate::base::Rgb;
use crate::material::param::{ABC_A, K_D, K_S, Param};

/// The parameters `f_r` is linear in (each with all others held).
const LINEAR: [&Param; 3] = [&K_D, &K_S, &ABC_A];

/// The linear numbers of a model: indices into [`FitModel::free`], grouped
/// by parameter.
#[derive(Clone, Debug)]
pub struct Linear {
    /// (the parameter, the indices of its free numbers).
    groups: Vec<(&'static Param, Vec<usize>)>,
}

impl Linear {
    /// The linear numbers of `model` under `metric`, or `None` when there
    /// are none or the metric is not a quadratic in them.
    pub fn of(model: &FitModel, metric: Metric) -> Option<Linear> {
        if metric != Metric::Ngan {
            return None;
        }
        let groups: Vec<_> = LINEAR
            .iter()
            .map(|&p| {
                let idx: Vec<usize> = (0..model.free.len())
                    .filter(|&k| std::ptr::eq(model.free[k].param, p))
                    .collect();
                (p, idx)
            })
            .filter(|(_, idx)| !idx.is_empty())
            .collect();
        // Cook-Torrance with a conductor Fresnel (a grey k_s) keeps its full
        // search: solving its k_d and k_s found worse minima (gold metallic
        // paint: E/E₀ 0.289 against 0.272 with Beckmann, 0.198 against
        // 0.183 with GGX; the simplex over roughness, η and κ alone stops
        // in a poorer valley), at no saving in time.
        let grey = groups
            .iter()
            .flat_map(|(_, idx)| idx)
            .any(|&k| model.free[k].channel.is_none());
        (!groups.is_empty() && !grey).then_some(Linear { groups })
    }

    /// Whether free number `k` is solved here.
    pub fn contains(&self, k: usize) -> bool {
        self.groups.iter().any(|(_, idx)| idx.contains(&k))
    }

    /// Solves the linear numbers of `values` (the other numbers as given;
    /// the linear ones are overwritten) for the least `ngan` mean against
    /// `samples` (`terms` made from them), and returns that mean
    /// ([`Metric::mean`]'s `E²`).
    ///
    /// A number of one channel reaches that channel's values alone, so the
    /// quadratic splits into one block per channel (`k_d` and `k_s` or `A`
    /// of that channel: 2 numbers, 3² patterns, instead of 6 numbers and
    /// 3⁶ patterns together), each minimized over its box on its own; a
    /// grey number (none is solved today, see [`Linear::of`]) would join
    /// them in one block.
    pub fn solve(
        &self,
        model: &FitModel,
        values: &mut [f64],
        samples: &[Sample],
        terms: &Terms,
    ) -> f64 {
        // The basis: f_r with one parameter at 1 (every channel), the other
        // solved ones at 0 (f_r is the sum of the solved numbers times
        // their bases: every other term is scaled by one of them).
        let mut base = model.material(values);
        for &k in self.groups.iter().flat_map(|(_, idx)| idx) {
            model.free[k].write(&mut base, 0.0);
        }
        let bases: Vec<Vec<Rgb>> = self
            .groups
            .iter()
            .map(|(_, idx)| {
                let mut m = base.clone();
                for &k in idx {
                    model.free[k].write(&mut m, 1.0);
                }
                let mut f = Vec::with_capacity(samples.len());
                terms.f_r(&m, samples, &mut f);
                f
            })
            .collect();
        // The unknowns, in group order, and the channels each reaches.
        let unknowns: Vec<(usize, usize)> = self
            .groups
            .iter()
            .enumerate()
            .flat_map(|(g, (_, idx))| idx.iter().map(move |&k| (g, k)))
            .collect();
        let reaches = |free: &Free, c: usize| free.channel.is_none_or(|ch| ch == c);
        let grey = unknowns
            .iter()
            .any(|&(_, k)| model.free[k].channel.is_none());
        let blocks: Vec<Vec<usize>> = if grey {
            vec![vec![0, 1, 2]]
        } else {
            vec![vec![0], vec![1], vec![2]]
        };
        let mut sum = 0.0;
        for channels in blocks {
            // The block's unknowns: those reaching one of its channels.
            let block: Vec<(usize, usize)> = unknowns
                .iter()
                .copied()
                .filter(|&(_, k)| channels.iter().any(|&c| reaches(&model.free[k], c)))
                .collect();
            let mut q = Quadratic::new(block.len());
            let mut row = vec![0.0; block.len()];
            for (i, s) in samples.iter().enumerate() {
                let w = s.weight * s.wi.z * s.wi.z;
                for &c in &channels {
                    for (r, &(g, k)) in row.iter_mut().zip(&block) {
                        *r = if reaches(&model.free[k], c) {
                            bases[g][i][c]
                        } else {
                            0.0
                        };
                    }
                    q.add(w, &row, s.measured[c]);
                }
            }
            let lo: Vec<f64> = block.iter().map(|&(_, k)| model.free[k].lo).collect();
            let hi: Vec<f64> = block.iter().map(|&(_, k)| model.free[k].hi).collect();
            let (u, block_sum) = q.minimize_in_box(&lo, &hi);
            for (&(_, k), v) in block.iter().zip(u) {
                values[k] = v;
            }
            sum += block_sum;
        }
        sum / 3.0
    }
}

/// `Σ w (y − aᵀu)²` as `c − 2 bᵀu + uᵀ A u`.
struct Quadratic {
    a: Vec<Vec<f64>>,
    b: Vec<f64>,
    c: f64,
}

impl Quadratic {
    fn new(n: usize) -> Self {
        Quadratic {
            a: vec![vec![0.0; n]; n],
            b: vec![0.0; n],
            c: 0.0,
        }
    }

    fn add(&mut self, w: f64, row: &[f64], y: f64) {
        for (i, &ri) in row.iter().enumerate() {
            if ri == 0.0 {
                continue;
            }
            self.b[i] += w * ri * y;
            for (j, &rj) in row.iter().enumerate() {
                self.a[i][j] += w * ri * rj;
            }
        }
        self.c += w * y * y;
    }

    fn value(&self, u: &[f64]) -> f64 {
        let n = u.len();
        let mut v = self.c;
        for i in 0..n {
            v -= 2.0 * self.b[i] * u[i];
            for j in 0..n {
                v += u[i] * self.a[i][j] * u[j];
            }
        }
        v.max(0.0)
    }

    /// The minimum over `lo ≤ u ≤ hi` (module doc) and its value.
    fn minimize_in_box(&self, lo: &[f64], hi: &[f64]) -> (Vec<f64>, f64) {
        let n = lo.len();
        let mut best: (Vec<f64>, f64) = (lo.to_vec(), self.value(lo));
        for pattern in 0..3usize.pow(n as u32) {
            // Digit j of the pattern: 0 free, 1 at lo, 2 at hi.
            let mut u = vec![0.0; n];
            let mut free = Vec::with_capacity(n);
            let mut p = pattern;
            for j in 0..n {
                match p % 3 {
                    0 => free.push(j),
                    1 => u[j] = lo[j],
                    _ => u[j] = hi[j],
                }
                p /= 3;
            }
            if !free.is_empty() && !self.solve_free(&free, &mut u) {
                continue;
            }
            let inside = free
                .iter()
                .all(|&j| u[j] >= lo[j] && u[j] <= hi[j] && u[j].is_finite());
            if inside {
                let v = self.value(&u);
                if v < best.1 {
                    best = (u, v);
                }
            }
        }
        best
    }

    /// Solves `A_ff u_f = b_f − A_fh u_h` for the `free` numbers (the
    /// others held at their values in `u`), by Gaussian elimination with
    /// partial pivoting; `false` when `A_ff` is singular (a number the
    /// samples do not see: a pattern holding it at a bound covers it).
    fn solve_free(&self, free: &[usize], u: &mut [f64]) -> bool {
        let m = free.len();
        let mut rows: Vec<Vec<f64>> = free
            .iter()
            .map(|&i| {
                let mut r: Vec<f64> = free.iter().map(|&j| self.a[i][j]).collect();
                let held: f64 = (0..u.len())
                    .filter(|j| !free.contains(j))
                    .map(|j| self.a[i][j] * u[j])
                    .sum();
                r.push(self.b[i] - held);
                r
            })
            .collect();
        let scale = free.iter().map(|&i| self.a[i][i].abs()).fold(0.0, f64::max);
        for col in 0..m {
            let p = (col..m)
                .max_by(|&x, &y| rows[x][col].abs().total_cmp(&rows[y][col].abs()))
                .expect("a row");
            if rows[p][col].abs() <= scale * 1e-13 {
                return false;
            }
            rows.swap(col, p);
            let pivot = rows[col].clone();
            for row in rows.iter_mut().skip(col + 1) {
                let f = row[col] / pivot[col];
                for (a, b) in row[col..].iter_mut().zip(&pivot[col..]) {
                    *a -= f * b;
                }
            }
        }
        for col in (0..m).rev() {
            let s: f64 = (col + 1..m).map(|k| rows[col][k] * u[free[k]]).sum();
            u[free[col]] = (rows[col][m] - s) / rows[col][col];
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::models::ALL;
    use crate::fit::problem::mean_of;
    use crate::fit::samples::samples_of;
    use crate::material::Material;

    /// The premise: every fitted model's `f_r` is linear in the numbers
    /// solved here, so the solved mean is the metric's mean at the solved
    /// values, and no other values of them do better.
    #[test]
    fn the_solved_numbers_are_the_least_squares_minimum() {
        use crate::base::frame::SurfaceFrame;
        use glam::DVec3;
        let truth = Material::new("m", crate::material::ReflectanceModel::Ward);
        let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
        let samples =
            samples_of(|_, _, _, wi, wo| truth.f_r(wi, wo, &frame) + Rgb::new(0.05, 0.02, 0.1));
        for spec in ALL {
            let model = FitModel::parse(spec).unwrap();
            let Some(linear) = Linear::of(&model, Metric::Ngan) else {
                continue;
            };
            let mut values: Vec<f64> = model.free.iter().map(|f| f.at(0.37)).collect();
            let mean = linear.solve(&model, &mut values, &samples, &Terms::new(&samples));
            let direct = mean_of(&model.material(&values), &samples, Metric::Ngan);
            assert!(
                (mean - direct).abs() <= 1e-9 * direct.max(1e-12),
                "{spec}: solved {mean:e} vs evaluated {direct:e}"
            );
            for (k, f) in model.free.iter().enumerate() {
                if !linear.contains(k) {
                    continue;
                }
                for step in [-1e-3, 1e-3] {
                    let mut v = values.clone();
                    v[k] = (v[k] + step * (f.hi - f.lo).min(1.0)).clamp(f.lo, f.hi);
                    let other = mean_of(&model.material(&v), &samples, Metric::Ngan);
                    assert!(
                        other >= direct * (1.0 - 1e-12),
                        "{spec}: {}[{k}] moved by {step} lowers the cost {direct:e} → {other:e}",
                        f.param.key
                    );
                }
            }
        }
    }

    #[test]
    fn the_box_minimum_of_a_quadratic_is_found() {
        // (u0 − 2)² + (u1 + 1)² + (u0 − u1)²: the normal equations
        // 2u0 − u1 = 2, 2u1 − u0 = −1 give (1, 0), value 3.
        let mut q = Quadratic::new(2);
        q.add(1.0, &[1.0, 0.0], 2.0);
        q.add(1.0, &[0.0, 1.0], -1.0);
        q.add(1.0, &[1.0, -1.0], 0.0);
        let (u, v) = q.minimize_in_box(&[-10.0, -10.0], &[10.0, 10.0]);
        assert!((u[0] - 1.0).abs() < 1e-12 && u[1].abs() < 1e-12, "{u:?}");
        assert!((v - 3.0).abs() < 1e-12);
        // Over [0, 0.5]²: u0 at its bound 0.5, then u1's own minimum
        // −0.25 lies below its bound, so u1 = 0; value 2.25 + 1 + 0.25.
        let (u, v) = q.minimize_in_box(&[0.0, 0.0], &[0.5, 0.5]);
        assert_eq!(u, vec![0.5, 0.0]);
        assert!((v - 3.5).abs() < 1e-12, "{v}");
    }
}
