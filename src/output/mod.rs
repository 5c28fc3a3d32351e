//! What happens to a rendered frame: written to PNG or EXR (atomically), or
//! compared with another frame.

pub mod compare;
pub mod write;

pub use compare::{Comparison, Tolerance, compare_with_jitter};
pub use write::{AtomicFile, OutputFile, OutputFormat};
