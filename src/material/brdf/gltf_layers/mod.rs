//! glTF's "PBR next" layers on the metallic-roughness BRDF: the contract's
//! "Layered glTF materials" (`shared/spec/conventions.md`), one layer per
//! file, composed as the KHR_materials_* specifications layer them:
//!
//! * [`base_ior_specular`]: the base (glTF 2.0 Appendix B) with
//!   `KHR_materials_ior`, `KHR_materials_specular` and the anisotropic GGX
//!   lobe of `KHR_materials_anisotropy` (Burley 2012);
//! * [`iridescence`]: the thin-film Fresnel of `KHR_materials_iridescence`
//!   (Belcour & Barla 2017, in the Khronos Sample Renderer's XYZ-Fourier
//!   form), mixed into the base's Fresnel terms;
//! * [`sheen`] and [`sheen_albedo`]: the Charlie sheen of
//!   `KHR_materials_sheen` (Conty & Kulla 2017) and the exact directional
//!   albedo `E(μ, α_sh)` its albedo scaling uses (Kulla & Conty 2017),
//!   read from a [`sheen_curve`] of measured error once a sheen `α` is
//!   asked for often;
//! * [`clearcoat`]: `KHR_materials_clearcoat`'s coat, a GGX lobe of IOR 1.5
//!   over everything below;
//! * [`stack`]: base → sheen → clearcoat;
//! * [`transmission`], [`volume_btdf`] and [`volume_albedo`]: light
//!   through the surface (`KHR_materials_transmission`,
//!   `_diffuse_transmission`, `_volume`, `_dispersion`): the thin-walled
//!   and diffuse BTDFs, the rough dielectric BSDF of Walter et al. 2007
//!   and its albedo by quadrature, and `n(λ)`.
//!
//! Every layer at its default leaves the core BRDF exactly as
//! [`super::gltf_pbr::gltf_pbr`] computes it (each layer is switched off by
//! its contract condition, and the base keeps the core's operations).
//!
//! WGSL twins: `shaders/brdf/gltf_layers/*.wgsl` (same files, names and
//! order).

pub mod base_ior_specular;
pub mod clearcoat;
pub mod iridescence;
pub mod sheen;
pub mod sheen_albedo;
pub mod sheen_albedo_nodes;
pub mod sheen_curve;
pub mod stack;
pub mod transmission;
pub mod volume_albedo;
pub mod volume_btdf;

use crate::base::Rgb;

pub use crate::material::layers::GltfLayers;

impl GltfLayers {
    /// Whether the thin film is on (`ι > 0` and `d > 0`, pinned choice 2).
    pub fn has_iridescence(&self) -> bool {
        self.iridescence > 0.0 && self.iridescence_thickness > 0.0
    }

    /// Whether the sheen is on (`c_sh ≠ 0`).
    pub fn has_sheen(&self) -> bool {
        self.sheen_color != Rgb::ZERO
    }

    /// Whether the coat is on (`k > 0`).
    pub fn has_clearcoat(&self) -> bool {
        self.clearcoat > 0.0
    }

    /// Whether the base lobe is anisotropic (`s_a > 0`).
    pub fn has_anisotropy(&self) -> bool {
        self.anisotropy_strength > 0.0
    }
}

#[cfg(test)]
mod tests;
