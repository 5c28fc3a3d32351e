//! Texture reuse (src/gpu/texture_pool.rs) with the passes drawn in parts
//! (src/gpu/scene_parts.rs): the first part of each pass must clear what
//! the previous render left in the reused textures, the later parts load.
//! The check runs in a child process of this test binary, started with
//! `GONIO_PASS_TRIANGLES=7` in its environment.

mod common;

use gonio::scene::scene_file::{self, SceneSource};

#[test]
fn a_render_in_parts_on_reused_textures_matches_a_fresh_device() {
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "in_parts_child", "--ignored", "--nocapture"])
        .env("GONIO_PASS_TRIANGLES", "7")
        .output()
        .unwrap();
    let log =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "the check in parts failed:\n{log}");
    assert!(log.contains("1 passed"), "the check did not run:\n{log}");
}

#[test]
#[ignore = "run by a_render_in_parts_on_reused_textures_matches_a_fresh_device with GONIO_PASS_TRIANGLES=7"]
fn in_parts_child() {
    assert_eq!(
        std::env::var("GONIO_PASS_TRIANGLES").as_deref(),
        Ok("7"),
        "started without the part size"
    );
    let scene = |positions: [[f64; 3]; 2]| {
        scene_file::load(
            &SceneSource::BuiltIn,
            &[
                common::shadowed_point_lights(&positions),
                "image.width=160".into(),
                "image.height=120".into(),
                "shadows.map_size=128".into(),
            ],
        )
        .unwrap()
    };
    let first = scene([[-2.0, 2.0, 2.5], [2.5, 1.5, -1.0]]);
    let second = scene([[3.0, 5.0, 3.0], [-3.0, 4.0, -3.0]]);
    let (expected, _) = common::gpu_renderer().render(&second).unwrap();
    let mut renderer = common::gpu_renderer();
    let (before, _) = renderer.render(&first).unwrap();
    let maps = renderer.context().textures.held("shadow maps");
    let (after, _) = renderer.render(&second).unwrap();
    assert!(maps.is_some());
    assert_eq!(
        renderer.context().textures.held("shadow maps"),
        maps,
        "reused"
    );
    assert_ne!(before.radiance, expected.radiance, "the scenes differ");
    let differing = common::differing_pixels(&after, &expected);
    assert_eq!(differing, 0, "pixels that differ from a fresh device's");
}
