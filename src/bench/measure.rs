//! Timing and error of one configuration.
//!
//! **Time** is the GPU time of a frame: the renderer's timestamp queries
//! around the shadow passes and the scene pass, summed ("render pass" and
//! "shadow passes (N layers)" in its [`Timings`]). Without timestamp
//! queries it is the wall time of the renderer's "render pass + readback"
//! step. Frames are repeated after warm-up (the first render also compiles
//! the pipeline) and summarized by median and interquartile range, which
//! shrug off the outliers a shared machine produces.
//!
//! **Error** is the relative RMS difference of the frame's radiance from
//! the truth image, `sqrt(Σ (L − L_truth)² / Σ L_truth²)` over the pixels
//! and channels covered in both (the same measure as the area-light
//! study, [`crate::reference::area::frame_error`]). A frame of another
//! resolution is resampled to the truth's grid first ([`resample`]).

use crate::frame::Frame;
use crate::gpu::timing::{Clock, Timings};
use crate::reference;
use crate::scene::Scene;

/// Median and quartiles of a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    pub median: f64,
    pub q1: f64,
    pub q3: f64,
    pub n: usize,
}

impl Stats {
    /// Median and quartiles (linear interpolation between order
    /// statistics) of `values`; all zero for an empty sample.
    pub fn of(values: &[f64]) -> Stats {
        if values.is_empty() {
            return Stats::default();
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let q = |p: f64| {
            let x = p * (v.len() - 1) as f64;
            let (lo, hi) = (x.floor() as usize, x.ceil() as usize);
            v[lo] + (v[hi] - v[lo]) * (x - lo as f64)
        };
        Stats {
            median: q(0.5),
            q1: q(0.25),
            q3: q(0.75),
            n: v.len(),
        }
    }

    /// Interquartile range relative to the median: the spread.
    pub fn relative_iqr(&self) -> f64 {
        if self.median > 0.0 {
            (self.q3 - self.q1) / self.median
        } else {
            0.0
        }
    }
}

/// The GPU time of one frame in milliseconds from the renderer's timings
/// (see the module docs), and how it was measured.
pub fn frame_ms(timings: &Timings) -> (f64, Clock) {
    let gpu: Vec<f64> = timings
        .entries
        .iter()
        .filter(|(name, _, clock)| {
            *clock == Clock::GpuTimestamp
                && (name == "render pass" || name.starts_with("shadow passes"))
        })
        .map(|(_, d, _)| d.as_secs_f64() * 1e3)
        .collect();
    if !gpu.is_empty() {
        return (gpu.iter().sum(), Clock::GpuTimestamp);
    }
    let wall = timings
        .entries
        .iter()
        .find(|(name, ..)| name == "render pass + readback")
        .map(|(_, d, _)| d.as_secs_f64() * 1e3)
        .unwrap_or(f64::NAN);
    (wall, Clock::Wall)
}

/// The scene pass alone (no shadow passes), in milliseconds.
pub fn render_pass_ms(timings: &Timings) -> f64 {
    timings
        .entries
        .iter()
        .find(|(name, _, clock)| name == "render pass" && *clock == Clock::GpuTimestamp)
        .or_else(|| {
            timings
                .entries
                .iter()
                .find(|(name, ..)| name == "render pass + readback")
        })
        .map(|(_, d, _)| d.as_secs_f64() * 1e3)
        .unwrap_or(f64::NAN)
}

/// The truth image of `base`: the CPU reference (f64, ray-traced shadows)
/// with per-pixel shading and every area light at `area_samples` samples;
/// an environment map lights through the whole BRDF, integrated by the
/// map's texel quadrature (`reference::environment::sampled::integrated`), whatever
/// `environment.specular` the GPU uses.
pub fn truth(base: &Scene, area_samples: u32) -> Frame {
    let mut scene = base.with_area_samples(area_samples);
    scene.shading = crate::scene::ShadingMode::Phong;
    if let Some(map) = &mut scene.environment.map {
        map.settings.specular = crate::environment::map::Specular::Sampled;
        map.settings.reference = crate::environment::map::ReferenceDiffuse::Integrated;
    }
    reference::render(&scene)
}

/// `frame` on the grid of a `width`×`height` frame covering the same view:
/// each target pixel averages the covered source pixels whose centres fall
/// inside it (a box filter when the source is finer) or takes the source
/// pixel under its centre (when the source is coarser); it is covered when
/// at least half of the source pixels it averages are.
pub fn resample(frame: &Frame, width: u32, height: u32) -> Frame {
    if frame.width == width && frame.height == height {
        return frame.clone();
    }
    let mut out = Frame::new(width, height);
    let (sx, sy) = (
        frame.width as f64 / width as f64,
        frame.height as f64 / height as f64,
    );
    for i in 0..height {
        for j in 0..width {
            // Source pixels whose centres lie in [j, j+1) × [i, i+1) of the target.
            let range = |t: u32, s: f64, n: u32| {
                let lo = ((t as f64 * s - 0.5).ceil().max(0.0)) as u32;
                let hi = (((t + 1) as f64 * s - 0.5).ceil().max(0.0) as u32).min(n);
                if lo < hi {
                    lo..hi
                } else {
                    let c = (((t as f64 + 0.5) * s) as u32).min(n - 1);
                    c..c + 1
                }
            };
            let (rows, cols) = (range(i, sy, frame.height), range(j, sx, frame.width));
            let (mut sum, mut covered, mut count) = ([0.0f64; 3], 0usize, 0usize);
            for r in rows {
                for c in cols.clone() {
                    let k = frame.index(r, c);
                    count += 1;
                    if frame.coverage[k] {
                        covered += 1;
                        for (s, v) in sum.iter_mut().zip(frame.radiance[k]) {
                            *s += v as f64;
                        }
                    }
                }
            }
            let k = out.index(i, j);
            if covered > 0 && 2 * covered >= count {
                out.coverage[k] = true;
                out.radiance[k] = sum.map(|s| (s / covered as f64) as f32);
            }
        }
    }
    out
}

/// Relative RMS and relative max error of `frame` against `truth` (see the
/// module docs); `frame` may have another resolution.
pub fn error(frame: &Frame, truth: &Frame) -> (f64, f64) {
    let on_grid = resample(frame, truth.width, truth.height);
    reference::area::frame_error(&on_grid, truth)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_a_known_sample() {
        let s = Stats::of(&[5.0, 1.0, 3.0, 2.0, 4.0]);
        assert_eq!((s.median, s.q1, s.q3, s.n), (3.0, 2.0, 4.0, 5));
        assert!((s.relative_iqr() - 2.0 / 3.0).abs() < 1e-12);
        assert_eq!(Stats::of(&[2.0, 4.0]).median, 3.0);
        assert_eq!(Stats::of(&[]).n, 0);
    }

    #[test]
    fn resample_box_filters_and_replicates() {
        let mut fine = Frame::new(4, 2);
        for k in 0..fine.len() {
            fine.radiance[k] = [k as f32; 3];
            fine.coverage[k] = true;
        }
        let coarse = resample(&fine, 2, 1);
        // Pixels 0,1,4,5 → 2.5; 2,3,6,7 → 4.5.
        assert_eq!(coarse.radiance, vec![[2.5; 3], [4.5; 3]]);
        let back = resample(&coarse, 4, 2);
        assert_eq!(back.radiance[0], [2.5; 3]);
        assert_eq!(back.radiance[7], [4.5; 3]);
        assert!(back.coverage.iter().all(|&c| c));
        // Identical frames have no error; a uniformly 10% brighter one 0.1.
        assert_eq!(error(&fine, &fine).0, 0.0);
        let mut brighter = fine.clone();
        for r in &mut brighter.radiance {
            *r = r.map(|v| v * 1.1);
        }
        assert!((error(&brighter, &fine).0 - 0.1).abs() < 1e-6);
    }
}
