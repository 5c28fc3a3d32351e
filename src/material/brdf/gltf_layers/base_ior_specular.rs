//! The base of the layered glTF material: glTF 2.0's metallic-roughness
//! BRDF (Appendix B, `mix` form) with `KHR_materials_ior`,
//! `KHR_materials_specular` and the anisotropic lobe of
//! `KHR_materials_anisotropy` (contract: "Layered glTF materials",
//! "Anisotropic lobe" and "Base"; pinned choices 4, 8, 9):
//!
//! `f0 = min(f0_ior · c_s, 1)`, `f0_ior = ((ior − 1)/(ior + 1))²`,
//! `F_d = s_w (f0 + (1 − f0) w)`, `F_m = b + (1 − b) w`, `w = (1 − |V·H|)⁵`,
//! `dielectric = (1 − max₃ F_d) · b/π + F_d · S`, `metal = F_m · S`,
//! `material = (1 − m) · dielectric + m · metal`,
//!
//! `S = D·Vis` the GGX lobe, isotropic (glTF's `G_α`) or, for `s_a > 0`,
//! Burley's (2012, "Physically-Based Shading at Disney", Appendix B.2)
//! anisotropic GGX with the height-correlated Smith visibility of Heitz
//! (2014, eq. 99) as `KHR_materials_anisotropy` writes them. The thin film
//! ([`super::iridescence`]) replaces the Fresnel terms by its mix when on.
//!
//! With the defaults (`ior = 1.5`, `s_w = 1`, `c_s = 1`, `s_a = 0`, no
//! film) every operation is the core's ([`crate::material::brdf::gltf_pbr`]),
//! so the value is the same to the bit: `f0_ior` is taken as
//! `(ior − 1)²/(ior + 1)²`, which is 0.25/6.25 = 0.04 correctly rounded
//! (`(0.5/2.5)²` would be one ulp above).
//!
//! WGSL twin: `shaders/brdf/gltf_layers/base_ior_specular.wgsl`.

use super::GltfLayers;
use super::iridescence::iridescence_fresnel;
use crate::base::Rgb;
use crate::material::brdf::COS_FLOOR;
use crate::material::brdf::energy::ms_factor;
use crate::material::brdf::microfacet::{d_ggx, half_vector, sin2_between};
use crate::material::brdf::microfacet::{schlick_weight, vis_smith_ggx_correlated};
use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_1_PI, PI};

/// `KHR_materials_ior`'s normal-incidence reflectance from air,
/// `((ior − 1)/(ior + 1))²`, evaluated as `(ior − 1)²/(ior + 1)²` (exact
/// for the default 1.5). `ior = 0` gives 1: the specular-glossiness mode
/// (pinned choice 4); `ior = 1` gives 0.
pub fn f0_from_ior(ior: f64) -> f64 {
    let (num, den) = (ior - 1.0, ior + 1.0);
    (num * num) / (den * den)
}

/// The dielectric's F0 per channel, `min(f0_ior · c_s, 1)`
/// (`KHR_materials_specular`, "Implementation").
pub fn dielectric_f0(ior: f64, specular_color: Rgb) -> Rgb {
    (Rgb::splat(f0_from_ior(ior)) * specular_color).min(Rgb::ONE)
}

/// The anisotropy direction `T = cos ρ · t + sin ρ · b` and `B = N × T`
/// from `direction = (cos ρ, sin ρ)` ([`GltfLayers::anisotropy_direction`])
/// (`KHR_materials_anisotropy`; pinned choice 8: ρ counter-clockwise from
/// the tangent towards the bitangent).
pub fn anisotropy_frame(direction: DVec2, n: DVec3, t: DVec3, b: DVec3) -> (DVec3, DVec3) {
    let dir = t * direction.x + b * direction.y;
    (dir, n.cross(dir))
}

/// `α_t = α + (1 − α) s_a²` (`KHR_materials_anisotropy`, "Implementation";
/// `α_b = α`).
pub fn anisotropic_alpha_t(alpha: f64, strength: f64) -> f64 {
    alpha + (1.0 - alpha) * strength * strength
}

/// Burley's anisotropic GGX (2012, eq. 13):
/// `D = 1 / (π α_t α_b ((H·T)²/α_t² + (H·B)²/α_b² + (N·H)²)²)`, evaluated
/// as `(α_t α_b)³ / (π (α_b² (H·T)² + α_t² (H·B)² + α_t² α_b² (N·H)²)²)`
/// (the same number; no `1/α²` that would leave `f32`'s range first), 0
/// for `N·H ≤ 0`. At `α_t = α_b = α` it is GGX's `D` (`d_ggx`).
pub fn d_ggx_anisotropic(alpha_t: f64, alpha_b: f64, cos_th: f64, cos_bh: f64, cos_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha_t * alpha_b;
    let (ft, fb, fn_) = (alpha_b * cos_th, alpha_t * cos_bh, a2 * cos_h);
    let w2 = a2 / (ft * ft + fb * fb + fn_ * fn_);
    a2 * w2 * w2 / PI
}

/// Height-correlated Smith visibility of the anisotropic GGX
/// (`KHR_materials_anisotropy`; Heitz 2014, eq. 99):
/// `½ / (μ_i √(α_t²(T·V)² + α_b²(B·V)² + μ_o²) + μ_o √(α_t²(T·L)² + α_b²(B·L)² + μ_i²))`,
/// with `χ⁺(H·L) χ⁺(H·V)` and the cosines in front floored at
/// [`COS_FLOOR`] as `vis_smith_ggx_correlated` does.
#[allow(clippy::too_many_arguments)]
pub fn vis_ggx_anisotropic(
    alpha_t: f64,
    alpha_b: f64,
    cos_i: f64,
    cos_o: f64,
    cos_ti: f64,
    cos_bi: f64,
    cos_to: f64,
    cos_bo: f64,
    cos_ih: f64,
    cos_oh: f64,
) -> f64 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0;
    }
    let (ci, co) = (cos_i.min(1.0), cos_o.min(1.0));
    let root_o = DVec3::new(alpha_t * cos_to, alpha_b * cos_bo, co).length();
    let root_i = DVec3::new(alpha_t * cos_ti, alpha_b * cos_bi, ci).length();
    0.5 / (ci.max(COS_FLOOR) * root_o + co.max(COS_FLOOR) * root_i)
}

/// The base lobe `S = D·Vis`: glTF's isotropic `G_α` at `s_a = 0` (the
/// core's functions, bit for bit), the anisotropic lobe above.
pub fn base_lobe(
    alpha: f64,
    layers: &GltfLayers,
    n: DVec3,
    t: DVec3,
    b: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> f64 {
    let h = half_vector(wi, wo);
    let (cos_i, cos_o, cos_h) = (n.dot(wi), n.dot(wo), n.dot(h));
    let (cos_ih, cos_oh) = (wi.dot(h), wo.dot(h));
    if !layers.has_anisotropy() {
        let sin2_h = sin2_between(n, h);
        return d_ggx(alpha, cos_h, sin2_h)
            * vis_smith_ggx_correlated(alpha, cos_i, cos_o, cos_ih, cos_oh);
    }
    let (at, bt) = anisotropy_frame(layers.anisotropy_direction(), n, t, b);
    let alpha_t = anisotropic_alpha_t(alpha, layers.anisotropy_strength);
    d_ggx_anisotropic(alpha_t, alpha, at.dot(h), bt.dot(h), cos_h)
        * vis_ggx_anisotropic(
            alpha_t,
            alpha,
            cos_i,
            cos_o,
            at.dot(wi),
            bt.dot(wi),
            at.dot(wo),
            bt.dot(wo),
            cos_ih,
            cos_oh,
        )
}

/// The base `material` of the contract for `N·L > 0`, `N·V > 0`: the
/// dielectric and metal Fresnel terms (mixed with the thin film's when
/// iridescence is on: `F* = (1 − ι) F_d + ι F_ir(s_w f0)`, pinned choice
/// 9, and `(1 − ι) F_m + ι F_ir(b)`), the diffuse weighted by
/// `1 − max₃ F*`. `ms` is energy compensation's `(1 − E)/E` (0 without):
/// the dielectric lobe is scaled by `1 + s_w f0 · ms`, the metal's by
/// `1 + b · ms`, as the core does with its F0s.
#[allow(clippy::too_many_arguments)]
pub fn gltf_base(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    layers: &GltfLayers,
    n: DVec3,
    t: DVec3,
    b: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let alpha = roughness * roughness;
    let specular = base_lobe(alpha, layers, n, t, b, wi, wo);
    let w = schlick_weight(wo.dot(half_vector(wi, wo)));
    let f0 = dielectric_f0(layers.ior, layers.specular_color);
    let mut f_dielectric = (f0 + (Rgb::ONE - f0) * w) * layers.specular;
    let mut f_metal = base_color + (Rgb::ONE - base_color) * w;
    if layers.has_iridescence() {
        let iota = layers.iridescence;
        let (eta_f, d, cos_o) = (
            layers.iridescence_ior,
            layers.iridescence_thickness,
            n.dot(wo),
        );
        f_dielectric = f_dielectric * (1.0 - iota)
            + iridescence_fresnel(cos_o, eta_f, d, f0 * layers.specular) * iota;
        f_metal = f_metal * (1.0 - iota) + iridescence_fresnel(cos_o, eta_f, d, base_color) * iota;
    }
    // Transmission takes its share of the diffuse part (exactly 1 without).
    let diffuse_weight = reflected_diffuse_weight(layers);
    let dielectric = base_color * ((1.0 - f_dielectric.max_element()) * FRAC_1_PI * diffuse_weight)
        + f_dielectric * specular * ms_factor(f0 * layers.specular, ms);
    let metal = f_metal * specular * ms_factor(base_color, ms);
    dielectric * (1.0 - metallic) + metal * metallic
}
/// The share of the base's diffuse part still reflected, `(1 − T)(1 − D)`
/// (`KHR_materials_transmission` and `KHR_materials_diffuse_transmission`
/// replace those shares of it; exactly 1 at the defaults, so the core
/// BRDF is unchanged bit for bit). WGSL twin: `reflected_diffuse_weight`
/// in shaders/brdf/gltf_layers/base_ior_specular.wgsl (`1 − T`: the GPU
/// does not draw diffuse transmission).
pub fn reflected_diffuse_weight(layers: &GltfLayers) -> f64 {
    (1.0 - layers.transmission) * (1.0 - layers.diffuse_transmission)
}
