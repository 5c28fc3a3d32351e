//! `[gltf_materials.NAME]`: edits of a glTF file's own materials, by the
//! material's name in the file (before, `--set materials.Suzanne.k_d`
//! failed, and the viewer's Save scene dropped such edits).
//!
//! A glTF material is not a `[materials]` entry: it has textures and
//! factors the scene file cannot express. An edit therefore names only the
//! keys it changes, and they are applied to the imported material after
//! the glTF is loaded, each as the viewer applies an edit
//! ([`crate::material::entry::with_key`]): `model` first, then `preset`,
//! then the rest, each validated. Textures stay.
//!
//! `--set materials.NAME.KEY=VALUE` where NAME is not a scene-file
//! material but the scene has glTF objects becomes
//! `gltf_materials.NAME.KEY=VALUE`; NAME must then be a material of one of
//! the glTF files (every imported material of that name is edited).

use super::diagnostics::nearest_name;
use crate::scene::Scene;
use crate::{Error, Result};
use std::collections::BTreeMap;

/// The scene-file section.
pub const SECTION: &str = "gltf_materials";

/// The override `kv` redirected into [`SECTION`] when it edits a material
/// the scene file does not define and the scene has glTF objects; `None`
/// to apply `kv` as it is.
pub fn redirect(table: &toml::Table, kv: &str) -> Option<String> {
    let (key, value) = kv.split_once('=')?;
    let parts = super::overrides::key_parts(key.trim());
    let [materials, name, field, ..] = parts.as_slice() else {
        return None;
    };
    let defined = matches!(table.get("materials"), Some(toml::Value::Table(m)) if m.contains_key(name.as_str()));
    (materials == "materials" && !defined && field != "model" && has_gltf_objects(table)).then(
        || {
            let mut redirected = parts.clone();
            redirected[0] = SECTION.to_string();
            format!("{}={value}", super::overrides::dotted_key(&redirected))
        },
    )
}

/// Whether any `[[objects]]` entry is a glTF file.
fn has_gltf_objects(table: &toml::Table) -> bool {
    matches!(table.get("objects"), Some(toml::Value::Array(objects))
        if objects.iter().any(|o| o.get("gltf").is_some()))
}

/// Applies every `[gltf_materials.NAME]` edit to the imported materials
/// of `scene` called NAME (the materials not in `file_materials`), and
/// returns a warning per key the material's model does not read.
/// `origin` names where an edit came from: the `--set` that made it, or
/// the scene file.
pub fn apply(
    scene: &mut Scene,
    file_materials: &[&str],
    edits: &BTreeMap<String, toml::Table>,
    origin: impl Fn(&str) -> String,
) -> Result<Vec<String>> {
    let mut warnings = Vec::new();
    for (name, keys) in edits {
        let bad = |problem: String| Error::argument(origin(name), problem);
        let targets: Vec<usize> = (0..scene.materials.len())
            .filter(|&i| {
                let m = &scene.materials[i];
                m.name == *name && !file_materials.contains(&m.name.as_str())
            })
            .collect();
        if targets.is_empty() {
            return Err(bad(no_such_material(scene, name)));
        }
        let mut ordered: Vec<(&String, &toml::Value)> = keys.iter().collect();
        ordered.sort_by_key(|(k, _)| match k.as_str() {
            "model" => 0,
            "preset" => 1,
            _ => 2,
        });
        for &i in &targets {
            for (key, value) in &ordered {
                let edited =
                    crate::material::entry::with_key(&scene.materials[i], key, (*value).clone())
                        .map_err(bad)?;
                scene.materials[i] = edited;
            }
        }
        // The keys as a `[materials]` entry of the edited model says which
        // it does not read, as for the scene file's own entries.
        let model = scene.materials[targets[0]].model;
        let row = model.row();
        let mut entry = keys.clone();
        entry.insert("model".into(), toml::Value::String(model.name().into()));
        let unread: Vec<String> = toml::Value::Table(entry)
            .try_into::<crate::material::MaterialEntry>()
            .map(|e| {
                crate::material::entry::keys_not_applying(&e)
                    .into_iter()
                    .map(|k| format!("`{k}`"))
                    .collect()
            })
            .unwrap_or_default();
        if !unread.is_empty() {
            warnings.push(format!(
                "{}{}: {} not read by model `{}` (its parameters: {}); ignored",
                super::WARNING,
                origin(name),
                unread.join(", "),
                model.name(),
                row.params
                    .iter()
                    .map(|p| p.key)
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    Ok(warnings)
}

/// The message for an edit of a material no one defines: the names there
/// are, the nearest one, and how to make a new material.
fn no_such_material(scene: &Scene, name: &str) -> String {
    let mut names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    names.dedup();
    let listed = if names.is_empty() {
        "it has none".to_string()
    } else {
        format!("it has {}", names.join(", "))
    };
    let hint = nearest_name(name, names.iter().copied())
        .map(|n| format!("; did you mean `{n}`?"))
        .unwrap_or_else(|| ".".into());
    format!(
        "the scene has no material `{name}` ({listed}){hint} A new material starts with its model (`--set materials.{name}.model=lambert`)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_edits_of_undefined_materials_in_gltf_scenes_are_redirected() {
        let gltf: toml::Table =
            "[[objects]]\ngltf = \"a.gltf\"\n[materials.ball]\nmodel = \"lambert\"\n"
                .parse()
                .unwrap();
        assert_eq!(
            redirect(&gltf, "materials.Suzanne.k_d=[1,0,0]").as_deref(),
            Some("gltf_materials.Suzanne.k_d=[1,0,0]")
        );
        assert_eq!(redirect(&gltf, "materials.ball.k_d=1"), None);
        assert_eq!(redirect(&gltf, "materials.new.model=lambert"), None);
        assert_eq!(redirect(&gltf, "lights.0.intensity=1"), None);
        let plain: toml::Table = "[[objects]]\nshape = \"sphere\"\n".parse().unwrap();
        assert_eq!(redirect(&plain, "materials.Suzanne.k_d=1"), None);
    }
}
