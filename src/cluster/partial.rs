//! A partial image: the rows of one shard of a reference render, as an
//! OpenEXR file a viewer opens (the shard's rows stacked, 32-bit float
//! RGB, lossless ZIP) whose header says what the merge needs.
//!
//! Header attributes (OpenEXR allows any named attribute; these are
//! text):
//! - `gonio.shard` = `I/N`: shard I of N; the file holds image rows
//!   `I−1, I−1+N, …` in that order ([`Shard::items`]).
//! - `gonio.image` = `WxH`: the whole image's size.
//! - `gonio.key`: a SHA-256 of the render's inputs as loaded ([`key`]), so
//!   that parts of different scenes, settings or gonio versions are never
//!   merged.
//! - `gonio.tone_map`: the scene's `image.tone_map`, which a PNG made by
//!   the merge applies as `gonio render` would.
//!
//! The file is written as every gonio output is ([`AtomicFile`]): a
//! partial file that exists is complete, which is what makes a shard
//! restartable (an existing file with this shard and key is skipped).

use super::shard::Shard;
use crate::frame::Frame;
use crate::output::AtomicFile;
use crate::output::tone_map::ToneMap;
use crate::scene::Scene;
use crate::{Error, Result};
use exr::prelude::{self as x, ReadChannels, ReadLayers, WritableImage};
use sha2::{Digest, Sha256};
use std::path::Path;

const SHARD: &str = "gonio.shard";
const IMAGE: &str = "gonio.image";
const KEY: &str = "gonio.key";
const TONE_MAP: &str = "gonio.tone_map";

/// What a partial file's header says.
#[derive(Clone, Debug, PartialEq)]
pub struct Header {
    pub shard: Shard,
    pub width: u32,
    pub height: u32,
    pub key: String,
    pub tone_map: ToneMap,
}

impl Header {
    /// The header of `shard` of a render of `scene`.
    pub fn new(scene: &Scene, shard: Shard) -> Self {
        Header {
            shard,
            width: scene.width,
            height: scene.height,
            key: key(scene),
            tone_map: scene.tone_map,
        }
    }

    /// The number of image rows this shard holds.
    pub fn rows(&self) -> usize {
        self.shard.items(self.height as usize).count()
    }

    /// `a 80x60 image in 8 shards (key 1a2b3c4d5e6f…)`, for messages.
    pub fn describe_render(&self) -> String {
        format!(
            "a {}x{} image in {} shards (key {}…)",
            self.width,
            self.height,
            self.shard.count,
            &self.key[..12.min(self.key.len())]
        )
    }

    /// `shard 3/8 of a 80x60 image (key 1a2b3c4d5e6f…)`, for messages.
    pub fn describe(&self) -> String {
        format!(
            "shard {} of a {}x{} image (key {}…)",
            self.shard,
            self.width,
            self.height,
            &self.key[..12.min(self.key.len())]
        )
    }
}

/// A SHA-256 (hex) of everything that decides the reference image: the
/// scene as loaded (every mesh, material, light, texture and setting,
/// with `--set`, `--width` and the rest applied) through its `Debug`
/// form, which prints every field, floats in shortest round-trip form,
/// and gonio's version. Two loads of the same inputs give the same key
/// in any process on any machine; any change to what is rendered
/// changes it.
pub fn key(scene: &Scene) -> String {
    struct Hasher(Sha256);
    impl std::fmt::Write for Hasher {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            self.0.update(s.as_bytes());
            Ok(())
        }
    }
    let mut h = Hasher(Sha256::new());
    let _ = std::fmt::write(
        &mut h,
        format_args!("gonio {} reference\n{scene:?}", env!("CARGO_PKG_VERSION")),
    );
    h.0.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// Encodes the shard's rows `rows` (a frame of `width × header.rows()`
/// pixels from `crate::reference::render_rows`) and moves the file into
/// place.
pub fn write(file: AtomicFile, header: &Header, rows: &Frame) -> Result<()> {
    debug_assert_eq!(rows.height as usize, header.rows());
    let width = rows.width as usize;
    let mut attributes = x::LayerAttributes::named("gonio partial render");
    for (name, value) in [
        (SHARD, header.shard.to_string()),
        (IMAGE, format!("{}x{}", header.width, header.height)),
        (KEY, header.key.clone()),
        (TONE_MAP, header.tone_map.to_string()),
    ] {
        attributes.other.insert(
            x::Text::from(name),
            x::AttributeValue::Text(x::Text::from(value.as_str())),
        );
    }
    let layer = x::Layer::new(
        (width, rows.height as usize),
        attributes,
        x::Encoding::SMALL_LOSSLESS,
        x::SpecificChannels::rgb(|p: x::Vec2<usize>| {
            let [r, g, b] = rows.radiance[p.y() * width + p.x()];
            (r, g, b)
        }),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    x::Image::from_layer(layer)
        .write()
        .non_parallel()
        .to_buffered(&mut bytes)
        .map_err(|e| Error::output(file.path(), format!("EXR encoding failed: {e}")))?;
    file.commit(&bytes.into_inner())
}

/// Reads the header of the partial file `path` (not its pixels).
pub fn read_header(path: &Path) -> Result<Header> {
    let not_partial = |problem: String| {
        Error::input(
            path,
            format!("not a partial image of `gonio render --reference --shard`: {problem}"),
        )
    };
    let meta = x::MetaData::read_from_file(path, false)
        .map_err(|e| not_partial(format!("cannot read it as OpenEXR ({e})")))?;
    let [header] = meta.headers.as_slice() else {
        return Err(not_partial(format!(
            "it has {} parts, a partial image has one",
            meta.headers.len()
        )));
    };
    let text = |name: &str| -> Result<String> {
        match header.own_attributes.other.get(&x::Text::from(name)) {
            Some(x::AttributeValue::Text(t)) => Ok(t.to_string()),
            _ => Err(not_partial(format!("its header has no `{name}` text"))),
        }
    };
    let bad = |name: &str, value: &str| not_partial(format!("`{name}` = `{value}` is malformed"));
    let shard_text = text(SHARD)?;
    let (shard, _) = Shard::parse(&shard_text, |_| None)
        .ok()
        .filter(|_| !shard_text.starts_with("auto"))
        .ok_or_else(|| bad(SHARD, &shard_text))?;
    let image = text(IMAGE)?;
    let (width, height) = image
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| bad(IMAGE, &image))?;
    let tone_text = text(TONE_MAP)?;
    let tone_map = tone_text
        .parse::<ToneMap>()
        .map_err(|_| bad(TONE_MAP, &tone_text))?;
    let parsed = Header {
        shard,
        width,
        height,
        key: text(KEY)?,
        tone_map,
    };
    let size = header.layer_size;
    if (size.x(), size.y()) != (width as usize, parsed.rows()) {
        return Err(not_partial(format!(
            "it holds {}x{} pixels where {} has {}x{}",
            size.x(),
            size.y(),
            parsed.describe(),
            width,
            parsed.rows()
        )));
    }
    Ok(parsed)
}

/// The shard's rows of the partial file `path` (`header` from
/// [`read_header`]), row-major, as written.
pub fn read_rows(path: &Path, header: &Header) -> Result<Vec<[f32; 3]>> {
    let width = header.width as usize;
    let image = x::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size, _| vec![[0.0f32; 3]; size.area()],
            move |pixels: &mut Vec<[f32; 3]>, p: x::Vec2<usize>, (r, g, b): (f32, f32, f32)| {
                pixels[p.y() * width + p.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_file(path)
        .map_err(|e| Error::input(path, format!("cannot read the partial image's pixels: {e}")))?;
    let pixels = image.layer_data.channel_data.pixels;
    if pixels.len() != width * header.rows() {
        return Err(Error::input(
            path,
            format!(
                "holds {} pixels, {} has {}",
                pixels.len(),
                header.describe(),
                width * header.rows()
            ),
        ));
    }
    Ok(pixels)
}

/// Whether `path` already holds the complete output of `header`'s shard
/// (same shard, size and key): the shard's work is done. `Err` carries
/// why an existing file does not count (it is then replaced).
pub fn is_done(path: &Path, header: &Header) -> std::result::Result<bool, String> {
    if !path.exists() {
        return Ok(false);
    }
    match read_header(path) {
        Ok(h) if &h == header => Ok(true),
        Ok(h) => Err(format!(
            "it holds {}, not {}",
            h.describe(),
            header.describe()
        )),
        Err(e) => Err(e.to_string()),
    }
}
