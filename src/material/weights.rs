//! Each model's default weights `(k_d, k_s)`: what a material shows when
//! its scene-file table (or `gonio brdf` spec) does not give `k_d` or
//! `k_s`. The rule is that a bare material shows its model: a model with
//! a specular lobe gets a visible lobe, a metal renders as that metal with
//! no other keys (a bare `cook-torrance` with `preset = "gold"`
//! used to default to `k_s = 0` and render as its diffuse part only).
//!
//! The contract fixes what `k_d` and `k_s` mean (`f_r = k_d/π + k_s ·
//! f_spec`), not their defaults; these are gonio's, chosen to stay
//! physically plausible: wherever the lobe is a normalized or corrected
//! form, the default material's directional albedo `ρ(θ_i) ≤ 1` (checked
//! at every θ_i by this file's tests with `explore::albedo`; the lecture's
//! own Phong and Blinn-Phong forms are not bounded by any weights, see
//! docs/brdf-models.md).
//!
//! When they are applied: `Material::new` takes the model's weights for
//! its default terms; a scene-file entry takes them again after its
//! `preset` and terms are applied (Cook-Torrance's depend on the Fresnel
//! term: [`cook_torrance`]), for whichever of `k_d`, `k_s` it does not
//! give. Keys given always win. The viewer's edits move a weight still
//! at its default along with the model, preset or term edited
//! (`Material::follow_default_weights`), so an edit gives what `--set` of
//! the same key in the scene file gives.

use super::{Fresnel, Material};
use crate::base::Rgb;

/// A material's diffuse and specular weights `(k_d, k_s)`.
pub type Weights = (Rgb, Rgb);

/// The diffuse models (`lambert`, the Oren-Nayar pair) and those that read
/// neither weight (`gltf-pbr`): a light grey `k_d = 0.8`, no `k_s`.
pub fn diffuse(_: &Material) -> Weights {
    (Rgb::splat(0.8), Rgb::ZERO)
}

/// The glossy lobes without a Fresnel term (Phong, Blinn-Phong, Ward, and
/// their forms): a plastic, half diffuse, half lobe, `k_d = k_s = 0.5`.
/// A normalized lobe reflects at most 1 (`k_s = 1`, `k_d = 0`), so the sum
/// stays ≤ 1.
pub fn plastic(_: &Material) -> Weights {
    (Rgb::splat(0.5), Rgb::splat(0.5))
}

/// Cook-Torrance: the Fresnel term is the lobe's weight, so `k_s = 1`
/// (a smaller `k_s` would dim F, which reaches 1 at grazing incidence),
/// and `k_d` depends on what reflects:
/// - a conductor (the Fresnel term reads η, κ — `conductor`,
///   `conductor-lecture`, `schlick` — and κ > 0 in some channel: every
///   metal preset, and the default, the lecture's gold): `k_d = 0`, a
///   bare metal (a metal has no diffuse body: what it does not reflect
///   it absorbs);
/// - a dielectric (`fresnel = "dielectric"`, every dielectric preset, or
///   an η with κ = 0): `k_d = 0.5`, a plastic whose lobe is its Fresnel
///   reflection;
/// - `fresnel = "none"` (F = 1, no weight of its own): [`plastic`]'s
///   `k_d = k_s = 0.5`.
pub fn cook_torrance(m: &Material) -> Weights {
    let reads_eta_kappa = matches!(
        m.fresnel,
        Fresnel::Conductor | Fresnel::ConductorLecture | Fresnel::Schlick
    );
    match m.fresnel {
        Fresnel::None => plastic(m),
        _ if reads_eta_kappa && m.kappa.max_element() > 0.0 => (Rgb::ZERO, Rgb::ONE),
        _ => (Rgb::splat(0.5), Rgb::ONE),
    }
}

/// The mirror: all of its δ lobe (`k_s = 1`, reflectance `F`), no
/// diffuse part.
pub fn mirror(_: &Material) -> Weights {
    (Rgb::ZERO, Rgb::ONE)
}

/// `measured`: neither weight applies (its `f_r` is the data's).
pub fn none(_: &Material) -> Weights {
    (Rgb::ZERO, Rgb::ZERO)
}

/// `abc`: the published form (`k_s = 1`) with the published fit of MERL's
/// gold-metallic-paint (Löw et al. 2012; shared/measured/merl100_abc_fits.csv),
/// whose other parameters are the model's defaults.
pub fn abc_published(_: &Material) -> Weights {
    (Rgb::new(0.009164, 0.005649, 0.000424), Rgb::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::table::ROWS;
    use crate::material::{ReflectanceModel, presets};

    /// Every model whose row weighs a lobe by `k_s` gets a lobe by
    /// default; the others keep `k_s = 0`.
    #[test]
    fn every_lobe_model_shows_its_lobe() {
        for row in ROWS {
            let m = Material::new("m", row.model);
            let weighs_a_lobe = row.params.iter().any(|p| p.key == "k_s");
            assert_eq!(
                m.k_s.min_element() > 0.0,
                weighs_a_lobe,
                "{}: k_s = {:?}",
                row.model,
                m.k_s
            );
        }
    }

    /// A metal preset is a bare metal, a dielectric one a plastic; the
    /// Fresnel term decides, whatever set it.
    #[test]
    fn cook_torrance_follows_its_fresnel_term() {
        let with = |preset: &str| {
            let mut m = Material::new("m", ReflectanceModel::CookTorrance);
            presets::preset(preset).unwrap().apply(&mut m);
            cook_torrance(&m)
        };
        let metal = (Rgb::ZERO, Rgb::ONE);
        let plastic_lobe = (Rgb::splat(0.5), Rgb::ONE);
        for p in ["gold", "silver", "copper", "steel", "gold-rgb", "iron-rgb"] {
            assert_eq!(with(p), metal, "{p}");
        }
        for p in ["glass", "water", "diamond"] {
            assert_eq!(with(p), plastic_lobe, "{p}");
        }
        let mut m = Material::new("m", ReflectanceModel::CookTorrance);
        assert_eq!((m.k_d, m.k_s), metal, "the default: the lecture's gold");
        m.fresnel = Fresnel::Schlick;
        assert_eq!(cook_torrance(&m), metal, "Schlick of gold's η, κ");
        m.fresnel = Fresnel::Dielectric;
        assert_eq!(cook_torrance(&m), plastic_lobe);
        m.fresnel = Fresnel::None;
        assert_eq!(cook_torrance(&m), plastic(&m));
    }

    /// A scene-file entry: the weights follow its preset and terms, and
    /// every key given wins (each of `k_d`, `k_s` alone).
    #[test]
    fn entries_take_the_weights_after_preset_and_terms() {
        use crate::material::{MaterialEntry, material_from_entry};
        use serde::Deserialize;
        let read = |text: &str| {
            let entry = MaterialEntry::deserialize(text.parse::<toml::Table>().unwrap()).unwrap();
            let m = material_from_entry("m", &entry).unwrap();
            (m.k_d, m.k_s)
        };
        let (metal, plastic_lobe) = ((Rgb::ZERO, Rgb::ONE), (Rgb::splat(0.5), Rgb::ONE));
        let ct = "model = \"cook-torrance\"\n";
        assert_eq!(read(&format!("{ct}preset = \"gold\"")), metal);
        assert_eq!(read(&format!("{ct}preset = \"glass\"")), plastic_lobe);
        assert_eq!(read(&format!("{ct}fresnel = \"dielectric\"")), plastic_lobe);
        assert_eq!(
            read(&format!("{ct}preset = \"glass\"\nfresnel = \"none\"")),
            (Rgb::splat(0.5), Rgb::splat(0.5))
        );
        assert_eq!(
            read(&format!("{ct}preset = \"gold\"\nk_d = 0.2")),
            (Rgb::splat(0.2), Rgb::ONE)
        );
        assert_eq!(
            read(&format!("{ct}preset = \"glass\"\nk_s = 0")),
            (Rgb::splat(0.5), Rgb::ZERO)
        );
        assert_eq!(
            read("model = \"ward\"\nk_s = [0.1, 0.2, 0.3]"),
            (Rgb::splat(0.5), Rgb::new(0.1, 0.2, 0.3))
        );
        assert_eq!(
            read("model = \"phong\""),
            plastic(&Material::new("m", ReflectanceModel::Phong))
        );
        assert_eq!(
            read("model = \"mirror\"\npreset = \"silver\""),
            mirror(&Material::new("m", ReflectanceModel::Mirror))
        );
        assert_eq!(read("model = \"lambert\""), (Rgb::splat(0.8), Rgb::ZERO));
    }

    /// Physically plausible defaults: the default material of every
    /// normalized or corrected lobe, and Cook-Torrance's with a dielectric,
    /// no Fresnel term and GGX, reflects at most what it receives,
    /// `ρ(θ_i) ≤ 1`, at every θ_i sampled up to grazing. The lecture's own
    /// Phong and Blinn-Phong (÷ I·N) are not bounded by any weights
    /// (docs/brdf-models.md) and are left out. Failing means the albedo
    /// exceeds 1 by more than the quadrature's own error bound.
    #[test]
    fn default_materials_reflect_at_most_what_they_receive() {
        use crate::explore::albedo::directional_albedo;
        use crate::material::{Distribution, Geometry};
        let mut materials: Vec<Material> = [
            ReflectanceModel::PhongNormalized,
            ReflectanceModel::BlinnPhongNormalized,
            ReflectanceModel::Ward,
            ReflectanceModel::WardAnisotropic,
            ReflectanceModel::CookTorrance,
        ]
        .into_iter()
        .map(|model| Material::new("m", model))
        .collect();
        for (preset, fresnel) in [
            ("gold-rgb", None),
            ("glass", None),
            ("glass", Some(Fresnel::Schlick)),
            ("glass", Some(Fresnel::None)),
        ] {
            let mut m = Material::new("m", ReflectanceModel::CookTorrance);
            presets::preset(preset).unwrap().apply(&mut m);
            if let Some(f) = fresnel {
                m.fresnel = f;
            }
            (m.k_d, m.k_s) = cook_torrance(&m);
            materials.push(m);
        }
        let mut ggx = Material::new("m", ReflectanceModel::CookTorrance);
        (ggx.distribution, ggx.geometry) = (Distribution::Ggx, Geometry::SmithCorrelated);
        materials.push(ggx);
        for m in &materials {
            for deg in [0.0, 30.0, 60.0, 75.0, 85.0, 89.0] {
                let e = directional_albedo(m, f64::to_radians(deg));
                assert!(
                    (e.value - e.error_bound).max_element() <= 1.0,
                    "{} ({:?}, {:?}, k_d {:?}, k_s {:?}) at θ_i = {deg}°: ρ = {:?} ± {:?}",
                    m.model,
                    m.distribution,
                    m.fresnel,
                    m.k_d,
                    m.k_s,
                    e.value,
                    e.error_bound
                );
            }
        }
    }

    /// An edit (the viewer's panel, `--edit`) gives the material a scene
    /// file with the same key set would: weights at their defaults follow
    /// the model, preset or term; weights set to other values stay.
    #[test]
    fn edits_move_default_weights_as_the_scene_file_does() {
        use crate::material::entry::with_key;
        use crate::material::{MaterialEntry, material_from_entry};
        use serde::Deserialize;
        let read = |text: &str| {
            let entry = MaterialEntry::deserialize(text.parse::<toml::Table>().unwrap()).unwrap();
            material_from_entry("m", &entry).unwrap()
        };
        let text = |s: &str| toml::Value::String(s.into());
        let floor = read("model = \"lambert\"\nk_d = 0.6");
        assert_eq!(
            with_key(&floor, "model", text("phong")).unwrap(),
            read("model = \"phong\"\nk_d = 0.6")
        );
        let gold = read("model = \"cook-torrance\"\npreset = \"gold\"");
        let glass = with_key(&gold, "preset", text("glass")).unwrap();
        assert_eq!((glass.k_d, glass.k_s), (Rgb::splat(0.5), Rgb::ONE));
        let tinted = read("model = \"cook-torrance\"\npreset = \"gold\"\nk_d = 0.2\nk_s = 0.3");
        let kept = with_key(&tinted, "preset", text("glass")).unwrap();
        assert_eq!((kept.k_d, kept.k_s), (Rgb::splat(0.2), Rgb::splat(0.3)));
    }
}
