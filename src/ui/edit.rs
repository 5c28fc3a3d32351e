//! Applying one `KEY=VALUE` edit to the document ([`Document::edit`], the
//! dispatcher over every feature's edits: materials, lights, the
//! environment, compared materials, shading, tone map, ambient) and
//! keeping the edits across a reload ([`Document::reload`]). Above the
//! features it dispatches to ([`super::environment::document`],
//! [`super::lights::document`], [`super::compare::materials`]).

use super::document::{Document, VARIANT_KEY};
use crate::scene::change::Change;
use crate::scene::scene_file::{self, LightEntry};
use crate::ui::edit_values::{edit_material, toml_value};
use crate::{Error, Result};
use serde::Deserialize;

impl Document {
    /// Reloads from the source with the same overrides, keeping edits of
    /// materials the new scene still has (by name), of `[[lights]]`
    /// entries it still has (by index; the whole list once lights were
    /// added or removed), the shading mode and ambient radiance, and of
    /// the environment map (its keys as one edit, as a material's:
    /// `environment::keep_edits`). (The viewer keeps its own camera
    /// unless the file's camera changed.)
    pub fn reload(&self) -> Result<Document> {
        let mut fresh = Document::load(self.source.clone(), self.overrides.clone(), self.limits)?;
        fresh.keep_edits_of(self);
        Ok(fresh)
    }

    /// The document with the glTF files drawn in variant `name`: loaded
    /// again with the override `gltf.variant = "name"` (replacing an
    /// earlier one), keeping the edits as a reload does; "Save scene"
    /// writes the key. An error naming the variants there are if none is
    /// called `name`.
    pub fn with_variant(&self, name: &str) -> Result<Document> {
        if !self.variants.iter().any(|v| v == name) {
            let problem = if self.variants.is_empty() {
                "the scene's glTF files have no material variants (KHR_materials_variants)"
                    .to_string()
            } else {
                let listed: Vec<String> =
                    self.variants.iter().map(|v| format!("\"{v}\"")).collect();
                format!("the variants are {}", listed.join(", "))
            };
            return Err(Error::argument(
                format!("gltf.variant = \"{name}\""),
                problem,
            ));
        }
        let mut overrides: Vec<String> = self
            .overrides
            .iter()
            .filter(|kv| {
                let key = kv.split_once('=').map_or(kv.as_str(), |(k, _)| k);
                key.trim() != VARIANT_KEY
            })
            .cloned()
            .collect();
        overrides.push(format!(
            "{}={}",
            VARIANT_KEY,
            toml::Value::String(name.to_string())
        ));
        let mut fresh = Document::load(self.source.clone(), overrides, self.limits)?;
        fresh.keep_edits_of(self);
        Ok(fresh)
    }

    /// Applies one `KEY=VALUE` edit as the panel would: materials, the
    /// shading mode, the ambient radiance, `[[lights]]` entries
    /// (`lights.N.KEY`) and the environment map's keys
    /// (`environment.KEY`, [`super::environment::document`]), each validated like
    /// the scene file. Returns what the edit changed, for the GPU to
    /// rewrite only that.
    pub fn edit(&mut self, assignment: &str) -> Result<Change> {
        let bad = |problem: String| Error::argument(format!("edit {assignment}"), problem);
        let (key, value) = assignment
            .split_once('=')
            .ok_or_else(|| bad("expected KEY=VALUE".into()))?;
        let parts = scene_file::overrides::key_parts(key.trim());
        let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
        if let Some(done) = self.edit_light_list(&parts, value) {
            return done.map(|()| Change::Lights).map_err(bad);
        }
        match parts.as_slice() {
            ["materials", name, field] => {
                let index = self
                    .scene
                    .materials
                    .iter()
                    .position(|m| m.name == *name)
                    .ok_or_else(|| bad(format!("no material is called `{name}`")))?;
                let m = &mut self.scene.materials[index];
                *m = edit_material(m, field, value).map_err(bad)?;
                // Another model may need another environment mode (which
                // the shader key holds: the GPU compares the key).
                crate::scene::environment_mode::choose(&mut self.scene);
                Ok(Change::Material(index))
            }
            ["shading", "mode"] => {
                let mode: String = toml_value(value).map_err(bad)?;
                self.scene.shading = mode.parse().map_err(bad)?;
                Ok(Change::Scene)
            }
            ["image", "tone_map"] => {
                let name: String = toml_value(value).map_err(bad)?;
                self.scene.tone_map = name.parse().map_err(bad)?;
                Ok(Change::Scene)
            }
            ["ambient", "radiance"] => {
                let v: [f64; 3] = toml_value(value).map_err(bad)?;
                if v.iter().any(|c| !c.is_finite() || *c < 0.0) {
                    return Err(bad("radiance must be finite and ≥ 0".into()));
                }
                self.scene.ambient = crate::scene::Rgb::from_array(v);
                Ok(Change::View)
            }
            ["environment", key] => {
                super::environment::document::edit(self, key, assignment).map(|()| Change::Environment)
            }
            ["compare", rest @ ..] => self
                .compare
                .edit(rest, value)
                .map(|()| Change::Compared)
                .map_err(bad),
            ["lights", index, _field] => {
                let index: usize = index
                    .parse()
                    .map_err(|_| bad(format!("`{index}` is not a light index")))?;
                let entry = self.light_entry_with(index, assignment)?;
                self.set_light(index, entry)
                    .map(|()| Change::Lights)
                    .map_err(bad)
            }
            _ => Err(bad(
                "the viewer edits materials.NAME.KEY, lights.N.KEY, lights.add=KIND, lights.remove=N, environment.KEY, compare.N.KEY, compare.split, compare.shown, shading.mode, image.tone_map and ambient.radiance"
                    .into(),
            )),
        }
    }

    /// The `[[lights]]` entry `lights.N.KEY=VALUE` makes: the entry as the
    /// file writes it, the key set by the override rules of `--set`, read
    /// back by the scene file's schema (so a misspelt key or a value of the
    /// wrong type is refused with the file's message).
    fn light_entry_with(&self, index: usize, assignment: &str) -> Result<LightEntry> {
        let entries = self.lights.entries.iter();
        let mut root = toml::Table::new();
        root.insert(
            "lights".into(),
            toml::Value::Array(entries.map(|e| toml::Value::Table(e.to_table())).collect()),
        );
        scene_file::apply_override(&mut root, assignment)?;
        LightEntry::deserialize(root["lights"][index].clone()).map_err(|e| {
            Error::argument(
                format!("edit {assignment}"),
                scene_file::diagnostics::clean_toml_error(&e),
            )
        })
    }

    fn keep_edits_of(&mut self, old: &Document) {
        self.compare = old.compare.clone();
        for (m, loaded) in old.scene.materials.iter().zip(&old.loaded_materials) {
            if m != loaded
                && let Some(slot) = self.scene.materials.iter_mut().find(|n| n.name == m.name)
            {
                *slot = m.clone();
            }
        }
        self.scene.shading = old.scene.shading;
        self.scene.ambient = old.scene.ambient;
        let mut lights = self.lights.clone();
        if old.lights_restructured() {
            // Lights were added or removed: the viewer's list stands.
            lights.entries = old.lights.entries.clone();
        }
        for ((i, entry), loaded) in old
            .lights
            .entries
            .iter()
            .enumerate()
            .zip(&old.loaded_lights)
        {
            if entry.to_table() != *loaded
                && let Some(slot) = lights.entries.get_mut(i)
            {
                *slot = entry.clone();
            }
        }
        // Edits the changed file no longer accepts are dropped.
        if let Ok(assembled) = lights.assemble() {
            assembled.install(&mut self.scene);
            self.lights = lights;
        }
        super::environment::document::keep_edits(self, old);
    }
}
