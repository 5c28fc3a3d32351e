//! Fresnel reflectance of a smooth interface (lecture: "Electric
//! Conductors (e.g. Metals)", "Dielectrics (e.g. Glass)"): exact for a
//! complex index (conductors) and for real indices (dielectrics), the
//! lecture's approximation for conductors, Schlick's approximation and the
//! normal-incidence values it needs.
//! WGSL twin: `shaders/brdf/fresnel.wgsl` (same names, same order).
//!
//! `cos_i` is the cosine of the angle of incidence measured from the
//! (micro)facet normal, `I·H` in a microfacet model. Every function clamps
//! it into [0, 1]: reflection from the outside only, and rounding of unit
//! vectors can push a cosine past 1.

use crate::base::Rgb;

/// Floor of the denominators of the Fresnel quotients, whose numerators
/// are never larger than their denominators (each is `|x − y|² / |x + y|²`
/// with `x`, `y` in the right half plane): where a denominator is 0 — only
/// `η = 1, κ = 0` (no interface) at `cos = 0`, or `η = κ = 0` — the
/// numerator is 0 too and the quotient becomes `0 / 1e-30 = 0`. 1e-30 is a
/// normal `f32`.
pub const FRESNEL_DENOM_FLOOR: f64 = 1e-30;

/// Exact conductor Fresnel (lecture: "Electric Conductors"; pbrt-v3,
/// Mitsuba 3): unpolarized reflectance for the complex index `η + iκ`
/// relative to the outside medium, per channel. The formulation of pbrt-v3 `FrConductor` /
/// Mitsuba 3 `fresnel_conductor` with `a² + b² = |n² − sin²θ|`,
/// `a + ib = sqrt(n² − sin²θ)` (taken the numerically stable way):
///
/// `r_s = ((a − cos)² + b²) / ((a + cos)² + b²)`,
/// `r_p = r_s ((a cos − sin²)² + b² cos²) / ((a cos + sin²)² + b² cos²)`,
/// `F = (r_s + r_p) / 2`.
///
/// These are the expanded forms of pbrt's `(t1 − t2)/(t1 + t2)` and
/// `(t3 − t4)/(t3 + t4)` (`t1 = a² + b² + cos²`, `t2 = 2a cos`, ...),
/// written as sums of squares so they are never negative in `f32`.
/// `κ = 0` is the exact dielectric with `η_i = 1, η_t = η`, including total
/// internal reflection for `η < 1` (`a = 0`). `cos = 1` gives
/// [`f0_conductor`], `cos = 0` gives 1 (except `η = 1, κ = 0`: 0).
pub fn fresnel_conductor(cos_i: f64, eta: Rgb, kappa: Rgb) -> Rgb {
    let cos_theta = cos_i.clamp(0.0, 1.0);
    let cos2 = cos_theta * cos_theta;
    let sin2 = 1.0 - cos2;
    let eta2 = eta * eta;
    let kappa2 = kappa * kappa;
    // Re(n² − sin²θ) as (η² − 1) − κ² + cos²θ: for η = 1 (index matched)
    // it is cos²θ exactly, where η² − κ² − sin²θ would cancel near grazing.
    let t0 = eta2 - 1.0 - kappa2 + cos2;
    let a2pb2 = (t0 * t0 + 4.0 * eta2 * kappa2).sqrt(); // a² + b² = |n² − sin²θ|
    // a + ib = sqrt(n² − sin²θ), the stable way: the larger of a, b is
    // sqrt((|z| + |Re z|)/2) (no cancellation), the other follows from
    // ab = ηκ. (pbrt's a = sqrt((a²+b² + t0)/2) cancels for t0 < 0: 1e-8
    // relative error in a for η 0.05, κ 0.001.) The floor: big = 0 only
    // for ηκ = 0, then small = 0 / 1e-30 = 0.
    let big = (0.5 * (a2pb2 + t0.abs())).sqrt();
    let small = eta * kappa / big.max(Rgb::splat(FRESNEL_DENOM_FLOOR));
    let t0_nonneg = t0.cmpge(Rgb::ZERO);
    let a = Rgb::select(t0_nonneg, big, small);
    let b = Rgb::select(t0_nonneg, small, big);
    let b2 = b * b;
    let a_minus = a - cos_theta;
    let a_plus = a + cos_theta;
    let r_s =
        (a_minus * a_minus + b2) / (a_plus * a_plus + b2).max(Rgb::splat(FRESNEL_DENOM_FLOOR));
    let p_minus = a * cos_theta - sin2;
    let p_plus = a * cos_theta + sin2;
    let r_p = r_s * (p_minus * p_minus + b2 * cos2)
        / (p_plus * p_plus + b2 * cos2).max(Rgb::splat(FRESNEL_DENOM_FLOOR));
    0.5 * (r_s + r_p)
}

/// The lecture's conductor Fresnel ("Electric Conductors"), exactly as
/// printed: `F = ½ (r∥² + r⊥²)` with
/// `r∥² = ((η²+κ²) cos² − 2η cos + 1) / ((η²+κ²) cos² + 2η cos + 1)`,
/// `r⊥² = ((η²+κ²) − 2η cos + cos²) / ((η²+κ²) + 2η cos + cos²)`.
/// An approximation of [`fresnel_conductor`] (exact at `cos = 1` and
/// `cos = 0`, good where `η² + κ² ≫ 1`; see `docs/brdf-math-notes.md`).
///
/// The printed polynomials are evaluated regrouped as sums of squares —
/// `(η²+κ²) cos² ∓ 2η cos + 1 = (η cos ∓ 1)² + κ² cos²` and
/// `(η²+κ²) ∓ 2η cos + cos² = (η ∓ cos)² + κ²` — the same numbers, but
/// rounding cannot make a numerator negative or cancel it (η near 1,
/// κ = 0, in `f32`). The first denominator is ≥ 1, the second is floored
/// at [`FRESNEL_DENOM_FLOOR`] (0 only for `η = κ = cos = 0`).
pub fn fresnel_conductor_lecture(cos_i: f64, eta: Rgb, kappa: Rgb) -> Rgb {
    let cos_theta = cos_i.clamp(0.0, 1.0);
    let cos2 = cos_theta * cos_theta;
    let kappa2 = kappa * kappa;
    let eta_cos = eta * cos_theta;
    let par_minus = eta_cos - 1.0; // (η²+κ²) cos² − 2η cos + 1 = (η cos − 1)² + κ² cos²
    let par_plus = eta_cos + 1.0;
    let r_par2 = (par_minus * par_minus + kappa2 * cos2) / (par_plus * par_plus + kappa2 * cos2);
    let perp_minus = eta - cos_theta; // (η²+κ²) − 2η cos + cos² = (η − cos)² + κ²
    let perp_plus = eta + cos_theta;
    let r_perp2 = (perp_minus * perp_minus + kappa2)
        / (perp_plus * perp_plus + kappa2).max(Rgb::splat(FRESNEL_DENOM_FLOOR));
    0.5 * (r_par2 + r_perp2)
}

/// Exact dielectric Fresnel (lecture: "Dielectrics"): unpolarized
/// reflectance of a smooth interface, `F = ½ (r∥² + r⊥²)` with
/// `r∥ = (η_t cos θ_i − η_i cos θ_t) / (η_t cos θ_i + η_i cos θ_t)`,
/// `r⊥ = (η_i cos θ_i − η_t cos θ_t) / (η_i cos θ_i + η_t cos θ_t)` and
/// Snell's law `η_i sin θ_i = η_t sin θ_t`.
///
/// - `η_i = η_t`: 0 (no interface), at every angle including grazing.
/// - Total internal reflection (`sin²θ_t ≥ 1`, possible for `η_i > η_t`)
///   returns 1. Otherwise `cos θ_t > 0`, so both denominators are > 0.
/// - `cos θ_i = 0` (grazing) with `η_i ≠ η_t`: 1.
pub fn fresnel_dielectric(cos_i: f64, eta_i: f64, eta_t: f64) -> f64 {
    if eta_i == eta_t {
        return 0.0; // no interface; also avoids 0/0 at grazing incidence
    }
    let cos_theta = cos_i.clamp(0.0, 1.0);
    let eta = eta_i / eta_t;
    let sin2_t = eta * eta * (1.0 - cos_theta * cos_theta); // Snell: sin θ_t = η sin θ_i
    if sin2_t >= 1.0 {
        return 1.0; // total internal reflection (and the critical angle)
    }
    let cos_t = (1.0 - sin2_t).sqrt(); // > 0 here
    let r_par = (eta_t * cos_theta - eta_i * cos_t) / (eta_t * cos_theta + eta_i * cos_t);
    let r_perp = (eta_i * cos_theta - eta_t * cos_t) / (eta_i * cos_theta + eta_t * cos_t);
    0.5 * (r_par * r_par + r_perp * r_perp)
}

/// Schlick's approximation (C. Schlick, "An Inexpensive BRDF Model for
/// Physically-based Rendering", 1994): `F0 + (1 − F0)(1 − cos)^5`, with
/// `F0` the normal-incidence reflectance ([`f0_conductor`],
/// [`f0_dielectric`]). The fifth power by multiplication (no `pow(0, 5)`).
pub fn fresnel_schlick(cos_i: f64, f0: Rgb) -> Rgb {
    let cos_theta = cos_i.clamp(0.0, 1.0);
    let m = 1.0 - cos_theta;
    let m2 = m * m;
    let m5 = m2 * m2 * m;
    f0 + (1.0 - f0) * m5
}

/// Conductor reflectance at normal incidence (lecture: "Electric
/// Conductors" at `cos = 1`; the `F0` of Schlick 1994): `((η − 1)² + κ²) / ((η + 1)² + κ²)`, per channel. The
/// denominator is ≥ 1 for `η ≥ 0`.
pub fn f0_conductor(eta: Rgb, kappa: Rgb) -> Rgb {
    let kappa2 = kappa * kappa;
    let eta_minus = eta - 1.0;
    let eta_plus = eta + 1.0;
    (eta_minus * eta_minus + kappa2) / (eta_plus * eta_plus + kappa2)
}

/// Dielectric reflectance at normal incidence (lecture: "Dielectrics" at
/// `cos = 1`; the `F0` of Schlick 1994):
/// `((η_t − η_i) / (η_t + η_i))²` (0.04 for glass, 1 → 1.5).
pub fn f0_dielectric(eta_i: f64, eta_t: f64) -> f64 {
    let r = (eta_t - eta_i) / (eta_t + eta_i);
    r * r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lecture's table of conductors (η, κ), one value for all channels.
    const METALS: [(&str, f64, f64); 4] = [
        ("gold", 0.370, 2.820),
        ("silver", 0.177, 3.638),
        ("copper", 0.617, 2.63),
        ("steel", 2.485, 3.433),
    ];

    /// A minimal complex number for an independent evaluation.
    #[derive(Clone, Copy, Debug)]
    struct C(f64, f64);

    impl C {
        fn add(self, o: C) -> C {
            C(self.0 + o.0, self.1 + o.1)
        }
        fn sub(self, o: C) -> C {
            C(self.0 - o.0, self.1 - o.1)
        }
        fn mul(self, o: C) -> C {
            C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
        }
        fn div(self, o: C) -> C {
            let d = o.0 * o.0 + o.1 * o.1;
            C(
                (self.0 * o.0 + self.1 * o.1) / d,
                (self.1 * o.0 - self.0 * o.1) / d,
            )
        }
        fn abs2(self) -> f64 {
            self.0 * self.0 + self.1 * self.1
        }
        /// Principal square root, computed the numerically stable way
        /// (the larger part by a root, the smaller from `2xy = Im`).
        fn sqrt(self) -> C {
            let r = self.0.hypot(self.1);
            if self.0 >= 0.0 {
                let x = (0.5 * (r + self.0)).sqrt();
                C(x, if x == 0.0 { 0.0 } else { self.1 / (2.0 * x) })
            } else {
                let y = (0.5 * (r - self.0)).sqrt().copysign(self.1);
                C(self.1 / (2.0 * y), y)
            }
        }
    }

    /// Fresnel from the textbook amplitude coefficients with complex
    /// `n = η + iκ` (outside index 1): `w = sqrt(n² − sin²θ)`,
    /// `r_s = (cos − w)/(cos + w)`, `r_p = (n² cos − w)/(n² cos + w)`.
    fn fresnel_complex(cos: f64, eta: f64, kappa: f64) -> f64 {
        let n = C(eta, kappa);
        let n2 = n.mul(n);
        let sin2 = 1.0 - cos * cos;
        let w = n2.sub(C(sin2, 0.0)).sqrt();
        let c = C(cos, 0.0);
        let r_s = c.sub(w).div(c.add(w));
        let r_p = n2.mul(c).sub(w).div(n2.mul(c).add(w));
        0.5 * (r_s.abs2() + r_p.abs2())
    }

    #[test]
    fn gold_golden_values_against_complex_arithmetic() {
        let (eta, kappa) = (Rgb::splat(0.370), Rgb::splat(2.820));
        for deg in [0.0, 30.0, 60.0, 80.0, 89.0f64] {
            let cos = deg.to_radians().cos();
            let f = fresnel_conductor(cos, eta, kappa);
            let g = fresnel_complex(cos, 0.370, 2.820);
            assert!((f.x - g).abs() < 1e-12, "{deg}°: {} vs {g}", f.x);
            assert_eq!(f.x, f.y);
            assert_eq!(f.x, f.z);
        }
        // Normal incidence by hand: ((0.37−1)² + 2.82²)/((1.37)² + 2.82²).
        let f0 = (0.63f64.powi(2) + 2.82f64.powi(2)) / (1.37f64.powi(2) + 2.82f64.powi(2));
        assert!((fresnel_conductor(1.0, eta, kappa).x - f0).abs() < 1e-15);
    }

    #[test]
    fn conductor_matches_complex_arithmetic_everywhere() {
        let etas = [0.05, 0.177, 0.37, 0.617, 0.9, 1.0, 1.0001, 1.5, 2.485, 4.0];
        let kappas = [0.0, 1e-3, 0.5, 2.82, 3.638, 10.0];
        for &eta in &etas {
            for &kappa in &kappas {
                for j in 0..=200 {
                    let cos = j as f64 / 200.0;
                    let f = fresnel_conductor(cos, Rgb::splat(eta), Rgb::splat(kappa)).x;
                    let g = fresnel_complex(cos, eta, kappa);
                    if cos == 0.0 && eta == 1.0 && kappa == 0.0 {
                        assert_eq!(f, 0.0); // no interface
                        continue;
                    }
                    assert!(
                        (f - g).abs() < 1e-12,
                        "η {eta} κ {kappa} cos {cos}: {f} vs {g}"
                    );
                }
            }
        }
    }

    #[test]
    fn conductor_at_normal_incidence_is_f0() {
        for (_, eta, kappa) in METALS {
            let (e, k) = (Rgb::splat(eta), Rgb::splat(kappa));
            let d = (fresnel_conductor(1.0, e, k) - f0_conductor(e, k))
                .abs()
                .max_element();
            assert!(d < 1e-15, "{d}");
            // The lecture's form is exact there too.
            let d = (fresnel_conductor_lecture(1.0, e, k) - f0_conductor(e, k))
                .abs()
                .max_element();
            assert!(d < 1e-15, "{d}");
        }
        let (e, k) = (Rgb::new(0.2, 1.0, 3.0), Rgb::new(3.0, 0.0, 1.0));
        let d = (fresnel_conductor(1.0, e, k) - f0_conductor(e, k))
            .abs()
            .max_element();
        assert!(d < 1e-15);
    }

    #[test]
    fn conductor_without_absorption_is_the_dielectric() {
        for eta in [0.5, 0.7, 0.9, 1.0001, 1.333, 1.5, 2.42] {
            for j in 0..=100 {
                let cos = j as f64 / 100.0;
                let c = fresnel_conductor(cos, Rgb::splat(eta), Rgb::ZERO).x;
                let d = fresnel_dielectric(cos, 1.0, eta);
                assert!((c - d).abs() < 1e-12, "η {eta} cos {cos}: {c} vs {d}");
            }
        }
    }

    #[test]
    fn dielectric_values() {
        assert!((fresnel_dielectric(1.0, 1.0, 1.5) - 0.04).abs() < 1e-15);
        assert!((f0_dielectric(1.0, 1.5) - 0.04).abs() < 1e-15);
        assert!((fresnel_dielectric(1.0, 1.5, 1.0) - 0.04).abs() < 1e-15);
        // Index-matched: no reflection at any angle.
        for j in 0..=10 {
            let cos = j as f64 / 10.0;
            assert_eq!(fresnel_dielectric(cos, 1.333, 1.333), 0.0);
        }
        // Nearly matched (air): tiny but grazing still → 1.
        let air = fresnel_dielectric(1.0, 1.0, 1.00029);
        assert!(air > 0.0 && air < 1e-7);
        assert_eq!(fresnel_dielectric(0.0, 1.0, 1.00029), 1.0);
        // Total internal reflection from glass to air past 41.8°.
        assert_eq!(fresnel_dielectric(45f64.to_radians().cos(), 1.5, 1.0), 1.0);
        assert!(fresnel_dielectric(40f64.to_radians().cos(), 1.5, 1.0) < 1.0);
        // Brewster's angle: r∥ = 0, F = r⊥²/2.
        let brewster = 1.5f64.atan();
        let f = fresnel_dielectric(brewster.cos(), 1.0, 1.5);
        let ct = (1.0 - (brewster.sin() / 1.5).powi(2)).sqrt();
        let r_perp = (brewster.cos() - 1.5 * ct) / (brewster.cos() + 1.5 * ct);
        assert!((f - 0.5 * r_perp * r_perp).abs() < 1e-15);
    }

    #[test]
    fn grazing_incidence_reflects_everything() {
        for (_, eta, kappa) in METALS {
            let (e, k) = (Rgb::splat(eta), Rgb::splat(kappa));
            assert!((fresnel_conductor(0.0, e, k).x - 1.0).abs() < 1e-15);
            assert!((fresnel_conductor(1e-8, e, k).x - 1.0).abs() < 1e-6);
            assert!((fresnel_conductor_lecture(0.0, e, k).x - 1.0).abs() < 1e-15);
            assert_eq!(fresnel_schlick(0.0, f0_conductor(e, k)).x, 1.0);
        }
        for (ei, et) in [(1.0, 1.5), (1.0, 1.00029), (1.5, 1.0), (1.0, 2.42)] {
            assert_eq!(fresnel_dielectric(0.0, ei, et), 1.0);
            assert!((fresnel_dielectric(1e-8, ei, et) - 1.0).abs() < 1e-4);
        }
    }

    /// The lecture's conductor form against the exact one: max |difference|
    /// over θ ∈ [0°, 90°] for the lecture's four metals (reported in
    /// docs/brdf-math-notes.md; gold within 0.01).
    #[test]
    fn lecture_conductor_is_close_to_exact() {
        for (name, eta, kappa) in METALS {
            let (e, k) = (Rgb::splat(eta), Rgb::splat(kappa));
            let mut worst = (0.0f64, 0.0);
            for j in 0..=9000 {
                let theta = (j as f64 / 100.0).to_radians();
                let d = (fresnel_conductor_lecture(theta.cos(), e, k)
                    - fresnel_conductor(theta.cos(), e, k))
                .x;
                if d.abs() > worst.0.abs() {
                    worst = (d, j as f64 / 100.0);
                }
            }
            eprintln!(
                "{name}: max lecture − exact = {:.6} at θ = {}°",
                worst.0, worst.1
            );
            if name == "gold" {
                assert!(worst.0.abs() < 0.01, "{worst:?}");
            }
            assert!(worst.0.abs() < 0.05, "{name} {worst:?}");
        }
    }

    #[test]
    fn schlick_endpoints_and_range() {
        let f0 = Rgb::new(0.04, 0.5, 0.95);
        assert_eq!(fresnel_schlick(1.0, f0), f0);
        assert_eq!(fresnel_schlick(0.0, f0), Rgb::ONE);
        assert_eq!(fresnel_schlick(-0.5, f0), Rgb::ONE);
        let mid = fresnel_schlick(0.5, f0);
        assert!((mid - (f0 + (1.0 - f0) / 32.0)).abs().max_element() < 1e-15);
    }

    #[test]
    fn finite_and_in_range_at_the_extremes() {
        let etas = [1e-3, 0.177, 1.0, 1.0 + 1e-7, 1.5, 10.0];
        let kappas = [0.0, 1e-7, 2.82, 10.0];
        let coss = [
            -1.0,
            -1e-8,
            0.0,
            1e-8,
            1e-4,
            0.5,
            1.0 - 1e-12,
            1.0,
            1.0 + 1e-7,
        ];
        for &eta in &etas {
            for &kappa in &kappas {
                for &cos in &coss {
                    let (e, k) = (Rgb::splat(eta), Rgb::splat(kappa));
                    for f in [
                        fresnel_conductor(cos, e, k),
                        fresnel_conductor_lecture(cos, e, k),
                        fresnel_schlick(cos, f0_conductor(e, k)),
                        Rgb::splat(fresnel_dielectric(cos, 1.0, eta)),
                        Rgb::splat(fresnel_dielectric(cos, eta, 1.0)),
                    ] {
                        assert!(f.is_finite(), "η {eta} κ {kappa} cos {cos}: {f}");
                        assert!(
                            f.min_element() >= 0.0 && f.max_element() <= 1.0 + 1e-15,
                            "{f}"
                        );
                    }
                }
            }
        }
        // η = κ = 0 is outside the contract (η > 0) but stays finite.
        let f = fresnel_conductor_lecture(0.0, Rgb::ZERO, Rgb::ZERO);
        assert!(f.is_finite());
        assert!(fresnel_conductor(0.0, Rgb::ZERO, Rgb::ZERO).is_finite());
    }
}
