//! Compressed glTF: the extensions whose data must be decoded before the
//! file can be read, all resolved here into what an uncompressed file
//! says, so the rest of the import (and every check it makes) runs
//! unchanged on the result.
//!
//! - Geometry: `EXT_meshopt_compression` / `KHR_meshopt_compression`
//!   buffer views (`meshopt`) and `KHR_draco_mesh_compression` primitives
//!   (`draco`) are decoded into new buffers, and the views and accessors
//!   are pointed at them.
//! - Images: a texture's `KHR_texture_basisu` or `EXT_texture_webp`
//!   `source` replaces its fallback `source` ([`use_extension_sources`]);
//!   the image itself is recognised by its bytes when it is decoded
//!   (`scene::texture::decode`).

use crate::scene::limits::Limits;
use std::borrow::Cow;

/// The texture extensions whose `source` gonio reads, in order of
/// preference: KTX2 (Basis Universal) first, then WebP.
const IMAGE_EXTENSIONS: [&str; 2] = ["KHR_texture_basisu", "EXT_texture_webp"];

/// Points each texture with an image extension at the extension's image.
/// An index out of range is left for validation to report (it checks
/// `source` against the images).
pub(super) fn use_extension_sources(root: &mut gltf::json::Root) -> Result<(), String> {
    for (index, texture) in root.textures.iter_mut().enumerate() {
        let Some(others) = texture.extensions.as_ref().map(|e| &e.others) else {
            continue;
        };
        for name in IMAGE_EXTENSIONS {
            let Some(value) = others.get(name) else {
                continue;
            };
            let source = value
                .get("source")
                .and_then(serde_json::Value::as_u64)
                .and_then(|s| u32::try_from(s).ok())
                .filter(|&s| s != u32::MAX)
                .ok_or_else(|| {
                    format!("texture {index}: {name}: `source` is missing or not an image index")
                })?;
            texture.source = gltf::json::Index::new(source);
            break;
        }
    }
    Ok(())
}

/// A document with its buffers, the compressed parts decoded.
type Decoded<'b> = (gltf::Document, Vec<Cow<'b, [u8]>>);

/// Decodes the compressed buffer views and primitives of `document`;
/// returns the document and buffers as if the file had been uncompressed.
/// The decoded bytes count against `limits.bytes` with `used_bytes`.
pub(super) fn decode<'b>(
    document: gltf::Document,
    mut buffers: Vec<Cow<'b, [u8]>>,
    used_bytes: &mut u64,
    limits: &Limits,
) -> Result<Decoded<'b>, String> {
    let mut root = document.into_json();
    super::meshopt::decode_views(&mut root, &mut buffers, used_bytes, limits.bytes)?;
    super::draco::decode_primitives(&mut root, &mut buffers, used_bytes, limits)?;
    Ok((gltf::Document::from_json_without_validation(root), buffers))
}
