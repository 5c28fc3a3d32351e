//! Fuzzes the WebP texture decoder (`EXT_texture_webp`); see `harness::webp_texture`.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::webp_texture(data));
