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
use super::visible_normals::{
    LOBE_SAMPLES, hammersley, second_point, to_local, to_world, visible_normal,
};
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::fresnel::fresnel_dielectric;
use crate::material::brdf::gltf_layers::volume_btdf::refract;
use crate::material::brdf::microfacet::lambda_ggx;
use glam::DVec3;

/// A direction (pointing away from the boundary), its weight, whether it
/// crosses the boundary (else it is reflected back), and the point of the
/// set it came from (the path's stratum, `super::visible_normals::second_point`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub direction: DVec3,
    pub weight: f64,
    pub refracted: bool,
    pub stratum: u32,
}

/// The geometry of one crossing: `frame`'s normal and `face` (the
/// geometric normal) both on `wi`'s side, `wi` pointing away from the
/// boundary towards the viewer, GGX `alpha`, the indices `(η_i, η_t)` on
/// `wi`'s side and beyond, and whether reflected directions are wanted.
#[derive(Clone, Copy, Debug)]
pub struct Boundary<'a> {
    pub frame: &'a SurfaceFrame,
    pub face: DVec3,
    pub wi: DVec3,
    pub alpha: f64,
    pub etas: (f64, f64),
    pub reflections: bool,
}

/// The refracted and, with `reflections`, the reflected directions of a
/// path's first rough crossing, at the [`LOBE_SAMPLES`] points of the
/// Hammersley set. Their weights sum to at most 1.
pub fn rough_boundary_samples(b: &Boundary) -> Vec<Sample> {
    samples_of(LOBE_SAMPLES, b)
}

/// [`rough_boundary_samples`] with `count` points of the Hammersley set
/// (the tests measure the rule's error against larger sets).
pub fn samples_of(count: u32, b: &Boundary) -> Vec<Sample> {
    let share = 1.0 / count as f64;
    (0..count)
        .flat_map(|k| split(b, hammersley(k, count), share, k))
        .collect()
}

/// The directions of a path's second rough crossing, the path spread at
/// stratum `k` by the first: one normal, at
/// [`super::visible_normals::second_point`]`(k)`, split as at the first
/// (weights summing to at most 1, the path's own weight aside).
pub fn second_crossing_samples(b: &Boundary, k: u32) -> Vec<Sample> {
    split(b, second_point(k), 1.0, k).collect()
}

/// The normal at `point` of the unit square, visible from `b.wi`, and the
/// directions it refracts and reflects into, each of weight `share` times
/// Fresnel's part and `G2/G1`.
fn split(b: &Boundary, point: (f64, f64), share: f64, k: u32) -> impl Iterator<Item = Sample> {
    let (frame, wi, alpha) = (b.frame, b.wi, b.alpha);
    let (eta_i, eta_t) = b.etas;
    let n = frame.n;
    let cos_i = n.dot(wi);
    let mut out = [None, None];
    if cos_i > 0.0 {
        let lambda_i = lambda_ggx(alpha, cos_i);
        // G2(i, o) / G1(i) for an outgoing `o` on either side.
        let masking = |o: DVec3| {
            let cos_o = n.dot(o).abs();
            (1.0 + lambda_i) / (1.0 + lambda_i + lambda_ggx(alpha, cos_o))
        };
        let h = to_world(
            frame,
            visible_normal(to_local(frame, wi), alpha, point.0, point.1),
        );
        let cos_ih = wi.dot(h);
        if cos_ih > 0.0 {
            let refracted = refract(wi, h, eta_i, eta_t);
            let f = match refracted {
                Some(_) => fresnel_dielectric(cos_ih, eta_i, eta_t),
                None => 1.0,
            };
            if let Some(o) = refracted
                && f < 1.0
                && n.dot(o) < 0.0
                && b.face.dot(o) < 0.0
            {
                out[0] = Some(Sample {
                    direction: o,
                    weight: (1.0 - f) * masking(o) * share,
                    refracted: true,
                    stratum: k,
                });
            }
            if b.reflections && f > 0.0 {
                let o = reflect(wi, h);
                if n.dot(o) > 0.0 && b.face.dot(o) > 0.0 {
                    out[1] = Some(Sample {
                        direction: o,
                        weight: f * masking(o) * share,
                        refracted: false,
                        stratum: k,
                    });
                }
            }
        }
    }
    out.into_iter().flatten()
}
