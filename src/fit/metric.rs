//! The error metrics a fit minimizes and reports.
//!
//! - `ngan`: the cosine-weighted L2 of Ngan, Durand, Matusik, "Experimental
//!   Analysis of BRDF Models", EGSR 2005, §4:
//!   `E = sqrt(∫ (f_m − f)² cos²θ_i dω_i dω_o / ∫ dω_i dω_o)` over pairs
//!   with `θ_i, θ_o ≤ 80°`, here the mean over the three channels, in 1/sr.
//!   The optimizer minimizes `E² / E₀²` (`E₀`: `E` of `f = 0`), the same
//!   minimizer made dimensionless so one stopping rule serves chrome and
//!   felt alike; the report gives `E` and `E / E₀`.
//! - `log`: the loss the Neural-BRDF networks were trained with
//!   (Sztrajman et al. 2021), `|ln(1 + f_m cos θ_i) − ln(1 + f cos θ_i)|`,
//!   averaged over the same pairs with the same weights and channels.
//!   It weighs a dim diffuse tail as much as a bright highlight's shape.

use super::samples::Sample;
use crate::base::Rgb;

/// Which metric (the `--metric` value).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Metric {
    /// Ngan et al. 2005's cosine-weighted L2.
    Ngan,
    /// The log metric of the Neural-BRDF training loss.
    Log,
}

impl Metric {
    pub fn name(self) -> &'static str {
        match self {
            Metric::Ngan => "ngan",
            Metric::Log => "log",
        }
    }

    /// The per-sample error of `model` against `s.measured`, summed over
    /// the channels (what [`Metric::mean`] averages).
    fn sample_error(self, s: &Sample, model: Rgb) -> f64 {
        let c = s.wi.z;
        match self {
            Metric::Ngan => ((s.measured - model) * c).length_squared(),
            Metric::Log => {
                let m = (s.measured * c).max(Rgb::ZERO);
                let f = (model * c).max(Rgb::ZERO);
                let d = |a: f64, b: f64| (a.ln_1p() - b.ln_1p()).abs();
                d(m.x, f.x) + d(m.y, f.y) + d(m.z, f.z)
            }
        }
    }

    /// The weighted mean over samples and channels: `E²` for `ngan`, the
    /// mean absolute log difference for `log`. `model(i)` is the model's
    /// `f_r` at sample `i`.
    pub fn mean(self, samples: &[Sample], model: impl Fn(usize) -> Rgb) -> f64 {
        samples
            .iter()
            .enumerate()
            .map(|(i, s)| s.weight * self.sample_error(s, model(i)))
            .sum::<f64>()
            / 3.0
    }

    /// The reported error from [`Metric::mean`]: `E = sqrt(mean)` for
    /// `ngan`, the mean itself for `log`.
    pub fn reported(self, mean: f64) -> f64 {
        match self {
            Metric::Ngan => mean.sqrt(),
            Metric::Log => mean,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_perfect_model_has_no_error_and_zero_has_the_norm() {
        let s = vec![Sample {
            wi: DVec3::new(0.6, 0.0, 0.8),
            wo: DVec3::Z,
            measured: Rgb::new(1.0, 2.0, 3.0),
            weight: 1.0,
        }];
        for m in [Metric::Ngan, Metric::Log] {
            assert_eq!(m.mean(&s, |_| s[0].measured), 0.0);
        }
        let e0 = Metric::Ngan.mean(&s, |_| Rgb::ZERO);
        assert!((e0 - 0.64 * 14.0 / 3.0).abs() < 1e-12);
        let l0 = Metric::Log.mean(&s, |_| Rgb::ZERO);
        let want = (1.8f64.ln() + 2.6f64.ln() + 3.4f64.ln()) / 3.0;
        assert!((l0 - want).abs() < 1e-12);
    }
}
