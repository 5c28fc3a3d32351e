//! Fuzzes the PNG/JPEG texture decoder and the mip chain builder.
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::texture_decode(data));
