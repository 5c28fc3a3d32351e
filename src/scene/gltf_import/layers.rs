//! The glTF material extensions that layer the `gltf-pbr` BRDF (the
//! contract's "Layered glTF materials"): `KHR_materials_ior`, `_specular`,
//! `_clearcoat`, `_sheen`, `_iridescence` and `_anisotropy`, read into
//! [`Material::layers`], with every texture each extension names as a
//! texture on the layer's key (its `texCoord`, sampler and
//! `KHR_texture_transform`; the channel and colour space its specification
//! gives).
//!
//! All six are read from the raw extension objects with one set of
//! checks: the `gltf` crate parses only two of them (`ior`, `specular`,
//! behind cargo features) and validates none of the texture indices inside
//! the others. Each value must lie in its schema's range; one outside is an
//! error naming the material, the extension and the property.
//!
//! | extension texture | key | read |
//! | --- | --- | --- |
//! | `specularTexture` | `specular` | A, linear |
//! | `specularColorTexture` | `specular_color` | RGB, sRGB |
//! | `clearcoatTexture` | `clearcoat` | R, linear |
//! | `clearcoatRoughnessTexture` | `clearcoat_roughness` | G, linear |
//! | `sheenColorTexture` | `sheen_color` | RGB, sRGB |
//! | `sheenRoughnessTexture` | `sheen_roughness` | A, linear |
//! | `iridescenceTexture` | `iridescence` | R, linear |
//! | `iridescenceThicknessTexture` | `iridescence_thickness` | G, linear, derived (below) |
//!
//! `clearcoatNormalTexture` (linear, with its `scale`) is the coat's own
//! normal map ([`TextureTarget::ClearcoatNormal`]) and `anisotropyTexture`
//! (linear: RG the direction, B the strength) the anisotropy map
//! ([`TextureTarget::Anisotropy`]), each with its `texCoord`, sampler and
//! `KHR_texture_transform` too.
//!
//! **The film thickness.** `KHR_materials_iridescence` gives the thickness
//! as `mix(minimum, maximum, G)`, not as a factor times the texel, and the
//! contract's key `iridescence_thickness` is the thickness itself, which a
//! texture multiplies. So the key is set to `s = max(minimum, maximum)`
//! (the maximum, unless a file inverts the two) and the texture reads an
//! image derived from the file's, texel by texel in linear f32 before the
//! mip chain is built: `t = mix(minimum, maximum, G) / s` in R, G and B,
//! so that `s·t` is the specification's thickness. The map is affine in
//! `G`, so filtering the derived image (bilinear, mip levels) gives the
//! derived value of the filtered `G`, as filtering the file's image and
//! mixing would. `t` lies in `[0, 1]` and is stored once as a half float
//! (relative rounding ≤ 2⁻¹¹), so the thickness is within `s·2⁻¹¹`
//! (0.2 nm at 400 nm) of the exact mix, below the file's own 8-bit step
//! `(maximum − minimum)/255` (1.2 nm for 100..400 nm).

use super::images::{Derived, ImageSource, RawTextureInfo};
use crate::material::Material;
use crate::material::texture::TextureTarget;
use crate::scene::Rgb;
use crate::scene::texture::Encoding;
use serde::Deserialize;
use serde::de::DeserializeOwned;

/// `KHR_materials_ior`.
#[derive(Deserialize)]
struct Ior {
    #[serde(default = "ior_default")]
    ior: f64,
}

/// `KHR_materials_specular`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Specular {
    #[serde(default = "one")]
    specular_factor: f64,
    specular_texture: Option<RawTextureInfo>,
    #[serde(default = "ones")]
    specular_color_factor: [f64; 3],
    specular_color_texture: Option<RawTextureInfo>,
}

/// `KHR_materials_clearcoat`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Clearcoat {
    #[serde(default)]
    clearcoat_factor: f64,
    clearcoat_texture: Option<RawTextureInfo>,
    #[serde(default)]
    clearcoat_roughness_factor: f64,
    clearcoat_roughness_texture: Option<RawTextureInfo>,
    clearcoat_normal_texture: Option<RawTextureInfo>,
}

/// `KHR_materials_sheen`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Sheen {
    #[serde(default)]
    sheen_color_factor: [f64; 3],
    sheen_color_texture: Option<RawTextureInfo>,
    #[serde(default)]
    sheen_roughness_factor: f64,
    sheen_roughness_texture: Option<RawTextureInfo>,
}

/// `KHR_materials_iridescence`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Iridescence {
    #[serde(default)]
    iridescence_factor: f64,
    iridescence_texture: Option<RawTextureInfo>,
    #[serde(default = "film_ior_default")]
    iridescence_ior: f64,
    #[serde(default = "thickness_minimum_default")]
    iridescence_thickness_minimum: f64,
    #[serde(default = "thickness_maximum_default")]
    iridescence_thickness_maximum: f64,
    iridescence_thickness_texture: Option<RawTextureInfo>,
}

/// `KHR_materials_anisotropy`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Anisotropy {
    #[serde(default)]
    anisotropy_strength: f64,
    #[serde(default)]
    anisotropy_rotation: f64,
    anisotropy_texture: Option<RawTextureInfo>,
}

fn one() -> f64 {
    1.0
}
pub(super) fn ones() -> [f64; 3] {
    [1.0; 3]
}
fn ior_default() -> f64 {
    1.5
}
fn film_ior_default() -> f64 {
    1.3
}
fn thickness_minimum_default() -> f64 {
    100.0
}
fn thickness_maximum_default() -> f64 {
    400.0
}

/// Extension `name` of `material` parsed as `T`, if the material has it.
pub(super) fn extension<T: DeserializeOwned>(
    material: &gltf::Material,
    name: &str,
) -> Result<Option<T>, String> {
    material
        .extension_value(name)
        .map(|v| T::deserialize(v).map_err(|e| format!("{name}: {e}")))
        .transpose()
}

/// `value` of `what` if it lies in `[min, max]`, else the error.
pub(super) fn within(what: &str, value: f64, min: f64, max: f64) -> Result<f64, String> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        let range = if max == f64::INFINITY {
            format!("≥ {min}")
        } else {
            format!("in [{min}, {max}]")
        };
        Err(format!("{what} is {value}, not {range}"))
    }
}

pub(super) fn unit(what: &str, value: f64) -> Result<f64, String> {
    within(what, value, 0.0, 1.0)
}

pub(super) fn colour(what: &str, c: [f64; 3], max: f64) -> Result<Rgb, String> {
    for v in c {
        within(what, v, 0.0, max)?;
    }
    Ok(Rgb::from(c))
}

/// Reads the layer extensions of glTF material `material` into
/// `out.layers` and their textures into `out.textures`.
/// Channels an extension's texture reads its parameter from.
pub(super) const R: usize = 0;
pub(super) const G: usize = 1;
pub(super) const A: usize = 3;

/// Adds the texture `info` (the extension's `what`) to `out` as the map of
/// scene-file key `key`, read from `channel` in `encoding`.
pub(super) fn param_texture(
    images: &mut ImageSource,
    document: &gltf::Document,
    info: &RawTextureInfo,
    (what, key): (&str, &'static str),
    encoding: Encoding,
    channel: usize,
    out: &mut Material,
) -> Result<(), String> {
    let mut t = images
        .raw_texture(document, info, TextureTarget::Param(key), encoding, None)
        .map_err(|e| format!("{what}: {e}"))?;
    t.channel = channel;
    out.textures.push(t);
    Ok(())
}

pub(super) fn read(
    material: &gltf::Material,
    document: &gltf::Document,
    images: &mut ImageSource,
    out: &mut Material,
) -> Result<(), String> {
    let texture = |images: &mut ImageSource,
                   info: &RawTextureInfo,
                   what: &str,
                   key: &'static str,
                   encoding: Encoding,
                   channel: usize,
                   out: &mut Material| {
        param_texture(images, document, info, (what, key), encoding, channel, out)
    };

    if let Some(e) = extension::<Ior>(material, "KHR_materials_ior")? {
        // Schema: "minimum": 1.0, and 0 for the specular-glossiness mode.
        if !(e.ior == 0.0 || e.ior >= 1.0) {
            return Err(format!(
                "KHR_materials_ior.ior is {}, neither 0 nor ≥ 1",
                e.ior
            ));
        }
        out.layers.ior = e.ior;
    }

    if let Some(e) = extension::<Specular>(material, "KHR_materials_specular")? {
        const NAME: &str = "KHR_materials_specular";
        out.layers.specular = unit(&format!("{NAME}.specularFactor"), e.specular_factor)?;
        out.layers.specular_color = colour(
            &format!("{NAME}.specularColorFactor"),
            e.specular_color_factor,
            f64::INFINITY,
        )?;
        if let Some(info) = &e.specular_texture {
            let what = format!("{NAME}.specularTexture");
            texture(images, info, &what, "specular", Encoding::Linear, A, out)?;
        }
        if let Some(info) = &e.specular_color_texture {
            let what = format!("{NAME}.specularColorTexture");
            texture(
                images,
                info,
                &what,
                "specular_color",
                Encoding::Srgb,
                R,
                out,
            )?;
        }
    }

    if let Some(e) = extension::<Clearcoat>(material, "KHR_materials_clearcoat")? {
        const NAME: &str = "KHR_materials_clearcoat";
        out.layers.clearcoat = unit(&format!("{NAME}.clearcoatFactor"), e.clearcoat_factor)?;
        out.layers.clearcoat_roughness = unit(
            &format!("{NAME}.clearcoatRoughnessFactor"),
            e.clearcoat_roughness_factor,
        )?;
        if let Some(info) = &e.clearcoat_texture {
            let what = format!("{NAME}.clearcoatTexture");
            texture(images, info, &what, "clearcoat", Encoding::Linear, R, out)?;
        }
        if let Some(info) = &e.clearcoat_roughness_texture {
            let what = format!("{NAME}.clearcoatRoughnessTexture");
            texture(
                images,
                info,
                &what,
                "clearcoat_roughness",
                Encoding::Linear,
                G,
                out,
            )?;
        }
        if let Some(info) = &e.clearcoat_normal_texture {
            let what = format!("{NAME}.clearcoatNormalTexture");
            if !info.scale.is_finite() {
                return Err(format!("{what}: scale {} is not finite", info.scale));
            }
            let target = TextureTarget::ClearcoatNormal { scale: info.scale };
            let t = images
                .raw_texture(document, info, target, Encoding::Linear, None)
                .map_err(|e| format!("{what}: {e}"))?;
            out.textures.push(t);
        }
    }

    if let Some(e) = extension::<Sheen>(material, "KHR_materials_sheen")? {
        const NAME: &str = "KHR_materials_sheen";
        out.layers.sheen_color = colour(
            &format!("{NAME}.sheenColorFactor"),
            e.sheen_color_factor,
            1.0,
        )?;
        out.layers.sheen_roughness = unit(
            &format!("{NAME}.sheenRoughnessFactor"),
            e.sheen_roughness_factor,
        )?;
        if let Some(info) = &e.sheen_color_texture {
            let what = format!("{NAME}.sheenColorTexture");
            texture(images, info, &what, "sheen_color", Encoding::Srgb, R, out)?;
        }
        if let Some(info) = &e.sheen_roughness_texture {
            let what = format!("{NAME}.sheenRoughnessTexture");
            texture(
                images,
                info,
                &what,
                "sheen_roughness",
                Encoding::Linear,
                A,
                out,
            )?;
        }
    }

    if let Some(e) = extension::<Iridescence>(material, "KHR_materials_iridescence")? {
        const NAME: &str = "KHR_materials_iridescence";
        out.layers.iridescence = unit(&format!("{NAME}.iridescenceFactor"), e.iridescence_factor)?;
        out.layers.iridescence_ior = within(
            &format!("{NAME}.iridescenceIor"),
            e.iridescence_ior,
            1.0,
            f64::INFINITY,
        )?;
        let minimum = within(
            &format!("{NAME}.iridescenceThicknessMinimum"),
            e.iridescence_thickness_minimum,
            0.0,
            f64::INFINITY,
        )?;
        let maximum = within(
            &format!("{NAME}.iridescenceThicknessMaximum"),
            e.iridescence_thickness_maximum,
            0.0,
            f64::INFINITY,
        )?;
        if let Some(info) = &e.iridescence_texture {
            let what = format!("{NAME}.iridescenceTexture");
            texture(images, info, &what, "iridescence", Encoding::Linear, R, out)?;
        }
        out.layers.iridescence_thickness = maximum;
        if let Some(info) = &e.iridescence_thickness_texture {
            let (key, map) = thickness_map(minimum, maximum);
            out.layers.iridescence_thickness = key;
            if key > 0.0 {
                let what = format!("{NAME}.iridescenceThicknessTexture");
                let derived = Derived {
                    label: format!("film thickness mix({minimum}, {maximum}, G) / {key}"),
                    map: &map,
                };
                let t = images
                    .raw_texture(
                        document,
                        info,
                        TextureTarget::Param("iridescence_thickness"),
                        Encoding::Linear,
                        Some(derived),
                    )
                    .map_err(|e| format!("{what}: {e}"))?;
                out.textures.push(t);
            }
        }
    }

    if let Some(e) = extension::<Anisotropy>(material, "KHR_materials_anisotropy")? {
        const NAME: &str = "KHR_materials_anisotropy";
        out.layers.anisotropy_strength =
            unit(&format!("{NAME}.anisotropyStrength"), e.anisotropy_strength)?;
        out.layers.anisotropy_rotation = e.anisotropy_rotation;
        if let Some(info) = &e.anisotropy_texture {
            let what = format!("{NAME}.anisotropyTexture");
            let t = images
                .raw_texture(
                    document,
                    info,
                    TextureTarget::Anisotropy,
                    Encoding::Linear,
                    None,
                )
                .map_err(|e| format!("{what}: {e}"))?;
            out.textures.push(t);
        }
    }
    Ok(())
}

/// The film thickness of `KHR_materials_iridescence` with a thickness
/// texture, `mix(minimum, maximum, G)`, as the key's value `s` and the map
/// of a texel to the derived image's `t = mix(minimum, maximum, G) / s`
/// (module documentation). `s = 0` (both 0): no film, no texture needed.
pub(super) fn thickness_map(minimum: f64, maximum: f64) -> (f64, impl Fn(&mut [f32; 4])) {
    let s = minimum.max(maximum);
    let map = move |texel: &mut [f32; 4]| {
        let g = f64::from(texel[1]);
        let t = if s > 0.0 {
            (minimum + (maximum - minimum) * g) / s
        } else {
            0.0
        };
        let t = t as f32;
        texel[0] = t;
        texel[1] = t;
        texel[2] = t;
    };
    (s, map)
}
