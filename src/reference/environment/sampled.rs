//! The environment integrated per shading point through the whole BRDF
//! (`environment.specular = "sampled"`, `environment.samples = N`):
//! `L_o = ∫ f_r(ω_i, ω_o) L_env(ω_i) cos θ_i dω_i`, estimated with N
//! directions of three strategies combined by multiple importance
//! sampling (Veach & Guibas 1995, the balance heuristic in its
//! multi-sample form): cosine-weighted directions (`p_c = cos θ/π`),
//! directions of the material's BRDF lobe (`p_b`, [`super::lobe`]) and
//! directions of the map's light (`p_m`,
//! [`crate::environment::importance`]), each weighted as a sample of the
//! mixture,
//! `L_o ≈ Σ_k f_r(ω_k) L_env(ω_k) cos θ_k / (n_c p_c + n_b p_b + n_m p_m)`.
//! The split ([`split`]): the map takes `⌊N/s⌋` of the N, `s` the number
//! of strategies (3 with a lobe, 2 without), and the rest is shared by
//! the cosine (`⌈rest/2⌉`) and the lobe. A material with no lobe
//! (Lambert, a zero `k_s`, …) has no lobe directions; a map whose light
//! is not concentrated (a uniform one) no map directions.
//!
//! Each strategy takes the Hammersley set of its own size,
//! `u = ((k + ½)/n, radical_inverse₂(k))`: deterministic, the same
//! directions for every pixel of the same normal and view. The cosine
//! directions keep the estimate unbiased wherever the other densities do
//! not reach (the diffuse term, the lobe's cut-off tails, a texel whose
//! bilinear radiance its grid cell does not carry); the map's find a
//! small bright source, which the others hit by chance (a sun of 2.5°
//! is 1/500 of the hemisphere). A white map takes cosine and lobe
//! directions alone, so a Lambertian surface under it shows exactly
//! `k_d` for every N (`cos θ / p_c = π`). WGSL twin:
//! `environment_sampled` in shaders/environment_sampled.wgsl (same
//! directions, same order).
//!
//! The truth it is measured against ([`integrated`]) is the quadrature of
//! the map's texels ([`crate::environment::quadrature::nodes`]) through the BRDF.

use super::lobe::{self, Lobe};
use crate::base::{Rgb, SurfaceFrame, any_tangent};
use crate::environment::EnvironmentMap;
use crate::environment::quadrature::Node;
use crate::material::Material;
use crate::reference::brdf::reference_brdf;
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

/// How the N samples are shared by the strategies, drawn in this order:
/// cosine-weighted, the BRDF lobe, the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Split {
    pub cosine: u32,
    pub lobe: u32,
    pub map: u32,
}

/// The split of `n` samples for a material of `lobe` under a map that is
/// or is not drawn by (`by_map`,
/// [`crate::environment::importance::ImportanceTable::concentrated`]).
/// Twin: the split in `environment_sampled`.
pub fn split(n: u32, lobe: Lobe, by_map: bool) -> Split {
    let has_lobe = lobe != Lobe::None;
    let strategies = 1 + has_lobe as u32 + by_map as u32;
    let map = if by_map { n / strategies } else { 0 };
    let rest = n - map;
    let cosine = if has_lobe { rest.div_ceil(2) } else { rest };
    Split {
        cosine,
        lobe: rest - cosine,
        map,
    }
}

/// The N-sample estimate of `L_o` of `material` in `frame` seen from `wo`.
pub fn estimate(map: &EnvironmentMap, material: &Material, frame: &SurfaceFrame, wo: DVec3) -> Rgb {
    let n = map.settings.samples.max(1);
    let lobe = lobe::lobe(material);
    let table = map.data.importance();
    let Split {
        cosine: n_c,
        lobe: n_b,
        map: n_m,
    } = split(n, lobe, table.concentrated());
    // The directions' frame depends on the normal alone (the twin's
    // `any_tangent`), so both renderers draw the same directions whatever
    // tangent the mesh has.
    let t = any_tangent(frame.n);
    let b = frame.n.cross(t);
    let brdf = reference_brdf(material);
    let mut sum = Rgb::ZERO;
    for k in 0..n {
        let wi = if k < n_c {
            let l = local_direction(k, n_c);
            t * l.x + b * l.y + frame.n * l.z
        } else if k < n_c + n_b {
            let (u1, u2) = hammersley(k - n_c, n_b);
            lobe::direction(lobe, u1, u2, wo, frame.n, t, b)
        } else {
            let (u1, u2) = hammersley(k - n_c - n_b, n_m);
            map.from_map(table.direction(u1, u2))
        };
        let cos = frame.n.dot(wi);
        let p_b = if n_b > 0 {
            lobe::pdf(lobe, wi, wo, frame.n)
        } else {
            0.0
        };
        let p_m = if n_m > 0 {
            table.pdf(map.to_map(wi))
        } else {
            0.0
        };
        let mixture = n_c as f64 * cos.max(0.0) * FRAC_1_PI + n_b as f64 * p_b + n_m as f64 * p_m;
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
    let brdf = reference_brdf(material);
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
