//! Buffers: the GLB `BIN` chunk, base64 `data:` URIs, or files inside the
//! glTF's folder. The `gltf` crate's own loader is not used: it follows any
//! path, reads whole files whatever their declared length, and knows no
//! limits.

use super::hostile::abbreviate;
use crate::scene::limits::{Limits, ReadError, exceeded};
use base64::Engine as _;
use std::borrow::Cow;
use std::fs::File;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Loads every buffer of the document, in order. The BIN chunk is borrowed,
/// not copied. The declared lengths of all other buffers are added to
/// `used_bytes` and checked against the limit before any is read.
pub(super) fn load<'b>(
    document: &gltf::Document,
    bin: Option<&'b [u8]>,
    folder: &Path,
    used_bytes: &mut u64,
    limits: &Limits,
) -> Result<Vec<Cow<'b, [u8]>>, String> {
    reserve(document, used_bytes, limits)?;
    document
        .buffers()
        .map(|buffer| {
            let index = buffer.index();
            let declared = buffer.length();
            match buffer.source() {
                // A meshopt fallback buffer without data: every view of it
                // is decoded from another buffer (`meshopt`).
                gltf::buffer::Source::Bin
                    if super::meshopt::is_placeholder(&buffer) && (index > 0 || bin.is_none()) =>
                {
                    Ok(Cow::Borrowed(&[][..]))
                }
                gltf::buffer::Source::Bin => bin_chunk(bin, index, declared).map(Cow::Borrowed),
                gltf::buffer::Source::Uri(uri) => load_uri(uri, declared, folder)
                    .map(Cow::Owned)
                    .map_err(|problem| {
                        format!("buffer {index} (uri \"{}\") {problem}", abbreviate(uri))
                    }),
            }
        })
        .collect()
}

/// Adds the declared lengths of the buffers that will be read (all but the
/// BIN chunk, which is part of the file) to `used_bytes`, against the limit.
fn reserve(document: &gltf::Document, used_bytes: &mut u64, limits: &Limits) -> Result<(), String> {
    for buffer in document.buffers() {
        if matches!(buffer.source(), gltf::buffer::Source::Bin) {
            continue;
        }
        *used_bytes = used_bytes.saturating_add(buffer.length() as u64);
        if *used_bytes > limits.bytes {
            return Err(format!(
                "buffer {}: {}",
                buffer.index(),
                exceeded(
                    "the file plus the buffers declared so far",
                    format!("{used_bytes} bytes"),
                    "bytes",
                    limits.bytes
                )
            ));
        }
    }
    Ok(())
}

fn bin_chunk(bin: Option<&[u8]>, index: usize, declared: usize) -> Result<&[u8], String> {
    let blob = bin.ok_or_else(|| {
        format!(
            "buffer {index} has no uri, so it must be the BIN chunk of a .glb file, but there is no BIN chunk"
        )
    })?;
    blob.get(..declared).ok_or_else(|| {
        format!(
            "buffer {index}: the GLB BIN chunk has {} bytes, fewer than the declared byteLength {declared}",
            blob.len()
        )
    })
}

/// Loads the bytes of a buffer URI. Errors are phrased to follow
/// "buffer N (uri "...")".
fn load_uri(uri: &str, declared: usize, folder: &Path) -> Result<Vec<u8>, String> {
    if uri
        .get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case("data:"))
    {
        return decode_data_uri(uri, declared);
    }
    if has_scheme(uri) {
        return Err(
            "has a URI scheme; buffers must be relative file references or base64 data: URIs"
                .into(),
        );
    }
    // A query or fragment is not part of the file name (RFC 3986).
    let reference = uri.split(['?', '#']).next().unwrap_or_default();
    let relative = relative_path(&percent_decode(reference)?)?;
    let resolved = confine(folder, &relative)?;
    read_prefix(&resolved, declared)
}

/// Resolves `relative` inside `folder`, following symlinks, and refuses the
/// result unless it is still inside the folder: a lexically clean path can
/// still lead out through a symlink.
pub(super) fn confine(folder: &Path, relative: &Path) -> Result<PathBuf, String> {
    let root = folder
        .canonicalize()
        .map_err(|e| format!("cannot be resolved: the glTF's folder is not accessible: {e}"))?;
    let resolved = folder
        .join(relative)
        .canonicalize()
        .map_err(|e| format!("cannot be opened: {e}"))?;
    if !resolved.starts_with(&root) {
        return Err(format!(
            "resolves to {}, which is outside the glTF's folder {}",
            resolved.display(),
            root.display()
        ));
    }
    Ok(resolved)
}

/// Reads the first `declared` bytes of a regular file. A shorter file is an
/// error; a longer one is read only as far as needed.
fn read_prefix(path: &Path, declared: usize) -> Result<Vec<u8>, String> {
    let too_short = |len: u64| {
        format!("refers to a file of {len} bytes, shorter than the declared byteLength {declared}")
    };
    // The type checks of `read_regular_file`, without reading the file:
    // only a prefix is wanted.
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot be opened: {e}"))?;
    if !meta.is_file() {
        return Err(ReadError::NotRegular.to_string());
    }
    let file = File::open(path).map_err(|e| format!("cannot be opened: {e}"))?;
    let meta = file
        .metadata()
        .map_err(|e| format!("cannot be opened: {e}"))?;
    if !meta.is_file() {
        return Err(ReadError::NotRegular.to_string());
    }
    if meta.len() < declared as u64 {
        return Err(too_short(meta.len()));
    }
    let mut data = Vec::new();
    data.try_reserve_exact(declared)
        .map_err(|e| format!("cannot be read: {e}"))?;
    file.take(declared as u64)
        .read_to_end(&mut data)
        .map_err(|e| format!("cannot be read: {e}"))?;
    if data.len() < declared {
        // The file shrank between the size check and the read.
        return Err(too_short(data.len() as u64));
    }
    Ok(data)
}

/// Decodes a `data:[<media type>];base64,<data>` URI.
pub(super) fn decode_data_uri(uri: &str, declared: usize) -> Result<Vec<u8>, String> {
    let mut data = decode_base64_uri(uri)?;
    if data.len() < declared {
        return Err(format!(
            "is a data: URI that decodes to {} bytes, fewer than the declared byteLength {declared}",
            data.len()
        ));
    }
    data.truncate(declared);
    Ok(data)
}

/// All bytes of a `data:[<media type>];base64,<data>` URI (images have no
/// declared length).
pub(super) fn decode_base64_uri(uri: &str) -> Result<Vec<u8>, String> {
    let (_, payload) = uri.split_once(";base64,").ok_or(
        "is a data: URI without base64 encoding; only the `data:...;base64,` form is supported",
    )?;
    // Exporters disagree about padding; accept it present or absent.
    let engine = base64::engine::GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        base64::engine::GeneralPurposeConfig::new()
            .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent),
    );
    engine
        .decode(payload)
        .map_err(|e| format!("is a data: URI with invalid base64 data ({e})"))
}

/// Whether a URI reference starts with a scheme (`http:`, `file:`, `C:`,
/// ...): RFC 3986's `ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"` before
/// any `/`, `?` or `#`.
pub(super) fn has_scheme(uri: &str) -> bool {
    let Some(colon) = uri.find(':') else {
        return false;
    };
    let scheme = &uri[..colon];
    let mut chars = scheme.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
}

/// Decodes `%XX` escapes; the result must be UTF-8 (file names in glTF
/// are).
pub(super) fn percent_decode(text: &str) -> Result<String, String> {
    fn hex(b: u8) -> Option<u8> {
        match b {
            b'0'..=b'9' => Some(b - b'0'),
            b'a'..=b'f' => Some(b - b'a' + 10),
            b'A'..=b'F' => Some(b - b'A' + 10),
            _ => None,
        }
    }
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let value = bytes
                .get(i + 1..i + 3)
                .and_then(|h| Some((hex(h[0])? << 4) | hex(h[1])?))
                .ok_or("has a malformed percent escape (expected % and two hex digits)")?;
            out.push(value);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "is not valid UTF-8 after percent-decoding".to_string())
}

/// Checks that a decoded reference is a relative path that never climbs
/// above its starting folder, and returns it.
pub(super) fn relative_path(decoded: &str) -> Result<PathBuf, String> {
    if decoded.is_empty() {
        return Err("is empty".into());
    }
    if decoded.contains('\0') {
        return Err("contains a NUL character".into());
    }
    if decoded.contains('\\') {
        // A separator on Windows, so it could smuggle in `..\` or a drive.
        return Err("contains a backslash; URIs separate folders with `/`".into());
    }
    let absolute = || "is an absolute path; only paths relative to the glTF's folder are allowed";
    let path = Path::new(decoded);
    if path.has_root() || path.is_absolute() {
        return Err(absolute().into());
    }
    let mut depth = 0usize;
    for component in path.components() {
        match component {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => {
                depth = depth
                    .checked_sub(1)
                    .ok_or("leaves the glTF's folder with `..`")?;
            }
            Component::RootDir | Component::Prefix(_) => return Err(absolute().into()),
        }
    }
    Ok(path.to_path_buf())
}
