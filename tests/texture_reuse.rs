//! One-shot renders on one device reuse the last render's textures (the
//! radiance and depth targets, the shadow-map array: src/gpu/texture_pool.rs)
//! and change no texel by it: a render that follows another, whose maps
//! and targets held other depths and colours, is bit for bit the render
//! of a fresh device.

mod common;

use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

/// Lights low beside the sphere: their maps hold near (large, reversed)
/// depths.
const LOW: [[f64; 3]; 2] = [[-2.0, 2.0, 2.5], [2.5, 1.5, -1.0]];
/// The same two lights moved up.
const HIGH: [[f64; 3]; 2] = [[3.0, 5.0, 3.0], [-3.0, 4.0, -3.0]];

/// The built-in scene with two shadowed point lights at `positions`.
fn two_lights(positions: [[f64; 3]; 2], width: u32) -> Scene {
    two_lights_with(positions, width, &[])
}

/// [`two_lights`] with more `--set`s.
fn two_lights_with(positions: [[f64; 3]; 2], width: u32, sets: &[&str]) -> Scene {
    let mut overrides = vec![
        common::shadowed_point_lights(&positions),
        format!("image.width={width}"),
        "image.height=192".into(),
        "shadows.map_size=256".into(),
    ];
    overrides.extend(sets.iter().map(|s| s.to_string()));
    scene_file::load(&SceneSource::BuiltIn, &overrides).unwrap()
}

#[test]
fn a_render_after_another_reuses_its_textures_and_matches_a_fresh_device() {
    // The same plan shape (two cubes of 256²) and image size, the lights
    // moved up: the first render's maps hold nearer (larger, reversed)
    // depths than the second draws, so a drawn layer not cleared would
    // keep them (the pass keeps the larger), and its targets the first's
    // colours.
    let first = two_lights(LOW, 256);
    let second = two_lights(HIGH, 256);

    let mut fresh = common::gpu_renderer();
    let (expected, _) = fresh.render(&second).unwrap();

    let mut renderer = common::gpu_renderer();
    let (before, _) = renderer.render(&first).unwrap();
    let pool = &renderer.context().textures;
    let maps = pool.held("shadow maps").expect("the shadow maps are held");
    let radiance = pool.held("radiance").expect("the radiance target is held");
    let depth = pool.held("depth").expect("the depth target is held");
    assert_eq!(pool.len(), 3, "one texture per role");

    let (after, _) = renderer.render(&second).unwrap();
    let pool = &renderer.context().textures;
    assert_eq!(pool.held("shadow maps"), Some(maps), "the maps were reused");
    assert_eq!(
        pool.held("radiance"),
        Some(radiance),
        "the target was reused"
    );
    assert_eq!(pool.held("depth"), Some(depth), "the depth was reused");

    assert!(
        common::differing_pixels(&before, &expected) > 0,
        "the two scenes must differ for the reuse to be tested"
    );
    assert_eq!(
        common::differing_pixels(&after, &expected),
        0,
        "pixels of the render on reused textures that differ from a fresh device's"
    );
}

#[test]
fn another_shape_gets_new_textures_and_the_pool_keeps_one_per_role() {
    let mut renderer = common::gpu_renderer();
    renderer.render(&two_lights(HIGH, 256)).unwrap();
    let old = renderer.context().textures.held("radiance").unwrap();
    let wider = two_lights(HIGH, 320);
    let (frame, _) = renderer.render(&wider).unwrap();
    let pool = &renderer.context().textures;
    let new = pool.held("radiance").unwrap();
    assert_ne!(new, old, "a wider image needs a new target");
    assert_eq!(new.width(), 320);
    assert_eq!(pool.len(), 3, "the old target was dropped, not kept beside");
    let (expected, _) = common::gpu_renderer().render(&wider).unwrap();
    assert_eq!(common::differing_pixels(&frame, &expected), 0);
}

#[test]
fn an_msaa_render_after_another_matches_a_fresh_device_and_a_plain_one_drops_its_target() {
    let msaa = ["image.msaa=4"];
    let first = two_lights_with(LOW, 256, &msaa);
    let second = two_lights_with(HIGH, 256, &msaa);
    let (expected, _) = common::gpu_renderer().render(&second).unwrap();
    let mut renderer = common::gpu_renderer();
    renderer.render(&first).unwrap();
    let held = renderer
        .context()
        .textures
        .held("radiance (multisampled)")
        .expect("the multisampled target is held");
    let (after, _) = renderer.render(&second).unwrap();
    let pool = &renderer.context().textures;
    assert_eq!(pool.held("radiance (multisampled)"), Some(held), "reused");
    assert_eq!(
        common::differing_pixels(&after, &expected),
        0,
        "pixels of the MSAA render on reused textures that differ from a fresh device's"
    );
    // A render without MSAA does not keep the multisampled target alive.
    renderer.render(&two_lights(HIGH, 256)).unwrap();
    let pool = &renderer.context().textures;
    assert!(pool.held("radiance (multisampled)").is_none());
    assert_eq!(pool.len(), 3);
}

#[test]
fn an_unshadowed_render_drops_the_held_shadow_maps() {
    let mut renderer = common::gpu_renderer();
    renderer.render(&two_lights(HIGH, 256)).unwrap();
    assert!(renderer.context().textures.held("shadow maps").is_some());
    let unshadowed = scene_file::load(
        &SceneSource::BuiltIn,
        &["image.width=256".into(), "image.height=192".into()],
    )
    .unwrap();
    renderer.render(&unshadowed).unwrap();
    let pool = &renderer.context().textures;
    assert!(
        pool.held("shadow maps").is_none(),
        "not held past a render that did not take it"
    );
    assert_eq!(pool.len(), 2);
}
