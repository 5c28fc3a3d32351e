//! `KHR_materials_unlit`: "the material's base color is the final color
//! of the fragment", no lighting. gonio has no unlit model, so the
//! material becomes a `gltf-pbr` one that reflects nothing and emits its
//! base colour: `emission = baseColorFactor.rgb` with the
//! `baseColorTexture` (sRGB) on `emission`, and a zero BRDF (`base_color`
//! 0, `metallic` 0, `specular` 0, so the contract's base has no diffuse
//! and no specular term; `k_a` 0, so an ambient light adds nothing). Under
//! any light and environment the pixel's radiance is then the base colour,
//! as the extension asks, and it goes through the same exposure and tone
//! map as every other pixel (as in the Khronos sample viewer). The alpha
//! stays the base colour's: `baseColorFactor.a`, and, for `MASK` and
//! `BLEND`, the texture's A (the texture also sits on the zero
//! `base_color`, where it carries only the alpha). Every other property of
//! the material (emissive, normal, occlusion, the other extensions) is
//! ignored, as the extension says; `COLOR_0` does not multiply the
//! emission (a warning where an unlit material meets vertex colours).

use super::images::ImageSource;
use crate::material::{AlphaMode, Material};
use crate::scene::Rgb;
use crate::scene::texture::Encoding;

pub(super) const NAME: &str = "KHR_materials_unlit";

/// Whether `material` is unlit.
pub(super) fn is_unlit(material: &gltf::Material) -> bool {
    material.extension_value(NAME).is_some()
}

/// Makes `out` (a `gltf-pbr` material with the core's factors) the unlit
/// material of `material` (module documentation).
pub(super) fn convert(
    material: &gltf::Material,
    images: &mut ImageSource,
    out: &mut Material,
) -> Result<(), String> {
    out.emission = out.base_color;
    out.base_color = Rgb::ZERO;
    out.k_a = Rgb::ZERO;
    out.k_d = Rgb::ZERO;
    out.metallic = 0.0;
    out.layers.specular = 0.0;
    if let Some(info) = material.pbr_metallic_roughness().base_color_texture() {
        let mut keys = vec!["emission"];
        if !matches!(out.alpha_mode, AlphaMode::Opaque) {
            keys.push("base_color");
        }
        for key in keys {
            let t = images.texture(&info, key, Encoding::Srgb, 0);
            out.textures
                .push(t.map_err(|e| format!("baseColorTexture: {e}"))?);
        }
    }
    Ok(())
}
