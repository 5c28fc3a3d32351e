//! PNG and EXR output, written atomically.
//!
//! The contract: `.exr` holds linear `L_o` as 32-bit float RGB, no tone
//! mapping; `.png` holds `clamp(L_o · 2^exposure)` with the sRGB transfer
//! function (or, with `image.tone_map`, another operator in place of the
//! clamp: [`super::tone_map`]). The file appears complete or not at all
//! ([`super::atomic`]); it is claimed before rendering, so an unwritable
//! destination fails before any work is done.

pub use super::atomic::AtomicFile;
use super::srgb8::srgb8;
use super::tone_map::ToneMap;
use crate::frame::Frame;
use crate::{Error, Result};
use std::io::Cursor;
use std::path::Path;

/// The output formats, chosen by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// 8-bit sRGB, exposure applied, clamped.
    Png,
    /// Linear 32-bit float RGB radiance.
    Exr,
}

impl OutputFormat {
    /// The format for `path`'s extension.
    pub fn from_path(path: &Path) -> Result<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(OutputFormat::Png),
            Some("exr") => Ok(OutputFormat::Exr),
            _ => Err(Error::output(
                path,
                "unknown image format; the file name must end in .png or .exr",
            )),
        }
    }
}

/// A render destination made ready before rendering.
pub struct OutputFile {
    format: OutputFormat,
    file: AtomicFile,
}

impl OutputFile {
    /// Checks the format and that the destination's folder accepts a file.
    pub fn prepare(path: &Path) -> Result<Self> {
        let format = OutputFormat::from_path(path)?;
        Ok(OutputFile {
            format,
            file: AtomicFile::create(path)?,
        })
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Encodes `frame` and moves it into place. `exposure` (stops) applies
    /// to PNG only.
    pub fn write(self, frame: &Frame, exposure: f64) -> Result<()> {
        self.write_tone_mapped(frame, exposure, ToneMap::Clamp)
    }

    /// As [`Self::write`], a PNG tone-mapped by `tone_map` after the
    /// exposure (an EXR stays linear).
    pub fn write_tone_mapped(self, frame: &Frame, exposure: f64, tone_map: ToneMap) -> Result<()> {
        let bytes = match self.format {
            OutputFormat::Png => encode_png(frame, exposure, tone_map),
            OutputFormat::Exr => encode_exr(frame),
        }
        .map_err(|e| Error::output(self.file.path(), e))?;
        self.file.commit(&bytes)
    }
}

/// Linear radiance to an 8-bit sRGB value: scale by `2^exposure`, clamp,
/// encode, round (by table: [`srgb8`], the same codes). NaN maps to 0.
pub fn to_srgb8(radiance: f32, exposure: f64) -> u8 {
    srgb8((radiance as f64 * exposure.exp2()).clamp(0.0, 1.0))
}

/// One pixel's linear radiance to 8-bit sRGB: scale by `2^exposure`,
/// tone-map (`ToneMap::Clamp`: exactly [`to_srgb8`] per channel), encode,
/// round (by table: [`srgb8`], the same codes).
pub fn pixel_to_srgb8(radiance: [f32; 3], exposure: f64, tone_map: ToneMap) -> [u8; 3] {
    let scale = exposure.exp2();
    tone_map
        .apply(radiance.map(|c| c as f64 * scale))
        .map(srgb8)
}

fn encode_png(frame: &Frame, exposure: f64, tone_map: ToneMap) -> Result<Vec<u8>, String> {
    let pixels: Vec<u8> = frame
        .radiance
        .iter()
        .flat_map(|p| pixel_to_srgb8([p[0], p[1], p[2]], exposure, tone_map))
        .collect();
    let image = image::RgbImage::from_raw(frame.width, frame.height, pixels)
        .ok_or("frame size does not match its pixels")?;
    let mut out = Cursor::new(Vec::new());
    image
        .write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| format!("PNG encoding failed: {e}"))?;
    Ok(out.into_inner())
}

fn encode_exr(frame: &Frame) -> Result<Vec<u8>, String> {
    let pixels: Vec<f32> = frame.radiance.iter().flatten().copied().collect();
    let image = image::Rgb32FImage::from_raw(frame.width, frame.height, pixels)
        .ok_or("frame size does not match its pixels")?;
    let mut out = Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(image)
        .write_to(&mut out, image::ImageFormat::OpenExr)
        .map_err(|e| format!("EXR encoding failed: {e}"))?;
    Ok(out.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_known_values() {
        assert_eq!(to_srgb8(0.0, 0.0), 0);
        assert_eq!(to_srgb8(1.0, 0.0), 255);
        assert_eq!(to_srgb8(0.5, 1.0), 255);
        assert_eq!(to_srgb8(0.214_041_14, 0.0), 128); // sRGB 0.5 ≈ linear 0.2140
        assert_eq!(to_srgb8(f32::NAN, 0.0), 0);
    }

    /// The default tone map leaves every PNG byte as it was: the pixel
    /// path with `ToneMap::Clamp` equals the per-channel clamp on a sweep
    /// of values around every 8-bit boundary, special values and
    /// exposures.
    #[test]
    fn the_clamp_tone_map_is_byte_identical() {
        let mut values: Vec<f32> =
            vec![f32::NAN, f32::INFINITY, -f32::INFINITY, -1.0, 0.0, 1.0, 3.5];
        for k in 0..=255u32 {
            let v = k as f64 / 255.0;
            let lin = if v <= 0.04045 {
                v / 12.92
            } else {
                ((v + 0.055) / 1.055).powf(2.4)
            } as f32;
            values.extend([
                lin,
                f32::from_bits(lin.to_bits() + 1),
                f32::from_bits(lin.to_bits().saturating_sub(1)),
            ]);
        }
        for exposure in [0.0, -1.5, 2.0] {
            for w in values.windows(3) {
                let px = [w[0], w[1], w[2]];
                let want = px.map(|c| to_srgb8(c, exposure));
                assert_eq!(
                    pixel_to_srgb8(px, exposure, ToneMap::Clamp),
                    want,
                    "{px:?} at {exposure}"
                );
            }
        }
    }

    #[test]
    fn exr_round_trips_linear_values() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.exr");
        let mut frame = Frame::new(3, 2);
        frame.radiance[4] = [1.5, 1e-3, 1234.5];
        OutputFile::prepare(&path)
            .unwrap()
            .write(&frame, 0.0)
            .unwrap();
        let back = image::open(&path).unwrap().into_rgb32f();
        assert_eq!(back.get_pixel(1, 1).0, [1.5, 1e-3, 1234.5]);
    }

    #[test]
    fn failed_write_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        let out = OutputFile::prepare(&path).unwrap();
        drop(out); // e.g. rendering failed
        assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
        assert!(OutputFile::prepare(&dir.path().join("t.jpg")).is_err());
        assert!(OutputFile::prepare(&dir.path().join("missing/t.png")).is_err());
    }
}
