//! One material parameter as the table of models describes it: its
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
}

impl Range {
    /// Whether `v` (one channel) is inside.
    pub fn contains(self, v: f64) -> bool {
        match self {
            Range::Closed { min, max, .. } => v.is_finite() && v >= min && v <= max,
            Range::OpenClosed { min, max, .. } => v > min && v <= max,
            Range::Positive => v.is_finite() && v > 0.0,
            Range::NonNegative => v.is_finite() && v >= 0.0,
        }
    }

    /// The lower and upper end as numbers (for sweeps): an open lower end
    /// and an unbounded upper end are returned as they are (`min`, ∞).
    pub fn bounds(self) -> (f64, f64) {
        match self {
            Range::Closed { min, max, .. } | Range::OpenClosed { min, max, .. } => (min, max),
            Range::Positive | Range::NonNegative => (0.0, f64::INFINITY),
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
