//! PNG, JPEG, WebP and KTX2 (Basis Universal, [`super::ktx2`]) bytes to
//! linear RGBA, with the size checked before any pixel is decoded.
//!
//! Colour images in 8- or 16-bit formats are sRGB-encoded (glTF 2.0 §3.9.6
//! for base colour and emission; the contract for scene files' colour
//! parameters) and are decoded to linear here, before any filtering;
//! data images (metallic-roughness, normals, occlusion, scalar
//! parameters) are linear and only scaled to [0, 1]. Embedded gamma
//! (`gAMA`), `sRGB` and ICC chunks are ignored, as the Khronos
//! TextureEncodingTest requires: a PNG's values are taken as sRGB whatever
//! it declares.

use image::ImageDecoder;
use rayon::prelude::*;
use std::io::Cursor;

/// How an image's values are to be read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// Colour: the sRGB transfer function is undone (IEC 61966-2-1) on
    /// R, G, B; alpha is linear.
    Srgb,
    /// Data: values as stored, scaled to [0, 1].
    Linear,
}

/// A decoded image: linear RGBA, row 0 at the top (glTF's UV (0, 0) is the
/// top-left corner).
#[derive(Clone, Debug, PartialEq)]
pub struct Decoded {
    pub width: u32,
    pub height: u32,
    /// `width · height` texels.
    pub rgba: Vec<[f32; 4]>,
}

/// Largest side of a texture: wgpu's default `max_texture_dimension_2d`,
/// which gonio's device requests (larger images would not upload).
pub const MAX_TEXTURE_SIDE: u32 = 8192;

/// Bytes per texel while one texture is decoded, for the budget: the
/// decoder's RGBA at up to 16 bits per channel (8 B), the f32 linear copy
/// (16 B), and the f16 levels being built (8 B · 4/3 ≈ 11 B). The first
/// two are freed once the chain is built ([`super::mips::chain`]).
pub const BYTES_PER_TEXEL: u64 = 8 + 16 + 11;

/// Bytes per texel a loaded texture keeps: its f16 RGBA levels, the full
/// chain 4/3 of the top level (8 B · 4/3, rounded up).
pub const HELD_BYTES_PER_TEXEL: u64 = 11;

/// What one texture takes of the byte budget: `peak` while it decodes
/// (checked against what is left), `held` once loaded (charged).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureCost {
    pub peak: u64,
    pub held: u64,
}

/// The size the header of `bytes` declares, read without decoding pixels.
pub fn dimensions(bytes: &[u8]) -> Result<(u32, u32), String> {
    if super::ktx2::is_ktx2(bytes) {
        return super::ktx2::dimensions(bytes);
    }
    let reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read it: {e}"))?;
    match reader.format() {
        Some(image::ImageFormat::Png | image::ImageFormat::Jpeg | image::ImageFormat::WebP) => {}
        Some(other) => {
            return Err(format!(
                "it is a {other:?} image; gonio reads PNG, JPEG, WebP and KTX2 (Basis Universal) textures"
            ));
        }
        None => return Err("it is not a PNG, JPEG, WebP or KTX2 image".into()),
    }
    reader
        .into_dimensions()
        .map_err(|e| format!("its header is corrupt: {e}"))
}

/// Checks a declared size against the texture limits and `budget` (bytes
/// left) at the decode's peak; returns the bytes it takes then and after.
pub fn check_size(width: u32, height: u32, budget: u64) -> Result<TextureCost, String> {
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "its size {width}×{height} is outside 1..={MAX_TEXTURE_SIDE} per side"
        ));
    }
    let texels = u64::from(width) * u64::from(height);
    let peak = texels * BYTES_PER_TEXEL;
    if peak > budget {
        return Err(crate::scene::limits::exceeded(
            &format!("decoding its {width}×{height} texels"),
            format!("{peak} bytes"),
            "bytes",
            budget,
        ));
    }
    Ok(TextureCost {
        peak,
        held: texels * HELD_BYTES_PER_TEXEL,
    })
}

/// Decodes `bytes` (PNG, JPEG, WebP or KTX2) to linear RGBA after
/// checking the declared size against `budget` bytes; the decoder is held
/// to the same allocation limit. Grey images repeat their value in R, G
/// and B. A KTX2 texture is transcoded to RGBA8 and then read as an 8-bit
/// image is.
pub fn decode(bytes: &[u8], encoding: Encoding, budget: u64) -> Result<Decoded, String> {
    let (width, height) = dimensions(bytes)?;
    check_size(width, height, budget)?;
    if bytes.starts_with(&[0xFF, 0xD8]) && !jpeg_is_complete(bytes) {
        // zune-jpeg decodes a cut-off scan as grey without an error; a
        // truncated PNG fails its CRC. Both are refused alike.
        return Err(
            "it is corrupt: the JPEG data ends before its end-of-image marker (the file is truncated)"
                .into(),
        );
    }
    let to_linear = |v: f32| match encoding {
        Encoding::Srgb => srgb_to_linear(v),
        Encoding::Linear => v,
    };
    if super::ktx2::is_ktx2(bytes) {
        let (_, _, rgba8) = super::ktx2::transcode_rgba8(bytes)?;
        let table = EightBitTable::new(encoding);
        let rgba = rgba8
            .par_chunks_exact(4)
            .map(|p| table.texel([p[0], p[1], p[2], p[3]]))
            .collect();
        return Ok(Decoded {
            width,
            height,
            rgba,
        });
    }
    let mut reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read it: {e}"))?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    limits.max_alloc = Some(budget);
    reader.limits(limits);
    let mut decoder = reader
        .into_decoder()
        .map_err(|e| format!("it is corrupt: {e}"))?;
    // No colour management: an embedded ICC profile is not applied.
    let _ = decoder.icc_profile();
    let image =
        image::DynamicImage::from_decoder(decoder).map_err(|e| format!("it is corrupt: {e}"))?;
    let rgba = if eight_bit(&image) {
        // 256 values per channel: each one's linear value computed once
        // ([`EightBitTable`]), the same f32 the per-texel path gives.
        let table = EightBitTable::new(encoding);
        image
            .into_rgba8()
            .into_raw()
            .par_chunks_exact(4)
            .map(|p| table.texel([p[0], p[1], p[2], p[3]]))
            .collect()
    } else {
        image
            .into_rgba32f()
            .into_raw()
            .par_chunks_exact(4)
            .map(|p| [to_linear(p[0]), to_linear(p[1]), to_linear(p[2]), p[3]])
            .collect()
    };
    Ok(Decoded {
        width,
        height,
        rgba,
    })
}

/// Whether `image` holds 8 bits per channel (JPEG, and most PNG and
/// WebP files): its RGBA8 form then loses nothing.
fn eight_bit(image: &image::DynamicImage) -> bool {
    use image::DynamicImage::*;
    matches!(
        image,
        ImageLuma8(_) | ImageLumaA8(_) | ImageRgb8(_) | ImageRgba8(_)
    )
}

/// The linear value of every 8-bit code, colour channels as `encoding`
/// reads them and alpha as stored: the sRGB EOTF in f64 per texel was the
/// largest cost of loading a JPEG-textured file (DamagedHelmet's five
/// 2048² images, 2026-12-06). Each entry is computed from the very f32
/// that `image`'s own conversion gives the code (`into_rgba32f` of a
/// 256-texel image), so a texel's value is the one the per-texel path
/// computes, bit for bit (test `the_table_is_the_per_texel_path`).
struct EightBitTable {
    colour: [f32; 256],
    alpha: [f32; 256],
}

impl EightBitTable {
    fn new(encoding: Encoding) -> Self {
        let codes = image::RgbaImage::from_fn(256, 1, |x, _| image::Rgba([x as u8; 4]));
        let scaled = image::DynamicImage::ImageRgba8(codes).into_rgba32f();
        let mut table = EightBitTable {
            colour: [0.0; 256],
            alpha: [0.0; 256],
        };
        for (c, p) in scaled.pixels().enumerate() {
            table.colour[c] = match encoding {
                Encoding::Srgb => srgb_to_linear(p.0[0]),
                Encoding::Linear => p.0[0],
            };
            table.alpha[c] = p.0[3];
        }
        table
    }

    fn texel(&self, [r, g, b, a]: [u8; 4]) -> [f32; 4] {
        let c = |v: u8| self.colour[usize::from(v)];
        [c(r), c(g), c(b), self.alpha[usize::from(a)]]
    }
}

/// Whether a JPEG stream reaches its end-of-image marker (`FF D9`) after
/// its first frame scan: the marker segments before the scan are skipped
/// by their lengths (an EXIF thumbnail inside APP1 has its own markers),
/// and entropy-coded data cannot hold `FF D9` (a data byte `FF` is
/// stuffed as `FF 00`; ITU T.81, B.1.1.5).
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let mut pos = 2;
    while let (Some(&0xFF), Some(&marker)) = (bytes.get(pos), bytes.get(pos + 1)) {
        match marker {
            // Fill bytes before a marker.
            0xFF => pos += 1,
            // Markers without a length: TEM, RSTn.
            0x01 | 0xD0..=0xD7 => pos += 2,
            // Start of scan: the rest must end the image.
            0xDA => {
                return bytes[pos + 2..].windows(2).any(|w| w == [0xFF, 0xD9]);
            }
            0xD9 => return false,
            _ => {
                let Some(len) = bytes.get(pos + 2..pos + 4) else {
                    return false;
                };
                pos += 2 + usize::from(u16::from_be_bytes([len[0], len[1]]));
            }
        }
    }
    false
}

/// The sRGB EOTF (IEC 61966-2-1), encoded value in [0, 1] to linear; in
/// f64 and rounded once, so the result is the correctly rounded f32 of
/// the exact value.
pub fn srgb_to_linear(v: f32) -> f32 {
    let v = f64::from(v);
    let linear = if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    };
    linear as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32, pixels: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        image::codecs::png::PngEncoder::new(&mut out)
            .write_image(pixels, width, height, image::ExtendedColorType::Rgb8)
            .unwrap();
        out
    }

    use image::ImageEncoder;

    /// The 8-bit table gives every code the value the per-texel path
    /// (`into_rgba32f`, then the EOTF for colour) gives it, bit for bit.
    #[test]
    fn the_table_is_the_per_texel_path() {
        for encoding in [Encoding::Srgb, Encoding::Linear] {
            let table = EightBitTable::new(encoding);
            for c in 0..=255u8 {
                let v = f32::from(c) / 255.0;
                let expected = match encoding {
                    Encoding::Srgb => srgb_to_linear(v),
                    Encoding::Linear => v,
                };
                let got = table.texel([c, c, c, c]);
                assert_eq!(got[0].to_bits(), expected.to_bits(), "{encoding:?} {c}");
                assert_eq!(got[3].to_bits(), v.to_bits(), "alpha {c}");
            }
        }
        // And a decoded 8-bit PNG takes its values from the table.
        let bytes = png(3, 1, &[0, 0, 0, 128, 128, 128, 255, 255, 255]);
        let srgb = decode(&bytes, Encoding::Srgb, 1 << 20).unwrap();
        assert_eq!(
            srgb.rgba[1][0].to_bits(),
            srgb_to_linear(128.0 / 255.0).to_bits()
        );
    }

    #[test]
    fn srgb_values_decode_to_linear_and_data_values_stay() {
        let bytes = png(2, 1, &[255, 128, 0, 10, 20, 30]);
        let srgb = decode(&bytes, Encoding::Srgb, 1 << 20).unwrap();
        assert_eq!((srgb.width, srgb.height), (2, 1));
        assert_eq!(srgb.rgba[0][0], 1.0);
        // sRGB 128/255 is 0.2158605 linear.
        assert!((srgb.rgba[0][1] - 0.215_860_5).abs() < 1e-6);
        assert_eq!(srgb.rgba[0][3], 1.0);
        assert!((srgb.rgba[1][0] - (10.0 / 255.0 / 12.92)).abs() < 1e-7);
        let data = decode(&bytes, Encoding::Linear, 1 << 20).unwrap();
        assert!((data.rgba[0][1] - 128.0 / 255.0).abs() < 1e-7);
    }

    /// A header declaring 65535² texels in a few dozen bytes is refused
    /// from the header alone.
    #[test]
    fn a_huge_declared_size_is_refused_before_decoding() {
        let mut bytes = png(1, 1, &[1, 2, 3]);
        // IHDR's width and height at bytes 16..24, and its CRC (over
        // bytes 12..29) made right, so the header is valid.
        bytes[16..20].copy_from_slice(&65535u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&65535u32.to_be_bytes());
        let mut crc = !0u32;
        for &b in &bytes[12..29] {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 != 0 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        let crc = !crc;
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        let e = decode(&bytes, Encoding::Srgb, 1 << 40).unwrap_err();
        assert!(e.contains("65535×65535"), "{e}");
        let e = check_size(4096, 4096, 1 << 20).unwrap_err();
        assert!(e.contains("--limit bytes="), "{e}");
    }

    #[test]
    fn corrupt_and_foreign_bytes_are_named() {
        let mut bytes = png(4, 4, &[7; 48]);
        let n = bytes.len();
        bytes.truncate(n - 20);
        assert!(
            decode(&bytes, Encoding::Srgb, 1 << 20)
                .unwrap_err()
                .contains("corrupt")
        );
        // A JPEG cut before its end-of-image marker (zune-jpeg alone
        // decodes it as grey).
        let mut jpeg = Vec::new();
        image::RgbImage::from_fn(64, 64, |x, y| {
            image::Rgb([(x * 4) as u8, (y * 4) as u8, (x ^ y) as u8 * 4])
        })
        .write_to(&mut Cursor::new(&mut jpeg), image::ImageFormat::Jpeg)
        .unwrap();
        assert!(decode(&jpeg, Encoding::Srgb, 1 << 20).is_ok());
        let e = decode(&jpeg[..jpeg.len() * 3 / 4], Encoding::Srgb, 1 << 20).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        let e = decode(b"GIF89a......", Encoding::Srgb, 1 << 20).unwrap_err();
        assert!(e.contains("PNG, JPEG, WebP and KTX2"), "{e}");
        let e = decode(b"hello", Encoding::Srgb, 1 << 20).unwrap_err();
        assert!(e.contains("not a PNG, JPEG, WebP or KTX2"), "{e}");
    }
}
