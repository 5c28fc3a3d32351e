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

    /// This frame with its normal turned toward unit `wo` where it faces
    /// away: an interpolated or normal-mapped normal can face away from
    /// the viewer at a silhouette, where the one-sided reflection
    /// equation (and the light through the surface) is 0, a black pixel
    /// that neither the Khronos sample renderer, Filament, three.js nor
    /// Bevy draws: they clamp `n·v` to a small positive value in the BRDF
    /// alone (`clampedDot`, `MIN_N_DOT_V`). Here the normal itself turns
    /// (in the plane of `n` and `wo`), so every term sees one consistent
    /// frame: where `c = n·wo < FACING_COS_MIN`,
    /// `n' = normalize(n + (FACING_COS_MIN − c)·wo)`, whose
    /// `n'·wo = FACING_COS_MIN / √(1 + FACING_COS_MIN² − c²) > 0`;
    /// continuous at `c = FACING_COS_MIN`, where it is `n` itself. The
    /// tangent is made orthogonal again ([`Self::new`]). Used for glTF
    /// materials (`Material::facing_normals`, `[gltf] facing_normals`).
    /// Twin: `facing_frame` in `shaders/surface.wgsl`.
    pub fn facing(&self, wo: DVec3) -> Self {
        let c = self.n.dot(wo);
        if c >= FACING_COS_MIN {
            return *self;
        }
        Self::new((self.n + (FACING_COS_MIN - c) * wo).normalize(), self.t)
    }
}

/// The least `n·wo` a facing normal keeps ([`SurfaceFrame::facing`]):
/// small, so a normal is turned only as far as it must be, and far above
/// f32's rounding of a dot product (≈ 6·10⁻⁸), so both renderers turn the
/// same normals.
pub const FACING_COS_MIN: f64 = 1e-3;

/// A unit vector orthogonal to unit `n`: the world X axis projected onto
/// the tangent plane, or Z where X is nearly parallel to `n`.
/// Twin: `any_tangent` in `shaders/shading.wgsl`.
pub fn any_tangent(n: DVec3) -> DVec3 {
    let axis = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Z };
    (axis - n * n.dot(axis)).normalize_or_zero()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit normal at angle `c = n·wo` to `wo = +Z`, tilted about X.
    fn normal_at(c: f64) -> DVec3 {
        DVec3::new(0.0, (1.0 - c * c).sqrt(), c)
    }

    #[test]
    fn a_normal_that_faces_the_viewer_is_kept() {
        for c in [FACING_COS_MIN, 0.01, 0.5, 1.0] {
            let f = SurfaceFrame::new(normal_at(c), DVec3::X);
            assert_eq!(f.facing(DVec3::Z), f, "c = {c}");
        }
    }

    /// `n'·wo = m / √(1 + m² − c²)` (the doc's formula), `n'` unit, in the
    /// plane of `n` and `wo`, the frame orthonormal; and just below the
    /// threshold `n'` is `n` to the gap's order.
    #[test]
    fn a_normal_that_faces_away_turns_just_past_the_silhouette() {
        let m = FACING_COS_MIN;
        let wo = DVec3::Z;
        for c in [-0.99, -0.5, -0.1, 0.0, 5e-4, m - 1e-9] {
            let n = normal_at(c);
            let f = SurfaceFrame::new(n, DVec3::X).facing(wo);
            let expected = m / (1.0 + m * m - c * c).sqrt();
            assert!(
                (f.n.dot(wo) - expected).abs() < 1e-15,
                "c = {c}: {}",
                f.n.dot(wo)
            );
            assert!((f.n.length() - 1.0).abs() < 1e-15);
            assert!(
                f.n.dot(n.cross(wo)).abs() < 1e-15,
                "c = {c}: out of the plane"
            );
            assert!(f.t.dot(f.n).abs() < 1e-15 && (f.b - f.n.cross(f.t)).length() < 1e-15);
            if c > m - 1e-6 {
                assert!(
                    (f.n - n).length() < 1e-8,
                    "c = {c}: turned by {}",
                    (f.n - n).length()
                );
            }
        }
    }
}
