//! The side panel's sections: material, view (the lights', the
//! environment's and compare mode's are in [`super::lights`],
//! [`super::environment`] and [`super::compare`]). Each edits a copy
//! and hands back what changed; the caller validates and applies it, so a
//! value the renderer rejects becomes a message, never a crash.

pub mod material;
pub mod widgets;

pub use material::material_editor;
pub use widgets::{radiance, shading_mode};
