//! Fuzzes the KTX2 / Basis Universal texture transcoder (`KHR_texture_basisu`); see `harness::ktx2_texture`.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::ktx2_texture(data));
