//! Fuzzes meshopt buffer-view decoding (`EXT_/KHR_meshopt_compression`) through the glTF loader; see `harness::meshopt_buffer`.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::meshopt_buffer(data));
