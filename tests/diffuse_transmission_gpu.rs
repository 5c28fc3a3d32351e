//! Diffuse transmission (`KHR_materials_diffuse_transmission`) on the GPU
//! (shaders/brdf/gltf_layers/transmission.wgsl) against the f64 reference
//! and a closed form: `assets/scenes/transmission/leaf.toml`, a thin wall
//! seen from above and lit only from below.

mod common;

use gonio::environment::map::{EnvironmentMap, MapSettings, Specular};
use gonio::environment::test_maps;
use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Rgb, Scene};
use std::path::PathBuf;
use std::sync::Arc;

fn leaf(sets: &[&str]) -> Scene {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/transmission/leaf.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    scene_file::load(&SceneSource::File(path), &sets).expect("leaf.toml loads")
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

/// The GPU's image of `scene` and the reference's (at the pixel centres),
/// asserted to agree within the derived tolerance of every
/// GPU-vs-reference comparison (`common::compare_to_reference`).
fn agreeing_with_the_reference(scene: &Scene, what: &str) -> (Frame, Frame) {
    let frame = gpu(scene);
    let (center, jittered) = common::reference_with_jitter(scene);
    let c = common::compare_to_reference(scene, &frame, &center, &jittered);
    common::assert_agrees("leaf", what, &c, &frame, &center);
    (frame, center)
}

/// A light behind the wall: `f_t E |cos θ_i|` with `f_t = (1 − m)(1 −
/// max₃ F(H))(1 − T) D c_dt/π` in both renderers, pixel by pixel, within
/// the derived tolerance of every GPU-vs-reference comparison
/// (`common::compare_to_reference`). Without the GPU's far-side term the
/// wall is black (it faces away from the light): the test fails.
#[test]
fn a_light_behind_shines_through_as_the_reference_says() {
    let (frame, center) =
        agreeing_with_the_reference(&leaf(&[]), "diffuse transmission, light behind");
    let k = frame.index(31, 31);
    assert!(
        center.radiance[k][0] > 0.05,
        "the wall is lit through: {:?}",
        center.radiance[k]
    );
}

/// The textures of diffuse transmission (`diffuse_transmission_texture`,
/// `diffuse_transmission_color_texture`: glTF's
/// `diffuseTransmissionTexture` and `diffuseTransmissionColorTexture`),
/// here the checker on both, shine through as in the reference, within
/// the same derived tolerance (which follows a texture's edges by the
/// pixel-centre jitter, `common::compare_to_reference`). The GPU reads
/// them through the texture slots' bits 5 and 6, which they share with
/// Ward's widths (`texture_fields::SHARED_BITS`); without them the wall
/// would be drawn with the factors alone, one colour, and fail.
#[test]
fn its_textures_shine_through_as_the_reference_says() {
    let checker = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/transmission/checker.png"
    );
    let share = format!("materials.leaf.diffuse_transmission_texture=\"{checker}\"");
    let colour = format!("materials.leaf.diffuse_transmission_color_texture=\"{checker}\"");
    let (frame, _) =
        agreeing_with_the_reference(&leaf(&[&share, &colour]), "diffuse transmission, textured");
    let lit: Vec<f32> = (0..frame.width)
        .map(|j| frame.radiance[frame.index(26, j)][0])
        .collect();
    let (lo, hi) = lit
        .iter()
        .fold((f32::MAX, f32::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    assert!(hi > 1.5 * lo, "the checker shows through: {lo} to {hi}");
}

/// A white furnace on the far side: with `D = 1` (no reflected diffuse
/// part) and a uniform map of radiance `L` whose "none" mode lights no
/// lobe, the GPU's pixel is exactly the transmitted light
/// `(1 − F(μ_o)) c_dt L` (SH irradiance of a constant map is `π L` in
/// every order; `F` at `N` as the reference's straight ray weighs the
/// lobe; `μ_o = 1` at the centre pixel of the odd image), within the f32
/// light loop's `64 ε`.
#[test]
fn a_white_environment_shines_through_by_the_closed_form() {
    let mut scene = leaf(&[
        "materials.leaf.diffuse_transmission=1",
        "lights.0.irradiance=[0, 0, 0]",
    ]);
    let l = Rgb::new(0.5, 1.0, 2.0);
    scene.environment.map = Some(EnvironmentMap {
        data: Arc::new(test_maps::uniform(32, l)),
        settings: MapSettings {
            specular: Specular::None,
            ..Default::default()
        },
    });
    let frame = gpu(&scene);
    let f0 = ((1.5f64 - 1.0) / (1.5 + 1.0)).powi(2);
    let c_dt = Rgb::new(0.9, 0.6, 0.1);
    let want = c_dt * l * (1.0 - f0);
    let k = frame.index(31, 31);
    let got = Rgb::from(frame.radiance[k].map(f64::from));
    for (g, w) in got.to_array().into_iter().zip(want.to_array()) {
        assert!(
            (g - w).abs() <= 64.0 * common::EPS * w,
            "furnace through the wall: GPU {got:?}, closed form {want:?}"
        );
    }
}
