//! The one range rule for every source of radiance and reflectance.
//!
//! The GPU computes in f32 (largest 3.4e38). A value that is finite in f64
//! but beyond what f32 products can hold gives Inf or NaN pixels where the
//! f64 reference stays finite (`lights.0.intensity = 3.5e38`,
//! `environment.scale = 1e39`, an RGBE exponent of 255, an EXR of
//! 3e38 texels, a MERL table of 1e300). So every source is refused, with
//! its key or file, when it is not finite, is negative, or exceeds:
//! - [`MAX_RADIANCE`] for radiance, intensity and irradiance: light
//!   intensities, ambient and gradient radiance, environment-map texels
//!   and the texels times `environment.scale`;
//! - [`MAX_REFLECTANCE`] for a tabulated `f_r` (MERL tables).
//!
//! Their product, 1e37, stays a factor of 34 below f32's largest value,
//! which leaves room for the cosines, solid angles and sums of a shading
//! step. Refused rather than clamped: a clamp would change the picture
//! without a word.

/// Largest radiance, intensity or irradiance component: the GPU
/// multiplies it in f32 by a BRDF value (the lecture's forms reach about
/// 4e16, shaders/brdf/phong.wgsl) and a cosine, which must stay below
/// f32's 3.4e38; 1e20 leaves a factor of 200.
pub const MAX_RADIANCE: f64 = 1e20;

/// Largest tabulated BRDF value `f_r` [1/sr] (MERL's measured peaks are
/// below 1e4): times [`MAX_RADIANCE`] it stays below f32's range.
pub const MAX_REFLECTANCE: f64 = 1e17;

/// Whether `v` is a radiance gonio computes with: finite, ≥ 0, at most
/// [`MAX_RADIANCE`].
pub fn is_radiance(v: f64) -> bool {
    v.is_finite() && (0.0..=MAX_RADIANCE).contains(&v)
}

/// Whether `v` is a tabulated `f_r` gonio computes with: finite, ≥ 0, at
/// most [`MAX_REFLECTANCE`].
pub fn is_reflectance(v: f64) -> bool {
    v.is_finite() && (0.0..=MAX_REFLECTANCE).contains(&v)
}
