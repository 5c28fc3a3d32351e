//! Caster culling for the shadow passes: each layer (a cube face, a spot's
//! or a sun's map) draws only the meshes whose bounding box can reach its
//! frustum.
//!
//! A point light's cube renders the scene six times; a caster seen by one
//! face is clipped away entirely by the other five, at the cost of its
//! vertex work and the clipper. A box lies wholly outside a layer when all
//! eight corners are outside one of the half-spaces that bound wgpu's clip
//! volume (`−w ≤ x ≤ w`, `−w ≤ y ≤ w`, `0 ≤ z ≤ w`, depth clipping on:
//! `pipelines::shadow_depth_state`); the box holds every triangle of its
//! mesh (convex hull), so every one of them would be clipped, and the
//! layer's texels are exactly those of the unculled pass. The test is
//! conservative (a box outside the frustum but across no single plane is
//! drawn) and leaves a relative slack far above f32 rounding, so that a
//! vertex the f64 test finds just outside but the GPU's f32 transform puts
//! just inside is still drawn.
//!
//! A light's markers (`crate::scene::light_markers`: emissive or BLEND
//! geometry around the light) are left out of that light's layers, as the
//! reference's shadow rays pass through them.

use super::geometry::ObjectRange;
use super::shadows::ShadowPlan;
use crate::scene::{LightMarkers, Scene, light_markers};
use glam::{DMat4, DVec3, DVec4};

/// Relative slack of the plane test: a corner counts as outside only
/// when its signed distance is below `−SLACK ×` the sum of the magnitudes
/// of the terms that make it. f32 transforms round each term to about
/// 6·10⁻⁸ of its size (four terms, a few ulps), 100× below this.
const SLACK: f64 = 1e-5;

/// The world-space bounding box of each object's mesh (taken when the
/// stream was planned: a GPU-only run frees the meshes as they upload).
pub fn object_bounds(objects: &[ObjectRange]) -> Vec<(DVec3, DVec3)> {
    objects.iter().map(|o| o.bounds).collect()
}

/// Which objects each layer draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LayerCasters {
    /// Per layer of the plan, the objects (indices into the stream's
    /// objects, ascending) whose boxes may reach it.
    pub layers: Vec<Vec<u32>>,
    /// Object draws the culling removed, over all layers.
    pub culled: usize,
}

impl LayerCasters {
    /// The objects with `bounds` each layer of `plan` must draw: those
    /// whose boxes reach the layer's frustum (all of them unless `cull`),
    /// but for the layer's [`markers`] (`markers[layer]`, ascending; an
    /// empty list for none).
    pub fn new(
        plan: &ShadowPlan,
        bounds: &[(DVec3, DVec3)],
        cull: bool,
        markers: &[Vec<u32>],
    ) -> Self {
        let mut culled = 0;
        let layers = plan
            .layers
            .iter()
            .enumerate()
            .map(|(i, layer)| {
                let passing = markers.get(i).map_or(&[][..], Vec::as_slice);
                let kept: Vec<u32> = (0..bounds.len() as u32)
                    .filter(|&o| {
                        let (lo, hi) = bounds[o as usize];
                        !(cull && outside(layer.clip_from_world, lo, hi))
                            && passing.binary_search(&o).is_err()
                    })
                    .collect();
                culled += bounds.len() - kept.len();
                kept
            })
            .collect();
        LayerCasters { layers, culled }
    }
}

/// Per layer of `plan`, the objects (ascending) that are markers of the
/// layer's light (`crate::scene::light_markers::marks` on the object's box
/// and material, at the map's position: an area light's centre); empty
/// when no layer has any, the common case.
pub fn markers(plan: &ShadowPlan, scene: &Scene, objects: &[ObjectRange]) -> Vec<Vec<u32>> {
    let mut layers = vec![Vec::new(); plan.layers.len()];
    for (light, shadow) in scene.lights.iter().zip(&plan.lights) {
        let (Some(shadow), Some(position)) = (shadow, light_markers::map_position(light)) else {
            continue;
        };
        if shadow.settings.markers != LightMarkers::Pass {
            continue;
        }
        let list: Vec<u32> = (0..objects.len() as u32)
            .filter(|&o| {
                let object = &objects[o as usize];
                let material = &scene.materials[object.material as usize];
                light_markers::marks(position, material, object.bounds)
            })
            .collect();
        let first = shadow.first_layer as usize;
        for layer in &mut layers[first..first + shadow.projection.layers() as usize] {
            layer.clone_from(&list);
        }
    }
    if layers.iter().all(Vec::is_empty) {
        Vec::new()
    } else {
        layers
    }
}

/// Whether the box `[lo, hi]` is wholly outside the clip volume of
/// `clip_from_world`: all its corners beyond one bounding plane.
pub fn outside(clip_from_world: DMat4, lo: DVec3, hi: DVec3) -> bool {
    let m = clip_from_world.transpose();
    let (x, y, z, w) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
    // The planes as rows acting on (p, 1): inside where row · (p, 1) ≥ 0.
    let planes = [w + x, w - x, w + y, w - y, z, w - z];
    let corners: [DVec4; 8] = std::array::from_fn(|i| {
        DVec4::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
            1.0,
        )
    });
    planes.iter().any(|plane| {
        corners
            .iter()
            .all(|c| plane.dot(*c) < -SLACK * plane.abs().dot(c.abs()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_is_culled_only_beyond_a_plane() {
        // A 90° face looking down −Z from the origin (reversed, infinite).
        let proj = glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
            std::f64::consts::FRAC_PI_2,
            1.0,
            1e-3,
        );
        let face = proj * DMat4::IDENTITY;
        let unit = DVec3::splat(0.5);
        let at = |c: DVec3| (c - unit, c + unit);
        let (lo, hi) = at(DVec3::new(0.0, 0.0, -5.0));
        assert!(!outside(face, lo, hi), "in front");
        let (lo, hi) = at(DVec3::new(0.0, 0.0, 5.0));
        assert!(outside(face, lo, hi), "behind the light");
        let (lo, hi) = at(DVec3::new(8.0, 0.0, -5.0));
        assert!(outside(face, lo, hi), "beyond the right plane");
        // Straddling the 45° plane x = −z: drawn.
        let (lo, hi) = at(DVec3::new(5.0, 0.0, -5.0));
        assert!(!outside(face, lo, hi), "across the right plane");
        // Touching the plane from outside within the slack: drawn.
        let (lo, hi) = (DVec3::new(5.0, -0.5, -5.0), DVec3::new(6.0, 0.5, -5.0));
        assert!(!outside(face, lo, hi), "on the plane");
    }
}
