//! The composition of the layered glTF material (contract: "Layered glTF
//! materials", "Composition"): the base (`material`, with `ior`,
//! `specular`, `iridescence`, `anisotropy` inside it,
//! [`super::base_ior_specular`]) → the sheen on top (`sheened`,
//! [`super::sheen`]) → the clearcoat on top (`f_r`, [`super::clearcoat`]),
//! each layer skipped when its contract condition is off (so the defaults
//! give the core BRDF exactly). [`gltf_layer_term`] gives one layer's
//! term of that sum apart (the explorer's; the GPU draws the whole).
//!
//! WGSL twin: `shaders/brdf/gltf_layers/stack.wgsl`.

use super::GltfLayers;
use super::base_ior_specular::gltf_base;
use super::clearcoat::{clearcoat_over, clearcoat_term, clearcoat_weight, coat_normal};
use super::sheen::{sheen_alpha, sheen_lobe, sheen_scaling};
use super::sheen_curve::sheen_albedo_of;
use crate::base::Rgb;
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::microfacet::{half_vector, sin2_between};
use crate::material::layers::LayerTerm;
use glam::DVec3;

/// The sheen's own term `c_sh · D_sh · V_sh` (the explorer's
/// [`LayerTerm::Sheen`] before the coat's `1 − k F_c`).
pub fn sheen_term(layers: &GltfLayers, n: DVec3, wi: DVec3, wo: DVec3) -> Rgb {
    let alpha = sheen_alpha(layers.sheen_roughness);
    let h = half_vector(wi, wo);
    let lobe = sheen_lobe(alpha, n.dot(h), sin2_between(n, h), n.dot(wi), n.dot(wo));
    layers.sheen_color * lobe
}

/// The sheen over `below`: `c_sh · D_sh · V_sh + σ · below`, with the
/// sheen's directional albedos `albedo_o = E(μ_o)`, `albedo_i = E(μ_i)`
/// given (exact in [`gltf_layered`]; the GPU's from its table).
pub fn sheen_over(
    below: Rgb,
    layers: &GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    sheen_term(layers, n, wi, wo) + below * sheen_scaling(layers.sheen_color, albedo_o, albedo_i)
}

/// The layered `f_r` for `N·L > 0`, `N·V > 0` with the sheen albedos
/// given: base → sheen → clearcoat. `ms` is energy compensation's ratio of
/// the base (0 without).
#[allow(clippy::too_many_arguments)]
pub fn gltf_layered_with_albedos(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    layers: &GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
    frame: &SurfaceFrame,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let n = frame.n;
    let mut f = gltf_base(
        base_color, metallic, roughness, ms, layers, n, frame.t, frame.b, wi, wo,
    );
    if layers.has_sheen() {
        f = sheen_over(f, layers, albedo_o, albedo_i, n, wi, wo);
    }
    if layers.has_clearcoat() {
        let n_c = coat_normal(frame, layers.clearcoat_normal);
        f = clearcoat_over(f, layers.clearcoat, layers.clearcoat_roughness, n_c, wi, wo);
    }
    f
}

/// The sheen's directional albedos `(E(μ_o), E(μ_i))`, exact (0, 0 without
/// sheen: not read): the integral, or its curve once this sheen `α` has
/// been asked for often ([`super::sheen_curve`], error under f32's).
pub fn sheen_albedos(layers: &GltfLayers, cos_i: f64, cos_o: f64) -> (f64, f64) {
    if !layers.has_sheen() {
        return (0.0, 0.0);
    }
    let albedo = sheen_albedo_of(sheen_alpha(layers.sheen_roughness));
    (albedo.at(cos_o), albedo.at(cos_i))
}

/// The layered `f_r` of the contract for `N·L > 0`, `N·V > 0`, the sheen
/// scaled by the exact albedos.
#[allow(clippy::too_many_arguments)]
pub fn gltf_layered(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    layers: &GltfLayers,
    frame: &SurfaceFrame,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let (e_o, e_i) = sheen_albedos(layers, frame.n.dot(wi), frame.n.dot(wo));
    gltf_layered_with_albedos(
        base_color, metallic, roughness, ms, layers, e_o, e_i, frame, wi, wo,
    )
}

/// One term of the layered `f_r` ([`LayerTerm`]) for `N·L > 0`,
/// `N·V > 0`, the sheen's albedos given as for
/// [`gltf_layered_with_albedos`]. The composition is linear in each
/// layer's lobe: `f_r = (1 − k F_c)(sheen + σ · base) + coat`, so each term
/// is its layer's lobe (the same functions the stack calls) times the
/// weights of the layers above it, `σ` (the sheen's albedo scaling) and
/// `1 − k F_c` (the coat's Fresnel), each 1 where that layer is off:
///
/// * base: `material · σ (1 − k F_c)`;
/// * sheen: `c_sh D_sh V_sh · (1 − k F_c)` (0 without sheen);
/// * clearcoat: `k F_c G_{α_c}` (0 without a coat).
///
/// Their sum is the whole (to rounding: the stack multiplies in another
/// order); [`LayerTerm::All`] returns the whole as the stack computes it.
/// CPU only, for the explorer's plots and albedo per layer: no WGSL twin.
#[allow(clippy::too_many_arguments)]
pub fn gltf_layer_term(
    term: LayerTerm,
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    layers: &GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
    frame: &SurfaceFrame,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let n = frame.n;
    let n_c = coat_normal(frame, layers.clearcoat_normal);
    let through_coat = if layers.has_clearcoat() {
        1.0 - clearcoat_weight(layers.clearcoat, n_c, wo)
    } else {
        1.0
    };
    match term {
        LayerTerm::All => gltf_layered_with_albedos(
            base_color, metallic, roughness, ms, layers, albedo_o, albedo_i, frame, wi, wo,
        ),
        LayerTerm::Base => {
            let sigma = if layers.has_sheen() {
                sheen_scaling(layers.sheen_color, albedo_o, albedo_i)
            } else {
                1.0
            };
            gltf_base(
                base_color, metallic, roughness, ms, layers, n, frame.t, frame.b, wi, wo,
            ) * (sigma * through_coat)
        }
        LayerTerm::Sheen if layers.has_sheen() => sheen_term(layers, n, wi, wo) * through_coat,
        LayerTerm::Clearcoat if layers.has_clearcoat() => {
            clearcoat_term(layers.clearcoat, layers.clearcoat_roughness, n_c, wi, wo)
        }
        LayerTerm::Sheen | LayerTerm::Clearcoat => Rgb::ZERO,
    }
}
