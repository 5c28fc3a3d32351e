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
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(Error::argument(
            arg(),
            "the key is empty or has an empty part",
        ));
    }
    let value = value_of(raw);

    let parts: Vec<&str> = key.split('.').collect();
    if parts.len() > MAX_KEY_DEPTH {
        return Err(Error::argument(
            arg(),
            format!(
                "the key has {} parts; scene keys have at most {MAX_KEY_DEPTH}",
                parts.len()
            ),
        ));
    }
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
