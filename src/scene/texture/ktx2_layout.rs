//! The KTX 2.0 file layout, checked before the Basis transcoder sees a
//! file: every region the header points at (the data format descriptor,
//! the key/value data, the supercompression global data and each mip
//! level) must lie inside the file, and a level's declared uncompressed
//! length must fit the largest payload a Basis texture of the header's
//! size can have.
//!
//! Why: the transcoder trusts these fields. A Zstandard-supercompressed
//! level whose `uncompressedByteLength` says 2⁴⁸ bytes makes it allocate
//! that much, and an allocation failure aborts the process (it cannot be
//! caught like a panic). Found by fuzzing the `ktx2_texture` target;
//! the reproducer is in `fuzz/corpus/ktx2_texture/`.
//!
//! Layout: KTX 2.0 specification (Khronos, 2020), section 3 "File
//! Structure": a 12-byte identifier, nine u32 header fields, the
//! index (four u32, two u64) and then `levelCount` (at least 1) level
//! entries of three u64, all little-endian.

/// Bytes of the identifier, header and index before the level index.
const LEVEL_INDEX_OFFSET: usize = 80;

/// Bytes of one level-index entry (`byteOffset`, `byteLength`,
/// `uncompressedByteLength`).
const LEVEL_ENTRY_BYTES: usize = 24;

/// The supercompression scheme of Zstandard (KTX 2.0 §3.1.4, table 2).
const ZSTANDARD: u32 = 2;

/// Bytes per 4×4 block of the largest Basis payload (UASTC: 128 bits per
/// block; ETC1S levels are smaller and BasisLZ-compressed).
const MAX_BLOCK_BYTES: u64 = 16;

fn u32_at(bytes: &[u8], at: usize) -> Result<u32, String> {
    bytes
        .get(at..at + 4)
        .map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
        .ok_or_else(|| "it is a truncated KTX2 file (its header is cut short)".to_string())
}

fn u64_at(bytes: &[u8], at: usize) -> Result<u64, String> {
    bytes
        .get(at..at + 8)
        .map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")))
        .ok_or_else(|| "it is a truncated KTX2 file (its level index is cut short)".to_string())
}

/// Checks that the region `name` at `offset`, `length` lies inside a file
/// of `size` bytes.
fn inside(name: &str, offset: u64, length: u64, size: u64) -> Result<(), String> {
    match offset.checked_add(length) {
        Some(end) if end <= size => Ok(()),
        _ => Err(format!(
            "it is a corrupt KTX2 file: its {name} ({length} bytes at offset {offset}) lies outside the file's {size} bytes"
        )),
    }
}

/// Checks the header's regions and level lengths against the file (see
/// the module doc); `Ok` says nothing of the payload itself, which the
/// transcoder reads.
pub fn check_layout(bytes: &[u8]) -> Result<(), String> {
    let size = bytes.len() as u64;
    let width = u64::from(u32_at(bytes, 20)?);
    let height = u64::from(u32_at(bytes, 24)?).max(1);
    let depth = u64::from(u32_at(bytes, 28)?).max(1);
    let layers = u64::from(u32_at(bytes, 32)?).max(1);
    let faces = u64::from(u32_at(bytes, 36)?).max(1);
    let levels = u32_at(bytes, 40)?.max(1);
    let scheme = u32_at(bytes, 44)?;
    let regions = [
        ("data format descriptor", 48, 52),
        ("key/value data", 56, 60),
    ];
    for (name, offset_at, length_at) in regions {
        let (offset, length) = (u32_at(bytes, offset_at)?, u32_at(bytes, length_at)?);
        inside(name, offset.into(), length.into(), size)?;
    }
    inside(
        "supercompression global data",
        u64_at(bytes, 64)?,
        u64_at(bytes, 72)?,
        size,
    )?;
    // A level count beyond the bits of the largest side is corrupt (and
    // keeps the loop below short whatever the header says).
    if levels > 32 {
        return Err(format!(
            "it is a corrupt KTX2 file: it declares {levels} mip levels"
        ));
    }
    for level in 0..levels {
        let at = LEVEL_INDEX_OFFSET + level as usize * LEVEL_ENTRY_BYTES;
        let (offset, length) = (u64_at(bytes, at)?, u64_at(bytes, at + 8)?);
        inside(&format!("mip level {level}"), offset, length, size)?;
        let blocks = |side: u64| (side >> level).max(1).div_ceil(4);
        let most = blocks(width)
            .saturating_mul(blocks(height))
            .saturating_mul(depth)
            .saturating_mul(layers)
            .saturating_mul(faces)
            .saturating_mul(MAX_BLOCK_BYTES);
        let uncompressed = u64_at(bytes, at + 16)?;
        if scheme == ZSTANDARD && uncompressed > most {
            return Err(format!(
                "it is a corrupt KTX2 file: mip level {level} declares {uncompressed} uncompressed bytes, more than the {most} a {width}×{height} Basis texture can hold"
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A minimal header: 8×8, one level of `length` bytes at offset 104,
    /// Zstandard, `uncompressed` declared.
    fn header(uncompressed: u64, length: u64) -> Vec<u8> {
        let mut b = super::super::ktx2::MAGIC.to_vec();
        for v in [0u32, 1, 8, 8, 0, 0, 1, 1, ZSTANDARD, 0, 0, 0, 0] {
            b.extend(v.to_le_bytes());
        }
        for v in [0u64, 0, 104, length, uncompressed] {
            b.extend(v.to_le_bytes());
        }
        b.resize(104 + 16, 0);
        b
    }

    #[test]
    fn a_level_inside_the_bound_passes() {
        // 8×8 is 2×2 blocks: at most 64 bytes of UASTC.
        assert_eq!(check_layout(&header(64, 16)), Ok(()));
    }

    #[test]
    fn an_uncompressed_length_past_the_bound_is_refused() {
        let e = check_layout(&header(1 << 48, 16)).unwrap_err();
        assert!(e.contains("uncompressed bytes"), "{e}");
    }

    #[test]
    fn a_level_past_the_end_is_refused() {
        let e = check_layout(&header(64, 17)).unwrap_err();
        assert!(e.contains("mip level 0"), "{e}");
    }

    #[test]
    fn a_short_header_is_refused() {
        assert!(check_layout(&super::super::ktx2::MAGIC).is_err());
    }
}
