//! glTF 2.0 import (`.gltf` with external or embedded buffers, and `.glb`).
//!
//! [`load`] turns the default scene of a glTF file into world-space meshes,
//! gonio materials, punctual lights and at most one camera. It is written
//! for files that may come from anywhere, so nothing in the file can make
//! it panic, read outside the file's folder, or allocate without bound:
//!
//! - Buffers are loaded here, not by the `gltf` crate: the GLB `BIN` chunk,
//!   base64 `data:` URIs, or files given as relative references, which must
//!   stay inside the glTF's folder after canonicalization (no absolute
//!   paths, no escaping `..`, no URI schemes, no symlinks that lead out)
//!   and be regular files. At most the declared `byteLength` is read, and a
//!   buffer larger than 1 GiB is refused.
//! - Every accessor is checked against its buffer view and buffer (with
//!   overflow-checked arithmetic) before the `gltf` crate's reader touches
//!   it, because that reader slices and indexes without checking.
//! - The node graph is walked iteratively with a visited set, so a cycle or
//!   a node shared by two parents is an error rather than a hang or a stack
//!   overflow.
//! - A panic inside the `gltf` crate is caught as a last line of defence and
//!   reported like any other malformed input.
//!
//! # What is imported
//!
//! The default scene (scene 0 if none is marked default; every root node if
//! there are no scenes), with node transforms composed into world space.
//! Triangle lists, strips and fans become indexed triangles; points and
//! lines are skipped and counted in [`GltfScene::skipped_primitives`].
//! `NORMAL` is used when present, otherwise normals are generated
//! (area-weighted). Textures, vertex colours, skins, morph targets,
//! emission, alpha and `doubleSided` are ignored; skinned meshes are drawn
//! in their rest pose.
//!
//! # Materials: metallic-roughness → Blinn-Phong
//!
//! glTF describes surfaces with the metal/rough model; gonio maps each
//! material to the lecture's Blinn-Phong ([`ReflectanceModel::BlinnPhong`]).
//! Only the factors are used (textures are ignored, so a textured model
//! shows its factors, usually white). With base colour factor `b` (linear
//! RGB, alpha dropped), metallic `m` and roughness `r`, each clamped to
//! [0, 1]:
//!
//! | gonio | from glTF | why |
//! |---|---|---|
//! | `k_d` | `b·(1 − m)` | metals have no diffuse lobe |
//! | `k_s` | `F0 · min(1, (k_e + 8)/(8π))`, `F0 = 0.04·(1 − m) + b·m` | F0 is the metal/rough model's normal-incidence reflectance; the factor (Blinn-Phong's normalization, capped at 1) keeps the lecture's unnormalized broad lobes from reflecting more than they receive |
//! | `k_e` | `clamp(2/α² − 2, 1, 1e6)`, `α = max(r², 10⁻³)` | the usual Blinn-Phong ↔ Beckmann exponent correspondence (Walter et al. 2007) |
//! | `k_a` | `k_d` | an ambient light lights the diffuse colour |
//!
//! Primitives without a material get glTF's default material (`b = 1`,
//! `m = 1`, `r = 1`) mapped by the same rule, named `gltf-default`.
//!
//! # Lights (`KHR_lights_punctual`)
//!
//! glTF gives photometric units; gonio's contract is radiometric. The import
//! takes 1 cd as 1 W/sr (point and spot: `intensity = color · intensity`)
//! and 1 lx as 1 W/m² (directional: `irradiance = color · intensity`), with
//! no luminous-efficacy factor, so a file's relative light levels carry
//! over unchanged. Lights shine along the node's world −Z axis; spot cone
//! angles are converted from radians to degrees; `range` is kept; no light
//! casts shadows (the scene file can ask for them).
//!
//! # Camera
//!
//! The first perspective camera met in scene order (depth-first, children in
//! order) becomes [`GltfScene::camera`]: it sits at the node's world origin,
//! looks along world −Z of the node with the node's +Y as up, and keeps
//! `yfov`. Its near/far are left at 0 for the caller to fit to the scene.
//! Orthographic cameras, and perspective ones whose transform or `yfov`
//! cannot give a valid camera, are skipped without error: the caller frames
//! the scene itself when there is none.

use crate::material::{Material, ReflectanceModel};
use crate::scene::mesh::area_weighted_normals;
use crate::scene::{Camera, Light, Mesh, Rgb};
use crate::{Error, Result};
use base64::Engine as _;
use glam::{DMat4, DQuat, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::json::validation::Validate as _;
use gltf::khr_lights_punctual::Kind as LightKind;
use gltf::mesh::{Mode, Semantic};
use std::borrow::Cow;
use std::fs::{self, File};
use std::io::Read;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Component, Path, PathBuf};

/// Largest buffer accepted, in bytes (1 GiB).
pub const MAX_BUFFER_BYTES: usize = 1 << 30;

/// Largest `.gltf`/`.glb` file accepted: a maximal GLB `BIN` chunk plus a
/// generous JSON chunk. Anything bigger is not a model we can render.
const MAX_FILE_BYTES: u64 = MAX_BUFFER_BYTES as u64 + (64 << 20);

/// Required extensions this importer honours.
const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] = &["KHR_lights_punctual"];

/// Message for a panic caught inside the `gltf` crate.
const PARSER_PANICKED: &str = "the glTF parser failed on malformed data";

/// glTF's metal/rough F0 for dielectrics.
const DIELECTRIC_F0: f64 = 0.04;

/// The contents of a glTF file, ready to join a [`crate::scene::Scene`].
#[derive(Clone, Debug)]
pub struct GltfScene {
    /// World-space meshes; `mesh.material` indexes [`GltfScene::materials`].
    pub meshes: Vec<Mesh>,
    /// One per glTF material, in file order, plus `gltf-default` at the end
    /// if an imported primitive has no material.
    pub materials: Vec<Material>,
    /// `KHR_lights_punctual` lights, world space.
    pub lights: Vec<Light>,
    /// The first perspective camera reached in the scene; near/far are 0.0
    /// (the caller fits them to the scene bounds).
    pub camera: Option<Camera>,
    /// Primitives of the scene that were skipped because they draw points
    /// or lines, which gonio does not render.
    pub skipped_primitives: usize,
}

/// Loads the default scene of a `.gltf` or `.glb` file. See the module
/// documentation for what is imported and how.
///
/// Every problem with the file (or a buffer it references) is an
/// [`Error::Input`] naming `path`.
pub fn load(path: &Path) -> Result<GltfScene> {
    let input = |problem: String| Error::input(path, problem);
    let bytes = read_file(path).map_err(input)?;
    let gltf = parse(&bytes).map_err(input)?;
    // The JSON now lives in `gltf` and a GLB's BIN chunk in `gltf.blob`.
    drop(bytes);
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let buffers = load_buffers(&gltf, folder).map_err(input)?;
    guarded(|| Importer::new(&gltf.document, &buffers).run())
        .and_then(|result| result)
        .map_err(input)
}

/// The glTF mapping of metallic-roughness factors to a Blinn-Phong
/// material (see the module documentation for the table). Inputs outside
/// [0, 1] are clamped.
pub fn material_from_metallic_roughness(
    name: impl Into<String>,
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
) -> Material {
    let b = base_color.clamp(Rgb::ZERO, Rgb::ONE);
    let m = metallic.clamp(0.0, 1.0);
    let r = roughness.clamp(0.0, 1.0);
    let k_d = b * (1.0 - m);
    let f0 = Rgb::splat(DIELECTRIC_F0 * (1.0 - m)) + b * m;
    let alpha = (r * r).max(1e-3);
    let k_e = (2.0 / (alpha * alpha) - 2.0).clamp(1.0, 1e6);
    // The lecture's lobe is not normalized: its albedo grows like 8π/k_e
    // for broad lobes (a rough metal with k_s = 1 reflects far more than it
    // receives). Scaling by Blinn-Phong's normalization (k_e + 8)/(8π),
    // capped at 1, keeps broad lobes near F0 and leaves sharp ones alone.
    let k_s = f0 * ((k_e + 8.0) / (8.0 * std::f64::consts::PI)).min(1.0);
    // Issue #4 will switch this default to Cook-Torrance with GGX, which
    // takes α directly; Blinn-Phong is the only glossy model there is now.
    let mut material = Material::new(name, ReflectanceModel::BlinnPhong);
    material.k_d = k_d.clamp(Rgb::ZERO, Rgb::ONE);
    material.k_s = k_s.clamp(Rgb::ZERO, Rgb::ONE);
    material.k_a = material.k_d;
    material.k_e = k_e;
    material
}

// ---------------------------------------------------------------------------
// Files and parsing

/// Reads the glTF/GLB file itself, refusing anything that is not a regular
/// file or is too large to be a model.
fn read_file(path: &Path) -> Result<Vec<u8>, String> {
    let meta = fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        return Err("is not a regular file".into());
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(format!(
            "the file has {} bytes, more than the {} bytes a glTF file may have here",
            meta.len(),
            MAX_FILE_BYTES
        ));
    }
    let file = File::open(path).map_err(|e| format!("cannot read the file: {e}"))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // `take` keeps the limit even if the file grows after the check.
    file.take(MAX_FILE_BYTES)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    Ok(bytes)
}

/// Runs `f`, turning a panic into the "malformed data" error. Only code of
/// the `gltf` crate is expected to panic here, and only on inputs our own
/// checks did not anticipate.
fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    panic::catch_unwind(AssertUnwindSafe(f)).map_err(|_| PARSER_PANICKED.to_string())
}

/// Parses and validates the document.
///
/// Validation is run here rather than by `Gltf::from_slice` so that (1) an
/// unsupported required extension gets its own message naming it, and (2)
/// a `POSITION` attribute naming a missing accessor is reported before
/// gltf-json's validation, which indexes with it unchecked and would panic.
fn parse(bytes: &[u8]) -> Result<gltf::Gltf, String> {
    let gltf = guarded(|| gltf::Gltf::from_slice_without_validation(bytes))?
        .map_err(describe_gltf_error)?;
    let root = gltf.document.as_json();

    let unsupported: Vec<&str> = root
        .extensions_required
        .iter()
        .map(String::as_str)
        .filter(|e| !SUPPORTED_REQUIRED_EXTENSIONS.contains(e))
        .collect();
    if !unsupported.is_empty() {
        return Err(format!(
            "the file requires the glTF extension{} {}, which gonio does not support (supported: {})",
            if unsupported.len() == 1 { "" } else { "s" },
            unsupported.join(", "),
            SUPPORTED_REQUIRED_EXTENSIONS.join(", ")
        ));
    }

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

    let mut problems = Vec::new();
    guarded(|| {
        root.validate(root, gltf::json::Path::new, &mut |path, error| {
            problems.push(format!("{}: {error}", path()));
        })
    })?;
    if !problems.is_empty() {
        const SHOWN: usize = 8;
        let more = problems.len().saturating_sub(SHOWN);
        problems.truncate(SHOWN);
        let mut text = format!("invalid glTF: {}", problems.join("; "));
        if more > 0 {
            text += &format!("; and {more} more problem(s)");
        }
        return Err(text);
    }
    Ok(gltf)
}

fn describe_gltf_error(err: gltf::Error) -> String {
    match err {
        gltf::Error::Binary(e) => format!("invalid GLB file: {e}"),
        e => format!("invalid glTF: {e}"),
    }
}

fn semantic_name(semantic: &gltf::json::validation::Checked<Semantic>) -> String {
    match semantic {
        gltf::json::validation::Checked::Valid(s) => s.to_string(),
        gltf::json::validation::Checked::Invalid => "(unknown attribute)".into(),
    }
}

// ---------------------------------------------------------------------------
// Buffers

/// Loads every buffer of the document, in order. The GLB BIN chunk is
/// borrowed, not copied.
fn load_buffers<'g>(gltf: &'g gltf::Gltf, folder: &Path) -> Result<Vec<Cow<'g, [u8]>>, String> {
    gltf.buffers()
        .map(|buffer| {
            let index = buffer.index();
            let declared = buffer.length();
            if declared > MAX_BUFFER_BYTES {
                return Err(format!(
                    "buffer {index} declares a byteLength of {declared} bytes; buffers larger than 1 GiB ({MAX_BUFFER_BYTES} bytes) are refused"
                ));
            }
            match buffer.source() {
                gltf::buffer::Source::Bin => {
                    let blob = gltf.blob.as_deref().ok_or_else(|| {
                        format!(
                            "buffer {index} has no uri, so it must be the BIN chunk of a .glb file, but there is no BIN chunk"
                        )
                    })?;
                    if blob.len() < declared {
                        return Err(format!(
                            "buffer {index}: the GLB BIN chunk has {} bytes, fewer than the declared byteLength {declared}",
                            blob.len()
                        ));
                    }
                    Ok(Cow::Borrowed(&blob[..declared]))
                }
                gltf::buffer::Source::Uri(uri) => load_uri(uri, declared, folder)
                    .map(Cow::Owned)
                    .map_err(|problem| format!("buffer {index} (uri \"{}\") {problem}", abbreviate(uri))),
            }
        })
        .collect()
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

    let root = folder
        .canonicalize()
        .map_err(|e| format!("cannot be resolved: the glTF's folder is not accessible: {e}"))?;
    let resolved = folder
        .join(&relative)
        .canonicalize()
        .map_err(|e| format!("cannot be opened: {e}"))?;
    if !resolved.starts_with(&root) {
        return Err(format!(
            "resolves to {}, which is outside the glTF's folder {}",
            resolved.display(),
            root.display()
        ));
    }
    let meta = fs::metadata(&resolved).map_err(|e| format!("cannot be opened: {e}"))?;
    if !meta.is_file() {
        return Err("is not a regular file".into());
    }
    let too_short = |len: u64| {
        format!("refers to a file of {len} bytes, shorter than the declared byteLength {declared}")
    };
    if meta.len() < declared as u64 {
        return Err(too_short(meta.len()));
    }
    let file = File::open(&resolved).map_err(|e| format!("cannot be opened: {e}"))?;
    let mut data = Vec::with_capacity(declared);
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
fn decode_data_uri(uri: &str, declared: usize) -> Result<Vec<u8>, String> {
    let (_, payload) = uri.split_once(";base64,").ok_or(
        "is a data: URI without base64 encoding; only the `data:...;base64,` form is supported",
    )?;
    // Exporters disagree about padding; accept it present or absent.
    let engine = base64::engine::GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        base64::engine::GeneralPurposeConfig::new()
            .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent),
    );
    let mut data = engine
        .decode(payload)
        .map_err(|e| format!("is a data: URI with invalid base64 data ({e})"))?;
    if data.len() < declared {
        return Err(format!(
            "is a data: URI that decodes to {} bytes, fewer than the declared byteLength {declared}",
            data.len()
        ));
    }
    data.truncate(declared);
    Ok(data)
}

/// Whether a URI reference starts with a scheme (`http:`, `file:`, `C:`,
/// ...): RFC 3986's `ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"` before
/// any `/`, `?` or `#`.
fn has_scheme(uri: &str) -> bool {
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
fn percent_decode(text: &str) -> Result<String, String> {
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
fn relative_path(decoded: &str) -> Result<PathBuf, String> {
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

/// The first 80 characters of a URI, for messages (data: URIs can be
/// megabytes long).
fn abbreviate(uri: &str) -> Cow<'_, str> {
    const KEEP: usize = 80;
    match uri.char_indices().nth(KEEP) {
        Some((cut, _)) => Cow::Owned(format!("{}…", &uri[..cut])),
        None => Cow::Borrowed(uri),
    }
}

// ---------------------------------------------------------------------------
// Accessors

/// What an accessor is read as, and therefore which types it may have.
#[derive(Clone, Copy)]
enum Usage {
    Position,
    Normal,
    Index,
}

impl Usage {
    fn name(self) -> &'static str {
        match self {
            Usage::Position => "POSITION",
            Usage::Normal => "NORMAL",
            Usage::Index => "indices",
        }
    }

    /// The types the reader can decode for this usage; the `gltf` reader
    /// misreads or panics (`unreachable!`) on anything else.
    fn accepts(self, data_type: DataType, dimensions: Dimensions) -> bool {
        match self {
            Usage::Position | Usage::Normal => {
                data_type == DataType::F32 && dimensions == Dimensions::Vec3
            }
            Usage::Index => {
                matches!(data_type, DataType::U8 | DataType::U16 | DataType::U32)
                    && dimensions == Dimensions::Scalar
            }
        }
    }

    fn expected(self) -> &'static str {
        match self {
            Usage::Position | Usage::Normal => "VEC3 of FLOAT",
            Usage::Index => "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
        }
    }
}

/// Checks that the `gltf` reader can read `accessor` for `usage` without
/// going out of bounds: right types, at least one element, and every byte
/// it will touch inside its buffer view and buffer (sparse parts
/// included). Errors name the accessor.
fn check_accessor(
    accessor: &gltf::Accessor,
    usage: Usage,
    buffers: &[Cow<[u8]>],
) -> Result<(), String> {
    let fail = |problem: String| {
        format!(
            "accessor {} ({}): {problem}",
            accessor.index(),
            usage.name()
        )
    };
    let (data_type, dimensions) = (accessor.data_type(), accessor.dimensions());
    if !usage.accepts(data_type, dimensions) {
        return Err(fail(format!(
            "has type {dimensions:?} of {data_type:?}, expected {}",
            usage.expected()
        )));
    }
    let element = accessor.size();
    let count = accessor.count();
    if count == 0 {
        return Err(fail("has count 0".into()));
    }
    // Sparse accessors without a buffer view are materialized from nothing;
    // cap them like everything else at what one maximal buffer could hold.
    if count > MAX_BUFFER_BYTES / element {
        return Err(fail(format!(
            "has count {count}, more than a 1 GiB buffer can hold"
        )));
    }
    if let Some(view) = accessor.view() {
        check_range(&view, accessor.offset(), count, element, buffers).map_err(fail)?;
    }
    if let Some(sparse) = accessor.sparse() {
        let sparse_count = sparse.count();
        if sparse_count == 0 || sparse_count > count {
            return Err(fail(format!(
                "has sparse count {sparse_count}, expected 1 to {count}"
            )));
        }
        let indices = sparse.indices();
        check_range(
            &indices.view(),
            indices.offset(),
            sparse_count,
            indices.index_type().size(),
            buffers,
        )
        .map_err(|p| fail(format!("sparse indices: {p}")))?;
        let values = sparse.values();
        check_range(
            &values.view(),
            values.offset(),
            sparse_count,
            element,
            buffers,
        )
        .map_err(|p| fail(format!("sparse values: {p}")))?;
    } else if accessor.view().is_none() {
        return Err(fail("has neither a buffer view nor sparse data".into()));
    }
    Ok(())
}

/// Checks `count ≥ 1` elements of `element` bytes, `offset` bytes into
/// `view`, at the view's stride, against the view and its buffer.
fn check_range(
    view: &gltf::buffer::View,
    offset: usize,
    count: usize,
    element: usize,
    buffers: &[Cow<[u8]>],
) -> Result<(), String> {
    let buffer = view.buffer().index();
    let buffer_len = buffers.get(buffer).map_or(0, |b| b.len());
    let view_fits = view
        .offset()
        .checked_add(view.length())
        .is_some_and(|end| end <= buffer_len);
    if !view_fits {
        return Err(format!(
            "buffer view {} (offset {}, length {}) does not fit in buffer {buffer} of {buffer_len} bytes",
            view.index(),
            view.offset(),
            view.length()
        ));
    }
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "buffer view {} has byteStride {stride}, smaller than the {element}-byte element",
            view.index()
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(element));
    match end {
        Some(end) if end <= view.length() => Ok(()),
        _ => Err(format!(
            "{count} elements of {element} bytes at offset {offset} with stride {stride} do not fit in buffer view {} of {} bytes",
            view.index(),
            view.length()
        )),
    }
}

// ---------------------------------------------------------------------------
// Scene traversal

/// One import: the document, its loaded buffers and what has been gathered.
struct Importer<'a> {
    document: &'a gltf::Document,
    buffers: &'a [Cow<'a, [u8]>],
    scene: GltfScene,
    /// Index of `gltf-default` in `scene.materials`, once a primitive needs it.
    default_material: Option<usize>,
}

impl<'a> Importer<'a> {
    fn new(document: &'a gltf::Document, buffers: &'a [Cow<'a, [u8]>]) -> Self {
        Importer {
            document,
            buffers,
            scene: GltfScene {
                meshes: Vec::new(),
                materials: Vec::new(),
                lights: Vec::new(),
                camera: None,
                skipped_primitives: 0,
            },
            default_material: None,
        }
    }

    fn run(mut self) -> Result<GltfScene, String> {
        for material in self.document.materials() {
            let index = material.index().unwrap_or_default();
            let name = material
                .name()
                .map_or_else(|| format!("material {index}"), str::to_string);
            let pbr = material.pbr_metallic_roughness();
            let material = material_from_pbr(
                name,
                pbr.base_color_factor(),
                pbr.metallic_factor(),
                pbr.roughness_factor(),
            )?;
            self.scene.materials.push(material);
        }

        // Depth-first, children in order, with an explicit stack: a deep
        // or cyclic graph must not exhaust the call stack.
        let mut stack: Vec<(gltf::Node, DMat4)> = self
            .root_nodes()
            .into_iter()
            .rev()
            .map(|node| (node, DMat4::IDENTITY))
            .collect();
        let mut visited = vec![false; self.document.nodes().len()];
        while let Some((node, parent)) = stack.pop() {
            let seen = visited
                .get_mut(node.index())
                .ok_or_else(|| format!("node {} does not exist", node.index()))?;
            if std::mem::replace(seen, true) {
                return Err(format!(
                    "node {} is reached twice from the scene: it is listed twice, has more than one parent, or is part of a cycle; glTF nodes must form disjoint trees",
                    node.index()
                ));
            }
            let world = parent * local_transform(&node)?;
            if !world.is_finite() {
                return Err(format!(
                    "node {}: the composed world transform is not finite",
                    node.index()
                ));
            }
            self.visit(&node, world)?;
            let children: Vec<_> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|child| (child, world)));
        }
        Ok(self.scene)
    }

    /// The default scene's roots, scene 0's if none is the default, or every
    /// node that is nobody's child if the file has no scenes.
    fn root_nodes(&self) -> Vec<gltf::Node<'a>> {
        let document = self.document;
        if let Some(scene) = document
            .default_scene()
            .or_else(|| document.scenes().next())
        {
            return scene.nodes().collect();
        }
        let mut is_child = vec![false; document.nodes().len()];
        for node in document.nodes() {
            for child in node.children() {
                if let Some(flag) = is_child.get_mut(child.index()) {
                    *flag = true;
                }
            }
        }
        document
            .nodes()
            .filter(|node| !is_child[node.index()])
            .collect()
    }

    fn visit(&mut self, node: &gltf::Node, world: DMat4) -> Result<(), String> {
        if let Some(mesh) = node.mesh() {
            self.add_mesh(node, &mesh, world)?;
        }
        if let Some(light) = node.light() {
            let light = convert_light(&light, world)
                .map_err(|p| format!("node {}: light {}: {p}", node.index(), light.index()))?;
            self.scene.lights.push(light);
        }
        if self.scene.camera.is_none()
            && let Some(camera) = node.camera()
        {
            self.scene.camera = convert_camera(&camera, world);
        }
        Ok(())
    }

    fn add_mesh(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        world: DMat4,
    ) -> Result<(), String> {
        let primitive_count = mesh.primitives().len();
        let mesh_name = mesh
            .name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
        for primitive in mesh.primitives() {
            let context = || {
                format!(
                    "mesh {} primitive {} (node {})",
                    mesh.index(),
                    primitive.index(),
                    node.index()
                )
            };
            let Some(raw) = read_primitive(&primitive, self.buffers)
                .map_err(|p| format!("{}: {p}", context()))?
            else {
                self.scene.skipped_primitives += 1;
                continue;
            };
            let name = if primitive_count > 1 {
                format!("{mesh_name}/primitive {}", primitive.index())
            } else {
                mesh_name.clone()
            };
            let material = match primitive.material().index() {
                Some(index) => index,
                None => self.default_material(),
            };
            let mut mesh = match raw.normals {
                Some(normals) => Mesh {
                    name,
                    positions: raw.positions,
                    normals,
                    indices: raw.indices,
                    material,
                },
                None => Mesh::with_generated_normals(name, raw.positions, raw.indices, material),
            };
            mesh.transform(world);
            if mesh.positions.iter().any(|p| !p.is_finite()) {
                return Err(format!(
                    "{}: the node's world transform sends vertices to infinity",
                    context()
                ));
            }
            // A singular transform (a zero scale) has no normal matrix;
            // fall back to normals of the flattened geometry.
            repair_normals(&mut mesh);
            self.scene.meshes.push(mesh);
        }
        Ok(())
    }

    fn default_material(&mut self) -> usize {
        *self.default_material.get_or_insert_with(|| {
            // glTF's default: base colour 1, metallic 1, roughness 1.
            let material = material_from_metallic_roughness("gltf-default", Rgb::ONE, 1.0, 1.0);
            self.scene.materials.push(material);
            self.scene.materials.len() - 1
        })
    }
}

/// A node's local transform, in `f64` from the file's `f32`s.
fn local_transform(node: &gltf::Node) -> Result<DMat4, String> {
    let matrix = match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|column| column.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let [x, y, z, w] = rotation.map(f64::from);
            let q = DQuat::from_xyzw(x, y, z, w);
            let length = q.length();
            if !(length.is_finite() && length > 0.0) {
                return Err(format!(
                    "node {}: rotation {rotation:?} is not a usable quaternion",
                    node.index()
                ));
            }
            // The file's f32 quaternion is only nearly unit length.
            DMat4::from_scale_rotation_translation(
                DVec3::from(scale.map(f64::from)),
                q / length,
                DVec3::from(translation.map(f64::from)),
            )
        }
    };
    if !matrix.is_finite() {
        return Err(format!(
            "node {}: the transform is not finite",
            node.index()
        ));
    }
    Ok(matrix)
}

/// Replaces zero normals (left by a singular transform or a zero-length
/// `NORMAL`) with area-weighted ones of the world-space geometry.
fn repair_normals(mesh: &mut Mesh) {
    if mesh.normals.iter().all(|n| n.length_squared() > 0.5) {
        return;
    }
    let generated = area_weighted_normals(&mesh.positions, &mesh.indices);
    for (n, g) in mesh.normals.iter_mut().zip(generated) {
        if n.length_squared() <= 0.5 {
            *n = g;
        }
    }
}

// ---------------------------------------------------------------------------
// Primitives

/// A primitive's data in object space, before it becomes a [`Mesh`].
struct RawPrimitive {
    positions: Vec<DVec3>,
    /// Unit normals, or zero where the file's normal had no length;
    /// `None` when the primitive has no `NORMAL`.
    normals: Option<Vec<DVec3>>,
    indices: Vec<[u32; 3]>,
}

/// Reads a primitive, or `None` if it draws points or lines.
fn read_primitive(
    primitive: &gltf::Primitive,
    buffers: &[Cow<[u8]>],
) -> Result<Option<RawPrimitive>, String> {
    let mode = primitive.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Ok(None);
    }
    let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(|b| &b[..]));

    let position_accessor = primitive
        .get(&Semantic::Positions)
        .ok_or("has no POSITION attribute")?;
    check_accessor(&position_accessor, Usage::Position, buffers)?;
    let positions = collect_vec3(reader.read_positions(), &position_accessor, Usage::Position)?;
    if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!(
            "accessor {} (POSITION): vertex {k} is not finite ({})",
            position_accessor.index(),
            positions[k]
        ));
    }
    let vertex_count = positions.len();
    let vertex_limit = u32::try_from(vertex_count).map_err(|_| {
        format!("has {vertex_count} vertices, more than 32-bit indices can address")
    })?;

    let normals = match primitive.get(&Semantic::Normals) {
        None => None,
        Some(accessor) => {
            check_accessor(&accessor, Usage::Normal, buffers)?;
            let normals = collect_vec3(reader.read_normals(), &accessor, Usage::Normal)?;
            if normals.len() != vertex_count {
                return Err(format!(
                    "accessor {} (NORMAL) has {} elements but POSITION has {vertex_count}",
                    accessor.index(),
                    normals.len()
                ));
            }
            if let Some(k) = normals.iter().position(|n| !n.is_finite()) {
                return Err(format!(
                    "accessor {} (NORMAL): normal {k} is not finite ({})",
                    accessor.index(),
                    normals[k]
                ));
            }
            Some(normals.into_iter().map(DVec3::normalize_or_zero).collect())
        }
    };

    let vertices: Vec<u32> = match primitive.indices() {
        None => (0..vertex_limit).collect(),
        Some(accessor) => {
            check_accessor(&accessor, Usage::Index, buffers)?;
            let indices: Vec<u32> = reader
                .read_indices()
                .ok_or_else(|| unreadable(&accessor, Usage::Index))?
                .into_u32()
                .collect();
            if indices.len() != accessor.count() {
                return Err(unreadable(&accessor, Usage::Index));
            }
            if let Some(k) = indices.iter().position(|&i| i >= vertex_limit) {
                return Err(format!(
                    "accessor {} (indices): index {} at position {k} is out of range for {vertex_count} vertices",
                    accessor.index(),
                    indices[k]
                ));
            }
            indices
        }
    };
    let indices = triangulate(mode, &vertices).map_err(|p| match primitive.indices() {
        Some(accessor) => format!("accessor {} (indices): {p}", accessor.index()),
        None => format!("accessor {} (POSITION): {p}", position_accessor.index()),
    })?;

    Ok(Some(RawPrimitive {
        positions,
        normals,
        indices,
    }))
}

fn collect_vec3(
    iter: Option<impl Iterator<Item = [f32; 3]>>,
    accessor: &gltf::Accessor,
    usage: Usage,
) -> Result<Vec<DVec3>, String> {
    let values: Vec<DVec3> = iter
        .ok_or_else(|| unreadable(accessor, usage))?
        .map(|v| DVec3::from(v.map(f64::from)))
        .collect();
    if values.len() != accessor.count() {
        return Err(unreadable(accessor, usage));
    }
    Ok(values)
}

/// Reported if the reader still fails after [`check_accessor`] passed.
fn unreadable(accessor: &gltf::Accessor, usage: Usage) -> String {
    format!(
        "accessor {} ({}) could not be read",
        accessor.index(),
        usage.name()
    )
}

/// Turns a vertex sequence into triangles, per glTF's definition of each
/// mode (strips alternate the winding back to counter-clockwise; fans turn
/// around the first vertex).
fn triangulate(mode: Mode, v: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let n = v.len();
    Ok(match mode {
        Mode::Triangles => {
            if !n.is_multiple_of(3) {
                return Err(format!(
                    "a triangle list needs a multiple of 3 vertices, got {n}"
                ));
            }
            v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect()
        }
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [v[i], v[i + 1], v[i + 2]]
                } else {
                    [v[i], v[i + 2], v[i + 1]]
                }
            })
            .collect(),
        Mode::TriangleFan => (0..n.saturating_sub(2))
            .map(|i| [v[i + 1], v[i + 2], v[0]])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => Vec::new(),
    })
}

// ---------------------------------------------------------------------------
// Materials, lights, cameras

fn material_from_pbr(
    name: String,
    base_color: [f32; 4],
    metallic: f32,
    roughness: f32,
) -> Result<Material, String> {
    let [r, g, b, _alpha] = base_color.map(f64::from);
    let material = material_from_metallic_roughness(
        name,
        Rgb::new(r, g, b),
        f64::from(metallic),
        f64::from(roughness),
    );
    // Clamping leaves only non-finite factors to fail here.
    material.validate()?;
    Ok(material)
}

fn convert_light(light: &gltf::khr_lights_punctual::Light, world: DMat4) -> Result<Light, String> {
    let color = Rgb::from(light.color().map(f64::from));
    let intensity = f64::from(light.intensity());
    let power = color * intensity;
    if !power.is_finite() || power.min_element() < 0.0 {
        return Err(format!(
            "color {color} × intensity {intensity} is not a finite non-negative value"
        ));
    }
    let range = match light.range() {
        None => None,
        Some(r) if r.is_finite() && r > 0.0 => Some(f64::from(r)),
        Some(r) => return Err(format!("range {r} is not a positive number")),
    };
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world_axis(world, DVec3::NEG_Z)
        .ok_or("the node's transform gives the light no direction (zero scale)")?;
    Ok(match light.kind() {
        LightKind::Directional => Light::Directional {
            direction,
            irradiance: power,
            shadows: false,
        },
        LightKind::Point => Light::Point {
            position,
            intensity: power,
            range,
            shadows: false,
        },
        LightKind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
            // glTF asks 0 ≤ inner < outer ≤ π/2; equal cones are harmless
            // (the falloff has a floor), so only an inverted or out-of-range
            // pair is refused. π/2 is compared in f32, as the file wrote it.
            if !(0.0 <= inner && inner <= outer && outer_cone_angle <= std::f32::consts::FRAC_PI_2)
            {
                return Err(format!(
                    "spot cone angles inner {inner_cone_angle} and outer {outer_cone_angle} (radians) are not 0 ≤ inner ≤ outer ≤ π/2"
                ));
            }
            Light::Spot {
                position,
                direction,
                intensity: power,
                inner_cone_deg: inner.to_degrees(),
                outer_cone_deg: outer.to_degrees(),
                range,
                shadows: false,
            }
        }
    })
}

/// A node's local axis in world space, unit length, or `None` if the
/// transform collapses it. The threshold is absolute, not zero: a zero
/// scale combined with a rotation leaves rounding residue of ~1e-17 that
/// would otherwise normalize into an arbitrary direction.
fn world_axis(world: DMat4, local: DVec3) -> Option<DVec3> {
    let v = world.transform_vector3(local);
    (v.length() > 1e-12).then(|| v.normalize())
}

/// The node's camera, if it is perspective and gives a usable frame.
fn convert_camera(camera: &gltf::Camera, world: DMat4) -> Option<Camera> {
    let gltf::camera::Projection::Perspective(perspective) = camera.projection() else {
        return None;
    };
    let fov_y_deg = f64::from(perspective.yfov()).to_degrees();
    if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
        return None;
    }
    let position = world.transform_point3(DVec3::ZERO);
    let forward = world_axis(world, DVec3::NEG_Z)?;
    let up = world_axis(world, DVec3::Y)?;
    if forward.cross(up).length_squared() < 1e-12 {
        return None;
    }
    Some(Camera {
        position,
        target: position + forward,
        up,
        fov_y_deg,
        near: 0.0,
        far: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASSETS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/gltf");

    fn asset(relative: &str) -> PathBuf {
        Path::new(ASSETS).join(relative)
    }

    fn load_asset(relative: &str) -> GltfScene {
        let path = asset(relative);
        load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    }

    fn triangles(scene: &GltfScene) -> usize {
        scene.meshes.iter().map(|m| m.indices.len()).sum()
    }

    fn scene_bounds(scene: &GltfScene) -> (DVec3, DVec3) {
        crate::scene::mesh::bounds(
            scene
                .meshes
                .iter()
                .flat_map(|m| m.positions.iter().copied()),
        )
        .expect("geometry")
    }

    fn assert_unit_normals(scene: &GltfScene) {
        for mesh in &scene.meshes {
            assert_eq!(mesh.normals.len(), mesh.positions.len());
            for n in &mesh.normals {
                assert!((n.length() - 1.0).abs() < 1e-9, "{}: normal {n}", mesh.name);
            }
        }
    }

    #[test]
    fn box_gltf_and_glb_agree() {
        let text = load_asset("Box/Box.gltf");
        let binary = load_asset("Box/Box.glb");
        assert_eq!(triangles(&text), 12);
        assert_eq!(triangles(&binary), 12);
        let (a, b) = (scene_bounds(&text), scene_bounds(&binary));
        assert!((a.0 - b.0).length() < 1e-12 && (a.1 - b.1).length() < 1e-12);
        // The unit box is rotated by the root node: still ±0.5 on all axes.
        assert!((a.0 + DVec3::splat(0.5)).length() < 1e-6, "{a:?}");
        assert!((a.1 - DVec3::splat(0.5)).length() < 1e-6, "{a:?}");
        assert_unit_normals(&text);
        assert_eq!(text.materials.len(), 1);
        assert_eq!(text.materials[0].name, "Red");
        assert_eq!(text.materials[0].model, ReflectanceModel::BlinnPhong);
        assert!((text.materials[0].k_d - DVec3::new(0.8, 0.0, 0.0)).length() < 1e-6);
        assert_eq!(text.skipped_primitives, 0);
    }

    #[test]
    fn box_normals_point_out_of_the_box() {
        let scene = load_asset("Box/Box.gltf");
        for mesh in &scene.meshes {
            for t in 0..mesh.indices.len() {
                let corners = mesh.triangle(t);
                let centroid = crate::scene::mesh::centroid(corners);
                let n = crate::scene::mesh::face_normal(corners);
                assert!(n.dot(centroid) > 0.0, "inward face {t}");
            }
        }
    }

    #[test]
    fn interleaved_box_matches_the_plain_box() {
        let plain = load_asset("Box/Box.gltf");
        let interleaved = load_asset("BoxInterleaved/BoxInterleaved.gltf");
        assert_eq!(triangles(&interleaved), 12);
        let (a, b) = (scene_bounds(&plain), scene_bounds(&interleaved));
        assert!((a.0 - b.0).length() < 1e-12 && (a.1 - b.1).length() < 1e-12);
        assert_unit_normals(&interleaved);
    }

    #[test]
    fn triangle_without_indices_gets_generated_normals() {
        let scene = load_asset("TriangleWithoutIndices/TriangleWithoutIndices.gltf");
        assert_eq!(scene.meshes.len(), 1);
        assert_eq!(triangles(&scene), 1);
        for n in &scene.meshes[0].normals {
            assert!((*n - DVec3::Z).length() < 1e-12, "{n}");
        }
        // No material in the file: glTF's default, mapped like the others.
        let material = &scene.materials[scene.meshes[0].material];
        assert_eq!(material.name, "gltf-default");
        assert_eq!(material.k_d, Rgb::ZERO);
        // F0 = b = 1, damped by (k_e + 8)/(8π) for k_e = 1.
        let k_s = 9.0 / (8.0 * std::f64::consts::PI);
        assert!((material.k_s - Rgb::splat(k_s)).abs().max_element() < 1e-15);
        assert_eq!(material.k_e, 1.0);
    }

    #[test]
    fn suzanne_has_its_own_normals() {
        let scene = load_asset("Suzanne/Suzanne.gltf");
        assert!(triangles(&scene) > 0);
        assert_unit_normals(&scene);
        // The file's normals are smooth, which generated ones would not
        // reproduce exactly; check they were taken from the file.
        let mesh = &scene.meshes[0];
        let generated = area_weighted_normals(&mesh.positions, &mesh.indices);
        assert!(
            mesh.normals
                .iter()
                .zip(&generated)
                .any(|(a, b)| (*a - *b).length() > 1e-3)
        );
    }

    #[test]
    fn other_samples_load() {
        for (file, min_triangles) in [
            ("Avocado/Avocado.gltf", 100),
            ("Triangle/Triangle.gltf", 1),
            ("NormalTangentTest/NormalTangentTest.glb", 100),
            ("MultipleScenes/MultipleScenes.gltf", 1),
        ] {
            let scene = load_asset(file);
            assert!(triangles(&scene) >= min_triangles, "{file}");
            assert_unit_normals(&scene);
            for m in &scene.materials {
                m.validate().unwrap();
            }
        }
    }

    #[test]
    fn multiple_scenes_uses_the_default_scene_only() {
        // `scene = 1` lists node 1 alone.
        let scene = load_asset("MultipleScenes/MultipleScenes.gltf");
        assert_eq!(scene.meshes.len(), 1);
        assert_eq!(scene.meshes[0].name, "mesh 1");
    }

    #[test]
    fn shadows_directional_has_a_directional_light_and_a_camera() {
        let scene = load_asset("ShadowsDirectional/shadows-directional.gltf");
        let directional: Vec<_> = scene
            .lights
            .iter()
            .filter_map(|l| match l {
                Light::Directional {
                    direction,
                    irradiance,
                    shadows,
                } => Some((*direction, *irradiance, *shadows)),
                _ => None,
            })
            .collect();
        assert_eq!(directional.len(), 1);
        let (direction, irradiance, shadows) = directional[0];
        assert!((direction.length() - 1.0).abs() < 1e-12);
        assert!(direction.y < 0.0, "the sun shines downwards: {direction}");
        assert!((irradiance - Rgb::splat(10.0)).length() < 1e-9);
        assert!(!shadows);
        let camera = scene.camera.expect("camera");
        assert!((camera.fov_y_deg - 0.39959652046304894f64.to_degrees()).abs() < 1e-5);
        assert_eq!((camera.near, camera.far), (0.0, 0.0));
        // The camera at (20, 17.5, 20) looks back towards the origin.
        assert!(camera.forward().dot(-camera.position.normalize()) > 0.9);
        assert_eq!(scene.materials.len(), 4);
    }

    #[test]
    fn simple_meshes_instances_the_shared_mesh() {
        let scene = load_asset("SimpleMeshes/SimpleMeshes.gltf");
        assert_eq!(scene.meshes.len(), 2);
        let shift = scene.meshes[1].positions[0] - scene.meshes[0].positions[0];
        assert!((shift - DVec3::X).length() < 1e-12, "{shift}");
    }

    #[test]
    fn cameras_takes_the_perspective_camera() {
        let scene = load_asset("Cameras/Cameras.gltf");
        let camera = scene.camera.expect("camera");
        assert!((camera.position - DVec3::new(0.5, 0.5, 3.0)).length() < 1e-6);
        assert!((camera.forward() - DVec3::NEG_Z).length() < 1e-12);
        assert!((camera.up - DVec3::Y).length() < 1e-12);
        assert!((camera.fov_y_deg - 0.7f64.to_degrees()).abs() < 1e-5);
    }

    #[test]
    fn metallic_roughness_mapping() {
        let b = Rgb::new(0.9, 0.5, 0.1);
        let dielectric = material_from_metallic_roughness("d", b, 0.0, 0.5);
        assert_eq!(dielectric.k_d, b);
        assert_eq!(dielectric.k_a, b);
        assert!((dielectric.k_s - Rgb::splat(0.04)).length() < 1e-15);
        // α = 0.25: 2/α² − 2 = 30.
        assert!((dielectric.k_e - 30.0).abs() < 1e-12);
        let metal = material_from_metallic_roughness("m", b, 1.0, 0.0);
        assert_eq!(metal.k_d, Rgb::ZERO);
        assert_eq!(metal.k_s, b);
        assert_eq!(metal.k_e, 1e6);
        let wild = material_from_metallic_roughness("w", Rgb::splat(7.0), -3.0, 9.0);
        wild.validate().unwrap();
        assert_eq!(wild.k_e, 1.0);
    }

    #[test]
    fn strips_and_fans_become_ccw_triangles() {
        let v = [0, 1, 2, 3, 4];
        assert_eq!(
            triangulate(Mode::TriangleStrip, &v).unwrap(),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            triangulate(Mode::TriangleFan, &v).unwrap(),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert!(triangulate(Mode::Triangles, &v).is_err());
        assert!(
            triangulate(Mode::TriangleStrip, &v[..2])
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn uri_helpers() {
        assert!(has_scheme("http://example.com/a.bin"));
        assert!(has_scheme("file:///etc/passwd"));
        assert!(has_scheme("C:/x.bin"));
        assert!(!has_scheme("a.bin"));
        assert!(!has_scheme("./a:b.bin"));
        assert_eq!(percent_decode("a%20b%2Fc.bin").unwrap(), "a b/c.bin");
        assert!(percent_decode("a%2").is_err());
        assert!(percent_decode("a%+1").is_err());
        assert!(percent_decode("%FF").is_err());
        assert!(relative_path("sub/../a.bin").is_ok());
        assert!(relative_path("sub/../../a.bin").is_err());
        assert!(relative_path("/etc/passwd").is_err());
        assert!(relative_path("..\\a.bin").is_err());
    }

    #[test]
    fn a_panic_in_the_parser_becomes_an_error() {
        // Prints the panic message; the point is that it is caught.
        let result: Result<(), String> = guarded(|| panic!("simulated gltf crate bug"));
        assert_eq!(result.unwrap_err(), PARSER_PANICKED);
    }

    // -- malformed files ---------------------------------------------------

    /// A one-triangle glTF whose only buffer has the given URI and 44
    /// bytes: three `VEC3` positions and three `u16` indices (+2 padding).
    /// Tests edit the text with `replace` to break one thing at a time.
    fn triangle_gltf(uri: &str) -> String {
        r#"{
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": "URI", "byteLength": 44}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 6}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ]
}"#
        .replace("URI", uri)
    }

    fn triangle_bytes(indices: [u16; 3]) -> Vec<u8> {
        let mut bytes = Vec::new();
        for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for c in p {
                bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
        for i in indices {
            bytes.extend_from_slice(&i.to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
        bytes
    }

    fn data_uri(bytes: &[u8]) -> String {
        format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        )
    }

    /// Writes `contents` as `name` in a fresh folder and loads it.
    fn load_written(dir: &Path, name: &str, contents: &[u8]) -> Result<GltfScene> {
        let path = dir.join(name);
        fs::write(&path, contents).unwrap();
        load(&path)
    }

    /// Asserts an input error naming the file whose message contains all
    /// of `needles`.
    fn assert_input_error(result: Result<GltfScene>, needles: &[&str]) {
        match result {
            Err(Error::Input { path, problem }) => {
                assert!(
                    path.to_string_lossy().contains("model"),
                    "{}",
                    path.display()
                );
                for needle in needles {
                    assert!(problem.contains(needle), "`{needle}` not in: {problem}");
                }
            }
            Err(e) => panic!("expected an input error, got {e}"),
            Ok(_) => panic!("expected an error for {needles:?}"),
        }
    }

    #[test]
    fn the_test_triangle_loads() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])));
        let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
        assert_eq!(triangles(&scene), 1);
        // External buffer, percent-encoded name, in a subfolder.
        fs::create_dir(dir.path().join("sub dir")).unwrap();
        fs::write(
            dir.path().join("sub dir/tri.bin"),
            triangle_bytes([0, 1, 2]),
        )
        .unwrap();
        let gltf = triangle_gltf("sub%20dir/./tri.bin");
        let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
        assert_eq!(triangles(&scene), 1);
    }

    #[test]
    fn invalid_json_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let result = load_written(dir.path(), "model.gltf", b"{ \"asset\": ");
        assert_input_error(result, &["invalid glTF"]);
    }

    #[test]
    fn truncated_glb_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let glb = fs::read(asset("Box/Box.glb")).unwrap();
        let result = load_written(dir.path(), "model.glb", &glb[..20]);
        assert_input_error(result, &["invalid GLB"]);
    }

    #[test]
    fn buffer_outside_the_folder_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join("outside.bin"), triangle_bytes([0, 1, 2])).unwrap();
        let inner = dir.path().join("inner");
        fs::create_dir(&inner).unwrap();
        for (uri, needle) in [
            ("../outside.bin", "leaves the glTF's folder"),
            ("sub/../../outside.bin", "leaves the glTF's folder"),
            ("%2E%2E/outside.bin", "leaves the glTF's folder"),
            ("/etc/passwd", "absolute path"),
            ("http://example.com/tri.bin", "URI scheme"),
            ("file:///etc/passwd", "URI scheme"),
            ("missing.bin", "cannot be opened"),
            (".", "is not a regular file"),
        ] {
            let gltf = triangle_gltf(uri);
            let result = load_written(&inner, "model.gltf", gltf.as_bytes());
            assert_input_error(result, &["buffer 0", needle]);
        }
    }

    #[cfg(unix)]
    #[test]
    fn symlink_out_of_the_folder_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join("outside.bin"), triangle_bytes([0, 1, 2])).unwrap();
        let inner = dir.path().join("inner");
        fs::create_dir(&inner).unwrap();
        std::os::unix::fs::symlink(dir.path().join("outside.bin"), inner.join("link.bin")).unwrap();
        let gltf = triangle_gltf("link.bin");
        let result = load_written(&inner, "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["outside the glTF's folder"]);
    }

    #[test]
    fn short_buffer_file_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join("tri.bin"), &triangle_bytes([0, 1, 2])[..40]).unwrap();
        let gltf = triangle_gltf("tri.bin");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["buffer 0", "40 bytes", "byteLength 44"]);
    }

    #[test]
    fn huge_buffer_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let gltf =
            triangle_gltf("tri.bin").replace("\"byteLength\": 44", "\"byteLength\": 2000000000");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["buffer 0", "1 GiB"]);
    }

    #[test]
    fn bad_base64_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf("data:application/octet-stream;base64,AAAA*AAA");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["buffer 0", "invalid base64"]);
        let gltf = triangle_gltf("data:application/octet-stream,plain");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["buffer 0", "without base64"]);
    }

    #[test]
    fn unsupported_required_extension_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2]))).replace(
            "\"scene\": 0,",
            r#""scene": 0,
  "extensionsUsed": ["KHR_draco_mesh_compression"],
  "extensionsRequired": ["KHR_draco_mesh_compression"],"#,
        );
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["KHR_draco_mesh_compression"]);
    }

    #[test]
    fn index_out_of_range_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 7])));
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 1", "index 7", "out of range"]);
    }

    #[test]
    fn accessor_outside_its_view_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let uri = data_uri(&triangle_bytes([0, 1, 2]));
        // Four positions in a 36-byte view.
        let gltf = triangle_gltf(&uri).replace(
            "\"count\": 3, \"type\": \"VEC3\"",
            "\"count\": 4, \"type\": \"VEC3\"",
        );
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 0 (POSITION)", "do not fit"]);
        // A view reaching past the end of its buffer.
        let gltf = triangle_gltf(&uri).replace(
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 40, \"byteLength\": 6",
        );
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 1 (indices)", "buffer view 1"]);
        // An offset so large that offset + stride·(count−1) overflows.
        let gltf = triangle_gltf(&uri).replace(
            "{\"bufferView\": 1, ",
            "{\"bufferView\": 1, \"byteOffset\": 18446744073709551610, ",
        );
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 1 (indices)", "do not fit"]);
        // Wrong component type for positions.
        let gltf =
            triangle_gltf(&uri).replace("\"componentType\": 5126", "\"componentType\": 5123");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 0 (POSITION)", "expected VEC3 of FLOAT"]);
    }

    #[test]
    fn non_finite_position_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let mut bytes = triangle_bytes([0, 1, 2]);
        bytes[12..16].copy_from_slice(&f32::NAN.to_le_bytes());
        let gltf = triangle_gltf(&data_uri(&bytes));
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["accessor 0 (POSITION)", "vertex 1", "not finite"]);
    }

    #[test]
    fn missing_position_accessor_does_not_panic() {
        // gltf-json's validation would index `accessors[99]` unchecked.
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
            .replace("\"POSITION\": 0", "\"POSITION\": 99");
        let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["POSITION", "accessor 99 does not exist"]);
    }

    #[test]
    fn cyclic_and_shared_nodes_are_input_errors() {
        let dir = tempfile::tempdir().unwrap();
        let base = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])));
        let cyclic = base.replace(
            "\"nodes\": [{\"mesh\": 0}]",
            "\"nodes\": [{\"mesh\": 0, \"children\": [1]}, {\"children\": [0]}]",
        );
        let result = load_written(dir.path(), "model.gltf", cyclic.as_bytes());
        assert_input_error(result, &["node 0", "reached twice"]);
        let shared = base
            .replace(
                "\"nodes\": [{\"mesh\": 0}]",
                "\"nodes\": [{\"children\": [2]}, {\"children\": [2]}, {\"mesh\": 0}]",
            )
            .replace(
                "\"scenes\": [{\"nodes\": [0]}]",
                "\"scenes\": [{\"nodes\": [0, 1]}]",
            );
        let result = load_written(dir.path(), "model.gltf", shared.as_bytes());
        assert_input_error(result, &["node 2", "reached twice"]);
    }

    #[test]
    fn points_are_skipped_and_counted() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
            .replace("\"indices\": 1}", "\"indices\": 1, \"mode\": 0}");
        let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
        assert!(scene.meshes.is_empty());
        assert_eq!(scene.skipped_primitives, 1);
        assert!(scene.materials.is_empty());
    }

    #[test]
    fn lights_and_scaled_nodes() {
        let dir = tempfile::tempdir().unwrap();
        let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
            .replace(
                "\"scene\": 0,",
                r#""scene": 0,
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "point", "color": [1, 0.5, 0], "intensity": 4, "range": 10},
    {"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}
  ]}},"#,
            )
            .replace(
                "\"scenes\": [{\"nodes\": [0]}]",
                "\"scenes\": [{\"nodes\": [0, 1, 2]}]",
            )
            .replace(
                "\"nodes\": [{\"mesh\": 0}]",
                r#""nodes": [
    {"mesh": 0, "scale": [2, 0, 1]},
    {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"rotation": [-0.7071068, 0, 0, 0.7071068], "extensions": {"KHR_lights_punctual": {"light": 1}}}
  ]"#,
            );
        let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
        // The zero scale flattens the triangle; normals stay unit length.
        assert_eq!(triangles(&scene), 1);
        assert_unit_normals(&scene);
        assert_eq!(scene.lights.len(), 2);
        match &scene.lights[0] {
            Light::Point {
                position,
                intensity,
                range,
                shadows,
            } => {
                assert!((*position - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
                assert!((*intensity - Rgb::new(4.0, 2.0, 0.0)).length() < 1e-12);
                assert_eq!(*range, Some(10.0));
                assert!(!shadows);
            }
            other => panic!("{other:?}"),
        }
        match &scene.lights[1] {
            Light::Spot {
                direction,
                intensity,
                inner_cone_deg,
                outer_cone_deg,
                range,
                ..
            } => {
                // −90° about X turns −Z into −Y.
                assert!((*direction - DVec3::NEG_Y).length() < 1e-6, "{direction}");
                assert_eq!(*intensity, Rgb::splat(2.0));
                assert!((inner_cone_deg - 0.1f64.to_degrees()).abs() < 1e-5);
                assert!((outer_cone_deg - 0.5f64.to_degrees()).abs() < 1e-5);
                assert_eq!(*range, None);
            }
            other => panic!("{other:?}"),
        }
        // Under the zero-scaled node the spot would have no direction.
        let nested = gltf
            .replace(
                "\"scale\": [2, 0, 1]}",
                "\"scale\": [2, 0, 1], \"children\": [2]}",
            )
            .replace("[0, 1, 2]", "[0, 1]");
        let result = load_written(dir.path(), "model.gltf", nested.as_bytes());
        assert_input_error(result, &["node 2", "light 1", "no direction"]);
    }
}
