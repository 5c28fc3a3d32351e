//! A `--set materials.NAME.model=M` that switches a material of the source
//! to another model: the source's keys the new model does not read are
//! dropped, as the viewer's model switch leaves them behind (before,
//! `--set materials.ball.model=measured` on the built-in scene failed with
//! "k_d does not apply … remove it", a key the user never wrote and could
//! not remove, and `model=cook-torrance` warned about the built-in `k_e`).
//! Keys given by a `--set` are the user's and stay (with the usual
//! warning or error when the model does not read them); keys of a scene
//! file the user wrote are dropped with a warning that names them.

use super::overrides::key_parts;
use crate::material::entry::{self, MAP_TEXTURE_KEYS, MaterialEntry, TEXTURE_SUFFIX};
use crate::material::{ReflectanceModel, table};
use std::collections::BTreeSet;

/// What the overrides wrote so far: `(material, key)` pairs.
#[derive(Default)]
pub struct Written(BTreeSet<(String, String)>);

impl Written {
    /// Records the material key `kv` sets, if it sets one.
    pub fn record(&mut self, kv: &str) {
        if let Some((material, key)) = material_key(kv) {
            self.0.insert((material, key));
        }
    }
}

/// `(NAME, KEY)` of a `materials.NAME.KEY=VALUE` override.
fn material_key(kv: &str) -> Option<(String, String)> {
    let (key, _) = kv.split_once('=')?;
    match key_parts(key.trim()).as_slice() {
        [materials, name, key] if materials == "materials" => Some((name.clone(), key.clone())),
        _ => None,
    }
}

/// After override `kv` was applied to `table`: when it set the model of a
/// material, removes the material's keys the model does not read that no
/// override wrote. Returns the removed keys (empty when none).
pub fn drop_unread_keys(table: &mut toml::Table, kv: &str, written: &Written) -> Vec<String> {
    let Some((name, key)) = material_key(kv) else {
        return Vec::new();
    };
    if key != "model" {
        return Vec::new();
    }
    let Some(toml::Value::Table(material)) = table
        .get_mut("materials")
        .and_then(|m| m.as_table_mut())
        .and_then(|m| m.get_mut(&name))
    else {
        return Vec::new();
    };
    let unread: Vec<String> = unread_keys(material)
        .into_iter()
        .filter(|k| !written.0.contains(&(name.clone(), k.clone())))
        .collect();
    for k in &unread {
        material.remove(k);
    }
    unread
}

/// The keys of a `[materials.NAME]` table its model does not read: for
/// `measured`, all but `measured` and the common keys (`k_a`, `emission`,
/// their textures, the normal and occlusion maps); for the others, the
/// parameters of other models and `measured`.
fn unread_keys(material: &toml::Table) -> Vec<String> {
    let Some(Ok(model)) = material
        .get("model")
        .and_then(toml::Value::as_str)
        .map(str::parse::<ReflectanceModel>)
    else {
        return Vec::new();
    };
    if model == ReflectanceModel::Measured {
        let common = |k: &str| {
            let param = k.strip_suffix(TEXTURE_SUFFIX).unwrap_or(k);
            table::COMMON.iter().any(|p| p.key == param)
        };
        return material
            .keys()
            .filter(|k| {
                !(k.as_str() == "model"
                    || k.as_str() == "measured"
                    || common(k)
                    || MAP_TEXTURE_KEYS.contains(&k.as_str()))
            })
            .cloned()
            .collect();
    }
    let mut unread: Vec<String> = toml::Value::Table(material.clone())
        .try_into::<MaterialEntry>()
        .map(|e| {
            entry::keys_not_applying(&e)
                .into_iter()
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default();
    if material.contains_key("measured") {
        unread.push("measured".into());
    }
    unread
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball() -> toml::Table {
        "[materials.ball]\nmodel = \"blinn-phong\"\nk_a = [0.8, 0.1, 0.1]\nk_d = [0.8, 0.1, 0.1]\nk_s = 0.5\nk_e = 60.0\n"
            .parse()
            .unwrap()
    }

    fn keys(table: &toml::Table) -> Vec<&str> {
        table["materials"]["ball"]
            .as_table()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect()
    }

    #[test]
    fn a_switch_drops_only_the_keys_no_override_wrote() {
        let mut table = ball();
        let mut written = Written::default();
        let kv = "materials.ball.model=measured";
        table["materials"]["ball"]["model"] = "measured".into();
        written.record(kv);
        let mut dropped = drop_unread_keys(&mut table, kv, &written);
        dropped.sort();
        assert_eq!(dropped, ["k_d", "k_e", "k_s"]);
        assert_eq!(keys(&table), ["k_a", "model"]);

        // A key the user set is kept (and refused or warned about later).
        let mut table = ball();
        let mut written = Written::default();
        written.record("materials.ball.k_e=20");
        let kv = "materials.ball.model=lambert";
        table["materials"]["ball"]["model"] = "lambert".into();
        written.record(kv);
        assert_eq!(drop_unread_keys(&mut table, kv, &written), ["k_s"]);
        assert_eq!(keys(&table), ["k_a", "k_d", "k_e", "model"]);

        // Other overrides drop nothing.
        let mut table = ball();
        assert!(drop_unread_keys(&mut table, "materials.ball.k_e=3", &written).is_empty());
    }
}
