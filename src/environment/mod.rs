//! Light from everywhere: an environment map (a latitude-longitude image
//! of radiance arriving from infinitely far away), its projections (SH,
//! the prefiltered stack, the quadrature) and the built-in sky and studio. Nothing
//! here knows a material or a scene (it depends on `base` only): the
//! per-pixel estimators that take a material are the reference's
//! (`crate::reference::environment`), the environment BRDF table is the
//! BRDFs' (`crate::material::brdf::dfg`), and the GPU's side is
//! `crate::gpu::environment`.
//!
//! * [`latlong`]: the contract's direction convention (`[environment]` in
//!   `shared/spec/conventions.md`), the one place it is written in Rust;
//!   its WGSL twin is `shaders/environment.wgsl`.
//! * [`map`]: the texels, their bilinear lookup, validation, the
//!   `[environment]` settings.
//! * [`load`]: reading `.exr` and Radiance `.hdr` files (`exr_header`:
//!   an EXR's size checked before decoding).
//! * [`sky`]: the procedural sky (`map = "sky"`), a generated map.
//! * [`studio`]: the neutral studio (`map = "studio"`), the light of a
//!   glTF file that brings none.
//! * [`test_maps`]: maps gonio makes for its tests (the shipped
//!   `assets/environment/blobs.hdr` among them).
//! * [`sh`]: spherical harmonics: projection of a map, the irradiance
//!   convolution of Ramamoorthi & Hanrahan (2001), evaluation.
//! * [`prefiltered`]: the radiance stack of the split-sum approximation
//!   (`environment.specular = "prefiltered"`).
//! * [`prefiltered_zonal`]: a stack averaged by a zonal kernel the caller
//!   gives (the sheen's, in the same mode).
//! * [`sh_phong`]: the lecture's Phong lobes by SH convolution, a zonal
//!   product (`environment.specular = "sh"`, Ramamoorthi & Hanrahan 2002).
//! * [`sh_error`]: SH irradiance error vs order against the truth.
//! * [`importance`]: the map's texels as a distribution of directions,
//!   the sampled mode's third strategy (a sun found by few samples).
//! * [`visibility`]: the part of the map's quadrature the geometry
//!   blocks, for the reference's `environment.visibility`.
//! * [`quadrature`]: the integrated truth `E(n) = ∫ L(ω) max(0, n·ω) dω`
//!   the reference uses and SH is measured against.

mod exr_header;
pub mod importance;
pub mod latlong;
pub mod load;
pub mod map;
pub mod prefiltered;
pub mod prefiltered_zonal;
pub mod quadrature;
pub mod sh;
pub mod sh_error;
pub mod sh_phong;
pub mod sky;
pub mod studio;
pub mod test_maps;
pub mod visibility;

pub use map::{EnvironmentMap, MapSettings};
