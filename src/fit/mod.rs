//! `gonio fit`: fitting the lecture's models (and the modern ones) to a
//! measured BRDF, the lecture's "BRDF modeling: fitting of parameterized
//! BRDF models to measured data", and ranking them over the 100 MERL
//! materials.
//!
//! The data flow: a measured material's [`samples`] (a fixed grid over
//! MERL's half/difference angles), a [`metric`], a model with its free
//! numbers and bounds ([`models`]), the search ([`problem`]: Nelder-Mead
//! from several starts; its inner loop, the model at every sample, is
//! [`terms`]), and for `--all` the [`report`] (shards, merge,
//! ranking). The command line is [`cli`].

pub mod cli;
pub mod linear;
pub mod metric;
pub mod models;
pub mod problem;
pub mod published;
pub mod report;
pub mod samples;
pub mod terms;
pub mod text_numbers;

pub use metric::Metric;
pub use models::FitModel;
pub use problem::{FitResult, fit};
