//! Lambert: ideal diffuse reflection (lecture: "Diffuse Reflection Model").
//! WGSL twin: `shaders/brdf/lambert.wgsl`.

use crate::base::Rgb;
use std::f64::consts::FRAC_1_PI;

/// `f_r = k_d / π` with `k_d` the albedo. (The lecture's `k_d` is in 1/sr:
/// it is this function's value.) Reciprocal, albedo exactly `k_d`.
pub fn lambert(k_d: Rgb) -> Rgb {
    k_d * FRAC_1_PI
}
