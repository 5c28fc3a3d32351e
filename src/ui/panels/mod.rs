//! The side panel's sections: material, lights, environment, view. Each edits a copy
//! and hands back what changed; the caller validates and applies it, so a
//! value the renderer rejects becomes a message, never a crash.

mod compare;
mod environment;
mod light;
mod light_list;
pub mod material;
mod widgets;

pub use compare::{Request as CompareRequest, compare_editor};
pub use environment::environment_editor;
pub use light::light_editor;
pub use light_list::{LightAction, light_list};
pub use material::material_editor;
pub use widgets::{radiance, shading_mode};
