//! World points to the 3D area's screen points and back, for the camera
//! the scene is drawn with: what the lights overlay draws
//! (`super::overlay`) lands on what the renderer draws, and a
//! dragged handle moves under the mouse (`super::drag`).
//!
//! The contract's camera ([`Camera::ray`]): `right = normalize(cross(
//! target − position, up))`, `fov_y_deg` the full vertical angle, the
//! image's x to the right and y down from its top-left corner. A point at
//! view depth `z` (along the viewing axis) lands at
//! `ndc = (p·right / (z·tan(fov/2)·aspect), p·up / (z·tan(fov/2)))`.

use crate::scene::Camera;
use glam::{DVec2, DVec3};

/// A camera and the screen rectangle its image fills.
#[derive(Clone, Copy, Debug)]
pub struct ScreenProjection {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    tan_half: f64,
    near: f64,
    /// Top-left corner and size of the image on the screen.
    origin: DVec2,
    size: DVec2,
}

impl ScreenProjection {
    /// `camera`'s image filling the rectangle at `origin` of `size`
    /// (any unit: egui points for drawing, window pixels for the mouse).
    pub fn new(camera: &Camera, origin: DVec2, size: DVec2) -> ScreenProjection {
        ScreenProjection {
            eye: camera.position,
            forward: camera.forward(),
            right: camera.right(),
            up: camera.true_up(),
            tan_half: (0.5 * camera.fov_y_deg.to_radians()).tan(),
            near: camera.near,
            origin,
            size: size.max(DVec2::ONE),
        }
    }

    fn aspect(&self) -> f64 {
        self.size.x / self.size.y
    }

    /// Depth of `p` along the viewing axis.
    pub fn depth(&self, p: DVec3) -> f64 {
        (p - self.eye).dot(self.forward)
    }

    /// The screen point of `p`, or `None` when it is not in front of the
    /// near plane.
    pub fn project(&self, p: DVec3) -> Option<DVec2> {
        (self.depth(p) >= self.near).then(|| self.screen_point(p))
    }

    /// The screen point of `p`, in front of the eye.
    fn screen_point(&self, p: DVec3) -> DVec2 {
        let v = p - self.eye;
        let z = v.dot(self.forward);
        let ndc = DVec2::new(
            v.dot(self.right) / (z * self.tan_half * self.aspect()),
            v.dot(self.up) / (z * self.tan_half),
        );
        self.origin + DVec2::new(0.5 * (ndc.x + 1.0), 0.5 * (1.0 - ndc.y)) * self.size
    }

    /// The segment `a`–`b` on the screen, its part behind the near plane
    /// cut off (`None` if nothing is left).
    pub fn project_segment(&self, a: DVec3, b: DVec3) -> Option<(DVec2, DVec2)> {
        let (za, zb) = (self.depth(a), self.depth(b));
        if za < self.near && zb < self.near {
            return None;
        }
        let cut = |from: DVec3, z_from: f64, to: DVec3, z_to: f64| {
            if z_from >= self.near {
                from
            } else {
                from + (to - from) * ((self.near - z_from) / (z_to - z_from))
            }
        };
        // A cut end is at the near plane (up to rounding): in front.
        let (a2, b2) = (cut(a, za, b, zb), cut(b, zb, a, za));
        Some((self.screen_point(a2), self.screen_point(b2)))
    }

    /// The world point at screen point `s` and view depth `depth` (the
    /// inverse of [`Self::project`] at that depth).
    pub fn unproject(&self, s: DVec2, depth: f64) -> DVec3 {
        let t = (s - self.origin) / self.size;
        let ndc = DVec2::new(2.0 * t.x - 1.0, 1.0 - 2.0 * t.y);
        let direction = self.forward
            + self.right * (ndc.x * self.tan_half * self.aspect())
            + self.up * (ndc.y * self.tan_half);
        self.eye + direction * depth
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            position: DVec3::new(1.0, 2.0, 5.0),
            target: DVec3::new(0.0, 0.5, 0.0),
            up: DVec3::Y,
            fov_y_deg: 40.0,
            near: 0.01,
            far: 100.0,
        }
    }

    #[test]
    fn projection_agrees_with_the_cameras_rays() {
        let cam = camera();
        let (w, h) = (320u32, 200u32);
        let proj = ScreenProjection::new(&cam, DVec2::new(10.0, 20.0), DVec2::new(320.0, 200.0));
        // A point on the ray through pixel point (x, y) projects back there.
        for (x, y) in [(0.5, 0.5), (160.0, 100.0), (300.25, 17.5), (3.0, 199.0)] {
            let ray = cam.ray(x, y, w, h);
            let p = ray.origin + ray.direction * 3.7;
            let s = proj.project(p).unwrap() - DVec2::new(10.0, 20.0);
            assert!((s - DVec2::new(x, y)).length() < 1e-9, "{s} vs ({x}, {y})");
            let back = proj.unproject(s + DVec2::new(10.0, 20.0), proj.depth(p));
            assert!((back - p).length() < 1e-9, "{back} vs {p}");
        }
        // The target is at the centre; a point behind the eye is nowhere.
        let centre = proj.project(cam.target).unwrap();
        assert!((centre - DVec2::new(170.0, 120.0)).length() < 1e-9);
        assert!(proj.project(cam.position * 2.0 - cam.target).is_none());
    }

    #[test]
    fn segments_are_cut_at_the_near_plane() {
        let cam = camera();
        let proj = ScreenProjection::new(&cam, DVec2::ZERO, DVec2::new(100.0, 100.0));
        let behind = cam.position - cam.forward();
        let (a, b) = proj.project_segment(behind, cam.target).unwrap();
        assert!(a.is_finite() && b.is_finite());
        assert!((b - DVec2::new(50.0, 50.0)).length() < 1e-9);
        assert!(
            proj.project_segment(behind, behind - cam.forward())
                .is_none()
        );
    }
}
