//! The side panel's sections: material, environment, view (the lights':
//! [`super::lights`]). Each edits a copy
//! and hands back what changed; the caller validates and applies it, so a
//! value the renderer rejects becomes a message, never a crash.

mod compare;
mod environment;
pub mod material;
pub mod widgets;

pub use compare::{Request as CompareRequest, compare_editor};
pub use environment::environment_editor;
pub use material::material_editor;
pub use widgets::{radiance, shading_mode};
