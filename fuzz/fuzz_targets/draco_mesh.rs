//! Fuzzes Draco decoding (`KHR_draco_mesh_compression`) through the glTF loader; see `harness::draco_mesh`.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::draco_mesh(data));
