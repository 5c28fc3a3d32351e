//! What happens to a rendered frame: written to PNG or EXR (atomically),
//! compared with another frame, or left behind beside a failed test.

pub mod atomic;
pub mod compare;
pub mod failure;
pub mod interrupt;
pub mod legend;
pub mod plot;
pub mod progress;
pub mod srgb8;
pub mod tone_map;
pub mod write;

pub use atomic::{AtomicFile, commit_all};
pub use compare::{Comparison, Tolerance, compare_with_jitter};
pub use write::{OutputFile, OutputFormat};
