//! Batch work split over processes and machines: every piece is a pure
//! function of (inputs, shard), so any scheduler runs it unchanged
//! (docs/cluster.md).
//!
//! [`shard`] says which piece this process runs (`--shard I/N`, or
//! `--shard auto` from Slurm, Kubernetes or HyperQueue variables);
//! [`partial`] writes and reads one shard of a reference render (an EXR
//! whose header names the shard, the image and a key of the inputs);
//! [`merge`] checks a set of them and joins it into the whole image;
//! [`render`] is `gonio render --reference --shard`.

pub mod merge;
pub mod partial;
pub mod render;
pub mod shard;

pub use shard::Shard;
