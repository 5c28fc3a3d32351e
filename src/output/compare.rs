//! GPU-vs-reference image comparison with a derived per-pixel tolerance.
//!
//! The GPU and the CPU reference compute the same function, but not at
//! exactly the same point: the rasterizer snaps vertices to a sub-pixel
//! grid (lavapipe: 1/256 px) and interpolates in `f32`, so the GPU sees
//! the surface at a point displaced by up to δ from the pixel centre, and
//! then evaluates the shading in `f32`. The tolerance therefore has two
//! parts, both derived rather than guessed:
//!
//! * **geometric**: the reference renders four extra frames with the sample
//!   point moved by ±δ in x and in y. With `D_x = max |L(±δ,0) − L(0)|` and
//!   `D_y` likewise, a displacement of at most δ per axis changes the
//!   radiance by at most about `D_x + D_y` (first order). This is large
//!   exactly where the image changes fast (highlights, triangle edges in
//!   flat shading) and zero where it is constant.
//! * **arithmetic**: `rel · |L| + abs`, from `f32` rounding of the shading
//!   formula (see [`Tolerance`]).
//!
//! Pixels where the five reference samples disagree on coverage lie on a
//! silhouette and are not compared; everywhere else the coverage must
//! match exactly.

use crate::frame::Frame;

/// The arithmetic part of the tolerance: `rel · |L| + abs` per channel.
#[derive(Clone, Copy, Debug)]
pub struct Tolerance {
    pub rel: f64,
    pub abs: f64,
}

/// Order of the jittered reference frames [`compare_with_jitter`] expects.
pub const JITTER_OFFSETS: [(f64, f64); 4] = [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)];

/// What a comparison found.
#[derive(Clone, Debug, Default)]
pub struct Comparison {
    /// Covered pixels compared channel by channel.
    pub compared: usize,
    /// Pixels skipped because the reference's samples straddle a silhouette.
    pub silhouette: usize,
    /// Pixels off the silhouette whose coverage differs.
    pub coverage_mismatches: usize,
    /// Compared pixels with a channel outside its tolerance.
    pub failing: usize,
    /// Largest |GPU − reference| over compared pixels and channels.
    pub max_abs_error: f64,
    /// Mean |GPU − reference| over compared pixels and channels.
    pub mean_abs_error: f64,
    /// Largest error as a fraction of the pixel's tolerance (≤ 1 passes).
    pub max_error_over_tolerance: f64,
    /// The pixel with the largest error/tolerance: (row, column, gpu, reference, tolerance).
    pub worst: Option<(u32, u32, f64, f64, f64)>,
}

impl Comparison {
    /// True when nothing failed.
    pub fn passed(&self) -> bool {
        self.failing == 0 && self.coverage_mismatches == 0
    }

    /// A one-paragraph summary.
    pub fn summary(&self) -> String {
        let worst = match self.worst {
            Some((i, j, g, r, t)) => format!(
                "; worst pixel (row {i}, col {j}): GPU {g:.6e}, reference {r:.6e}, tolerance {t:.3e}"
            ),
            None => String::new(),
        };
        format!(
            "{} pixels compared, {} on silhouettes skipped, {} coverage mismatches, {} failing; max |error| {:.3e}, mean {:.3e}, max error/tolerance {:.3}{worst}",
            self.compared,
            self.silhouette,
            self.coverage_mismatches,
            self.failing,
            self.max_abs_error,
            self.mean_abs_error,
            self.max_error_over_tolerance
        )
    }
}

/// Compares `gpu` with the reference `center` (sampled at pixel centres)
/// using `jittered`, the reference sampled at the centre plus
/// [`JITTER_OFFSETS`] × δ, for the geometric tolerance.
pub fn compare_with_jitter(
    gpu: &Frame,
    center: &Frame,
    jittered: &[Frame; 4],
    tolerance: Tolerance,
) -> Comparison {
    compare_with_spreads(
        gpu,
        center,
        &[(&jittered[0], &jittered[1]), (&jittered[2], &jittered[3])],
        tolerance,
    )
}

/// [`compare_with_jitter`] with any pairs of perturbed reference frames:
/// each pair adds its spread `max(|L₊ − L|, |L₋ − L|)` to a pixel's
/// tolerance (the jitter along x and along y are two pairs; a texture's
/// level of detail moved both ways is another, tests/textures.rs).
pub fn compare_with_spreads(
    gpu: &Frame,
    center: &Frame,
    pairs: &[(&Frame, &Frame)],
    tolerance: Tolerance,
) -> Comparison {
    assert_eq!((gpu.width, gpu.height), (center.width, center.height));
    let mut c = Comparison::default();
    let mut sum = 0.0;
    for k in 0..center.len() {
        let covered = center.coverage[k];
        if pairs
            .iter()
            .any(|(a, b)| a.coverage[k] != covered || b.coverage[k] != covered)
        {
            c.silhouette += 1;
            continue;
        }
        if gpu.coverage[k] != covered {
            c.coverage_mismatches += 1;
            continue;
        }
        if !covered {
            continue;
        }
        c.compared += 1;
        let mut pixel_failed = false;
        for ch in 0..3 {
            let reference = center.radiance[k][ch] as f64;
            let value = gpu.radiance[k][ch] as f64;
            let spread = |a: &Frame, b: &Frame| {
                ((a.radiance[k][ch] as f64 - reference).abs())
                    .max((b.radiance[k][ch] as f64 - reference).abs())
            };
            let geometric: f64 = pairs.iter().map(|(a, b)| spread(a, b)).sum();
            let tol = geometric + tolerance.rel * reference.abs() + tolerance.abs;
            let err = (value - reference).abs();
            // A NaN on either side fails.
            let ratio = if err.is_nan() {
                f64::INFINITY
            } else {
                err / tol
            };
            sum += err;
            c.max_abs_error = c.max_abs_error.max(err);
            if ratio > c.max_error_over_tolerance || c.worst.is_none() {
                c.max_error_over_tolerance = c.max_error_over_tolerance.max(ratio);
                let (i, j) = (k as u32 / center.width, k as u32 % center.width);
                c.worst = Some((i, j, value, reference, tol));
            }
            pixel_failed |= ratio > 1.0;
        }
        c.failing += pixel_failed as usize;
    }
    c.mean_abs_error = if c.compared > 0 {
        sum / (3 * c.compared) as f64
    } else {
        0.0
    };
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_frame(v: f32) -> Frame {
        let mut f = Frame::new(4, 4);
        f.radiance.fill([v; 3]);
        f.coverage.fill(true);
        f
    }

    #[test]
    fn identical_frames_pass_and_a_big_error_fails() {
        let reference = flat_frame(0.5);
        let jitter = [
            reference.clone(),
            reference.clone(),
            reference.clone(),
            reference.clone(),
        ];
        let tol = Tolerance {
            rel: 1e-4,
            abs: 1e-6,
        };
        assert!(compare_with_jitter(&reference, &reference, &jitter, tol).passed());
        let mut gpu = reference.clone();
        gpu.radiance[5][1] = 0.51;
        let c = compare_with_jitter(&gpu, &reference, &jitter, tol);
        assert_eq!(c.failing, 1);
        assert_eq!(c.worst.unwrap().0, 1);
    }

    #[test]
    fn jitter_widens_the_tolerance_where_the_image_changes() {
        let reference = flat_frame(0.5);
        let mut right = reference.clone();
        right.radiance[5] = [0.6; 3];
        let jitter = [
            right,
            reference.clone(),
            reference.clone(),
            reference.clone(),
        ];
        let mut gpu = reference.clone();
        gpu.radiance[5] = [0.58; 3];
        let c = compare_with_jitter(
            &gpu,
            &reference,
            &jitter,
            Tolerance {
                rel: 0.0,
                abs: 1e-6,
            },
        );
        assert!(c.passed(), "{}", c.summary());
    }

    #[test]
    fn silhouettes_are_skipped_and_interior_coverage_must_match() {
        let reference = flat_frame(0.5);
        let mut edge = reference.clone();
        edge.coverage[0] = false;
        let jitter = [
            edge,
            reference.clone(),
            reference.clone(),
            reference.clone(),
        ];
        let mut gpu = reference.clone();
        gpu.coverage[0] = false;
        gpu.coverage[7] = false;
        let c = compare_with_jitter(
            &gpu,
            &reference,
            &jitter,
            Tolerance {
                rel: 0.0,
                abs: 1e-6,
            },
        );
        assert_eq!(c.silhouette, 1);
        assert_eq!(c.coverage_mismatches, 1);
    }
}
