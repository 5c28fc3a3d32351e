//! The ground floor: small value types every other module builds on
//! (colours, the shading frame, closed sets of names). Nothing here imports anything of gonio's.

pub mod color;
pub mod frame;
pub mod input;
pub mod named;
pub mod quiet_panic;
pub mod range;

pub use color::{ColorValue, Rgb, rgb_to_toml};
pub use frame::{SurfaceFrame, any_tangent};
pub(crate) use named::named_enum;
pub use named::{did_you_mean, nearest_name};
