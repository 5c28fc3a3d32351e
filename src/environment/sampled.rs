//! The environment integrated per shading point through the whole BRDF
//! (`environment.specular = "sampled"`, `environment.samples = N`):
//! `L_o = ∫ f_r(ω_i, ω_o) L_env(ω_i) cos θ_i dω_i`, estimated with N
//! cosine-weighted directions of the Hammersley set,
//! `L_o ≈ (π/N) Σ_k f_r(ω_k, ω_o) L_env(ω_k)` (`cos θ / pdf = π`):
//! deterministic, exact for a Lambertian surface under a constant sky for
//! every N, and converging to the integral as N grows. WGSL twin:
//! `environment_sampled` in shaders/environment.wgsl (same directions, same
//! order).
//!
//! The truth it is measured against ([`integrated`]) is the quadrature of
//! the map's texels ([`super::quadrature::nodes`]) through the BRDF.

use super::EnvironmentMap;
use super::quadrature::Node;
use crate::base::{SurfaceFrame, any_tangent};
use crate::material::Material;
use crate::scene::Rgb;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// Sample `k` of `n`'s direction in the local frame (z = normal): the
/// Hammersley point `((k + ½)/n, radical_inverse₂(k))` mapped to the
/// cosine-weighted hemisphere (Malley's method).
pub fn local_direction(k: u32, n: u32) -> DVec3 {
    let u1 = (k as f64 + 0.5) / n as f64;
    let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
    let r = u1.sqrt();
    let phi = TAU * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).sqrt())
}

/// The N-sample estimate of `L_o` of `material` in `frame` seen from `wo`.
pub fn estimate(map: &EnvironmentMap, material: &Material, frame: &SurfaceFrame, wo: DVec3) -> Rgb {
    let n = map.settings.samples.max(1);
    // The directions' frame depends on the normal alone (the twin's
    // `any_tangent`), so both renderers draw the same directions whatever
    // tangent the mesh has.
    let t = any_tangent(frame.n);
    let b = frame.n.cross(t);
    let mut sum = Rgb::ZERO;
    for k in 0..n {
        let l = local_direction(k, n);
        let wi = t * l.x + b * l.y + frame.n * l.z;
        sum += material.f_r(wi, wo, frame) * map.radiance(wi);
    }
    sum * (PI / n as f64)
}

/// The integral by the texel quadrature (the truth of the sampled mode).
pub fn integrated(
    map: &EnvironmentMap,
    nodes: &[Node],
    material: &Material,
    frame: &SurfaceFrame,
    wo: DVec3,
) -> Rgb {
    let mut sum = Rgb::ZERO;
    for node in nodes {
        // The node's direction in world space (the map turned).
        let wi = map.from_map(node.direction);
        let cos = frame.n.dot(wi);
        if cos > 0.0 {
            sum += material.f_r(wi, wo, frame) * node.radiance * (cos * node.weight);
        }
    }
    sum * map.settings.scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_are_unit_and_above_the_surface() {
        for k in 0..64 {
            let d = local_direction(k, 64);
            assert!((d.length() - 1.0).abs() < 1e-12 && d.z > 0.0);
        }
    }
}
