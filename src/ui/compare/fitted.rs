//! A measured material's fit, to put beside it: the
//! parameters `gonio fit --all` stored in `docs/fit/fits.toml` (compiled
//! in; `[materials.NAME--LABEL]`, e.g. `gold-metallic-paint--ct-ggx-conductor`),
//! or, for a material or model not there, a fit run now with the same
//! fitter, samples and metric as `gonio fit` (`crate::fit`: Ngan et al.
//! 2005's cosine-weighted L2; seconds to a minute, so the panel runs it in
//! the background).

use crate::fit::{FitModel, Metric, models::ALL, problem, published, samples::samples};
use crate::material::measured::MeasuredBrdf;
use crate::material::{Material, MaterialEntry, material_from_entry};
use serde::Deserialize;
use std::sync::OnceLock;

/// `docs/fit/fits.toml`, the fits of `gonio fit --all`.
const FITS_TOML: &str = include_str!("../../../docs/fit/fits.toml");

/// The fit models' short labels (`ct-ggx-conductor`, `ward`, ...), in
/// the ranking's order.
pub fn labels() -> Vec<String> {
    ALL.iter()
        .filter_map(|s| FitModel::parse(s).ok())
        .map(|m| m.label())
        .collect()
}

/// The fit model `text` names: a label of [`labels`] or a `gonio fit
/// --model` spec.
pub fn model(text: &str) -> Result<FitModel, String> {
    let text = text.trim();
    for spec in ALL {
        if let Ok(m) = FitModel::parse(spec)
            && m.label() == text
        {
            return Ok(m);
        }
    }
    FitModel::parse(text).map_err(|e| {
        format!(
            "{e}; the fit models are {} (or a `gonio fit --model` spec)",
            labels().join(", ")
        )
    })
}

fn fits() -> &'static toml::Table {
    static FITS: OnceLock<toml::Table> = OnceLock::new();
    FITS.get_or_init(|| {
        let all: toml::Table = FITS_TOML.parse().unwrap_or_default();
        match all.get("materials") {
            Some(toml::Value::Table(t)) => t.clone(),
            _ => toml::Table::new(),
        }
    })
}

/// The stored fit of the built-in measured material `name` under `model`,
/// named `fit LABEL`, if `docs/fit/fits.toml` has it.
pub fn stored(name: &str, model: &FitModel) -> Option<Material> {
    let value = fits().get(&format!("{name}--{}", model.label()))?;
    let entry = MaterialEntry::deserialize(value.clone()).ok()?;
    material_from_entry(&label(model, "fits.toml"), &entry).ok()
}

/// Fits `model` to `brdf` now (seconds to a minute), as `gonio fit` does.
pub fn fit_now(brdf: &MeasuredBrdf, model: &FitModel) -> Result<Material, String> {
    let data = samples(brdf);
    let result = if model.is_published() || model.starts_from_published() {
        let start = published::abc(&brdf.name)
            .ok_or_else(|| format!("`{}` has no published ABC fit", brdf.name))?;
        if model.is_published() {
            problem::score(&start, &data, Metric::Ngan)
        } else {
            problem::fit_from(model, &data, Metric::Ngan, Some(&start))
        }
    } else {
        problem::fit(model, &data, Metric::Ngan)
    };
    let mut m = result.material;
    m.name = label(
        model,
        &format!("fitted now, error {:.3e} 1/sr", result.error),
    );
    Ok(m)
}

/// The fit of `brdf` under `model`: stored if there, else fitted now.
pub fn fit(brdf: &MeasuredBrdf, model: &FitModel) -> Result<Material, String> {
    match stored(&brdf.name, model) {
        Some(m) => Ok(m),
        None => fit_now(brdf, model),
    }
}

fn label(model: &FitModel, source: &str) -> String {
    format!("fit {} ({source})", model.label())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;

    /// Every stored fit reads back as a valid material of its model; the
    /// labels name the 18 models of the ranking.
    #[test]
    fn stored_fits_read_back() {
        assert_eq!(labels().len(), ALL.len());
        let m = model("ct-ggx-conductor").unwrap();
        assert_eq!(m.base.model, ReflectanceModel::CookTorrance);
        let names: Vec<&String> = fits().keys().collect();
        assert!(names.len() >= 100, "{}", names.len());
        let first = names[0].split("--").next().unwrap();
        let gold = stored(first, &m).expect("stored");
        assert_eq!(gold.model, ReflectanceModel::CookTorrance);
        assert!(gold.validate().is_ok());
        assert!(model("cook-torrance,distribution=ggx,fresnel=conductor").is_ok());
        assert!(model("phonk").unwrap_err().contains("ct-ggx-conductor"));
    }

    /// The path for a material or model not in fits.toml: a fit run now
    /// is `gonio fit`'s (the same fitter, samples and metric, all
    /// deterministic), so for a stored pair it gives the stored numbers
    /// (to the 1e-9 relative fits.toml's decimal printing keeps, with
    /// room), named as fitted now.
    #[test]
    fn a_fit_run_now_is_the_stored_fit() {
        let brdf = crate::material::measured::library::builtin("gold-metallic-paint").unwrap();
        for label in ["lambert", "blinn-phong-normalized"] {
            let m = model(label).unwrap();
            let stored = stored(&brdf.name, &m).expect("in fits.toml");
            let now = fit_now(brdf, &m).unwrap();
            assert!(now.name.contains("fitted now"), "{}", now.name);
            for (a, b) in [(now.k_d, stored.k_d), (now.k_s, stored.k_s)] {
                for c in 0..3 {
                    assert!(
                        (a[c] - b[c]).abs() <= 1e-6 * b[c].abs().max(1e-3),
                        "{label}: {a:?} vs {b:?}"
                    );
                }
            }
            assert!(
                (now.k_e - stored.k_e).abs() <= 1e-6 * stored.k_e.abs().max(1.0),
                "{label}: k_e {} vs {}",
                now.k_e,
                stored.k_e
            );
        }
    }
}
