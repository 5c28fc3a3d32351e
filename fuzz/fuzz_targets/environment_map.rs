//! Fuzzes the environment-map loader (Radiance `.hdr` and OpenEXR, chosen
//! by the first byte) and the look-up of a map it accepts.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::environment_map(data));
