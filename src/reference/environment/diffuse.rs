//! The diffuse albedo the environment lights in the modes that take the
//! diffuse term by SH irradiance: shared by the reflection equation
//! (`specular = "none"`, `super::super::shading`) and the `"prefiltered"`
//! and `"sh"` estimates.

use crate::base::Rgb;
use crate::material::{Material, ReflectanceModel};

/// The albedo the environment's SH irradiance lights (`specular =
/// "none"`): `k_d` for the lecture's models; for gltf-pbr its Lambert part
/// `(1 − m)·b` from the per-pixel base colour and metallic (the factor
/// `1 − F_d` of the mix form depends on `V·H` and is left out: at most 4 %
/// at normal incidence, more towards grazing); nothing for a measured table
/// (its `f_r` has no separate diffuse term; `specular = "sampled"`
/// integrates all of it). WGSL twin: `environment_diffuse_albedo` in
/// shaders/shading.wgsl.
pub fn environment_diffuse_albedo(material: &Material) -> Rgb {
    match material.model {
        // Transmission takes its share of the diffuse part (1 without).
        ReflectanceModel::GltfPbr => material.base_color
            * ((1.0 - material.metallic)
                * crate::material::brdf::gltf_layers::base_ior_specular::reflected_diffuse_weight(
                    &material.layers,
                )),
        ReflectanceModel::Measured => Rgb::ZERO,
        _ => material.brdf().k_d,
    }
}
