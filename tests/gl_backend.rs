//! The headless renderer on wgpu's GL backend (Mesa's llvmpipe through
//! EGL): it renders, and what it renders agrees with the CPU reference
//! under the same derived tolerance as on Vulkan (tests/gpu_vs_cpu.rs).
//!
//! Shadowed scenes are compared with the same scenes rendered on Vulkan
//! (the outer test renders those): the same shader on the same
//! rasterizer, so the frames must agree within the f32 tolerance at every
//! pixel. Before the fix in `gpu::shadow_maps::texture_layers`, GL drew
//! every receiver in shadow (wgpu's GL backend made a one-layer map a
//! `TEXTURE_2D` and a six-layer one a cube map, which the scene pass then
//! sampled as a 2D array).
//!
//! llvmpipe's GLES lacks `EXT_color_buffer_float`, so the radiance target
//! there is `Rgba32Uint` holding the f32 bits
//! (`GpuContext::radiance_format`); before that, `WGPU_BACKEND=gl gonio
//! render` panicked in pipeline creation.
//!
//! The backend is chosen by the `WGPU_BACKEND` variable, which is
//! process-wide: the one test here runs this test binary again with the
//! variable set and only the ignored inner test selected. `./setup.sh`
//! installs the EGL and GLES libraries; without them the test fails and
//! says so (tests never skip).

mod common;

use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::PathBuf;

/// Scene sources with their overrides (160 × 120 pixels).
fn load(source: SceneSource, sets: &[&str]) -> Scene {
    // A glTF without lights under the directional default light, which
    // both renderers evaluate exactly (not the studio's split sum).
    let mut all = vec![
        "image.width=160",
        "image.height=120",
        "gltf.default_light=\"directional\"",
    ];
    all.extend_from_slice(sets);
    let sets: Vec<String> = all.iter().map(|s| s.to_string()).collect();
    scene_file::load(&source, &sets).expect("scene loads")
}

fn asset(relative: &str) -> SceneSource {
    SceneSource::File(
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("assets")
            .join(relative),
    )
}

/// The scenes rendered on GL: every shading mode, textures, a glTF asset,
/// an environment map.
fn scenes() -> Vec<(&'static str, Scene)> {
    vec![
        ("built-in, phong", load(SceneSource::BuiltIn, &[])),
        (
            "built-in, flat",
            load(SceneSource::BuiltIn, &["shading.mode=\"flat\""]),
        ),
        (
            "built-in, gouraud",
            load(SceneSource::BuiltIn, &["shading.mode=\"gouraud\""]),
        ),
        (
            "textured.toml",
            load(asset("scenes/textured/textured.toml"), &[]),
        ),
        (
            "Suzanne.gltf",
            load(asset("gltf/Suzanne/Suzanne.gltf"), &[]),
        ),
        (
            "environment.toml (SH twin)",
            load(
                asset("scenes/environment.toml"),
                &["environment.reference=\"sh\""],
            ),
        ),
    ]
}

/// Shadowed scenes of each projection (the point light's cube, a spot's
/// perspective map, the sun's orthographic one), and two point lights
/// (twelve layers: a cube-map array to wgpu's GL guess).
fn shadowed_scenes() -> Vec<(&'static str, Scene)> {
    let spot = "lights=[{kind=\"spot\", position=[2.0,4.0,2.0], direction=[-0.4,-1.0,-0.4], intensity=[60.0,60.0,60.0], inner_cone_deg=20.0, outer_cone_deg=35.0, shadows=true}]";
    vec![
        (
            "point light, cube map",
            load(SceneSource::BuiltIn, &["lights.0.shadows=true"]),
        ),
        ("spot light", load(SceneSource::BuiltIn, &[spot])),
        (
            "two point lights",
            load(
                SceneSource::BuiltIn,
                &[
                    "lights=[{kind=\"point\", position=[2.0,4.0,2.0], intensity=[30.0,30.0,30.0], shadows=true}, {kind=\"point\", position=[-3.0,3.0,1.0], intensity=[20.0,20.0,20.0], shadows=true}]",
                ],
            ),
        ),
        (
            "shadows-directional.gltf",
            load(
                asset("gltf/ShadowsDirectional/shadows-directional.gltf"),
                &[],
            ),
        ),
    ]
}

/// Where the outer test leaves the Vulkan frames of [`shadowed_scenes`]
/// for the inner one: `frame-N.f32`, RGB little-endian.
const VULKAN_FRAMES: &str = "GONIO_TEST_VULKAN_FRAMES";

#[test]
fn the_gl_backend_renders_what_the_reference_renders() {
    let frames = tempfile::tempdir().unwrap();
    let mut vulkan = GpuRenderer::new(GpuContext::new(&AdapterChoice::Auto).expect("adapter"));
    for (i, (label, scene)) in shadowed_scenes().into_iter().enumerate() {
        let (frame, _) = vulkan
            .render(&scene)
            .unwrap_or_else(|e| panic!("{label}: Vulkan render failed: {e}"));
        let bytes: Vec<u8> = frame
            .radiance
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(frames.path().join(format!("frame-{i}.f32")), bytes).unwrap();
    }
    let output = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--ignored",
            "--exact",
            "on_gl_as_set_by_the_outer_test",
            "--nocapture",
        ])
        .env("WGPU_BACKEND", "gl")
        .env(VULKAN_FRAMES, frames.path())
        .output()
        .expect("the test binary runs again");
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "the GL run failed (./setup.sh installs libegl1, libgles2 and Mesa's GL driver; on Debian 12: `sudo apt-get install libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri`):\n{stdout}\n{stderr}"
    );
    // The inner test's table (`--nocapture` shows it).
    for line in stderr.lines().filter(|l| l.starts_with("GL ")) {
        eprintln!("{line}");
    }
    assert!(
        stdout.contains("1 passed"),
        "the inner test did not run:\n{stdout}\n{stderr}"
    );
}

#[test]
#[ignore = "run by the_gl_backend_renders_what_the_reference_renders with WGPU_BACKEND=gl"]
fn on_gl_as_set_by_the_outer_test() {
    assert_eq!(std::env::var("WGPU_BACKEND").as_deref(), Ok("gl"));
    let context =
        GpuContext::new(&AdapterChoice::Auto).unwrap_or_else(|e| panic!("no GL adapter: {e}"));
    assert_eq!(context.adapter_info.backend, wgpu::Backend::Gl);
    eprintln!(
        "adapter: {}, radiance target {:?}",
        context.describe(),
        context.radiance_format()
    );
    let mut renderer = GpuRenderer::new(context);
    for (label, scene) in scenes() {
        let (gpu, _) = renderer
            .render(&scene)
            .unwrap_or_else(|e| panic!("{label}: GL render failed: {e}"));
        let (center, jittered) = common::reference_with_jitter(&scene);
        let c = common::compare_to_reference(&scene, &gpu, &center, &jittered);
        eprintln!("GL {label:<40} | {}", c.summary());
        assert!(
            c.compared > scene.width as usize * scene.height as usize / 10,
            "{label}: too few covered pixels"
        );
        common::assert_agrees(
            &format!("gl {label}"),
            "GL and reference disagree",
            &c,
            &gpu,
            &center,
        );
    }
    let frames = PathBuf::from(std::env::var(VULKAN_FRAMES).expect("set by the outer test"));
    for (i, (label, scene)) in shadowed_scenes().into_iter().enumerate() {
        let (gl, _) = renderer
            .render(&scene)
            .unwrap_or_else(|e| panic!("{label}: GL render failed: {e}"));
        let bytes = std::fs::read(frames.join(format!("frame-{i}.f32"))).unwrap();
        let mut vulkan = gl.clone();
        for (pixel, rgb) in vulkan.radiance.iter_mut().zip(bytes.chunks_exact(12)) {
            for (v, b) in pixel.iter_mut().zip(rgb.chunks_exact(4)) {
                *v = f32::from_le_bytes(b.try_into().unwrap());
            }
        }
        let jitter = [
            vulkan.clone(),
            vulkan.clone(),
            vulkan.clone(),
            vulkan.clone(),
        ];
        let c = gonio::output::compare::compare_with_jitter(
            &gl,
            &vulkan,
            &jitter,
            common::tolerance(&scene, &vulkan),
        );
        eprintln!("GL vs Vulkan {label:<30} | {}", c.summary());
        common::assert_agrees(
            &format!("gl shadows {label}"),
            "GL and Vulkan shadows disagree",
            &c,
            &gl,
            &vulkan,
        );
    }
}
