//! Reading an environment map: OpenEXR (`.exr`) or Radiance RGBE
//! (`.hdr`, `.pic`) through the `image` crate, or a built-in map
//! (`map = "sky"`, `map = "studio"`). Every failure is one sentence the caller prefixes
//! with the scene file and key.

use super::exr_header;
use super::map::{MAX_SIDE, MapData};
use super::sky::{self, SKY};
use super::studio::STUDIO;
use crate::base::input::exceeded;
use crate::base::input::{ReadError, read_regular_file};
use std::path::Path;

/// The map `value` names, relative to `base_dir` (the scene file's
/// folder): [`SKY`] or a path to an `.exr` / `.hdr` file, read as a
/// regular file ([`read_regular_file`]) and held to `max_bytes` (what is
/// left of `--limit bytes`: the file and its decoded texels together,
/// checked from the header before decoding).
pub fn load(value: &str, base_dir: &Path, max_bytes: u64) -> Result<MapData, String> {
    if value == SKY {
        return Ok(sky::map());
    }
    if value == STUDIO {
        return Ok(super::studio::map());
    }
    let path = base_dir.join(value);
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let Some(format) = format_of(&extension) else {
        return Err(format!(
            "`{value}` is neither an .exr nor an .hdr file (nor \"{SKY}\" or \"{STUDIO}\", the built-in maps)"
        ));
    };
    let name = path.display().to_string();
    let bytes = read_regular_file(&path, max_bytes).map_err(|e| match e {
        ReadError::TooLarge(len) => format!(
            "{name}: {}",
            exceeded("the map file", format!("{len} bytes"), "bytes", max_bytes)
        ),
        ReadError::Io(e) => format!("cannot read {name}: {e}"),
        other => format!("{name} {other}"),
    })?;
    let budget = Budget {
        file_bytes: bytes.len() as u64,
        max_bytes,
    };
    decode(&bytes, format, &name, MAX_TEXELS, budget).map_err(|e| format!("{name}: {e}"))
}

/// The bytes a map load may hold: its file and its decoded texels
/// together at most `max_bytes` (`--limit bytes`, as for textures).
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    pub file_bytes: u64,
    pub max_bytes: u64,
}

impl Budget {
    /// No limit beyond [`MAX_TEXELS`] (the fuzz target's and tests').
    pub const UNLIMITED: Budget = Budget {
        file_bytes: 0,
        max_bytes: u64::MAX,
    };

    /// Refuses `decoded` bytes of texels (plus the file) over the budget.
    fn check(&self, what: &str, decoded: u64) -> Result<(), String> {
        let total = decoded.saturating_add(self.file_bytes);
        if total > self.max_bytes {
            return Err(exceeded(
                &format!("loading it ({what} and the file)"),
                format!("{total} bytes"),
                "bytes",
                self.max_bytes,
            ));
        }
        Ok(())
    }
}

/// Texels a map file may declare: the largest map side gonio accepts
/// ([`MAX_SIDE`] × [`MAX_SIDE`]/2, 1.5 GiB of f32 RGB).
pub const MAX_TEXELS: u64 = MAX_SIDE as u64 * (MAX_SIDE as u64 / 2);

/// Most decoded bytes (f32 RGB) one byte of a map file may stand for:
/// twice deflate's largest ratio (about 1032 : 1), the most any codec of
/// Radiance RGBE or OpenEXR reaches.
const MAX_EXPANSION: u64 = 2048;

/// What a map file that does not decode as `expected` is, by its first
/// bytes (a PNG or JPEG named `.hdr`, a text file): `None` when it looks
/// like the expected format (then it is a damaged one).
fn what_it_is(bytes: &[u8], expected: image::ImageFormat) -> Option<String> {
    if bytes.is_empty() {
        return Some("an empty file".into());
    }
    if let Ok(actual) = image::guess_format(bytes) {
        return (actual != expected).then(|| {
            format!(
                "a {} image",
                actual
                    .extensions_str()
                    .first()
                    .unwrap_or(&"other")
                    .to_uppercase()
            )
        });
    }
    let radiance = bytes.starts_with(b"#?");
    let text = std::str::from_utf8(&bytes[..bytes.len().min(512)]).is_ok();
    match (radiance, text) {
        (true, _) => None,
        (false, true) => Some("a text file".into()),
        (false, false) => Some("a file of an unknown format".into()),
    }
}

/// The decoder for a file extension (lower case): `exr`, or `hdr`/`pic`.
pub fn format_of(extension: &str) -> Option<image::ImageFormat> {
    match extension {
        "exr" => Some(image::ImageFormat::OpenExr),
        "hdr" | "pic" => Some(image::ImageFormat::Hdr),
        _ => None,
    }
}

/// Decodes a map file's `bytes`. The header's dimensions are checked (a
/// 2 : 1 lat-long map, at most `max_texels`, its texels within `budget`)
/// before any texel is decoded, so a few bytes declaring a huge image
/// allocate nothing; the decoder's own allocations are capped just above
/// the texels' size. `name` is for [`MapData`]; errors are one sentence
/// without it.
pub fn decode(
    bytes: &[u8],
    format: image::ImageFormat,
    name: &str,
    max_texels: u64,
    budget: Budget,
) -> Result<MapData, String> {
    let kind = format.extensions_str()[0];
    let unreadable = |e: image::ImageError| match what_it_is(bytes, format) {
        Some(actual) => format!(
            "it is {actual}, not a {kind} image (an environment map is an OpenEXR .exr or a Radiance .hdr file; convert it, or name it by what it is)"
        ),
        None => format!("it is not a readable {kind} image: {e}"),
    };
    let reader = |limits: image::Limits| {
        let mut reader = image::ImageReader::with_format(std::io::Cursor::new(bytes), format);
        reader.limits(limits);
        reader
    };
    // The `exr` crate sizes its block buffers from the header's tile and
    // chunk table, beyond `image`'s allocation limit, already while it
    // reads the header: checked before it sees the file.
    if format == image::ImageFormat::OpenExr {
        exr_header::check(bytes, max_texels)?;
    }
    let (width, height) = reader(image::Limits::default())
        .into_dimensions()
        .map_err(unreadable)?;
    MapData::check_dimensions(width, height)?;
    let texels = u64::from(width) * u64::from(height);
    if texels > max_texels {
        return Err(format!(
            "it declares {width} × {height} texels, over the {max_texels} this load allows"
        ));
    }
    // A few bytes declaring a map of gigabytes cannot be a real file: no
    // codec of these formats expands more than deflate's about 1032 : 1
    // (RGBE's run-length coding, EXR's RLE, PIZ and B44 far less).
    let declared = 12 * texels;
    if declared > MAX_EXPANSION * bytes.len() as u64 + (1 << 20) {
        return Err(format!(
            "it declares {width} × {height} texels ({declared} bytes) in a file of {} bytes, more than any of its codecs expands ({MAX_EXPANSION} : 1): the file is truncated or corrupt",
            bytes.len()
        ));
    }
    // The least a load holds: the texels as f32 RGB.
    budget.check("its texels as f32 RGB", 12 * texels)?;
    // RGB or RGBA f32 and one converted copy, plus slack for the decoder.
    let alloc_cap = 2 * 16 * texels + (1 << 20);
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(alloc_cap);
    let decoder = reader(limits).into_decoder().map_err(unreadable)?;
    // The decoder's own buffer is sized from what it will decode, which an
    // OpenEXR file may declare apart from the size its header reports (a
    // data window beyond the display window): checked here, before the
    // decoder allocates it.
    let decoded = image::ImageDecoder::dimensions(&decoder);
    let bytes = image::ImageDecoder::total_bytes(&decoder);
    if decoded != (width, height) || bytes > alloc_cap {
        return Err(format!(
            "its header says {width} × {height} texels but it decodes {} × {} ({bytes} bytes)",
            decoded.0, decoded.1
        ));
    }
    // A decoder that does not give f32 RGB (an EXR with alpha) is
    // converted: its buffer and the copy are held at once.
    let rgb32f = image::ImageDecoder::color_type(&decoder) == image::ColorType::Rgb32F;
    let peak = if rgb32f { bytes } else { bytes + 12 * texels };
    budget.check("its decoded texels", peak)?;
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(unreadable)?
        .into_rgb32f();
    // The decoded buffer becomes the map's texels without a copy.
    let texels: Vec<[f32; 3]> = bytemuck::allocation::try_cast_vec(image.into_raw())
        .unwrap_or_else(|(_, raw)| raw.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
    MapData::new(name, width, height, texels)
}

/// Writes `map` as a Radiance `.hdr` file (RGBE: 8-bit mantissas, a
/// relative precision of 2⁻⁸); for the test maps gonio ships.
pub fn write_hdr(map: &MapData, path: &Path) -> std::io::Result<()> {
    let pixels: Vec<image::Rgb<f32>> = map.texels.iter().map(|t| image::Rgb(*t)).collect();
    let mut bytes = Vec::new();
    image::codecs::hdr::HdrEncoder::new(&mut bytes)
        .encode(&pixels, map.width as usize, map.height as usize)
        .map_err(std::io::Error::other)?;
    std::fs::write(path, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_files_say_what_is_wrong() {
        let dir = tempfile::tempdir().unwrap();
        let e = load("nope.exr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("cannot read") && e.contains("nope.exr"), "{e}");
        let e = load("sky.png", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("neither an .exr nor an .hdr"), "{e}");
        std::fs::write(dir.path().join("bad.hdr"), b"#?RADIANCE\ngarbage").unwrap();
        let e = load("bad.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("not a readable hdr image"), "{e}");
        // A file of another kind is named as what it is.
        std::fs::write(dir.path().join("fake.hdr"), b"not an image at all\n").unwrap();
        let e = load("fake.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("it is a text file, not a hdr image"), "{e}");
        let mut png = Vec::new();
        image::RgbImage::new(2, 1)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        std::fs::write(dir.path().join("png.hdr"), png).unwrap();
        let e = load("png.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("it is a PNG image, not a hdr image"), "{e}");
        // A header declaring a huge map is refused before decoding.
        std::fs::write(
            dir.path().join("bomb.hdr"),
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n",
        )
        .unwrap();
        let e = load("bomb.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("200000 × 100000"), "{e}");
        // 4096 × 2048 texels (100 MB decoded) declared in 50 bytes.
        std::fs::write(
            dir.path().join("small-bomb.hdr"),
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2048 +X 4096\n",
        )
        .unwrap();
        let e = load("small-bomb.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("more than any of its codecs expands"), "{e}");
        // A height whose double overflows u32 (a fuzz finding): 2³¹ + 8
        // doubled wrapped to 16, and a 16-wide map passed as 2 : 1.
        std::fs::write(
            dir.path().join("tall.hdr"),
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2147483656 +X 16\n",
        )
        .unwrap();
        let e = load("tall.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(
            e.contains("twice as wide as high") && e.contains("16 × 2147483656"),
            "{e}"
        );
    }

    #[test]
    fn an_hdr_file_reads_back_within_rgbe_precision_and_dims_are_checked() {
        let dir = tempfile::tempdir().unwrap();
        let map = super::super::test_maps::blobs();
        let path = dir.path().join("blobs.hdr");
        write_hdr(&map, &path).unwrap();
        let back = load("blobs.hdr", dir.path(), u64::MAX).unwrap();
        assert_eq!((back.width, back.height), (map.width, map.height));
        for (a, b) in back.texels.iter().zip(&map.texels) {
            // RGBE shares one exponent: 2⁻⁷ of the largest channel.
            let largest = b.iter().fold(0.0f32, |m, v| m.max(*v));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() <= largest / 128.0, "{a:?} {b:?}");
            }
        }
        // A square image is not a lat-long map.
        let square = MapData {
            width: 8,
            height: 8,
            texels: vec![[1.0; 3]; 64],
            ..map
        };
        write_hdr(&square, &dir.path().join("square.hdr")).unwrap();
        let e = load("square.hdr", dir.path(), u64::MAX).unwrap_err();
        assert!(e.contains("8 × 8"), "{e}");
    }
}
