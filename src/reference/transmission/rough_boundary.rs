//! The rays a rough volume boundary sends a path along: the rough
//! dielectric BSDF of Walter, Marschner, Li & Torrance 2007, "Microfacet
//! Models for Refraction through Rough Surfaces" (GGX, eq. 33; the BTDF
//! of eq. 21 is [`crate::material::brdf::gltf_layers::volume_btdf`]),
//! sampled at [`LOBE_SAMPLES`] microfacet normals visible from the viewer
//! (Heitz 2018, [`super::visible_normals`]) at the points of a Hammersley
//! set. Each normal `h` splits the path by the exact dielectric Fresnel
//! reflectance `F(i·h)` into the direction refracted through `h` (Snell's
//! law on the microfacet, weight `1 − F`) and the mirror direction about
//! `h` (weight `F`; all of it at total internal reflection), both times
//! `G2(i, o) / G1(i)`:
//!
//! the weight of a direction `o` drawn with density `pdf(o)` is
//! `f(i, o) |o·n| / pdf(o)`; the visible normals' density is
//! `G1(i) (i·h) D(h) / (i·n)`, turned into `pdf(o)` by the Jacobians
//! `∂ω_h/∂ω_o` of Walter's eq. 14 (reflection, `1 / (4 |o·h|)`) and
//! eq. 17 (refraction, `η_o² |o·h| / (η_i (i·h) + η_o (o·h))²`), and with
//! eq. 20 and 21 for `f` everything but Fresnel's share and the masking
//! cancels (Walter's eq. 41, with `D(h) |h·n|` sampling, is the same
//! computation). `G2 = 1 / (1 + Λ(i) + Λ(o))` is the height-correlated
//! Smith term (Heitz 2014, eq. 99) of the BTDF, so the weights of one
//! path sum to the BSDF's single-scattering albedo `∫ (f_r + f_t) |o·n|
//! dω_o ≤ 1` (the rest, Smith's `1 − G2/G1`, is light that would scatter
//! again among the microfacets).
//!
//! `i` is the viewer's side: the weights are the BSDF with the light's
//! directions reversed, without the radiance's `(η_i/η_o)²` as at the
//! smooth boundary (`super::path`): the factor cancels on a path that
//! leaves every volume it entered. A direction below the macroscopic
//! surface on its side (`G2`'s χ⁺), or on the wrong side of the face where
//! the shading normal leans away from it, carries nothing.

use super::interface::reflect;
use super::visible_normals::{LOBE_SAMPLES, hammersley, to_local, to_world, visible_normal};
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::fresnel::fresnel_dielectric;
use crate::material::brdf::gltf_layers::volume_btdf::refract;
use crate::material::brdf::microfacet::lambda_ggx;
use glam::DVec3;

/// A direction (pointing away from the boundary), its weight, and whether
/// it crosses the boundary (else it is reflected back).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub direction: DVec3,
    pub weight: f64,
    pub refracted: bool,
}

/// The refracted and, with `reflections`, the reflected directions of a
/// boundary of GGX `α` between `eta_i` (the side of `wi`, which points
/// away from the boundary towards the viewer) and `eta_t`: `frame`'s
/// normal and `face` (the geometric normal) both on `wi`'s side. Their
/// weights sum to at most 1.
pub fn rough_boundary_samples(
    frame: &SurfaceFrame,
    face: DVec3,
    wi: DVec3,
    alpha: f64,
    (eta_i, eta_t): (f64, f64),
    reflections: bool,
) -> Vec<Sample> {
    samples_of(
        LOBE_SAMPLES,
        frame,
        face,
        wi,
        alpha,
        (eta_i, eta_t),
        reflections,
    )
}

/// [`rough_boundary_samples`] with `count` points of the Hammersley set
/// (the tests measure the rule's error against larger sets).
pub fn samples_of(
    count: u32,
    frame: &SurfaceFrame,
    face: DVec3,
    wi: DVec3,
    alpha: f64,
    (eta_i, eta_t): (f64, f64),
    reflections: bool,
) -> Vec<Sample> {
    let n = frame.n;
    let cos_i = n.dot(wi);
    let mut out = Vec::new();
    if cos_i <= 0.0 {
        return out;
    }
    let v = to_local(frame, wi);
    let lambda_i = lambda_ggx(alpha, cos_i);
    let share = 1.0 / count as f64;
    // G2(i, o) / G1(i) for an outgoing `o` on either side.
    let masking = |o: DVec3| {
        let cos_o = n.dot(o).abs();
        (1.0 + lambda_i) / (1.0 + lambda_i + lambda_ggx(alpha, cos_o))
    };
    for k in 0..count {
        let (u1, u2) = hammersley(k, count);
        let h = to_world(frame, visible_normal(v, alpha, u1, u2));
        let cos_ih = wi.dot(h);
        if cos_ih <= 0.0 {
            continue;
        }
        let refracted = refract(wi, h, eta_i, eta_t);
        let f = match refracted {
            Some(_) => fresnel_dielectric(cos_ih, eta_i, eta_t),
            None => 1.0,
        };
        if let Some(o) = refracted
            && f < 1.0
            && n.dot(o) < 0.0
            && face.dot(o) < 0.0
        {
            out.push(Sample {
                direction: o,
                weight: (1.0 - f) * masking(o) * share,
                refracted: true,
            });
        }
        if reflections && f > 0.0 {
            let o = reflect(wi, h);
            if n.dot(o) > 0.0 && face.dot(o) > 0.0 {
                out.push(Sample {
                    direction: o,
                    weight: f * masking(o) * share,
                    refracted: false,
                });
            }
        }
    }
    out
}
