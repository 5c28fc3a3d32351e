//! Colours: linear RGB triples and their text form.

use glam::DVec3;
use serde::Deserialize;

/// Linear RGB triple (radiance, reflectance, intensity, ...).
pub type Rgb = DVec3;

/// A colour given as `[r, g, b]` or as one number for all channels.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(untagged)]
pub enum ColorValue {
    Gray(f64),
    Rgb([f64; 3]),
}

impl ColorValue {
    pub fn rgb(self) -> Rgb {
        match self {
            ColorValue::Gray(v) => Rgb::splat(v),
            ColorValue::Rgb(v) => Rgb::from_array(v),
        }
    }
}

/// `v` as a scene file writes a colour: `[r, g, b]` (the inverse of
/// [`ColorValue::Rgb`]; Save scene and a material's text form use it).
pub fn rgb_to_toml(v: Rgb) -> toml::Value {
    toml::Value::Array(v.to_array().map(toml::Value::Float).to_vec())
}
