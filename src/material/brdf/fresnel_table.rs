//! A Fresnel reflectance `F(cos θ)` given as a table over `cos θ` and
//! interpolated: for a Fresnel term that is too costly to evaluate at
//! every shading point but depends on the angle alone (the reference's
//! spectral conductors, `crate::reference::spectral::fresnel_tables`,
//! which integrate 81 wavelengths per value).
//!
//! Nodes at `cos θ = i / (n − 1)`, `i = 0 … n − 1`; between them a cubic
//! Catmull-Rom interpolation (E. Catmull, R. Rom, "A class of local
//! interpolating splines", 1974): through the nodes, C¹, exact for
//! quadratics, error `O(h³)` for a smooth `F`. At the two ends the missing
//! outer node is the quadratic extrapolation `3 p₀ − 3 p₁ + p₂`, which
//! keeps that order there. The conductor Fresnel is a smooth (analytic)
//! function of `cos θ` on [0, 1] for `κ > 0`, so the order holds
//! everywhere; the builder measures the error it reaches.

use crate::base::Rgb;
use std::fmt;

/// `F(cos θ)` per channel at evenly spaced `cos θ` in [0, 1].
#[derive(Clone, PartialEq)]
pub struct FresnelTable {
    /// What it tabulates (for messages and `Debug`).
    pub label: &'static str,
    nodes: Vec<Rgb>,
}

impl FresnelTable {
    /// `f` at `n ≥ 3` nodes `cos θ = i / (n − 1)`.
    pub fn from_fn(label: &'static str, n: usize, f: impl Fn(f64) -> Rgb) -> Self {
        assert!(n >= 3, "a cubic table needs 3 nodes or more");
        let last = (n - 1) as f64;
        FresnelTable {
            label,
            nodes: (0..n).map(|i| f(i as f64 / last)).collect(),
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether it has no nodes (never: [`Self::from_fn`] makes 3 or more).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// `F(cos θ)`, `cos_theta` clamped into [0, 1] as every Fresnel term
    /// clamps it (`super::fresnel`).
    pub fn eval(&self, cos_theta: f64) -> Rgb {
        let p = &self.nodes;
        let last = p.len() - 1;
        let x = cos_theta.clamp(0.0, 1.0) * last as f64;
        let i = x.floor() as usize;
        if i >= last {
            return p[last];
        }
        let t = x - i as f64;
        let node = |j: isize| -> Rgb {
            match j {
                -1 => 3.0 * p[0] - 3.0 * p[1] + p[2],
                j if j as usize > last => 3.0 * p[last] - 3.0 * p[last - 1] + p[last - 2],
                j => p[j as usize],
            }
        };
        let i = i as isize;
        let (p0, p1, p2, p3) = (node(i - 1), node(i), node(i + 1), node(i + 2));
        // Catmull-Rom in Horner form.
        let a = -0.5 * p0 + 1.5 * p1 - 1.5 * p2 + 0.5 * p3;
        let b = p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3;
        let c = 0.5 * (p2 - p0);
        ((a * t + b) * t + c) * t + p1
    }
}

impl fmt::Debug for FresnelTable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "FresnelTable({}, {} nodes)",
            self.label,
            self.nodes.len()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Through the nodes, exact for a quadratic in every interval
    /// including the two ends (the extrapolated outer nodes), clamped
    /// outside [0, 1].
    #[test]
    fn interpolates_quadratics_exactly() {
        let q = |c: f64| Rgb::new(c * c, 1.0 - 2.0 * c + 3.0 * c * c, 0.5 * c);
        let t = FresnelTable::from_fn("q", 9, q);
        for k in 0..=800 {
            let c = k as f64 / 800.0;
            assert!((t.eval(c) - q(c)).abs().max_element() < 1e-14, "{c}");
        }
        assert_eq!(t.eval(-1.0), t.eval(0.0));
        assert_eq!(t.eval(2.0), t.eval(1.0));
        assert_eq!(t.eval(0.5), q(0.5));
    }
}
