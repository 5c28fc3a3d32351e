//! Widgets of the side panel's sections: the material editor (the
//! Material and Compare sections') and small ones the sections share (the
//! sections themselves are [`super::material_section`],
//! [`super::view_section`] and the features' folders). Each edits a copy and hands back what
//! changed; the caller validates and applies it, so a value the renderer
//! rejects becomes a message, never a crash.

pub mod material;
pub mod widgets;

pub use material::material_editor;
pub use widgets::{radiance, shading_mode};
