//! Scene-file values written back as TOML, for the entries the viewer
//! edits and saves ([`super::schema::LightEntry::to_table`]).

use crate::base::ColorValue;

/// A scene-file value written back as TOML (`None`: not written).
pub trait TomlValue {
    fn to_toml(&self) -> Option<toml::Value>;
}

impl TomlValue for f64 {
    fn to_toml(&self) -> Option<toml::Value> {
        Some(toml::Value::Float(*self))
    }
}

impl TomlValue for u32 {
    fn to_toml(&self) -> Option<toml::Value> {
        Some(toml::Value::Integer(i64::from(*self)))
    }
}

impl TomlValue for bool {
    fn to_toml(&self) -> Option<toml::Value> {
        Some(toml::Value::Boolean(*self))
    }
}

impl TomlValue for String {
    fn to_toml(&self) -> Option<toml::Value> {
        Some(toml::Value::String(self.clone()))
    }
}

impl<const N: usize> TomlValue for [f64; N] {
    fn to_toml(&self) -> Option<toml::Value> {
        Some(toml::Value::Array(
            self.iter().map(|&v| toml::Value::Float(v)).collect(),
        ))
    }
}

impl TomlValue for ColorValue {
    fn to_toml(&self) -> Option<toml::Value> {
        match *self {
            ColorValue::Gray(v) => v.to_toml(),
            ColorValue::Rgb(v) => v.to_toml(),
        }
    }
}

impl<T: TomlValue> TomlValue for Option<T> {
    fn to_toml(&self) -> Option<toml::Value> {
        self.as_ref().and_then(T::to_toml)
    }
}
