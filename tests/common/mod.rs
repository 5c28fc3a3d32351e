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

/// The gonio binary built for this test run.
pub fn gonio() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_gonio"))
}
