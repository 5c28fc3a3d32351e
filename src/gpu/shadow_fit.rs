//! Shadow-map resolution fitted to the screen (`shadow_resolution =
//! "fit"`): each map gets the side at which its texels, on the receivers
//! the camera sees and the light reaches, are about as large as the
//! pixels they land in, instead of the fixed `shadow_map_size`, which
//! stays the upper bound.
//!
//! A map texel at a receiver `x` spans `texel(x)` metres across the light
//! (`LightShadow::texel_at`: constant for an orthographic map, growing
//! with the distance from the light for a perspective map or cube face);
//! a pixel spans `pixel(x) = 2·tan(fov_y/2)·z(x) / H` metres across the
//! view (`z` the view depth, `H` the image height). A map of side `s` has
//! texels as large as the pixels at `x` when
//! `s_x = s_cap · texel_cap(x) / pixel(x)` (the map drawn at `s_cap` has
//! `texel_cap`). The fitted side is `texels_per_pixel ·` the root mean
//! square of `s_x` over the receivers: on average (by area) one texel per
//! pixel along each axis, fewer where receivers are close to the camera
//! and far from the light, more where they are far from the camera. Only
//! perspective aliasing is fitted: the slopes of the receiver to the light
//! and to the view (projective aliasing) are left out, as resolution
//! cannot cure grazing light. The side is rounded up to a multiple of 16
//! and clamped to `[MIN_FIT_SIDE, shadow_map_size]`.
//!
//! The receivers are found by tracing primary rays (the scene's BVH, `crate::scene::bvh`, which the reference
//! traces too)
//! through a grid of about [`GRID`] samples across the image's longer
//! side, once per plan. The error this choice costs against ray-traced
//! shadows is measured by `gonio bench` (knob `shadow_resolution`).

use crate::scene::bvh::Bvh;
use crate::scene::{Light, Scene, mesh};
use glam::DVec3;

/// Smallest fitted side: a map that lights a few pixels still resolves a
/// 3×3 PCF footprint and its margin.
pub const MIN_FIT_SIDE: u32 = 64;
/// Samples across the image's longer side (a 96×54 grid at 16:9).
pub const GRID: u32 = 96;

/// A receiver seen through one grid sample.
#[derive(Clone, Copy, Debug)]
struct Sample {
    x: DVec3,
    /// The geometric normal, turned towards the camera.
    n: DVec3,
    /// World size of a pixel at `x`.
    pixel: f64,
}

/// The receivers the camera sees, on a coarse grid of the image.
#[derive(Clone, Debug, Default)]
pub struct ScreenSamples {
    samples: Vec<Sample>,
}

impl ScreenSamples {
    /// Traces `scene`'s camera through the grid.
    pub fn new(scene: &Scene) -> Self {
        let (w, h) = (scene.width.max(1), scene.height.max(1));
        let step = (w.max(h) as f64 / GRID as f64).max(1.0);
        let (nx, ny) = (
            (w as f64 / step).round().max(1.0) as u32,
            (h as f64 / step).round().max(1.0) as u32,
        );
        let bvh = Bvh::new(&scene.meshes);
        let camera = &scene.camera;
        let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
        let mut samples = Vec::with_capacity((nx * ny) as usize);
        for j in 0..ny {
            for i in 0..nx {
                let px = (i as f64 + 0.5) * w as f64 / nx as f64;
                let py = (j as f64 + 0.5) * h as f64 / ny as f64;
                let ray = camera.ray(px, py, w, h);
                let Some(hit) = bvh.intersect(&ray, 0.0, f64::INFINITY) else {
                    continue;
                };
                let x = ray.origin + hit.t * ray.direction;
                let m = &scene.meshes[hit.id.mesh as usize];
                let mut n = mesh::face_normal(m.triangle(hit.id.triangle as usize));
                if n.dot(ray.direction) > 0.0 {
                    n = -n;
                }
                let pixel = 2.0 * tan_half * camera.view_depth(x) / h as f64;
                if pixel > 0.0 {
                    samples.push(Sample { x, n, pixel });
                }
            }
        }
        ScreenSamples { samples }
    }

    /// The fitted side of `light`'s map, whose texel at `x` is
    /// `texel_at(x)` when drawn at side `cap` (the light's
    /// `shadow_map_size`), with `texels_per_pixel` texels per pixel along
    /// each axis on average over the receivers the light reaches.
    pub fn fitted_side(
        &self,
        light: &Light,
        texel_at: impl Fn(DVec3) -> f64,
        cap: u32,
        texels_per_pixel: f64,
    ) -> u32 {
        let (mut sum, mut count) = (0.0, 0usize);
        for s in &self.samples {
            let incidence = light.incidence(s.x);
            if incidence.wi.dot(s.n) <= 0.0 || incidence.irradiance.max_element() <= 0.0 {
                continue;
            }
            let side = cap as f64 * texel_at(s.x) / s.pixel;
            sum += side * side;
            count += 1;
        }
        let low = MIN_FIT_SIDE.min(cap);
        if count == 0 {
            return low;
        }
        let need = texels_per_pixel * (sum / count as f64).sqrt();
        let rounded = (need / 16.0).ceil().min(f64::from(u32::MAX / 16)) as u32 * 16;
        rounded.clamp(low, cap)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::{self, SceneSource};

    fn built_in(sets: &[&str]) -> Scene {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        scene_file::load(&SceneSource::BuiltIn, &sets).unwrap()
    }

    #[test]
    fn the_fitted_side_follows_the_image_height() {
        // A constant texel (an orthographic map) of 2 mm at the cap:
        // doubling the image height halves the pixels, doubling the side.
        let side_at = |h: u32| {
            let scene = built_in(&[&format!("image.width={h}"), &format!("image.height={h}")]);
            ScreenSamples::new(&scene).fitted_side(&scene.lights[0], |_| 0.002, 8192, 1.0)
        };
        let (a, b) = (side_at(200), side_at(400));
        assert!(a > MIN_FIT_SIDE && b < 8192, "{a} {b}");
        // Rounding up to 16 texels moves the ratio by at most 16 / a.
        let ratio = b as f64 / a as f64;
        assert!((ratio - 2.0).abs() <= 2.0 * 16.0 / a as f64, "{a} {b}");
    }

    #[test]
    fn a_light_that_reaches_nothing_seen_gets_the_smallest_side() {
        // A spot aimed away from everything.
        let scene = built_in(&[
            "lights=[{kind=\"spot\", position=[0.0, 5.0, 0.0], direction=[0.0, 1.0, 0.0], intensity=1.0, inner_cone_deg=10.0, outer_cone_deg=20.0}]",
        ]);
        let samples = ScreenSamples::new(&scene);
        assert!(!samples.samples.is_empty());
        assert_eq!(
            samples.fitted_side(&scene.lights[0], |_| 0.01, 2048, 1.0),
            MIN_FIT_SIDE
        );
    }
}
