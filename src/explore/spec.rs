//! Materials from the command line, parsed exactly as a scene file's
//! `[materials.NAME]` table: the `KEY=VALUE` pairs become a TOML table, which
//! the scene-file parser (`MaterialEntry`, `material_from_entry`) turns into
//! a validated [`Material`]. Key names, defaults, presets, validation and
//! the wording of errors are therefore the scene file's.
//!
//! A *material spec* is `MODEL[,KEY=VALUE]...`, e.g.
//! `cook-torrance,preset=gold,roughness=0.1` or `phong,k_e=50,k_d=[0.1,0.2,0.3]`
//! (commas inside `[...]` belong to the value).

use super::Labelled;
use crate::material::{Material, ReflectanceModel};
use crate::material::{MaterialEntry, material_from_entry};
use crate::scene::scene_file::apply_override;
use crate::{Error, Result};
use serde::Deserialize;

/// The material `model` with the shared `--set` assignments, then the
/// spec's own `own` assignments (which win), for the argument called
/// `argument` in errors. Its label is the model followed by its own keys.
pub fn material(
    argument: &str,
    model: &str,
    shared: &[String],
    own: &[String],
) -> Result<Labelled> {
    let bad = |problem: String| Error::argument(argument, problem);
    model.parse::<ReflectanceModel>().map_err(bad)?;
    let label = std::iter::once(model.to_string())
        .chain(own.iter().map(|kv| compact(kv)))
        .collect::<Vec<_>>()
        .join(" ");
    let mut table = toml::Table::new();
    table.insert("model".into(), toml::Value::String(model.into()));
    for (kv, arg) in shared
        .iter()
        .map(|kv| (kv, format!("--set {kv}")))
        .chain(own.iter().map(|kv| (kv, format!("{argument} (`{kv}`)"))))
    {
        let key = kv.split_once('=').map_or(kv.as_str(), |(k, _)| k.trim());
        if key == "model" {
            return Err(Error::argument(
                arg,
                "the model is chosen by --model or the first word of a --compare spec",
            ));
        }
        if key.contains('.') {
            return Err(Error::argument(
                arg,
                format!(
                    "`{key}` is a dotted path; `gonio brdf` takes a material's own keys, e.g. `k_e=80` (not `materials.ball.k_e=80`)"
                ),
            ));
        }
        apply_override(&mut table, kv)?;
        // Deserialize after each assignment, so an error names its culprit.
        MaterialEntry::deserialize(toml::Value::Table(table.clone()))
            .map_err(|e| Error::argument(arg, one_line(&e.to_string())))?;
    }
    // A bare `measured` plots the material the viewer starts a measured
    // material as (measured::DEFAULT_NAME), and says so; a scene file
    // still names its table (its error says how).
    if model == ReflectanceModel::Measured.name() && !table.contains_key("measured") {
        let default = crate::material::measured::DEFAULT_NAME;
        let hint = if argument.starts_with("--compare") {
            format!("`{argument},measured=chrome`")
        } else {
            "`--set measured=chrome`".to_string()
        };
        eprintln!(
            "gonio: note: {argument}: no `measured=NAME` given; plotting measured={default} (the default, as in the viewer); name another with e.g. {hint}"
        );
        table.insert("measured".into(), toml::Value::String(default.into()));
    }
    let entry = MaterialEntry::deserialize(toml::Value::Table(table))
        .map_err(|e| bad(one_line(&e.to_string())))?;
    // As `render` warns of a scene file's key the model does not read
    // (`brdf --model lambert --set k_e=50` once said nothing).
    let unread = crate::material::entry::keys_not_applying(&entry);
    if !unread.is_empty() {
        let params: Vec<&str> = entry
            .model
            .parse::<ReflectanceModel>()
            .map(|m| m.row().params.iter().map(|p| p.key).collect())
            .unwrap_or_default();
        eprintln!(
            "gonio: warning: {argument}: {} not read by model `{model}` (its parameters: {}); ignored",
            unread
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", "),
            params.join(", ")
        );
    }
    let given: Material = material_from_entry(&label, &entry).map_err(bad)?;
    // The spectral Fresnel is the reference renderer's (`reference`, a
    // layer the explorer does not use); here the metal's preset, with a
    // word.
    if let Some(metal) = given.spectral_metal {
        eprintln!(
            "gonio: note: {label}: spectral_metal = \"{metal}\" is evaluated with its three-channel preset `{}` here; the spectral Fresnel of the published table is the reference renderer's (`gonio render --reference`)",
            metal.preset_name()
        );
    }
    // The renderers evaluate roughness no smaller than the floor (f32's
    // range on the GPU); `gonio brdf` shows what they render, and says so.
    let material = given.with_roughness_floor(0.0);
    for (key, was, is) in [
        ("roughness", given.roughness, material.roughness),
        ("sigma_x", given.sigma_x, material.sigma_x),
        ("sigma_y", given.sigma_y, material.sigma_y),
    ] {
        let used = material.model.row().params.iter().any(|p| p.key == key);
        if used && was != is {
            eprintln!(
                "gonio: note: {label}: {key} = {was:e} is below the roughness floor; evaluated as {is:e}, as the renderers do"
            );
        }
    }
    Ok(Labelled { label, material })
}

/// Parses a `--compare` spec `MODEL[,KEY=VALUE]...` with the shared `--set`
/// assignments underneath.
pub fn compare_spec(spec: &str, shared: &[String]) -> Result<Labelled> {
    let argument = format!("--compare {spec}");
    let mut parts = split_top_level(spec).into_iter();
    let model = parts.next().unwrap_or_default();
    if model.is_empty() || model.contains('=') {
        return Err(Error::argument(
            argument,
            "a material spec starts with the model, e.g. `cook-torrance,preset=gold,roughness=0.1`",
        ));
    }
    let own: Vec<String> = parts.collect();
    if let Some(empty) = own.iter().find(|kv| !kv.contains('=')) {
        return Err(Error::argument(
            argument,
            format!("`{empty}` is not KEY=VALUE (items are separated by commas)"),
        ));
    }
    material(&argument, &model, shared, &own)
}

/// Splits at commas outside brackets and quotes, trimming each part.
fn split_top_level(spec: &str) -> Vec<String> {
    let (mut parts, mut current, mut depth, mut quoted) = (Vec::new(), String::new(), 0i32, false);
    for c in spec.chars() {
        match c {
            '"' | '\'' => quoted = !quoted,
            '[' if !quoted => depth += 1,
            ']' if !quoted => depth -= 1,
            ',' if depth <= 0 && !quoted => {
                parts.push(current.trim().to_string());
                current.clear();
                continue;
            }
            _ => {}
        }
        current.push(c);
    }
    parts.push(current.trim().to_string());
    parts
}

/// `k_d = [0.1, 0.2]` → `k_d=[0.1,0.2]`: short labels for legends.
fn compact(kv: &str) -> String {
    kv.chars().filter(|c| !c.is_whitespace()).collect()
}

/// toml's messages can span lines; errors are one paragraph.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Distribution, Fresnel};
    use crate::scene::Rgb;

    #[test]
    fn specs_parse_like_scene_materials() {
        let m = compare_spec(
            "cook-torrance, preset=gold, roughness=0.1, distribution=ggx, k_d=[0.1, 0.2, 0.3]",
            &["k_s=0.5".into()],
        )
        .unwrap();
        assert_eq!(m.material.model, ReflectanceModel::CookTorrance);
        assert_eq!(m.material.roughness, 0.1);
        assert_eq!(m.material.distribution, Distribution::Ggx);
        assert_eq!(m.material.fresnel, Fresnel::Conductor);
        assert_eq!(m.material.k_d, Rgb::new(0.1, 0.2, 0.3));
        assert_eq!(m.material.k_s, Rgb::splat(0.5));
        assert_eq!(
            m.label,
            "cook-torrance preset=gold roughness=0.1 distribution=ggx k_d=[0.1,0.2,0.3]"
        );
    }

    #[test]
    fn own_keys_win_over_shared_ones() {
        let m = compare_spec("phong,k_e=5", &["k_e=80".into()]).unwrap();
        assert_eq!(m.material.k_e, 5.0);
    }

    #[test]
    fn errors_name_the_culprit() {
        let cases = [
            ("phonk", vec![], "unknown reflectance model `phonk`"),
            (
                "phong",
                vec!["rougness=0.2".to_string()],
                "--set rougness=0.2",
            ),
            (
                "phong",
                vec!["k_e=2e6".to_string()],
                "k_e = 2000000 is outside",
            ),
            (
                "phong",
                vec!["materials.x.k_e=2".to_string()],
                "dotted path",
            ),
            ("phong", vec!["model=ward".to_string()], "--set model=ward"),
            (
                "cook-torrance",
                vec!["distribution=phong".to_string()],
                "unknown distribution",
            ),
        ];
        for (model, sets, expected) in cases {
            let err = material(&format!("--model {model}"), model, &sets, &[]).unwrap_err();
            let text = err.to_string();
            assert!(text.contains(expected), "{model} {sets:?}: {text}");
            assert!(!text.contains('\n'), "{text}");
            assert_eq!(err.exit_code(), 2);
        }
        assert!(compare_spec("k_e=3,phong", &[]).is_err());
        assert!(compare_spec("phong,k_e", &[]).is_err());
    }
}
