//! What the viewer shows: a scene loaded like `gonio render` loads it, and
//! the edits made since, kept so they can be saved as a scene file.
//!
//! Two kinds of edit, by cost:
//! - material, camera, shading and ambient edits change the loaded
//!   [`Scene`] in place (a slider drag redraws at frame rate; the GPU
//!   side writes one buffer);
//! - light edits are `--set` overrides of the file's `[[lights]]` entries
//!   and reload the scene (an area light expands into samples, a light
//!   moves its shadow maps: the loader does that once, as for `render`).
//!
//! Saving writes the file's table with every edit applied, so
//! `gonio render saved.toml` draws what the viewer shows.

use crate::material::Material;
use crate::scene::Scene;
use crate::scene::limits::Limits;
use crate::scene::scene_file::{self, SceneSource};
use crate::{Error, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// The scene on screen and how it was made.
pub struct Document {
    pub source: SceneSource,
    /// `--set` overrides: the command line's, then light edits.
    pub overrides: Vec<String>,
    pub limits: Limits,
    /// The scene as loaded, with in-place edits applied.
    pub scene: Scene,
    /// Materials as loaded (to tell which ones were edited).
    loaded_materials: Vec<Material>,
    /// The camera as loaded (the viewer's orbit starts and resets there).
    pub loaded_camera: crate::scene::Camera,
    /// Names of the scene file's own `[materials]` (those a saved file can
    /// address; materials a glTF file brings have no key).
    pub file_materials: BTreeSet<String>,
    /// The scene file's `[[lights]]` entries as tables (after overrides).
    pub file_lights: Vec<toml::Table>,
    /// Modification time of the scene file when loaded (reload on change).
    modified: Option<SystemTime>,
}

impl Document {
    /// Loads `source` with `overrides`.
    pub fn load(source: SceneSource, overrides: Vec<String>, limits: Limits) -> Result<Document> {
        let (scene, _notes) = scene_file::load_with_limits(&source, &overrides, limits)?;
        let (_, _, mut table) = scene_file::scene_table(&source)?;
        for kv in &overrides {
            scene_file::apply_override(&mut table, kv)?;
        }
        let file_materials = table
            .get("materials")
            .and_then(|m| m.as_table())
            .map(|m| m.keys().cloned().collect())
            .unwrap_or_default();
        let file_lights = table
            .get("lights")
            .and_then(|l| l.as_array())
            .map(|a| a.iter().filter_map(|l| l.as_table().cloned()).collect())
            .unwrap_or_default();
        Ok(Document {
            modified: modified_time(&source),
            loaded_materials: scene.materials.clone(),
            loaded_camera: scene.camera,
            source,
            overrides,
            limits,
            scene,
            file_materials,
            file_lights,
        })
    }

    /// The path of the scene file, if it is one.
    pub fn path(&self) -> Option<&Path> {
        match &self.source {
            SceneSource::File(p) => Some(p),
            SceneSource::BuiltIn => None,
        }
    }

    /// A short name for the title bar.
    pub fn title(&self) -> String {
        match self.path() {
            Some(p) => p.display().to_string(),
            None => "built-in scene".into(),
        }
    }

    /// Whether the file changed on disk since it was loaded.
    pub fn changed_on_disk(&self) -> bool {
        let now = modified_time(&self.source);
        now.is_some() && now != self.modified
    }

    /// Takes the file's current modification time as seen (after a
    /// failed reload, so it is not retried until the file changes again).
    pub fn mark_seen(&mut self) {
        self.modified = modified_time(&self.source);
    }

    /// Reloads from the source with the same overrides, keeping in-place
    /// edits of materials the new scene still has (by name), the shading
    /// mode and ambient radiance. (The viewer keeps its own camera unless
    /// the file's camera changed.)
    pub fn reload(&self) -> Result<Document> {
        let mut fresh = Document::load(self.source.clone(), self.overrides.clone(), self.limits)?;
        fresh.keep_edits_of(self);
        Ok(fresh)
    }

    /// Sets `lights.INDEX.KEY = VALUE` (a TOML value) and reloads; on error
    /// nothing changes.
    pub fn set_light(&self, index: usize, key: &str, value: &str) -> Result<Document> {
        let assignment = format!("lights.{index}.{key}={value}");
        let mut overrides = self.overrides.clone();
        // The newest value of a key replaces the older one.
        let prefix = format!("lights.{index}.{key}=");
        overrides.retain(|o| !o.starts_with(&prefix));
        overrides.push(assignment);
        let mut fresh = Document::load(self.source.clone(), overrides, self.limits)?;
        fresh.keep_edits_of(self);
        Ok(fresh)
    }

    /// Applies one `KEY=VALUE` edit as the panel would: materials, the
    /// shading mode and the ambient radiance in place (validated like the
    /// scene file), lights by reloading. Returns a new document when it
    /// reloaded.
    pub fn edit(&mut self, assignment: &str) -> Result<Option<Document>> {
        let bad = |problem: String| Error::argument(format!("edit {assignment}"), problem);
        let (key, value) = assignment
            .split_once('=')
            .ok_or_else(|| bad("expected KEY=VALUE".into()))?;
        let parts: Vec<&str> = key.trim().split('.').collect();
        match parts.as_slice() {
            ["materials", name, field] => {
                let m = self
                    .scene
                    .materials
                    .iter_mut()
                    .find(|m| m.name == *name)
                    .ok_or_else(|| bad(format!("no material is called `{name}`")))?;
                *m = edit_material(m, field, value).map_err(bad)?;
                Ok(None)
            }
            ["shading", "mode"] => {
                let mode: String = toml_value(value).map_err(bad)?;
                self.scene.shading = mode.parse().map_err(bad)?;
                Ok(None)
            }
            ["ambient", "radiance"] => {
                let v: [f64; 3] = toml_value(value).map_err(bad)?;
                if v.iter().any(|c| !c.is_finite() || *c < 0.0) {
                    return Err(bad("radiance must be finite and ≥ 0".into()));
                }
                self.scene.ambient = crate::scene::Rgb::from_array(v);
                Ok(None)
            }
            ["lights", index, field] => {
                let index: usize = index
                    .parse()
                    .map_err(|_| bad(format!("`{index}` is not a light index")))?;
                Ok(Some(self.set_light(index, field, value)?))
            }
            _ => Err(bad(
                "the viewer edits materials.NAME.KEY, lights.N.KEY, shading.mode and ambient.radiance"
                    .into(),
            )),
        }
    }

    fn keep_edits_of(&mut self, old: &Document) {
        for (m, loaded) in old.scene.materials.iter().zip(&old.loaded_materials) {
            if m != loaded
                && let Some(slot) = self.scene.materials.iter_mut().find(|n| n.name == m.name)
            {
                *slot = m.clone();
            }
        }
        self.scene.shading = old.scene.shading;
        self.scene.ambient = old.scene.ambient;
    }

    /// Materials changed since loading, by index.
    pub fn edited_materials(&self) -> impl Iterator<Item = &Material> {
        self.scene
            .materials
            .iter()
            .zip(&self.loaded_materials)
            .filter(|(m, loaded)| m != loaded)
            .map(|(m, _)| m)
    }

    /// The scene file that reproduces the current state; and the edits it
    /// cannot express (materials of glTF files).
    pub fn to_scene_file(&self) -> Result<(String, Vec<String>)> {
        super::save::scene_file_text(self)
    }

    /// The folder relative paths of the source resolve in.
    pub fn base_dir(&self) -> PathBuf {
        match self.path().and_then(Path::parent) {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    }
}

fn modified_time(source: &SceneSource) -> Option<SystemTime> {
    match source {
        SceneSource::File(p) => std::fs::metadata(p).and_then(|m| m.modified()).ok(),
        SceneSource::BuiltIn => None,
    }
}

/// The error for a scene the viewer cannot open, as a one-line message.
pub fn describe_error(e: &Error) -> String {
    e.to_string()
}

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

fn toml_value<T: serde::de::DeserializeOwned>(text: &str) -> std::result::Result<T, String> {
    let table: toml::Table = format!("v = {text}")
        .parse()
        .map_err(|e: toml::de::Error| format!("`{text}` is not a TOML value: {}", e.message()))?;
    table["v"]
        .clone()
        .try_into()
        .map_err(|e: toml::de::Error| format!("`{text}`: {}", e.message()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;

    #[test]
    fn material_edits_are_checked_like_the_scene_file() {
        let m = Material::new("ball", ReflectanceModel::Lambert);
        let blue = edit_material(&m, "k_d", "[0.0, 0.0, 1.0]").unwrap();
        assert_eq!(blue.k_d, crate::scene::Rgb::new(0.0, 0.0, 1.0));
        let ct = edit_material(&m, "model", "\"cook-torrance\"").unwrap();
        assert_eq!(ct.model, ReflectanceModel::CookTorrance);
        assert!(edit_material(&m, "roughness", "-1.0").is_err());
        assert!(edit_material(&m, "k_e", "\"big\"").is_err());
        assert!(edit_material(&m, "colour", "1.0").is_err());
    }

    #[test]
    fn a_changed_file_is_noticed_and_reloaded_with_the_edits_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        let text = crate::scene::default_scene::DEFAULT_SCENE_TOML;
        std::fs::write(&path, text).unwrap();
        let mut doc =
            Document::load(SceneSource::File(path.clone()), vec![], Limits::default()).unwrap();
        assert!(!doc.changed_on_disk());
        doc.edit("materials.ball.k_e=7").unwrap();
        std::fs::write(&path, text.replace("fov_y_deg = 40.0", "fov_y_deg = 30.0")).unwrap();
        let later = std::time::SystemTime::now() + std::time::Duration::from_secs(5);
        std::fs::File::options()
            .write(true)
            .open(&path)
            .unwrap()
            .set_modified(later)
            .unwrap();
        assert!(doc.changed_on_disk());
        let fresh = doc.reload().unwrap();
        assert_eq!(fresh.scene.materials, doc.scene.materials, "edits kept");
        assert_eq!(
            fresh.loaded_camera.fov_y_deg, 30.0,
            "the file's change is seen"
        );
        // A file broken on disk: the reload fails, the document stays.
        std::fs::write(&path, "[camera\n").unwrap();
        let err = doc.reload().err().expect("broken file").to_string();
        assert!(err.contains("scene.toml"), "{err}");
    }

    #[test]
    fn documents_take_edits_and_save_what_they_show() {
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        assert!(doc.edit("materials.ball.k_e=500").unwrap().is_none());
        assert!(doc.edit("materials.ball.k_e=-3").is_err());
        assert!(doc.edit("shading.mode=\"gouraud\"").unwrap().is_none());
        let relit = doc
            .edit("lights.0.intensity=[1.0, 2.0, 3.0]")
            .unwrap()
            .unwrap();
        assert_eq!(relit.scene.materials, doc.scene.materials);
        let (text, unsaved) = relit.to_scene_file().unwrap();
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
