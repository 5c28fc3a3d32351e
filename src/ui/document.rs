//! What the viewer shows: a scene loaded like `gonio render` loads it, and
//! the edits made since, kept so they can be saved as a scene file.
//!
//! Every edit is a typed value applied to the loaded [`Scene`]:
//! - material, camera, shading and ambient edits change it in place (a
//!   slider drag redraws at frame rate; each edit names what it changed,
//!   `crate::scene::change`, and the GPU rewrites that: one material
//!   record for a material's value);
//! - a light edit changes one typed `[[lights]]` entry and runs the
//!   loader's light step again ([`LightSetup::assemble`]: area lights
//!   expanded into samples, shadow settings merged with `[shadows]`),
//!   without reading the scene file or importing its glTF files again.
//!
//! Saving writes the file's table with every edit applied, so
//! `gonio render saved.toml` draws what the viewer shows. Lights can also
//! be added, removed and retyped ([`super::lights::document`]); the
//! environment map's keys are edited by [`super::environment::document`].
//! Applying an edit by its key and keeping the edits across a reload
//! ([`super::edit`]) sit above those, so this file holds the document and
//! what was loaded, and uses none of them.

use crate::material::Material;
use crate::scene::Scene;
use crate::scene::limits::Limits;
use crate::scene::scene_file::{self, LightEntry, LightSetup, SceneSource};
use crate::{Error, Result};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// The scene on screen and how it was made.
pub struct Document {
    pub source: SceneSource,
    /// The command line's `--set` overrides.
    pub overrides: Vec<String>,
    pub limits: Limits,
    /// The scene as loaded, with edits applied.
    pub scene: Scene,
    /// Materials as loaded (to tell which ones were edited).
    pub(in crate::ui) loaded_materials: Vec<Material>,
    /// The camera as loaded (the viewer's orbit starts and resets there).
    pub loaded_camera: crate::scene::Camera,
    /// Names of the scene file's own `[materials]` (those a saved file can
    /// address; materials a glTF file brings have no key).
    pub file_materials: BTreeSet<String>,
    /// The scene table with the overrides applied ("Save scene" writes it
    /// with the edits).
    pub table: toml::Table,
    /// The folder the table's relative paths resolve in.
    pub source_dir: PathBuf,
    /// What the scene's lights are made from, with light edits applied.
    pub lights: LightSetup,
    /// The `[[lights]]` entries as loaded, written out (to tell which ones
    /// were edited).
    pub(in crate::ui) loaded_lights: Vec<toml::Table>,
    /// Modification time of the scene file when loaded (reload on change).
    modified: Option<SystemTime>,
    /// The `[environment]` map keys while the map is switched off in the
    /// viewer ([`super::environment`]); `None` while it is on.
    pub parked_environment: Option<toml::Table>,
    /// The `[environment]` map keys as loaded (to tell whether the
    /// environment was edited: `super::environment::document::edited`).
    pub(in crate::ui) loaded_environment: toml::Table,
    /// Materials compared with the selected one (not part of the scene
    /// file, kept across a reload; [`super::compare`]).
    pub compare: super::compare::materials::Compare,
    /// The glTF files' material variants (`KHR_materials_variants`), each
    /// once: the panel's variant choice ([`Document::with_variant`]).
    pub variants: Vec<String>,
}

impl Document {
    /// Loads `source` with `overrides`.
    pub fn load(source: SceneSource, overrides: Vec<String>, limits: Limits) -> Result<Document> {
        let loaded = scene_file::load_for_editing(&source, &overrides, limits)?;
        // As `gonio render` does: warnings are shown, other notes are not.
        for warning in loaded
            .notes
            .iter()
            .filter(|n| n.starts_with(scene_file::WARNING))
        {
            eprintln!("gonio: {warning}");
        }
        let file_materials = loaded
            .table
            .get("materials")
            .and_then(|m| m.as_table())
            .map(|m| m.keys().cloned().collect())
            .unwrap_or_default();
        let scene = loaded.scene;
        Ok(Document {
            modified: modified_time(&source),
            loaded_materials: scene.materials.clone(),
            loaded_camera: scene.camera,
            loaded_lights: loaded
                .lights
                .entries
                .iter()
                .map(LightEntry::to_table)
                .collect(),
            source,
            overrides,
            limits,
            scene,
            file_materials,
            source_dir: loaded.base_dir,
            lights: loaded.lights,
            parked_environment: None,
            loaded_environment: map_keys(&loaded.table),
            table: loaded.table,
            compare: Default::default(),
            variants: loaded.variants,
        })
    }

    /// The chosen material variant (`gltf.variant` of the file or of an
    /// override), `None` for the files' own materials.
    pub fn variant(&self) -> Option<&str> {
        self.table.get("gltf")?.get("variant")?.as_str()
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

    /// Replaces `[[lights]]` entry `index` and assembles the lights again;
    /// on error (a value the scene file would refuse) nothing changes.
    pub fn set_light(
        &mut self,
        index: usize,
        entry: LightEntry,
    ) -> std::result::Result<(), String> {
        let mut setup = self.lights.clone();
        let slot = setup
            .entries
            .get_mut(index)
            .ok_or_else(|| format!("there is no light {index}"))?;
        *slot = entry;
        setup.assemble()?.install(&mut self.scene);
        self.lights = setup;
        Ok(())
    }

    /// `[[lights]]` entries changed since loading: index and entry.
    pub fn edited_lights(&self) -> impl Iterator<Item = (usize, &LightEntry)> {
        self.lights
            .entries
            .iter()
            .enumerate()
            .zip(&self.loaded_lights)
            .filter(|((_, e), loaded)| e.to_table() != **loaded)
            .map(|(entry, _)| entry)
    }

    /// Materials changed since loading, each with its state as loaded.
    pub fn edited_materials(&self) -> impl Iterator<Item = (&Material, &Material)> {
        self.scene
            .materials
            .iter()
            .zip(&self.loaded_materials)
            .filter(|(m, loaded)| m != loaded)
    }

    /// The folder relative paths of the source resolve in.
    pub fn base_dir(&self) -> PathBuf {
        match self.path().and_then(Path::parent) {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    }
}

/// The scene key of the material variant.
pub const VARIANT_KEY: &str = "gltf.variant";

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

/// The `[environment]` keys of a map (the gradient's `zenith`, `horizon`
/// and `ground` are not edited here).
pub const MAP_KEYS: [&str; 8] = [
    "map",
    "scale",
    "sh_order",
    "reference",
    "rotation_deg",
    "specular",
    "samples",
    "prefilter_size",
];

/// The map keys of `table`'s `[environment]` (what the viewer edits).
pub fn map_keys(table: &toml::Table) -> toml::Table {
    let mut keys = toml::Table::new();
    if let Some(toml::Value::Table(e)) = table.get("environment") {
        for key in MAP_KEYS {
            if let Some(v) = e.get(key) {
                keys.insert(key.into(), v.clone());
            }
        }
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;
    use crate::ui::edit_values::edit_material;

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
        doc.edit("lights.0.intensity=[5.0, 5.0, 5.0]").unwrap();
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
        assert_eq!(fresh.scene.lights, doc.scene.lights, "light edits kept");
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
    fn edits_read_values_as_set_does() {
        // `--edit 35:shading.mode=flat` once said "invalid boolean"
        // where `--set shading.mode=flat` worked: unquoted words are strings.
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("shading.mode=flat").unwrap();
        assert_eq!(doc.scene.shading, crate::scene::ShadingMode::Flat);
        doc.edit("shading.mode=\"gouraud\"").unwrap();
        assert_eq!(doc.scene.shading, crate::scene::ShadingMode::Gouraud);
        doc.edit("materials.ball.model=phong").unwrap();
        assert_eq!(doc.scene.materials[0].model, ReflectanceModel::Phong);
        assert!(doc.edit("shading.mode=sideways").is_err());
    }

    #[test]
    fn light_edits_reassemble_the_lights_without_reloading() {
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("materials.ball.k_e=500").unwrap();
        let materials = doc.scene.materials.clone();
        let meshes = doc.scene.meshes.clone();
        doc.edit("lights.0.intensity=[1.0, 2.0, 3.0]").unwrap();
        assert_eq!(doc.scene.materials, materials, "material edits kept");
        assert_eq!(doc.scene.meshes, meshes);
        match &doc.scene.lights[0] {
            crate::scene::Light::Point { intensity, .. } => {
                assert_eq!(*intensity, crate::scene::Rgb::new(1.0, 2.0, 3.0))
            }
            other => panic!("{other:?}"),
        }
        // The same values through `--set` give the same lights.
        let sets = vec!["lights.0.intensity=[1.0, 2.0, 3.0]".to_string()];
        let set = Document::load(SceneSource::BuiltIn, sets, Limits::default()).unwrap();
        assert_eq!(set.scene.lights, doc.scene.lights);
        // Shadow keys merge with `[shadows]` as the loader merges them.
        doc.edit("lights.0.shadows=true").unwrap();
        doc.edit("lights.0.shadow_filter=\"none\"").unwrap();
        assert!(doc.scene.has_shadows());
        assert_eq!(
            doc.scene.shadow_settings(0).filter,
            crate::scene::ShadowFilter::None
        );
        assert_eq!(doc.lights.shadow_settings(0), doc.scene.shadow_settings(0));
        // Refused values leave the document as it was.
        let before = doc.scene.lights.clone();
        for bad in [
            "lights.0.intensity=-1",
            "lights.0.intensty=1",
            "lights.0.shadow_map_size=3",
            "lights.1.intensity=1",
            "lights.x.intensity=1",
        ] {
            let err = doc.edit(bad).expect_err(bad);
            assert_eq!(err.exit_code(), 2, "{bad}");
        }
        assert_eq!(doc.scene.lights, before);
    }

    #[test]
    fn an_area_light_edit_expands_into_its_samples() {
        let light = "lights=[{kind = \"area\", shape = \"disk\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radius = 0.5, radiance = 2.0, samples = 9}]";
        let mut doc =
            Document::load(SceneSource::BuiltIn, vec![light.into()], Limits::default()).unwrap();
        assert_eq!(doc.scene.lights.len(), 9);
        let mut entry = doc.lights.entries[0].clone();
        if let LightEntry::Area(area) = &mut entry {
            area.samples = Some(16);
        }
        doc.set_light(0, entry).unwrap();
        assert_eq!(doc.scene.lights.len(), 16);
        assert_eq!(doc.scene.light_shadows.len(), 16);
        assert_eq!(doc.scene.area_lights[0].samples, 16);
        let sets = vec![light.into(), "lights.0.samples=16".into()];
        let set = Document::load(SceneSource::BuiltIn, sets, Limits::default()).unwrap();
        assert_eq!(set.scene.lights, doc.scene.lights);
        assert_eq!(doc.edited_lights().count(), 1);
    }
}
