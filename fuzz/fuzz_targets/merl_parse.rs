//! Fuzzes the MERL `.binary` reader (and the look-up of a table it accepts).
#![no_main]

#[path = "harness.rs"]
mod harness;

libfuzzer_sys::fuzz_target!(|data: &[u8]| harness::merl_parse(data));
