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
    /// edits of materials the new scene still has (by name), the camera,
    /// shading mode and ambient radiance.
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

    fn keep_edits_of(&mut self, old: &Document) {
        for (m, loaded) in old.scene.materials.iter().zip(&old.loaded_materials) {
            if m != loaded
                && let Some(slot) = self.scene.materials.iter_mut().find(|n| n.name == m.name)
            {
                *slot = m.clone();
            }
        }
        self.scene.camera = old.scene.camera;
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
