//! The environment's light at a shading point, as the reference computes
//! it: one estimator per `environment.specular` mode, each taking the
//! material and the map (`crate::environment` holds the map and its
//! projections; these take the [`crate::material::Material`] as well).
//!
//! * [`sampled`]: the whole BRDF integrated with N directions (cosine and
//!   BRDF lobe, [`lobe`], by multiple importance sampling)
//!   (`"sampled"`) and its quadrature truth.
//! * [`prefiltered`]: glossy reflection by the split-sum approximation
//!   (`"prefiltered"`), gltf-pbr's layers by [`prefiltered_layers`].
//! * [`sh_phong`]: the lecture's Phong lobes by SH convolution (`"sh"`).
//! * [`diffuse`]: the diffuse albedo SH irradiance lights.

pub mod diffuse;
pub mod dominant;
pub mod lobe;
pub mod prefiltered;
pub mod prefiltered_layers;
pub mod sampled;
pub mod sh_phong;
