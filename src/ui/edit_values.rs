//! The value of one `KEY=VALUE` edit (`--edit`, the panel, `compare.N`),
//! read as `--set` reads it, and a material with one key so edited,
//! checked as the scene file checks it.

use crate::material::Material;

/// `m` with `field = value` (TOML), checked as the scene file checks it:
/// the value is read as the table of models types the key and set through
/// the parameter's binding (no round trip through the scene file's text).
pub fn edit_material(
    m: &Material,
    field: &str,
    value: &str,
) -> std::result::Result<Material, String> {
    let value: toml::Value =
        toml_value(value).map_err(|e| format!("materials.{}.{field}: {e}", m.name))?;
    crate::material::entry::with_key(m, field, value)
}

/// VALUE of an `--edit` read as `--set` reads it (unquoted words are
/// strings: `shading.mode=flat`), then as a `T`.
pub fn toml_value<T: serde::de::DeserializeOwned>(text: &str) -> std::result::Result<T, String> {
    crate::scene::scene_file::overrides::value_of(text.trim())
        .try_into()
        .map_err(|e: toml::de::Error| format!("`{text}`: {}", e.message()))
}
