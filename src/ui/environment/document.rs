//! The viewer's environment-map edits: the keys
//! of `[environment]` that choose and use a map (`map`, `scale`,
//! `sh_order`, `rotation_deg`, `specular`, `samples`, `prefilter_size`,
//! `reference`), from the panel, a `.hdr`/`.exr` dropped on the window or
//! `--edit FRAME:environment.KEY=VALUE`, and switching the map off and on
//! (`environment.enabled`, a viewer-only key).
//!
//! An edit sets the key in the document's scene table (what "Save scene"
//! writes) and reads the section back with the loader's own rules
//! ([`environment_keys`]), so a value the scene file refuses is refused
//! with the file's message. When the `map` value is unchanged the texels
//! (and their SH projection, quadrature and prefiltered stacks) are kept
//! and only the settings change: a rotation or SH-order slider redraws at
//! frame rate.
//!
//! On reload (the file changed on disk) an edited environment is kept as
//! an edited material is: the map keys as the user left them (and the map
//! switched off if it was) replace the changed file's; an environment the
//! user did not touch takes the file's new keys ([`keep_edits`]).

use crate::environment::EnvironmentMap;
use crate::scene::scene_file::diagnostics::clean_toml_error;
use crate::scene::scene_file::schema::EnvironmentSection;
use crate::scene::scene_file::{apply_override, environment_keys};
use crate::ui::document::{Document, MAP_KEYS, map_keys};
use crate::{Error, Result};
use serde::Deserialize;
use std::path::Path;

/// Whether `path` names a map file the viewer takes as the environment
/// when dropped (`.hdr`, `.exr`, any case).
pub fn is_map_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("hdr") || e.eq_ignore_ascii_case("exr"))
}

/// The edit that makes the file at `path` the map (absolute, so a saved
/// scene finds it from anywhere).
pub fn map_assignment(path: &Path) -> String {
    let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let value = toml::Value::String(path.display().to_string());
    format!("environment.map={value}")
}

/// Applies `environment.KEY=VALUE` (`assignment`) to `doc`. Editing a key
/// of a switched-off map switches it on first; choosing another
/// `specular` mode drops the other modes' `samples` and `prefilter_size`
/// (which the loader refuses beside it).
pub fn edit(doc: &mut Document, key: &str, assignment: &str) -> Result<()> {
    let bad = |problem: String| Error::argument(format!("edit {assignment}"), problem);
    if key == "enabled" {
        let (_, value) = assignment.split_once('=').unwrap_or_default();
        let on: bool = value
            .trim()
            .parse()
            .map_err(|_| bad("environment.enabled is true or false".into()))?;
        return set_enabled(doc, on).map_err(bad);
    }
    if !MAP_KEYS.contains(&key) {
        return Err(bad(format!(
            "the viewer edits environment.{} and environment.enabled",
            MAP_KEYS.join(", environment.")
        )));
    }
    let mut table = with_parked(doc);
    if key == "specular"
        && let Some(toml::Value::Table(e)) = table.get_mut("environment")
    {
        e.remove("samples");
        e.remove("prefilter_size");
    }
    apply_override(&mut table, assignment)?;
    install(doc, table).map_err(bad)?;
    doc.parked_environment = None;
    Ok(())
}

/// Switches the map off (its keys are kept aside; the scene has no map,
/// a saved file none) or back on.
pub fn set_enabled(doc: &mut Document, on: bool) -> std::result::Result<(), String> {
    if on {
        if doc.parked_environment.is_some() {
            let table = with_parked(doc);
            install(doc, table)?;
            doc.parked_environment = None;
        }
        return Ok(());
    }
    if doc.parked_environment.is_some() || doc.scene.environment.map.is_none() {
        return Ok(());
    }
    let mut parked = toml::Table::new();
    if let Some(toml::Value::Table(e)) = doc.table.get_mut("environment") {
        for key in MAP_KEYS {
            if let Some(v) = e.remove(key) {
                parked.insert(key.into(), v);
            }
        }
    }
    set_map(doc, None)?;
    doc.parked_environment = Some(parked);
    Ok(())
}

/// Gives the scene `map` and assembles its lights again: a scene without
/// lights gets the default light exactly when it has no map (the
/// contract's rule, as the loader applies it), so the viewer shows what
/// the saved file renders.
fn set_map(doc: &mut Document, map: Option<EnvironmentMap>) -> std::result::Result<(), String> {
    let mut lights = doc.lights.clone();
    lights.environment_map = map.is_some();
    lights.assemble()?.install(&mut doc.scene);
    doc.lights = lights;
    doc.scene.environment.map = map;
    crate::scene::environment_mode::choose(&mut doc.scene);
    Ok(())
}

/// Whether the map is switched off (it has keys to switch back on).
pub fn is_off(doc: &Document) -> bool {
    doc.parked_environment.is_some()
}

/// The document's table with the parked keys (if any) back in place.
fn with_parked(doc: &Document) -> toml::Table {
    let mut table = doc.table.clone();
    if let Some(parked) = &doc.parked_environment {
        let e = table
            .entry("environment")
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        if let toml::Value::Table(e) = e {
            e.extend(parked.clone());
        }
    }
    table
}

/// The `[environment]` section of `table`, read by the schema.
fn section(table: &toml::Table) -> std::result::Result<EnvironmentSection, String> {
    match table.get("environment") {
        None => Ok(EnvironmentSection::default()),
        Some(v) => EnvironmentSection::deserialize(v.clone())
            .map_err(|e| format!("environment: {}", clean_toml_error(&e))),
    }
}

/// Makes `table`'s environment the document's (its table and its scene's
/// map); on error nothing changes.
fn install(doc: &mut Document, table: toml::Table) -> std::result::Result<(), String> {
    let new = section(&table)?;
    // A glTF scene without lights shows the studio when it names no map.
    let default_map = doc
        .lights
        .default_studio
        .then_some(crate::environment::studio::STUDIO);
    let named = |s: &EnvironmentSection| s.map.clone().or(default_map.map(String::from));
    let old = section(&doc.table).ok().and_then(|s| named(&s));
    let map = match &doc.scene.environment.map {
        // The same file: keep its texels and what is derived from them.
        Some(current) if named(&new).is_some() && named(&new) == old => {
            let settings = environment_keys::settings(&new)?;
            environment_keys::check_scaled(&current.data, &settings)?;
            Some(EnvironmentMap {
                data: current.data.clone(),
                settings,
            })
        }
        _ => {
            environment_keys::environment_map(&new, &doc.source_dir, default_map, doc.limits.bytes)?
        }
    };
    set_map(doc, map)?;
    doc.table = table;
    Ok(())
}

/// Whether `doc`'s environment was edited since loading (a key changed,
/// or the map switched off).
pub fn edited(doc: &Document) -> bool {
    is_off(doc) || map_keys(&doc.table) != doc.loaded_environment
}

/// After a reload: `fresh` takes `old`'s environment if the user edited
/// it (the whole set of map keys, and off if it was off), as a reload
/// keeps an edited material whole. An edit the changed file no longer
/// accepts (the map file is gone) is dropped, as light edits are.
pub fn keep_edits(fresh: &mut Document, old: &Document) {
    if !edited(old) {
        return;
    }
    let mut table = fresh.table.clone();
    let e = table
        .entry("environment")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let toml::Value::Table(e) = e {
        for key in MAP_KEYS {
            e.remove(key);
        }
        e.extend(map_keys(&with_parked(old)));
    }
    if install(fresh, table).is_ok() && is_off(old) {
        let _ = set_enabled(fresh, false);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::map::Specular;
    use crate::scene::limits::Limits;
    use crate::scene::scene_file::SceneSource;
    use std::sync::Arc;

    fn doc() -> Document {
        Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap()
    }

    #[test]
    fn edits_set_the_map_and_its_settings_keeping_the_texels() {
        let mut d = doc();
        assert!(d.scene.environment.map.is_none());
        // A setting without a map: the loader's message.
        let e = d.edit("environment.sh_order=3").unwrap_err().to_string();
        assert!(e.contains("no environment.map"), "{e}");
        d.edit("environment.map=sky").unwrap();
        let texels = d.scene.environment.map.as_ref().unwrap().data.clone();
        d.edit("environment.sh_order=4").unwrap();
        d.edit("environment.rotation_deg=90").unwrap();
        d.edit("environment.specular=sampled").unwrap();
        d.edit("environment.samples=16").unwrap();
        let m = d.scene.environment.map.as_ref().unwrap();
        assert!(Arc::ptr_eq(&m.data, &texels));
        assert_eq!(
            (
                m.settings.sh_order,
                m.settings.rotation_deg,
                m.settings.samples
            ),
            (4, 90.0, 16)
        );
        // Another mode drops `samples` (refused beside it).
        d.edit("environment.specular=sh").unwrap();
        let m = d.scene.environment.map.as_ref().unwrap();
        assert_eq!(m.settings.specular, Specular::Sh);
        assert!(d.table["environment"].get("samples").is_none());
        // Bad values are refused and change nothing.
        for bad in [
            "environment.sh_order=9",
            "environment.specular=\"glossy\"",
            "environment.samples=16",
            "environment.zenith=[1, 1, 1]",
            "environment.map=\"missing.hdr\"",
        ] {
            assert!(d.edit(bad).is_err(), "{bad}");
        }
        assert_eq!(
            d.scene.environment.map.as_ref().unwrap().settings.sh_order,
            4
        );
    }

    #[test]
    fn the_map_switches_off_and_on_and_saves_as_shown() {
        let mut d = doc();
        d.edit("environment.map=sky").unwrap();
        d.edit("environment.scale=0.5").unwrap();
        d.edit("environment.enabled=false").unwrap();
        assert!(d.scene.environment.map.is_none() && is_off(&d));
        let saved = crate::ui::save::scene_file_text(&d).unwrap();
        assert!(!saved.contains("sky"), "{saved}");
        d.edit("environment.enabled=true").unwrap();
        let m = d.scene.environment.map.as_ref().unwrap();
        assert_eq!(m.settings.scale, 0.5);
        let saved = crate::ui::save::scene_file_text(&d).unwrap();
        assert!(
            saved.contains("map = \"sky\"") && saved.contains("scale = 0.5"),
            "{saved}"
        );
        // Editing a key of a switched-off map switches it on.
        d.edit("environment.enabled=false").unwrap();
        d.edit("environment.sh_order=1").unwrap();
        assert!(!is_off(&d));
        assert_eq!(
            d.scene.environment.map.as_ref().unwrap().settings.sh_order,
            1
        );
        assert!(d.edit("environment.enabled=maybe").is_err());
    }

    /// A reload keeps an edited environment whole (the file's changes to
    /// it are not taken, as for an edited material), takes the file's new
    /// keys when the environment was not edited, and keeps a switched-off
    /// map off.
    #[test]
    fn reload_keeps_environment_edits_as_material_edits() {
        let dir = std::env::temp_dir().join(format!("gonio-env-reload-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.toml");
        let write = |scale: f64, k_d: f64| {
            let text = format!(
                "[[objects]]\nshape = \"sphere\"\nmaterial = \"ball\"\n\n[materials.ball]\nmodel = \"lambert\"\nk_d = {k_d}\n\n[environment]\nmap = \"sky\"\nscale = {scale}\n"
            );
            std::fs::write(&path, text).unwrap();
        };
        write(0.3, 0.5);
        let load =
            || Document::load(SceneSource::File(path.clone()), vec![], Limits::default()).unwrap();
        let settings = |d: &Document| d.scene.environment.map.as_ref().map(|m| m.settings);
        // Not edited: the file's new scale.
        let d = load();
        assert!(!edited(&d));
        write(0.7, 0.5);
        let r = d.reload().unwrap();
        assert_eq!(settings(&r).unwrap().scale, 0.7);
        // Edited: the user's keys, whole (the file's new scale is not taken),
        // beside the file's new material.
        let mut d = load();
        d.edit("environment.rotation_deg=90").unwrap();
        d.edit("environment.specular=sampled").unwrap();
        d.edit("environment.samples=16").unwrap();
        assert!(edited(&d));
        write(0.2, 0.25);
        let r = d.reload().unwrap();
        let s = settings(&r).unwrap();
        assert_eq!(
            (s.rotation_deg, s.scale, s.samples, s.specular),
            (90.0, 0.7, 16, Specular::Sampled)
        );
        assert_eq!(r.scene.materials[0].k_d.x, 0.25);
        assert!(
            edited(&r),
            "the kept edit is still an edit (saved, kept again)"
        );
        // Switched off: stays off, and on again with the user's keys.
        let mut d = load();
        d.edit("environment.scale=0.9").unwrap();
        d.edit("environment.enabled=false").unwrap();
        write(0.1, 0.25);
        let mut r = d.reload().unwrap();
        assert!(r.scene.environment.map.is_none() && is_off(&r));
        r.edit("environment.enabled=true").unwrap();
        assert_eq!(settings(&r).unwrap().scale, 0.9);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn dropped_map_files_are_recognized() {
        assert!(is_map_file(Path::new("/a/sky.HDR")) && is_map_file(Path::new("b.exr")));
        assert!(!is_map_file(Path::new("scene.toml")) && !is_map_file(Path::new("hdr")));
        // Quotes in a path survive the assignment's TOML.
        let path = "/maps/a \"b\" 'c'.hdr";
        let mut table = toml::Table::new();
        apply_override(&mut table, &map_assignment(Path::new(path))).unwrap();
        assert_eq!(table["environment"]["map"].as_str(), Some(path));
    }
}
