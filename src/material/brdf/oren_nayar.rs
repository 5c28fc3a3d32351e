//! Oren-Nayar: diffuse reflection from rough surfaces (M. Oren and S. K.
//! Nayar, "Generalization of Lambert's Reflectance Model", SIGGRAPH 1994).
//! The lecture asks "Lambertian objects (?)" of the full Moon, whose dust
//! is brighter towards the light than Lambert allows: Oren and Nayar model
//! such a surface as V-cavities of Lambertian facets whose slope angles are
//! Gaussian with standard deviation σ (radians), and account for their
//! foreshortening, masking, shadowing and one interreflection.
//! WGSL twin: `shaders/brdf/oren_nayar.wgsl` (same names, same order).
//!
//! Both forms of the paper, each under its own name:
//! - [`oren_nayar_qualitative`], the paper's "qualitative model" (its
//!   eq. 30), which drops the small terms: `ρ/π (A + B max(0, cos Δφ)
//!   sin α tan β)`. The form renderers usually call Oren-Nayar.
//! - [`oren_nayar_full`], the full model (the paper's eqs. 27–29): the
//!   direct term `L1` with the coefficients C1, C2, C3 plus the
//!   interreflection term `L2`, which is quadratic in ρ.
//!
//! Here `α = max(θ_i, θ_o)`, `β = min(θ_i, θ_o)`, `Δφ` the azimuth between
//! I and V, ρ the facets' albedo (gonio's `k_d`). Both forms are
//! reciprocal (symmetric in θ_i, θ_o and Δφ) and equal Lambert at σ = 0.
//! Neither is energy-conserving by construction (both are fits to the
//! V-cavity model): a white surface reflects at most what it receives near
//! normal incidence, but up to about 1.4 % (qualitative, σ = 0.2) and 4.4 %
//! (full, σ = 0.3) more at θ_i = 89° (the tests below measure both).
//!
//! Decided edge values, the same on both sides:
//! - `cos Δφ = (N×I)·(N×V) / (|N×I| |N×V|)` (the Lagrange identity makes
//!   it the cosine of the angle between the projections, without the
//!   cancellation of `1 − cos²`), taken as 0 where either projection
//!   vanishes: the azimuth is undefined there, and every term it enters is
//!   multiplied by something that vanishes with β.
//! - `tan β = sin β / max(cos β, COS_FLOOR)`: the paper's form diverges
//!   when both directions are grazing; the floor keeps it finite, as for
//!   the lecture's forms.
//! - the full model's `L1` falls below zero at grazing, opposite azimuths
//!   (`C2 tan β → 6B/π` as β → 90° while C1 ≥ ½: at σ = π/2 from
//!   θ_i = θ_o ≈ 70° on, down to −0.27 at 89.8°); a BRDF cannot be
//!   negative, so `L1` is clamped at 0 there (docs/brdf-models.md says so).

use super::COS_FLOOR;
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, FRAC_2_PI};

/// The coefficients of both forms, derived from σ once per material
/// (Oren & Nayar 1994, eqs. 27–30): `a` = A = C1 `= 1 − 0.5 σ²/(σ² + 0.33)`;
/// `b` = B `= 0.45 σ²/(σ² + 0.09)`, the factor of C2; `c3 = 0.125 σ²/(σ² +
/// 0.09)`, the factor of C3; `l2 = 0.17 σ²/(σ² + 0.13)`, the factor of
/// the interreflection term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrenNayarTerms {
    pub a: f64,
    pub b: f64,
    pub c3: f64,
    pub l2: f64,
}

/// [`OrenNayarTerms`] of the slope-angle deviation `sigma` (radians).
pub fn oren_nayar_terms(sigma: f64) -> OrenNayarTerms {
    let s2 = sigma * sigma;
    OrenNayarTerms {
        a: 1.0 - 0.5 * s2 / (s2 + 0.33),
        b: 0.45 * s2 / (s2 + 0.09),
        c3: 0.125 * s2 / (s2 + 0.09),
        l2: 0.17 * s2 / (s2 + 0.13),
    }
}

/// The angles both forms need, from unit `n`, `wi`, `wo` above the surface.
#[derive(Clone, Copy, Debug)]
pub struct OrenNayarAngles {
    /// `sin α`, `cos α` of the larger polar angle α.
    pub sin_alpha: f64,
    pub cos_alpha: f64,
    /// `sin β`, `cos β` of the smaller polar angle β.
    pub sin_beta: f64,
    pub cos_beta: f64,
    /// `cos Δφ`, 0 where the azimuth is undefined.
    pub cos_phi: f64,
}

/// [`OrenNayarAngles`] of a pair of directions: sines from `|N×I|` (exact
/// near the normal, where `sqrt(1 − cos²)` is not), cosines from `N·I`.
pub fn oren_nayar_angles(n: DVec3, wi: DVec3, wo: DVec3) -> OrenNayarAngles {
    let (n_x_i, n_x_o) = (n.cross(wi), n.cross(wo));
    let (sin_i, sin_o) = (n_x_i.length(), n_x_o.length());
    let (cos_i, cos_o) = (n.dot(wi), n.dot(wo));
    let projections = sin_i * sin_o;
    let cos_phi = if projections > 0.0 {
        (n_x_i.dot(n_x_o) / projections).clamp(-1.0, 1.0)
    } else {
        0.0
    };
    // The larger angle has the smaller cosine.
    let (sin_alpha, cos_alpha, sin_beta, cos_beta) = if cos_i < cos_o {
        (sin_i, cos_i, sin_o, cos_o)
    } else {
        (sin_o, cos_o, sin_i, cos_i)
    };
    OrenNayarAngles {
        sin_alpha,
        cos_alpha,
        sin_beta,
        cos_beta,
        cos_phi,
    }
}

/// The qualitative model (Oren & Nayar 1994, eq. 30):
/// `f_r = k_d/π (A + B max(0, cos Δφ) sin α tan β)`.
pub fn oren_nayar_qualitative(k_d: Rgb, t: &OrenNayarTerms, g: &OrenNayarAngles) -> Rgb {
    let tan_beta = g.sin_beta / g.cos_beta.max(COS_FLOOR);
    k_d * (FRAC_1_PI * (t.a + t.b * g.cos_phi.max(0.0) * g.sin_alpha * tan_beta))
}

/// The full model (Oren & Nayar 1994, eqs. 27–29), `f_r = L1 + L2` per
/// unit irradiance:
/// - `L1 = k_d/π (C1 + cos Δφ C2 tan β + (1 − |cos Δφ|) C3 tan((α+β)/2))`,
///   `C2 = B sin α` for `cos Δφ ≥ 0`, else `B (sin α − (2β/π)³)`;
///   `C3 = c3 (4αβ/π²)²`; clamped at 0 (module docs);
/// - `L2 = l2 k_d²/π (1 − cos Δφ (2β/π)²)`.
///
/// `tan((α+β)/2) = (sin α + sin β) / (cos α + cos β)` (half-angle
/// identity: no angle needed); α and β themselves from `atan2`.
pub fn oren_nayar_full(k_d: Rgb, t: &OrenNayarTerms, g: &OrenNayarAngles) -> Rgb {
    let alpha = g.sin_alpha.atan2(g.cos_alpha);
    let beta = g.sin_beta.atan2(g.cos_beta);
    let tan_beta = g.sin_beta / g.cos_beta.max(COS_FLOOR);
    let tan_half_sum = (g.sin_alpha + g.sin_beta) / (g.cos_alpha + g.cos_beta).max(COS_FLOOR);
    let two_beta_over_pi = FRAC_2_PI * beta;
    let c2 = if g.cos_phi >= 0.0 {
        t.b * g.sin_alpha
    } else {
        t.b * (g.sin_alpha - two_beta_over_pi * two_beta_over_pi * two_beta_over_pi)
    };
    let four_alpha_beta = 4.0 * FRAC_1_PI * FRAC_1_PI * alpha * beta;
    let c3 = t.c3 * four_alpha_beta * four_alpha_beta;
    let direct =
        (t.a + g.cos_phi * c2 * tan_beta + (1.0 - g.cos_phi.abs()) * c3 * tan_half_sum).max(0.0);
    let interreflection = t.l2 * (1.0 - g.cos_phi * two_beta_over_pi * two_beta_over_pi);
    k_d * (FRAC_1_PI * direct) + k_d * k_d * (FRAC_1_PI * interreflection)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta: f64, phi: f64) -> DVec3 {
        DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    }

    /// At σ = 0 both forms are Lambert.
    #[test]
    fn smooth_is_lambert() {
        let t = oren_nayar_terms(0.0);
        let k_d = Rgb::new(0.8, 0.5, 0.2);
        for (ti, to, phi) in [(0.3, 1.2, 0.0), (1.5, 0.1, 2.0), (0.0, 0.7, 1.0)] {
            let g = oren_nayar_angles(DVec3::Z, dir(ti, 0.0), dir(to, phi));
            for f in [
                oren_nayar_qualitative(k_d, &t, &g),
                oren_nayar_full(k_d, &t, &g),
            ] {
                assert!((f - k_d * FRAC_1_PI).abs().max_element() < 1e-15, "{f}");
            }
        }
    }

    /// The paper's backscatter: rougher surfaces are brighter towards the
    /// light (retro-reflection) than sideways; reciprocity holds.
    #[test]
    fn rough_surfaces_backscatter_and_are_reciprocal() {
        let t = oren_nayar_terms(0.5);
        let k_d = Rgb::splat(0.9);
        let wi = dir(1.0, 0.0);
        for f in [oren_nayar_qualitative, oren_nayar_full] {
            let back = f(k_d, &t, &oren_nayar_angles(DVec3::Z, wi, dir(0.9, 0.0))).x;
            let side = f(k_d, &t, &oren_nayar_angles(DVec3::Z, wi, dir(0.9, 1.6))).x;
            assert!(back > side, "{back} {side}");
            let (a, b) = (dir(0.4, 0.3), dir(1.3, 2.9));
            let ab = f(k_d, &t, &oren_nayar_angles(DVec3::Z, a, b));
            let ba = f(k_d, &t, &oren_nayar_angles(DVec3::Z, b, a));
            assert!((ab - ba).abs().max_element() < 1e-15, "{ab} {ba}");
        }
    }

    /// Both forms stay finite and non-negative at the ends of σ's range
    /// (σ → 0 is Lambert, σ = π/2 the roughest) for the extreme direction
    /// pairs: normal incidence (azimuth undefined), grazing (tan β at its
    /// floor), coincident and opposite directions.
    #[test]
    fn finite_at_the_ends_of_the_range() {
        let grazing = 89.9999f64.to_radians();
        let pairs = [
            (0.0, 0.0, 0.0),
            (0.0, grazing, 1.0),
            (grazing, grazing, 0.0),
            (grazing, grazing, std::f64::consts::PI),
            (grazing, 0.3, 2.0),
            (1.2, 1.2, 0.0),
        ];
        for sigma in [0.0, 1e-12, 1e-3, std::f64::consts::FRAC_PI_2] {
            let t = oren_nayar_terms(sigma);
            for &(ti, to, phi) in &pairs {
                let g = oren_nayar_angles(DVec3::Z, dir(ti, 0.0), dir(to, phi));
                for f in [oren_nayar_qualitative, oren_nayar_full] {
                    let v = f(Rgb::ONE, &t, &g);
                    assert!(
                        v.is_finite() && v.min_element() >= 0.0,
                        "σ {sigma} θ_i {ti} θ_o {to} φ {phi}: {v}"
                    );
                }
            }
        }
    }

    type OrenNayarForm = fn(Rgb, &OrenNayarTerms, &OrenNayarAngles) -> Rgb;

    /// The directional albedo `ρ(θ_i) = ∫ f_r cos θ_o dω_o` of a white
    /// surface (k_d = 1) by midpoint quadrature on an n × 2n grid in
    /// (θ_o, φ_o), with its error estimated from the grid of half the size
    /// (`|ρ_n − ρ_{n/2}|`, doubled for safety): `(ρ, error)`.
    fn albedo(f: OrenNayarForm, sigma: f64, theta_i_deg: f64) -> (f64, f64) {
        let t = oren_nayar_terms(sigma);
        let wi = dir(theta_i_deg.to_radians(), 0.0);
        let on_grid = |n: usize| {
            let dt = std::f64::consts::FRAC_PI_2 / n as f64;
            let dp = std::f64::consts::PI / n as f64;
            let mut sum = 0.0;
            for a in 0..n {
                let theta = (a as f64 + 0.5) * dt;
                for b in 0..2 * n {
                    let wo = dir(theta, (b as f64 + 0.5) * dp);
                    sum += f(Rgb::ONE, &t, &oren_nayar_angles(DVec3::Z, wi, wo)).x
                        * theta.cos()
                        * theta.sin();
                }
            }
            sum * dt * dp
        };
        let (fine, coarse) = (on_grid(240), on_grid(120));
        (fine, 2.0 * (fine - coarse).abs())
    }

    /// Near normal incidence a white surface reflects at most what it
    /// receives (ρ ≤ 1 up to the quadrature's error) for σ over its whole
    /// range, in both forms: the facets are Lambertian and masking and
    /// shadowing lose light.
    #[test]
    fn albedo_is_at_most_one_up_to_30_degrees() {
        for sigma in [0.0, 0.1, 0.3, 1.0, std::f64::consts::FRAC_PI_2] {
            for theta_i in [0.0, 15.0, 30.0] {
                for f in [oren_nayar_qualitative, oren_nayar_full] {
                    let (rho, error) = albedo(f, sigma, theta_i);
                    assert!(
                        rho - error <= 1.0,
                        "σ {sigma} θ_i {theta_i}°: ρ = {rho} ± {error}"
                    );
                }
            }
        }
    }

    /// At grazing incidence the paper's formulas reflect more than they
    /// receive for moderate σ: the qualitative form by about 1.4 % (σ = 0.2),
    /// the full form by about 4.4 % (σ = 0.3, its interreflection term on
    /// top), at θ_i = 89°. They are approximations fitted to the exact
    /// V-cavity model, not energy-conserving by construction; gonio
    /// implements them as printed and docs/brdf-models.md says so. This
    /// test fails if that excess ever disappears unnoticed.
    #[test]
    fn albedo_exceeds_one_at_grazing_incidence() {
        let cases: [(OrenNayarForm, f64, &str); 2] = [
            (oren_nayar_qualitative, 0.2, "qualitative"),
            (oren_nayar_full, 0.3, "full"),
        ];
        for (f, sigma, form) in cases {
            let (rho, error) = albedo(f, sigma, 89.0);
            assert!(rho - error > 1.0, "{form} σ {sigma}: ρ = {rho} ± {error}");
        }
    }
}
