//! The image both renderers return: linear radiance plus a coverage mask.

/// A rendered image: linear `L_o` per pixel (three channels, linear Rec.709)
/// and whether any geometry covers the pixel centre.
///
/// Radiance is stored as `f32`. The CPU reference computes in `f64` and
/// rounds once on store (relative error ≤ 2⁻²⁴, far below every tolerance
/// that compares frames).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    /// Row-major, row 0 at the top.
    pub radiance: Vec<[f32; 3]>,
    /// `true` where a triangle covers the pixel centre.
    pub coverage: Vec<bool>,
}

impl Frame {
    /// A black, uncovered frame.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Frame {
            width,
            height,
            radiance: vec![[0.0; 3]; n],
            coverage: vec![false; n],
        }
    }

    /// Index of pixel (row `i`, column `j`).
    pub fn index(&self, i: u32, j: u32) -> usize {
        i as usize * self.width as usize + j as usize
    }

    /// Number of pixels.
    pub fn len(&self) -> usize {
        self.radiance.len()
    }

    /// True for a 0-pixel frame.
    pub fn is_empty(&self) -> bool {
        self.radiance.is_empty()
    }

    /// Largest channel value over covered pixels (0 for an empty frame).
    pub fn max_radiance(&self) -> f32 {
        self.radiance
            .iter()
            .zip(&self.coverage)
            .filter(|(_, c)| **c)
            .flat_map(|(r, _)| r.iter().copied())
            .fold(0.0, f32::max)
    }
}
