//! Light through surfaces in the reference (contract: "Light through
//! surfaces"; docs/transmission.md): rays through thin-walled transmissive
//! surfaces, refracted through volumes with Beer–Lambert attenuation and
//! dispersion per wavelength, deterministic.
//!
//! * [`path`]: the paths through surfaces and volumes ([`path::through`]);
//! * [`thin`]: the directions a thin wall is looked through, and weights;
//! * [`rough_boundary`]: the directions a rough volume boundary refracts
//!   and reflects a path along, and weights;
//! * [`visible_normals`]: the deterministic microfacet normals both
//!   sample;
//! * [`interface`]: media, their indices per wavelength, Beer–Lambert;
//! * [`spectrum`]: the wavelengths of a dispersive path and their RGB.

pub mod interface;
pub mod path;
pub mod rough_boundary;
pub mod spectrum;
pub mod thin;
pub mod visible_normals;

#[cfg(test)]
mod rough_boundary_tests;

pub use path::{Crossing, Scenery, Traced, through};
