//! The side panel's sections: material, view (the lights' and the
//! environment's are in [`super::lights`] and [`super::environment`]). Each edits a copy
//! and hands back what changed; the caller validates and applies it, so a
//! value the renderer rejects becomes a message, never a crash.

mod compare;
pub mod material;
pub mod widgets;

pub use compare::{Request as CompareRequest, compare_editor};
pub use material::material_editor;
pub use widgets::{radiance, shading_mode};
