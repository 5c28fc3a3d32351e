//! The archived `KHR_materials_pbrSpecularGlossiness`, converted on load
//! into `gltf-pbr` as `KHR_materials_specular`'s README ("Conversions",
//! "Specular-glossiness materials") describes: `ior = 0` (the Fresnel
//! term's F0 is then the specular colour itself), `specular_color` =
//! `specularFactor`, `base_color` = `diffuseFactor` (its A the alpha),
//! `metallic = 0` and `roughness = 1 − glossinessFactor`. The BRDF this
//! gives is the extension's own: a diffuse `diffuse·(1 − max₃ F)/π` under
//! a GGX lobe with `F = F0 + (1 − F0)(1 − V·H)⁵`, `F0 = specular`,
//! `α = (1 − glossiness)²` (the contract's base with `ior = 0`).
//!
//! Textures: `diffuseTexture` (sRGB, A the alpha) as a base colour
//! texture; `specularGlossinessTexture`'s RGB (sRGB) on `specular_color`,
//! and its A, the glossiness `g_t`, as the roughness `1 − g·g_t`. That is
//! not a factor times the texel, so the roughness key is set to 1 and the
//! texture reads an image derived from the file's, texel by texel in
//! linear f32 before the mip chain (`1 − g·A` in R, G and B; affine in A,
//! so filtering commutes with it; stored once as a half float, within
//! 2⁻¹¹ of the exact value).

use super::images::{Derived, ImageSource, RawTextureInfo};
use crate::material::Material;
use crate::material::texture::TextureTarget;
use crate::scene::Rgb;
use crate::scene::texture::Encoding;
use serde::Deserialize;

pub(super) const NAME: &str = "KHR_materials_pbrSpecularGlossiness";

/// The extension's properties, with the schema's defaults.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct SpecularGlossiness {
    #[serde(default = "white")]
    diffuse_factor: [f64; 4],
    diffuse_texture: Option<RawTextureInfo>,
    #[serde(default = "ones")]
    specular_factor: [f64; 3],
    #[serde(default = "one")]
    glossiness_factor: f64,
    specular_glossiness_texture: Option<RawTextureInfo>,
}

fn white() -> [f64; 4] {
    [1.0; 4]
}
fn ones() -> [f64; 3] {
    [1.0; 3]
}
fn one() -> f64 {
    1.0
}

/// Converts `material`'s specular-glossiness properties onto `out` (a
/// `gltf-pbr` material with the core's factors, which this replaces);
/// `false` if the material does not have the extension.
pub(super) fn convert(
    material: &gltf::Material,
    document: &gltf::Document,
    images: &mut ImageSource,
    out: &mut Material,
) -> Result<bool, String> {
    let Some(e) = super::layers::extension::<SpecularGlossiness>(material, NAME)? else {
        return Ok(false);
    };
    let in_unit = |what: &str, v: f64| {
        if (0.0..=1.0).contains(&v) {
            Ok(v)
        } else {
            Err(format!("{NAME}.{what} has {v}, outside [0, 1]"))
        }
    };
    let [r, g, b, a] = e.diffuse_factor;
    for v in e.diffuse_factor {
        in_unit("diffuseFactor", v)?;
    }
    for v in e.specular_factor {
        in_unit("specularFactor", v)?;
    }
    let glossiness = in_unit("glossinessFactor", e.glossiness_factor)?;
    let diffuse = Rgb::new(r, g, b);
    out.base_color = diffuse;
    out.k_a = diffuse;
    out.k_d = diffuse;
    out.alpha = a;
    out.metallic = 0.0;
    out.roughness = (1.0 - glossiness).max(crate::material::ROUGHNESS_FLOOR);
    out.layers.ior = 0.0;
    out.layers.specular = 1.0;
    out.layers.specular_color = Rgb::from(e.specular_factor);
    if let Some(info) = &e.diffuse_texture {
        for key in ["base_color", "k_a"] {
            let t = images
                .raw_texture(
                    document,
                    info,
                    TextureTarget::Param(key),
                    Encoding::Srgb,
                    None,
                )
                .map_err(|e| format!("{NAME}.diffuseTexture: {e}"))?;
            out.textures.push(t);
        }
    }
    if let Some(info) = &e.specular_glossiness_texture {
        let what = format!("{NAME}.specularGlossinessTexture");
        let mut t = images
            .raw_texture(
                document,
                info,
                TextureTarget::Param("specular_color"),
                Encoding::Srgb,
                None,
            )
            .map_err(|e| format!("{what}: {e}"))?;
        t.channel = 0;
        out.textures.push(t);
        out.roughness = 1.0;
        let map = roughness_map(glossiness);
        let derived = Derived {
            label: format!("roughness 1 − {glossiness}·A"),
            map: &map,
        };
        let t = images
            .raw_texture(
                document,
                info,
                TextureTarget::Param("roughness"),
                Encoding::Linear,
                Some(derived),
            )
            .map_err(|e| format!("{what}: {e}"))?;
        out.textures.push(t);
    }
    Ok(true)
}

/// The derived roughness image of a specular-glossiness texture: `1 − g·A`
/// in R, G and B (module documentation).
pub(super) fn roughness_map(glossiness: f64) -> impl Fn(&mut [f32; 4]) {
    move |texel: &mut [f32; 4]| {
        let r = (1.0 - glossiness * f64::from(texel[3])) as f32;
        texel[0] = r;
        texel[1] = r;
        texel[2] = r;
    }
}
