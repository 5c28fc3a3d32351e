//! Light through surfaces in the reference (contract: "Light through
//! surfaces"; docs/transmission.md): rays through thin-walled transmissive
//! surfaces, refracted through volumes with Beer–Lambert attenuation and
//! dispersion per wavelength, deterministic.
//!
//! * [`path`]: the paths through surfaces and volumes ([`path::through`]);
//! * [`thin`]: the directions a thin wall is looked through, and weights;
//! * [`visible_normals`]: the deterministic microfacet normals its lobe
//!   is sampled at;
//! * [`interface`]: media, their indices per wavelength, Beer–Lambert;
//! * [`spectrum`]: the wavelengths of a dispersive path and their RGB.

pub mod interface;
pub mod path;
pub mod spectrum;
pub mod thin;
pub mod visible_normals;

pub use path::{Crossing, Scenery, Traced, through};
