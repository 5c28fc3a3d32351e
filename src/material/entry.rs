//! A material's text form: the keys of a scene file's `[materials.NAME]`
//! table (also `gonio brdf --set` and `--compare`), and their validation
//! into a [`Material`].

use super::{Material, ReflectanceModel, presets};
use crate::base::ColorValue;
use crate::base::Rgb;
use serde::Deserialize;
use toml::Value;

/// `[materials.NAME]`: the model, an optional preset from the lecture's
/// tables, then any parameter (given keys override the preset).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialEntry {
    pub model: String,
    pub preset: Option<String>,
    pub k_a: Option<ColorValue>,
    pub k_d: Option<ColorValue>,
    pub k_s: Option<ColorValue>,
    pub k_e: Option<f64>,
    pub roughness: Option<f64>,
    /// Ward: sets σ_x and σ_y.
    pub sigma: Option<f64>,
    pub sigma_x: Option<f64>,
    pub sigma_y: Option<f64>,
    pub eta: Option<ColorValue>,
    pub kappa: Option<ColorValue>,
    pub eta_i: Option<f64>,
    pub eta_t: Option<f64>,
    pub distribution: Option<String>,
    pub geometry: Option<String>,
    pub fresnel: Option<String>,
    pub denominator: Option<String>,
}

/// The validated material of entry `e`, named `name` (messages name the
/// key as `materials.NAME.KEY`).
pub fn material_from_entry(name: &str, e: &MaterialEntry) -> std::result::Result<Material, String> {
    let model: ReflectanceModel = e
        .model
        .parse()
        .map_err(|p| format!("materials.{name}.model: {p}"))?;
    let mut m = Material::new(name, model);
    let key = |k: &str| format!("materials.{name}.{k}");
    if let Some(p) = &e.preset {
        presets::preset(p)
            .map_err(|p| format!("{}: {p}", key("preset")))?
            .apply(&mut m);
    }
    let colors = [
        (e.k_a, &mut m.k_a),
        (e.k_d, &mut m.k_d),
        (e.k_s, &mut m.k_s),
        (e.eta, &mut m.eta),
        (e.kappa, &mut m.kappa),
    ];
    for (value, slot) in colors {
        if let Some(c) = value {
            *slot = c.rgb();
        }
    }
    if let Some(s) = e.sigma {
        (m.sigma_x, m.sigma_y) = (s, s);
    }
    let scalars = [
        (e.k_e, &mut m.k_e),
        (e.roughness, &mut m.roughness),
        (e.sigma_x, &mut m.sigma_x),
        (e.sigma_y, &mut m.sigma_y),
        (e.eta_i, &mut m.eta_i),
        (e.eta_t, &mut m.eta_t),
    ];
    for (value, slot) in scalars {
        if let Some(v) = value {
            *slot = v;
        }
    }
    fn parse<T: std::str::FromStr<Err = String>>(
        key: String,
        v: &Option<String>,
        slot: &mut T,
    ) -> Result<(), String> {
        if let Some(text) = v {
            *slot = text.parse().map_err(|p| format!("{key}: {p}"))?;
        }
        Ok(())
    }
    parse(key("distribution"), &e.distribution, &mut m.distribution)?;
    parse(key("geometry"), &e.geometry, &mut m.geometry)?;
    parse(key("fresnel"), &e.fresnel, &mut m.fresnel)?;
    parse(key("denominator"), &e.denominator, &mut m.denominator)?;
    m.validate()?;
    Ok(m)
}

/// Every parameter of `m` under its scene-file key (no preset: the values
/// it set are written out).
pub fn material_table(m: &Material) -> toml::Table {
    let mut t = toml::Table::new();
    let mut put = |k: &str, v: Value| {
        t.insert(k.into(), v);
    };
    put("model", Value::String(m.model.name().into()));
    put("k_a", vec3(m.k_a));
    put("k_d", vec3(m.k_d));
    put("k_s", vec3(m.k_s));
    put("k_e", Value::Float(m.k_e));
    put("roughness", Value::Float(m.roughness));
    put("sigma_x", Value::Float(m.sigma_x));
    put("sigma_y", Value::Float(m.sigma_y));
    put("eta", vec3(m.eta));
    put("kappa", vec3(m.kappa));
    put("eta_i", Value::Float(m.eta_i));
    put("eta_t", Value::Float(m.eta_t));
    put("distribution", Value::String(m.distribution.name().into()));
    put("geometry", Value::String(m.geometry.name().into()));
    put("fresnel", Value::String(m.fresnel.name().into()));
    put("denominator", Value::String(m.denominator.name().into()));
    t
}

fn vec3(v: Rgb) -> Value {
    Value::Array(v.to_array().map(Value::Float).to_vec())
}
