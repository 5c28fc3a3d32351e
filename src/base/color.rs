//! Colours: linear RGB triples and their text form.

use glam::DVec3;
use serde::Deserialize;

/// Linear RGB triple (radiance, reflectance, intensity, ...).
pub type Rgb = DVec3;

/// A colour given as `[r, g, b]` or as one number for all channels.
#[derive(Clone, Copy, Debug)]
pub enum ColorValue {
    Gray(f64),
    Rgb([f64; 3]),
}

/// By hand rather than `#[serde(untagged)]`, whose error for `[0.8, 0.1]`
/// was "data did not match any variant of untagged enum ColorValue":
/// this one says what a colour is and what was given.
impl<'de> Deserialize<'de> for ColorValue {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ColorVisitor)
    }
}

struct ColorVisitor;

impl<'de> serde::de::Visitor<'de> for ColorVisitor {
    type Value = ColorValue;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a colour: one number for all channels or [r, g, b] (three numbers)")
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<ColorValue, E> {
        Ok(ColorValue::Gray(v))
    }

    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<ColorValue, E> {
        Ok(ColorValue::Gray(v as f64))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<ColorValue, E> {
        Ok(ColorValue::Gray(v as f64))
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<ColorValue, A::Error> {
        let mut values = Vec::new();
        while let Some(v) = seq.next_element::<NumberValue>()? {
            values.push(v.0);
        }
        <[f64; 3]>::try_from(values.as_slice())
            .map(ColorValue::Rgb)
            .map_err(|_| {
                serde::de::Error::custom(format!(
                    "a colour is [r, g, b] (three numbers) or one number; this array has {} number{}",
                    values.len(),
                    if values.len() == 1 { "" } else { "s" }
                ))
            })
    }
}

/// One number of a colour array, integer or float.
struct NumberValue(f64);

impl<'de> Deserialize<'de> for NumberValue {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = NumberValue;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number (a colour's channel)")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<NumberValue, E> {
                Ok(NumberValue(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<NumberValue, E> {
                Ok(NumberValue(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<NumberValue, E> {
                Ok(NumberValue(v as f64))
            }
        }
        deserializer.deserialize_any(V)
    }
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
