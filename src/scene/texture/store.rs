//! The images of one scene, loaded once each and held to the scene's
//! limits: every image counts against `--limit textures=N` and its
//! decoded bytes (texels, the linear copy and the mip chain,
//! [`decode::BYTES_PER_TEXEL`]) against `--limit bytes=N`, both checked
//! from the image's header before its pixels are decoded.

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
        self.bytes_left -= cost;
        self.count_left -= 1;
        self.images
            .push(Arc::new(Image::new(&name, encoding, decoded)));
        self.loaded.insert((name, encoding), self.images.len() - 1);
        Ok(self.images.len() - 1)
    }
}
