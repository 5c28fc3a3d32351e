//! The images textures read: decoded once on load ([`decode`]), turned
//! into linear values, filtered into a mip chain in linear space
//! ([`mips`]), and stored as the half floats both renderers read (the GPU
//! uploads them as `rgba16float`, the CPU reference reads the same
//! halves, so the two start from identical texels).

pub mod decode;
pub mod ktx2;
pub mod ktx2_layout;
pub mod mips;
pub mod store;

pub use decode::Encoding;
pub use mips::{Level, to_half_bits};

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
