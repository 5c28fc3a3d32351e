//! The ABC microfacet model: J. Löw, J. Kronander, A. Ynnerman, J. Unger,
//! "BRDF Models for Accurate and Efficient Rendering of Glossy Surfaces",
//! ACM TOG 31(1) 2012, the "ABC" distribution of its microfacet model,
//!
//! `D(θ_h) = A / (1 + B (1 − cos θ_h))^C`,
//!
//! in the full BRDF its published fits of the 100 MERL materials were made
//! for (`shared/measured/merl100_abc_fits.csv`: `kD, A, B, C, ior`, the
//! table `abc::s_data[]` of J. Dupuy's public-domain `dj_brdf.h`, whose
//! `abc::eval` states the model the parameters belong to):
//!
//! `f_r = k_d/π + F(I·H; 1 → ior) · D(θ_h) · G / (π (N·V)(N·I))`,
//!
//! `G` the V-groove attenuation of Cook & Torrance 1982 (`min(1,
//! 2(N·H)(N·I)/(I·H), 2(N·H)(N·V)/(V·H))`) and `F` the exact unpolarized
//! dielectric Fresnel of the relative index `ior` (Cook & Torrance's form,
//! the same function as [`fresnel_dielectric`] with `η_i = 1, η_t = ior`).
//! The constant in front is π, the lecture's Cook-Torrance denominator:
//! `A` absorbs the scale, so `A` and `π` together are the published fit.
//!
//! In gonio, `A` is a colour (`abc_a`), `B`, `C` scalars (`abc_b`,
//! `abc_c`), `ior = η_t/η_i` (`eta_t`, `eta_i`), and `k_s` (default 1)
//! scales the lobe as in every other model, so a `k_s` texture works alike.
//! `D` peaks at `A` (`θ_h = 0`) and is not normalized: the published
//! values put the lobe's energy in `A`.
//!
//! WGSL twin: `shaders/brdf/abc.wgsl` (same names, same order).

use super::fresnel::fresnel_dielectric;
use super::microfacet::{cook_torrance_specular, g_vgroove, half_vector};
use super::phong::{exp_cutoff, sin2_between};
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::PI;

/// The ABC distribution's shape `(1 + B(1 − cos θ_h))^−C` (peak 1; `A`
/// multiplies it outside), from `cos_h = N·H` and `sin2_h = |N × H|²`:
/// `1 − cos θ_h` is taken as `sin²θ_h / (1 + cos θ_h)`, which keeps full
/// relative precision near the peak where `cos_h` rounds to 1 in `f32` (at
/// B = 8e6 the lobe is 5e-4 rad wide, 1 − cos θ_h ≈ 1e-7, two `f32` ulps
/// of 1). As `e^(−C ln(1 + B(1 − cos θ_h)))` through [`exp_cutoff`]: 0
/// below e^−80, like every other lobe. 0 for `cos_h ≤ 0`.
pub fn d_abc_shape(b: f64, c: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let one_minus_cos = sin2_h / (1.0 + cos_h.min(1.0));
    exp_cutoff(-c * (b * one_minus_cos).ln_1p())
}

/// The ABC specular lobe without `A`: `F·D̂·G / (π (N·V)(N·I))` with `D̂`
/// = [`d_abc_shape`], for `N·I > 0`, `N·V > 0` (the caller's one-sided
/// test). The cosines are floored as Cook-Torrance's are
/// ([`cook_torrance_specular`]).
pub fn abc_specular(b: f64, c: f64, eta_i: f64, eta_t: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let h = half_vector(wi, wo);
    let cos_i = n.dot(wi);
    let cos_o = n.dot(wo);
    let cos_h = n.dot(h);
    let sin2_h = sin2_between(n, h);
    let cos_ih = wi.dot(h);
    let cos_oh = wo.dot(h);
    let d = d_abc_shape(b, c, cos_h, sin2_h);
    let g = g_vgroove(cos_h, cos_o, cos_i, cos_oh);
    let f = fresnel_dielectric(cos_ih, eta_i, eta_t);
    cook_torrance_specular(d, g, Rgb::splat(f), cos_i, cos_o, PI).x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// The published form typed out independently of the functions above:
    /// `A/(1 + B(1 − cos θ_h))^C`, the Cook-Torrance (1982) form of the
    /// unpolarized dielectric Fresnel `½ (g−c)²/(g+c)² (1 + ((c(g+c)−1)/(c(g−c)+1))²)`,
    /// `g = sqrt(n² + c² − 1)`, the V-groove G, over `π cos θ_i cos θ_o`.
    #[test]
    fn matches_the_published_form() {
        let (a, b, c, ior) = (986.846741, 64661.257812, 1.905420, 1.5); // chrome's A_r, B, C
        for (ti, pi, to, po) in [
            (10.0, 0.0, 12.0, 180.0),
            (30.0, 0.0, 50.0, 160.0),
            (60.0, 20.0, 70.0, 220.0),
            (5.0, 0.0, 5.0, 180.0),
        ] {
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            let h = (wi + wo).normalize();
            let d = a / (1.0 + b * (1.0 - h.z)).powf(c);
            let cc = wi.dot(h);
            let g_ = (ior * ior + cc * cc - 1.0).sqrt();
            let t = (cc * (g_ + cc) - 1.0) / (cc * (g_ - cc) + 1.0);
            let f = 0.5 * (g_ - cc).powi(2) / (g_ + cc).powi(2) * (1.0 + t * t);
            let g = 1f64
                .min(2.0 * h.z * wi.z / wi.dot(h))
                .min(2.0 * h.z * wo.z / wo.dot(h));
            let expected = f * d * g / (PI * wi.z * wo.z);
            let got = a * abc_specular(b, c, 1.0, ior, DVec3::Z, wi, wo);
            assert!(
                (got - expected).abs() <= 1e-12 * expected.abs().max(1e-300),
                "{ti} {to}: {got} vs {expected}"
            );
        }
    }

    /// The shape is 1 at the peak, falls to 2^−C where B(1 − cos θ_h) = 1,
    /// and is 0 below the horizon of H.
    #[test]
    fn shape_peak_half_width_and_horizon() {
        let (b, c) = (1e4, 1.5);
        assert_eq!(d_abc_shape(b, c, 1.0, 0.0), 1.0 - (-80f64).exp());
        let cos = 1.0 - 1.0 / b;
        let v = d_abc_shape(b, c, cos, 1.0 - cos * cos);
        assert!((v - 2f64.powf(-c)).abs() < 1e-12, "{v}");
        assert_eq!(d_abc_shape(b, c, -0.1, 0.99), 0.0);
    }
}
