//! The `unlit` model (contract "Other glTF material extensions", glTF
//! `KHR_materials_unlit`) rendered by the GPU against the f64 reference:
//! a textured unlit floor beside a lit ball (assets/scenes/textured/
//! unlit.toml) and the Khronos UnlitTest sample, with the derived
//! tolerance of tests/gpu_vs_cpu.rs (`common::tolerance`, the jitter and
//! the level-of-detail envelope of the textures). Unlit adds nothing to
//! that tolerance: `L = b` is a copy of the textured, vertex-coloured base
//! colour both renderers already compute.
//!
//! Unlit means unlit: the floor's pixels are the same with the light, the
//! ambient and the shadow gone, on the GPU and in the reference, and the
//! ball's are not.

mod common;

use gonio::frame::Frame;
use gonio::material::ReflectanceModel;
use gonio::output::compare::compare_with_spreads;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::PathBuf;

fn asset(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(relative)
}

fn load(path: &str, sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    scene_file::load(&SceneSource::File(asset(path)), &sets)
        .unwrap_or_else(|e| panic!("{path} loads: {e}"))
}

/// GPU against reference under the derived tolerance; returns both.
fn gpu_matches_reference(label: &str, scene: &Scene, min_pixels: usize) -> (Frame, Frame) {
    let gpu = common::gpu_renderer().render(scene).expect("GPU render").0;
    let (center, jittered) = common::reference_with_jitter(scene);
    let (low, high) = common::lod_envelope(scene, &center);
    let c = compare_with_spreads(
        &gpu,
        &center,
        &[
            (&jittered[0], &jittered[1]),
            (&jittered[2], &jittered[3]),
            (&low, &high),
        ],
        common::tolerance(scene, &center),
    );
    eprintln!("{label}: {}", c.summary());
    assert!(
        c.compared > min_pixels,
        "{label}: {} pixels compared",
        c.compared
    );
    common::assert_agrees(label, "GPU and reference disagree", &c, &gpu, &center);
    (gpu, center)
}

/// Pixel (x, y) of `f`.
fn pixel(f: &Frame, x: u32, y: u32) -> [f32; 3] {
    f.radiance[f.index(y, x)]
}

#[test]
fn unlit_textured_floor_gpu_matches_reference_and_ignores_the_light() {
    let path = "assets/scenes/textured/unlit.toml";
    let scene = load(path, &[]);
    let floor = scene.materials.iter().find(|m| m.name == "floor").unwrap();
    assert_eq!(floor.model, ReflectanceModel::Unlit);
    assert_eq!(floor.textures.len(), 1);
    let (gpu, reference) = gpu_matches_reference("unlit floor", &scene, 10_000);
    // The same scene under a dimmer light from the other side, unshadowed,
    // without the ambient: the floor (the image's lower edge) keeps its
    // pixels exactly, the ball darkens.
    let dark = load(
        path,
        &[
            "lights=[{kind=\"point\", position=[-3.0, 5.0, 3.0], intensity=[10.0, 10.0, 10.0]}]",
            "ambient.radiance=[0.0, 0.0, 0.0]",
        ],
    );
    let gpu_dark = common::gpu_renderer().render(&dark).expect("GPU render").0;
    let reference_dark = gonio::reference::render(&dark);
    let (w, h) = (gpu.width, gpu.height);
    let floor_row = h - 3;
    for x in 0..w {
        assert_eq!(
            pixel(&gpu, x, floor_row),
            pixel(&gpu_dark, x, floor_row),
            "GPU, pixel ({x}, {floor_row})"
        );
        assert_eq!(
            pixel(&reference, x, floor_row),
            pixel(&reference_dark, x, floor_row),
            "reference, pixel ({x}, {floor_row})"
        );
    }
    let ball = (w / 2, h / 3);
    for f in [&gpu, &reference] {
        assert!(pixel(f, ball.0, ball.1)[0] > 2.0 * pixel(&gpu_dark, ball.0, ball.1)[0]);
    }
}

/// The Khronos UnlitTest (assets/gltf-pbr-next/UnlitTest): two unlit
/// boxes, one by its factor, one by vertex colours... as the sample's
/// README shows them; GPU against reference.
#[test]
fn unlit_test_sample_gpu_matches_reference() {
    let path = "assets/gltf-pbr-next/UnlitTest/UnlitTest.glb";
    let scene = load(path, &["image.width=160", "image.height=120"]);
    let unlit = scene
        .effective_materials()
        .iter()
        .filter(|m| m.model == ReflectanceModel::Unlit)
        .count();
    assert!(unlit > 0, "UnlitTest has unlit materials");
    // The two boxes cover about a fifth of the image.
    gpu_matches_reference("UnlitTest", &scene, 3_000);
}
