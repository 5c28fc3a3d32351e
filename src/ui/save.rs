//! The viewer's state as a scene `.toml` that `gonio render` reproduces.
//!
//! The saved file is the source's table with the overrides applied, the
//! current camera, shading, ambient and image size, and every edited
//! material and `[[lights]]` entry of the file written out in full (the
//! whole list once lights were added or removed), and
//! the `[environment]` as edited (no map while it is switched off). glTF
//! and map paths become absolute, so the saved file may live anywhere.

use super::document::Document;
use crate::Result;
use crate::base::rgb_to_toml;
use toml::Value;

/// The text of the saved file.
pub fn scene_file_text(doc: &Document) -> Result<String> {
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

    // The environment map's path likewise (`sky` is no file).
    if let Some(Value::Table(e)) = table.get_mut("environment")
        && let Some(Value::String(path)) = e.get_mut("map")
        && path != "sky"
    {
        let absolute =
            std::path::absolute(base_dir.join(&*path)).unwrap_or_else(|_| base_dir.join(&*path));
        *path = absolute.display().to_string();
    }

    if doc.lights_restructured() {
        // Lights were added or removed: the list as it stands.
        let entries = doc.lights.entries.iter();
        let all = entries.map(|e| Value::Table(e.to_table())).collect();
        table.insert("lights".into(), Value::Array(all));
    } else if let Some(Value::Array(lights)) = table.get_mut("lights") {
        for (i, entry) in doc.edited_lights() {
            if let Some(slot) = lights.get_mut(i) {
                *slot = Value::Table(entry.to_table());
            }
        }
    }

    // Scene-file materials are written in full; a glTF file's own
    // material as its edit by name (`[gltf_materials.NAME]`): the keys
    // whose values changed since loading (the model whenever another key
    // is written, so each reads back under the right model), its textures
    // staying the file's.
    for (m, loaded) in doc.edited_materials() {
        let (section, entry) = if doc.file_materials.contains(&m.name) {
            ("materials", crate::material::material_table(m))
        } else {
            let before = crate::material::material_table(loaded);
            let mut changed: toml::Table = crate::material::material_table(m)
                .into_iter()
                .filter(|(k, v)| before.get(k) != Some(v))
                .collect();
            changed.insert("model".into(), Value::String(m.model.name().into()));
            (
                crate::scene::scene_file::gltf_material_edits::SECTION,
                changed,
            )
        };
        let entries = table
            .entry(section)
            .or_insert_with(|| Value::Table(toml::Table::new()));
        if let Value::Table(t) = entries {
            // Merged into an edit the table already has (from the file or
            // a `--set`), which the loaded state includes.
            match t.get_mut(&m.name) {
                Some(Value::Table(existing)) if section != "materials" => existing.extend(entry),
                _ => {
                    t.insert(m.name.clone(), Value::Table(entry));
                }
            }
        }
    }
    let text = toml::to_string(&table)
        .map_err(|e| crate::Error::Gpu(format!("cannot write the scene as TOML: {e}")))?;
    Ok(format!(
        "# Saved by `gonio view` from {}.\n{text}",
        doc.title()
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
        let text = scene_file_text(&relit).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("saved.toml");
        std::fs::write(&path, text).unwrap();
        let saved = Document::load(SceneSource::File(path), vec![], Limits::default()).unwrap();
        assert_eq!(saved.scene.materials, relit.scene.materials);
        assert_eq!(saved.scene.lights, relit.scene.lights);
        assert_eq!(saved.scene.shading, relit.scene.shading);
        assert_eq!(saved.scene.camera, relit.scene.camera);
    }

    /// A glTF file's own material, edited by name, is saved as its edit
    /// and reads back the same, textures kept (Save once dropped it).
    #[test]
    fn edits_of_gltf_materials_are_saved_by_name() {
        let suzanne = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/gltf/Suzanne/Suzanne.gltf");
        let mut doc = Document::load(
            SceneSource::File(suzanne),
            vec!["materials.Suzanne.metallic=0.25".into()],
            Limits::default(),
        )
        .unwrap();
        let m = |d: &Document| d.scene.materials[0].clone();
        assert_eq!(m(&doc).name, "Suzanne");
        assert_eq!(m(&doc).metallic, 0.25);
        assert!(!m(&doc).textures.is_empty());
        doc.edit("materials.Suzanne.roughness=0.7").unwrap();
        let text = scene_file_text(&doc).unwrap();
        assert!(text.contains("[gltf_materials.Suzanne]"), "{text}");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("saved.toml");
        std::fs::write(&path, text).unwrap();
        let saved = Document::load(SceneSource::File(path), vec![], Limits::default()).unwrap();
        assert_eq!(m(&saved), m(&doc));
        assert_eq!(m(&saved).roughness, 0.7);
    }

    /// Lights added, retyped, edited and removed in the viewer are saved
    /// and read back the same, in a scene file and on a
    /// glTF file that had no `[[lights]]`.
    #[test]
    fn added_removed_and_retyped_lights_are_saved() {
        let suzanne = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/gltf/Suzanne/Suzanne.gltf");
        for source in [SceneSource::BuiltIn, SceneSource::File(suzanne)] {
            let mut doc = Document::load(source, vec![], Limits::default()).unwrap();
            let n = doc.lights.entries.len();
            doc.edit("lights.add=spot").unwrap();
            doc.edit("lights.add=point").unwrap();
            doc.edit("lights.add=directional").unwrap();
            doc.edit(&format!("lights.{n}.kind=area")).unwrap();
            doc.edit(&format!("lights.{n}.shadows=true")).unwrap();
            doc.edit(&format!("lights.{n}.shadow_per_sample=true"))
                .unwrap();
            doc.edit(&format!("lights.{n}.shadow_normal_offset=3.5"))
                .unwrap();
            doc.edit(&format!("lights.{n}.tangent=[0.0, 0.0, 1.0]"))
                .unwrap();
            doc.edit(&format!("lights.{}.range=4.0", n + 1)).unwrap();
            doc.edit(&format!("lights.remove={}", n + 2)).unwrap();
            assert_eq!(doc.lights.entries.len(), n + 2);
            let text = scene_file_text(&doc).unwrap();
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("saved.toml");
            std::fs::write(&path, &text).unwrap();
            let saved = Document::load(SceneSource::File(path), vec![], Limits::default())
                .unwrap_or_else(|e| panic!("{e}\n{text}"));
            assert_eq!(saved.scene.lights, doc.scene.lights, "{text}");
            assert_eq!(saved.scene.light_shadows, doc.scene.light_shadows);
            assert_eq!(saved.scene.area_lights, doc.scene.area_lights);
            assert!(saved.scene.area_lights[0].shadow_per_sample);
            let tables = |d: &Document| -> Vec<toml::Table> {
                d.lights.entries.iter().map(|e| e.to_table()).collect()
            };
            assert_eq!(tables(&saved), tables(&doc));
        }
    }

    /// Every parameter of a layered gltf-pbr material (the table of
    /// models' row, so a future layer key is covered without a new line
    /// here), edited as the panel and `--edit` edit it, is saved and reads
    /// back the same with no warning (a key the model does not read would
    /// be one).
    #[test]
    fn layer_edits_are_saved_and_read_back_without_a_warning() {
        use crate::material::param::{Kind, Widget};
        use crate::material::{ReflectanceModel, table};
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("materials.ball.model=\"gltf-pbr\"").unwrap();
        let params = ReflectanceModel::GltfPbr.row().params;
        assert!(params.iter().any(|p| p.key == "sheen_roughness"));
        for p in table::COMMON.iter().chain(params) {
            // A value inside the widget's range, off every default.
            let (min, max) = match p.widget {
                Widget::Slider { min, max, .. } | Widget::Drag { min, max, .. } => (min, max),
                Widget::ColorPicker => (0.0, 1.0),
            };
            let v = min + 0.37 * (max.min(1e3) - min);
            let value = match p.kind {
                Kind::Scalar => format!("{v}"),
                Kind::Color => format!("[{v}, {}, {}]", v * 0.5, v * 0.25),
            };
            doc.edit(&format!("materials.ball.{}={value}", p.key))
                .unwrap_or_else(|e| panic!("{}: {e}", p.key));
        }
        let edited = doc.scene.materials.clone();
        let ball = edited.iter().find(|m| m.name == "ball").unwrap();
        assert!(ball.layers.has_clearcoat() && ball.layers.has_sheen());
        assert!(ball.layers.has_iridescence() && ball.layers.has_anisotropy());
        let text = scene_file_text(&doc).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("saved.toml");
        std::fs::write(&path, &text).unwrap();
        let loaded = crate::scene::scene_file::load_for_editing(
            &SceneSource::File(path),
            &[],
            Limits::default(),
        )
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
        let warnings: Vec<&String> = loaded
            .notes
            .iter()
            .filter(|n| n.starts_with(crate::scene::scene_file::WARNING))
            .collect();
        assert!(warnings.is_empty(), "{warnings:?}\n{text}");
        // What the model reads (the fields of the earlier model, k_d and
        // k_e, are not saved and not read).
        for (saved, m) in loaded.scene.materials.iter().zip(&edited) {
            assert_eq!(saved.brdf().specular, m.brdf().specular, "{}", m.name);
            for p in table::COMMON.iter().chain(m.model.row().params) {
                assert_eq!(p.read(saved), p.read(m), "{}.{}", m.name, p.key);
            }
        }
    }

    /// A material variant chosen in the viewer is saved as `[gltf]
    /// variant` and drawn again in it.
    #[test]
    fn the_chosen_variant_is_saved() {
        let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/scenes/variants/variants.toml");
        let doc = Document::load(SceneSource::File(scene), vec![], Limits::default()).unwrap();
        assert_eq!(doc.variants, ["red coat", "blue"]);
        assert_eq!(doc.variant(), None);
        let drawn = |d: &Document| d.scene.materials[d.scene.meshes[0].material].name.clone();
        assert_eq!(drawn(&doc), "grey");
        let err = doc.with_variant("green").err().unwrap().to_string();
        assert!(err.contains("\"red coat\", \"blue\""), "{err}");
        let mut coated = doc.with_variant("red coat").unwrap();
        assert_eq!(coated.variant(), Some("red coat"));
        assert_eq!(drawn(&coated), "red coat");
        // Edits are kept across the switch, as across a reload.
        coated.edit("materials.blue.roughness=0.9").unwrap();
        let blue = coated.with_variant("blue").unwrap();
        assert_eq!(drawn(&blue), "blue");
        let m = &blue.scene.materials[blue.scene.meshes[0].material];
        assert_eq!(m.roughness, 0.9);
        let text = scene_file_text(&blue).unwrap();
        assert!(text.contains("variant = \"blue\""), "{text}");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("saved.toml");
        std::fs::write(&path, &text).unwrap();
        let saved = Document::load(SceneSource::File(path), vec![], Limits::default()).unwrap();
        assert_eq!(drawn(&saved), "blue");
        assert_eq!(saved.scene.materials, blue.scene.materials);
    }
}
