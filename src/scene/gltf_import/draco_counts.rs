//! The counts a Draco stream declares, checked before the decoder
//! allocates for them.
//!
//! draco-oxide's decoder (0.1.0-alpha.12) sizes its edgebreaker tables
//! from the stream's LEB128 counts as read: a face count of 2⁶⁰ is a
//! capacity-overflow panic (caught, [`super::hostile::guarded`]), but a
//! count just small enough to be a valid capacity is an allocation the
//! machine cannot make, and Rust aborts the process on that without
//! unwinding. Google's reference decoder refuses such streams
//! (`MeshEdgebreakerDecoderImpl::DecodeConnectivity`: "There cannot be
//! more vertices than 3 * num_faces", split symbols no more than
//! symbols, symbols no more than faces); the port does only part of it.
//! So gonio reads the header (Draco bitstream 2.2: magic, version,
//! geometry type, method, flags, the optional metadata section, then the
//! connectivity header) and holds the counts to the reference decoder's
//! rules, to what the glTF accessors declare (the extension requires the
//! decoded data to match them), to `--limit triangles|vertices`, and the
//! decoder's working memory to `--limit memory`.
//!
//! A stream this reader does not understand (another version, a point
//! cloud) is left to the decoder, which refuses those itself before
//! allocating.

use crate::scene::limits::Limits;

/// Bytes the decoder holds per face while it rebuilds edgebreaker
/// connectivity: three corners, each with an opposite corner, a vertex
/// and a point (8-byte indices), seam flags and attribute ranks
/// (reconstruct.rs, lazy.rs), about 170 bytes; rounded up.
const DECODER_BYTES_PER_FACE: u64 = 192;

/// Bytes per vertex or point: vertex-to-corner maps, hole flags and at
/// least one decoded 3-component attribute in 8-byte lanes.
const DECODER_BYTES_PER_VERTEX: u64 = 64;

/// What the glTF primitive declares for the decoded data.
pub(super) struct Declared {
    /// The `indices` accessor's count (three per face).
    pub indices: u64,
    /// The largest count among the attribute accessors the extension
    /// fills (every Draco point becomes one element of each).
    pub points: u64,
}

/// The counts of the connectivity header.
#[derive(Debug, PartialEq)]
enum Connectivity {
    Sequential {
        faces: u64,
        points: u64,
    },
    Edgebreaker {
        vertices: u64,
        faces: u64,
        symbols: u64,
        split_symbols: u64,
        topology_splits: u64,
        bytes_left: u64,
    },
    /// A header this reader leaves to the decoder.
    NotRead,
}

/// Checks the counts `stream` declares; `Err` says which count is
/// refused and why.
pub(super) fn check(stream: &[u8], declared: &Declared, limits: &Limits) -> Result<(), String> {
    let (faces, points) = match read(stream)? {
        Connectivity::NotRead => return Ok(()),
        Connectivity::Sequential { faces, points } => (faces, points),
        Connectivity::Edgebreaker {
            vertices,
            faces,
            symbols,
            split_symbols,
            topology_splits,
            bytes_left,
        } => {
            if vertices > faces.saturating_mul(3) {
                return Err(format!(
                    "the Draco stream declares {vertices} vertices for {faces} faces \
                     (at most three per face)"
                ));
            }
            if symbols > faces || split_symbols > symbols {
                return Err(format!(
                    "the Draco stream declares {symbols} symbols and {split_symbols} split \
                     symbols for {faces} faces (at most one symbol per face, at most one \
                     split per symbol)"
                ));
            }
            // Each topology split takes at least two bytes of the stream.
            if topology_splits > bytes_left / 2 {
                return Err(format!(
                    "the Draco stream declares {topology_splits} topology splits in \
                     {bytes_left} bytes"
                ));
            }
            (faces, vertices.saturating_add(split_symbols))
        }
    };
    if faces.saturating_mul(3) > declared.indices {
        return Err(format!(
            "the Draco stream declares {faces} faces, more than the `indices` accessor's \
             count of {} holds",
            declared.indices
        ));
    }
    if points > declared.points {
        return Err(format!(
            "the Draco stream declares {points} points, more than the attribute accessors' \
             count of {}",
            declared.points
        ));
    }
    let exceeded = crate::scene::limits::exceeded;
    if faces > limits.triangles {
        return Err(exceeded(
            "the Draco stream",
            format!("{faces} triangles"),
            "triangles",
            limits.triangles,
        ));
    }
    if points > limits.vertices {
        return Err(exceeded(
            "the Draco stream",
            format!("{points} vertices"),
            "vertices",
            limits.vertices,
        ));
    }
    let working = faces
        .saturating_mul(DECODER_BYTES_PER_FACE)
        .saturating_add(points.saturating_mul(DECODER_BYTES_PER_VERTEX));
    if working > limits.memory {
        return Err(exceeded(
            "decoding the Draco stream",
            format!("about {working} bytes"),
            "memory",
            limits.memory,
        ));
    }
    Ok(())
}

/// Reads the header and the connectivity counts of a Draco 2.2 mesh.
fn read(stream: &[u8]) -> Result<Connectivity, String> {
    let mut r = Cursor { bytes: stream };
    let truncated = |_| "the Draco stream ends inside its header".to_string();
    if r.take(5).map_err(truncated)? != b"DRACO" {
        return Ok(Connectivity::NotRead);
    }
    let (major, minor, geometry) = (
        r.u8().map_err(truncated)?,
        r.u8().map_err(truncated)?,
        r.u8().map_err(truncated)?,
    );
    if (major, minor, geometry) != (2, 2, 1) {
        return Ok(Connectivity::NotRead);
    }
    let method = r.u8().map_err(truncated)?;
    let flags = u16::from_le_bytes([r.u8().map_err(truncated)?, r.u8().map_err(truncated)?]);
    if flags & 0x8000 != 0 {
        skip_metadata(&mut r)?;
    }
    let counts = |_| "the Draco stream ends inside its connectivity header".to_string();
    match method {
        0 => Ok(Connectivity::Sequential {
            faces: r.leb128().map_err(counts)?,
            points: r.leb128().map_err(counts)?,
        }),
        1 => {
            let _traversal = r.u8().map_err(counts)?;
            let vertices = r.leb128().map_err(counts)?;
            let faces = r.leb128().map_err(counts)?;
            let _attribute_data = r.u8().map_err(counts)?;
            let symbols = r.leb128().map_err(counts)?;
            let split_symbols = r.leb128().map_err(counts)?;
            let topology_splits = r.leb128().map_err(counts)?;
            Ok(Connectivity::Edgebreaker {
                vertices,
                faces,
                symbols,
                split_symbols,
                topology_splits,
                bytes_left: r.bytes.len() as u64,
            })
        }
        _ => Ok(Connectivity::NotRead),
    }
}

/// Skips the metadata section as the decoder reads it
/// (draco-oxide-decoder metadata.rs; Draco's `MetadataDecoder`): a count
/// of per-attribute blocks, each an id and a block, then the geometry's
/// block; a block is entries (name, value) then named sub-blocks, nested
/// at most 1000 deep. Every loop step consumes at least one byte, so a
/// huge count ends at the stream's end.
fn skip_metadata(r: &mut Cursor) -> Result<(), String> {
    const MAX_LEVEL: usize = 1000;
    fn block(r: &mut Cursor, level: usize) -> Result<(), ()> {
        if level > MAX_LEVEL {
            return Err(());
        }
        for _ in 0..r.leb128()? {
            let name = r.u8()?;
            r.take(name as u64)?;
            let size = r.leb128()?;
            r.take(size)?;
        }
        for _ in 0..r.leb128()? {
            let name = r.u8()?;
            r.take(name as u64)?;
            block(r, level + 1)?;
        }
        Ok(())
    }
    let bad = |_| "the Draco stream's metadata section is truncated or nested too deeply";
    for _ in 0..r.leb128().map_err(bad)? {
        r.leb128().map_err(bad)?;
        block(r, 0).map_err(bad)?;
    }
    block(r, 0).map_err(bad)?;
    Ok(())
}

/// A byte reader that fails at the end of its slice.
struct Cursor<'a> {
    bytes: &'a [u8],
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: u64) -> Result<&'a [u8], ()> {
        let n = usize::try_from(n).map_err(|_| ())?;
        if n > self.bytes.len() {
            return Err(());
        }
        let (head, tail) = self.bytes.split_at(n);
        self.bytes = tail;
        Ok(head)
    }

    fn u8(&mut self) -> Result<u8, ()> {
        Ok(self.take(1)?[0])
    }

    /// An unsigned LEB128 value of at most 64 bits.
    fn leb128(&mut self) -> Result<u64, ()> {
        let mut value = 0u64;
        for shift in (0..64).step_by(7) {
            let byte = self.u8()?;
            value |= u64::from(byte & 0x7f) << shift;
            if byte & 0x80 == 0 {
                return Ok(value);
            }
        }
        Err(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Draco 2.2 edgebreaker mesh header with the given counts.
    fn edgebreaker(vertices: u64, faces: u64, symbols: u64, splits: u64) -> Vec<u8> {
        let mut s = b"DRACO".to_vec();
        s.extend([2, 2, 1, 1, 0, 0, 0]);
        for v in [vertices, faces] {
            leb(&mut s, v);
        }
        s.push(0);
        for v in [symbols, splits, 0] {
            leb(&mut s, v);
        }
        s
    }

    fn leb(out: &mut Vec<u8>, mut v: u64) {
        loop {
            let byte = (v & 0x7f) as u8;
            v >>= 7;
            if v == 0 {
                out.push(byte);
                return;
            }
            out.push(byte | 0x80);
        }
    }

    const ROOMY: Declared = Declared {
        indices: 3 << 20,
        points: 1 << 20,
    };

    #[test]
    fn plausible_counts_pass() {
        let stream = edgebreaker(500, 1000, 1000, 2);
        assert_eq!(check(&stream, &ROOMY, &Limits::default()), Ok(()));
    }

    #[test]
    fn a_face_count_past_the_accessor_is_refused_before_decoding() {
        // 2^58 faces: a valid-looking capacity whose allocation would abort.
        let stream = edgebreaker(3, 1 << 58, 1, 0);
        let e = check(&stream, &ROOMY, &Limits::default()).unwrap_err();
        assert!(e.contains("faces, more than the `indices`"), "{e}");
    }

    #[test]
    fn more_vertices_than_three_per_face_is_refused() {
        let stream = edgebreaker(3001, 1000, 1000, 0);
        let e = check(&stream, &ROOMY, &Limits::default()).unwrap_err();
        assert!(e.contains("at most three per face"), "{e}");
    }

    #[test]
    fn more_split_symbols_than_symbols_is_refused() {
        let stream = edgebreaker(10, 10, 5, 6);
        assert!(check(&stream, &ROOMY, &Limits::default()).is_err());
    }

    #[test]
    fn the_decoder_memory_is_held_to_the_memory_limit() {
        let stream = edgebreaker(1 << 19, 1 << 20, 1 << 20, 0);
        let small = Limits {
            memory: 1 << 20,
            ..Limits::default()
        };
        let e = check(&stream, &ROOMY, &small).unwrap_err();
        assert!(e.contains("memory"), "{e}");
    }

    #[test]
    fn metadata_is_skipped_and_a_truncated_section_refused() {
        let mut s = b"DRACO".to_vec();
        s.extend([2, 2, 1, 0, 0x00, 0x80]);
        // One attribute block (id 0: one entry "a" = [7]), empty geometry block.
        s.extend([1, 0, 1, 1, b'a', 1, 7, 0, 0, 0]);
        leb(&mut s, 4);
        leb(&mut s, 6);
        assert_eq!(
            read(&s),
            Ok(Connectivity::Sequential {
                faces: 4,
                points: 6
            })
        );
        assert!(read(&s[..14]).is_err());
    }

    #[test]
    fn other_streams_are_left_to_the_decoder() {
        assert_eq!(read(b"DRACO\x02\x03\x00"), Ok(Connectivity::NotRead));
        assert_eq!(read(b"NOTDRACO"), Ok(Connectivity::NotRead));
    }
}
