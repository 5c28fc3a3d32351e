//! gonio: a GPU renderer for looking at materials.
//!
//! The data flow reads top to bottom: a [`scene`] is loaded (glTF, scene
//! `.toml` or the built-in default), its [`material`]s and lights decide which
//! shader code exists, the [`gpu`] renders it or the CPU [`reference`](mod@reference) does,
//! and the resulting [`frame::Frame`] is written, compared or measured by
//! [`output`].

pub mod base;
pub mod bench;
pub mod cli;
pub mod cluster;
pub mod environment;
pub mod error;
pub mod explore;
pub mod fit;
pub mod frame;
pub mod gpu;
pub mod material;
pub mod output;
pub mod reference;
pub mod scene;
#[cfg(feature = "viewer")]
pub mod ui;

pub use error::{Error, Result};
