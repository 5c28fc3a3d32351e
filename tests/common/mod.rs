//! Helpers shared by the integration tests.
#![allow(dead_code)]

use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use std::path::PathBuf;

/// A GPU renderer on the default adapter (lavapipe in CI). Tests never skip:
/// without an adapter they fail, and the message says how to install one.
pub fn gpu_renderer() -> GpuRenderer {
    match GpuContext::new(&AdapterChoice::from_flag_or_env(None)) {
        Ok(ctx) => GpuRenderer::new(ctx),
        Err(e) => panic!("GPU tests need a Vulkan adapter and none could be opened: {e}"),
    }
}

/// The glTF sample models shipped in `assets/gltf`.
pub fn gltf_asset(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/gltf")
        .join(relative)
}

/// Appended to failures of tests that run the binary on the GPU: the
/// binary's own error names the missing adapter; this says what to do.
pub const LAVAPIPE_TEST_HINT: &str = "\n(if no GPU adapter was found: install lavapipe with `sudo apt-get install mesa-vulkan-drivers libvulkan1`, or run ./setup.sh)";

/// The gonio binary built for this test run.
pub fn gonio() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_gonio"))
}

// ---------------------------------------------------------------------
// The derived GPU-vs-reference tolerance (the same derivation as
// tests/gpu_vs_cpu.rs; see its module docs and gonio::output::compare).

use gonio::frame::Frame;
use gonio::material::Material;
use gonio::output::compare::{Comparison, JITTER_OFFSETS, Tolerance, compare_with_jitter};
use gonio::scene::Scene;

/// Sample-point jitter of the geometric tolerance (lavapipe snaps to
/// 1/256 px; see tests/gpu_vs_cpu.rs).
pub const JITTER_PX: f64 = 1.0 / 128.0;
/// f32 unit roundoff, 2⁻²⁴.
pub const EPS: f64 = 1.0 / 16_777_216.0;

/// The arithmetic tolerance for `scene`: the largest over its materials.
pub fn tolerance(scene: &Scene, reference: &Frame) -> Tolerance {
    let rel = scene
        .effective_materials()
        .iter()
        .map(arithmetic_rel)
        .fold(64.0 * EPS, f64::max);
    Tolerance {
        rel,
        abs: 64.0 * EPS * reference.max_radiance() as f64,
    }
}

/// Relative f32 error of one material's shading beyond the light loop's
/// 64ε (derivation: tests/gpu_vs_cpu.rs): its model's row says it.
pub fn arithmetic_rel(m: &Material) -> f64 {
    let compensation = if m.energy_compensation {
        gonio::material::brdf::energy::F32_ERROR
    } else {
        0.0
    };
    (m.model.row().f32_error)(m) + compensation
}

/// The reference frame at the pixel centres and the four jittered ones.
pub fn reference_with_jitter(scene: &Scene) -> (Frame, [Frame; 4]) {
    let center = gonio::reference::render(scene);
    let jittered = JITTER_OFFSETS
        .map(|(dx, dy)| gonio::reference::render_offset(scene, dx * JITTER_PX, dy * JITTER_PX));
    (center, jittered)
}

/// Compares a GPU frame with the reference under the derived tolerance;
/// a scene with textures also gets the spread of the reference with the
/// textures' level of detail moved by ±½, the most Vulkan lets an
/// implementation's λ differ (derivation: tests/textures.rs).
pub fn compare_to_reference(
    scene: &Scene,
    gpu: &Frame,
    center: &Frame,
    jittered: &[Frame; 4],
) -> Comparison {
    if !scene.has_textures() {
        return compare_with_jitter(gpu, center, jittered, tolerance(scene, center));
    }
    let up = gonio::reference::render_with_lod_bias(scene, 0.5);
    let down = gonio::reference::render_with_lod_bias(scene, -0.5);
    gonio::output::compare::compare_with_spreads(
        gpu,
        center,
        &[
            (&jittered[0], &jittered[1]),
            (&jittered[2], &jittered[3]),
            (&up, &down),
        ],
        tolerance(scene, center),
    )
}

/// Where a failing image test leaves its pictures:
/// `target/tmp/image-failures/LABEL/`.
pub fn failure_dir(label: &str) -> PathBuf {
    let safe: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("image-failures")
        .join(safe)
}

/// Asserts that `c` (a comparison of `actual` with `expected`) passed. On
/// failure it first writes the actual frame, the expected one and their
/// difference ([`gonio::output::failure::write_failure_images`]) and names
/// the folder in the panic message.
pub fn assert_agrees(label: &str, what: &str, c: &Comparison, actual: &Frame, expected: &Frame) {
    if c.passed() {
        return;
    }
    let dir = failure_dir(label);
    let saved = match gonio::output::failure::write_failure_images(&dir, actual, expected) {
        Ok(_) => format!(
            "actual, expected and difference images in {}",
            dir.display()
        ),
        Err(e) => format!("(could not save the images: {e})"),
    };
    panic!("{label}: {what}: {}\n{saved}", c.summary());
}
