//! Rusinkiewicz's half/difference coordinates (S. Rusinkiewicz, "A New
//! Change of Variables for Efficient BRDF Representation", EGWR 1998), the
//! coordinates of the MERL tables and of the Neural-BRDF networks: the
//! half vector `h` by its angles `(θ_h, φ_h)` and the light direction seen
//! from `h`, `d = R_y(−θ_h) R_z(−φ_h) ω_i`, by `(θ_d, φ_d)`.

use crate::material::brdf::SurfaceFrame;
use glam::DVec3;

/// Below this `sin θ_h` the half vector is the normal and `φ_h` is taken as
/// 0 (the contract's rule: `atan2` of two roundings is meaningless there).
pub const SIN_THETA_H_FLOOR: f64 = 1e-9;

/// The half/difference angles of one pair of directions, with the unit
/// vectors the network reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfDiff {
    /// Angle of the half vector from the normal, in [0, π/2].
    pub theta_h: f64,
    /// Angle of `ω_i` from the half vector, in [0, π/2].
    pub theta_d: f64,
    /// Azimuth of `ω_i` around the half vector, in (−π, π].
    pub phi_d: f64,
    /// `(sin θ_h, 0, cos θ_h)`: the half vector with `φ_h` set to 0
    /// (isotropy), the network's first three inputs.
    pub h: DVec3,
    /// `(sin θ_d cos φ_d, sin θ_d sin φ_d, cos θ_d)`: the network's last
    /// three inputs.
    pub d: DVec3,
}

/// The half/difference coordinates of `ω_i = wi` (towards the light) and
/// `ω_o = wo` (towards the viewer), unit vectors above the surface, in the
/// frame `frame` (`t`, `b`, `n` as x, y, z).
pub fn half_diff(wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> HalfDiff {
    let local = |w: DVec3| DVec3::new(w.dot(frame.t), w.dot(frame.b), w.dot(frame.n));
    let (i, o) = (local(wi), local(wo));
    let h = (i + o).normalize();
    let sin_h = (h.x * h.x + h.y * h.y).sqrt();
    let cos_h = h.z;
    let (cos_phi_h, sin_phi_h) = if sin_h < SIN_THETA_H_FLOOR {
        (1.0, 0.0)
    } else {
        (h.x / sin_h, h.y / sin_h)
    };
    // R_z(−φ_h): turn h's azimuth to 0.
    let x = i.x * cos_phi_h + i.y * sin_phi_h;
    let y = -i.x * sin_phi_h + i.y * cos_phi_h;
    // R_y(−θ_h): tilt h onto the z axis.
    let d = DVec3::new(x * cos_h - i.z * sin_h, y, x * sin_h + i.z * cos_h);
    HalfDiff {
        theta_h: sin_h.atan2(cos_h),
        theta_d: (d.x * d.x + d.y * d.y).sqrt().atan2(d.z),
        phi_d: d.y.atan2(d.x),
        h: DVec3::new(sin_h, 0.0, cos_h),
        d,
    }
}

/// The coordinates of given half/difference angles (`φ_h = 0`): what
/// [`half_diff`] returns for the directions of [`directions`].
pub fn half_diff_of_angles(theta_h: f64, theta_d: f64, phi_d: f64) -> HalfDiff {
    HalfDiff {
        theta_h,
        theta_d,
        phi_d,
        h: DVec3::new(theta_h.sin(), 0.0, theta_h.cos()),
        d: DVec3::new(
            theta_d.sin() * phi_d.cos(),
            theta_d.sin() * phi_d.sin(),
            theta_d.cos(),
        ),
    }
}

/// The directions `(ω_i, ω_o)` of given half/difference angles (the
/// inverse of [`half_diff`] with `φ_h = 0`), in the frame `x, y, z =
/// t, b, n`. For tests and for generating tables.
pub fn directions(theta_h: f64, theta_d: f64, phi_d: f64) -> (DVec3, DVec3) {
    let d = DVec3::new(
        theta_d.sin() * phi_d.cos(),
        theta_d.sin() * phi_d.sin(),
        theta_d.cos(),
    );
    // R_y(θ_h) takes d (and its mirror about z, ω_o) back to the surface frame.
    let rot = |v: DVec3| {
        DVec3::new(
            v.x * theta_h.cos() + v.z * theta_h.sin(),
            v.y,
            -v.x * theta_h.sin() + v.z * theta_h.cos(),
        )
    };
    (rot(d), rot(DVec3::new(-d.x, -d.y, d.z)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> SurfaceFrame {
        SurfaceFrame::new(DVec3::Z, DVec3::X)
    }

    #[test]
    fn directions_and_half_diff_are_inverse() {
        for (th, td, pd) in [(0.3, 0.5, 1.0), (1.2, 0.1, -2.5), (0.01, 1.4, 3.0)] {
            let (wi, wo) = directions(th, td, pd);
            let c = half_diff(wi, wo, &frame());
            assert!((c.theta_h - th).abs() < 1e-12, "{c:?}");
            assert!((c.theta_d - td).abs() < 1e-12, "{c:?}");
            assert!((c.phi_d - pd).abs() < 1e-12, "{c:?}");
        }
    }

    #[test]
    fn the_mirror_pair_has_its_half_vector_on_the_normal() {
        let wi = DVec3::new(0.6, 0.0, 0.8);
        let wo = DVec3::new(-0.6, 0.0, 0.8);
        let c = half_diff(wi, wo, &frame());
        assert_eq!(c.theta_h, 0.0);
        assert!((c.theta_d - 0.6f64.asin()).abs() < 1e-15);
        assert_eq!(c.phi_d, 0.0);
        assert_eq!(c.d, wi);
    }
}
