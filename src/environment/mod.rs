//! Light from everywhere: an environment map (a latitude-longitude image
//! of radiance arriving from infinitely far away), what the renderers
//! derive from it, and the built-in sky and studio.
//!
//! * [`latlong`]: the contract's direction convention (`[environment]` in
//!   `shared/spec/conventions.md`), the one place it is written in Rust;
//!   its WGSL twin is `shaders/environment.wgsl`.
//! * [`map`]: the texels, their bilinear lookup, validation.
//! * [`load`]: reading `.exr` and Radiance `.hdr` files.
//! * [`sky`]: the procedural sky (`map = "sky"`), a generated map.
//! * [`studio`]: the neutral studio (`map = "studio"`), the light of a
//!   glTF file that brings none.
//! * [`test_maps`]: maps gonio makes for its tests (the shipped
//!   `assets/environment/blobs.hdr` among them).
//! * [`sh`]: spherical harmonics: projection of a map, the irradiance
//!   convolution of Ramamoorthi & Hanrahan (2001), evaluation.
//! * [`sampled`]: the whole BRDF integrated with N directions (cosine and
//!   BRDF lobe, [`lobe`], by multiple importance sampling)
//!   (`environment.specular = "sampled"`) and its quadrature truth.
//! * [`prefiltered`]: glossy reflection by the split-sum approximation
//!   (`environment.specular = "prefiltered"`), with the environment BRDF
//!   table of [`dfg`].
//! * [`sh_phong`]: the lecture's Phong lobes by SH convolution, a zonal
//!   product (`environment.specular = "sh"`, Ramamoorthi & Hanrahan 2002).
//! * [`mode_warnings`]: what the `"sh"` and `"prefiltered"` modes leave
//!   out for a scene's models, said at load time.
//! * [`sh_error`]: SH irradiance error vs order against the truth.
//! * [`visibility`]: the reference's environment term with ray-traced
//!   occlusion (`environment.visibility`).
//! * [`quadrature`]: the integrated truth `E(n) = ∫ L(ω) max(0, n·ω) dω`
//!   the reference uses and SH is measured against.

pub mod dfg;
mod exr_header;
pub mod latlong;
pub mod load;
pub mod lobe;
pub mod map;
pub mod mode_warnings;
pub mod prefiltered;
pub mod quadrature;
pub mod sampled;
pub mod sh;
pub mod sh_error;
pub mod sh_phong;
pub mod sky;
pub mod studio;
pub mod test_maps;
pub mod visibility;

pub use map::{EnvironmentMap, MapSettings};
