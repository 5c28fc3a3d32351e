//! The shading frame every model is evaluated in, shared by the scene (mesh
//! tangents), the materials and both renderers.

use glam::DVec3;

/// An orthonormal shading frame: normal, tangent, bitangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceFrame {
    pub n: DVec3,
    pub t: DVec3,
    pub b: DVec3,
}

impl SurfaceFrame {
    /// A frame around unit `n` with `t` made orthogonal to it
    /// (Gram-Schmidt); if `t` is (nearly) parallel to `n` or zero, a
    /// tangent is derived from `n` alone ([`any_tangent`]).
    /// `b = n × t`. Twin: `surface_frame` in `shaders/shading.wgsl`.
    pub fn new(n: DVec3, t: DVec3) -> Self {
        let projected = t - n * n.dot(t);
        let t = if projected.length_squared() > 1e-12 {
            projected.normalize()
        } else {
            any_tangent(n)
        };
        SurfaceFrame {
            n,
            t,
            b: n.cross(t),
        }
    }

    /// A frame around `n` with an arbitrary tangent (isotropic models).
    pub fn from_normal(n: DVec3) -> Self {
        Self::new(n, any_tangent(n))
    }
}

/// A unit vector orthogonal to unit `n`: the world X axis projected onto
/// the tangent plane, or Z where X is nearly parallel to `n`.
/// Twin: `any_tangent` in `shaders/shading.wgsl`.
pub fn any_tangent(n: DVec3) -> DVec3 {
    let axis = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Z };
    (axis - n * n.dot(axis)).normalize_or_zero()
}
