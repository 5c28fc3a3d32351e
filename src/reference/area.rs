//! How far N point lights are from the area light they stand for.
//!
//! The "exact" image of a scene's area lights is, where it applies,
//! analytic: for Lambertian receivers (`f_r` constant over the light) and
//! no shadows from the area lights, `L_o = f_r · E` with `E` from Lambert's
//! polygon formula ([`crate::scene::AreaLight::exact_irradiance`]).
//! Otherwise it is the reference with [`EXACT_SAMPLES`] samples per area
//! light (a 64 × 64 grid, one shadow ray each), whose own error is far
//! below that of the sample counts a GPU uses.

use super::renderer::{AreaLights, render_with};
use crate::frame::Frame;
use crate::material::ReflectanceModel;
use crate::scene::Scene;

/// Samples per area light of the numerical "exact" render.
pub const EXACT_SAMPLES: u32 = 64 * 64;

/// Error of one sample count against the exact image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaError {
    /// N, samples per area light.
    pub samples: u32,
    /// `sqrt(Σ (L − L_exact)² / Σ L_exact²)` over covered pixels and
    /// channels.
    pub rel_rms: f64,
    /// `max |L − L_exact|` over the largest exact value.
    pub max_rel: f64,
}

/// Whether [`render_exact`] is analytic for `scene`: every mesh is
/// Lambertian and no area light casts shadows.
pub fn exact_is_analytic(scene: &Scene) -> bool {
    scene
        .meshes
        .iter()
        .all(|m| scene.materials[m.material].model == ReflectanceModel::Lambert)
        && scene.area_lights.iter().all(|a| !a.shadows)
}

/// The scene with its area lights rendered exactly (see the module docs).
pub fn render_exact(scene: &Scene) -> Frame {
    if exact_is_analytic(scene) {
        render_with(scene, 0.0, 0.0, AreaLights::ExactUnoccluded)
    } else {
        render_with(
            &scene.with_area_samples(EXACT_SAMPLES),
            0.0,
            0.0,
            AreaLights::Samples,
        )
    }
}

/// Relative RMS and max error of `frame` against `exact` (see
/// [`AreaError`]); pixels either frame leaves uncovered are skipped.
pub fn frame_error(frame: &Frame, exact: &Frame) -> (f64, f64) {
    let (mut num, mut den, mut max_err, mut max_val) = (0.0, 0.0, 0.0f64, 0.0f64);
    for k in 0..exact.len() {
        if !(frame.coverage[k] && exact.coverage[k]) {
            continue;
        }
        for ch in 0..3 {
            let (a, e) = (frame.radiance[k][ch] as f64, exact.radiance[k][ch] as f64);
            num += (a - e) * (a - e);
            den += e * e;
            max_err = max_err.max((a - e).abs());
            max_val = max_val.max(e.abs());
        }
    }
    let ratio = |n: f64, d: f64| if d > 0.0 { n / d } else { 0.0 };
    (ratio(num, den).sqrt(), ratio(max_err, max_val))
}

/// The reference's error for each N in `samples` (every area light of the
/// scene rendered with N point lights) against the exact image: the
/// error-vs-N table of `docs/shadows.md`.
pub fn error_vs_samples(scene: &Scene, samples: &[u32]) -> Vec<AreaError> {
    let exact = render_exact(scene);
    samples
        .iter()
        .map(|&n| {
            let frame = render_with(&scene.with_area_samples(n), 0.0, 0.0, AreaLights::Samples);
            let (rel_rms, max_rel) = frame_error(&frame, &exact);
            AreaError {
                samples: n,
                rel_rms,
                max_rel,
            }
        })
        .collect()
}
