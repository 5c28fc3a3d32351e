//! The lobe the sampled mode (`environment.specular = "sampled"`, [`super::sampled`])
//! draws its BRDF samples from: per model a density close to `f_r cos θ_i`
//! that can be sampled in closed form, and that density's value at any
//! direction (which multiple importance sampling needs for every sample,
//! whichever strategy drew it). WGSL twin: the `lobe_*` functions of
//! `shaders/environment_sampled.wgsl` (same kinds, same formulas, same
//! order).
//!
//! The density need not be the BRDF's own: [`super::sampled`] combines it
//! with cosine sampling by the balance heuristic, so any density gives an
//! unbiased estimate; the closer it is to `f_r cos θ_i`, the smaller the
//! error for a given N. The kinds (Walter et al. 2007, "Microfacet Models
//! for Refraction through Rough Surfaces", eqs. 28–39; Pharr, Jakob &
//! Humphreys, PBRT 3rd ed., 14.1 for the change of variables):
//!
//! * **Half-vector lobes**, `p(h) = D_s(h) cos θ_h`, turned into a density
//!   of `ω_i = 2(ω_o·h)h − ω_o` by `p(ω_i) = p(h) / (4 ω_o·h)`:
//!   * [`Lobe::Ggx`]: GGX of `α`, `tan²θ_h = α² u/(1 − u)`;
//!   * [`Lobe::Beckmann`]: Beckmann of slope `m`, `tan²θ_h = −m² ln(1 − u)`;
//!   * [`Lobe::HalfPower`]: `p(h) = (s+1)/(2π) cos^s θ_h`, `cos θ_h =
//!     (1 − u)^{1/(s+1)}`.
//! * **The mirror lobe** [`Lobe::MirrorPower`]: `p(ω_i) = (s+1)/(2π)
//!   (R·ω_i)^s` about the mirror direction `R` of `ω_o`, the same
//!   inversion.
//!
//! Which kind each model gets ([`lobe`]): the lecture's Phong and
//! normalized Phong the mirror lobe of their exponent (`f_r cos θ_i` is
//! exactly `(R·ω)^n`, times `N·ω` for the normalized form); the lecture's
//! Blinn-Phong `(N·H)^n` the half-vector power `n`, the normalized one
//! `n + 1` (its `D cos θ_h`); Cook-Torrance its distribution's own
//! sampling (GGX, Beckmann), Blinn's distributions the half-vector power
//! `e + 1` (exactly `D cos θ_h` of the normalized Blinn), the Gaussians
//! Beckmann of the matched slope `m/√ln 2` (Smith's, `smith_beckmann_slope`);
//! gltf-pbr GGX of `α = r²`; Ward Beckmann of `σ` (its distribution is
//! Beckmann's exponential; the anisotropic one of the larger `σ`, a wider
//! isotropic lobe that covers both axes); ABC the half-vector power `B·C`
//! (`(1 + B(1 − c))^{−C} ≈ e^{−BC(1−c)} ≈ c^{BC}` near the peak). A zero
//! `k_s`, and Lambert, Oren-Nayar, the mirror's diffuse part and the
//! measured tables (no parameter to shape a lobe): no lobe, all samples
//! cosine-weighted.

use crate::base::Rgb;
use crate::material::Material;
use crate::material::brdf::phong::{ln_cos, mirror_direction, sin2_between};
use crate::material::brdf::{DistributionTerm, Specular};
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, LN_2, TAU};

/// The sampling lobe of a material. Twin: `SampledLobe` (`kind`, `param`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lobe {
    /// No lobe: cosine-weighted samples only.
    None,
    /// GGX half vectors of `α`.
    Ggx { alpha: f64 },
    /// Beckmann half vectors of slope `m`.
    Beckmann { m: f64 },
    /// Half vectors of density `(s+1)/(2π) cos^s θ_h`.
    HalfPower { s: f64 },
    /// Directions of density `(s+1)/(2π) (R·ω)^s` about the mirror direction.
    MirrorPower { s: f64 },
}

/// The lobe of `material` (module docs). Twin: `sampled_lobe`.
pub fn lobe(material: &Material) -> Lobe {
    let brdf = material.brdf();
    let glossy = brdf.k_s != Rgb::ZERO;
    match brdf.specular {
        Specular::GltfPbr { roughness, .. } => Lobe::Ggx {
            alpha: roughness * roughness,
        },
        _ if !glossy => Lobe::None,
        Specular::Phong { k_e } | Specular::PhongNormalized { k_e } => Lobe::MirrorPower { s: k_e },
        Specular::BlinnPhong { k_e } => Lobe::HalfPower { s: k_e },
        Specular::BlinnPhongNormalized { k_e } => Lobe::HalfPower { s: k_e + 1.0 },
        Specular::Ward { sigma } => Lobe::Beckmann { m: sigma },
        Specular::WardAnisotropic { sigma_x, sigma_y } => Lobe::Beckmann {
            m: sigma_x.max(sigma_y),
        },
        Specular::CookTorrance(ct) => match ct.d {
            DistributionTerm::Ggx { alpha } => Lobe::Ggx { alpha },
            DistributionTerm::Beckmann { m } => Lobe::Beckmann { m },
            DistributionTerm::Blinn { e } | DistributionTerm::BlinnNormalized { e } => {
                Lobe::HalfPower { s: e + 1.0 }
            }
            DistributionTerm::Gaussian { m } | DistributionTerm::GaussianNormalized { m, .. } => {
                Lobe::Beckmann { m: m / LN_2.sqrt() }
            }
        },
        Specular::Abc { b, c, .. } => Lobe::HalfPower { s: b * c },
        _ => Lobe::None,
    }
}

/// `1 − e^x` for `x ≤ 0`, accurate for small `|x|` (the twin sums the
/// series of `expm1` there: WGSL has none).
fn one_minus_exp(x: f64) -> f64 {
    -x.exp_m1()
}

/// `(cos² θ, sin² θ)` of the lobe's polar angle (about `N` for the
/// half-vector kinds, about `R` for the mirror lobe) for the uniform
/// variate `u ∈ (0, 1)`, each computed where it is accurate (a narrow
/// lobe's `sin²` would cancel in `1 − cos²`). Twin: `lobe_polar`.
pub fn polar(lobe: Lobe, u: f64) -> (f64, f64) {
    match lobe {
        Lobe::Ggx { alpha } => {
            let a = alpha * alpha * u;
            let d = (1.0 - u) + a;
            ((1.0 - u) / d, a / d)
        }
        Lobe::Beckmann { m } => {
            let t = -m * m * (-u).ln_1p(); // tan²θ
            (1.0 / (1.0 + t), t / (1.0 + t))
        }
        Lobe::HalfPower { s } | Lobe::MirrorPower { s } => {
            // cos θ = (1 − u)^{1/(s+1)}: cos²θ = e^x, x = 2 ln(1 − u)/(s + 1).
            let x = 2.0 * (-u).ln_1p() / (s + 1.0);
            (x.exp(), one_minus_exp(x))
        }
        Lobe::None => (1.0, 0.0),
    }
}

/// Sample `(u1, u2)`'s direction `ω_i` of `lobe` for the view `wo` at the
/// normal `n` (`t`, `b` the sampling frame's tangents, from the normal
/// alone). Twin: `lobe_direction`.
pub fn direction(lobe: Lobe, u1: f64, u2: f64, wo: DVec3, n: DVec3, t: DVec3, b: DVec3) -> DVec3 {
    let (cos2, sin2) = polar(lobe, u1);
    let (cos, sin) = (cos2.sqrt(), sin2.sqrt());
    let phi = TAU * u2;
    if let Lobe::MirrorPower { .. } = lobe {
        let r = mirror_direction(wo, n);
        let tr = crate::base::any_tangent(r);
        let br = r.cross(tr);
        return tr * (sin * phi.cos()) + br * (sin * phi.sin()) + r * cos;
    }
    let h = t * (sin * phi.cos()) + b * (sin * phi.sin()) + n * cos;
    2.0 * wo.dot(h) * h - wo
}

/// `(s+1)/(2π) cos^s θ` from `cos θ` and `sin² θ` (0 for `cos θ ≤ 0`).
fn power_density(s: f64, cos: f64, sin2: f64) -> f64 {
    if cos <= 0.0 {
        return 0.0;
    }
    (s + 1.0) * 0.5 * FRAC_1_PI * crate::material::brdf::phong::exp_cutoff(s * ln_cos(cos, sin2))
}

/// The density of `ω_i = wi` under `lobe` [1/sr] (0 where the lobe never
/// sends a sample). Twin: `lobe_pdf`.
pub fn pdf(lobe: Lobe, wi: DVec3, wo: DVec3, n: DVec3) -> f64 {
    if let Lobe::MirrorPower { s } = lobe {
        let r = mirror_direction(wo, n);
        return power_density(s, r.dot(wi), sin2_between(r, wi).min(1.0));
    }
    let h = (wi + wo).normalize_or_zero();
    let (cos, sin2) = (n.dot(h), sin2_between(n, h).min(1.0));
    let cos_oh = wo.dot(h);
    if cos <= 0.0 || cos_oh <= 0.0 {
        return 0.0;
    }
    let cos2 = cos * cos;
    let p_h = match lobe {
        Lobe::Ggx { alpha } => {
            let a2 = alpha * alpha;
            let d = a2 * cos2 + sin2;
            a2 * FRAC_1_PI / (d * d) * cos
        }
        Lobe::Beckmann { m } => {
            let m2 = m * m;
            if sin2 >= crate::material::brdf::phong::EXP_CUTOFF * cos2 * m2 {
                return 0.0; // exponent ≤ −80, as d_beckmann
            }
            (-sin2 / (cos2 * m2)).exp() * FRAC_1_PI / (m2 * cos2 * cos)
        }
        Lobe::HalfPower { s } => power_density(s, cos, sin2),
        Lobe::MirrorPower { .. } | Lobe::None => 0.0,
    };
    p_h / (4.0 * cos_oh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::any_tangent;

    /// Each kind's density integrates to 1 over the sphere (a quadrature
    /// of `pdf`, at normal and oblique view; the part below the horizon
    /// counted too; at 0.3 rad the half vectors with `ω_o·h ≤ 0` that the
    /// density leaves out carry < 1e-3 for these widths), and `direction`
    /// lands at the polar angle `polar` gave (the half vector or the
    /// angle from `R` recovered from `ω_i`).
    #[test]
    fn the_densities_are_normalized() {
        let n = DVec3::Z;
        for lobe in [
            Lobe::Ggx { alpha: 0.2 },
            Lobe::Beckmann { m: 0.3 },
            Lobe::HalfPower { s: 20.0 },
            Lobe::MirrorPower { s: 20.0 },
        ] {
            for theta_o in [0.0f64, 0.3] {
                let wo = DVec3::new(theta_o.sin(), 0.0, theta_o.cos());
                let (t, b) = (any_tangent(n), n.cross(any_tangent(n)));
                for u in [0.1, 0.5, 0.9] {
                    let wi = direction(lobe, u, 0.3, wo, n, t, b);
                    let axis = match lobe {
                        Lobe::MirrorPower { .. } => mirror_direction(wo, n),
                        _ => n,
                    };
                    let probe = match lobe {
                        Lobe::MirrorPower { .. } => wi,
                        _ => (wi + wo).normalize(),
                    };
                    let cos = axis.dot(probe);
                    assert!((cos * cos - polar(lobe, u).0).abs() < 1e-12, "{lobe:?} {u}");
                }
                let (rings, segments) = (2000, 400);
                let mut total = 0.0;
                for i in 0..rings {
                    let z = 1.0 - 2.0 * (i as f64 + 0.5) / rings as f64;
                    let r = (1.0 - z * z).sqrt();
                    for j in 0..segments {
                        let phi = TAU * (j as f64 + 0.5) / segments as f64;
                        let wi = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                        total += pdf(lobe, wi, wo, n);
                    }
                }
                total *= 4.0 * std::f64::consts::PI / (rings * segments) as f64;
                assert!((total - 1.0).abs() < 2e-3, "{lobe:?} at {theta_o}: {total}");
            }
        }
    }

    /// `polar` keeps `cos² + sin² = 1` and both non-negative down to a
    /// roughness of 1e-8 and exponents of 1e8 (no NaN).
    #[test]
    fn polar_angles_are_consistent() {
        for lobe in [
            Lobe::Ggx { alpha: 1e-8 },
            Lobe::Beckmann { m: 1e-8 },
            Lobe::HalfPower { s: 1e8 },
            Lobe::MirrorPower { s: 0.0 },
        ] {
            for u in [1e-9, 0.5, 1.0 - 1e-9] {
                let (c, s) = polar(lobe, u);
                assert!(
                    c >= 0.0 && s >= 0.0 && (c + s - 1.0).abs() < 1e-12,
                    "{lobe:?} {u}"
                );
            }
        }
    }
}
