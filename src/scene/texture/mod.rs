//! The images textures read: decoded once on load ([`decode`]), turned
//! into linear values, filtered into a mip chain in linear space
//! ([`mips`]), and stored as the half floats both renderers read (the GPU
//! uploads them as `rgba16float`, the CPU reference reads the same
//! halves, so the two start from identical texels).

pub mod decode;
pub mod ktx2;
pub mod mips;
pub mod store;

pub use decode::Encoding;

use glam::DVec4;
use half::f16;

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

/// A texture image with its mip chain, in linear values.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// What messages and `--verbose` call it: the file, or the glTF image.
    pub name: String,
    pub encoding: Encoding,
    /// Level 0 first, down to 1×1.
    pub levels: Vec<Level>,
}

impl Image {
    /// An image from decoded linear RGBA, with its mip chain.
    pub fn new(name: impl Into<String>, encoding: Encoding, decoded: decode::Decoded) -> Self {
        Image {
            name: name.into(),
            encoding,
            levels: mips::chain(decoded),
        }
    }

    /// Bytes of all levels on the GPU (8 per texel).
    pub fn gpu_bytes(&self) -> u64 {
        self.levels.iter().map(|l| 8 * l.texels.len() as u64).sum()
    }
}

/// The half nearest to `v` (round to nearest even, as the GPU's f16
/// conversion; the texels are rounded here, once, for both renderers).
pub fn to_half_bits(v: f32) -> u16 {
    f16::from_f32(v).to_bits()
}
