//! The CPU reference renderer: ray casting in `f64`, one primary ray per
//! pixel sample, shaded exactly as the GPU shades (same shading points,
//! normals, interpolation and clip planes), so the two frames can be
//! compared pixel by pixel.
//!
//! [`brdf`] is the BRDF it evaluates for a material (a spectral metal's
//! Fresnel from its spectral table, where the GPU has three channels);
//! [`crate::scene::bvh`] finds what a ray hits (and whether a shadow ray
//! is blocked); [`renderer`] turns hits into a [`crate::frame::Frame`],
//! each hit shaded by the reflection equation of [`shading`] (the
//! environment's part by the estimators of [`environment`]); [`texture`]
//! samples the material textures; [`area`] measures the error of
//! rendering an area light by N point lights; [`spectral`] measures the
//! three-channel thin film and conductors against their spectral truth;
//! [`transmission`] follows light through transmissive surfaces and
//! volumes (refraction, attenuation, dispersion).

pub mod area;
pub mod brdf;
pub mod environment;
pub mod renderer;
pub mod shading;
pub mod spectral;
pub mod texture;
pub mod transmission;

pub use renderer::{
    AreaLights, memory_estimate, refracted_path, render, render_offset, render_reporting,
    render_rows, render_with, render_with_lod_bias, shadow_epsilon, visibility,
};
