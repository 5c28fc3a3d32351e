//! The table of reflectance models: one [`ModelRow`] per model says
//! everything the rest of gonio needs to know about it — its name and
//! summary, whether it is the lecture's form, the WGSL files its GPU twin
//! needs, whether it needs tangents, which Cook-Torrance-style terms
//! apply, its parameters (key, label, range, widget, field binding: see
//! [`Param`]), its typed BRDF value and its `f32` error bound. From it come
//! the scene-file keys and their validation (`entry.rs`), "Save scene"
//! ([`super::material_table`]), the viewer's material panel, the shader
//! generator's file list, the bench's model knob, the albedo table of
//! `docs/brdf-models.md` and the parameter sweeps of the equivalence and
//! property tests.
//!
//! # Adding a model
//!
//! 1. Its `f64` BRDF in `src/material/brdf/NAME.rs` (a `pub mod` line in
//!    `brdf/mod.rs`), citing its source, and its WGSL twin
//!    `shaders/brdf/NAME.wgsl` with the same function names and order.
//! 2. Its name in [`ReflectanceModel`] (`src/material/model.rs`).
//! 3. Its row in [`ROWS`] below (new parameters as `static`s beside the
//!    others in `param.rs`; a new `Material` field, if it needs one, with
//!    its default in `Material::new` and the model's own in the row's
//!    `defaults`; its default `k_d`, `k_s` in `weights`, one of
//!    `material/weights.rs`).
//! 4. One [`Specular`] variant with its arm in `brdf::eval` and in
//!    `Brdf::shader_params` (`brdf/value.rs`; the compiler points at both:
//!    constants the named GPU fields do not cover go in `lobe`, four
//!    numbers the WGSL twin reads as `m.lobe`), and one arm in the WGSL
//!    dispatch (`eval_brdf` in `shaders/brdf/eval.wgsl`, in a block
//!    `#if NAME`; its code constant `MODEL_NAME` is generated).
//!
//! `build.rs` embeds the new WGSL file; the file order of a scene's module
//! comes from the rows' `wgsl` lists. The shader snapshots
//! (`GONIO_UPDATE_SNAPSHOTS=1`) gain the model's code constant, and
//! `docs/brdf-models.md` its formula and its albedo rows (`gonio brdf
//! --albedo-table`). `oren-nayar` was added this way: see its commit.
//!
//! Nothing else lists models: the panel, the scene-file keys, "Save
//! scene", the shader's file list, the tests' sweeps and tolerances, the
//! bench and `gonio brdf --albedo-table` all read this table.

use super::brdf::oren_nayar::oren_nayar_terms;
use super::brdf::{CookTorrance, FresnelTerm, Specular};
use super::param::{
    ABC_A, ABC_B, ABC_C, ANISOTROPY_ROTATION, ANISOTROPY_STRENGTH, BASE_COLOR, CLEARCOAT,
    CLEARCOAT_ROUGHNESS, EMISSION, ETA, ETA_I, ETA_T, FACET_SIGMA, IOR, IRIDESCENCE,
    IRIDESCENCE_IOR, IRIDESCENCE_THICKNESS, K_A, K_D, K_E, K_S, KAPPA, METALLIC,
    PERCEPTUAL_ROUGHNESS, Param, ROUGHNESS, SHEEN_COLOR, SHEEN_ROUGHNESS, SIGMA_X, SIGMA_Y,
    SPECULAR, SPECULAR_COLOR, WARD_SIGMA,
};
use super::param::{
    ATTENUATION_COLOR, ATTENUATION_DISTANCE, DIFFUSE_TRANSMISSION, DIFFUSE_TRANSMISSION_COLOR,
    DISPERSION, THICKNESS, TRANSMISSION,
};
use super::weights::{self, Weights};
use super::{Material, ReflectanceModel};
use crate::base::Rgb;

/// Whether a model is the formula as the lecture writes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// As the lecture writes it (not necessarily reciprocal or normalized).
    Lecture,
    /// A corrected form (normalized, reciprocal).
    Corrected,
    /// The lecture's model with terms to choose, lecture or corrected.
    Terms,
    /// A published model the lecture points to but does not write out.
    Paper,
}

/// Which selectable terms a model has (the keys `distribution`,
/// `geometry`, `fresnel`, `denominator`; see `material/terms.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Terms {
    pub distribution: bool,
    pub geometry: bool,
    pub fresnel: bool,
    pub denominator: bool,
}

impl Terms {
    const NONE: Terms = Terms {
        distribution: false,
        geometry: false,
        fresnel: false,
        denominator: false,
    };
}

/// Everything about one model: see the module doc.
#[derive(Debug)]
pub struct ModelRow {
    pub model: ReflectanceModel,
    /// One line for the docs and the panel's tooltip.
    pub summary: &'static str,
    pub form: Form,
    /// The WGSL files of its GPU twin, relative to `shaders/`, in
    /// dependency order (each may use the ones before).
    pub wgsl: &'static [&'static str],
    /// Whether it reads the tangent frame (anisotropy): the vertex stream
    /// then carries tangents.
    pub needs_tangents: bool,
    pub terms: Terms,
    /// Its parameters, in the panel's order (`k_a` is every model's: see
    /// [`COMMON`]).
    pub params: &'static [&'static Param],
    /// Whether `f_r(i, o) = f_r(o, i)` (the property tests check it).
    pub reciprocal: bool,
    /// Whether the bench's `model` knob measures it.
    pub benched: bool,
    /// Whether it offers energy compensation (the material key
    /// `energy_compensation`, `brdf::energy`): its lobe is GGX-like
    /// microfacet scattering whose lost energy the albedo table measures.
    pub energy_compensation: bool,
    /// Its own defaults, applied by `Material::new` over the common ones.
    pub defaults: fn(&mut Material),
    /// Its default `k_d`, `k_s` for the rest of the material (see
    /// [`super::weights`]: a model with a lobe shows it, a metal preset
    /// renders as that metal).
    pub weights: fn(&Material) -> Weights,
    /// The specular term of a material of this model, its derived
    /// constants computed.
    pub specular: fn(&Material) -> Specular,
    /// The relative `f32` error of its shading beyond the light loop's
    /// (the GPU-vs-reference tolerance; derivation in tests/gpu_vs_cpu.rs).
    pub f32_error: fn(&Material) -> f64,
    /// The extra error, relative to `|f_r|`, that Vulkan allows the
    /// transcendental functions its WGSL calls (the per-sample tolerance
    /// of tests/brdf_equivalence.rs, derived in its `transcendental`).
    pub transcendental_error: fn(&Material) -> f64,
    /// Its rows in the albedo table of `docs/brdf-models.md`: parameters
    /// (`KEY=VALUE,...` after the model's name) and a remark.
    pub albedo_table: &'static [(&'static str, &'static str)],
}

/// The model's row.
pub fn row(model: ReflectanceModel) -> &'static ModelRow {
    ROWS.iter()
        .find(|r| r.model == model)
        .expect("every model has a row (tests: every_model_has_one_row)")
}

impl ReflectanceModel {
    /// The model's row in the table of models.
    pub fn row(self) -> &'static ModelRow {
        row(self)
    }

    /// Whether the model needs a tangent frame (anisotropy).
    pub fn needs_tangents(self) -> bool {
        self.row().needs_tangents
    }
}

/// Parameters of every model (not a BRDF's: the ambient term, emission).
pub const COMMON: &[&Param] = &[&K_A, &EMISSION];

/// Every distinct parameter: [`COMMON`], then each row's in table order
/// (each once, by identity).
pub fn all_params() -> Vec<&'static Param> {
    let mut out: Vec<&'static Param> = Vec::new();
    for &p in COMMON
        .iter()
        .chain(ROWS.iter().flat_map(|r| r.params.iter()))
    {
        if !out.iter().any(|q| std::ptr::eq(*q, p)) {
            out.push(p);
        }
    }
    out
}

/// The parameter `key` names for a material of `model`: the model's own
/// (or a common one), else the first of that key in table order (a key of
/// another model is kept for when the material switches to it).
pub fn param_for(model: ReflectanceModel, key: &str) -> Option<&'static Param> {
    let own = COMMON.iter().chain(row(model).params.iter());
    own.copied()
        .find(|p| p.key == key)
        .or_else(|| all_params().into_iter().find(|p| p.key == key))
}

/// The parameters that are fields of their own, in table order: what
/// "Save scene" writes and [`Material::validate`] checks.
pub fn stored_params() -> Vec<&'static Param> {
    all_params().into_iter().filter(|p| p.stored).collect()
}

/// For every model, a material with its defaults, then each of its terms
/// varied alone around them: every term's code once (the bench's uber
/// shader, the equivalence test).
pub fn each_term_once() -> Vec<Material> {
    use super::{Denominator, Distribution, Fresnel, Geometry};
    let mut out = Vec::new();
    for row in ROWS {
        let base = Material::new("each term", row.model);
        out.push(base.clone());
        let vary =
            |out: &mut Vec<Material>, applies: bool, set: &dyn Fn(&mut Material, usize), n| {
                if applies {
                    for i in 0..n {
                        let mut m = base.clone();
                        set(&mut m, i);
                        out.push(m);
                    }
                }
            };
        let t = row.terms;
        vary(
            &mut out,
            t.distribution,
            &|m, i| m.distribution = Distribution::ALL[i],
            Distribution::ALL.len(),
        );
        vary(
            &mut out,
            t.geometry,
            &|m, i| m.geometry = Geometry::ALL[i],
            Geometry::ALL.len(),
        );
        vary(
            &mut out,
            t.fresnel,
            &|m, i| m.fresnel = Fresnel::ALL[i],
            Fresnel::ALL.len(),
        );
        vary(
            &mut out,
            t.denominator,
            &|m, i| m.denominator = Denominator::ALL[i],
            Denominator::ALL.len(),
        );
    }
    out
}

// ---------------------------------------------------------------------
// f32 error bounds (derivation: tests/gpu_vs_cpu.rs).

/// f32 unit roundoff, 2⁻²⁴.
const EPS: f64 = 1.0 / 16_777_216.0;

/// A power `c^k`: `k` times the error of `ln c` (8ε, and Vulkan's 2⁻²¹
/// absolute for `log`).
fn pow_error(k: f64) -> f64 {
    k * (8.0 * EPS + 2f64.powi(-21) * std::f64::consts::LN_2)
}

/// A lobe of width `r` in slope: 128ε / r.
fn slope_error(r: f64) -> f64 {
    128.0 * EPS / r
}

/// Every lobe ends in `exp(x)` with |x| ≤ 80 (the e⁻⁸⁰ cut-off): Vulkan
/// allows 3 + 2|x| ≤ 163 ulp.
const EXP_ERROR: f64 = 163.0 * EPS;

/// Smith's G1 (or Λ) for Beckmann in the GPU's default erf form, for
/// both directions (`brdf::microfacet::G1_BECKMANN_F32_ERROR`): the
/// materials whose G uses it, else 0. `approximation` alone: the f32
/// `erfc`'s 2 × 7.5e-8 (the formula's difference from the truth, for the
/// image tolerance); else with Vulkan's `exp` allowance (the per-sample
/// tolerance of tests/brdf_equivalence.rs).
fn smith_beckmann_error(m: &Material, approximation: bool) -> f64 {
    use super::{Distribution, Geometry};
    use crate::material::brdf::microfacet::{ERFC_F32_ERROR, G1_BECKMANN_F32_ERROR};
    let uses = matches!(m.geometry, Geometry::Smith | Geometry::SmithCorrelated)
        && m.distribution != Distribution::Ggx;
    match (uses, approximation) {
        (false, _) => 0.0,
        (true, true) => 2.0 * 0.5 * ERFC_F32_ERROR,
        (true, false) => 2.0 * G1_BECKMANN_F32_ERROR,
    }
}

fn no_error(_: &Material) -> f64 {
    0.0
}

// ---------------------------------------------------------------------
// The rows.

const LOBE: &[&Param] = &[&K_D, &K_S, &K_E];
const PHONG_WGSL: &[&str] = &["brdf/lambert.wgsl", "brdf/phong.wgsl"];
const FRESNEL_PARAMS: &[&Param] = &[&K_D, &K_S, &ETA, &KAPPA, &ETA_I, &ETA_T];

fn fresnel_term(m: &Material) -> FresnelTerm {
    FresnelTerm::new(m.fresnel, m.eta, m.kappa, m.eta_i, m.eta_t)
}

/// Every model's row, in the contract's order.
pub static ROWS: &[ModelRow] = &[
    ModelRow {
        model: ReflectanceModel::Lambert,
        summary: "ideal diffuse reflection, f_r = k_d/π",
        form: Form::Lecture,
        wgsl: &["brdf/lambert.wgsl"],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&K_D],
        reciprocal: true,
        benched: true,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::diffuse,
        specular: |_| Specular::None,
        f32_error: no_error,
        transcendental_error: |_| EXP_ERROR,
        albedo_table: &[("k_d=1", "albedo k_d exactly")],
    },
    ModelRow {
        model: ReflectanceModel::Phong,
        summary: "the lecture's Phong lobe (R(I)·V)^k_e / (I·N)",
        form: Form::Lecture,
        wgsl: PHONG_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: LOBE,
        reciprocal: false,
        benched: false,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::Phong { k_e: m.k_e },
        f32_error: |m| pow_error(m.k_e),
        transcendental_error: |m| EXP_ERROR + 2f64.powi(-21) * m.k_e.min(1240.0),
        albedo_table: &[
            ("k_d=0,k_s=1,k_e=1", "lecture form: ÷ I·N"),
            ("k_d=0,k_s=1,k_e=10", "lecture form"),
            ("k_d=0,k_s=1,k_e=100", "lecture form"),
        ],
    },
    ModelRow {
        model: ReflectanceModel::PhongNormalized,
        summary: "Phong normalized: (k_e+2)/2π (R(I)·V)^k_e",
        form: Form::Corrected,
        wgsl: PHONG_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: LOBE,
        reciprocal: true,
        benched: true,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::PhongNormalized { k_e: m.k_e },
        f32_error: |m| pow_error(m.k_e),
        transcendental_error: |m| EXP_ERROR + 2f64.powi(-21) * m.k_e.min(1240.0),
        albedo_table: &[
            ("k_d=0,k_s=1,k_e=1", "(k_e+2)/2π"),
            ("k_d=0,k_s=1,k_e=10", ""),
            ("k_d=0,k_s=1,k_e=100", ""),
            ("k_d=0,k_s=1,k_e=10000", ""),
        ],
    },
    ModelRow {
        model: ReflectanceModel::BlinnPhong,
        summary: "the lecture's Blinn-Phong lobe (H·N)^k_e / (I·N)",
        form: Form::Lecture,
        wgsl: PHONG_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: LOBE,
        reciprocal: false,
        benched: false,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::BlinnPhong { k_e: m.k_e },
        f32_error: |m| pow_error(m.k_e),
        transcendental_error: |m| EXP_ERROR + 2f64.powi(-21) * m.k_e.min(1240.0),
        albedo_table: &[
            ("k_d=0,k_s=1,k_e=1", "lecture form: ÷ I·N"),
            ("k_d=0,k_s=1,k_e=10", "lecture form"),
            ("k_d=0,k_s=1,k_e=100", "lecture form"),
        ],
    },
    ModelRow {
        model: ReflectanceModel::BlinnPhongNormalized,
        summary: "Blinn-Phong normalized (reciprocal, energy conserving)",
        form: Form::Corrected,
        wgsl: PHONG_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: LOBE,
        reciprocal: true,
        benched: true,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::BlinnPhongNormalized { k_e: m.k_e },
        f32_error: |m| pow_error(m.k_e),
        transcendental_error: |m| EXP_ERROR + 2f64.powi(-21) * m.k_e.min(1240.0),
        albedo_table: &[
            ("k_d=0,k_s=1,k_e=1", ""),
            ("k_d=0,k_s=1,k_e=10", ""),
            ("k_d=0,k_s=1,k_e=100", ""),
            ("k_d=0,k_s=1,k_e=10000", ""),
        ],
    },
    ModelRow {
        model: ReflectanceModel::Ward,
        summary: "Ward's isotropic Gaussian lobe, RMS slope σ",
        form: Form::Lecture,
        wgsl: &["brdf/lambert.wgsl", "brdf/phong.wgsl", "brdf/ward.wgsl"],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&K_D, &K_S, &WARD_SIGMA],
        reciprocal: true,
        benched: true,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::Ward { sigma: m.sigma_x },
        f32_error: |m| slope_error(m.sigma_x),
        transcendental_error: |_| EXP_ERROR,
        albedo_table: &[
            ("k_d=0,k_s=1,sigma=0.05", "lecture form"),
            ("k_d=0,k_s=1,sigma=0.2", "lecture form"),
            ("k_d=0,k_s=1,sigma=0.5", "lecture form"),
        ],
    },
    ModelRow {
        model: ReflectanceModel::WardAnisotropic,
        summary: "Ward's anisotropic lobe, σ_x along the tangent, σ_y along the bitangent",
        form: Form::Lecture,
        wgsl: &["brdf/lambert.wgsl", "brdf/phong.wgsl", "brdf/ward.wgsl"],
        needs_tangents: true,
        terms: Terms::NONE,
        params: &[&K_D, &K_S, &SIGMA_X, &SIGMA_Y],
        reciprocal: true,
        benched: false,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::plastic,
        specular: |m| Specular::WardAnisotropic {
            sigma_x: m.sigma_x,
            sigma_y: m.sigma_y,
        },
        f32_error: |m| slope_error(m.sigma_x.min(m.sigma_y)),
        transcendental_error: |_| EXP_ERROR,
        albedo_table: &[("k_d=0,k_s=1,sigma_x=0.05,sigma_y=0.3", "φ_i along σ_x")],
    },
    ModelRow {
        model: ReflectanceModel::CookTorrance,
        summary: "Cook-Torrance microfacets D·G·F / (c (N·V)(N·I)), terms selectable",
        form: Form::Terms,
        wgsl: &[
            "brdf/lambert.wgsl",
            "brdf/phong.wgsl",
            "brdf/fresnel.wgsl",
            "brdf/microfacet.wgsl",
            "brdf/energy.wgsl",
        ],
        needs_tangents: false,
        terms: Terms {
            distribution: true,
            geometry: true,
            fresnel: true,
            denominator: true,
        },
        params: &[&K_D, &K_S, &ROUGHNESS, &ETA, &KAPPA, &ETA_I, &ETA_T],
        reciprocal: true,
        benched: true,
        energy_compensation: true,
        defaults: |_| {},
        weights: weights::cook_torrance,
        specular: |m| {
            Specular::CookTorrance(CookTorrance::new(
                m.distribution,
                m.geometry,
                fresnel_term(m),
                m.denominator,
                m.roughness,
            ))
        },
        f32_error: |m| {
            use super::Distribution;
            let d = match m.distribution {
                Distribution::Blinn | Distribution::BlinnNormalized => {
                    pow_error(-std::f64::consts::LN_2 / m.roughness.cos().ln())
                }
                // The lecture's Gaussian takes its angle from acos (4096 ulp).
                Distribution::Gaussian | Distribution::GaussianNormalized => {
                    2.0 * std::f64::consts::LN_2 * 30.0 * 4096.0 * EPS
                }
                _ => slope_error(m.roughness),
            };
            d + smith_beckmann_error(m, true)
        },
        transcendental_error: |m| {
            use super::Distribution;
            let d = match m.distribution {
                Distribution::Gaussian | Distribution::GaussianNormalized => {
                    EXP_ERROR + 2.0 * 80.0 * 4096.0 * EPS
                }
                _ => EXP_ERROR,
            };
            d + smith_beckmann_error(m, false)
        },
        albedo_table: CT_ALBEDO,
    },
    ModelRow {
        model: ReflectanceModel::Mirror,
        summary: "ideal mirror: a Dirac lobe of reflectance k_s·F(cos θ)",
        form: Form::Lecture,
        wgsl: &["brdf/lambert.wgsl", "brdf/phong.wgsl", "brdf/fresnel.wgsl"],
        needs_tangents: false,
        terms: Terms {
            fresnel: true,
            ..Terms::NONE
        },
        params: FRESNEL_PARAMS,
        reciprocal: true,
        benched: false,
        energy_compensation: false,
        defaults: |m| m.fresnel = super::Fresnel::None,
        weights: weights::mirror,
        specular: |m| Specular::Mirror(fresnel_term(m)),
        f32_error: no_error,
        transcendental_error: |_| EXP_ERROR,
        albedo_table: &[
            ("k_s=1,fresnel=none", "δ lobe, closed form"),
            ("preset=silver", "silver, exact Fresnel"),
        ],
    },
    ModelRow {
        model: ReflectanceModel::OrenNayar,
        summary: "Oren-Nayar rough diffuse, qualitative: k_d/π (A + B max(0, cos Δφ) sin α tan β)",
        form: Form::Paper,
        wgsl: ON_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&K_D, &FACET_SIGMA],
        reciprocal: true,
        benched: true,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::diffuse,
        specular: |m| Specular::OrenNayar(oren_nayar_terms(m.facet_sigma)),
        f32_error: |_| ON_ERROR,
        transcendental_error: |_| 0.0,
        albedo_table: ON_ALBEDO,
    },
    ModelRow {
        model: ReflectanceModel::OrenNayarFull,
        summary: "Oren-Nayar rough diffuse, full: C1, C2, C3 and one interreflection",
        form: Form::Paper,
        wgsl: ON_WGSL,
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&K_D, &FACET_SIGMA],
        reciprocal: true,
        benched: false,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::diffuse,
        specular: |m| Specular::OrenNayarFull(oren_nayar_terms(m.facet_sigma)),
        f32_error: |_| ON_ERROR + ATAN2_TERMS_ERROR,
        transcendental_error: |_| ATAN2_TERMS_ERROR,
        albedo_table: ON_ALBEDO,
    },
    ModelRow {
        model: ReflectanceModel::Measured,
        summary: "measured f_r: a MERL material (built-in Neural-BRDF network) or a MERL .binary table",
        form: Form::Paper,
        wgsl: &["brdf/measured.wgsl"],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[],
        reciprocal: false,
        benched: false,
        energy_compensation: false,
        defaults: |m| m.measured = Some(super::measured::default_brdf()),
        weights: weights::none,
        specular: |m| Specular::Measured(m.measured.unwrap_or_else(super::measured::default_brdf)),
        f32_error: |_| MEASURED_F32_ERROR,
        transcendental_error: |_| 0.0,
        // Broad lobes only: chrome's highlight (about 1° wide) is narrower
        // than the albedo quadrature resolves (it reports 0.08 at 0°).
        albedo_table: &[
            ("measured=gold-metallic-paint", "MERL, Neural-BRDF"),
            ("measured=blue-fabric", "MERL, Neural-BRDF"),
        ],
    },
    ModelRow {
        model: ReflectanceModel::GltfPbr,
        summary: "glTF 2.0 metallic-roughness (Appendix B, mix form): base colour, metallic, perceptual roughness r (α = r²)",
        form: Form::Paper,
        wgsl: &[
            "brdf/lambert.wgsl",
            "brdf/phong.wgsl",
            "brdf/microfacet.wgsl",
            "brdf/energy.wgsl",
            "brdf/gltf_pbr.wgsl",
        ],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[
            &BASE_COLOR,
            &METALLIC,
            &PERCEPTUAL_ROUGHNESS,
            &IOR,
            &SPECULAR,
            &SPECULAR_COLOR,
            &CLEARCOAT,
            &CLEARCOAT_ROUGHNESS,
            &SHEEN_COLOR,
            &SHEEN_ROUGHNESS,
            &IRIDESCENCE,
            &IRIDESCENCE_IOR,
            &IRIDESCENCE_THICKNESS,
            &ANISOTROPY_STRENGTH,
            &ANISOTROPY_ROTATION,
            &TRANSMISSION,
            &THICKNESS,
            &ATTENUATION_DISTANCE,
            &ATTENUATION_COLOR,
            &DISPERSION,
            &DIFFUSE_TRANSMISSION,
            &DIFFUSE_TRANSMISSION_COLOR,
        ],
        reciprocal: true,
        benched: false,
        energy_compensation: true,
        defaults: |_| {},
        weights: weights::diffuse,
        specular: |m| Specular::GltfPbr {
            base_color: m.base_color,
            metallic: m.metallic,
            roughness: m.roughness,
            layers: m.layers,
        },
        // GGX's lobe of width α = r² (slope_error); no transcendental
        // function: w = (1 − |V·H|)⁵ is taken by multiplications, the rest
        // is arithmetic and sqrt.
        f32_error: |m| slope_error((m.roughness * m.roughness).max(super::ROUGHNESS_FLOOR)),
        transcendental_error: |_| 0.0,
        albedo_table: GLTF_PBR_ALBEDO,
    },
    ModelRow {
        model: ReflectanceModel::Abc,
        summary: "ABC microfacets (Löw et al. 2012): k_d/π + k_s·F·D·G/(π (N·V)(N·I)), D = A/(1 + B(1 − cos θ_h))^C, V-groove G, dielectric F",
        form: Form::Paper,
        wgsl: &[
            "brdf/lambert.wgsl",
            "brdf/phong.wgsl",
            "brdf/fresnel.wgsl",
            "brdf/microfacet.wgsl",
            "brdf/abc.wgsl",
        ],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&K_D, &K_S, &ABC_A, &ABC_B, &ABC_C, &ETA_I, &ETA_T],
        reciprocal: true,
        benched: false,
        energy_compensation: false,
        // The published fit of MERL's gold-metallic-paint (Löw et al.
        // 2012; shared/measured/merl100_abc_fits.csv).
        defaults: |m| {
            m.abc_a = Rgb::new(1.685630, 1.147257, 0.418757);
            (m.abc_b, m.abc_c) = (53.738525, 1.511730);
            (m.eta_i, m.eta_t) = (1.0, 9.031934);
        },
        weights: weights::abc_published,
        specular: |m| Specular::Abc {
            a: m.abc_a,
            b: m.abc_b,
            c: m.abc_c,
            eta_i: m.eta_i,
            eta_t: m.eta_t,
        },
        f32_error: |m| abc_log_error(m.abc_c),
        transcendental_error: |m| EXP_ERROR + abc_log_error(m.abc_c),
        albedo_table: &[
            ("k_d=0", "gold-metallic-paint's lobe, published fit"),
            (
                "k_d=0,abc_a=0.262721,abc_b=3115416.5,abc_c=0.138407,eta_t=2.581633",
                "blue-fabric's red lobe, published fit",
            ),
        ],
    },
    ModelRow {
        model: ReflectanceModel::Unlit,
        summary: "unlit (glTF KHR_materials_unlit): the surface shows its base colour as radiance, f_r = 0",
        form: Form::Paper,
        wgsl: &["brdf/unlit.wgsl"],
        needs_tangents: false,
        terms: Terms::NONE,
        params: &[&BASE_COLOR],
        reciprocal: true,
        benched: false,
        energy_compensation: false,
        defaults: |_| {},
        weights: weights::none,
        specular: |m| Specular::Unlit {
            base_color: m.base_color,
        },
        // L = b is a copy: no arithmetic beyond the renderers' own.
        f32_error: no_error,
        transcendental_error: |_| 0.0,
        albedo_table: &[("base_color=1", "f_r = 0: reflects nothing")],
    },
];

/// abc's `(1 + B x)^−C` is `e^(−C ln(1 + B x))`: `C` times the error of
/// the logarithm, Vulkan's 2⁻²¹ absolute near 1 or 3 ulp of a value
/// whose `C` multiple is ≤ 80 where the lobe is not cut off (240ε), and 8ε
/// of rounding in its argument.
fn abc_log_error(c: f64) -> f64 {
    c * (8.0 * EPS + 2f64.powi(-21)) + 240.0 * EPS
}

const GLTF_PBR_ALBEDO: &[(&str, &str)] = &[
    (
        "base_color=1,metallic=1,roughness=0.1",
        "white metal: F = 1, D·Vis alone",
    ),
    ("base_color=1,metallic=1,roughness=0.5", ""),
    (
        "base_color=1,metallic=1,roughness=1",
        "single scattering loses energy",
    ),
    ("base_color=1,metallic=0,roughness=0.5", "white dielectric"),
    ("base_color=1,metallic=0,roughness=0.1", "white dielectric"),
    ("base_color=0.5,metallic=0.5,roughness=0.5", ""),
];

/// A measured material on the GPU is a trilinear look-up in a table of
/// `f32`: eight samples, seven lerps, each rounding once (the table's own
/// error against the source is the table test's, tests/measured.rs).
const MEASURED_F32_ERROR: f64 = 32.0 * EPS;

/// Oren-Nayar's WGSL: its file uses phong.wgsl's `COS_FLOOR`.
const ON_WGSL: &[&str] = &[
    "brdf/lambert.wgsl",
    "brdf/phong.wgsl",
    "brdf/oren_nayar.wgsl",
];

/// Oren-Nayar's rounding beyond the light loop's: about twenty more
/// roundings, and `tan β = sin β / cos β` doubles the relative error of
/// the cosines it divides by: 128ε.
const ON_ERROR: f64 = 128.0 * EPS;

/// The full Oren-Nayar model takes α and β from `atan2` (Vulkan allows
/// 4096 ulp): its terms hold them to the powers 3 ((2β/π)³), 4
/// ((4αβ/π²)²) and 2 ((2β/π)²), so each is off by at most 4 · 4096 ulp.
const ATAN2_TERMS_ERROR: f64 = 4.0 * 4096.0 * EPS;

const ON_ALBEDO: &[(&str, &str)] = &[
    ("k_d=1,sigma=0", "Lambert"),
    (
        "k_d=1,sigma=0.2",
        "fit, not energy-conserving: ρ > 1 near grazing",
    ),
    ("k_d=1,sigma=0.3", ""),
    ("k_d=1,sigma=1.5707963", "σ = π/2"),
];

const CT_ALBEDO: &[(&str, &str)] = &[
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=0.05",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=smith,roughness=1",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=v-groove,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=none,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=0.05",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=smith,roughness=1",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=v-groove,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=ggx,geometry=none,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=blinn-normalized,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=blinn-normalized,geometry=smith,roughness=1",
        "Smith G of the matched Beckmann slope",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=gaussian-normalized,geometry=smith,roughness=1",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=gaussian-normalized,geometry=smith,roughness=0.3",
        "",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=blinn,geometry=smith,roughness=0.3",
        "lecture D, peak 1",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=gaussian,geometry=smith,roughness=0.3",
        "lecture D, peak 1",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=beckmann,geometry=v-groove,denominator=lecture,roughness=0.3",
        "lecture: ÷ π(N·V)(N·I)",
    ),
    (
        "k_d=0,k_s=1,fresnel=none,distribution=blinn,geometry=v-groove,denominator=lecture,roughness=0.3",
        "all lecture terms",
    ),
    (
        "k_d=0,k_s=1,preset=gold,fresnel=conductor,roughness=0.3",
        "gold, exact Fresnel",
    ),
    (
        "k_d=0,k_s=1,preset=gold,fresnel=conductor-lecture,roughness=0.3",
        "gold, lecture Fresnel",
    ),
    (
        "k_d=0,k_s=1,preset=gold,fresnel=schlick,roughness=0.3",
        "gold, Schlick",
    ),
    (
        "k_d=0,k_s=1,preset=glass,fresnel=dielectric,roughness=0.3",
        "glass 1.5",
    ),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::param::{Kind, Widget};

    #[test]
    fn every_model_has_one_row() {
        for model in ReflectanceModel::ALL {
            assert_eq!(ROWS.iter().filter(|r| r.model == model).count(), 1);
        }
        assert_eq!(ROWS.len(), ReflectanceModel::ALL.len());
        let order: Vec<_> = ROWS.iter().map(|r| r.model).collect();
        assert_eq!(order, ReflectanceModel::ALL, "rows in the contract's order");
    }

    #[test]
    fn every_wgsl_file_exists() {
        let shaders = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        for r in ROWS {
            for f in r.wgsl {
                assert!(shaders.join(f).is_file(), "{}: no shaders/{f}", r.model);
            }
        }
    }

    #[test]
    fn keys_resolve_to_the_models_own_parameter() {
        assert!(std::ptr::eq(
            param_for(ReflectanceModel::Ward, "sigma").unwrap(),
            &WARD_SIGMA
        ));
        assert!(std::ptr::eq(
            param_for(ReflectanceModel::Lambert, "roughness").unwrap(),
            &ROUGHNESS
        ));
        assert!(param_for(ReflectanceModel::Lambert, "rougness").is_none());
    }

    #[test]
    fn every_widget_fits_its_kind() {
        for p in all_params() {
            let fits = match p.widget {
                Widget::ColorPicker => p.kind == Kind::Color,
                Widget::Slider { .. } => p.kind == Kind::Scalar,
                Widget::Drag { .. } => true,
            };
            assert!(fits, "{}: {:?} for a {:?}", p.key, p.widget, p.kind);
        }
    }

    #[test]
    fn samples_lie_in_the_range() {
        for p in all_params() {
            for &v in p.samples {
                assert!(p.range.contains(v), "{}: sample {v}", p.key);
            }
        }
    }
}
