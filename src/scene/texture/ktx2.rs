//! KTX2 textures with Basis Universal payloads (`KHR_texture_basisu`):
//! ETC1S (BasisLZ) or UASTC, the latter optionally Zstandard-
//! supercompressed. The base level of the first layer and face is
//! transcoded to uncompressed RGBA8 by the `basisu` crate (a port of the
//! reference transcoder, `basisu_transcoder.cpp`), and then read like an
//! 8-bit PNG: the texture's slot decides sRGB or linear, as glTF asks
//! (KHR_texture_basisu: the transfer function follows the material slot),
//! and gonio builds its own mip chain.

/// The 12-byte KTX 2.0 identifier («KTX 20»\r\n\x1A\n).
pub const MAGIC: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

/// Whether `bytes` start as a KTX2 file.
pub fn is_ktx2(bytes: &[u8]) -> bool {
    bytes.starts_with(&MAGIC)
}

fn transcoder(bytes: &[u8]) -> Result<basisu::Transcoder<'_>, String> {
    super::ktx2_layout::check_layout(bytes)?;
    guarded(|| basisu::Transcoder::new(bytes))?.map_err(|e| {
        format!("it is a KTX2 file gonio cannot read as Basis Universal ({e:?}); glTF's KHR_texture_basisu needs ETC1S or UASTC data")
    })
}

/// Runs the transcoder, turning a panic in it (malformed data it did not
/// anticipate; none is known) into an error, its text kept off stderr.
fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    crate::base::quiet_panic::catch_quietly(f)
        .ok_or_else(|| "it is a corrupt KTX2 texture (the transcoder failed on it)".to_string())
}

/// The base level's size, from the header alone.
pub fn dimensions(bytes: &[u8]) -> Result<(u32, u32), String> {
    Ok(transcoder(bytes)?.base_dimensions())
}

/// The base level as RGBA8, row 0 at the top (KHR_texture_basisu requires
/// the KTX2 orientation "rd", glTF's own). The size was checked against
/// the limits by the caller.
pub fn transcode_rgba8(bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), String> {
    let texture = transcoder(bytes)?;
    let (width, height) = texture.base_dimensions();
    let rgba = guarded(|| {
        texture.transcode_image(
            0,
            0,
            0,
            basisu::TargetFormat::Rgba32,
            basisu::DecodeFlags::NONE,
        )
    })?
    .map_err(|e| format!("it is a corrupt or unsupported KTX2 texture ({e:?})"))?;
    if rgba.len() as u64 != u64::from(width) * u64::from(height) * 4 {
        return Err(format!(
            "its transcoded base level has {} bytes, not the {width}×{height}×4 its header declares",
            rgba.len()
        ));
    }
    Ok((width, height, rgba))
}
