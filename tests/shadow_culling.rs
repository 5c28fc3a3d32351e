//! Caster culling per shadow-map layer (src/gpu/shadow_culling.rs), flat
//! casters drawn only where other objects' lookups read included, changes
//! no pixel: scenes whose cube faces really skip casters render exactly
//! (bit for bit, every channel of every pixel) as with every caster drawn
//! into every face. That includes the faces culling leaves empty, which
//! are not drawn at all (src/gpu/shadow_maps.rs: the scene pass reads them
//! as lit through a zeroed view).

mod common;

use gonio::gpu::geometry::GeometryData;
use gonio::gpu::shadow_culling::{LayerCasters, object_boxes};
use gonio::gpu::shadows::ShadowPlan;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

/// Object draws the culling removes from `scene`'s shadow passes, and
/// how many there are without it.
fn culled(scene: &Scene) -> (usize, usize) {
    let plan = ShadowPlan::new(scene);
    let objects = GeometryData::new(scene, false, false).objects;
    let casters = LayerCasters::new(&plan, &object_boxes(&objects), false);
    (casters.culled, plan.layers.len() * objects.len())
}

/// Draws of flat casters `scene`'s shadow passes limit to what other
/// objects' lookups read.
fn clipped(scene: &Scene) -> usize {
    let plan = ShadowPlan::new(scene);
    let objects = GeometryData::new(scene, false, false).objects;
    LayerCasters::new(&plan, &object_boxes(&objects), false).clipped
}

/// Renders `scene` with and without culling and requires identical frames.
fn same_with_and_without(scene: &Scene, what: &str) {
    let (removed, total) = culled(scene);
    println!("{what}: {removed} of {total} caster draws culled");
    assert!(
        removed > 0,
        "{what}: the culling must remove draws for this test to mean anything"
    );
    let mut renderer = common::gpu_renderer();
    renderer.cull_shadow_casters = false;
    let (all, _) = renderer.render(scene).unwrap();
    renderer.cull_shadow_casters = true;
    let (culled, timings) = renderer.render(scene).unwrap();
    let differing = common::differing_pixels(&all, &culled);
    assert_eq!(differing, 0, "{what}: pixels that differ");
    // The map's shadows are really in the image (a lit-only frame would
    // agree trivially): turning shadows off changes it.
    let mut unshadowed = scene.clone();
    unshadowed
        .lights
        .iter_mut()
        .for_each(|l| l.set_shadows(false));
    let (lit, _) = renderer.render(&unshadowed).unwrap();
    assert_ne!(lit.radiance, culled.radiance, "{what}: shadows visible");
    if let Some((name, ..)) = timings
        .entries
        .iter()
        .find(|(n, ..)| n.starts_with("shadow passes"))
    {
        assert!(
            name.contains(&format!("{removed} of {total} caster draws culled")),
            "{name}"
        );
    }
}

#[test]
fn four_point_lights_on_the_built_in_scene_render_the_same_culled() {
    let lights = [[3.0, 5.0, 3.0], [-3.0, 5.0, 3.0], [3.0, 4.0, -3.0], [-3.0, 4.0, -3.0]]
        .map(|[x, y, z]| {
            format!(
                "{{kind=\"point\", position=[{x}, {y}, {z}], intensity=[20.0, 20.0, 20.0], shadows=true}}"
            )
        })
        .join(", ");
    let scene = scene_file::load(
        &SceneSource::BuiltIn,
        &[
            format!("lights=[{lights}]"),
            "image.width=320".into(),
            "image.height=240".into(),
            "shadows.map_size=512".into(),
        ],
    )
    .unwrap();
    // The upward faces of lights above everything see no caster: the
    // culled render skips them.
    let plan = ShadowPlan::new(&scene);
    let objects = GeometryData::new(&scene, false, false).objects;
    let casters = LayerCasters::new(&plan, &object_boxes(&objects), false);
    let empty = casters.layers.iter().filter(|l| l.is_empty()).count();
    assert!(
        empty > 0,
        "no empty face: the skipped-layer path is not tested"
    );
    assert!(
        clipped(&scene) > 0,
        "the floor is drawn whole: the flat-caster path is not tested"
    );
    same_with_and_without(&scene, "built-in, 4 point lights");
}

/// A floor drawn only under what stands on it (docs/shadows.md, "A floor
/// drawn only under what stands on it") changes no texel a lookup reads,
/// for every light kind, near grazing and steep, with and without PCF,
/// in each shading mode: the ball touches the floor, and the lights
/// include one 0.4 m above it (the floor seen at up to 87° from its
/// normal), a sun 78° from it and one below it, for which the floor is
/// the ball's only occluder.
#[test]
fn flat_casters_clipped_to_what_others_read_render_the_same() {
    let lights = [
        "{kind=\"point\", position=[3.5, 0.4, 0.5], intensity=[20.0, 20.0, 20.0], shadows=true}",
        "{kind=\"point\", position=[-1.0, 3.0, 1.0], intensity=[20.0, 20.0, 20.0], shadows=true}",
        // Below the floor, which hides the ball from it: the floor's
        // depth under the ball is what shadows the ball's underside.
        "{kind=\"point\", position=[0.5, -1.5, 0.8], intensity=[20.0, 20.0, 20.0], shadows=true}",
        "{kind=\"spot\", position=[-2.0, 3.0, 2.0], direction=[0.5, -1.0, -0.5], intensity=[30.0, 30.0, 30.0], inner_cone_deg=20.0, outer_cone_deg=40.0, shadows=true}",
        "{kind=\"directional\", direction=[-1.0, -0.22, -0.3], irradiance=[2.0, 2.0, 2.0], shadows=true}",
    ]
    .join(", ");
    for (mode, filter) in [
        ("phong", "none"),
        ("phong", "pcf"),
        ("gouraud", "pcf"),
        ("flat", "pcf"),
    ] {
        let scene = scene_file::load(
            &SceneSource::BuiltIn,
            &[
                format!("lights=[{lights}]"),
                format!("shading.mode=\"{mode}\""),
                format!("shadows.filter=\"{filter}\""),
                "image.width=256".into(),
                "image.height=192".into(),
                "shadows.map_size=512".into(),
            ],
        )
        .unwrap();
        let clipped = clipped(&scene);
        println!("{mode}, filter {filter}: {clipped} flat caster draws clipped");
        assert!(clipped > 0, "{mode}, {filter}: the floor is drawn whole");
        same_with_and_without(
            &scene,
            &format!("built-in, {mode}, filter {filter}, 5 lights of 3 kinds"),
        );
    }
}

#[test]
fn alpha_mask_casters_render_the_same_culled() {
    // Nine meshes, MASK among them: the culled runs switch between the
    // depth-only and the masked pipeline per object.
    let scene = scene_file::load(
        &SceneSource::File(common::gltf_asset("AlphaBlendModeTest/AlphaBlendModeTest.glb")),
        &[
            "lights=[{kind=\"point\", position=[0.0, 1.5, 1.5], intensity=[5.0, 5.0, 5.0], shadows=true}, {kind=\"spot\", position=[-2.0, 3.0, 2.0], direction=[0.5, -1.0, -0.5], intensity=[9.0, 9.0, 9.0], inner_cone_deg=10.0, outer_cone_deg=20.0, shadows=true}]".into(),
            "image.width=256".into(),
            "image.height=192".into(),
            "shadows.map_size=512".into(),
        ],
    )
    .unwrap();
    same_with_and_without(&scene, "AlphaBlendModeTest, a point and a spot light");
}
