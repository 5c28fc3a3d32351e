//! What surfaces do: validated material parameters and the reflectance
//! models of the lecture, as an `f64` reference ([`brdf`]).
//!
//! A [`Material`] holds parameters only; the maths lives in [`brdf`], one
//! file per family, mirrored function by function in `shaders/brdf/*.wgsl`.

pub mod brdf;
mod model;

pub use model::ReflectanceModel;

use crate::scene::Rgb;
use glam::DVec3;

/// A validated material. Build it with [`Material::new`] and
/// [`Material::validate`]; renderers trust what they get.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub model: ReflectanceModel,
    /// Ambient coefficient: the reflected ambient term is `k_a · L_a`.
    pub k_a: Rgb,
    /// Diffuse albedo: Lambert `f_r = k_d / π`. The lecture's `k_d` is in
    /// 1/sr and equals gonio's `k_d / π`.
    pub k_d: Rgb,
    /// Specular coefficient of the glossy lobe.
    pub k_s: Rgb,
    /// Phong / Blinn-Phong exponent, in [0, 1e6].
    pub k_e: f64,
}

impl Material {
    /// A material with the given model and neutral parameters: `k_d = 0.8`,
    /// `k_s = 0`, `k_a = 0`, `k_e = 32`.
    pub fn new(name: impl Into<String>, model: ReflectanceModel) -> Self {
        Material {
            name: name.into(),
            model,
            k_a: Rgb::ZERO,
            k_d: Rgb::splat(0.8),
            k_s: Rgb::ZERO,
            k_e: 32.0,
        }
    }

    /// Checks every parameter against the contract's ranges; the message
    /// names the parameter and the offending value.
    pub fn validate(&self) -> Result<(), String> {
        for (key, v) in [("k_a", self.k_a), ("k_d", self.k_d), ("k_s", self.k_s)] {
            if !v.is_finite() || v.min_element() < 0.0 || v.max_element() > 1.0 {
                return Err(format!(
                    "material `{}`: {key} = [{}, {}, {}] is outside [0, 1]³",
                    self.name, v.x, v.y, v.z
                ));
            }
        }
        if !(0.0..=1e6).contains(&self.k_e) {
            return Err(format!(
                "material `{}`: k_e = {} is outside [0, 1e6]",
                self.name, self.k_e
            ));
        }
        Ok(())
    }

    /// The BRDF `f_r(ω_i, ω_o)` [1/sr] at a point with unit shading normal
    /// `n`; `wi` points to the light, `wo` to the viewer (both unit).
    ///
    /// One-sided, as the contract says: zero where `N·I ≤ 0` or `N·V ≤ 0`.
    pub fn f_r(&self, wi: DVec3, wo: DVec3, n: DVec3) -> Rgb {
        let n_dot_i = n.dot(wi);
        let n_dot_o = n.dot(wo);
        if n_dot_i <= 0.0 || n_dot_o <= 0.0 {
            return Rgb::ZERO;
        }
        brdf::eval(self, wi, wo, n)
    }
}
