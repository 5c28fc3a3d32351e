//! The ground floor: small value types every other module builds on
//! (colours, the shading frame). Nothing here imports anything of gonio's.

pub mod color;
pub mod frame;

pub use color::{ColorValue, Rgb};
pub use frame::{SurfaceFrame, any_tangent};
