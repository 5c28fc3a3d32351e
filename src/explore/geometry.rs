//! The geometry of every exploration: the surface normal is `n = +Z`,
//! the tangent `t = +X`, the bitangent `b = +Y`; polar angles θ from the
//! normal, azimuths φ from the tangent towards the bitangent.

use crate::material::brdf::SurfaceFrame;
use glam::DVec3;

/// The shading frame of every exploration: `n = +Z`, `t = +X`, `b = +Y`.
pub fn frame() -> SurfaceFrame {
    SurfaceFrame::new(DVec3::Z, DVec3::X)
}

/// The unit direction with polar angle `theta` (from `n = +Z`) and azimuth
/// `phi` (from `t = +X`), both in radians.
pub fn direction(theta: f64, phi: f64) -> DVec3 {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    DVec3::new(st * cp, st * sp, ct)
}
