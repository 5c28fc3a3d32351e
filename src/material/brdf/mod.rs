//! The `f64` reference of every reflectance model: the truth the WGSL in
//! `shaders/brdf/` is checked against. Same families, same function names,
//! same argument order as the WGSL, so one grep finds both homes.

pub mod lambert;
pub mod phong;

use super::{Material, ReflectanceModel};
use crate::scene::Rgb;
use glam::DVec3;

/// Lower bound for the cosines the lecture's forms divide by (`I·N`):
/// cos θ = 1e-6 is θ = 89.99994°. It keeps `f_r` finite (≤ k_s · 10⁶) where
/// the formula as written diverges; `f_r · cos θ_i` is unaffected above it.
pub const COS_FLOOR: f64 = 1e-6;

/// `f_r` of `material` for `N·I > 0`, `N·V > 0` (checked by the caller,
/// [`Material::f_r`]). Mirrors `eval_brdf` in the generated WGSL.
pub fn eval(material: &Material, wi: DVec3, wo: DVec3, n: DVec3) -> Rgb {
    let diffuse = lambert::lambert(material.k_d);
    match material.model {
        ReflectanceModel::Lambert => diffuse,
        ReflectanceModel::Phong => {
            diffuse + material.k_s * phong::phong_lecture(material.k_e, n, wi, wo)
        }
        ReflectanceModel::BlinnPhong => {
            diffuse + material.k_s * phong::blinn_phong_lecture(material.k_e, n, wi, wo)
        }
    }
}
