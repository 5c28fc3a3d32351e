//! The viewer's state as a scene `.toml` that `gonio render` reproduces.
//!
//! The saved file is the source's table with the overrides applied, the
//! current camera, shading, ambient and image size, and every edited
//! material and `[[lights]]` entry of the file written out in full. glTF
//! paths become absolute, so the saved file may live anywhere.

use super::document::Document;
use crate::Result;
use crate::base::rgb_to_toml;
use toml::Value;

/// The text of the saved file and notes on edits it cannot hold.
pub fn scene_file_text(doc: &Document) -> Result<(String, Vec<String>)> {
    let mut table = doc.table.clone();
    let base_dir = &doc.source_dir;
    let scene = &doc.scene;
    let mut image = toml::Table::new();
    image.insert("width".into(), Value::Integer(scene.width as i64));
    image.insert("height".into(), Value::Integer(scene.height as i64));
    if scene.tone_map != Default::default() {
        image.insert(
            "tone_map".into(),
            Value::String(scene.tone_map.name().into()),
        );
    }
    table.insert("image".into(), Value::Table(image));

    let c = &scene.camera;
    let mut camera = toml::Table::new();
    camera.insert("position".into(), rgb_to_toml(c.position));
    camera.insert("target".into(), rgb_to_toml(c.target));
    camera.insert("up".into(), rgb_to_toml(c.up));
    camera.insert("fov_y_deg".into(), Value::Float(c.fov_y_deg));
    table.insert("camera".into(), Value::Table(camera));

    let mut shading = toml::Table::new();
    shading.insert("mode".into(), Value::String(scene.shading.to_string()));
    table.insert("shading".into(), Value::Table(shading));

    let ambient = table
        .entry("ambient")
        .or_insert_with(|| Value::Table(toml::Table::new()));
    if let Value::Table(t) = ambient {
        t.insert("radiance".into(), rgb_to_toml(scene.ambient));
    }

    // glTF paths relative to the source's folder → absolute.
    if let Some(Value::Array(objects)) = table.get_mut("objects") {
        for object in objects.iter_mut().filter_map(Value::as_table_mut) {
            if let Some(Value::String(path)) = object.get_mut("gltf") {
                let absolute = std::path::absolute(base_dir.join(&*path))
                    .unwrap_or_else(|_| base_dir.join(&*path));
                *path = absolute.display().to_string();
            }
        }
    }

    if let Some(Value::Array(lights)) = table.get_mut("lights") {
        for (i, entry) in doc.edited_lights() {
            if let Some(slot) = lights.get_mut(i) {
                *slot = Value::Table(entry.to_table());
            }
        }
    }

    let mut unsaved = Vec::new();
    for m in doc.edited_materials() {
        if doc.file_materials.contains(&m.name) {
            let materials = table
                .entry("materials")
                .or_insert_with(|| Value::Table(toml::Table::new()));
            if let Value::Table(t) = materials {
                t.insert(
                    m.name.clone(),
                    Value::Table(crate::material::material_table(m)),
                );
            }
        } else {
            unsaved.push(format!(
                "material `{}` comes from a glTF file; a scene file cannot address it, so its edits are not saved (define a [materials] entry and name it in the object's `material` instead)",
                m.name
            ));
        }
    }
    let text = toml::to_string(&table)
        .map_err(|e| crate::Error::Gpu(format!("cannot write the scene as TOML: {e}")))?;
    Ok((
        format!("# Saved by `gonio view` from {}.\n{text}", doc.title()),
        unsaved,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::limits::Limits;
    use crate::scene::scene_file::SceneSource;

    #[test]
    fn documents_take_edits_and_save_what_they_show() {
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("materials.ball.k_e=500").unwrap();
        assert!(doc.edit("materials.ball.k_e=-3").is_err());
        doc.edit("shading.mode=\"gouraud\"").unwrap();
        let materials = doc.scene.materials.clone();
        doc.edit("lights.0.intensity=[1.0, 2.0, 3.0]").unwrap();
        let relit = doc;
        assert_eq!(relit.scene.materials, materials);
        let (text, unsaved) = scene_file_text(&relit).unwrap();
        assert!(unsaved.is_empty());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("saved.toml");
        std::fs::write(&path, text).unwrap();
        let saved = Document::load(SceneSource::File(path), vec![], Limits::default()).unwrap();
        assert_eq!(saved.scene.materials, relit.scene.materials);
        assert_eq!(saved.scene.lights, relit.scene.lights);
        assert_eq!(saved.scene.shading, relit.scene.shading);
        assert_eq!(saved.scene.camera, relit.scene.camera);
    }
}
