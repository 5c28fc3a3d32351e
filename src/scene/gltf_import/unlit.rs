//! `KHR_materials_unlit`: "the material's base color is the final color
//! of the fragment", no lighting. The material becomes one of model
//! `unlit` (contract "Other glTF material extensions";
//! `crate::material::brdf::unlit`): its `base_color` is
//! `baseColorFactor.rgb`, the `baseColorTexture` (sRGB) multiplies it, and
//! so does `COLOR_0` (as it multiplies every base colour,
//! `Material::vertex_coloured`), so the pixel's radiance is
//! `factor × texture × COLOR_0` under any light and environment, through
//! the same exposure and tone map as every other pixel (as in the Khronos
//! sample viewer). The alpha stays the base colour's: `baseColorFactor.a`,
//! and, for `MASK` and `BLEND`, the texture's A and `COLOR_0`'s A. Every
//! other property of the material (emissive, normal, occlusion, the other
//! extensions) is ignored, as the extension says: emission and `k_a` stay
//! 0.

use super::images::ImageSource;
use crate::material::{Material, ReflectanceModel};
use crate::scene::texture::Encoding;

pub(super) const NAME: &str = "KHR_materials_unlit";

/// Whether `material` is unlit.
pub(super) fn is_unlit(material: &gltf::Material) -> bool {
    material.extension_value(NAME).is_some()
}

/// Makes `out` (a `gltf-pbr` material with the core's factors, sides and
/// alpha) the unlit material of `material` (module documentation).
pub(super) fn convert(
    material: &gltf::Material,
    images: &mut ImageSource,
    out: &mut Material,
) -> Result<(), String> {
    let mut unlit = Material::new(out.name.clone(), ReflectanceModel::Unlit);
    unlit.base_color = out.base_color;
    unlit.alpha = out.alpha;
    unlit.alpha_mode = out.alpha_mode;
    unlit.sides = out.sides;
    if let Some(info) = material.pbr_metallic_roughness().base_color_texture() {
        let t = images.texture(&info, "base_color", Encoding::Srgb, 0);
        unlit
            .textures
            .push(t.map_err(|e| format!("baseColorTexture: {e}"))?);
    }
    *out = unlit;
    Ok(())
}
