//! The deterministic microfacet normals the reference looks through a
//! rough surface along, shared by the thin wall ([`super::thin`]) and the
//! rough boundary of a volume ([`super::rough_boundary`]): the points of a
//! Hammersley set mapped to GGX's distribution of normals visible from the
//! viewer (Heitz 2018). The same points serve every pixel, so a lobe costs
//! a fixed number of rays and adds no noise: what remains is the
//! quadrature's error, measured where the lobes are tested.

use crate::material::brdf::SurfaceFrame;
use glam::DVec3;
use std::f64::consts::TAU;

/// Points of the Hammersley set per lobe.
pub const LOBE_SAMPLES: u32 = 64;

/// The Hammersley point `k` of `n`: `((k + ½)/n, radical inverse of k)`.
pub fn hammersley(k: u32, n: u32) -> (f64, f64) {
    (
        (k as f64 + 0.5) / n as f64,
        k.reverse_bits() as f64 / 4_294_967_296.0,
    )
}

/// The point of the unit square a path spread at stratum `k` of a first
/// rough crossing takes at its second (`super::rough_boundary`): the
/// radical inverses of `k` in bases 3 and 5, the third and fourth
/// coordinates of a four-dimensional Hammersley set whose first two are
/// [`hammersley`]`(k, n)`. Each of the `n` paths crosses the second
/// boundary along one normal, and together they cover both boundaries'
/// normals as evenly as a Halton set, without a path splitting twice.
pub fn second_point(k: u32) -> (f64, f64) {
    (radical_inverse(k, 3), radical_inverse(k, 5))
}

/// The digits of `k` in base `base` mirrored about the point.
fn radical_inverse(mut k: u32, base: u32) -> f64 {
    let (mut value, mut scale) = (0.0, 1.0 / base as f64);
    while k > 0 {
        value += (k % base) as f64 * scale;
        k /= base;
        scale /= base as f64;
    }
    value
}

/// A GGX normal of `α` visible from `v` (the frame's coordinates, `v.z >
/// 0`) at the point `(u1, u2)` of the unit square: Heitz 2018, "Sampling
/// the GGX Distribution of Visible Normals" (JCGT 7(4), listing 1). Its
/// density is `G1(v) max(0, v·h) D(h) / v.z` (Heitz 2018, eq. 1), so a
/// lobe's weight `f cos / pdf` stays below 1 even at grazing views, where
/// sampling `D` alone leaves a few samples of very large weight.
pub fn visible_normal(v: DVec3, alpha: f64, u1: f64, u2: f64) -> DVec3 {
    let vh = DVec3::new(alpha * v.x, alpha * v.y, v.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 {
        DVec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        DVec3::X
    };
    let t2 = vh.cross(t1);
    let (r, phi) = (u1.sqrt(), TAU * u2);
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    DVec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(0.0)).normalize()
}

/// `v` given in `frame`'s coordinates `(t, b, n)`, in world space.
pub fn to_world(frame: &SurfaceFrame, v: DVec3) -> DVec3 {
    frame.t * v.x + frame.b * v.y + frame.n * v.z
}

/// `w` (world space) in `frame`'s coordinates `(t, b, n)`.
pub fn to_local(frame: &SurfaceFrame, w: DVec3) -> DVec3 {
    DVec3::new(frame.t.dot(w), frame.b.dot(w), frame.n.dot(w))
}
