//! `[materials.NAME] PARAM_texture = "image.png"`: a texture on any
//! colour or scalar parameter (the contract's "Textures"), relative to the
//! scene file. The texture multiplies the parameter's constant; a colour
//! parameter (one the viewer edits with a colour picker: `k_a`, `k_d`,
//! `k_s`, ...) reads an sRGB-encoded image's RGB decoded to linear, any
//! other parameter (`roughness`, `k_e`, `eta`, ...) a linear image, a
//! scalar one its first channel. `normal_texture` is a tangent-space
//! normal map (glTF's encoding, scale 1; the contract) and
//! `occlusion_texture` glTF's occlusion on the ambient and environment
//! terms (R, strength 1), `clearcoat_normal_texture` the coat's own
//! normal map (as `normal_texture`) and `anisotropy_texture`
//! `KHR_materials_anisotropy`'s direction (RG) and strength (B), all
//! linear. Scene-file textures read UV set 0 with
//! glTF's default sampler (repeat, bilinear, trilinear mipmaps).

use crate::material::param::Widget;
use crate::material::texture::{MaterialTexture, Sampler, TextureTarget, UvTransform};
use crate::material::{Material, MaterialEntry, entry::TEXTURE_SUFFIX, table};
use crate::scene::texture::{Encoding, store::ImageStore};
use std::path::Path;

/// Loads the textures `entry` names into `images` and attaches them to
/// `m` (the material made from `entry`, named `name`); the message of a
/// failure names the key and the image file.
pub fn attach(
    m: &mut Material,
    name: &str,
    entry: &MaterialEntry,
    base_dir: &Path,
    images: &mut ImageStore,
) -> Result<(), String> {
    for (key, file) in &entry.textures {
        let at = format!("materials.{name}.{key}");
        let map = match key.as_str() {
            "normal_texture" => Some(TextureTarget::Normal { scale: 1.0 }),
            "occlusion_texture" => Some(TextureTarget::Occlusion { strength: 1.0 }),
            "clearcoat_normal_texture" => Some(TextureTarget::ClearcoatNormal { scale: 1.0 }),
            "anisotropy_texture" => Some(TextureTarget::Anisotropy),
            _ => None,
        };
        if let Some(target) = map {
            let path = base_dir.join(file);
            let image = images
                .load_file(&path, Encoding::Linear)
                .map_err(|e| format!("{at}: the image {}: {e}", path.display()))?;
            m.textures.push(MaterialTexture {
                target,
                image,
                channel: 0,
                tex_coord: 0,
                transform: UvTransform::default(),
                sampler: Sampler::default(),
            });
            continue;
        }
        let param_key = key.strip_suffix(TEXTURE_SUFFIX).unwrap_or(key);
        let param = table::param_for(m.model, param_key).ok_or_else(|| {
            format!(
                "{at}: the model {} has no parameter `{param_key}` to texture",
                m.model.name()
            )
        })?;
        let encoding = match param.widget {
            Widget::ColorPicker => Encoding::Srgb,
            _ => Encoding::Linear,
        };
        let path = base_dir.join(file);
        let image = images
            .load_file(&path, encoding)
            .map_err(|e| format!("{at}: the image {}: {e}", path.display()))?;
        m.textures.push(MaterialTexture {
            target: TextureTarget::Param(param.key),
            image,
            channel: 0,
            tex_coord: 0,
            transform: UvTransform::default(),
            sampler: Sampler::default(),
        });
        crate::material::texture_fields::gpu_field_mask(m, param_key)
            .map_err(|e| format!("materials.{name}.{e}"))?;
    }
    Ok(())
}
