//! What an image test leaves behind when it fails: the actual frame, the
//! expected one and their difference, side by side in one folder, so a
//! failure can be looked at instead of guessed from a summary line.

use super::write::OutputFile;
use crate::Result;
use crate::frame::Frame;
use std::path::{Path, PathBuf};

/// Writes `actual.exr`, `expected.exr` (linear radiance, exact), the same
/// two as `actual.png` / `expected.png` (sRGB, exposure 0) and
/// `difference.png` into `dir` (created if missing), and returns the
/// paths in that order.
///
/// The difference image is `|actual − expected|` per channel, scaled so
/// that the largest difference is white (linear, then sRGB-encoded): where
/// the frames agree it is black, and the brightest spot is the worst pixel
/// whatever its magnitude. Pixels covered in one frame only are magenta.
pub fn write_failure_images(dir: &Path, actual: &Frame, expected: &Frame) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| crate::Error::output(dir, e.to_string()))?;
    let mut written = Vec::new();
    for (name, frame) in [("actual", actual), ("expected", expected)] {
        for ext in ["exr", "png"] {
            let path = dir.join(format!("{name}.{ext}"));
            OutputFile::prepare(&path)?.write(frame, 0.0)?;
            written.push(path);
        }
    }
    let path = dir.join("difference.png");
    OutputFile::prepare(&path)?.write(&difference(actual, expected), 0.0)?;
    written.push(path);
    Ok(written)
}

/// `|a − b|` per channel over the largest such difference (see
/// [`write_failure_images`]); frames of different sizes compare over the
/// common rectangle.
pub fn difference(a: &Frame, b: &Frame) -> Frame {
    let (width, height) = (a.width.min(b.width), a.height.min(b.height));
    let mut out = Frame::new(width, height);
    let mut max = 0.0f32;
    for i in 0..height {
        for j in 0..width {
            let (pa, pb) = (a.index(i, j), b.index(i, j));
            let k = out.index(i, j);
            out.coverage[k] = true;
            if a.coverage[pa] != b.coverage[pb] {
                out.radiance[k] = [f32::INFINITY, 0.0, f32::INFINITY];
                continue;
            }
            for c in 0..3 {
                let d = (a.radiance[pa][c] - b.radiance[pb][c]).abs();
                out.radiance[k][c] = d;
                if d.is_finite() {
                    max = max.max(d);
                }
            }
        }
    }
    let scale = if max > 0.0 { 1.0 / max } else { 1.0 };
    for p in &mut out.radiance {
        *p = p.map(|d| if d.is_finite() { d * scale } else { 1.0 });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn difference_is_scaled_to_the_worst_pixel_and_marks_coverage() {
        let mut a = Frame::new(3, 1);
        let mut b = Frame::new(3, 1);
        a.coverage = vec![true, true, true];
        b.coverage = vec![true, true, false];
        a.radiance = vec![[1.0, 1.0, 1.0], [0.5, 0.0, 0.0], [0.0; 3]];
        b.radiance = vec![[1.0, 0.75, 1.0], [0.0, 0.0, 0.0], [0.0; 3]];
        let d = difference(&a, &b);
        assert_eq!(d.radiance[0], [0.0, 0.5, 0.0]);
        assert_eq!(d.radiance[1], [1.0, 0.0, 0.0]);
        assert_eq!(d.radiance[2], [1.0, 0.0, 1.0]);
    }

    #[test]
    fn failure_images_are_written() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = Frame::new(2, 2);
        a.coverage = vec![true; 4];
        a.radiance[1] = [0.25, 0.5, 1.0];
        let paths = write_failure_images(&dir.path().join("case"), &a, &Frame::new(2, 2)).unwrap();
        assert_eq!(paths.len(), 5);
        assert!(paths.iter().all(|p| p.is_file()), "{paths:?}");
    }
}
