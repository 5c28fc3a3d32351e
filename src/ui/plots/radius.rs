//! The polar slice's radius scale: linear (the lecture's "intensity as
//! length of vector from origin") or logarithmic over a chosen number of
//! decades (BRDF Explorer's log option: a highlight can be 10⁶ times the
//! diffuse level, which a linear radius draws as a dot on a spike).
//!
//! Both scales come with their rings: circles at round values, each
//! labelled, so the radius can be read off the plot.

/// How a value becomes a radius in plot units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Radius {
    /// Radius = value; rings every `step` up to `outer`.
    Linear { step: f64, outer: f64 },
    /// Radius = `log10(value / top) + decades` (0 at `top · 10^−decades`
    /// and below), so the plot is `decades` units across; rings at every
    /// power of ten. `top` is a power of ten.
    Log { top: f64, decades: u32 },
}

impl Radius {
    /// The scale for values up to `peak` (> 0): linear rings at a round
    /// step (1, 2 or 5 × 10^k, 3 to 7 rings), or `decades` decades below
    /// the power of ten at or above `peak`.
    pub fn new(peak: f64, log: bool, decades: u32) -> Radius {
        let peak = if peak.is_finite() && peak > 0.0 {
            peak
        } else {
            1.0
        };
        if log {
            Radius::Log {
                top: 10f64.powi(peak.log10().ceil() as i32),
                decades: decades.max(1),
            }
        } else {
            let step = round_step(peak / 4.0);
            Radius::Linear {
                step,
                outer: (peak / step).ceil().max(1.0) * step,
            }
        }
    }

    /// The radius of `value` (a non-positive value is at the origin).
    pub fn map(&self, value: f64) -> f64 {
        match *self {
            Radius::Linear { .. } => value.max(0.0),
            Radius::Log { top, decades } => {
                if value > 0.0 {
                    ((value / top).log10() + decades as f64).max(0.0)
                } else {
                    0.0
                }
            }
        }
    }

    /// The outermost ring's radius (the plot's extent).
    pub fn outer(&self) -> f64 {
        match *self {
            Radius::Linear { outer, .. } => outer,
            Radius::Log { decades, .. } => decades as f64,
        }
    }

    /// Rings: (radius in plot units, label of the value there).
    pub fn rings(&self) -> Vec<(f64, String)> {
        match *self {
            Radius::Linear { step, outer } => {
                let n = (outer / step).round() as usize;
                (1..=n)
                    .map(|k| {
                        let v = k as f64 * step;
                        (v, format_value(v))
                    })
                    .collect()
            }
            Radius::Log { top, decades } => {
                let e_top = top.log10().round() as i32;
                (1..=decades)
                    .map(|k| {
                        let e = e_top - decades as i32 + k as i32;
                        (k as f64, format!("1e{e}"))
                    })
                    .collect()
            }
        }
    }
}

/// The round number (1, 2 or 5 × 10^k) at or above `x`.
fn round_step(x: f64) -> f64 {
    let p = 10f64.powi(x.log10().floor() as i32);
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// A ring label: few digits, no trailing zeros.
fn format_value(v: f64) -> String {
    if (1e-3..1e4).contains(&v) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_rings_are_round_and_cover_the_peak() {
        let r = Radius::new(0.37, false, 6);
        assert_eq!(
            r,
            Radius::Linear {
                step: 0.1,
                outer: 0.4
            }
        );
        let rings = r.rings();
        assert_eq!(rings.len(), 4);
        assert_eq!(rings[1].1, "0.2");
        assert_eq!(r.map(0.25), 0.25);
        let big = Radius::new(1234.0, false, 6);
        assert!(big.outer() >= 1234.0 && big.rings().len() <= 8);
    }

    /// Log radius: each decade one unit, the top decade at the outer ring,
    /// values below the range at the origin.
    #[test]
    fn log_radius_spans_the_decades() {
        let r = Radius::new(3.0e5, true, 6);
        assert_eq!(
            r,
            Radius::Log {
                top: 1e6,
                decades: 6
            }
        );
        assert!((r.map(1e6) - 6.0).abs() < 1e-12);
        assert!((r.map(1.0) - 0.0).abs() < 1e-12);
        assert!((r.map(10.0) - 1.0).abs() < 1e-12);
        assert_eq!(r.map(1e-3), 0.0);
        assert_eq!(r.map(0.0), 0.0);
        let rings = r.rings();
        assert_eq!(rings.first().unwrap(), &(1.0, "1e1".to_string()));
        assert_eq!(rings.last().unwrap(), &(6.0, "1e6".to_string()));
    }
}
