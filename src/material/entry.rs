//! A material's text form: the keys of a scene file's `[materials.NAME]`
//! table (also `gonio brdf --set` and `--compare`), and their validation
//! into a [`Material`]. The keys and their types come from the table of
//! models ([`super::table`]): `model`, `preset`, the term names and every
//! model's parameters.

use super::conductors::Metal;
use super::param::{Kind, Param, Value};
use super::{Material, ReflectanceModel, measured, presets, spectral_metal, table};
use crate::base::{ColorValue, rgb_to_toml};
use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, Visitor};
use std::path::Path;
use std::sync::LazyLock;
use toml::Value as Toml;

/// The keys of the selectable terms (`material/terms.rs`).
const TERM_KEYS: [&str; 4] = ["distribution", "geometry", "fresnel", "denominator"];

/// `[materials.NAME]`: the model, an optional preset (the lecture's tables
/// or a coloured conductor, [`super::presets`]), then any parameter or term
/// (given keys override the preset and the model's default `k_d`, `k_s`,
/// which follow the preset and terms: [`super::weights`]).
/// Keys of another model than the given one are accepted (and kept for
/// when the material switches models).
#[derive(Clone, Debug, Default)]
pub struct MaterialEntry {
    pub model: String,
    pub preset: Option<String>,
    /// Parameters as given, by key, of the type the table says.
    pub params: Vec<(String, Value)>,
    /// Terms as given: (key, name).
    pub terms: Vec<(&'static str, String)>,
    /// `measured = NAME|PATH` as given (model `measured`).
    pub measured: Option<String>,
    /// `spectral_metal = NAME` as given (a conductor whose Fresnel the
    /// reference evaluates spectrally, [`super::spectral_metal`]).
    pub spectral_metal: Option<String>,
    /// Textures as given: (`PARAM_texture` key, image path as written).
    /// The scene file resolves the paths (`scene_file::textures`).
    pub textures: Vec<(String, String)>,
    /// `energy_compensation = true|false` as given (the microfacet
    /// models' multiple-scattering compensation, `brdf::energy`).
    pub energy_compensation: Option<bool>,
}

/// The key of energy compensation (a boolean, default false; validated
/// against the model by `Material::validate`).
pub const ENERGY_COMPENSATION_KEY: &str = "energy_compensation";

/// The suffix that turns a parameter's key into its texture's key.
pub const TEXTURE_SUFFIX: &str = "_texture";

/// Texture keys that scale no parameter: `normal_texture` (the
/// contract's tangent-space normal map, glTF's encoding, scale 1),
/// `occlusion_texture` (glTF's occlusion on the ambient and environment
/// terms, R, strength 1), `clearcoat_normal_texture` (the coat's own
/// normal map, `gltf-pbr`) and `anisotropy_texture`
/// (`KHR_materials_anisotropy`'s direction and strength, `gltf-pbr`).
pub const MAP_TEXTURE_KEYS: [&str; 4] = [
    "normal_texture",
    "occlusion_texture",
    "clearcoat_normal_texture",
    "anisotropy_texture",
];

/// The parameter a map texture needs its model to have (it acts on that
/// layer: none for the normal and occlusion maps, which every model
/// takes).
pub fn map_texture_layer(key: &str) -> Option<&'static str> {
    match key {
        "clearcoat_normal_texture" => Some("clearcoat"),
        "anisotropy_texture" => Some("anisotropy_strength"),
        _ => None,
    }
}

/// Whether `key` is `PARAM_texture` for some parameter of the table, or
/// one of [`MAP_TEXTURE_KEYS`].
pub fn is_texture_key(key: &str) -> bool {
    MAP_TEXTURE_KEYS.contains(&key)
        || key
            .strip_suffix(TEXTURE_SUFFIX)
            .is_some_and(|p| table::all_params().iter().any(|q| q.key == p))
}

/// Every key a `[materials.NAME]` table accepts, in the order errors list
/// them.
static KEYS: LazyLock<Vec<&'static str>> = LazyLock::new(|| {
    let mut keys = vec!["model", "preset", spectral_metal::KEY];
    for p in table::all_params() {
        if !keys.contains(&p.key) {
            keys.push(p.key);
        }
    }
    keys.extend(TERM_KEYS);
    keys.push("measured");
    keys.push(ENERGY_COMPENSATION_KEY);
    keys
});

/// Every key a `[materials.NAME]` table accepts (`model`, `preset`, each
/// model's parameters, the terms).
pub fn keys() -> &'static [&'static str] {
    &KEYS
}

impl<'de> Deserialize<'de> for MaterialEntry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(EntryVisitor)
    }
}

struct EntryVisitor;

impl<'de> Visitor<'de> for EntryVisitor {
    type Value = MaterialEntry;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a material table (`model = ...` and its parameters)")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<MaterialEntry, A::Error> {
        let mut model = None;
        let mut entry = MaterialEntry::default();
        while let Some(key) = map.next_key::<String>()? {
            let duplicate = |seen: bool| {
                if seen {
                    Err(de::Error::custom(format!("duplicate key `{key}`")))
                } else {
                    Ok(())
                }
            };
            match key.as_str() {
                "model" => {
                    duplicate(model.is_some())?;
                    model = Some(map.next_value::<String>()?);
                }
                "preset" => {
                    duplicate(entry.preset.is_some())?;
                    entry.preset = Some(map.next_value::<String>()?);
                }
                "measured" => {
                    duplicate(entry.measured.is_some())?;
                    entry.measured = Some(map.next_value::<String>()?);
                }
                spectral_metal::KEY => {
                    duplicate(entry.spectral_metal.is_some())?;
                    entry.spectral_metal = Some(map.next_value::<String>()?);
                }
                ENERGY_COMPENSATION_KEY => {
                    duplicate(entry.energy_compensation.is_some())?;
                    entry.energy_compensation = Some(map.next_value::<bool>()?);
                }
                k if TERM_KEYS.contains(&k) => {
                    let k = TERM_KEYS.into_iter().find(|t| *t == k).unwrap_or_default();
                    duplicate(entry.terms.iter().any(|(t, _)| *t == k))?;
                    entry.terms.push((k, map.next_value::<String>()?));
                }
                k if is_texture_key(k) => {
                    duplicate(entry.textures.iter().any(|(t, _)| t == k))?;
                    entry
                        .textures
                        .push((key.clone(), map.next_value::<String>()?));
                }
                k => {
                    // A key's type is the same for every parameter of that
                    // key (checked by the table's tests).
                    let kind = table::all_params()
                        .into_iter()
                        .find(|p| p.key == k)
                        .map(|p| p.kind)
                        .ok_or_else(|| de::Error::unknown_field(k, &KEYS))?;
                    duplicate(entry.params.iter().any(|(p, _)| p == k))?;
                    let value = match kind {
                        Kind::Color => Value::Color(map.next_value::<ColorValue>()?.rgb()),
                        Kind::Scalar => Value::Scalar(map.next_value::<f64>()?),
                    };
                    entry.params.push((key, value));
                }
            }
        }
        entry.model = model.ok_or_else(|| de::Error::missing_field("model"))?;
        Ok(entry)
    }
}

/// The validated material of entry `e`, named `name` (messages name the
/// key as `materials.NAME.KEY`); a `measured` path is relative to the
/// working directory.
pub fn material_from_entry(name: &str, e: &MaterialEntry) -> std::result::Result<Material, String> {
    material_from_entry_in(name, e, Path::new(""))
}

/// [`material_from_entry`] for an entry of a file in `base_dir`: a
/// `measured` path is relative to it.
pub fn material_from_entry_in(
    name: &str,
    e: &MaterialEntry,
    base_dir: &Path,
) -> std::result::Result<Material, String> {
    let model: ReflectanceModel = e
        .model
        .parse()
        .map_err(|p| format!("materials.{name}.model: {p}"))?;
    let mut m = Material::new(name, model);
    let key = |k: &str| format!("materials.{name}.{k}");
    if model == ReflectanceModel::Measured {
        measured_keys_apply(e).map_err(|(k, p)| format!("{}: {p}", key(k)))?;
    }
    if let Some(text) = &e.measured {
        m.measured = Some(
            measured::resolve(text, base_dir).map_err(|p| format!("{}: {p}", key("measured")))?,
        );
    }
    if let Some(p) = &e.preset {
        presets::preset(p)
            .map_err(|p| format!("{}: {p}", key("preset")))?
            .apply(&mut m);
    }
    for (k, text) in &e.terms {
        set_term(&mut m, k, text).map_err(|p| format!("{}: {p}", key(k)))?;
    }
    if let Some(metal) =
        spectral_metal_of(e, model).map_err(|p| format!("{}: {p}", key(spectral_metal::KEY)))?
    {
        spectral_metal::set(&mut m, metal);
    }
    // The model's default k_d, k_s for the preset and terms now set (a
    // metal preset on Cook-Torrance: a bare metal; `weights.rs`); the
    // keys given win below.
    (m.k_d, m.k_s) = (model.row().weights)(&m);
    // In the table's key order, whatever the file's: a key that sets
    // several fields (Ward's `sigma`) comes before the ones that set one
    // of them (`sigma_x`), which then win.
    for &k in KEYS.iter() {
        if let Some((_, v)) = e.params.iter().find(|(p, _)| p == k)
            && let Some(p) = table::param_for(model, k)
        {
            p.write(&mut m, *v);
        }
    }
    if let Some(on) = e.energy_compensation {
        m.energy_compensation = on;
    }
    m.validate()?;
    Ok(m)
}

/// The metal of `e`'s `spectral_metal` checked against its other keys
/// ([`spectral_metal::check_keys`]); `None` without the key or on a model
/// that does not read it (a warning: [`keys_not_applying`]).
fn spectral_metal_of(e: &MaterialEntry, model: ReflectanceModel) -> Result<Option<Metal>, String> {
    let Some(text) = &e.spectral_metal else {
        return Ok(None);
    };
    let metal: Metal = text.parse()?;
    if !spectral_metal::applies(model) {
        return Ok(None);
    }
    let given =
        |k: &str| e.params.iter().any(|(p, _)| p == k) || e.textures.iter().any(|(t, _)| t == k);
    let fresnel = e
        .terms
        .iter()
        .find(|(k, _)| *k == "fresnel")
        .map(|(_, f)| f.as_str());
    spectral_metal::check_keys(metal, e.preset.as_deref(), given, fresnel)?;
    Ok(Some(metal))
}

/// The parameter keys of `e` that its model does not read (`sigma_x` on
/// `ward`, `roughness` on `blinn-phong`, `k_e` on `lambert`): accepted, so
/// a material can switch models in the viewer and back, but worth a
/// warning (they were once ignored without a word). `measured`
/// refuses them instead (`measured_keys_apply`).
pub fn keys_not_applying(e: &MaterialEntry) -> Vec<&str> {
    let Ok(model) = e.model.parse::<ReflectanceModel>() else {
        return Vec::new();
    };
    let row = model.row();
    let applies = |k: &str| {
        table::COMMON
            .iter()
            .chain(row.params.iter())
            .any(|p| p.key == k)
    };
    // A texture on a parameter the model does not read is as ignored as
    // the parameter (`k_e_texture` on `lambert`); so is a map
    // of a layer the model does not have (`anisotropy_texture` on `ward`).
    let textured =
        e.textures
            .iter()
            .map(|(k, _)| k.as_str())
            .filter(|k| match map_texture_layer(k) {
                Some(layer) => !applies(layer),
                None => {
                    !MAP_TEXTURE_KEYS.contains(k)
                        && k.strip_suffix(TEXTURE_SUFFIX).is_some_and(|p| !applies(p))
                }
            });
    let metal = e
        .spectral_metal
        .as_ref()
        .filter(|_| !spectral_metal::applies(model))
        .map(|_| spectral_metal::KEY);
    e.params
        .iter()
        .map(|(k, _)| k.as_str())
        .filter(|k| !applies(k))
        .chain(textured)
        .chain(metal)
        .collect()
}

/// For a `measured` material: the `measured` key is given, and no key a
/// measured BRDF does not read (its `f_r` is the data's, in 1/sr; `k_a`,
/// the ambient term, still applies). Else the key and the problem.
fn measured_keys_apply(e: &MaterialEntry) -> Result<(), (&str, String)> {
    let not_read = |k| {
        (
            k,
            "does not apply to model `measured` (its f_r is the measured data, in 1/sr; only `measured` and `k_a` apply); remove it".to_string(),
        )
    };
    if e.preset.is_some() {
        return Err(not_read("preset"));
    }
    if e.spectral_metal.is_some() {
        return Err(not_read(spectral_metal::KEY));
    }
    if let Some((k, _)) = e
        .params
        .iter()
        .find(|(k, _)| !table::COMMON.iter().any(|p| p.key == k))
    {
        return Err(not_read(k));
    }
    if let Some((k, _)) = e.terms.first() {
        return Err(not_read(k));
    }
    // A texture multiplies its parameter: on one the measured BRDF does
    // not read it is refused as the parameter is (`k_d_texture`).
    if let Some((k, _)) = e.textures.iter().find(|(k, _)| {
        !MAP_TEXTURE_KEYS.contains(&k.as_str())
            && k.strip_suffix(TEXTURE_SUFFIX)
                .is_some_and(|p| !table::COMMON.iter().any(|c| c.key == p))
    }) {
        return Err(not_read(k));
    }
    if e.measured.is_none() {
        return Err((
            "measured",
            format!(
                "model `measured` needs `measured = NAME` (a built-in MERL material, e.g. \"{}\") or `measured = \"path/file.binary\"` (a MERL table, relative to the scene file)",
                measured::DEFAULT_NAME
            ),
        ));
    }
    Ok(())
}

/// `m` with `key` set to `value` as a scene file would give it (the
/// viewer's edits; `k_d`, `k_s` left at their defaults follow it:
/// [`Material::follow_default_weights`]), validated; messages name `materials.NAME.KEY` (a
/// `measured` path is relative to the working directory).
pub fn with_key(m: &Material, key: &str, value: Toml) -> Result<Material, String> {
    let name = &m.name;
    let bad = |problem: String| format!("materials.{name}.{key}: {problem}");
    let typed = |e: toml::de::Error| bad(e.message().to_string());
    let mut out = m.clone();
    let before = (m.model.row().weights)(m);
    match key {
        "model" => {
            let text: String = value.try_into().map_err(typed)?;
            out.model = text.parse().map_err(bad)?;
            // A model without energy compensation drops it (switching a
            // compensated gltf-pbr material to phong in the viewer).
            out.energy_compensation &= out.model.row().energy_compensation;
        }
        "preset" => {
            let text: String = value.try_into().map_err(typed)?;
            presets::preset(&text).map_err(bad)?.apply(&mut out);
        }
        "measured" => {
            let text: String = value.try_into().map_err(typed)?;
            out.measured = Some(measured::resolve(&text, Path::new("")).map_err(bad)?);
        }
        spectral_metal::KEY => {
            let text: String = value.try_into().map_err(typed)?;
            let metal: Metal = text.parse().map_err(bad)?;
            if !spectral_metal::applies(out.model) {
                return Err(bad(format!(
                    "model `{}` has no Fresnel term; `{}` applies to the models with one ({})",
                    out.model.name(),
                    spectral_metal::KEY,
                    fresnel_models()
                )));
            }
            spectral_metal::set(&mut out, metal);
        }
        k if TERM_KEYS.contains(&k) => {
            let text: String = value.try_into().map_err(typed)?;
            set_term(&mut out, k, &text).map_err(bad)?;
        }
        ENERGY_COMPENSATION_KEY => {
            out.energy_compensation = value.try_into().map_err(typed)?;
        }
        k => {
            let p = table::param_for(m.model, k).ok_or_else(|| {
                bad(format!(
                    "unknown key; expected one of {}",
                    KEYS.iter()
                        .map(|k| format!("`{k}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })?;
            let v = match p.kind {
                Kind::Color => Value::Color(value.try_into::<ColorValue>().map_err(typed)?.rgb()),
                Kind::Scalar => Value::Scalar(value.try_into::<f64>().map_err(typed)?),
            };
            p.write(&mut out, v);
        }
    }
    // An edit of η, κ, the preset or the Fresnel term away from the
    // spectral metal's leaves the three channels it set.
    if !spectral_metal::still_holds(&out) {
        out.spectral_metal = None;
    }
    // Weights left at their defaults follow the edit, as a scene file's
    // `--set` of the same key would have them.
    out.follow_default_weights(before);
    out.validate()?;
    Ok(out)
}

/// The models that read `spectral_metal`, as a list for messages.
fn fresnel_models() -> String {
    table::ROWS
        .iter()
        .filter(|r| spectral_metal::applies(r.model))
        .map(|r| format!("`{}`", r.model.name()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Sets the term `key` (`distribution`, ...) of `m` from its name.
pub fn set_term(m: &mut Material, key: &str, name: &str) -> Result<(), String> {
    match key {
        "distribution" => m.distribution = name.parse()?,
        "geometry" => m.geometry = name.parse()?,
        "fresnel" => m.fresnel = name.parse()?,
        "denominator" => m.denominator = name.parse()?,
        _ => return Err(format!("`{key}` is not a term")),
    }
    Ok(())
}

/// Every field of `m` under its scene-file key (no preset: the values
/// it set are written out). A parameter is written under its key only when
/// that key reads back as the same parameter for `m`'s model.
pub fn material_table(m: &Material) -> toml::Table {
    let mut t = toml::Table::new();
    t.insert("model".into(), Toml::String(m.model.name().into()));
    if m.model == ReflectanceModel::Measured {
        // Only what applies (`measured_keys_apply`).
        for p in table::COMMON {
            t.insert(p.key.into(), text_value(p, m));
        }
        let brdf = m.measured.unwrap_or_else(measured::default_brdf);
        t.insert("measured".into(), Toml::String(brdf.key_text().into()));
        return t;
    }
    // The model's own parameters, each through its own accessor
    // (gltf-pbr's `roughness` is the perceptual r, not a stored field of
    // its own: Save scene dropped it), and its own terms: only what the
    // model reads, so the file reads back without a warning (before,
    // `gonio fit -o f.toml` wrote 8 keys `render f.toml` warned about).
    let row = m.model.row();
    // A spectral metal is written by its name; its η, κ (the preset's)
    // follow from it, and the key refuses them beside it.
    let metal = m
        .spectral_metal
        .filter(|_| spectral_metal::applies(m.model));
    if let Some(metal) = metal {
        t.insert(
            spectral_metal::KEY.into(),
            Toml::String(metal.name().into()),
        );
    }
    for p in table::COMMON.iter().chain(row.params.iter()) {
        if metal.is_some() && (p.key == "eta" || p.key == "kappa") {
            continue;
        }
        t.insert(p.key.into(), text_value(p, m));
    }
    for (key, has, name) in [
        (
            "distribution",
            row.terms.distribution,
            m.distribution.name(),
        ),
        ("geometry", row.terms.geometry, m.geometry.name()),
        ("fresnel", row.terms.fresnel, m.fresnel.name()),
        ("denominator", row.terms.denominator, m.denominator.name()),
    ] {
        if has {
            t.insert(key.into(), Toml::String(name.into()));
        }
    }
    if m.model.row().energy_compensation {
        t.insert(
            ENERGY_COMPENSATION_KEY.into(),
            Toml::Boolean(m.energy_compensation),
        );
    }
    t
}

/// `p`'s value in `m` as TOML.
fn text_value(p: &Param, m: &Material) -> Toml {
    match p.read(m) {
        Value::Color(v) => rgb_to_toml(v),
        Value::Scalar(v) => Toml::Float(v),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saved_material_reads_back_equal() {
        let mut m = Material::new("m", ReflectanceModel::WardAnisotropic);
        (m.sigma_x, m.sigma_y) = (0.1, 0.4);
        let entry = MaterialEntry::deserialize(Toml::Table(material_table(&m))).unwrap();
        assert_eq!(material_from_entry("m", &entry).unwrap(), m);
        // Every model's table holds only keys it reads (no warning when
        // read back), and reads back to the same table.
        for model in ReflectanceModel::ALL {
            let mut m = Material::new("m", model);
            (m.k_e, m.sigma_x) = (7.0, 0.3);
            m.distribution = super::super::Distribution::Ggx;
            if model == ReflectanceModel::Measured {
                m.measured = Some(measured::default_brdf());
            }
            let written = material_table(&m);
            let entry = MaterialEntry::deserialize(Toml::Table(written.clone())).unwrap();
            assert!(keys_not_applying(&entry).is_empty(), "{model}: {written:?}");
            let back = material_from_entry("m", &entry).unwrap();
            assert_eq!(material_table(&back), written, "{model}");
        }
    }

    /// `energy_compensation`: a boolean, saved and read back, refused
    /// with the reason on a model without it, dropped when the viewer
    /// switches a compensated material to such a model.
    #[test]
    fn energy_compensation_is_a_validated_boolean() {
        let entry = |text: &str| MaterialEntry::deserialize(text.parse::<toml::Table>().unwrap());
        let m = material_from_entry(
            "m",
            &entry("model = \"gltf-pbr\"\nenergy_compensation = true").unwrap(),
        )
        .unwrap();
        assert!(m.energy_compensation);
        let back = MaterialEntry::deserialize(Toml::Table(material_table(&m))).unwrap();
        assert_eq!(material_from_entry("m", &back).unwrap(), m);
        let off = material_from_entry("m", &entry("model = \"cook-torrance\"").unwrap()).unwrap();
        assert!(!off.energy_compensation);
        let e = material_from_entry(
            "m",
            &entry("model = \"phong\"\nenergy_compensation = true").unwrap(),
        )
        .unwrap_err();
        assert!(
            e.contains("energy_compensation") && e.contains("`phong` has no energy compensation"),
            "{e}"
        );
        assert!(entry("model = \"gltf-pbr\"\nenergy_compensation = 1").is_err());
        let switched = with_key(&m, "model", Toml::String("phong".into())).unwrap();
        assert!(!switched.energy_compensation);
        let on = with_key(&off, ENERGY_COMPENSATION_KEY, Toml::Boolean(true)).unwrap();
        assert!(on.energy_compensation);
    }

    /// `spectral_metal`: sets the metal's preset and the exact conductor
    /// Fresnel, accepts its own preset beside it, refuses what it would
    /// make the reference ignore and a bad name (listing the metals),
    /// warns on a model without a Fresnel term, is refused by `measured`,
    /// is saved by name and read back, and an edit of η drops it.
    #[test]
    fn spectral_metal_sets_its_preset_and_refuses_what_it_overrides() {
        let entry =
            |text: &str| MaterialEntry::deserialize(text.parse::<toml::Table>().unwrap()).unwrap();
        let ct = |keys: &str| {
            material_from_entry("m", &entry(&format!("model = \"cook-torrance\"\n{keys}")))
        };
        let gold = ct("spectral_metal = \"gold\"").unwrap();
        let preset = ct("preset = \"gold-rgb\"").unwrap();
        assert_eq!(gold.spectral_metal, Some(Metal::Gold));
        assert_eq!(
            (gold.eta, gold.kappa, gold.fresnel),
            (preset.eta, preset.kappa, preset.fresnel)
        );
        assert_eq!((gold.k_d, gold.k_s), (preset.k_d, preset.k_s));
        assert_eq!(
            ct("spectral_metal = \"gold\"\npreset = \"gold-rgb\"\nfresnel = \"conductor\"")
                .unwrap(),
            gold
        );
        for (keys, names) in [
            ("preset = \"silver-rgb\"", "`preset = \"silver-rgb\"`"),
            (
                "preset = \"gold\"",
                "remove `preset` or set it to \"gold-rgb\"",
            ),
            ("eta = 0.2", "`eta` cannot be combined"),
            ("kappa = [3.0, 2.0, 1.0]", "`kappa` cannot be combined"),
            (
                "eta_texture = \"e.png\"",
                "`eta_texture` cannot be combined",
            ),
            (
                "fresnel = \"schlick\"",
                "`fresnel = \"schlick\"` cannot be combined",
            ),
        ] {
            let e = ct(&format!("spectral_metal = \"gold\"\n{keys}")).unwrap_err();
            assert!(
                e.starts_with("materials.m.spectral_metal: ") && e.contains(names),
                "{e}"
            );
        }
        let e = ct("spectral_metal = \"platinum\"").unwrap_err();
        assert!(
            e.contains("unknown spectral metal `platinum`")
                && e.contains("gold, silver, copper, aluminium, iron"),
            "{e}"
        );
        let phong = entry("model = \"phong\"\nspectral_metal = \"gold\"");
        assert_eq!(keys_not_applying(&phong), [spectral_metal::KEY]);
        assert_eq!(
            material_from_entry("m", &phong).unwrap().spectral_metal,
            None
        );
        let e = material_from_entry(
            "m",
            &entry("model = \"measured\"\nmeasured = \"chrome\"\nspectral_metal = \"gold\""),
        )
        .unwrap_err();
        assert!(
            e.contains("spectral_metal: does not apply to model `measured`"),
            "{e}"
        );
        let mirror = material_from_entry(
            "m",
            &entry("model = \"mirror\"\nspectral_metal = \"copper\""),
        )
        .unwrap();
        assert_eq!(mirror.spectral_metal, Some(Metal::Copper));
        for m in [&gold, &mirror] {
            let written = material_table(m);
            assert!(
                !written.contains_key("eta") && !written.contains_key("kappa"),
                "{written:?}"
            );
            let back = MaterialEntry::deserialize(Toml::Table(written)).unwrap();
            assert!(keys_not_applying(&back).is_empty());
            assert_eq!(&material_from_entry("m", &back).unwrap(), m);
        }
        let set = with_key(&preset, spectral_metal::KEY, Toml::String("gold".into())).unwrap();
        assert_eq!(set, gold);
        let edited = with_key(&gold, "eta", Toml::Float(0.3)).unwrap();
        assert_eq!(edited.spectral_metal, None);
        let kept = with_key(&gold, "roughness", Toml::Float(0.1)).unwrap();
        assert_eq!(kept.spectral_metal, Some(Metal::Gold));
        let phong = Material::new("m", ReflectanceModel::Phong);
        assert!(
            with_key(&phong, spectral_metal::KEY, Toml::String("gold".into()))
                .unwrap_err()
                .contains("`cook-torrance`, `mirror`")
        );
    }

    #[test]
    fn every_key_has_one_type() {
        for k in KEYS.iter() {
            let kinds: Vec<Kind> = table::all_params()
                .into_iter()
                .filter(|p| p.key == *k)
                .map(|p| p.kind)
                .collect();
            assert!(kinds.windows(2).all(|w| w[0] == w[1]), "{k}");
        }
    }
}
