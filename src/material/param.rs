//! Material parameters as the table of models describes them, and every
//! parameter gonio's models take (`K_D`, `ROUGHNESS`, ...). Each has its
//! scene-file key, its label in the viewer, its kind, its contract range
//! (what [`super::Material::validate`] checks), its widget, and how it
//! reads and writes the [`Material`] field(s) it stands for.
//!
//! A parameter is a `static` (not a `const`): rows refer to it by address,
//! and two parameters may share a key while binding different fields (Ward's
//! `sigma` sets σ_x = σ_y; another model's `sigma` may be an angle of its
//! own). [`super::table::param_for`] resolves a key for a model.

use super::Material;
use crate::base::Rgb;

/// A parameter's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// Three channels (a colour or a per-channel index of refraction).
    Color(Rgb),
    Scalar(f64),
}

impl Value {
    /// The triple (one number stands for all three channels).
    pub fn color(self) -> Rgb {
        match self {
            Value::Color(c) => c,
            Value::Scalar(v) => Rgb::splat(v),
        }
    }

    /// The number (a triple's first channel).
    pub fn scalar(self) -> f64 {
        match self {
            Value::Color(c) => c.x,
            Value::Scalar(v) => v,
        }
    }
}

/// Whether a parameter is a triple or one number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Color,
    Scalar,
}

/// The contract's range of a parameter (of every channel, for a triple);
/// [`Param::check`] words the violation the way scene-file errors do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// `[min, max]`; `text` is how messages write it, e.g. `[0, 1e6]`.
    Closed {
        min: f64,
        max: f64,
        text: &'static str,
    },
    /// `(min, max]`, e.g. a roughness in `(0, 1]`.
    OpenClosed {
        min: f64,
        max: f64,
        text: &'static str,
    },
    /// Finite and `> 0`.
    Positive,
    /// Finite and `≥ 0`.
    NonNegative,
    /// `> 0`, `∞` included (a distance where `∞` means "never", glTF's
    /// `attenuationDistance`).
    PositiveOrInfinite,
    /// Finite and `≥ min`; `text` as messages write it, e.g. `≥ 1`.
    AtLeast { min: f64, text: &'static str },
    /// Exactly 0, or finite and `≥ min` (glTF's `ior`: 0 or ≥ 1).
    ZeroOrAtLeast { min: f64, text: &'static str },
    /// Any finite number (an angle).
    Finite,
}

impl Range {
    /// Whether `v` (one channel) is inside.
    pub fn contains(self, v: f64) -> bool {
        match self {
            Range::Closed { min, max, .. } => v.is_finite() && v >= min && v <= max,
            Range::OpenClosed { min, max, .. } => v > min && v <= max,
            Range::Positive => v.is_finite() && v > 0.0,
            Range::NonNegative => v.is_finite() && v >= 0.0,
            Range::PositiveOrInfinite => v > 0.0,
            Range::AtLeast { min, .. } => v.is_finite() && v >= min,
            Range::ZeroOrAtLeast { min, .. } => v == 0.0 || (v.is_finite() && v >= min),
            Range::Finite => v.is_finite(),
        }
    }

    /// The lower and upper end as numbers (for sweeps): an open lower end
    /// and an unbounded upper end are returned as they are (`min`, ∞).
    pub fn bounds(self) -> (f64, f64) {
        match self {
            Range::Closed { min, max, .. } | Range::OpenClosed { min, max, .. } => (min, max),
            Range::Positive
            | Range::NonNegative
            | Range::PositiveOrInfinite
            | Range::ZeroOrAtLeast { .. } => (0.0, f64::INFINITY),
            Range::AtLeast { min, .. } => (min, f64::INFINITY),
            Range::Finite => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// What a message says after `key = value`: `is outside [0, 1]³`,
    /// `must be finite and > 0`.
    fn violation(self, kind: Kind) -> String {
        let cube = if kind == Kind::Color { "³" } else { "" };
        match self {
            Range::Closed { text, .. } | Range::OpenClosed { text, .. } => {
                format!("is outside {text}{cube}")
            }
            Range::Positive => "must be finite and > 0".into(),
            Range::NonNegative => "must be finite and ≥ 0".into(),
            Range::PositiveOrInfinite => "must be > 0 (inf: no attenuation)".into(),
            Range::AtLeast { text, .. } => format!("must be finite and {text}"),
            Range::ZeroOrAtLeast { text, .. } => format!("must be 0 or finite and {text}"),
            Range::Finite => "must be finite".into(),
        }
    }
}

/// How the viewer edits a parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Widget {
    /// A colour picker (sRGB) beside the three linear values.
    ColorPicker,
    /// A slider over `[min, max]`, logarithmic or linear.
    Slider { min: f64, max: f64, scale: Scale },
    /// Drag values (one per channel of a triple) with this speed and range.
    Drag { speed: f64, min: f64, max: f64 },
}

/// A slider's scale.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Linear,
    /// For parameters spanning decades (exponents, roughness).
    Log,
}

/// One parameter: see the module doc.
#[derive(Debug)]
pub struct Param {
    /// The scene-file key, `[materials.NAME] KEY = ...`.
    pub key: &'static str,
    /// The viewer's label.
    pub label: &'static str,
    pub kind: Kind,
    pub range: Range,
    pub widget: Widget,
    /// Whether it is a field of its own: "Save scene" writes it and
    /// [`Material::validate`] checks it. `false` for a parameter that only
    /// sets fields others stand for (Ward's `sigma` sets σ_x and σ_y).
    pub stored: bool,
    /// Values across the range (per channel for a triple) that the
    /// equivalence test sweeps; the property tests draw between the
    /// smallest and the largest (log-uniformly for a [`Scale::Log`] slider).
    pub samples: &'static [f64],
    pub get: fn(&Material) -> Value,
    pub set: fn(&mut Material, Value),
}

impl Param {
    /// The value in `m`.
    pub fn read(&self, m: &Material) -> Value {
        (self.get)(m)
    }

    /// Sets the value in `m` (no range check: [`Material::validate`]).
    pub fn write(&self, m: &mut Material, v: Value) {
        (self.set)(m, v)
    }

    /// `m`'s value against the range; the message names the material and
    /// the key, as [`Material::validate`] reports it.
    pub fn check(&self, m: &Material) -> Result<(), String> {
        let name = &m.name;
        let (key, range) = (self.key, self.range);
        match self.read(m) {
            Value::Color(v) if !v.to_array().iter().all(|&c| range.contains(c)) => Err(format!(
                "material `{name}`: {key} = [{}, {}, {}] {}",
                v.x,
                v.y,
                v.z,
                range.violation(self.kind)
            )),
            Value::Scalar(v) if !range.contains(v) => Err(format!(
                "material `{name}`: {key} = {v} {}",
                range.violation(self.kind)
            )),
            _ => Ok(()),
        }
    }
}

// ---------------------------------------------------------------------
// The parameters of gonio's models (rows of the table refer to them).

const UNIT: Range = Range::Closed {
    min: 0.0,
    max: 1.0,
    text: "[0, 1]",
};
const SLOPE: Range = Range::OpenClosed {
    min: 0.0,
    max: 1.0,
    text: "(0, 1]",
};
const SLOPE_SLIDER: Widget = Widget::Slider {
    min: 1e-4,
    max: 1.0,
    scale: Scale::Log,
};
/// Roughness values the equivalence test sweeps, 1e-4 to 1.
const SLOPE_SAMPLES: &[f64] = &[1e-4, 1e-3, 0.01, 0.05, 0.1, 0.3, 0.5, 0.8, 1.0];
const INDEX: Widget = Widget::Drag {
    speed: 0.005,
    min: 0.0,
    max: 50.0,
};
const INDEX_SAMPLES: &[f64] = &[1.0, 1.0001, 1.01, 1.5, 0.37, 2.485];
const MEDIUM: Widget = Widget::Drag {
    speed: 0.005,
    min: 0.01,
    max: 10.0,
};

/// Ambient coefficient `k_a`.
pub static K_A: Param = Param {
    key: "k_a",
    label: "k_a",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[0.0, 0.5, 1.0],
    get: |m| Value::Color(m.k_a),
    set: |m, v| m.k_a = v.color(),
};
/// Diffuse albedo `k_d`.
pub static K_D: Param = Param {
    key: "k_d",
    label: "k_d",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[0.0, 0.2, 0.5, 1.0],
    get: |m| Value::Color(m.k_d),
    set: |m, v| m.k_d = v.color(),
};
/// Specular coefficient `k_s`.
pub static K_S: Param = Param {
    key: "k_s",
    label: "k_s",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[0.0, 0.3, 0.7, 1.0],
    get: |m| Value::Color(m.k_s),
    set: |m, v| m.k_s = v.color(),
};
/// Phong exponent `k_e`.
pub static K_E: Param = Param {
    key: "k_e",
    label: "k_e",
    kind: Kind::Scalar,
    range: Range::Closed {
        min: 0.0,
        max: 1e6,
        text: "[0, 1e6]",
    },
    widget: Widget::Slider {
        min: 1e-2,
        max: 1e6,
        scale: Scale::Log,
    },
    stored: true,
    samples: &[0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6],
    get: |m| Value::Scalar(m.k_e),
    set: |m, v| m.k_e = v.scalar(),
};
/// Microfacet roughness `m` (or α).
pub static ROUGHNESS: Param = Param {
    key: "roughness",
    label: "roughness m",
    kind: Kind::Scalar,
    range: SLOPE,
    widget: SLOPE_SLIDER,
    stored: true,
    samples: SLOPE_SAMPLES,
    get: |m| Value::Scalar(m.roughness),
    set: |m, v| m.roughness = v.scalar(),
};
/// Ward's isotropic σ: sets σ_x = σ_y.
pub static WARD_SIGMA: Param = Param {
    key: "sigma",
    label: "σ",
    kind: Kind::Scalar,
    range: SLOPE,
    widget: SLOPE_SLIDER,
    stored: false,
    samples: SLOPE_SAMPLES,
    get: |m| Value::Scalar(m.sigma_x),
    set: |m, v| (m.sigma_x, m.sigma_y) = (v.scalar(), v.scalar()),
};
/// Ward's σ_x, along the tangent.
pub static SIGMA_X: Param = Param {
    key: "sigma_x",
    label: "σ_x",
    kind: Kind::Scalar,
    range: SLOPE,
    widget: SLOPE_SLIDER,
    stored: true,
    samples: SLOPE_SAMPLES,
    get: |m| Value::Scalar(m.sigma_x),
    set: |m, v| m.sigma_x = v.scalar(),
};
/// Ward's σ_y, along the bitangent.
pub static SIGMA_Y: Param = Param {
    key: "sigma_y",
    label: "σ_y",
    kind: Kind::Scalar,
    range: SLOPE,
    widget: SLOPE_SLIDER,
    stored: true,
    samples: SLOPE_SAMPLES,
    get: |m| Value::Scalar(m.sigma_y),
    set: |m, v| m.sigma_y = v.scalar(),
};
/// Oren-Nayar's σ, the standard deviation of the facets' slope angle in
/// radians (Oren & Nayar 1994): 0 is Lambert, π/2 the roughest surface
/// the model describes. Same key as Ward's `sigma`, another meaning.
pub static FACET_SIGMA: Param = Param {
    key: "sigma",
    label: "σ (facet slope, rad)",
    kind: Kind::Scalar,
    range: Range::Closed {
        min: 0.0,
        max: std::f64::consts::FRAC_PI_2,
        text: "[0, π/2]",
    },
    widget: Widget::Slider {
        min: 0.0,
        max: std::f64::consts::FRAC_PI_2,
        scale: Scale::Linear,
    },
    stored: true,
    samples: &[0.0, 0.05, 0.2, 0.5, 1.0, std::f64::consts::FRAC_PI_2],
    get: |m| Value::Scalar(m.facet_sigma),
    set: |m, v| m.facet_sigma = v.scalar(),
};
/// A conductor's η (real part of the index), per channel.
pub static ETA: Param = Param {
    key: "eta",
    label: "η (R G B)",
    kind: Kind::Color,
    range: Range::Positive,
    widget: INDEX,
    stored: true,
    samples: INDEX_SAMPLES,
    get: |m| Value::Color(m.eta),
    set: |m, v| m.eta = v.color(),
};
/// A conductor's κ (extinction), per channel.
pub static KAPPA: Param = Param {
    key: "kappa",
    label: "κ (R G B)",
    kind: Kind::Color,
    range: Range::NonNegative,
    widget: INDEX,
    stored: true,
    samples: &[0.0, 0.5, 2.82, 3.638, 10.0],
    get: |m| Value::Color(m.kappa),
    set: |m, v| m.kappa = v.color(),
};
/// A dielectric's index on the incident side.
pub static ETA_I: Param = Param {
    key: "eta_i",
    label: "η_i",
    kind: Kind::Scalar,
    range: Range::Positive,
    widget: MEDIUM,
    stored: true,
    samples: &[1.0, 1.333, 1.5],
    get: |m| Value::Scalar(m.eta_i),
    set: |m, v| m.eta_i = v.scalar(),
};
/// A dielectric's index on the transmitted side.
pub static ETA_T: Param = Param {
    key: "eta_t",
    label: "η_t",
    kind: Kind::Scalar,
    range: Range::Positive,
    widget: MEDIUM,
    stored: true,
    samples: &[1.0, 1.0001, 1.01, 1.5],
    get: |m| Value::Scalar(m.eta_t),
    set: |m, v| m.eta_t = v.scalar(),
};
/// gltf-pbr's base colour `b` (glTF's `baseColorFactor`, linear).
pub static BASE_COLOR: Param = Param {
    key: "base_color",
    label: "base colour",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[0.0, 0.2, 0.5, 1.0],
    get: |m| Value::Color(m.base_color),
    set: |m, v| m.base_color = v.color(),
};
/// gltf-pbr's metallic `m` (glTF's `metallicFactor`).
pub static METALLIC: Param = Param {
    key: "metallic",
    label: "metallic",
    kind: Kind::Scalar,
    range: UNIT,
    widget: Widget::Slider {
        min: 0.0,
        max: 1.0,
        scale: Scale::Linear,
    },
    stored: true,
    samples: &[0.0, 0.25, 0.5, 0.9, 1.0],
    get: |m| Value::Scalar(m.metallic),
    set: |m, v| m.metallic = v.scalar(),
};
/// gltf-pbr's roughness: glTF's *perceptual* roughness r, GGX α = r² (the
/// same key and field as Cook-Torrance's `roughness`, which is α itself).
/// Its samples start at 0.01 (α = 1e-4, the renderer's floor).
pub static PERCEPTUAL_ROUGHNESS: Param = Param {
    key: "roughness",
    label: "roughness r (α = r²)",
    kind: Kind::Scalar,
    range: SLOPE,
    widget: Widget::Slider {
        min: 0.01,
        max: 1.0,
        scale: Scale::Linear,
    },
    stored: false,
    samples: &[0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0],
    get: |m| Value::Scalar(m.roughness),
    set: |m, v| m.roughness = v.scalar(),
};
/// abc's `A`, per channel: the distribution's peak `D(0)` in 1/sr (Löw
/// et al. 2012 fold the microfacet density's scale and the specular
/// albedo into it; the published MERL fits span 0.08 to 5710).
pub static ABC_A: Param = Param {
    key: "abc_a",
    label: "A (R G B)",
    kind: Kind::Color,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 0.1,
        min: 0.0,
        max: 1e6,
    },
    stored: true,
    samples: &[0.0, 0.1, 1.0, 100.0, 5000.0],
    get: |m| Value::Color(m.abc_a),
    set: |m, v| m.abc_a = v.color(),
};
/// abc's `B`: the inverse width of the lobe in `1 − cos θ_h` (the
/// published MERL fits span 11 to 8.1e6).
pub static ABC_B: Param = Param {
    key: "abc_b",
    label: "B",
    kind: Kind::Scalar,
    range: Range::Positive,
    widget: Widget::Slider {
        min: 1.0,
        max: 1e8,
        scale: Scale::Log,
    },
    stored: true,
    samples: &[1.0, 10.0, 1e3, 1e5, 1e7],
    get: |m| Value::Scalar(m.abc_b),
    set: |m, v| m.abc_b = v.scalar(),
};
/// abc's `C`: the power of the tail, `D ∝ (1 − cos θ_h)^−C` far from the
/// peak (the published MERL fits span 0.024 to 2.7).
pub static ABC_C: Param = Param {
    key: "abc_c",
    label: "C",
    kind: Kind::Scalar,
    range: Range::Positive,
    widget: Widget::Slider {
        min: 0.01,
        max: 10.0,
        scale: Scale::Log,
    },
    stored: true,
    samples: &[0.02, 0.1, 0.5, 1.0, 2.0, 3.0],
    get: |m| Value::Scalar(m.abc_c),
    set: |m, v| m.abc_c = v.scalar(),
};
/// Emitted radiance [W/(m²·sr)], every model's: it adds to `L_o`.
pub static EMISSION: Param = Param {
    key: "emission",
    label: "emission [W/(m²·sr)]",
    kind: Kind::Color,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 0.01,
        min: 0.0,
        max: 1e6,
    },
    stored: true,
    samples: &[0.0, 1.0],
    get: |m| Value::Color(m.emission),
    set: |m, v| m.emission = v.color(),
};

// ---------------------------------------------------------------------
// gltf-pbr's layers (contract: "Layered glTF materials", keys): the glTF
// property names in snake_case, with the glTF defaults (`GltfLayers`).
//
// Their `samples` are the defaults alone until the GPU's gltf-pbr
// dispatch reads the layers: the model-wide sweeps (tests/brdf_equivalence.rs,
// tests/brdf_properties.rs) compare the GPU renderer's model, and the
// layers are swept over their ranges by tests/layer_equivalence.rs and
// tests/layer_properties.rs.

const UNIT_SLIDER: Widget = Widget::Slider {
    min: 0.0,
    max: 1.0,
    scale: Scale::Linear,
};

/// `KHR_materials_ior.ior`: 0 is the specular-glossiness mode (the IOR's
/// Fresnel term is 1), else ≥ 1.
pub static IOR: Param = Param {
    key: "ior",
    label: "ior (0: specular-glossiness)",
    kind: Kind::Scalar,
    range: Range::ZeroOrAtLeast {
        min: 1.0,
        text: "≥ 1",
    },
    widget: Widget::Drag {
        speed: 0.005,
        min: 0.0,
        max: 10.0,
    },
    stored: true,
    samples: &[1.5],
    get: |m| Value::Scalar(m.layers.ior),
    set: |m, v| m.layers.ior = v.scalar(),
};
/// `KHR_materials_specular.specularFactor`, `s_w`.
pub static SPECULAR: Param = Param {
    key: "specular",
    label: "specular weight",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[1.0],
    get: |m| Value::Scalar(m.layers.specular),
    set: |m, v| m.layers.specular = v.scalar(),
};
/// `KHR_materials_specular.specularColorFactor`, `c_s` (may exceed 1).
pub static SPECULAR_COLOR: Param = Param {
    key: "specular_color",
    label: "specular colour",
    kind: Kind::Color,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 0.01,
        min: 0.0,
        max: 100.0,
    },
    stored: true,
    samples: &[1.0],
    get: |m| Value::Color(m.layers.specular_color),
    set: |m, v| m.layers.specular_color = v.color(),
};
/// `KHR_materials_clearcoat.clearcoatFactor`, `k`.
pub static CLEARCOAT: Param = Param {
    key: "clearcoat",
    label: "clearcoat",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.clearcoat),
    set: |m, v| m.layers.clearcoat = v.scalar(),
};
/// `…clearcoatRoughnessFactor`, perceptual `r_c` (0: a mirror coat).
pub static CLEARCOAT_ROUGHNESS: Param = Param {
    key: "clearcoat_roughness",
    label: "clearcoat roughness r_c (α = r_c²)",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.clearcoat_roughness),
    set: |m, v| m.layers.clearcoat_roughness = v.scalar(),
};
/// `KHR_materials_sheen.sheenColorFactor`, `c_sh`.
pub static SHEEN_COLOR: Param = Param {
    key: "sheen_color",
    label: "sheen colour",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Color(m.layers.sheen_color),
    set: |m, v| m.layers.sheen_color = v.color(),
};
/// `…sheenRoughnessFactor`, perceptual `r_sh`.
pub static SHEEN_ROUGHNESS: Param = Param {
    key: "sheen_roughness",
    label: "sheen roughness",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.sheen_roughness),
    set: |m, v| m.layers.sheen_roughness = v.scalar(),
};
/// `KHR_materials_iridescence.iridescenceFactor`, `ι`.
pub static IRIDESCENCE: Param = Param {
    key: "iridescence",
    label: "iridescence",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.iridescence),
    set: |m, v| m.layers.iridescence = v.scalar(),
};
/// `…iridescenceIor`, the film's index `η_f`.
pub static IRIDESCENCE_IOR: Param = Param {
    key: "iridescence_ior",
    label: "film ior",
    kind: Kind::Scalar,
    range: Range::AtLeast {
        min: 1.0,
        text: "≥ 1",
    },
    widget: Widget::Drag {
        speed: 0.005,
        min: 1.0,
        max: 5.0,
    },
    stored: true,
    samples: &[1.3],
    get: |m| Value::Scalar(m.layers.iridescence_ior),
    set: |m, v| m.layers.iridescence_ior = v.scalar(),
};
/// The film's thickness `d` \[nm\] (`…iridescenceThicknessMaximum`; with a
/// thickness texture the maximum).
pub static IRIDESCENCE_THICKNESS: Param = Param {
    key: "iridescence_thickness",
    label: "film thickness [nm]",
    kind: Kind::Scalar,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 1.0,
        min: 0.0,
        max: 2000.0,
    },
    stored: true,
    samples: &[400.0],
    get: |m| Value::Scalar(m.layers.iridescence_thickness),
    set: |m, v| m.layers.iridescence_thickness = v.scalar(),
};
/// `KHR_materials_anisotropy.anisotropyStrength`, `s_a`.
pub static ANISOTROPY_STRENGTH: Param = Param {
    key: "anisotropy_strength",
    label: "anisotropy strength",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.anisotropy_strength),
    set: |m, v| m.layers.anisotropy_strength = v.scalar(),
};
/// `…anisotropyRotation`, `ρ` \[rad\] from the tangent towards the
/// bitangent.
pub static ANISOTROPY_ROTATION: Param = Param {
    key: "anisotropy_rotation",
    label: "anisotropy rotation ρ [rad]",
    kind: Kind::Scalar,
    range: Range::Finite,
    widget: Widget::Slider {
        min: -std::f64::consts::PI,
        max: std::f64::consts::PI,
        scale: Scale::Linear,
    },
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.anisotropy_rotation),
    set: |m, v| m.layers.anisotropy_rotation = v.scalar(),
};

// ---------------------------------------------------------------------
// Light through surfaces (contract: "Layered glTF materials", "Light
// through surfaces"): KHR_materials_transmission, _volume, _dispersion and
// _diffuse_transmission. The reference traces them
// (`reference::transmission`), the GPU draws them in screen space
// (shaders/transmission.wgsl, docs/transmission.md).

/// `KHR_materials_transmission.transmissionFactor`.
pub static TRANSMISSION: Param = Param {
    key: "transmission",
    label: "transmission",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.transmission),
    set: |m, v| m.layers.transmission = v.scalar(),
};
/// `KHR_materials_volume.thicknessFactor` (mesh space; 0: thin-walled).
pub static THICKNESS: Param = Param {
    key: "thickness",
    label: "volume thickness (0: thin-walled)",
    kind: Kind::Scalar,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 0.01,
        min: 0.0,
        max: 1e6,
    },
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.thickness),
    set: |m, v| m.layers.thickness = v.scalar(),
};
/// `KHR_materials_volume.attenuationDistance` (`inf`: a clear medium).
pub static ATTENUATION_DISTANCE: Param = Param {
    key: "attenuation_distance",
    label: "attenuation distance (inf: none)",
    kind: Kind::Scalar,
    range: Range::PositiveOrInfinite,
    widget: Widget::Drag {
        speed: 0.01,
        min: 1e-6,
        max: f64::INFINITY,
    },
    stored: true,
    samples: &[f64::INFINITY],
    get: |m| Value::Scalar(m.layers.attenuation_distance),
    set: |m, v| m.layers.attenuation_distance = v.scalar(),
};
/// `KHR_materials_volume.attenuationColor`.
pub static ATTENUATION_COLOR: Param = Param {
    key: "attenuation_color",
    label: "attenuation colour",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[1.0],
    get: |m| Value::Color(m.layers.attenuation_color),
    set: |m, v| m.layers.attenuation_color = v.color(),
};
/// `KHR_materials_dispersion.dispersion`, `20 / V_d`.
pub static DISPERSION: Param = Param {
    key: "dispersion",
    label: "dispersion (20 / Abbe number)",
    kind: Kind::Scalar,
    range: Range::NonNegative,
    widget: Widget::Drag {
        speed: 0.01,
        min: 0.0,
        max: 10.0,
    },
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.dispersion),
    set: |m, v| m.layers.dispersion = v.scalar(),
};
/// `KHR_materials_diffuse_transmission.diffuseTransmissionFactor`.
pub static DIFFUSE_TRANSMISSION: Param = Param {
    key: "diffuse_transmission",
    label: "diffuse transmission",
    kind: Kind::Scalar,
    range: UNIT,
    widget: UNIT_SLIDER,
    stored: true,
    samples: &[0.0],
    get: |m| Value::Scalar(m.layers.diffuse_transmission),
    set: |m, v| m.layers.diffuse_transmission = v.scalar(),
};
/// `KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor`.
pub static DIFFUSE_TRANSMISSION_COLOR: Param = Param {
    key: "diffuse_transmission_color",
    label: "diffuse transmission colour",
    kind: Kind::Color,
    range: UNIT,
    widget: Widget::ColorPicker,
    stored: true,
    samples: &[1.0],
    get: |m| Value::Color(m.layers.diffuse_transmission_color),
    set: |m, v| m.layers.diffuse_transmission_color = v.color(),
};
