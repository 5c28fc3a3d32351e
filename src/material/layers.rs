//! The layer parameters of a `gltf-pbr` material: the keys of the
//! glTF material extensions (contract, "Layered glTF materials"), a plain
//! value the material holds and its BRDF (`brdf::gltf_layers`) reads.

use crate::base::Rgb;

/// The layer parameters of a `gltf-pbr` material (the contract's keys,
/// with its defaults); the core's `base_color`, `metallic` and
/// `roughness` are passed beside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfLayers {
    /// `KHR_materials_ior.ior`; 0 is the specular-glossiness mode (the
    /// Fresnel term of the IOR is 1).
    pub ior: f64,
    /// `KHR_materials_specular.specularFactor`, `s_w`.
    pub specular: f64,
    /// `…specularColorFactor`, `c_s` (may exceed 1).
    pub specular_color: Rgb,
    /// `KHR_materials_clearcoat.clearcoatFactor`, `k`.
    pub clearcoat: f64,
    /// `…clearcoatRoughnessFactor`, perceptual `r_c` (α_c = r_c²).
    pub clearcoat_roughness: f64,
    /// `KHR_materials_sheen.sheenColorFactor`, `c_sh`.
    pub sheen_color: Rgb,
    /// `…sheenRoughnessFactor`, perceptual `r_sh`.
    pub sheen_roughness: f64,
    /// `KHR_materials_iridescence.iridescenceFactor`, `ι`.
    pub iridescence: f64,
    /// `…iridescenceIor`, the film's index `η_f`.
    pub iridescence_ior: f64,
    /// The film's thickness `d` \[nm\].
    pub iridescence_thickness: f64,
    /// `KHR_materials_anisotropy.anisotropyStrength`, `s_a`.
    pub anisotropy_strength: f64,
    /// `…anisotropyRotation`, `ρ` \[rad\] from `t` towards `b`.
    pub anisotropy_rotation: f64,
}

impl Default for GltfLayers {
    /// The glTF defaults: every layer off, the core BRDF unchanged.
    fn default() -> Self {
        GltfLayers {
            ior: 1.5,
            specular: 1.0,
            specular_color: Rgb::ONE,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            sheen_color: Rgb::ZERO,
            sheen_roughness: 0.0,
            iridescence: 0.0,
            iridescence_ior: 1.3,
            iridescence_thickness: 400.0,
            anisotropy_strength: 0.0,
            anisotropy_rotation: 0.0,
        }
    }
}
