//! A light's markers: the geometry that shows where a light is, and that
//! would shadow everything the light reaches if it cast the light's shadow.
//!
//! Assets place visible geometry around their lights: a bulb, a lamp's
//! glowing shade, the emissive cone an exporter draws for a spot light
//! (KHR's `ShadowsSpot` sample wraps its spot light in a closed, emissive,
//! alpha-blended cone). glTF's `KHR_lights_punctual` light is a point with
//! no surface, so nothing in the file says that the cone is "the light";
//! drawn as an ordinary caster, a closed marker around the light leaves
//! the whole scene in its shadow. The Khronos sample viewer, three.js and
//! Filament draw no shadows from glTF lights by default, so the asset's
//! authors never see it.
//!
//! The rule: a mesh is a **marker** of a light with a position (point,
//! spot, an area light's sample) when its material emits or is alpha
//! BLEND — what a light's visible form is made of — and its box holds the
//! light's position. With `shadow_markers = "pass"` (the default) a
//! light's markers cast none of *its* shadow; they still shadow every
//! other light, and are lit and drawn as always. A directional light has
//! no position and no markers. `"cast"` draws them as casters like any
//! other surface.
//!
//! Both renderers apply the one predicate [`marks`] to the box of a mesh's
//! indexed vertices (the GPU's `ObjectRange::bounds`, the reference's
//! [`mesh_box`]); the GPU's area light shares one map at its centre, so
//! there the centre is the position tested.

use super::{Light, LightMarkers, Mesh, Scene};
use crate::material::{AlphaMode, Material};
use glam::DVec3;

/// Relative slack of the box test, against the box's extent: a light on a
/// marker's face (a flat emitter with the light's sample on it) is inside,
/// whatever the f32 rounding of the GPU's vertex positions.
const SLACK: f64 = 1e-6;

/// Whether a mesh of `material` whose indexed vertices span `bounds` is a
/// marker of a light at `position`.
pub fn marks(position: DVec3, material: &Material, bounds: (DVec3, DVec3)) -> bool {
    if !(material.emits() || matches!(material.alpha_mode, AlphaMode::Blend)) {
        return false;
    }
    let (lo, hi) = bounds;
    let slack = SLACK * (hi - lo).max_element().max(1e-12);
    position.cmpge(lo - slack).all() && position.cmple(hi + slack).all()
}

/// The box of the vertices `mesh`'s triangles use (`None` without
/// triangles).
pub fn mesh_box(mesh: &Mesh) -> Option<(DVec3, DVec3)> {
    super::mesh::bounds(
        mesh.indices
            .iter()
            .flatten()
            .map(|&v| mesh.positions[v as usize]),
    )
}

/// Per light of `scene`, per mesh: whether the mesh casts none of the
/// light's shadow (a marker of a light whose `shadow_markers` is
/// `"pass"`). Empty inner lists for lights without a position or with
/// `"cast"`, and when no mesh is a marker of any light (the common case:
/// the reference's shadow rays then ask nothing per hit).
pub fn passing(scene: &Scene) -> Vec<Vec<bool>> {
    let boxes: Vec<Option<(DVec3, DVec3)>> = scene.meshes.iter().map(mesh_box).collect();
    scene
        .lights
        .iter()
        .enumerate()
        .map(|(l, light)| {
            let position = match light.position() {
                Some(p) if scene.shadow_settings(l).markers == LightMarkers::Pass => p,
                _ => return Vec::new(),
            };
            let list: Vec<bool> = scene
                .meshes
                .iter()
                .zip(&boxes)
                .map(|(mesh, b)| {
                    b.is_some_and(|b| marks(position, &scene.materials[mesh.material], b))
                })
                .collect();
            if list.contains(&true) {
                list
            } else {
                Vec::new()
            }
        })
        .collect()
}

/// Where the GPU's shadow map of `light` sits: its position, an area
/// light's centre for its samples (they share one map there).
pub fn map_position(light: &Light) -> Option<DVec3> {
    match *light {
        Light::AreaSample { center, .. } => Some(center),
        _ => light.position(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::Rgb;

    fn material(emission: f64, blend: bool) -> Material {
        let mut m = Material::new("lamp", crate::material::ReflectanceModel::Lambert);
        m.emission = Rgb::splat(emission);
        if blend {
            m.alpha_mode = AlphaMode::Blend;
        }
        m
    }

    #[test]
    fn an_emissive_or_blended_box_around_the_light_is_its_marker() {
        let unit = (DVec3::splat(-1.0), DVec3::splat(1.0));
        let inside = DVec3::new(0.2, 0.9, -0.5);
        assert!(marks(inside, &material(1.0, false), unit));
        assert!(marks(inside, &material(0.0, true), unit));
        // An opaque, dark lamp shade shadows as it should.
        assert!(!marks(inside, &material(0.0, false), unit));
        // Outside the box: a bright object next to the light casts.
        assert!(!marks(
            DVec3::new(0.0, 1.01, 0.0),
            &material(1.0, false),
            unit
        ));
        // On a face, within the slack (a flat emitter with the light on it).
        let flat = (DVec3::new(-1.0, 0.0, -1.0), DVec3::new(1.0, 0.0, 1.0));
        assert!(marks(
            DVec3::new(0.3, 1e-9, 0.0),
            &material(1.0, false),
            flat
        ));
    }
}
