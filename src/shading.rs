//! The reflection equation for punctual lights, summed (contract):
//! `L_o = k_a·L_a + Σ_l f_r(ω_l, ω_o) · E_l · cosθ_l · V_l`.
//!
//! This is the CPU twin of `shade` in `shaders/shading.wgsl`.

use crate::material::Material;
use crate::scene::{Light, Rgb};
use glam::DVec3;

/// Reflected radiance at `x` with unit shading normal `n`, seen from `eye`.
/// `visibility(l, x)` is `V_l` in [0, 1] for light index `l`.
pub fn reflected_radiance(
    material: &Material,
    lights: &[Light],
    ambient: Rgb,
    x: DVec3,
    n: DVec3,
    eye: DVec3,
    visibility: impl Fn(usize, DVec3) -> f64,
) -> Rgb {
    let wo = (eye - x).normalize_or_zero();
    let mut radiance = material.k_a * ambient;
    for (l, light) in lights.iter().enumerate() {
        let incidence = light.incidence(x);
        let cos_theta_i = n.dot(incidence.wi);
        if cos_theta_i <= 0.0 {
            continue;
        }
        let v = visibility(l, x);
        if v <= 0.0 {
            continue;
        }
        radiance += material.f_r(incidence.wi, wo, n) * incidence.irradiance * (cos_theta_i * v);
    }
    radiance
}
