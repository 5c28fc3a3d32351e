//! The images of one scene, loaded once each and held to the scene's
//! limits: every image counts against `--limit textures=N` and its
//! bytes against `--limit bytes=N`, both checked from the image's header
//! before its pixels are decoded. A texture is checked at its decode's
//! peak (texels, the linear copy and the mip chain,
//! [`decode::BYTES_PER_TEXEL`]) and charged what it keeps (its f16 mip
//! chain, [`decode::HELD_BYTES_PER_TEXEL`]): images decode one after
//! another, so the transient copies of one are gone before the next.

use super::Image;
use super::decode::{self, Encoding};
use crate::scene::limits::{Limits, ReadError, exceeded, read_regular_file};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// The scene's images, by index, and what is left of the budget.
#[derive(Debug)]
pub struct ImageStore {
    pub images: Vec<Arc<Image>>,
    /// An image already loaded, by its name and encoding (the same file
    /// read as colour and as data is two images).
    loaded: HashMap<(String, Encoding), usize>,
    bytes_left: u64,
    count_left: u64,
}

impl ImageStore {
    pub fn new(limits: &Limits) -> Self {
        ImageStore {
            images: Vec::new(),
            loaded: HashMap::new(),
            bytes_left: limits.bytes,
            count_left: limits.textures,
        }
    }

    /// The image file at `path` (a regular file), decoded as `encoding`;
    /// its index. The error says what is wrong with it, not which file
    /// (the caller names it).
    pub fn load_file(&mut self, path: &Path, encoding: Encoding) -> Result<usize, String> {
        let name = path.display().to_string();
        if let Some(&i) = self.loaded.get(&(name.clone(), encoding)) {
            return Ok(i);
        }
        let bytes = read_regular_file(path, self.bytes_left).map_err(|e| match e {
            ReadError::TooLarge(len) => exceeded(
                "the image file",
                format!("{len} bytes"),
                "bytes",
                self.bytes_left,
            ),
            other => other.to_string(),
        })?;
        self.load_bytes(name, &bytes, encoding)
    }

    /// What is left of `--limit bytes` for the scene's images and its
    /// environment map.
    pub fn bytes_left(&self) -> u64 {
        self.bytes_left
    }

    /// Charges `bytes` held by an input loaded elsewhere (the environment
    /// map, checked against [`Self::bytes_left`] before it was decoded).
    pub fn charge(&mut self, bytes: u64) {
        self.bytes_left = self.bytes_left.saturating_sub(bytes);
    }

    /// Adds images loaded elsewhere (a glTF file's, held to that file's
    /// budget); the index of the first.
    pub fn append(&mut self, images: Vec<Arc<Image>>) -> usize {
        let first = self.images.len();
        self.images.extend(images);
        first
    }

    /// An image given by its bytes (a glTF buffer view or data URI), named
    /// `name` for messages and for loading it once.
    pub fn load_bytes(
        &mut self,
        name: String,
        bytes: &[u8],
        encoding: Encoding,
    ) -> Result<usize, String> {
        self.load_bytes_mapped(name, bytes, encoding, |_| {})
    }

    /// [`Self::load_bytes`] with `map` applied to every decoded linear
    /// texel before the mip chain is built: an image derived from a file's
    /// (a glTF value stored as `1 − A`, say), computed from the decoded
    /// f32 values so that it is rounded to the stored halves once. `name`
    /// must tell the derivation apart from the plain image.
    pub fn load_bytes_mapped(
        &mut self,
        name: String,
        bytes: &[u8],
        encoding: Encoding,
        map: impl Fn(&mut [f32; 4]),
    ) -> Result<usize, String> {
        if let Some(&i) = self.loaded.get(&(name.clone(), encoding)) {
            return Ok(i);
        }
        if self.count_left == 0 {
            return Err(
                "one image more than the limit on images (raise it with `--limit textures=N` if the input is trusted)".into(),
            );
        }
        let (width, height) = decode::dimensions(bytes)?;
        let cost = decode::check_size(width, height, self.bytes_left)?;
        let mut decoded = decode::decode(bytes, encoding, self.bytes_left)?;
        decoded.rgba.iter_mut().for_each(map);
        self.bytes_left -= cost.held;
        self.count_left -= 1;
        self.images
            .push(Arc::new(Image::new(&name, encoding, decoded)));
        self.loaded.insert((name, encoding), self.images.len() - 1);
        Ok(self.images.len() - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::texture::decode::{BYTES_PER_TEXEL, HELD_BYTES_PER_TEXEL};

    fn png(side: u32, value: u8) -> Vec<u8> {
        let image = image::RgbaImage::from_pixel(side, side, image::Rgba([value, 0, 0, 255]));
        let mut bytes = Vec::new();
        image
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .expect("encode");
        bytes
    }

    /// Textures decode one after another: each needs its peak free, and
    /// keeps only its f16 chain. A budget of one peak plus two chains
    /// takes three textures; charging each its peak took one.
    #[test]
    fn a_texture_is_checked_at_its_peak_and_charged_what_it_keeps() {
        let texels = 64 * 64;
        let budget = texels * BYTES_PER_TEXEL + 2 * texels * HELD_BYTES_PER_TEXEL;
        let mut store = ImageStore::new(&Limits {
            bytes: budget,
            ..Limits::default()
        });
        for value in 1..=3 {
            store
                .load_bytes(format!("t{value}"), &png(64, value), Encoding::Srgb)
                .unwrap_or_else(|e| panic!("texture {value}: {e}"));
        }
        assert_eq!(
            store.bytes_left(),
            budget - 3 * texels * HELD_BYTES_PER_TEXEL
        );
        let e = store
            .load_bytes("t4".into(), &png(64, 4), Encoding::Srgb)
            .unwrap_err();
        assert!(e.contains("--limit bytes="), "{e}");
    }
}
