//! The glTF material extensions of light through surfaces (the contract's
//! "Light through surfaces"): `KHR_materials_transmission`, `_volume`,
//! `_dispersion` and `_diffuse_transmission`, read into
//! [`Material::layers`] with every texture each extension names, as
//! [`super::layers`] reads the reflection layers (same checks: each value
//! in its schema's range, an error naming the extension and the property).
//!
//! | extension texture | key | read |
//! | --- | --- | --- |
//! | `transmissionTexture` | `transmission` | R, linear |
//! | `thicknessTexture` | `thickness` | G, linear |
//! | `diffuseTransmissionTexture` | `diffuse_transmission` | A, linear |
//! | `diffuseTransmissionColorTexture` | `diffuse_transmission_color` | RGB, sRGB |
//!
//! `attenuationDistance` absent is `∞` (JSON has no infinity; the
//! extension's default is "+Infinity").

use super::images::{ImageSource, RawTextureInfo};
use super::layers::{A, G, R, colour, extension, ones, param_texture, unit, within};
use crate::material::Material;
use crate::scene::texture::Encoding;
use serde::Deserialize;

/// `KHR_materials_transmission`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Transmission {
    #[serde(default)]
    transmission_factor: f64,
    transmission_texture: Option<RawTextureInfo>,
}

/// `KHR_materials_volume`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Volume {
    #[serde(default)]
    thickness_factor: f64,
    thickness_texture: Option<RawTextureInfo>,
    attenuation_distance: Option<f64>,
    #[serde(default = "ones")]
    attenuation_color: [f64; 3],
}

/// `KHR_materials_dispersion`.
#[derive(Deserialize)]
struct Dispersion {
    #[serde(default)]
    dispersion: f64,
}

/// `KHR_materials_diffuse_transmission`.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct DiffuseTransmission {
    #[serde(default)]
    diffuse_transmission_factor: f64,
    diffuse_transmission_texture: Option<RawTextureInfo>,
    #[serde(default = "ones")]
    diffuse_transmission_color_factor: [f64; 3],
    diffuse_transmission_color_texture: Option<RawTextureInfo>,
}

/// Reads the transmission extensions of glTF material `material` into
/// `out.layers` and their textures into `out.textures`.
pub(super) fn read(
    material: &gltf::Material,
    document: &gltf::Document,
    images: &mut ImageSource,
    out: &mut Material,
) -> Result<(), String> {
    let mut texture = |info: &RawTextureInfo,
                       what: &str,
                       key: &'static str,
                       encoding: Encoding,
                       channel: usize,
                       out: &mut Material| {
        param_texture(images, document, info, (what, key), encoding, channel, out)
    };

    if let Some(e) = extension::<Transmission>(material, "KHR_materials_transmission")? {
        const NAME: &str = "KHR_materials_transmission";
        out.layers.transmission =
            unit(&format!("{NAME}.transmissionFactor"), e.transmission_factor)?;
        if let Some(info) = &e.transmission_texture {
            let what = format!("{NAME}.transmissionTexture");
            texture(info, &what, "transmission", Encoding::Linear, R, out)?;
        }
    }

    if let Some(e) = extension::<Volume>(material, "KHR_materials_volume")? {
        const NAME: &str = "KHR_materials_volume";
        out.layers.thickness = within(
            &format!("{NAME}.thicknessFactor"),
            e.thickness_factor,
            0.0,
            f64::INFINITY,
        )?;
        if let Some(d) = e.attenuation_distance {
            if d.is_nan() || d <= 0.0 {
                return Err(format!(
                    "{NAME}.attenuationDistance is {d}, not > 0 (leave it out for no attenuation)"
                ));
            }
            out.layers.attenuation_distance = d;
        }
        out.layers.attenuation_color = colour(
            &format!("{NAME}.attenuationColor"),
            e.attenuation_color,
            1.0,
        )?;
        if let Some(info) = &e.thickness_texture {
            let what = format!("{NAME}.thicknessTexture");
            texture(info, &what, "thickness", Encoding::Linear, G, out)?;
        }
    }

    if let Some(e) = extension::<Dispersion>(material, "KHR_materials_dispersion")? {
        out.layers.dispersion = within(
            "KHR_materials_dispersion.dispersion",
            e.dispersion,
            0.0,
            f64::INFINITY,
        )?;
    }

    if let Some(e) =
        extension::<DiffuseTransmission>(material, "KHR_materials_diffuse_transmission")?
    {
        const NAME: &str = "KHR_materials_diffuse_transmission";
        out.layers.diffuse_transmission = unit(
            &format!("{NAME}.diffuseTransmissionFactor"),
            e.diffuse_transmission_factor,
        )?;
        out.layers.diffuse_transmission_color = colour(
            &format!("{NAME}.diffuseTransmissionColorFactor"),
            e.diffuse_transmission_color_factor,
            1.0,
        )?;
        if let Some(info) = &e.diffuse_transmission_texture {
            let what = format!("{NAME}.diffuseTransmissionTexture");
            texture(
                info,
                &what,
                "diffuse_transmission",
                Encoding::Linear,
                A,
                out,
            )?;
        }
        if let Some(info) = &e.diffuse_transmission_color_texture {
            let what = format!("{NAME}.diffuseTransmissionColorTexture");
            let key = "diffuse_transmission_color";
            texture(info, &what, key, Encoding::Srgb, R, out)?;
        }
    }
    Ok(())
}
