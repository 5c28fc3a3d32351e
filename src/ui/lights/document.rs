//! The document's list of `[[lights]]` entries: add, remove, change a
//! light's kind. Each change assembles the lights again
//! as the loader does ([`LightSetup::assemble`]) and is refused, leaving
//! the document as it was, when the loader would refuse it.

use super::kinds;
use crate::scene::scene_file::{LightEntry, LightSetup};
use crate::ui::document::Document;
use crate::ui::edit_values::toml_value;

impl Document {
    /// Appends `entry`; returns its index.
    pub fn add_light(&mut self, entry: LightEntry) -> Result<usize, String> {
        let mut setup = self.lights.clone();
        setup.entries.push(entry);
        self.install_lights(setup)?;
        Ok(self.lights.entries.len() - 1)
    }

    /// Appends a new light of `kind` aimed at what the camera looks at
    /// ([`kinds::new_light`]); returns its index.
    pub fn add_light_of_kind(&mut self, kind: &str) -> Result<usize, String> {
        let c = self.scene.camera;
        let slot = self.lights.entries.len();
        self.add_light(kinds::new_light(kind, c.position, c.target, slot)?)
    }

    /// Removes `[[lights]]` entry `index`.
    pub fn remove_light(&mut self, index: usize) -> Result<(), String> {
        let mut setup = self.lights.clone();
        if index >= setup.entries.len() {
            return Err(no_light(index, setup.entries.len()));
        }
        setup.entries.remove(index);
        self.install_lights(setup)
    }

    /// Makes entry `index` a light of `kind`, keeping its place, axis,
    /// shadows and brightness where the camera looks
    /// ([`kinds::retype`]).
    pub fn retype_light(&mut self, index: usize, kind: &str) -> Result<(), String> {
        let entry = self
            .lights
            .entries
            .get(index)
            .ok_or_else(|| no_light(index, self.lights.entries.len()))?;
        let c = self.scene.camera;
        let new = kinds::retype(entry, kind, c.position, c.target)?;
        self.set_light(index, new)
    }

    /// Whether entries were added or removed since loading (then "Save
    /// scene" writes the whole list and a reload keeps it).
    pub fn lights_restructured(&self) -> bool {
        self.lights.entries.len() != self.loaded_lights.len()
    }

    /// The list edits of `--edit`: `lights.add=KIND`, `lights.remove=N`,
    /// `lights.N.kind=KIND`; `None` for any other key.
    pub(in crate::ui) fn edit_light_list(
        &mut self,
        parts: &[&str],
        value: &str,
    ) -> Option<Result<(), String>> {
        Some(match parts {
            ["lights", "add"] => toml_value::<String>(value)
                .and_then(|kind| self.add_light_of_kind(&kind))
                .map(|_| ()),
            ["lights", "remove"] => toml_value::<usize>(value)
                .map_err(|e| format!("{e}: give the index of a light"))
                .and_then(|i| self.remove_light(i)),
            ["lights", index, "kind"] => index
                .parse::<usize>()
                .map_err(|_| format!("`{index}` is not a light index"))
                .and_then(|i| Ok((i, toml_value::<String>(value)?)))
                .and_then(|(i, kind)| self.retype_light(i, &kind)),
            _ => return None,
        })
    }

    fn install_lights(&mut self, setup: LightSetup) -> Result<(), String> {
        setup.assemble()?.install(&mut self.scene);
        self.lights = setup;
        Ok(())
    }
}

fn no_light(index: usize, count: usize) -> String {
    match count {
        0 => format!("there is no light {index}: the scene file has no [[lights]] entry"),
        n => format!(
            "there is no light {index}: the scene file has {n} (0..={})",
            n - 1
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::limits::Limits;
    use crate::scene::scene_file::SceneSource;

    fn built_in() -> Document {
        Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap()
    }

    #[test]
    fn lights_are_added_retyped_and_removed_by_edits() {
        let mut doc = built_in();
        let n = doc.lights.entries.len();
        let lights = doc.scene.lights.len();
        doc.edit("lights.add=spot").unwrap();
        assert_eq!(doc.lights.entries.len(), n + 1);
        assert_eq!(doc.scene.lights.len(), lights + 1);
        assert!(doc.lights_restructured());
        doc.edit(&format!("lights.{n}.kind=area")).unwrap();
        assert_eq!(doc.lights.entries[n].kind(), "area");
        assert_eq!(doc.scene.area_lights.len(), 1);
        // 16 samples stand in for it.
        assert_eq!(doc.scene.lights.len(), lights + 16);
        doc.edit(&format!("lights.{n}.shape=\"disk\""))
            .expect_err("no radius");
        doc.edit(&format!("lights.{n}.samples=4")).unwrap();
        assert_eq!(doc.scene.lights.len(), lights + 4);
        doc.edit(&format!("lights.remove={n}")).unwrap();
        assert_eq!(doc.scene.lights, built_in().scene.lights);
        // Refused, and nothing changes.
        let before = doc.scene.lights.clone();
        for bad in [
            "lights.add=lamp",
            "lights.remove=7",
            "lights.remove=x",
            "lights.0.kind=torch",
            "lights.9.kind=spot",
        ] {
            let err = doc.edit(bad).expect_err(bad);
            assert_eq!(err.exit_code(), 2, "{bad}");
            assert!(!err.to_string().is_empty());
        }
        assert_eq!(doc.scene.lights, before);
        assert!(
            doc.edit("lights.add=lamp")
                .unwrap_err()
                .to_string()
                .contains("point, spot, directional, area")
        );
    }

    #[test]
    fn removing_every_light_brings_the_default_light() {
        let mut doc = built_in();
        while !doc.lights.entries.is_empty() {
            doc.remove_light(0).unwrap();
        }
        assert_eq!(
            doc.scene.lights,
            vec![crate::scene::scene_file::default_light()]
        );
    }
}
