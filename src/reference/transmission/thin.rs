//! Light through a thin wall (`KHR_materials_transmission` without a
//! volume, and `KHR_materials_diffuse_transmission`): the directions on
//! the far side the reference looks along, each with its weight, so that
//! `Σ_k w_k L(ω_k)` stands for `∫ f_t(ω, V) L(ω) |N·ω| dω` over the far
//! hemisphere ([`crate::material::brdf::gltf_layers::transmission`]).
//!
//! * Specular, smooth (the material's own `α` below `STRAIGHT_ALPHA`,
//!   [`spreads`]): one ray straight on (`ω = −V`; the wall does not
//!   refract), of weight `(1 − m)(1 − max₃ F(μ_o)) T b`, the lobe's
//!   integral in the smooth limit. The lobe is then narrower than 10⁻³
//!   rad (0.06°).
//! * Specular, rougher: [`LOBE_SAMPLES`] GGX normals visible from `V`
//!   at the rendered `α` (the pixel's roughness floor included)
//!   (Heitz 2018) at the points of a Hammersley set
//!   ([`super::visible_normals`], shared with a volume's rough boundary),
//!   the mirror direction of `V` about each mirrored to the far side, of
//!   weight `f_t |cos θ_i| / pdf`. The set is the same for every pixel:
//!   deterministic, no noise, and exact for a uniform background (a
//!   furnace) up to the quadrature's error on the lobe itself (measured
//!   in tests/transmission.rs against `dfg::integrate`, docs/transmission.md);
//!   on a structured background the error is the Hammersley rule's,
//!   `O(log N / N)` of the background's variation over the lobe.
//! * Diffuse transmission: [`LOBE_SAMPLES`] cosine-distributed directions
//!   on the far side (a Hammersley set mapped by Malley's method), weight
//!   `f_t π`.
//!
//! The lobe is sampled only for the first rough wall along a path
//! (`depth 0`); a rough wall seen through another goes straight on with
//! the lobe's integral as its weight, so a pixel costs at most
//! `2 · LOBE_SAMPLES` paths.

use super::visible_normals::{LOBE_SAMPLES, hammersley, to_world, visible_normal};
use crate::base::Rgb;
use crate::material::Material;
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::gltf_layers::transmission::{
    gltf_transmitted_parts, mirrored, transmission_fresnel,
};
use crate::material::brdf::microfacet::{d_ggx, lambda_ggx};
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// Below this GGX α the specular lobe is followed as one straight ray.
pub const STRAIGHT_ALPHA: f64 = 1e-3;

/// Whether a lobe of rendered GGX `alpha` is followed as a lobe: the
/// material's own `α`, the rendered one without the pixel's roughness
/// floor `floor` that [`Material::with_roughness_floor`] adds in
/// quadrature (`α² = alpha² − floor²`), at least [`STRAIGHT_ALPHA`].
/// The floor widens lobes so that a light's highlight covers a pixel; a
/// smooth surface sends what lies behind it along one ray, which the
/// pixel grid resolves as sharply as it can. Deciding on the rendered
/// `alpha` would make every surface rough at ordinary image sizes (the
/// floor of a 40° view 200 pixels high is 1.7·10⁻³) and cost
/// [`LOBE_SAMPLES`] paths for a blur of under a pixel.
pub fn spreads(alpha: f64, floor: f64) -> bool {
    alpha * alpha - floor * floor >= STRAIGHT_ALPHA * STRAIGHT_ALPHA
}

/// A direction on the far side (pointing away from the wall) and its weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub direction: DVec3,
    pub weight: Rgb,
}

/// The directions through a thin wall of `material` (roughness and base
/// colour as rendered) seen from `wo` in `frame` (its normal on the
/// viewer's side), sampling the lobes when `sample_lobes`, else straight
/// on with the lobes' weights; the specular lobe is sampled only where
/// it [`spreads`] beyond the pixel's roughness floor `floor`.
pub fn thin_samples(
    material: &Material,
    frame: &SurfaceFrame,
    wo: DVec3,
    sample_lobes: bool,
    floor: f64,
) -> Vec<Sample> {
    let n = frame.n;
    let l = &material.layers;
    let (b, m, r) = (material.base_color, material.metallic, material.roughness);
    let alpha = r * r;
    let cos_o = n.dot(wo);
    let mut out = Vec::new();
    if cos_o <= 0.0 {
        return out;
    }
    let straight = -wo;
    let at = |wi: DVec3| gltf_transmitted_parts(b, m, r, l, 0.0, 0.0, n, wi, wo);
    let lobe_weight = |diffuse: bool| {
        // The lobe's integral for the straight ray: the smooth limit of
        // the specular one; the diffuse one by the Fresnel term at N.
        let f = transmission_fresnel(l, n, wo).max_element();
        let mut s = (1.0 - m) * (1.0 - f);
        if l.has_clearcoat() {
            s *= 1.0
                - l.clearcoat
                    * crate::material::brdf::gltf_layers::clearcoat::clearcoat_fresnel(cos_o);
        }
        if diffuse {
            l.diffuse_transmission_color * ((1.0 - l.transmission) * l.diffuse_transmission * s)
        } else {
            b * (l.transmission * s)
        }
    };
    if l.transmission > 0.0 {
        if !spreads(alpha, floor) || !sample_lobes {
            out.push(Sample {
                direction: straight,
                weight: lobe_weight(false),
            });
        } else {
            let n_samples = LOBE_SAMPLES;
            // The view in the frame's coordinates.
            let v = DVec3::new(frame.t.dot(wo), frame.b.dot(wo), cos_o);
            let g1_v = 1.0 / (1.0 + lambda_ggx(alpha, cos_o));
            for k in 0..n_samples {
                let (u1, u2) = hammersley(k, n_samples);
                let h_local = visible_normal(v, alpha, u1, u2);
                let h = to_world(frame, h_local);
                let vh = wo.dot(h);
                let reflected = h * (2.0 * vh) - wo;
                if vh <= 0.0 || n.dot(reflected) <= 0.0 {
                    continue;
                }
                let wi = mirrored(n, reflected);
                // The density of the reflected direction: the visible
                // normals' `G1(V) max(0, V·H) D(H) / (N·V)` over `4 V·H`.
                let cos_h = h_local.z;
                let sin2_h = h_local.x * h_local.x + h_local.y * h_local.y;
                let pdf = g1_v * d_ggx(alpha, cos_h, sin2_h) / (4.0 * cos_o);
                if pdf <= 0.0 {
                    continue;
                }
                let (specular, _) = at(wi);
                out.push(Sample {
                    direction: wi,
                    weight: specular * (-n.dot(wi) / pdf / n_samples as f64),
                });
            }
        }
    }
    if l.diffuse_transmission > 0.0 && l.transmission < 1.0 {
        if !sample_lobes {
            out.push(Sample {
                direction: straight,
                weight: lobe_weight(true),
            });
        } else {
            let n_samples = LOBE_SAMPLES;
            for k in 0..n_samples {
                let (u1, u2) = hammersley(k, n_samples);
                let (sin_t, phi) = (u1.sqrt(), TAU * u2);
                let cos_t = (1.0 - u1).sqrt();
                let wi = to_world(
                    frame,
                    DVec3::new(sin_t * phi.cos(), sin_t * phi.sin(), -cos_t),
                );
                let (_, diffuse) = at(wi);
                out.push(Sample {
                    direction: wi,
                    weight: diffuse * (PI / n_samples as f64),
                });
            }
        }
    }
    out
}
