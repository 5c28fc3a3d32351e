//! The mip chain of an image, built on load in linear space.
//!
//! Each level halves the one above (sizes rounded down, at least 1, as
//! Vulkan and wgpu count levels: `⌊log₂ max(w, h)⌋ + 1` of them) and each
//! of its texels is the mean of the 2×2 block it covers (at an odd edge the
//! block's missing column or row repeats the last one: a box filter, the
//! usual `generateMipmap` rule). Filtering happens on linear values in
//! f32, from the unrounded level above, because averaging sRGB-encoded
//! values darkens (glTF 2.0 §3.9.6: colour textures are filtered in
//! linear space); every level is then rounded to f16 once.

use super::decode::Decoded;
use glam::DVec4;
use half::f16;
use half::slice::{HalfBitsSliceExt, HalfFloatSliceExt};
use rayon::prelude::*;

/// One level of a mip chain: `width · height` RGBA texels as f16 bits,
/// row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[u16; 4]>,
}

impl Level {
    /// Texel (x, y) in f64 (exact: every half is an f64).
    pub fn texel(&self, x: u32, y: u32) -> DVec4 {
        let t = self.texels[(y * self.width + x) as usize];
        DVec4::from_array(t.map(|h| f16::from_bits(h).to_f64()))
    }
}

/// The half nearest to `v` (round to nearest even, as the GPU's f16
/// conversion; the texels are rounded here, once, for both renderers).
pub fn to_half_bits(v: f32) -> u16 {
    f16::from_f32(v).to_bits()
}

/// Every level of `image`, level 0 first.
pub fn chain(image: Decoded) -> Vec<Level> {
    let (mut width, mut height, mut rgba) = (image.width, image.height, image.rgba);
    let mut levels = vec![round(width, height, &rgba)];
    while width > 1 || height > 1 {
        let (w, h) = ((width / 2).max(1), (height / 2).max(1));
        rgba = halve(width, height, &rgba, w, h);
        (width, height) = (w, h);
        levels.push(round(width, height, &rgba));
    }
    levels
}

/// The next level `w × h` of `src` (`width × height`).
fn halve(width: u32, height: u32, src: &[[f32; 4]], w: u32, h: u32) -> Vec<[f32; 4]> {
    let at = |x: u32, y: u32| src[(y.min(height - 1) * width + x.min(width - 1)) as usize];
    // Rows in parallel (each texel is its own block's mean: the same
    // values in any order).
    (0..h)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..w).map(move |x| {
                let (x0, y0) = (2 * x, 2 * y);
                let block = [
                    at(x0, y0),
                    at(x0 + 1, y0),
                    at(x0, y0 + 1),
                    at(x0 + 1, y0 + 1),
                ];
                let mut mean = [0.0f32; 4];
                for (c, m) in mean.iter_mut().enumerate() {
                    *m = 0.25 * block.iter().map(|t| t[c]).sum::<f32>();
                }
                mean
            })
        })
        .collect()
}

/// `rgba` rounded to halves: [`to_half_bits`] of every value, by the
/// `half` crate's slice conversion (the F16C instructions eight at a time
/// where the CPU has them, the same round to nearest even), in parallel
/// blocks.
fn round(width: u32, height: u32, rgba: &[[f32; 4]]) -> Level {
    const BLOCK: usize = 1 << 14;
    let mut texels = vec![[0u16; 4]; rgba.len()];
    texels
        .par_chunks_mut(BLOCK)
        .zip(rgba.par_chunks(BLOCK))
        .for_each(|(out, block)| {
            let out: &mut [u16] = out.as_flattened_mut();
            out.reinterpret_cast_mut::<f16>()
                .convert_from_f32_slice(block.as_flattened());
        });
    Level {
        width,
        height,
        texels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_halve_down_to_one_texel_and_average_in_linear_space() {
        // A 5×2 image: black and white columns alternate.
        let rgba = (0..10)
            .map(|i| if i % 2 == 0 { [0.0; 4] } else { [1.0; 4] })
            .collect();
        let levels = chain(Decoded {
            width: 5,
            height: 2,
            rgba,
        });
        let sizes: Vec<_> = levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(5, 2), (2, 1), (1, 1)]);
        // Level 1: blocks (0,1) and (2,3) are half white: linear 0.5.
        assert_eq!(levels[1].texel(0, 0).x, 0.5);
        assert_eq!(levels[1].texel(1, 0).x, 0.5);
        assert_eq!(levels[2].texel(0, 0).x, 0.5);
    }

    /// The slice conversion rounds every value as [`to_half_bits`] does:
    /// halves, values between them (ties included), the subnormal range,
    /// overflow and the extremes of the f32 range.
    #[test]
    fn a_level_rounds_as_to_half_bits() {
        let mut values: Vec<f32> = (0..=u16::MAX)
            .map(f16::from_bits)
            .filter(|h| h.is_finite())
            .flat_map(|h| {
                let v = h.to_f32();
                [v, f32::from_bits(v.to_bits() + 1), v * 1.000_244_1]
            })
            .collect();
        values.extend([
            6.0e-8,
            3.0e-8,
            65_519.0,
            65_520.0,
            1.0e30,
            -1.0e30,
            f32::MIN_POSITIVE,
        ]);
        values.truncate(values.len() / 4 * 4);
        let rgba: Vec<[f32; 4]> = values
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        let level = round(rgba.len() as u32, 1, &rgba);
        for (t, h) in rgba.iter().zip(&level.texels) {
            assert_eq!(t.map(to_half_bits), *h, "{t:?}");
        }
    }
}
