//! Step 3 of loading, the overrides: `--set KEY=VALUE` applied to the scene
//! table by dotted path, one at a time, so an error names the override
//! that caused it.

use crate::{Error, Result};

/// Most parts a `--set` key may have; the deepest real key has three
/// (`materials.ball.roughness`). Without a cap a key of 60 000 parts builds
/// tables so deep that dropping them overflows the stack.
const MAX_KEY_DEPTH: usize = 16;

/// Applies one `KEY=VALUE` override. Keys are dotted paths; array elements
/// are addressed by index (`lights.0.intensity`). VALUE is a TOML value
/// (`0.2`, `[1, 1, 1]`, `"ggx"`, `true`); anything that is not valid TOML
/// is taken as a string, so `--set shading.mode=flat` works unquoted.
pub fn apply_override(table: &mut toml::Table, kv: &str) -> Result<()> {
    let arg = || format!("--set {kv}");
    let (key, raw) = kv
        .split_once('=')
        .ok_or_else(|| Error::argument(arg(), "expected KEY=VALUE, e.g. materials.ball.k_e=80"))?;
    let key = key.trim();
    let raw = raw.trim();
    let parts = key_parts(key);
    if parts.is_empty() || parts.iter().any(String::is_empty) {
        return Err(Error::argument(
            arg(),
            "the key is empty or has an empty part",
        ));
    }
    let value = value_of(raw);
    let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
    if parts.len() > MAX_KEY_DEPTH {
        return Err(Error::argument(
            arg(),
            format!(
                "the key has {} parts; scene keys have at most {MAX_KEY_DEPTH}",
                parts.len()
            ),
        ));
    }
    must_exist(table, &parts).map_err(|p| Error::argument(arg(), p))?;
    let (last, path) = parts.split_last().expect("non-empty key");
    let mut node = TableOrArray::Table(table);
    for (depth, part) in path.iter().enumerate() {
        let prefix = parts[..=depth].join(".");
        node = node
            .child(part)
            .map_err(|p| Error::argument(arg(), format!("`{prefix}`: {p}")))?;
    }
    node.set(last, value)
        .map_err(|p| Error::argument(arg(), format!("`{key}`: {p}")))
}

/// Refuses a path into something the scene must already have, with the
/// reason in the user's words: a misspelt material
/// (`materials.bal.k_e` said "missing field `model`") and an array entry
/// of an array the scene lacks (`lights.0.shadows` on a bare glTF said
/// "invalid type: map, expected a sequence").
fn must_exist(table: &toml::Table, parts: &[&str]) -> std::result::Result<(), String> {
    if let ["materials", name, key, ..] = parts {
        let names: Vec<&str> = match table.get("materials") {
            Some(toml::Value::Table(m)) => m.keys().map(String::as_str).collect(),
            _ => Vec::new(),
        };
        if !names.contains(name) && *key != "model" {
            let listed = if names.is_empty() {
                "it has none".to_string()
            } else {
                format!("it has {}", names.join(", "))
            };
            let hint = super::diagnostics::nearest_name(name, names.iter().copied())
                .map(|n| format!("; did you mean `{n}`?"))
                .unwrap_or_else(|| ".".into());
            return Err(format!(
                "the scene has no material `{name}` ({listed}){hint} A new material starts with its model (`--set materials.{name}.model=lambert`); in a scene with glTF objects, `materials.NAME.KEY` also edits a glTF file's own material of that name"
            ));
        }
    }
    if let [array, index, ..] = parts
        && index.parse::<usize>().is_ok()
        && !table.contains_key(*array)
    {
        let extra = if *array == "lights" {
            "; a glTF's own lights (KHR_lights_punctual) are not `lights` entries: `--set shadows.imported_lights=true` makes them cast shadows"
        } else {
            ""
        };
        return Err(format!(
            "the scene has no `{array}`, so no entry {index}: entries of `[[{array}]]` are added in a scene file{extra}"
        ));
    }
    Ok(())
}

/// The parts of a dotted `--set` key, read as TOML reads a dotted key in a
/// file: a part may be quoted, so a name with dots or spaces is addressed
/// as in the file (`gltf_materials."Material.005".emission`,
/// `materials."material 0".k_d`). A key that is not a TOML key (a bare
/// part with a space, say) is split at its dots as written.
pub fn key_parts(key: &str) -> Vec<String> {
    let quoted = key.contains('"') || key.contains('\'');
    let parsed = quoted
        .then(|| format!("{key} = 0").parse::<toml::Table>().ok())
        .flatten();
    let Some(mut table) = parsed else {
        return key.split('.').map(str::to_string).collect();
    };
    let mut parts = Vec::new();
    loop {
        let Some((part, value)) = table.into_iter().next() else {
            return parts;
        };
        parts.push(part);
        match value {
            toml::Value::Table(inner) => table = inner,
            _ => return parts,
        }
    }
}

/// `parts` as one dotted key that [`key_parts`] reads back: a part that
/// is not a bare TOML key (letters, digits, `_`, `-`) is quoted.
pub fn dotted_key<S: AsRef<str>>(parts: &[S]) -> String {
    parts
        .iter()
        .map(|p| {
            let p = p.as_ref();
            let bare = !p.is_empty()
                && p.bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
            if bare {
                p.to_string()
            } else {
                toml::Value::String(p.to_string()).to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// VALUE of a `--set` (and of the viewer's `--edit`): a TOML value, or
/// the text as a string when it is not valid TOML (`flat`, `ggx`).
pub fn value_of(raw: &str) -> toml::Value {
    format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()))
}

/// A step in a dotted path: tables by key (created when missing), arrays by
/// index (which must exist).
enum TableOrArray<'a> {
    Table(&'a mut toml::Table),
    Array(&'a mut Vec<toml::Value>),
}

impl<'a> TableOrArray<'a> {
    fn child(self, part: &str) -> std::result::Result<TableOrArray<'a>, String> {
        let slot = match self {
            TableOrArray::Table(t) => t
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new())),
            TableOrArray::Array(a) => {
                let len = a.len();
                let i: usize = part
                    .parse()
                    .map_err(|_| format!("`{part}` is not an index into an array of {len}"))?;
                a.get_mut(i)
                    .ok_or_else(|| format!("index {i} is out of range (the array has {len})"))?
            }
        };
        match slot {
            toml::Value::Table(t) => Ok(TableOrArray::Table(t)),
            toml::Value::Array(a) => Ok(TableOrArray::Array(a)),
            other => Err(format!("is a {}, not a table", other.type_str())),
        }
    }

    fn set(self, part: &str, value: toml::Value) -> std::result::Result<(), String> {
        match self {
            TableOrArray::Table(t) => {
                t.insert(part.to_string(), value);
                Ok(())
            }
            TableOrArray::Array(a) => {
                let len = a.len();
                let i: usize = part
                    .parse()
                    .map_err(|_| format!("`{part}` is not an index into an array of {len}"))?;
                *a.get_mut(i)
                    .ok_or_else(|| format!("index {i} is out of range (the array has {len})"))? =
                    value;
                Ok(())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_parts_keep_their_dots() {
        assert_eq!(
            key_parts("gltf_materials.\"Material.005\".emission"),
            ["gltf_materials", "Material.005", "emission"]
        );
        assert_eq!(
            key_parts("materials.'material 0'.k_d"),
            ["materials", "material 0", "k_d"]
        );
        assert_eq!(
            key_parts("lights.0.intensity"),
            ["lights", "0", "intensity"]
        );
        assert_eq!(key_parts("a..b"), ["a", "", "b"]);
        let parts = ["gltf_materials", "Material.005", "k_d"];
        assert_eq!(key_parts(&dotted_key(&parts)), parts);
        assert_eq!(dotted_key(&parts), "gltf_materials.\"Material.005\".k_d");
    }
}
