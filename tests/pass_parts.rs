//! A one-shot render drawn in parts writes the same bytes as one drawn
//! whole. `gonio render` splits its scene pass and its shadow passes into
//! parts of at most `GONIO_PASS_TRIANGLES` triangles (20,000 by default),
//! each submitted and finished before the next is recorded, so that
//! lavapipe's binned scene stays small (src/gpu/scene_parts.rs). A part
//! loads the depth (and colour, or shadow-map layer) the one before it
//! stored, and a rasterizer's result does not depend on where a pass
//! boundary falls, so the EXR (linear `f32` radiance) must be identical,
//! byte for byte, for any part size; this checks it with parts of 7 and
//! 500 triangles against the whole passes (`0`), on scenes whose shadow
//! maps are a cube (six layers), a sun's orthographic map and a spot's.

mod common;

use std::path::Path;

/// `gonio render ARGS -o DIR/NAME.exr` with `GONIO_PASS_TRIANGLES=parts`;
/// the EXR's bytes.
fn render(dir: &Path, name: &str, parts: &str, args: &[&str]) -> Vec<u8> {
    let out = dir.join(format!("{name}-{parts}.exr"));
    let result = common::gonio()
        .arg("render")
        .args(args)
        .arg("-o")
        .arg(&out)
        .env("GONIO_PASS_TRIANGLES", parts)
        .output()
        .expect("gonio runs");
    assert!(
        result.status.success(),
        "{name} with parts of {parts}: {}{}",
        String::from_utf8_lossy(&result.stderr),
        common::LAVAPIPE_TEST_HINT
    );
    std::fs::read(&out).expect("the EXR was written")
}

fn check(name: &str, args: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let whole = render(dir.path(), name, "0", args);
    for parts in ["7", "500"] {
        let split = render(dir.path(), name, parts, args);
        assert!(
            split == whole,
            "{name}: the render in parts of {parts} triangles differs from the whole passes' \
             (the split must not change a byte)"
        );
    }
}

#[test]
fn point_light_cube_map_in_parts_is_the_whole_render() {
    // About 3,600 sphere triangles plus the floor: hundreds of parts of 7.
    check(
        "point",
        &[
            "--set",
            "objects.0.segments=40",
            "--set",
            "lights.0.shadows=true",
            "--set",
            "image.width=96",
            "--set",
            "image.height=72",
        ],
    );
}

#[test]
fn sun_and_spot_maps_in_parts_are_the_whole_render() {
    check(
        "sun",
        &[
            "--set",
            r#"lights=[{kind="directional", direction=[-0.4, -1.0, -0.3], irradiance=[3.0, 3.0, 3.0], shadows=true}]"#,
            "--set",
            "image.width=96",
            "--set",
            "image.height=72",
        ],
    );
    check(
        "spot",
        &[
            concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/spot-bench.toml"),
            "--set",
            "image.width=96",
            "--set",
            "image.height=72",
        ],
    );
}
