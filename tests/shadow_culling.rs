//! Caster culling per shadow-map layer (src/gpu/shadow_culling.rs) changes
//! no texel: scenes whose cube faces really skip casters render exactly
//! (bit for bit, every channel of every pixel) as with every caster drawn
//! into every face. That includes the faces culling leaves empty, which
//! are not drawn at all (src/gpu/shadow_maps.rs: the scene pass reads them
//! as lit through a zeroed view).

mod common;

use gonio::gpu::geometry::GeometryData;
use gonio::gpu::shadow_culling::{LayerCasters, object_bounds};
use gonio::gpu::shadows::ShadowPlan;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

/// Object draws the culling removes from `scene`'s shadow passes, and
/// how many there are without it.
fn culled(scene: &Scene) -> (usize, usize) {
    let plan = ShadowPlan::new(scene);
    let objects = GeometryData::new(scene, false, false).objects;
    let casters = LayerCasters::new(&plan, &object_bounds(&objects), true, &[]);
    (casters.culled, plan.layers.len() * objects.len())
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
    let casters = LayerCasters::new(&plan, &object_bounds(&objects), true, &[]);
    let empty = casters.layers.iter().filter(|l| l.is_empty()).count();
    assert!(
        empty > 0,
        "no empty face: the skipped-layer path is not tested"
    );
    same_with_and_without(&scene, "built-in, 4 point lights");
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
