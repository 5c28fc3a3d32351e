//! The perspective camera of the contract: it looks from `position` to
//! `target`; `right = normalize(cross(target - position, up))`; `fov_y_deg`
//! is the full vertical angle; pixel (i, j) is centred at (j + 0.5, i + 0.5)
//! with row 0 at the top.

use glam::{DMat4, DVec3, DVec4};

/// A pinhole camera with the clip planes both renderers honour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: DVec3,
    pub target: DVec3,
    pub up: DVec3,
    /// Full vertical field of view, degrees, in (0, 180).
    pub fov_y_deg: f64,
    /// Near and far clip distances along the viewing axis. The GPU clips
    /// there; the CPU reference discards hits outside the same range, so
    /// both see the same geometry.
    pub near: f64,
    pub far: f64,
}

/// A ray `origin + t · direction`, `direction` unit length.
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

/// The primary rays of one camera and image size ([`Camera::rays`]).
#[derive(Clone, Copy, Debug)]
pub struct PrimaryRays {
    origin: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    tan_half: f64,
    aspect: f64,
    width: f64,
    height: f64,
}

impl PrimaryRays {
    /// The primary ray through image point (x, y) in pixels
    /// ([`Camera::ray`]).
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let ndc_x = 2.0 * x / self.width - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height;
        let direction = self.forward
            + self.right * (ndc_x * self.tan_half * self.aspect)
            + self.up * (ndc_y * self.tan_half);
        Ray {
            origin: self.origin,
            direction: direction.normalize(),
        }
    }
}

impl Camera {
    /// Unit viewing direction.
    pub fn forward(&self) -> DVec3 {
        (self.target - self.position).normalize()
    }

    /// Unit right vector: `normalize(cross(forward, up))`.
    pub fn right(&self) -> DVec3 {
        self.forward().cross(self.up).normalize()
    }

    /// The true up vector of the image plane (orthogonal to forward, right).
    pub fn true_up(&self) -> DVec3 {
        self.right().cross(self.forward())
    }

    /// `view_from_world`, right-handed (camera looks down −Z).
    pub fn view_from_world(&self) -> DMat4 {
        glam::dcamera::rh::view::look_at_mat4(self.position, self.target, self.up)
    }

    /// `clip_from_view` for wgpu's 0..1 depth range.
    pub fn clip_from_view(&self, aspect: f64) -> DMat4 {
        glam::dcamera::rh::proj::directx::perspective(
            self.fov_y_deg.to_radians(),
            aspect,
            self.near,
            self.far,
        )
    }

    /// `clip_from_world` for an image of the given aspect (width / height).
    pub fn clip_from_world(&self, aspect: f64) -> DMat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// The primary ray through image point (x, y) in pixels, x to the right
    /// from the left edge, y down from the top edge; the centre of pixel
    /// (row i, column j) is (j + 0.5, i + 0.5).
    pub fn ray(&self, x: f64, y: f64, width: u32, height: u32) -> Ray {
        self.rays(width, height).ray(x, y)
    }

    /// [`Camera::ray`] for many points of one image: the basis, the
    /// tangent of the half angle and the aspect computed once (a tangent
    /// and three normalizations per ray were a fifth of the reference's
    /// camera-ray cost; docs/notes/reference-timing.md). Same arithmetic in the
    /// same order, so the same bits as [`Camera::ray`].
    pub fn rays(&self, width: u32, height: u32) -> PrimaryRays {
        PrimaryRays {
            origin: self.position,
            forward: self.forward(),
            right: self.right(),
            up: self.true_up(),
            tan_half: (0.5 * self.fov_y_deg.to_radians()).tan(),
            aspect: width as f64 / height as f64,
            width: width as f64,
            height: height as f64,
        }
    }

    /// Depth of a point along the viewing axis (what the near/far planes cut).
    pub fn view_depth(&self, p: DVec3) -> f64 {
        (p - self.position).dot(self.forward())
    }

    /// A camera that frames the bounds `(lo, hi)` from a three-quarter view
    /// above the front (+Z), with a 45° vertical field of view: the bounding
    /// sphere fits the frame with a 10 % margin.
    pub fn framing(lo: DVec3, hi: DVec3, aspect: f64) -> Camera {
        let fov_y_deg: f64 = 45.0;
        let center = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).length()).max(1e-6);
        let half = 0.5 * fov_y_deg.to_radians();
        // Fit the sphere to the narrower of the two half-angles.
        let half_narrow = if aspect < 1.0 {
            (half.tan() * aspect).atan()
        } else {
            half
        };
        let distance = 1.1 * radius / half_narrow.sin();
        let direction = DVec3::new(0.35, 0.45, 1.0).normalize();
        let mut camera = Camera {
            position: center + direction * distance,
            target: center,
            up: DVec3::Y,
            fov_y_deg,
            near: 0.0,
            far: 0.0,
        };
        camera.fit_clip_planes(lo, hi);
        camera
    }

    /// Sets near/far to enclose the bounds `(lo, hi)` with a margin, and
    /// keeps near positive (1/10000 of far at least, which keeps a 32-bit
    /// float depth buffer well conditioned).
    pub fn fit_clip_planes(&mut self, lo: DVec3, hi: DVec3) {
        let center = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).length()).max(1e-6);
        let d = self.view_depth(center);
        self.far = (d + radius) * 1.01 + 1e-6;
        self.near = ((d - radius) * 0.99).max(self.far * 1e-4);
    }
}

impl Camera {
    /// Projects a world point to pixel coordinates (x right, y down) and
    /// returns them with the point's depth; used by tests to check that the
    /// ray and the projection matrix agree.
    pub fn project(&self, p: DVec3, width: u32, height: u32) -> (f64, f64) {
        let clip = self.clip_from_world(width as f64 / height as f64) * DVec4::from((p, 1.0));
        let ndc = clip.truncate() / clip.w;
        (
            (ndc.x + 1.0) * 0.5 * width as f64,
            (1.0 - ndc.y) * 0.5 * height as f64,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_and_projection_agree() {
        let camera = Camera {
            position: DVec3::new(1.0, 2.0, 5.0),
            target: DVec3::new(0.0, 0.5, 0.0),
            up: DVec3::Y,
            fov_y_deg: 50.0,
            near: 0.1,
            far: 100.0,
        };
        let (w, h) = (320, 200);
        for (x, y) in [(0.5, 0.5), (160.0, 100.0), (319.5, 12.25), (3.0, 199.0)] {
            let ray = camera.ray(x, y, w, h);
            let p = ray.origin + ray.direction * 7.0;
            let (px, py) = camera.project(p, w, h);
            assert!(
                (px - x).abs() < 1e-9 && (py - y).abs() < 1e-9,
                "{x},{y} -> {px},{py}"
            );
        }
    }

    #[test]
    fn framing_sees_the_whole_box() {
        let (lo, hi) = (DVec3::new(-1.0, 0.0, -2.0), DVec3::new(3.0, 1.0, 0.5));
        let camera = Camera::framing(lo, hi, 4.0 / 3.0);
        for i in 0..8 {
            let corner = DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let (x, y) = camera.project(corner, 400, 300);
            assert!((0.0..=400.0).contains(&x) && (0.0..=300.0).contains(&y));
            let d = camera.view_depth(corner);
            assert!(d > camera.near && d < camera.far);
        }
    }
}
