//! Fuzzes the glTF/GLB loader with arbitrary file contents. Relative
//! buffer URIs resolve in a scratch folder (see `harness::workspace`).
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::gltf_load(data));
