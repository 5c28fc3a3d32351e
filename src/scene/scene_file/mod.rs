//! The scene `.toml` of the contract, `--set` overrides by dotted path, and
//! the assembly of a [`Scene`] from it, one file per step:
//! 1. [`schema`]: parse the text into serde types (syntax and type errors
//!    carry line and column, made readable by [`diagnostics`]);
//! 2. [`overrides`]: apply `--set KEY=VALUE` overrides one by one, so an
//!    error names the override that caused it;
//! 3. [`assembly`]: validate values and assemble the scene (range errors
//!    name the key); its lights are a step of their own ([`lights`]), which
//!    the viewer runs again after a light edit. The shadow-map keys are
//!    defined once, in [`shadow_keys`].
//!
//! A `.gltf`/`.glb` argument and the built-in scene go through the same
//! steps: they are turned into an equivalent scene table first.

pub mod assembly;
pub mod diagnostics;
pub mod environment_keys;
pub mod gltf_keys;
pub mod gltf_material_edits;
pub mod lights;
pub mod mode_warnings;
pub mod model_switch;
pub mod overrides;
pub mod schema;
pub mod shadow_keys;
pub mod textures;
pub mod toml_value;
mod values;

pub use assembly::MAX_IMAGE_SIDE;
pub use diagnostics::WARNING;
pub use lights::{LightSetup, MAX_POINT_LIGHTS, SceneLights, default_light};
pub use overrides::apply_override;
pub use schema::{LightEntry, SceneFile};
pub use shadow_keys::{ShadowKeys, ShadowsSection};

use crate::scene::Scene;
use crate::scene::default_scene::DEFAULT_SCENE_TOML;
use crate::scene::gltf_import;
use crate::scene::limits::{Limits, ReadError, read_regular_file};
use crate::{Error, Result};
use diagnostics::clean_toml_error;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Where a scene comes from.
#[derive(Clone, Debug)]
pub enum SceneSource {
    /// The built-in scene.
    BuiltIn,
    /// A file: `.toml`, `.gltf` or `.glb`.
    File(PathBuf),
}

/// Loads a scene from `source`, applying `overrides` (`KEY=VALUE`, dotted
/// keys) in order.
pub fn load(source: &SceneSource, overrides: &[String]) -> Result<Scene> {
    load_with_limits(source, overrides, Limits::default()).map(|(scene, _notes)| scene)
}

/// [`load`] with the glTF files of the scene held to `limits` (one budget
/// for all of them); also returns the notes their import left, such as
/// ignored optional extensions, for `--verbose`.
pub fn load_with_limits(
    source: &SceneSource,
    overrides: &[String],
    limits: Limits,
) -> Result<(Scene, Vec<String>)> {
    load_for_editing(source, overrides, limits).map(|loaded| (loaded.scene, loaded.notes))
}

/// A scene as the viewer keeps it: the scene, the table it was read from
/// (overrides applied) and what its lights were made from.
pub struct Loaded {
    pub scene: Scene,
    /// The scene table after overrides (what "Save scene" starts from).
    pub table: toml::Table,
    /// The folder the source's relative paths resolve in.
    pub base_dir: PathBuf,
    pub lights: LightSetup,
    /// Notes of the glTF import (see [`load_with_limits`]).
    pub notes: Vec<String>,
    /// The glTF files' material variants (`KHR_materials_variants`), each
    /// once; `gltf.variant` picks one.
    pub variants: Vec<String>,
}

/// [`load_with_limits`], keeping what the viewer edits and saves.
pub fn load_for_editing(
    source: &SceneSource,
    overrides: &[String],
    limits: Limits,
) -> Result<Loaded> {
    let (origin, base_dir, mut table) = scene_table(source)?;
    // Parse once without overrides: errors here are the file's, with spans.
    let mut file = parse_table(&origin, &table)?;
    // Which `--set` made each `[gltf_materials.NAME]` edit, for messages.
    let mut edit_origins = std::collections::BTreeMap::new();
    let mut written = model_switch::Written::default();
    let mut switch_notes = Vec::new();
    for kv in overrides {
        let redirected = gltf_material_edits::redirect(&table, kv);
        if let Some(r) = &redirected
            && let Some((key, _)) = r.split_once('=')
            && let Some(name) = overrides::key_parts(key).into_iter().nth(1)
        {
            edit_origins
                .entry(name.to_string())
                .or_insert_with(|| format!("--set {kv}"));
        }
        apply_override(&mut table, redirected.as_deref().unwrap_or(kv))?;
        written.record(kv);
        let dropped = model_switch::drop_unread_keys(&mut table, kv, &written);
        if !dropped.is_empty() {
            let keys: Vec<String> = dropped.iter().map(|k| format!("`{k}`")).collect();
            // The built-in scene's keys are not the user's: a note only.
            let prefix = if matches!(source, SceneSource::BuiltIn) {
                ""
            } else {
                WARNING
            };
            switch_notes.push(format!(
                "{prefix}--set {kv}: {} of {} not read by the new model; dropped",
                keys.join(", "),
                origin.display()
            ));
        }
        file = SceneFile::deserialize(toml::Value::Table(table.clone()))
            .map_err(|e| Error::argument(format!("--set {kv}"), clean_toml_error(&e)))?;
    }
    let mut notes = inapplicable_keys(&file);
    notes.extend(switch_notes);
    let mut gltf_files = gltf_import::GltfLoader::new(limits);
    let gltf_edits = std::mem::take(&mut file.gltf_materials);
    let file_materials: Vec<String> = file.materials.keys().cloned().collect();
    let (mut scene, lights, variants) =
        assembly::assemble(&origin, &base_dir, file, &mut gltf_files)?;
    let file_names: Vec<&str> = file_materials.iter().map(String::as_str).collect();
    let edit_warnings = gltf_material_edits::apply(&mut scene, &file_names, &gltf_edits, |name| {
        edit_origins.get(name).cloned().unwrap_or_else(|| {
            format!(
                "{}: [{}.{name}]",
                origin.display(),
                gltf_material_edits::SECTION
            )
        })
    })?;
    notes.extend(edit_warnings);
    crate::scene::environment_mode::choose(&mut scene);
    notes.extend(gltf_files.notes().iter().cloned());
    notes.extend(lights.notes());
    if let Some(kv) = overrides.iter().find(|kv| {
        kv.split_once('=')
            .is_some_and(|(k, _)| k.trim() == "lights")
    }) && !lights.imported.is_empty()
    {
        notes.push(format!(
            "{WARNING}--set {kv} sets the scene's `[[lights]]`; the {} KHR_lights_punctual light(s) of the glTF file(s) are not `lights` entries and are drawn as well",
            lights.imported.len()
        ));
    }
    notes.extend(
        mode_warnings::warnings(&scene)
            .into_iter()
            .map(|w| format!("{WARNING}{w}")),
    );
    Ok(Loaded {
        scene,
        table,
        base_dir,
        lights,
        notes,
        variants,
    })
}
/// A warning per material with keys its model does not read.
fn inapplicable_keys(file: &SceneFile) -> Vec<String> {
    file.materials
        .iter()
        .filter_map(|(name, entry)| {
            let keys = crate::material::entry::keys_not_applying(entry);
            (!keys.is_empty()).then(|| {
                let params: Vec<&str> = entry
                    .model
                    .parse::<crate::material::ReflectanceModel>()
                    .map(|m| m.row().params.iter().map(|p| p.key).collect())
                    .unwrap_or_default();
                format!(
                    "{WARNING}materials.{name}: {} not read by model `{}` (its parameters: {}); ignored",
                    keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", "),
                    entry.model,
                    params.join(", ")
                )
            })
        })
        .collect()
}

/// The scene table of `source` before overrides, with the file (or a
/// pseudo-path for the built-in scene) that errors name and the folder
/// its relative paths resolve in.
pub fn scene_table(source: &SceneSource) -> Result<(PathBuf, PathBuf, toml::Table)> {
    match source {
        SceneSource::BuiltIn => {
            let table = DEFAULT_SCENE_TOML
                .parse::<toml::Table>()
                .expect("the built-in scene is valid TOML");
            Ok(("<built-in scene>".into(), PathBuf::from("."), table))
        }
        SceneSource::File(path) => {
            let base_dir = path
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_else(|| PathBuf::from("."));
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            match ext.as_deref() {
                Some("toml") => {
                    let text = read_scene_text(path)?;
                    // Typed parse first: syntax and type errors with line/column.
                    toml::from_str::<SceneFile>(&text).map_err(|e| {
                        Error::input(path, diagnostics::clean_toml_error_in(&e, &text))
                    })?;
                    let table = text
                        .parse::<toml::Table>()
                        .map_err(|e| Error::input(path, clean_toml_error(&e)))?;
                    Ok((path.clone(), base_dir, table))
                }
                Some("gltf") | Some("glb") => {
                    match std::fs::metadata(path) {
                        Ok(meta) if meta.is_file() => {}
                        Ok(_) => {
                            return Err(Error::input(
                                path,
                                "is not a regular file (a directory, FIFO or device); a glTF scene must be a .gltf or .glb file",
                            ));
                        }
                        Err(e) => {
                            return Err(Error::input(path, format!("cannot read the file: {e}")));
                        }
                    }
                    let name = path.file_name().unwrap_or_default().to_string_lossy();
                    let mut object = toml::Table::new();
                    object.insert("gltf".into(), toml::Value::String(name.into_owned()));
                    let mut table = toml::Table::new();
                    table.insert(
                        "objects".into(),
                        toml::Value::Array(vec![toml::Value::Table(object)]),
                    );
                    Ok((path.clone(), base_dir, table))
                }
                _ if path.is_dir() => Err(Error::input(
                    path,
                    "it is a directory; SCENE is a scene file: a .toml, a .gltf or a .glb",
                )),
                _ => Err(Error::input(
                    path,
                    "unknown scene type: expected a .toml scene file, a .gltf or a .glb",
                )),
            }
        }
    }
}

fn parse_table(origin: &Path, table: &toml::Table) -> Result<SceneFile> {
    SceneFile::deserialize(toml::Value::Table(table.clone()))
        .map_err(|e| Error::input(origin, clean_toml_error(&e)))
}

/// Largest scene file read. Scene files are hand-written text, far
/// smaller; the cap bounds what parsing can allocate.
const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// The text of a scene file: a regular file (not a FIFO or a device, which
/// would block or never end), of bounded size, in UTF-8.
fn read_scene_text(path: &Path) -> Result<String> {
    let bytes = read_regular_file(path, MAX_SCENE_FILE_BYTES).map_err(|e| {
        let problem = match e {
            ReadError::TooLarge(len) => format!(
                "the scene file has {len} bytes; scene files may have at most {MAX_SCENE_FILE_BYTES}"
            ),
            other => other.to_string(),
        };
        Error::input(path, problem)
    })?;
    String::from_utf8(bytes).map_err(|e| {
        Error::input(
            path,
            format!(
                "the scene file is not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, Rgb, ShadingMode, ShadowFilter, ShadowSettings, area_light};

    #[test]
    fn built_in_scene_loads() {
        let scene = load(&SceneSource::BuiltIn, &[]).unwrap();
        assert_eq!((scene.width, scene.height), (640, 480));
        assert_eq!(scene.meshes.len(), 2);
        assert_eq!(scene.lights.len(), 1);
    }

    #[test]
    fn overrides_reach_the_scene() {
        let sets = [
            "materials.ball.k_e=7".to_string(),
            "shading.mode=flat".to_string(),
            "lights.0.intensity=[1, 2, 3]".to_string(),
            "image.width=33".to_string(),
        ];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        let ball = scene.materials.iter().find(|m| m.name == "ball").unwrap();
        assert_eq!(ball.k_e, 7.0);
        assert_eq!(scene.shading, ShadingMode::Flat);
        assert_eq!(scene.width, 33);
        match &scene.lights[0] {
            Light::Point { intensity, .. } => assert_eq!(*intensity, Rgb::new(1.0, 2.0, 3.0)),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn shadow_keys_reach_the_scene() {
        let scene = load(&SceneSource::BuiltIn, &[]).unwrap();
        assert!(!scene.has_shadows());
        assert_eq!(scene.shadow_settings(0), ShadowSettings::default());
        let sets = [
            "lights.0.shadows=true".to_string(),
            "lights.0.shadow_map_size=1024".to_string(),
            "lights.0.shadow_filter=none".to_string(),
            "lights.0.shadow_bias=0.001".to_string(),
        ];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        assert!(scene.lights[0].casts_shadows());
        let s = scene.shadow_settings(0);
        assert_eq!(
            (s.map_size, s.filter, s.bias, s.slope_bias),
            (1024, ShadowFilter::None, 0.001, 0.0)
        );
        assert_eq!(
            s.normal_offset,
            ShadowSettings::default_normal_offset(ShadowFilter::None)
        );
        // `[shadows]` gives defaults; a light's own key wins.
        let sets = [
            "shadows.map_size=512".to_string(),
            "shadows.pcf_kernel=5".to_string(),
            "lights.0.shadow_normal_offset=3".to_string(),
        ];
        let s = load(&SceneSource::BuiltIn, &sets)
            .unwrap()
            .shadow_settings(0);
        assert_eq!(
            (s.map_size, s.filter, s.normal_offset),
            (512, ShadowFilter::Pcf { kernel: 5 }, 3.0)
        );
    }

    #[test]
    fn imported_lights_cast_shadows_when_asked() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/gltf/ShadowsDirectional/shadows-directional.gltf");
        let source = SceneSource::File(path);
        // The file's light is the scene's only light: it casts shadows by
        // default, and --verbose says so.
        let (scene, notes) = load_with_limits(&source, &[], Limits::default()).unwrap();
        assert!(scene.has_shadows());
        assert!(
            notes.iter().any(|n| n.contains("cast shadows")),
            "{notes:?}"
        );
        let off = ["shadows.imported_lights=false".to_string()];
        assert!(!load(&source, &off).unwrap().has_shadows());
        // With a light of the scene's own, the imported ones do not.
        let own = [
            "lights=[{kind = \"point\", position = [0.0, 3.0, 0.0], intensity = 1.0}]".to_string(),
        ];
        let scene = load(&source, &own).unwrap();
        assert!(!scene.lights[0].casts_shadows());
        // `lights = []` empties the scene's own lights, not the file's:
        // said, as the light is still drawn.
        let none = ["lights=[]".to_string()];
        let (scene, notes) = load_with_limits(&source, &none, Limits::default()).unwrap();
        assert_eq!(scene.lights.len(), 1);
        assert!(
            notes
                .iter()
                .any(|n| n.starts_with(WARNING) && n.contains("--set lights=[]")),
            "{notes:?}"
        );
        let (_, notes) = load_with_limits(&source, &[], Limits::default()).unwrap();
        assert!(!notes.iter().any(|n| n.contains("--set lights")));
        // A glTF without any light gets the studio, said in the notes;
        // with `gltf.default_light = "directional"` the default light.
        let bare = SceneSource::File(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gltf/Box/Box.gltf"),
        );
        let (scene, notes) = load_with_limits(&bare, &[], Limits::default()).unwrap();
        assert!(scene.lights.is_empty());
        assert_eq!(
            scene.environment.map.as_ref().unwrap().data.name,
            crate::environment::studio::STUDIO
        );
        assert!(notes.iter().any(|n| n.contains("studio")), "{notes:?}");
        let directional = ["gltf.default_light=\"directional\"".to_string()];
        let (scene, notes) = load_with_limits(&bare, &directional, Limits::default()).unwrap();
        assert_eq!(scene.lights.len(), 1);
        assert!(scene.environment.map.is_none());
        assert!(
            notes.iter().any(|n| n.contains("default light")),
            "{notes:?}"
        );
        // With an environment map it gets none (the contract), also when
        // the lights are assembled again (the viewer after an edit or a
        // reload), and the notes do not claim one.
        let sky = ["environment.map=\"sky\"".to_string()];
        let loaded = load_for_editing(&bare, &sky, Limits::default()).unwrap();
        assert!(loaded.scene.environment.map.is_some());
        assert!(loaded.scene.lights.is_empty(), "{:?}", loaded.scene.lights);
        assert!(loaded.lights.assemble().unwrap().lights.is_empty());
        assert!(
            !loaded.notes.iter().any(|n| n.contains("default light")),
            "{:?}",
            loaded.notes
        );
        // A light of the scene's own is kept beside the map.
        let sky_and_own = [sky[0].clone(), own[0].clone()];
        assert_eq!(load(&bare, &sky_and_own).unwrap().lights.len(), 1);
        let scene = load(
            &source,
            &[
                "shadows.imported_lights=true".into(),
                "shadows.filter=none".into(),
            ],
        )
        .unwrap();
        assert!(scene.lights.iter().all(Light::casts_shadows));
        assert_eq!(scene.shadow_settings(0).filter, ShadowFilter::None);
    }

    #[test]
    fn area_lights_expand_into_their_samples() {
        let light = "lights=[{kind = \"area\", shape = \"disk\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radius = 0.5, radiance = 2.0, samples = 9, shadows = true}]";
        let scene = load(&SceneSource::BuiltIn, &[light.into()]).unwrap();
        assert_eq!(scene.area_lights.len(), 1);
        assert_eq!(scene.lights.len(), 9);
        assert_eq!(scene.light_shadows.len(), 9);
        let area = std::f64::consts::PI * 0.25;
        for l in &scene.lights {
            match l {
                Light::AreaSample {
                    intensity,
                    area: 0,
                    shadows: true,
                    ..
                } => {
                    assert!((intensity.x - 2.0 * area / 9.0).abs() < 1e-12)
                }
                other => panic!("{other:?}"),
            }
        }
        let scene = load(
            &SceneSource::BuiltIn,
            &[light.into(), "lights.0.samples=64".into()],
        )
        .unwrap();
        assert_eq!(scene.lights.len(), 64);
        assert_eq!(scene.with_area_samples(4).lights.len(), 4);
        assert!(!scene.area_lights[0].shadow_per_sample);
        let sets = [light.into(), "lights.0.shadow_per_sample=true".into()];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        assert!(scene.area_lights[0].shadow_per_sample);
        assert_eq!(
            crate::gpu::shadows::ShadowPlan::new(&scene).layers.len(),
            6 * 9
        );
        let rect = "lights=[{kind = \"area\", shape = \"rect\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], size = [1.0, 2.0], tangent = [1.0, 0.0, 0.0], radiance = 1.0}]";
        let scene = load(&SceneSource::BuiltIn, &[rect.into()]).unwrap();
        assert_eq!(scene.lights.len(), area_light::DEFAULT_SAMPLES as usize);
    }

    #[test]
    fn bad_shadow_and_area_keys_are_rejected() {
        let area = |extra: &str| {
            format!(
                "lights=[{{kind = \"area\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radiance = 1.0, {extra}}}]"
            )
        };
        for kv in [
            "lights.0.shadow_map_size=8".to_string(),
            "lights.0.shadow_map_size=100000".to_string(),
            "lights.0.shadow_pcf_kernel=4".to_string(),
            "lights.0.shadow_filter=soft".to_string(),
            "lights.0.shadow_bias=-1".to_string(),
            "lights.0.shadow_normal_offset=nan".to_string(),
            "shadows.map_size=1".to_string(),
            "shadows.imported=true".to_string(),
            "lights.0.shadow_resolution=auto".to_string(),
            "shadows.texels_per_pixel=2".to_string(),
            "lights.0.shadow_texels_per_pixel=100".to_string(),
            area("shape = \"rect\", radius = 1.0"),
            area("shape = \"rect\", size = [1.0, 0.0]"),
            area("shape = \"disk\", radius = 1.0, samples = 0"),
            area("shape = \"disk\", radius = 1.0, samples = 5000"),
            area("shape = \"disk\", size = [1.0, 1.0]"),
            area("shape = \"square\", radius = 1.0"),
            area("shape = \"rect\", size = [1.0, 1.0], tangent = [0.0, 2.0, 0.0]"),
        ] {
            let err = load(&SceneSource::BuiltIn, std::slice::from_ref(&kv));
            assert!(err.is_err(), "{kv} accepted");
            assert_eq!(err.unwrap_err().exit_code(), 2, "{kv}");
        }
        for (sets, key) in [
            (
                ["shadows.resolution=fit", "shadows.texels_per_pixel=0"],
                "texels_per_pixel",
            ),
            (
                [
                    "lights.0.shadow_resolution=fit",
                    "lights.0.shadow_texels_per_pixel=17",
                ],
                "shadow_texels_per_pixel",
            ),
        ] {
            let sets = sets.map(String::from);
            let err = load(&SceneSource::BuiltIn, &sets).unwrap_err();
            assert_eq!(err.exit_code(), 2, "{sets:?}");
            assert!(err.to_string().contains(key), "{err}");
        }
        let fit = load(
            &SceneSource::BuiltIn,
            &[
                "shadows.resolution=fit".into(),
                "shadows.texels_per_pixel=0.5".into(),
            ],
        )
        .unwrap();
        assert_eq!(
            fit.shadow_settings(0).resolution,
            crate::scene::MapResolution::Fit {
                texels_per_pixel: 0.5
            }
        );
    }

    #[test]
    fn unknown_override_key_is_named() {
        let err = load(
            &SceneSource::BuiltIn,
            &["materials.ball.rougness=0.2".into()],
        )
        .unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("--set materials.ball.rougness=0.2"), "{msg}");
        assert!(msg.contains("rougness"), "{msg}");
        assert_eq!(err.exit_code(), 2);
    }

    /// `--set` reaches a material's
    /// `energy_compensation` (refused, exit 2, on a model without it) and
    /// `environment.visibility` (refused with the SH reference).
    #[test]
    fn energy_compensation_and_visibility_keys() {
        let ok = load(
            &SceneSource::BuiltIn,
            &[
                "materials.ball.model=gltf-pbr".into(),
                "materials.ball.energy_compensation=true".into(),
                "environment.map=sky".into(),
                "environment.visibility=true".into(),
            ],
        )
        .unwrap();
        assert!(ok.materials.iter().any(|m| m.energy_compensation));
        assert!(ok.environment.map.as_ref().unwrap().settings.visibility);
        for sets in [
            vec![
                "materials.ball.model=phong",
                "materials.ball.energy_compensation=true",
            ],
            vec![
                "environment.map=sky",
                "environment.reference=sh",
                "environment.visibility=true",
            ],
            vec!["environment.visibility=true"],
        ] {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let err = load(&SceneSource::BuiltIn, &sets).unwrap_err();
            let msg = err.to_string();
            assert!(
                msg.contains("energy_compensation") || msg.contains("visibility"),
                "{msg}"
            );
            assert_eq!(err.exit_code(), 2, "{msg}");
        }
    }

    #[test]
    fn bad_values_are_rejected() {
        for kv in [
            "materials.ball.k_d=nan",
            "materials.ball.k_d=-0.5",
            "materials.ball.k_e=2e6",
            "lights.0.intensity=-1",
            "image.width=0",
            "shading.mode=smooth",
            "materials.ball.model=cook-torrrance",
            "materials.ball.distribution=phong",
            "materials.ball.preset=unobtainium",
            "materials.ball.roughness=0",
            "materials.ball.kappa=-1",
            "lights.3.intensity=1",
        ] {
            assert!(
                load(&SceneSource::BuiltIn, &[kv.into()]).is_err(),
                "{kv} accepted"
            );
        }
    }

    #[test]
    fn light_entries_write_back_as_they_read() {
        let lights = "lights=[\
            {kind = \"point\", position = [0.0, 3.0, 0.0], intensity = 2, range = 9.0, shadows = true, shadow_map_size = 512, shadow_bias = 0.01, shadow_slope_bias = 1.5, shadow_normal_offset = 2.0, shadow_filter = \"pcf\", shadow_pcf_kernel = 5},\
            {kind = \"directional\", direction = [0.0, -1.0, 0.2], irradiance = [1, 2, 3], shadow_filter = \"none\"},\
            {kind = \"spot\", position = [0.0, 3.0, 0.0], direction = [0.0, -1.0, 0.0], intensity = 4.0, inner_cone_deg = 10.0, outer_cone_deg = 30.0},\
            {kind = \"area\", shape = \"rect\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], size = [1.0, 2.0], tangent = [1.0, 0.0, 0.0], radiance = 1.0, samples = 4, shadow_per_sample = true, shadows = true}]";
        let sets = [lights.to_string(), "shadows.map_size=1024".into()];
        let loaded = load_for_editing(&SceneSource::BuiltIn, &sets, Limits::default()).unwrap();
        assert_eq!(loaded.lights.entries.len(), 4);
        let mut again = loaded.lights.clone();
        for entry in &mut again.entries {
            let table = entry.to_table();
            *entry = LightEntry::deserialize(toml::Value::Table(table.clone())).unwrap();
            assert_eq!(entry.to_table(), table);
        }
        let assembled = again.assemble().unwrap();
        assert_eq!(assembled.lights, loaded.scene.lights);
        assert_eq!(assembled.light_shadows, loaded.scene.light_shadows);
        assert_eq!(assembled.area_lights, loaded.scene.area_lights);
        // An entry's own key wins over `[shadows]`, which fills the rest.
        assert_eq!(loaded.lights.shadow_settings(0).map_size, 512);
        assert_eq!(loaded.lights.shadow_settings(1).map_size, 1024);
        assert_eq!(
            loaded.lights.shadow_settings(1),
            loaded.scene.shadow_settings(1)
        );
    }

    #[test]
    fn one_list_names_the_shadow_keys_of_both_places() {
        let keys = ShadowKeys {
            map_size: Some(512),
            bias: Some(0.5),
            slope_bias: Some(1.0),
            normal_offset: Some(2.0),
            filter: Some("none".into()),
            pcf_kernel: Some(3),
            resolution: Some("fit".into()),
            texels_per_pixel: Some(0.5),
            markers: Some("cast".into()),
        };
        let section: Vec<_> = keys.to_toml(false);
        let entry: Vec<_> = keys.to_toml(true);
        assert_eq!(section.len(), 9);
        for ((short, a), (long, b)) in section.iter().zip(&entry) {
            assert_eq!(format!("shadow_{short}"), *long);
            assert_eq!(a, b);
            // Both spellings are keys the scene file accepts
            // (texels_per_pixel only beside resolution = "fit").
            for (set, fit) in [
                (format!("shadows.{short}={a}"), "shadows.resolution=fit"),
                (
                    format!("lights.0.{long}={a}"),
                    "lights.0.shadow_resolution=fit",
                ),
            ] {
                load(&SceneSource::BuiltIn, &[fit.to_string(), set]).unwrap();
            }
        }
    }
}
