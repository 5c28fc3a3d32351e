//! From bytes to a validated glTF document: the GLB container, a census of
//! the JSON before it is parsed (see [`super::census`]), the parse, the
//! extension checks and gltf-json's validation.

use super::census::Census;
use super::hostile::guarded;
use crate::scene::limits::Limits;
use gltf::json::validation::{Checked, Validate as _};
use gltf::mesh::Semantic;

/// Required extensions this importer honours.
pub(super) const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] = &[
    "EXT_meshopt_compression",
    "EXT_texture_webp",
    "KHR_draco_mesh_compression",
    "KHR_lights_punctual",
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume",
    "KHR_mesh_quantization",
    "KHR_meshopt_compression",
    "KHR_texture_basisu",
    "KHR_texture_transform",
];

/// Required extensions users are likely to meet, with what they do: the
/// message says why the file cannot be drawn without them.
const KNOWN_UNSUPPORTED: &[(&str, &str)] = &[
    ("EXT_mesh_gpu_instancing", "GPU instancing"),
    ("EXT_texture_avif", "AVIF textures"),
];

/// The GLB header: magic, version, total length.
const GLB_HEADER_BYTES: usize = 12;
/// A GLB chunk header: length, type.
const CHUNK_HEADER_BYTES: usize = 8;
const CHUNK_JSON: u32 = u32::from_le_bytes(*b"JSON");
const CHUNK_BIN: u32 = u32::from_le_bytes(*b"BIN\0");

/// The two parts of a glTF file.
pub(super) struct Container<'a> {
    pub json: &'a [u8],
    /// The GLB `BIN` chunk, if the file is a GLB and has one.
    pub bin: Option<&'a [u8]>,
}

/// Splits a GLB into its JSON and BIN chunks, or takes the bytes as JSON.
/// The magic decides; `expect_glb` (a `.glb` file name) only makes a
/// missing magic an error about the GLB header rather than about JSON.
pub(super) fn split<'a>(
    bytes: &'a [u8],
    expect_glb: bool,
    notes: &mut Vec<String>,
) -> Result<Container<'a>, String> {
    if bytes.is_empty() {
        return Err("the file is empty".into());
    }
    if bytes.starts_with(b"glTF") {
        return split_glb(bytes, notes).map_err(|p| format!("invalid GLB file: {p}"));
    }
    if expect_glb {
        let start = bytes[..bytes.len().min(4)].escape_ascii();
        return Err(format!(
            "invalid GLB file: it starts with `{start}`, not the magic `glTF`"
        ));
    }
    Ok(Container {
        json: bytes,
        bin: None,
    })
}

fn split_glb<'a>(bytes: &'a [u8], notes: &mut Vec<String>) -> Result<Container<'a>, String> {
    if bytes.len() < GLB_HEADER_BYTES {
        return Err(format!(
            "the file has {} bytes, fewer than the {GLB_HEADER_BYTES}-byte header",
            bytes.len()
        ));
    }
    let version = le_u32(bytes, 4);
    if version != 2 {
        return Err(format!("version {version}; only version 2 is supported"));
    }
    let declared = le_u32(bytes, 8) as usize;
    if declared > bytes.len() {
        return Err(format!(
            "the header declares a length of {declared} bytes but the file has {} (truncated?)",
            bytes.len()
        ));
    }
    if declared < bytes.len() {
        notes.push(format!(
            "{} bytes after the end the GLB header declares were ignored",
            bytes.len() - declared
        ));
    }
    let mut chunks = Chunks {
        bytes: &bytes[..declared],
        offset: GLB_HEADER_BYTES,
    };
    let json = match chunks.next().transpose()? {
        Some((CHUNK_JSON, data)) => data,
        Some((kind, _)) => {
            return Err(format!(
                "the first chunk has type {}, but it must be the JSON chunk",
                chunk_name(kind)
            ));
        }
        None => return Err("there is no JSON chunk".into()),
    };
    let mut bin = None;
    for chunk in chunks {
        match chunk? {
            (CHUNK_BIN, data) if bin.is_none() => bin = Some(data),
            (kind @ (CHUNK_JSON | CHUNK_BIN), _) => {
                return Err(format!("a second {} chunk", chunk_name(kind)));
            }
            // The GLB spec asks readers to skip chunks of unknown types.
            (kind, _) => notes.push(format!(
                "GLB chunk of unknown type {} ignored",
                chunk_name(kind)
            )),
        }
    }
    Ok(Container { json, bin })
}

/// The chunks after the header, each checked to lie inside the file.
struct Chunks<'a> {
    bytes: &'a [u8],
    offset: usize,
}

impl<'a> Iterator for Chunks<'a> {
    type Item = Result<(u32, &'a [u8]), String>;

    fn next(&mut self) -> Option<Self::Item> {
        let start = self.offset;
        if start >= self.bytes.len() {
            return None;
        }
        // Any error ends the iteration.
        self.offset = self.bytes.len();
        let data_start = start + CHUNK_HEADER_BYTES;
        if data_start > self.bytes.len() {
            return Some(Err(format!(
                "a chunk header at byte {start} is cut off by the end of the file"
            )));
        }
        let length = le_u32(self.bytes, start);
        let kind = le_u32(self.bytes, start + 4);
        // `length` is a u32 and `data_start` at most the file length, so
        // this cannot overflow a 64-bit usize; checked all the same.
        let end = data_start.checked_add(length as usize);
        match end {
            Some(end) if end <= self.bytes.len() => {
                self.offset = end;
                Some(Ok((kind, &self.bytes[data_start..end])))
            }
            _ => Some(Err(format!(
                "the {} chunk at byte {start} declares {length} bytes, but only {} remain",
                chunk_name(kind),
                self.bytes.len() - data_start
            ))),
        }
    }
}

fn le_u32(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

fn chunk_name(kind: u32) -> String {
    let bytes = kind.to_le_bytes();
    if bytes.iter().all(|b| b.is_ascii_graphic() || *b == 0) {
        format!(
            "`{}`",
            String::from_utf8_lossy(&bytes).trim_end_matches('\0')
        )
    } else {
        format!("0x{kind:08x}")
    }
}

// ---------------------------------------------------------------------------
// The JSON

/// Parses the JSON into a document, after checking that parsing it stays
/// within `limits`, and validates it. `used_bytes` is what the input already
/// holds (the file); the estimated parsed size is added to it.
pub(super) fn parse(
    json: &[u8],
    used_bytes: &mut u64,
    limits: &Limits,
    notes: &mut Vec<String>,
) -> Result<gltf::Document, String> {
    Census::take(json)?.check(used_bytes, limits)?;
    let mut root: gltf::json::Root =
        gltf::json::deserialize::from_slice(json).map_err(|e| format!("invalid glTF: {e}"))?;
    check_version(&root.asset)?;
    check_extensions(&root, notes)?;
    super::compressed::use_extension_sources(&mut root)?;
    check_position_accessors(&root)?;
    check_cameras(&root)?;
    validate(&root, notes)?;
    Ok(gltf::Document::from_json_without_validation(root))
}

/// glTF 2.x only: a file of another major version may mean something else
/// by the same keys, and one whose `minVersion` is above 2.0 asks for
/// features of a later minor version (glTF 2.0, "Asset": a loader must
/// refuse both).
fn check_version(asset: &gltf::json::Asset) -> Result<(), String> {
    let parse = |key: &str, text: &str| -> Result<(u32, u32), String> {
        text.split_once('.')
            .and_then(|(major, minor)| Some((major.parse().ok()?, minor.parse().ok()?)))
            .ok_or_else(|| format!("asset.{key} is \"{text}\", not MAJOR.MINOR (e.g. \"2.0\")"))
    };
    let (major, _) = parse("version", &asset.version)?;
    if major != 2 {
        return Err(format!(
            "asset.version is \"{}\": gonio reads glTF 2.x files only",
            asset.version
        ));
    }
    if let Some(min) = &asset.min_version
        && parse("minVersion", min)? > (2, 0)
    {
        return Err(format!(
            "asset.minVersion is \"{min}\": the file needs a later glTF than 2.0, which gonio implements"
        ));
    }
    Ok(())
}

/// A required extension gonio does not implement makes the file
/// undrawable: an error naming it (glTF 2.0, 3.12: a loader must refuse
/// it). The optional ones gonio ignores are named in one warning, shown
/// by `render` and `view` without `--verbose`: the file draws, but not as
/// its authors show it.
fn check_extensions(root: &gltf::json::Root, notes: &mut Vec<String>) -> Result<(), String> {
    let unsupported: Vec<String> = root
        .extensions_required
        .iter()
        .filter(|e| !SUPPORTED_REQUIRED_EXTENSIONS.contains(&e.as_str()))
        .map(|e| describe_extension(e))
        .collect();
    if !unsupported.is_empty() {
        return Err(format!(
            "the file requires the glTF extension{} {}, which gonio does not support (supported: {})",
            if unsupported.len() == 1 { "" } else { "s" },
            unsupported.join(", "),
            SUPPORTED_REQUIRED_EXTENSIONS.join(", ")
        ));
    }
    let ignored: Vec<String> = root
        .extensions_used
        .iter()
        .filter(|e| !SUPPORTED_REQUIRED_EXTENSIONS.contains(&e.as_str()))
        .map(|e| describe_extension(e))
        .collect();
    if !ignored.is_empty() {
        notes.push(format!(
            "{}the file uses the glTF extension{} {}, which gonio ignores",
            super::hostile::WARNING,
            if ignored.len() == 1 { "" } else { "s" },
            ignored.join(", ")
        ));
    }
    Ok(())
}

fn describe_extension(name: &str) -> String {
    let shown = super::hostile::abbreviate(name);
    match KNOWN_UNSUPPORTED.iter().find(|(known, _)| *known == name) {
        Some((_, what)) => format!("{shown} ({what})"),
        None => shown.into_owned(),
    }
}

/// gltf-json's validation indexes `accessors` with a primitive's
/// `POSITION` unchecked and would panic on a missing one, so that is
/// checked here first.
fn check_position_accessors(root: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, accessor) in &primitive.attributes {
                if accessor.value() >= root.accessors.len() {
                    return Err(format!(
                        "invalid glTF: meshes[{m}].primitives[{p}].attributes.{}: accessor {} does not exist (there are {})",
                        semantic_name(semantic),
                        accessor.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A camera's `type` must come with the object of that name: the `gltf`
/// crate's `Camera::projection` unwraps it, and gltf-json's validation does
/// not check it. (Found by fuzzing.)
fn check_cameras(root: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::camera::Type;
    for (index, camera) in root.cameras.iter().enumerate() {
        let missing = match camera.type_ {
            Checked::Valid(Type::Perspective) if camera.perspective.is_none() => "perspective",
            Checked::Valid(Type::Orthographic) if camera.orthographic.is_none() => "orthographic",
            // Present as required, or an unknown type that validation reports.
            _ => continue,
        };
        return Err(format!(
            "invalid glTF: cameras[{index}] has type \"{missing}\" but no `{missing}` object"
        ));
    }
    Ok(())
}

fn semantic_name(semantic: &Checked<Semantic>) -> String {
    match semantic {
        Checked::Valid(s) => s.to_string(),
        Checked::Invalid => "(unknown attribute)".into(),
    }
}

/// gltf-json's validation: every index in range, every enum value known,
/// required properties present. The first few problems are reported.
///
/// One kind is not a problem here: vertex attributes with names gltf-json
/// does not know (application-specific ones such as `_BATCHID`, which the
/// spec allows). gonio reads only `POSITION`, `NORMAL` and indices, so they
/// are ignored, with a note. Nor are required extensions gltf-json does
/// not parse but gonio implements (`check_extensions` ran first), nor a
/// missing `bufferView` of an accessor a Draco stream fills.
fn validate(root: &gltf::json::Root, notes: &mut Vec<String>) -> Result<(), String> {
    const SHOWN: usize = 8;
    const UNKNOWN_ATTRIBUTE: &str = "attributes[\"<invalid semantic name>\"]";
    let mut problems = Vec::new();
    let mut more = 0usize;
    let mut unknown_attributes = 0usize;
    let draco_filled = super::draco::filled_accessors(root);
    let filled_by_draco = |path: &str| {
        path.strip_prefix("accessors[")
            .and_then(|rest| rest.strip_suffix("].bufferView"))
            .and_then(|index| index.parse::<usize>().ok())
            .is_some_and(|index| draco_filled.contains(&index))
    };
    guarded(|| {
        root.validate(root, gltf::json::Path::new, &mut |path, error| {
            let path = path().to_string();
            if path.ends_with(UNKNOWN_ATTRIBUTE) {
                unknown_attributes += 1;
            } else if error == gltf::json::validation::Error::Missing && filled_by_draco(&path) {
                // Filled from the Draco stream (`draco`).
            } else if path.starts_with("extensionsRequired")
                && error == gltf::json::validation::Error::Unsupported
            {
                // gltf-json knows only the extensions it parses;
                // `check_extensions` already refused the ones gonio does
                // not implement (KHR_mesh_quantization it does, here).
            } else if problems.len() < SHOWN {
                problems.push(format!("{path}: {error}"));
            } else {
                more += 1;
            }
        })
    })?;
    if unknown_attributes > 0 {
        notes.push(format!(
            "{unknown_attributes} vertex attribute(s) with names gonio does not use were ignored"
        ));
    }
    if problems.is_empty() {
        return Ok(());
    }
    let mut text = format!("invalid glTF: {}", problems.join("; "));
    if more > 0 {
        text += &format!("; and {more} more problem(s)");
    }
    Err(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(chunks: &[(&[u8; 4], &[u8])]) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend_from_slice(&(data.len() as u32).to_le_bytes());
            body.extend_from_slice(*kind);
            body.extend_from_slice(data);
        }
        let mut file = b"glTF".to_vec();
        file.extend_from_slice(&2u32.to_le_bytes());
        file.extend_from_slice(&((body.len() + 12) as u32).to_le_bytes());
        file.extend_from_slice(&body);
        file
    }

    fn split_err(bytes: &[u8]) -> String {
        match split(bytes, true, &mut Vec::new()) {
            Ok(_) => panic!("accepted"),
            Err(e) => e,
        }
    }

    #[test]
    fn glb_chunks_are_split() {
        let file = glb(&[(b"JSON", b"{}"), (b"BIN\0", b"1234"), (b"XTRA", b"")]);
        let mut notes = Vec::new();
        let container = split(&file, true, &mut notes).unwrap();
        assert_eq!(container.json, b"{}");
        assert_eq!(container.bin, Some(&b"1234"[..]));
        assert_eq!(notes.len(), 1, "{notes:?}");
        let json_only = glb(&[(b"JSON", b"{}")]);
        let container = split(&json_only, true, &mut notes).unwrap();
        assert_eq!(container.bin, None);
    }

    #[test]
    fn broken_glb_headers_and_chunks_are_named() {
        let good = glb(&[(b"JSON", b"{}"), (b"BIN\0", b"1234")]);
        assert!(split_err(&good[..7]).contains("fewer than the 12-byte header"));
        assert!(split_err(b"GLTF\x02\0\0\0\x0c\0\0\0").contains("magic"));
        let mut v1 = good.clone();
        v1[4] = 1;
        assert!(split_err(&v1).contains("version 1"));
        let mut long = good.clone();
        long[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(split_err(&long).contains("truncated"));
        let mut chunk = good.clone();
        chunk[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(split_err(&chunk).contains("declares 4294967295 bytes"));
        let bin_first = glb(&[(b"BIN\0", b"1234"), (b"JSON", b"{}")]);
        assert!(split_err(&bin_first).contains("must be the JSON chunk"));
        let twice = glb(&[(b"JSON", b"{}"), (b"JSON", b"{}")]);
        assert!(split_err(&twice).contains("second `JSON` chunk"));
        assert!(split_err(&glb(&[])).contains("no JSON chunk"));
        // A header cut in the middle of the second chunk's header.
        let mut cut = glb(&[(b"JSON", b"{}")]);
        cut.extend_from_slice(&[1, 0, 0]);
        let len = cut.len() as u32;
        cut[8..12].copy_from_slice(&len.to_le_bytes());
        assert!(split_err(&cut).contains("cut off"));
    }
}
