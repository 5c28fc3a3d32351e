//! Fuzzes the scene `.toml` loader (parse, `--set` overrides, validation,
//! and the glTF files a scene names) with arbitrary file contents.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::scene_toml(data));
