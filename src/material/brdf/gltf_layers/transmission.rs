//! Light through the surface of the layered glTF material (contract:
//! "Light through surfaces"): the BTDFs of `KHR_materials_transmission`
//! and `KHR_materials_diffuse_transmission`, and the index of refraction
//! per wavelength of `KHR_materials_dispersion`. The volume's rough
//! dielectric BTDF (Walter et al. 2007) is [`super::volume_btdf`].
//!
//! `KHR_materials_transmission` ("BTDF") replaces a share `T` of the
//! dielectric base's diffuse part by the thin-walled specular BTDF,
//! `KHR_materials_diffuse_transmission` a share `D` of what remains by
//! Lambert on the far side:
//!
//! `dielectric = (1 − max₃ F) · mix(mix(b/π, c_dt/π ⁻, D), b · btdf, T) + F · S`
//!
//! (`⁻`: on the far side; `b` the base colour, `c_dt` the diffuse
//! transmission colour). The reflected diffuse thus keeps
//! `(1 − T)(1 − D)` of itself ([`reflected_diffuse_weight`], applied in
//! [`super::base_ior_specular::gltf_base`]), and for `L` on the far side
//! `f_t = (1 − m)(1 − max₃ F)(T · b · btdf + (1 − T) D · c_dt/π)`
//! ([`gltf_transmitted`]), scaled by the sheen and the coat above it as
//! the reflected base is. `F` is the base's Fresnel term at the half
//! vector of the mirrored light direction ([`mirrored_half_vector`]).
//!
//! WGSL twins: `reflected_diffuse_weight` and `transmission_fresnel` in
//! shaders/brdf/gltf_layers/base_ior_specular.wgsl (the GPU draws the
//! light through a surface in screen space, shaders/transmission.wgsl;
//! it has no BTDF to evaluate per light).

use super::GltfLayers;
use super::base_ior_specular::dielectric_f0;
use super::clearcoat::clearcoat_fresnel;
use super::sheen::sheen_scaling;
use crate::base::Rgb;
use crate::material::brdf::microfacet::vis_smith_ggx_correlated;
use crate::material::brdf::microfacet::{d_ggx, schlick_weight, sin2_between};
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// Defined beside the base it weighs (which may not import this file:
/// this file builds on the base's Fresnel term).
pub use super::base_ior_specular::reflected_diffuse_weight;

/// `L` mirrored to the viewer's side of the surface, `L − 2 (N·L) N`
/// (`KHR_materials_transmission`, "BTDF": "the half vector is computed
/// from the mirrored light direction").
pub fn mirrored(n: DVec3, wi: DVec3) -> DVec3 {
    wi - 2.0 * n.dot(wi) * n
}

/// The half vector of the thin-walled BTDF, `normalize(L' + V)` with `L'`
/// the mirrored light direction ([`mirrored`]); `N` for the straight
/// transmission `L = −V`.
pub fn mirrored_half_vector(n: DVec3, wi: DVec3, wo: DVec3) -> DVec3 {
    (mirrored(n, wi) + wo).normalize_or(n)
}

/// `KHR_materials_transmission`'s thin-walled `specular_btdf`
/// ("Implementation": `G_T D_T / (4 |N·L| |N·V|)`, the GGX lobe of
/// `α = r²` about the mirrored light direction), for `N·V > 0` and
/// `N·L < 0` (0 elsewhere): the reflection lobe `D·Vis` evaluated at
/// `(L', V)`, so the light goes straight through the wall, spread by the
/// roughness, with no macroscopic refraction. Untinted (the caller
/// multiplies by the base colour).
pub fn specular_btdf(alpha: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let (cos_i, cos_o) = (n.dot(wi), n.dot(wo));
    if cos_o <= 0.0 || cos_i >= 0.0 {
        return 0.0;
    }
    let l = mirrored(n, wi);
    let h = mirrored_half_vector(n, wi, wo);
    d_ggx(alpha, n.dot(h), sin2_between(n, h))
        * vis_smith_ggx_correlated(alpha, -cos_i, cos_o, l.dot(h), wo.dot(h))
}

/// `KHR_materials_diffuse_transmission`'s `diffuse_btdf`: Lambert on the
/// far side, `c_dt/π` for `N·V > 0`, `N·L < 0` (0 elsewhere).
pub fn diffuse_btdf(color: Rgb, n: DVec3, wi: DVec3, wo: DVec3) -> Rgb {
    if n.dot(wo) <= 0.0 || n.dot(wi) >= 0.0 {
        return Rgb::ZERO;
    }
    color * FRAC_1_PI
}

/// The base's Fresnel term `F_d = s_w (f0 + (1 − f0) w)` at the half
/// vector `h` (the reflected base's, contract "Base"; iridescence is not
/// mixed in here: the film is a reflection effect of the layered BRDF).
pub fn transmission_fresnel(layers: &GltfLayers, h: DVec3, wo: DVec3) -> Rgb {
    let f0 = dielectric_f0(layers.ior, layers.specular_color);
    (f0 + (Rgb::ONE - f0) * schlick_weight(wo.dot(h))) * layers.specular
}

/// The transmitted part `f_t` of the layered glTF material for `N·V > 0`,
/// `N·L < 0` (module doc): `(1 − m)(1 − max₃ F)(T b btdf + (1 − T) D
/// c_dt/π)`, under the sheen's albedo scaling (`albedo_o = E(μ_o)`,
/// `albedo_i = E(|μ_i|)`, 0 without sheen) and the coat's `1 − k F_c`.
/// Not reciprocal for the same reason the reflected layers are not
/// (`F_c` reads `V` alone).
#[allow(clippy::too_many_arguments)]
pub fn gltf_transmitted(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    layers: &GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let (specular, diffuse) = gltf_transmitted_parts(
        base_color, metallic, roughness, layers, albedo_o, albedo_i, n, wi, wo,
    );
    specular + diffuse
}

/// [`gltf_transmitted`]'s two lobes apart, `(specular, diffuse)`: the
/// thin-walled specular BTDF's term and diffuse transmission's (a
/// renderer samples each by its own density).
#[allow(clippy::too_many_arguments)]
pub fn gltf_transmitted_parts(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    layers: &GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> (Rgb, Rgb) {
    let cos_o = n.dot(wo);
    if cos_o <= 0.0 || n.dot(wi) >= 0.0 || !layers.transmits() {
        return (Rgb::ZERO, Rgb::ZERO);
    }
    let alpha = roughness * roughness;
    let h = mirrored_half_vector(n, wi, wo);
    let f = transmission_fresnel(layers, h, wo).max_element();
    let mut scale = (1.0 - metallic) * (1.0 - f);
    if layers.has_sheen() {
        scale *= sheen_scaling(layers.sheen_color, albedo_o, albedo_i);
    }
    if layers.has_clearcoat() {
        scale *= 1.0 - layers.clearcoat * clearcoat_fresnel(cos_o);
    }
    let specular = base_color * (layers.transmission * specular_btdf(alpha, n, wi, wo) * scale);
    let diffuse = diffuse_btdf(layers.diffuse_transmission_color, n, wi, wo)
        * ((1.0 - layers.transmission) * layers.diffuse_transmission * scale);
    (specular, diffuse)
}

/// `KHR_materials_dispersion`'s index of refraction at wavelength
/// `lambda_nm`: `n(λ) = max(n_d + (n_d − 1)/V_d · (523655/λ² − 1.5168), 1)`
/// with `V_d = 20 / dispersion` (the extension's "Implementation", a
/// Cauchy form fitted through the Fraunhofer d, F and C lines:
/// `n_d = n(587.56 nm)`, `V_d = (n_d − 1)/(n_F − n_C)`). `dispersion = 0`
/// gives `n_d` at every wavelength.
pub fn dispersion_ior(ior: f64, dispersion: f64, lambda_nm: f64) -> f64 {
    if dispersion <= 0.0 {
        return ior;
    }
    let abbe = 20.0 / dispersion;
    (ior + (ior - 1.0) / abbe * (523_655.0 / (lambda_nm * lambda_nm) - 1.5168)).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::brdf::SurfaceFrame;
    use crate::material::brdf::dfg;
    use crate::material::brdf::gltf_layers::stack::gltf_layered;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    fn dir(theta: f64, phi: f64) -> DVec3 {
        DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    }

    /// `(R, T)`: the directional albedos reflected (`∫ f_r cos` over the
    /// front) and transmitted (`∫ f_t |cos|` over the back) of a
    /// `gltf-pbr` material seen from `wo`, by the midpoint rule on a
    /// `(θ, φ)` grid of `n × 2n` per hemisphere, θ dense towards the
    /// pole (`θ = (π/2) u²`, so a narrow lobe at normal incidence is
    /// resolved).
    fn albedos(b: Rgb, r: f64, layers: &GltfLayers, wo: DVec3, n: usize) -> (Rgb, Rgb) {
        let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
        let (mut refl, mut trans) = (Rgb::ZERO, Rgb::ZERO);
        for a in 0..n {
            let u = (a as f64 + 0.5) / n as f64;
            let theta = FRAC_PI_2 * u * u;
            let dtheta = PI * u / n as f64;
            for c in 0..2 * n {
                let phi = TAU * (c as f64 + 0.5) / (2 * n) as f64;
                let dw = theta.sin() * dtheta * TAU / (2 * n) as f64;
                let wi = dir(theta, phi);
                refl += gltf_layered(b, 0.0, r, 0.0, layers, &frame, wi, wo) * (wi.z * dw);
                let below = DVec3::new(wi.x, wi.y, -wi.z);
                trans += gltf_transmitted(b, 0.0, r, layers, 0.0, 0.0, DVec3::Z, below, wo)
                    * (wi.z * dw);
            }
        }
        (refl, trans)
    }

    fn glass() -> GltfLayers {
        GltfLayers {
            transmission: 1.0,
            ..GltfLayers::default()
        }
    }

    /// The thin-wall white furnace: a white, non-absorbing dielectric at
    /// transmission 1 reflects `F·S` and transmits `(1 − F)·S` about the
    /// mirrored direction, so `R + T = ∫ D·Vis cos`, the GGX lobe's
    /// single-scattering albedo `E(μ_o, α)` (Smith's model loses the
    /// light that scatters more than once; `dfg::integrate`'s `A + B`
    /// at `F0 = 1`). Checked against it within 2·10⁻³ (the grid's error
    /// for these lobes, measured below 5·10⁻⁴ against a grid of twice
    /// the resolution, plus the 4096-sample quadrature's), and `R + T ≤ 1`.
    /// In the smooth limit (r = 0.1, α = 0.01, normal incidence) the loss
    /// `1 − E` is 1.1·10⁻⁴ (below 2·10⁻⁴) and `R + T = 1` within 10⁻³:
    /// light is either reflected or transmitted.
    #[test]
    fn thin_wall_white_furnace() {
        for (r, theta_o) in [(0.5, 0.0), (0.5, 1.0), (0.7, 0.3), (0.3, 1.3), (1.0, 0.5)] {
            let wo = dir(theta_o, 0.0);
            let (refl, trans) = albedos(Rgb::ONE, r, &glass(), wo, 400);
            let sum = (refl + trans).x;
            let [a, b] = dfg::integrate(wo.z, r * r, 1 << 16);
            let e = a + b;
            assert!(sum <= 1.0 + 1e-3, "r {r} θ {theta_o}: {sum}");
            assert!(
                (sum - e).abs() < 2e-3,
                "r {r} θ {theta_o}: R {refl} T {trans} vs E {e}"
            );
            assert!(
                trans.x > refl.x,
                "a dielectric transmits most: {refl} {trans}"
            );
        }
        let (refl, trans) = albedos(Rgb::ONE, 0.1, &glass(), DVec3::Z, 2000);
        let [a, b] = dfg::integrate(1.0, 0.01, 1 << 16);
        assert!(1.0 - (a + b) < 2e-4, "Smith's loss {}", 1.0 - (a + b));
        let sum = (refl + trans).x;
        assert!((sum - 1.0).abs() < 1e-3, "R {refl} + T {trans} = {sum}");
        // Reflected share at normal incidence: F(0) = 0.04.
        assert!((refl.x - 0.04).abs() < 1e-3, "{refl}");
    }

    /// Half transmission, diffuse transmission and a coloured base: every
    /// channel's `R + T ≤ 1` at every angle to 80° from the normal (lobes
    /// of r ≥ 0.5, which the 300 × 600 grid resolves there; nearer the
    /// horizon the reflected lobe crowds against it and the grid, dense at
    /// the pole, overestimates it) (the glTF mix is not exactly
    /// energy conserving, but never creates energy), and a black base
    /// colour transmits nothing specular.
    #[test]
    fn mixed_transmission_never_exceeds_one() {
        let layers = [
            GltfLayers {
                transmission: 0.5,
                ..GltfLayers::default()
            },
            GltfLayers {
                diffuse_transmission: 1.0,
                ..GltfLayers::default()
            },
            GltfLayers {
                transmission: 0.3,
                diffuse_transmission: 0.6,
                diffuse_transmission_color: Rgb::new(1.0, 0.5, 0.0),
                ..GltfLayers::default()
            },
        ];
        let mut gain = 0.0f64;
        for l in &layers {
            for theta_o in [0.0, 0.7, 1.1, 1.4] {
                for r in [0.5, 0.8] {
                    let wo = dir(theta_o, 0.0);
                    let (refl, trans) = albedos(Rgb::new(1.0, 0.7, 0.2), r, l, wo, 300);
                    let sum = refl + trans;
                    let bound = if l.diffuse_transmission > 0.0 {
                        let (r_s, _) = albedos(Rgb::ZERO, r, l, wo, 300);
                        1.0 + r_s.max_element()
                    } else {
                        1.0
                    };
                    assert!(
                        sum.max_element() <= bound + 1e-3,
                        "{l:?} θ {theta_o}: {sum} above {bound}"
                    );
                    assert!(trans.min_element() >= 0.0);
                    gain = gain.max(sum.max_element() - 1.0);
                }
            }
        }
        eprintln!("largest R + T − 1 of the specification's mix: {gain:.3}");
        let (_, trans) = albedos(Rgb::ZERO, 0.5, &glass(), DVec3::Z, 50);
        assert_eq!(trans, Rgb::ZERO);
    }

    /// Finite at the extremes: roughness at the floor (α = 10⁻⁸), grazing
    /// views and lights, `ior = 1` (F0 = 0) and `ior = 0` (F = 1: nothing
    /// transmitted).
    #[test]
    fn btdfs_are_finite_at_the_extremes() {
        let n = DVec3::Z;
        for r in [1e-4, 1e-2, 1.0] {
            for ior in [0.0, 1.0, 1.5] {
                let l = GltfLayers {
                    ior,
                    transmission: 1.0,
                    diffuse_transmission: 0.5,
                    ..GltfLayers::default()
                };
                for to in [0.0, 1.0, FRAC_PI_2 - 1e-4, FRAC_PI_2] {
                    for ti in [0.0, 0.5, FRAC_PI_2 - 1e-4, FRAC_PI_2] {
                        let (wo, wi) = (dir(to, 0.0), -dir(ti, 0.3));
                        let f = gltf_transmitted(Rgb::ONE, 0.0, r, &l, 0.0, 0.0, n, wi, wo);
                        assert!(
                            f.is_finite() && f.min_element() >= 0.0,
                            "r {r} ior {ior} {to} {ti}: {f}"
                        );
                        if ior == 0.0 {
                            assert_eq!(f, Rgb::ZERO);
                        }
                    }
                }
            }
        }
        // Straight through at normal incidence, the peak: D = 1/(π α²),
        // Vis = 1/4 (as the reflection lobe's at the mirror direction).
        let alpha: f64 = 0.25;
        let f = specular_btdf(alpha, n, -n, n);
        assert!((f - 1.0 / (PI * alpha * alpha) / 4.0).abs() < 1e-12 * f);
    }

    /// The dispersion's index at the Fraunhofer lines: `n(587.56) = n_d`
    /// (to the rounding of the constant 1.5168: `523655/587.56²` is
    /// 1.516848, so within 5·10⁻⁵ of `(n_d − 1)/V_d`) and
    /// `n_F − n_C = (n_d − 1)/V_d` (the Abbe number's definition, to 10⁻⁴
    /// relative: the constants are rounded to five digits).
    #[test]
    fn dispersion_recovers_the_abbe_number() {
        let (nd, dispersion) = (1.5, 20.0 / 40.0);
        let vd = 20.0 / dispersion;
        let n = |l| dispersion_ior(nd, dispersion, l);
        assert!((n(587.56) - nd).abs() < 5e-5 * (nd - 1.0) / vd);
        let spread = n(486.13) - n(656.27);
        assert!((spread * vd / (nd - 1.0) - 1.0).abs() < 1e-4, "{spread}");
        assert_eq!(dispersion_ior(1.5, 0.0, 400.0), 1.5);
    }
}
