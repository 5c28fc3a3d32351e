//! The environment integrated per shading point through the whole BRDF
//! (`environment.specular = "sampled"`, `environment.samples = N`):
//! `L_o = ∫ f_r(ω_i, ω_o) L_env(ω_i) cos θ_i dω_i`, estimated with N
//! directions of two strategies combined by multiple importance sampling
//! (Veach & Guibas 1995, the balance heuristic in its multi-sample form):
//! `n_c = ⌈N/2⌉` cosine-weighted directions (`p_c = cos θ/π`) and `n_b =
//! N − n_c` directions of the material's BRDF lobe (`p_b`,
//! [`super::lobe`]), each weighted as a sample of the mixture,
//! `L_o ≈ Σ_k f_r(ω_k) L_env(ω_k) cos θ_k / (n_c p_c(ω_k) + n_b p_b(ω_k))`.
//! Each strategy takes the Hammersley set of its own size,
//! `u = ((k + ½)/n, radical_inverse₂(k))`: deterministic, the same
//! directions for every pixel of the same normal and view. A material with
//! no lobe (Lambert, a zero `k_s`, …) takes all N cosine-weighted, which
//! is `(π/N) Σ f_r L_env` (`cos θ / p_c = π`): exact for a Lambertian
//! surface under a constant sky for every N. The estimate converges to
//! the integral as N grows; the cosine directions keep it unbiased
//! wherever the lobe's density does not reach (the diffuse term, the
//! lobe's cut-off tails). WGSL twin: `environment_sampled` in
//! shaders/environment_sampled.wgsl (same directions, same order).
//!
//! The truth it is measured against ([`integrated`]) is the quadrature of
//! the map's texels ([`crate::environment::quadrature::nodes`]) through the BRDF.

use super::lobe::{self, Lobe};
use crate::base::{Rgb, SurfaceFrame, any_tangent};
use crate::environment::EnvironmentMap;
use crate::environment::quadrature::Node;
use crate::material::Material;
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, TAU};

/// Sample `k` of `n`'s Hammersley point `((k + ½)/n, radical_inverse₂(k))`.
pub fn hammersley(k: u32, n: u32) -> (f64, f64) {
    let u1 = (k as f64 + 0.5) / n as f64;
    let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
    (u1, u2)
}

/// Sample `k` of `n`'s direction in the local frame (z = normal): the
/// Hammersley point mapped to the cosine-weighted hemisphere (Malley's
/// method).
pub fn local_direction(k: u32, n: u32) -> DVec3 {
    let (u1, u2) = hammersley(k, n);
    let r = u1.sqrt();
    let phi = TAU * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u1).sqrt())
}

/// How the N samples are split: `(n_c, n_b)`, cosine and lobe.
pub fn split(n: u32, lobe: Lobe) -> (u32, u32) {
    if lobe == Lobe::None {
        (n, 0)
    } else {
        let cosine = n.div_ceil(2);
        (cosine, n - cosine)
    }
}

/// The N-sample estimate of `L_o` of `material` in `frame` seen from `wo`.
pub fn estimate(map: &EnvironmentMap, material: &Material, frame: &SurfaceFrame, wo: DVec3) -> Rgb {
    let n = map.settings.samples.max(1);
    let lobe = lobe::lobe(material);
    let (n_c, n_b) = split(n, lobe);
    // The directions' frame depends on the normal alone (the twin's
    // `any_tangent`), so both renderers draw the same directions whatever
    // tangent the mesh has.
    let t = any_tangent(frame.n);
    let b = frame.n.cross(t);
    let brdf = material.brdf();
    let mut sum = Rgb::ZERO;
    for k in 0..n {
        let from_lobe = k >= n_c;
        let wi = if from_lobe {
            let (u1, u2) = hammersley(k - n_c, n_b);
            lobe::direction(lobe, u1, u2, wo, frame.n, t, b)
        } else {
            let l = local_direction(k, n_c);
            t * l.x + b * l.y + frame.n * l.z
        };
        let cos = frame.n.dot(wi);
        let p_b = if n_b > 0 {
            lobe::pdf(lobe, wi, wo, frame.n)
        } else {
            0.0
        };
        let mixture = n_c as f64 * cos.max(0.0) * FRAC_1_PI + n_b as f64 * p_b;
        if cos > 0.0 && mixture > 0.0 {
            sum += brdf.f_r(wi, wo, frame) * map.radiance(wi) * (cos / mixture);
        }
    }
    sum
}

/// The integral by the texel quadrature (the truth of the sampled mode).
pub fn integrated(
    map: &EnvironmentMap,
    nodes: &[Node],
    material: &Material,
    frame: &SurfaceFrame,
    wo: DVec3,
) -> Rgb {
    let brdf = material.brdf();
    let mut sum = Rgb::ZERO;
    for node in nodes {
        // The node's direction in world space (the map turned).
        let wi = map.from_map(node.direction);
        let cos = frame.n.dot(wi);
        if cos > 0.0 {
            sum += brdf.f_r(wi, wo, frame) * node.radiance * (cos * node.weight);
        }
    }
    sum * map.settings.scale
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::environment::{MapSettings, map::Specular, test_maps};
    use crate::material::ReflectanceModel;
    use std::sync::Arc;

    /// The estimate is finite and non-negative for every lobe kind at the
    /// mirror limit (roughness 0, taken to the renderer's floor as the
    /// renderers do; exponents of 10⁶ and 10⁸) and at grazing and
    /// back-facing views (`N·V` = 1e-7, 0, −1e-3).
    #[test]
    fn no_nan_at_the_mirror_limit_or_grazing() {
        let map = EnvironmentMap {
            data: Arc::new(test_maps::blobs()),
            settings: MapSettings {
                specular: Specular::Sampled,
                samples: 16,
                ..Default::default()
            },
        };
        let mut materials = Vec::new();
        for model in [
            ReflectanceModel::GltfPbr,
            ReflectanceModel::CookTorrance,
            ReflectanceModel::Ward,
            ReflectanceModel::PhongNormalized,
            ReflectanceModel::BlinnPhongNormalized,
            ReflectanceModel::BlinnPhong,
        ] {
            let mut m = Material::new("limit", model);
            (m.roughness, m.sigma_x, m.sigma_y, m.k_e) = (0.0, 0.0, 0.0, 1e6);
            m.k_s = Rgb::splat(0.5);
            materials.push(m.with_roughness_floor(0.0));
        }
        let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
        for m in &materials {
            for c in [1.0, 1e-7, 0.0, -1e-3] {
                let wo = DVec3::new((1.0f64 - c * c).sqrt(), 0.0, c);
                let l = estimate(&map, m, &frame, wo);
                assert!(
                    l.is_finite() && l.min_element() >= 0.0,
                    "{:?} at N·V = {c}: {l:?}",
                    m.model
                );
            }
        }
    }

    #[test]
    fn directions_are_unit_and_above_the_surface() {
        for k in 0..64 {
            let d = local_direction(k, 64);
            assert!((d.length() - 1.0).abs() < 1e-12 && d.z > 0.0);
        }
    }
}
