//! The viewer's camera control: orbit around a target, pan, zoom.
//!
//! The state is spherical (yaw and pitch of the eye around the target,
//! distance), so orbiting never drifts or rolls; it is turned back into the
//! scene's [`Camera`] (position, target, up) every frame, so the renderer
//! and a saved scene file see an ordinary look-at camera.

use crate::scene::Camera;
use glam::DVec3;

/// Radians of orbit per pixel of mouse drag.
const ORBIT_PER_PIXEL: f64 = 0.008;
/// Pitch stays this far from the poles (where yaw is undefined).
const PITCH_LIMIT: f64 = 1.55;
/// Zoom factor per scroll step (a wheel notch).
const ZOOM_PER_STEP: f64 = 0.9;

/// An orbiting camera about `target` with world up +Y... or whatever `up`
/// the scene's camera had.
#[derive(Clone, Debug, PartialEq)]
pub struct Orbit {
    pub target: DVec3,
    pub distance: f64,
    /// Angle about `up`, radians.
    pub yaw: f64,
    /// Elevation above the plane normal to `up`, radians.
    pub pitch: f64,
    up: DVec3,
    /// A basis of the plane normal to `up`: yaw 0 looks along −`ahead`.
    ahead: DVec3,
    side: DVec3,
    /// The camera the orbit was made from (fov, clip distances, reset).
    home: Camera,
}

impl Orbit {
    /// The orbit that reproduces `camera` exactly.
    pub fn from_camera(camera: &Camera) -> Orbit {
        let up = camera.up.normalize();
        let offset = camera.position - camera.target;
        let distance = offset.length().max(1e-9);
        // A basis of the horizontal plane with `ahead` along the eye's
        // horizontal offset (or any direction if the eye is at a pole).
        let horizontal = offset - up * offset.dot(up);
        let ahead = if horizontal.length() > 1e-12 * distance {
            horizontal.normalize()
        } else {
            up.any_orthonormal_vector()
        };
        let side = up.cross(ahead);
        let pitch = (offset.dot(up) / distance).clamp(-1.0, 1.0).asin();
        Orbit {
            target: camera.target,
            distance,
            yaw: 0.0,
            pitch,
            up,
            ahead,
            side,
            home: *camera,
        }
    }

    /// The camera of the current orbit. Near and far planes keep their
    /// ratio to the distance, so zooming out never clips the scene away.
    pub fn camera(&self) -> Camera {
        let horizontal = self.ahead * self.yaw.cos() + self.side * self.yaw.sin();
        let offset = self.distance * (horizontal * self.pitch.cos() + self.up * self.pitch.sin());
        let home_distance = (self.home.position - self.home.target).length().max(1e-9);
        let scale = (self.distance / home_distance).max(1.0);
        Camera {
            position: self.target + offset,
            target: self.target,
            up: self.up,
            fov_y_deg: self.home.fov_y_deg,
            near: self.home.near,
            far: self.home.far * scale,
        }
    }

    /// Back to the camera the orbit was made from.
    pub fn reset(&mut self) {
        *self = Orbit::from_camera(&self.home);
    }

    /// Orbits by a mouse drag of `(dx, dy)` pixels: right drags the scene
    /// right (the eye moves left), down tilts the eye up.
    pub fn rotate(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * ORBIT_PER_PIXEL;
        self.pitch = (self.pitch + dy * ORBIT_PER_PIXEL).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Orbits by angles in degrees (scripted runs).
    pub fn rotate_degrees(&mut self, yaw_deg: f64, pitch_deg: f64) {
        let per_pixel = ORBIT_PER_PIXEL.to_degrees();
        self.rotate(yaw_deg / per_pixel, pitch_deg / per_pixel);
    }

    /// Moves the target (and the eye with it) by a drag of `(dx, dy)`
    /// pixels in a view `height` pixels tall, so the point under the
    /// cursor at the target's depth follows the cursor.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64) {
        let camera = self.camera();
        let world_per_pixel =
            2.0 * self.distance * (0.5 * camera.fov_y_deg.to_radians()).tan() / height.max(1.0);
        self.target += (-dx * camera.right() + dy * camera.true_up()) * world_per_pixel;
    }

    /// Zooms by `steps` wheel notches (positive: closer).
    pub fn zoom(&mut self, steps: f64) {
        let near = self.home.near * 2.0;
        self.distance = (self.distance * ZOOM_PER_STEP.powf(steps)).max(near);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            position: DVec3::new(1.0, 2.0, 3.0),
            target: DVec3::new(0.0, 0.5, 0.0),
            up: DVec3::Y,
            fov_y_deg: 40.0,
            near: 0.01,
            far: 100.0,
        }
    }

    #[test]
    fn the_orbit_of_a_camera_is_that_camera() {
        let c = camera();
        let o = Orbit::from_camera(&c).camera();
        assert!((o.position - c.position).length() < 1e-12, "{o:?}");
        assert_eq!(o.target, c.target);
        assert_eq!(o.fov_y_deg, c.fov_y_deg);
    }

    #[test]
    fn rotating_keeps_distance_and_reset_returns() {
        let c = camera();
        let mut o = Orbit::from_camera(&c);
        let d = o.distance;
        o.rotate(120.0, -40.0);
        let moved = o.camera();
        assert!(((moved.position - moved.target).length() - d).abs() < 1e-12);
        assert!((moved.position - c.position).length() > 0.1);
        o.reset();
        assert!((o.camera().position - c.position).length() < 1e-12);
    }

    #[test]
    fn pitch_never_reaches_the_pole() {
        let mut o = Orbit::from_camera(&camera());
        o.rotate(0.0, 1e6);
        let c = o.camera();
        assert!(c.forward().cross(c.up).length() > 0.01);
    }

    #[test]
    fn zoom_closes_in_but_not_past_the_near_plane() {
        let mut o = Orbit::from_camera(&camera());
        let d = o.distance;
        o.zoom(1.0);
        assert!(o.distance < d);
        o.zoom(1e4);
        assert!(o.distance >= 0.02);
        o.zoom(-200.0);
        let c = o.camera();
        assert!(c.far >= 100.0 && (c.position - c.target).length() <= c.far);
    }

    #[test]
    fn panning_moves_target_and_eye_together() {
        let mut o = Orbit::from_camera(&camera());
        let before = o.camera();
        o.pan(10.0, 0.0, 100.0);
        let after = o.camera();
        let shift = after.target - before.target;
        assert!(shift.length() > 0.0);
        assert!(((after.position - before.position) - shift).length() < 1e-12);
        assert!(shift.dot(before.right()) < 0.0);
    }
}
