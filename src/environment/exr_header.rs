//! A look at an OpenEXR file's headers before the `exr` crate decodes it.
//!
//! The `exr` crate sizes its block buffers from what a header declares —
//! a tile's `xSize × ySize` (the `tiles` attribute), a chunk table of
//! `chunkCount` entries — and allocates them before it finds the data
//! missing. The environment_map fuzz target found a 719-byte file
//! declaring an 8 × 4 image in tiles of 6,094,912 × 16,384 texels, which
//! made the decoder allocate 1.7 GB; `image`'s `max_alloc` does not reach
//! inside. So gonio reads the headers itself (the layout is the OpenEXR
//! file format document's, "File Layout": magic, version field, then
//! `name\0type\0size value` attributes ending in an empty name; a
//! multi-part file has one such header per part, ending in an empty
//! header) and refuses a block or chunk table larger than the decode
//! budget before any of it is allocated.

/// OpenEXR's magic number, the file's first four bytes.
const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];
/// Version-field flags ("File Layout", version field).
const NON_IMAGE: u32 = 0x800;
const MULTI_PART: u32 = 0x1000;

/// Checks that no header of `bytes` declares more than `max_texels`
/// texels, no block larger than what its texels decode to (the budget
/// [`super::load::decode`] gives `image`, twice 16 bytes a texel plus
/// 1 MiB), no chunk table has more entries than the file has
/// room for, and no part holds deep (non-image) data, which gonio does
/// not read. One sentence on failure.
pub fn check(bytes: &[u8], max_texels: u64) -> Result<(), String> {
    let mut at = Cursor { bytes, at: 0 };
    if at.take(4)? != MAGIC {
        return Err(
            "it is not a readable exr image: it does not start with OpenEXR's magic number".into(),
        );
    }
    let version = at.u32()?;
    if version & NON_IMAGE != 0 {
        return Err("it holds deep (non-image) data, which is not a map".into());
    }
    loop {
        let header = read_header(&mut at)?;
        header.check(bytes.len() as u64, max_texels)?;
        if version & MULTI_PART == 0 || at.peek() == Some(0) {
            return Ok(());
        }
    }
}

/// What one header declares that sizes the decoder's buffers.
#[derive(Default)]
struct Header {
    /// `dataWindow` width and height, when present.
    window: Option<(u64, u64)>,
    /// `tiles`: the tile's width and height.
    tile: Option<(u64, u64)>,
    /// Bytes per texel over all channels of `channels`.
    texel_bytes: u64,
    chunk_count: Option<u64>,
    deep: bool,
}

fn read_header(at: &mut Cursor) -> Result<Header, String> {
    let mut header = Header::default();
    loop {
        let name = at.text()?;
        if name.is_empty() {
            return Ok(header);
        }
        let kind = at.text()?;
        // The `exr` crate reads a type name's first byte whatever it is:
        // an empty one would make it read a different header than this.
        if kind.is_empty() {
            return Err(format!(
                "its OpenEXR header's attribute `{}` has no type",
                name.escape_debug()
            ));
        }
        let size = at.u32()?;
        let value = at.take(size as usize)?;
        let mut v = Cursor {
            bytes: value,
            at: 0,
        };
        match (name, kind) {
            ("dataWindow", "box2i") => {
                let (x0, y0, x1, y1) = (v.i32()?, v.i32()?, v.i32()?, v.i32()?);
                let side = |a: i32, b: i32| (i64::from(b) - i64::from(a) + 1).max(0) as u64;
                header.window = Some((side(x0, x1), side(y0, y1)));
            }
            ("tiles", "tiledesc") => header.tile = Some((v.u32()?.into(), v.u32()?.into())),
            ("channels", "chlist") => header.texel_bytes = channel_bytes(&mut v)?,
            ("chunkCount", "int") => header.chunk_count = Some(v.i32()?.max(0) as u64),
            ("type", "string") => header.deep = value.starts_with(b"deep"),
            _ => {}
        }
    }
}

/// Bytes per texel of a `chlist` value: each channel is `name\0`, a pixel
/// type (0 uint, 1 half, 2 float), then 12 bytes of linearity and
/// sampling; the list ends in an empty name.
fn channel_bytes(v: &mut Cursor) -> Result<u64, String> {
    let mut total = 0;
    loop {
        if v.text()?.is_empty() {
            return Ok(total);
        }
        total += if v.i32()? == 1 { 2 } else { 4 };
        v.take(12)?;
    }
}

impl Header {
    fn check(&self, file_bytes: u64, max_texels: u64) -> Result<(), String> {
        if self.deep {
            return Err("it holds deep (non-image) data, which is not a map".into());
        }
        let (width, height) = self.window.unwrap_or((0, 0));
        let texels = width.saturating_mul(height);
        if texels > max_texels {
            return Err(format!(
                "its data window is {width} × {height} texels, over the {max_texels} this load allows"
            ));
        }
        let budget = 2 * 16 * texels + (1 << 20);
        if let Some(count) = self.chunk_count
            && count.saturating_mul(8) > file_bytes
        {
            return Err(format!(
                "its header declares {count} chunks, more than a file of {file_bytes} bytes has room for: the file is truncated or corrupt"
            ));
        }
        let texel = self.texel_bytes.max(4);
        // A `tiles` attribute sizes the blocks whatever the version flag
        // says (a multi-part file marks tiles per part, by `type`).
        let block = match self.tile {
            Some((w, h)) => Some(("a tile", w, h)),
            // Scan-line blocks are at most 256 lines (PXR24/B44 use 16, ZIP
            // 16, PIZ 32, DWAB 256) of the data window's width.
            _ => self.window.map(|(w, _)| ("a block of scan lines", w, 256)),
        };
        if let Some((what, w, h)) = block {
            let size = w.saturating_mul(h).saturating_mul(texel);
            if size > budget {
                return Err(format!(
                    "its header declares {what} of {w} × {h} texels ({size} bytes), more than the {budget} bytes this map may decode to: the file is corrupt"
                ));
            }
            // Every block has an 8-byte entry in the chunk table, which
            // the decoder allocates from this count, not from the file.
            let blocks = width.div_ceil(w.max(1)) * height.div_ceil(h.max(1));
            if blocks.saturating_mul(8) > file_bytes {
                return Err(format!(
                    "its header declares {width} × {height} texels in at least {blocks} blocks, whose chunk table alone is more than the file's {file_bytes} bytes: the file is truncated or corrupt"
                ));
            }
        }
        Ok(())
    }
}

/// Bounds-checked little-endian reads; running out is the one error.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or("its OpenEXR header is truncated")?;
        let slice = &self.bytes[self.at..end];
        self.at = end;
        Ok(slice)
    }
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.at).copied()
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    fn i32(&mut self) -> Result<i32, String> {
        Ok(i32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    /// A null-terminated attribute name or type (at most 255 bytes with
    /// the long-names flag; not UTF-8 is read as no known name).
    fn text(&mut self) -> Result<&'a str, String> {
        let rest = &self.bytes[self.at..];
        let len = rest.iter().take(256).position(|&b| b == 0);
        let len = len.ok_or("its OpenEXR header has an attribute name without its end")?;
        let text = std::str::from_utf8(&rest[..len]).unwrap_or("\u{fffd}");
        self.at += len + 1;
        Ok(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A single-part header of the given attributes.
    fn file(version: u32, attributes: &[(&str, &str, Vec<u8>)]) -> Vec<u8> {
        let mut out = MAGIC.to_vec();
        out.extend(version.to_le_bytes());
        for (name, kind, value) in attributes {
            out.extend(name.as_bytes());
            out.push(0);
            out.extend(kind.as_bytes());
            out.push(0);
            out.extend((value.len() as u32).to_le_bytes());
            out.extend(value);
        }
        out.push(0);
        out.extend([0; 64]);
        out
    }

    fn words(values: &[u32]) -> Vec<u8> {
        values.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    fn rgb_float() -> Vec<u8> {
        let mut list = Vec::new();
        for name in ["B", "G", "R"] {
            list.extend(name.as_bytes());
            list.push(0);
            list.extend(words(&[2, 0, 1, 1]));
        }
        list.push(0);
        list
    }

    #[test]
    fn a_tile_larger_than_the_budget_is_refused_before_decoding() {
        let window = ("dataWindow", "box2i", words(&[0, 0, 7, 3]));
        let tiled = |w, h| {
            file(
                2 | 0x200, // the version field's single-part tiled flag
                &[
                    ("channels", "chlist", rgb_float()),
                    window.clone(),
                    ("tiles", "tiledesc", [words(&[w, h]), vec![0]].concat()),
                ],
            )
        };
        // The fuzz finding's tile: 6,094,912 × 16,384.
        let e = check(&tiled(0x005d_0040, 0x4000), 1 << 20).unwrap_err();
        assert!(e.contains("a tile of 6094912 × 16384 texels"), "{e}");
        let e = check(&tiled(64, 64), 16).unwrap_err();
        assert!(e.contains("8 × 4 texels, over the 16"), "{e}");
        // A 64² tile on an 8 × 4 image is ordinary: 48 KiB.
        check(&tiled(64, 64), 1 << 20).unwrap();
        // 1 × 1 tiles: 32 chunks, a 256-byte table the 88-byte file lacks.
        let e = check(&tiled(1, 1), 1 << 20).unwrap_err();
        assert!(e.contains("at least 32 blocks"), "{e}");
    }

    #[test]
    fn chunk_tables_deep_data_and_truncation_are_refused() {
        let count = ("chunkCount", "int", words(&[1 << 30]));
        let e = check(&file(2, &[count]), 1 << 20).unwrap_err();
        assert!(e.contains("1073741824 chunks"), "{e}");
        let deep = ("type", "string", b"deepscanline".to_vec());
        let e = check(&file(2, &[deep]), 1 << 20).unwrap_err();
        assert!(e.contains("deep"), "{e}");
        let whole = file(2, &[("channels", "chlist", rgb_float())]);
        let e = check(&whole[..20], 1 << 20).unwrap_err();
        assert!(
            e.contains("truncated") || e.contains("without its end"),
            "{e}"
        );
        assert!(
            check(b"\x89PNG....", 1 << 20)
                .unwrap_err()
                .contains("magic")
        );
        let e = check(&file(2, &[("x", "", vec![])]), 1 << 20).unwrap_err();
        assert!(e.contains("`x` has no type"), "{e}");
    }

    #[test]
    fn ordinary_exr_files_pass() {
        let seeds = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/corpus/environment_map/");
        // Each seed's first byte picks the format (fuzz_targets/environment_map.rs).
        let seed = |name: &str| std::fs::read(format!("{seeds}{name}")).unwrap()[1..].to_vec();
        check(&seed("small.exr"), 1 << 20).unwrap();
        check(&seed("nan-texel.exr"), 1 << 20).unwrap();
    }
}
