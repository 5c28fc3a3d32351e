//! The environment's sheen stack: the map averaged by the Charlie sheen
//! lobe seen along the normal ([`sheen_normal_view_ln_weight`], a zonal
//! kernel), which `environment.specular = "prefiltered"` reads at the
//! normal for a sheen's split-sum radiance (the reference's
//! `environment::prefiltered_layers`, the GPU's
//! `environment_prefiltered_gltf`). Here because the kernel is the
//! material's and the stack the environment's, and neither knows the
//! other.

use crate::environment::EnvironmentMap;
use crate::environment::prefiltered_zonal::{ZonalKernel, ZonalStack};
use crate::material::brdf::gltf_layers::sheen::sheen_normal_view_ln_weight;
use std::sync::Arc;

/// The sheen's kernel.
pub const SHEEN_KERNEL: ZonalKernel = ZonalKernel {
    name: "sheen",
    ln_weight: sheen_normal_view_ln_weight,
};

/// The sheen stack of `map` (made on first use, then shared).
pub fn sheen_stack(map: &EnvironmentMap) -> Arc<ZonalStack> {
    map.data.zonal_stack(&SHEEN_KERNEL)
}
