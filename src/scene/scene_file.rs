//! The scene `.toml` of the contract, `--set` overrides by dotted path, and
//! the assembly of a [`Scene`] from it.
//!
//! Loading has three steps, each with its own kind of error message:
//! 1. parse the text (syntax and type errors carry line and column);
//! 2. apply `--set KEY=VALUE` overrides one by one, so an error names the
//!    override that caused it;
//! 3. validate values and assemble the scene (range errors name the key).
//!
//! A `.gltf`/`.glb` argument and the built-in scene go through the same
//! steps: they are turned into an equivalent scene table first.

use crate::base::ColorValue;
use crate::material::{Material, MaterialEntry, ReflectanceModel, material_from_entry};
use crate::scene::limits::{Limits, ReadError, read_regular_file};
use crate::scene::{
    AreaLight, Camera, Environment, Light, Mesh, Rgb, Scene, ShadingMode, ShadowFilter,
    ShadowSettings, area_light, default_scene::DEFAULT_SCENE_TOML, gltf_import, primitives,
};
use crate::{Error, Result};
use glam::DVec3;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest image side gonio accepts (a 16k render is ~3 GiB of f32 RGBA).
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The whole scene file. Unknown keys anywhere are errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(default)]
    pub image: ImageSection,
    pub camera: Option<CameraSection>,
    #[serde(default)]
    pub shading: ShadingSection,
    #[serde(default)]
    pub objects: Vec<ObjectEntry>,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialEntry>,
    #[serde(default)]
    pub lights: Vec<LightEntry>,
    #[serde(default)]
    pub shadows: ShadowsSection,
    #[serde(default)]
    pub ambient: AmbientSection,
    #[serde(default)]
    pub environment: EnvironmentSection,
}

/// `[image]`: output size in pixels.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageSection {
    #[serde(default = "default_width")]
    pub width: u32,
    #[serde(default = "default_height")]
    pub height: u32,
    /// Samples per pixel of the GPU renderer's multisampling: 1 (none,
    /// the default) or 4. The CPU reference always takes one sample at
    /// the pixel centre.
    #[serde(default)]
    pub msaa: Option<u32>,
}

fn default_width() -> u32 {
    640
}
fn default_height() -> u32 {
    480
}

impl Default for ImageSection {
    fn default() -> Self {
        ImageSection {
            width: default_width(),
            height: default_height(),
            msaa: None,
        }
    }
}

/// `[camera]`: a perspective camera looking from `position` to `target`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    pub position: [f64; 3],
    pub target: [f64; 3],
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    #[serde(default = "default_fov")]
    pub fov_y_deg: f64,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov() -> f64 {
    45.0
}

/// `[shading]`: flat | gouraud | phong.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadingSection {
    #[serde(default)]
    pub mode: Option<String>,
}

/// One `[[objects]]` entry: a glTF file or a generated shape.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectEntry {
    /// A `.gltf`/`.glb`, relative to the scene file.
    pub gltf: Option<String>,
    /// A generated shape: `sphere` or `plane` (gonio's extension).
    pub shape: Option<String>,
    /// Sphere centre or plane centre.
    pub center: Option<[f64; 3]>,
    /// Sphere radius.
    pub radius: Option<f64>,
    /// Plane side length.
    pub size: Option<f64>,
    /// Tessellation: sphere slices, or plane divisions per side.
    pub segments: Option<u32>,
    /// Material name in `[materials]`; overrides a glTF's own materials.
    pub material: Option<String>,
}

/// `[[lights]]`, tagged by `kind`. Every kind takes `shadows` and the
/// shadow-map keys `shadow_map_size`, `shadow_bias`, `shadow_slope_bias`,
/// `shadow_normal_offset`, `shadow_filter`, `shadow_pcf_kernel` (defaults
/// from `[shadows]`; meanings in `docs/shadows.md`).
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightEntry {
    Point {
        position: [f64; 3],
        intensity: ColorValue,
        #[serde(default)]
        range: Option<f64>,
        #[serde(default)]
        shadows: bool,
        #[serde(default)]
        shadow_map_size: Option<u32>,
        #[serde(default)]
        shadow_bias: Option<f64>,
        #[serde(default)]
        shadow_slope_bias: Option<f64>,
        #[serde(default)]
        shadow_normal_offset: Option<f64>,
        #[serde(default)]
        shadow_filter: Option<String>,
        #[serde(default)]
        shadow_pcf_kernel: Option<u32>,
    },
    Directional {
        direction: [f64; 3],
        irradiance: ColorValue,
        #[serde(default)]
        shadows: bool,
        #[serde(default)]
        shadow_map_size: Option<u32>,
        #[serde(default)]
        shadow_bias: Option<f64>,
        #[serde(default)]
        shadow_slope_bias: Option<f64>,
        #[serde(default)]
        shadow_normal_offset: Option<f64>,
        #[serde(default)]
        shadow_filter: Option<String>,
        #[serde(default)]
        shadow_pcf_kernel: Option<u32>,
    },
    Spot {
        position: [f64; 3],
        direction: [f64; 3],
        intensity: ColorValue,
        #[serde(default)]
        inner_cone_deg: Option<f64>,
        #[serde(default)]
        outer_cone_deg: Option<f64>,
        #[serde(default)]
        range: Option<f64>,
        #[serde(default)]
        shadows: bool,
        #[serde(default)]
        shadow_map_size: Option<u32>,
        #[serde(default)]
        shadow_bias: Option<f64>,
        #[serde(default)]
        shadow_slope_bias: Option<f64>,
        #[serde(default)]
        shadow_normal_offset: Option<f64>,
        #[serde(default)]
        shadow_filter: Option<String>,
        #[serde(default)]
        shadow_pcf_kernel: Option<u32>,
    },
    /// A rectangle or disk emitting radiance `L` with a cosine
    /// distribution about `normal`, rendered as `samples` point lights.
    Area {
        shape: String,
        position: [f64; 3],
        normal: [f64; 3],
        /// Rectangle: `[w, h]`, `w` along `tangent`.
        #[serde(default)]
        size: Option<[f64; 2]>,
        #[serde(default)]
        tangent: Option<[f64; 3]>,
        /// Disk radius.
        #[serde(default)]
        radius: Option<f64>,
        radiance: ColorValue,
        #[serde(default)]
        samples: Option<u32>,
        /// GPU: one shadow cube per sample instead of one shared at the
        /// centre.
        #[serde(default)]
        shadow_per_sample: bool,
        #[serde(default)]
        shadows: bool,
        #[serde(default)]
        shadow_map_size: Option<u32>,
        #[serde(default)]
        shadow_bias: Option<f64>,
        #[serde(default)]
        shadow_slope_bias: Option<f64>,
        #[serde(default)]
        shadow_normal_offset: Option<f64>,
        #[serde(default)]
        shadow_filter: Option<String>,
        #[serde(default)]
        shadow_pcf_kernel: Option<u32>,
    },
}

/// The shadow-map keys of one `[[lights]]` entry.
#[derive(Clone, Debug, Default)]
pub struct ShadowKeys {
    pub map_size: Option<u32>,
    pub bias: Option<f64>,
    pub slope_bias: Option<f64>,
    pub normal_offset: Option<f64>,
    pub filter: Option<String>,
    pub pcf_kernel: Option<u32>,
}

impl LightEntry {
    /// The entry's `shadows` flag and shadow-map keys.
    pub fn shadow_keys(&self) -> (bool, ShadowKeys) {
        match self {
            LightEntry::Point {
                shadows,
                shadow_map_size,
                shadow_bias,
                shadow_slope_bias,
                shadow_normal_offset,
                shadow_filter,
                shadow_pcf_kernel,
                ..
            }
            | LightEntry::Directional {
                shadows,
                shadow_map_size,
                shadow_bias,
                shadow_slope_bias,
                shadow_normal_offset,
                shadow_filter,
                shadow_pcf_kernel,
                ..
            }
            | LightEntry::Spot {
                shadows,
                shadow_map_size,
                shadow_bias,
                shadow_slope_bias,
                shadow_normal_offset,
                shadow_filter,
                shadow_pcf_kernel,
                ..
            }
            | LightEntry::Area {
                shadows,
                shadow_map_size,
                shadow_bias,
                shadow_slope_bias,
                shadow_normal_offset,
                shadow_filter,
                shadow_pcf_kernel,
                ..
            } => (
                *shadows,
                ShadowKeys {
                    map_size: *shadow_map_size,
                    bias: *shadow_bias,
                    slope_bias: *shadow_slope_bias,
                    normal_offset: *shadow_normal_offset,
                    filter: shadow_filter.clone(),
                    pcf_kernel: *shadow_pcf_kernel,
                },
            ),
        }
    }
}

/// `[shadows]`: shadow-map defaults for every light that does not set its
/// own (gonio's extension), and whether lights imported from glTF files
/// cast shadows.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowsSection {
    /// `KHR_lights_punctual` lights cast shadows (default: no).
    #[serde(default)]
    pub imported_lights: bool,
    pub map_size: Option<u32>,
    pub bias: Option<f64>,
    pub slope_bias: Option<f64>,
    pub normal_offset: Option<f64>,
    pub filter: Option<String>,
    pub pcf_kernel: Option<u32>,
}

impl ShadowsSection {
    fn keys(&self) -> ShadowKeys {
        ShadowKeys {
            map_size: self.map_size,
            bias: self.bias,
            slope_bias: self.slope_bias,
            normal_offset: self.normal_offset,
            filter: self.filter.clone(),
            pcf_kernel: self.pcf_kernel,
        }
    }
}

/// `[environment]`: the sky a mirror reflects (gonio's extension); every
/// key defaults to the ambient radiance.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    pub zenith: Option<ColorValue>,
    pub horizon: Option<ColorValue>,
    pub ground: Option<ColorValue>,
}

/// `[ambient]`: constant incoming radiance `L_a`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AmbientSection {
    #[serde(default)]
    pub radiance: Option<ColorValue>,
}

/// Where a scene comes from.
#[derive(Clone, Debug)]
pub enum SceneSource {
    /// The built-in scene.
    BuiltIn,
    /// A file: `.toml`, `.gltf` or `.glb`.
    File(PathBuf),
}

/// Loads a scene from `source`, applying `overrides` (`KEY=VALUE`, dotted
/// keys) in order.
pub fn load(source: &SceneSource, overrides: &[String]) -> Result<Scene> {
    load_with_limits(source, overrides, Limits::default()).map(|(scene, _notes)| scene)
}

/// [`load`] with the glTF files of the scene held to `limits` (one budget
/// for all of them); also returns the notes their import left, such as
/// ignored optional extensions, for `--verbose`.
pub fn load_with_limits(
    source: &SceneSource,
    overrides: &[String],
    limits: Limits,
) -> Result<(Scene, Vec<String>)> {
    let (origin, base_dir, mut table) = scene_table(source)?;
    // Parse once without overrides: errors here are the file's, with spans.
    let mut file = parse_table(&origin, &table)?;
    for kv in overrides {
        apply_override(&mut table, kv)?;
        file = SceneFile::deserialize(toml::Value::Table(table.clone()))
            .map_err(|e| Error::argument(format!("--set {kv}"), clean_toml_error(&e)))?;
    }
    let mut gltf_files = gltf_import::GltfLoader::new(limits);
    let scene = assemble(&origin, &base_dir, file, &mut gltf_files)?;
    Ok((scene, gltf_files.notes().to_vec()))
}

/// The scene table of `source` before overrides, with the file (or a
/// pseudo-path for the built-in scene) that errors name and the folder
/// its relative paths resolve in.
pub fn scene_table(source: &SceneSource) -> Result<(PathBuf, PathBuf, toml::Table)> {
    match source {
        SceneSource::BuiltIn => {
            let table = DEFAULT_SCENE_TOML
                .parse::<toml::Table>()
                .expect("the built-in scene is valid TOML");
            Ok(("<built-in scene>".into(), PathBuf::from("."), table))
        }
        SceneSource::File(path) => {
            let base_dir = path
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_else(|| PathBuf::from("."));
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            match ext.as_deref() {
                Some("toml") => {
                    let text = read_scene_text(path)?;
                    // Typed parse first: syntax and type errors with line/column.
                    toml::from_str::<SceneFile>(&text)
                        .map_err(|e| Error::input(path, clean_toml_error(&e)))?;
                    let table = text
                        .parse::<toml::Table>()
                        .map_err(|e| Error::input(path, clean_toml_error(&e)))?;
                    Ok((path.clone(), base_dir, table))
                }
                Some("gltf") | Some("glb") => {
                    match std::fs::metadata(path) {
                        Ok(meta) if meta.is_file() => {}
                        Ok(_) => {
                            return Err(Error::input(
                                path,
                                "is not a regular file (a directory, FIFO or device); a glTF scene must be a .gltf or .glb file",
                            ));
                        }
                        Err(e) => {
                            return Err(Error::input(path, format!("cannot read the file: {e}")));
                        }
                    }
                    let name = path.file_name().unwrap_or_default().to_string_lossy();
                    let mut object = toml::Table::new();
                    object.insert("gltf".into(), toml::Value::String(name.into_owned()));
                    let mut table = toml::Table::new();
                    table.insert(
                        "objects".into(),
                        toml::Value::Array(vec![toml::Value::Table(object)]),
                    );
                    Ok((path.clone(), base_dir, table))
                }
                _ => Err(Error::input(
                    path,
                    "unknown scene type: expected a .toml scene file, a .gltf or a .glb",
                )),
            }
        }
    }
}

fn parse_table(origin: &Path, table: &toml::Table) -> Result<SceneFile> {
    SceneFile::deserialize(toml::Value::Table(table.clone()))
        .map_err(|e| Error::input(origin, clean_toml_error(&e)))
}

/// Largest scene file read. Scene files are hand-written text, far
/// smaller; the cap bounds what parsing can allocate.
const MAX_SCENE_FILE_BYTES: u64 = 16 << 20;

/// Most parts a `--set` key may have; the deepest real key has three
/// (`materials.ball.roughness`). Without a cap a key of 60 000 parts builds
/// tables so deep that dropping them overflows the stack.
const MAX_KEY_DEPTH: usize = 16;

/// Longest error message kept from toml (its messages quote the offending
/// value, which may be megabytes long).
const MAX_MESSAGE_CHARS: usize = 600;

/// The text of a scene file: a regular file (not a FIFO or a device, which
/// would block or never end), of bounded size, in UTF-8.
fn read_scene_text(path: &Path) -> Result<String> {
    let bytes = read_regular_file(path, MAX_SCENE_FILE_BYTES).map_err(|e| {
        let problem = match e {
            ReadError::TooLarge(len) => format!(
                "the scene file has {len} bytes; scene files may have at most {MAX_SCENE_FILE_BYTES}"
            ),
            other => other.to_string(),
        };
        Error::input(path, problem)
    })?;
    String::from_utf8(bytes).map_err(|e| {
        Error::input(
            path,
            format!(
                "the scene file is not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Makes one paragraph of a toml error: `line L, column C (`source
/// line`): message`, without toml's caret diagram, cut to a readable
/// length, and with a suggestion when the problem is a misspelt key or
/// value name.
fn clean_toml_error(e: &impl std::fmt::Display) -> String {
    let text = e.to_string();
    let mut location = None;
    let mut source_line = None;
    let mut message = Vec::new();
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(at) = line.strip_prefix("TOML parse error at ") {
            location = Some(at);
        } else if let Some(code) = snippet_code(line) {
            source_line = source_line.or(code);
        } else {
            message.push(line);
        }
    }
    let message = message.join(" ");
    let suggestion = unknown_name_suggestion(&message)
        .map(|name| format!("; did you mean `{name}`?"))
        .unwrap_or_default();
    let mut out = String::new();
    if let Some(at) = location {
        out += at;
        if let Some(code) = source_line {
            out += &format!(" (`{}`)", shorten(code, 60));
        }
        out += ": ";
    }
    out += &shorten(&message, MAX_MESSAGE_CHARS);
    out + &suggestion
}

/// A line of toml's caret diagram: `|`, `  |   ^^^` or `12 | code`. Returns
/// `Some(Some(code))` for a source line, `Some(None)` for the others.
fn snippet_code(line: &str) -> Option<Option<&str>> {
    if line.starts_with('|') {
        return Some(None);
    }
    let (number, code) = line.split_once(" |")?;
    (!number.is_empty() && number.bytes().all(|b| b.is_ascii_digit()))
        .then(|| Some(code.trim()).filter(|c| !c.is_empty()))
}

/// At most `max` characters of `text`, with `…` where it was cut.
fn shorten(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

/// For serde's `unknown field `x`, expected one of `a`, `b`` (and the same
/// for variants), the expected name nearest to `x`, if one is near enough
/// to be a likely misspelling.
fn unknown_name_suggestion(message: &str) -> Option<&str> {
    let rest = message
        .split_once("unknown field `")
        .or_else(|| message.split_once("unknown variant `"))?
        .1;
    let (unknown, rest) = rest.split_once('`')?;
    let expected = rest.split_once("expected")?.1;
    // Deserializing from a table appends the table's path: ` in `camera``.
    let expected = expected.split(" in `").next().unwrap_or_default();
    let candidates = expected.split('`').skip(1).step_by(2);
    nearest_name(unknown, candidates)
}

/// The candidate closest to `unknown` by edit distance (ignoring case), if
/// within a third of its length (at least 2 edits), or if one is a prefix
/// of the other (`fov` for `fov_y_deg`).
fn nearest_name<'c>(unknown: &str, candidates: impl Iterator<Item = &'c str>) -> Option<&'c str> {
    // Keys are short; a long one is not a typo, and edit distance is
    // quadratic.
    if unknown.is_empty() || unknown.len() > 64 {
        return None;
    }
    let unknown = unknown.to_lowercase();
    let budget = (unknown.chars().count() / 3).max(2);
    candidates
        .filter(|c| !c.is_empty())
        .map(|c| {
            let lower = c.to_lowercase();
            let prefix = lower.starts_with(&unknown) || unknown.starts_with(&lower);
            (edit_distance(&unknown, &lower), prefix, c)
        })
        .filter(|&(distance, prefix, _)| distance <= budget || prefix)
        .min_by_key(|&(distance, _, _)| distance)
        .map(|(_, _, c)| c)
}

/// Levenshtein distance (insertions, deletions, substitutions), by chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        current[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitute.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

/// Applies one `KEY=VALUE` override. Keys are dotted paths; array elements
/// are addressed by index (`lights.0.intensity`). VALUE is a TOML value
/// (`0.2`, `[1, 1, 1]`, `"ggx"`, `true`); anything that is not valid TOML
/// is taken as a string, so `--set shading.mode=flat` works unquoted.
pub fn apply_override(table: &mut toml::Table, kv: &str) -> Result<()> {
    let arg = || format!("--set {kv}");
    let (key, raw) = kv
        .split_once('=')
        .ok_or_else(|| Error::argument(arg(), "expected KEY=VALUE, e.g. materials.ball.k_e=80"))?;
    let key = key.trim();
    let raw = raw.trim();
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(Error::argument(
            arg(),
            "the key is empty or has an empty part",
        ));
    }
    let value = format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_string()));

    let parts: Vec<&str> = key.split('.').collect();
    if parts.len() > MAX_KEY_DEPTH {
        return Err(Error::argument(
            arg(),
            format!(
                "the key has {} parts; scene keys have at most {MAX_KEY_DEPTH}",
                parts.len()
            ),
        ));
    }
    let (last, path) = parts.split_last().expect("non-empty key");
    let mut node = TableOrArray::Table(table);
    for (depth, part) in path.iter().enumerate() {
        let prefix = parts[..=depth].join(".");
        node = node
            .child(part)
            .map_err(|p| Error::argument(arg(), format!("`{prefix}`: {p}")))?;
    }
    node.set(last, value)
        .map_err(|p| Error::argument(arg(), format!("`{key}`: {p}")))
}

/// A step in a dotted path: tables by key (created when missing), arrays by
/// index (which must exist).
enum TableOrArray<'a> {
    Table(&'a mut toml::Table),
    Array(&'a mut Vec<toml::Value>),
}

impl<'a> TableOrArray<'a> {
    fn child(self, part: &str) -> std::result::Result<TableOrArray<'a>, String> {
        let slot = match self {
            TableOrArray::Table(t) => t
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new())),
            TableOrArray::Array(a) => {
                let len = a.len();
                let i: usize = part
                    .parse()
                    .map_err(|_| format!("`{part}` is not an index into an array of {len}"))?;
                a.get_mut(i)
                    .ok_or_else(|| format!("index {i} is out of range (the array has {len})"))?
            }
        };
        match slot {
            toml::Value::Table(t) => Ok(TableOrArray::Table(t)),
            toml::Value::Array(a) => Ok(TableOrArray::Array(a)),
            other => Err(format!("is a {}, not a table", other.type_str())),
        }
    }

    fn set(self, part: &str, value: toml::Value) -> std::result::Result<(), String> {
        match self {
            TableOrArray::Table(t) => {
                t.insert(part.to_string(), value);
                Ok(())
            }
            TableOrArray::Array(a) => {
                let len = a.len();
                let i: usize = part
                    .parse()
                    .map_err(|_| format!("`{part}` is not an index into an array of {len}"))?;
                *a.get_mut(i)
                    .ok_or_else(|| format!("index {i} is out of range (the array has {len})"))? =
                    value;
                Ok(())
            }
        }
    }
}

/// Validated assembly of the scene.
fn assemble(
    origin: &Path,
    base_dir: &Path,
    file: SceneFile,
    gltf_files: &mut gltf_import::GltfLoader,
) -> Result<Scene> {
    let bad = |problem: String| Error::input(origin, problem);

    let (width, height) = (file.image.width, file.image.height);
    for (key, v) in [("image.width", width), ("image.height", height)] {
        if v == 0 || v > MAX_IMAGE_SIDE {
            return Err(bad(format!("{key} = {v} is outside 1..={MAX_IMAGE_SIDE}")));
        }
    }
    let msaa = file.image.msaa.unwrap_or(1);
    if msaa != 1 && msaa != 4 {
        return Err(bad(format!(
            "image.msaa = {msaa}: the GPU renderer takes 1 (no multisampling) or 4 samples per pixel"
        )));
    }
    let shading = match &file.shading.mode {
        None => ShadingMode::default(),
        Some(s) => s.parse().map_err(|e| bad(format!("shading.mode: {e}")))?,
    };

    // Named materials first, in name order; glTF materials are appended.
    let mut materials = Vec::new();
    let mut material_index = BTreeMap::new();
    for (name, entry) in &file.materials {
        material_index.insert(name.clone(), materials.len());
        materials.push(material_from_entry(name, entry).map_err(bad)?);
    }

    let mut meshes = Vec::new();
    let mut lights = Vec::new();
    let mut gltf_camera = None;
    for (k, object) in file.objects.iter().enumerate() {
        let forced_material = match &object.material {
            None => None,
            Some(name) => Some(*material_index.get(name).ok_or_else(|| {
                bad(format!(
                    "objects[{k}].material = \"{name}\" names no material; defined: {}",
                    names(&file.materials)
                ))
            })?),
        };
        match (&object.gltf, &object.shape) {
            (Some(gltf), None) => {
                let path = base_dir.join(gltf);
                let imported = gltf_files.load(&path)?;
                let offset = materials.len();
                for mut mesh in imported.meshes {
                    mesh.material = forced_material.unwrap_or(mesh.material + offset);
                    meshes.push(mesh);
                }
                if forced_material.is_none() {
                    materials.extend(imported.materials);
                }
                lights.extend(imported.lights);
                if gltf_camera.is_none() {
                    gltf_camera = imported.camera;
                }
            }
            (None, Some(shape)) => {
                let material = match forced_material {
                    Some(m) => m,
                    None => {
                        materials.push(Material::new(
                            format!("objects[{k}] default"),
                            ReflectanceModel::Lambert,
                        ));
                        materials.len() - 1
                    }
                };
                // Charged to the budget before it is built: a fine
                // tessellation must not allocate past the limits first.
                let (vertices, triangles) = shape_size(k, object, shape).map_err(bad)?;
                gltf_files
                    .charge(vertices, triangles, 0)
                    .map_err(|p| bad(format!("objects[{k}]: {p}")))?;
                meshes.push(shape_mesh(k, object, shape, material).map_err(bad)?);
            }
            _ => {
                return Err(bad(format!(
                    "objects[{k}] needs exactly one of `gltf = \"file.gltf\"` or `shape = \"sphere\" | \"plane\"`"
                )));
            }
        }
    }

    gltf_files
        .charge(0, 0, file.lights.len() as u64)
        .map_err(|p| bad(format!("lights: {p}")))?;
    // Shadow settings: `[shadows]` gives the defaults (and decides for the
    // lights imported from glTF files), each entry's own keys override.
    let section_keys = file.shadows.keys();
    let shadow_defaults =
        shadow_settings(&section_keys, &|key| format!("shadows.{key}")).map_err(bad)?;
    let mut light_shadows = vec![shadow_defaults; lights.len()];
    if file.shadows.imported_lights {
        lights.iter_mut().for_each(|l| l.set_shadows(true));
    }
    let mut area_lights: Vec<AreaLight> = Vec::new();
    for (k, entry) in file.lights.iter().enumerate() {
        let at = |p: String| bad(format!("lights[{k}]: {p}"));
        let (_, keys) = entry.shadow_keys();
        let merged = ShadowKeys {
            map_size: keys.map_size.or(section_keys.map_size),
            bias: keys.bias.or(section_keys.bias),
            slope_bias: keys.slope_bias.or(section_keys.slope_bias),
            normal_offset: keys.normal_offset.or(section_keys.normal_offset),
            filter: keys.filter.or(section_keys.filter.clone()),
            pcf_kernel: keys.pcf_kernel.or(section_keys.pcf_kernel),
        };
        let settings = shadow_settings(&merged, &|key| format!("shadow_{key}")).map_err(at)?;
        match light_from_entry(entry).map_err(at)? {
            LightSource::Punctual(light) => {
                lights.push(light);
                light_shadows.push(settings);
            }
            LightSource::Area(area) => {
                let index = area_lights.len();
                for sample in area.point_lights(index, area.samples) {
                    lights.push(sample);
                    light_shadows.push(settings);
                }
                area_lights.push(area);
                if lights.len() > MAX_POINT_LIGHTS {
                    return Err(at(format!(
                        "the area lights expand into more than {MAX_POINT_LIGHTS} point lights; use fewer samples"
                    )));
                }
            }
        }
    }
    if lights.is_empty() {
        lights.push(default_light());
        light_shadows.push(shadow_defaults);
    }

    let ambient = match file.ambient.radiance {
        None => Rgb::ZERO,
        Some(c) => non_negative("ambient.radiance", c.rgb()).map_err(bad)?,
    };

    let environment = {
        let e = &file.environment;
        let get = |key: &str, c: Option<ColorValue>| match c {
            None => Ok(ambient),
            Some(c) => non_negative(&format!("environment.{key}"), c.rgb()),
        };
        Environment {
            zenith: get("zenith", e.zenith).map_err(bad)?,
            horizon: get("horizon", e.horizon).map_err(bad)?,
            ground: get("ground", e.ground).map_err(bad)?,
        }
    };

    let scene_bounds =
        crate::scene::mesh::bounds(meshes.iter().flat_map(|m| m.positions.iter().copied()))
            .filter(|_| meshes.iter().any(|m| !m.indices.is_empty()))
            .ok_or_else(|| bad("the scene has no triangles to draw".into()))?;
    let aspect = width as f64 / height as f64;
    let camera = match &file.camera {
        Some(section) => camera_from_section(section, scene_bounds).map_err(bad)?,
        None => match gltf_camera {
            Some(mut c) => {
                c.fit_clip_planes(scene_bounds.0, scene_bounds.1);
                c
            }
            None => Camera::framing(scene_bounds.0, scene_bounds.1, aspect),
        },
    };

    Ok(Scene {
        width,
        height,
        msaa,
        camera,
        shading,
        meshes,
        materials,
        lights,
        light_shadows,
        area_lights,
        ambient,
        environment,
    })
}

fn names<V>(map: &BTreeMap<String, V>) -> String {
    if map.is_empty() {
        "none".into()
    } else {
        map.keys()
            .map(|k| format!("`{k}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Most point lights a scene may have once its area lights are expanded.
pub const MAX_POINT_LIGHTS: usize = 65536;

/// What one `[[lights]]` entry becomes.
enum LightSource {
    Punctual(Light),
    Area(AreaLight),
}

/// Validated shadow settings from `keys`; `name(key)` is how the scene
/// file spells `key` where the keys came from.
fn shadow_settings(
    keys: &ShadowKeys,
    name: &dyn Fn(&str) -> String,
) -> std::result::Result<ShadowSettings, String> {
    let map_size = keys.map_size.unwrap_or(ShadowSettings::DEFAULT_MAP_SIZE);
    let sizes = ShadowSettings::MAP_SIZES;
    if !sizes.contains(&map_size) {
        return Err(format!(
            "{} = {map_size} is outside {}..={}",
            name("map_size"),
            sizes.start(),
            sizes.end()
        ));
    }
    let kernel = keys
        .pcf_kernel
        .unwrap_or(ShadowSettings::DEFAULT_PCF_KERNEL);
    if kernel.is_multiple_of(2) || !(1..=ShadowSettings::MAX_PCF_KERNEL).contains(&kernel) {
        return Err(format!(
            "{} = {kernel} must be an odd number in 1..={}",
            name("pcf_kernel"),
            ShadowSettings::MAX_PCF_KERNEL
        ));
    }
    let filter = match keys.filter.as_deref() {
        None | Some("pcf") => ShadowFilter::Pcf { kernel },
        Some("none") => ShadowFilter::None,
        Some(other) => {
            return Err(format!(
                "{} = \"{other}\" is not a shadow filter; expected none or pcf",
                name("filter")
            ));
        }
    };
    let length = |key: &str, v: Option<f64>, default: f64, max: f64| match v {
        None => Ok(default),
        Some(v) if v.is_finite() && (0.0..=max).contains(&v) => Ok(v),
        Some(v) => Err(format!("{} = {v} is outside 0..={max}", name(key))),
    };
    Ok(ShadowSettings {
        map_size,
        bias: length("bias", keys.bias, 0.0, 1e6)?,
        slope_bias: length("slope_bias", keys.slope_bias, 0.0, 1e3)?,
        normal_offset: length(
            "normal_offset",
            keys.normal_offset,
            ShadowSettings::default_normal_offset(filter),
            1e3,
        )?,
        filter,
    })
}

/// The light a scene without lights gets, so a bare glTF is visible: a
/// directional light from the upper front left, irradiance 3 W/m².
pub fn default_light() -> Light {
    Light::Directional {
        direction: DVec3::new(0.4, -1.0, -0.6).normalize(),
        irradiance: Rgb::splat(3.0),
        shadows: false,
    }
}

/// The `segments` of a generated shape, range-checked.
fn shape_segments(k: usize, o: &ObjectEntry) -> std::result::Result<u32, String> {
    let segments = o.segments.unwrap_or(48);
    if !(1..=4096).contains(&segments) {
        return Err(format!(
            "objects[{k}].segments = {segments} is outside 1..=4096"
        ));
    }
    Ok(segments)
}

/// Vertices and triangles of the shape `shape_mesh` would build.
fn shape_size(k: usize, o: &ObjectEntry, shape: &str) -> std::result::Result<(u64, u64), String> {
    let segments = shape_segments(k, o)?;
    Ok(match shape {
        "sphere" => primitives::uv_sphere_size(segments.max(3)),
        "plane" => primitives::plane_size(segments),
        // shape_mesh names the problem.
        _ => (0, 0),
    })
}

fn shape_mesh(
    k: usize,
    o: &ObjectEntry,
    shape: &str,
    material: usize,
) -> std::result::Result<Mesh, String> {
    let center = finite_vec(
        &format!("objects[{k}].center"),
        o.center.unwrap_or([0.0; 3]),
    )?;
    let positive = |key: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(format!(
                "objects[{k}].{key} = {v} must be a positive number"
            ))
        }
    };
    let segments = shape_segments(k, o)?;
    match shape {
        "sphere" => Ok(primitives::uv_sphere(
            center,
            positive("radius", o.radius.unwrap_or(1.0))?,
            segments.max(3),
            material,
        )),
        "plane" => Ok(primitives::plane(
            center,
            positive("size", o.size.unwrap_or(10.0))?,
            segments,
            material,
        )),
        other => Err(format!(
            "objects[{k}].shape = \"{other}\" is not a known shape; expected sphere or plane"
        )),
    }
}

fn finite_vec(key: &str, v: [f64; 3]) -> std::result::Result<DVec3, String> {
    let d = DVec3::from_array(v);
    if d.is_finite() {
        Ok(d)
    } else {
        Err(format!("{key} = {v:?} is not finite"))
    }
}

fn unit_vec(key: &str, v: [f64; 3]) -> std::result::Result<DVec3, String> {
    finite_vec(key, v)?
        .try_normalize()
        .ok_or_else(|| format!("{key} = {v:?} has no direction (zero length)"))
}

fn non_negative(key: &str, c: Rgb) -> std::result::Result<Rgb, String> {
    if c.is_finite() && c.min_element() >= 0.0 {
        Ok(c)
    } else {
        Err(format!(
            "{key} = [{}, {}, {}] must be finite and ≥ 0",
            c.x, c.y, c.z
        ))
    }
}

fn range(v: Option<f64>) -> std::result::Result<Option<f64>, String> {
    match v {
        Some(r) if !(r.is_finite() && r > 0.0) => Err(format!("range = {r} must be positive")),
        other => Ok(other),
    }
}

fn light_from_entry(e: &LightEntry) -> std::result::Result<LightSource, String> {
    Ok(match e {
        LightEntry::Point {
            position,
            intensity,
            range: r,
            shadows,
            ..
        } => LightSource::Punctual(Light::Point {
            position: finite_vec("position", *position)?,
            intensity: non_negative("intensity", intensity.rgb())?,
            range: range(*r)?,
            shadows: *shadows,
        }),
        LightEntry::Directional {
            direction,
            irradiance,
            shadows,
            ..
        } => LightSource::Punctual(Light::Directional {
            direction: unit_vec("direction", *direction)?,
            irradiance: non_negative("irradiance", irradiance.rgb())?,
            shadows: *shadows,
        }),
        LightEntry::Spot {
            position,
            direction,
            intensity,
            inner_cone_deg,
            outer_cone_deg,
            range: r,
            shadows,
            ..
        } => {
            // glTF's defaults: inner 0, outer π/4.
            let inner = inner_cone_deg.unwrap_or(0.0);
            let outer = outer_cone_deg.unwrap_or(45.0);
            if !(0.0..=90.0).contains(&outer) || !(0.0..=outer).contains(&inner) {
                return Err(format!(
                    "cones must satisfy 0 ≤ inner_cone_deg ≤ outer_cone_deg ≤ 90 (got {inner}, {outer})"
                ));
            }
            LightSource::Punctual(Light::Spot {
                position: finite_vec("position", *position)?,
                direction: unit_vec("direction", *direction)?,
                intensity: non_negative("intensity", intensity.rgb())?,
                inner_cone_deg: inner,
                outer_cone_deg: outer,
                range: range(*r)?,
                shadows: *shadows,
            })
        }
        LightEntry::Area {
            shape,
            position,
            normal,
            size,
            tangent,
            radius,
            radiance,
            samples,
            shadows,
            shadow_per_sample,
            ..
        } => LightSource::Area(AreaLight {
            shadow_per_sample: *shadow_per_sample,
            ..area_light_from_entry(
                shape, *position, *normal, *size, *tangent, *radius, *radiance, *samples, *shadows,
            )?
        }),
    })
}

#[allow(clippy::too_many_arguments)]
fn area_light_from_entry(
    shape: &str,
    position: [f64; 3],
    normal: [f64; 3],
    size: Option<[f64; 2]>,
    tangent: Option<[f64; 3]>,
    radius: Option<f64>,
    radiance: ColorValue,
    samples: Option<u32>,
    shadows: bool,
) -> std::result::Result<AreaLight, String> {
    let normal = unit_vec("normal", normal)?;
    let tangent = match tangent {
        None => crate::base::any_tangent(normal),
        Some(t) => {
            let t = unit_vec("tangent", t)?;
            (t - normal * normal.dot(t))
                .try_normalize()
                .filter(|_| t.cross(normal).length() > 1e-6)
                .ok_or_else(|| format!("tangent = {:?} is parallel to the normal", t.to_array()))?
        }
    };
    let positive = |key: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(format!("{key} = {v} must be a positive number"))
        }
    };
    let shape = match (shape, size, radius) {
        ("rect", Some([w, h]), None) => area_light::AreaShape::Rect {
            width: positive("size[0]", w)?,
            height: positive("size[1]", h)?,
        },
        ("disk", None, Some(r)) => area_light::AreaShape::Disk {
            radius: positive("radius", r)?,
        },
        ("rect", _, _) => {
            return Err("shape = \"rect\" needs `size = [w, h]` and no `radius`".into());
        }
        ("disk", _, _) => return Err("shape = \"disk\" needs `radius` and no `size`".into()),
        (other, _, _) => {
            return Err(format!(
                "shape = \"{other}\" is not an area light shape; expected rect or disk"
            ));
        }
    };
    let samples = samples.unwrap_or(area_light::DEFAULT_SAMPLES);
    if !(1..=area_light::MAX_SAMPLES).contains(&samples) {
        return Err(format!(
            "samples = {samples} is outside 1..={}",
            area_light::MAX_SAMPLES
        ));
    }
    Ok(AreaLight {
        shape,
        position: finite_vec("position", position)?,
        normal,
        tangent,
        radiance: non_negative("radiance", radiance.rgb())?,
        samples,
        shadows,
        shadow_per_sample: false,
    })
}

fn camera_from_section(
    s: &CameraSection,
    (lo, hi): (DVec3, DVec3),
) -> std::result::Result<Camera, String> {
    let position = finite_vec("camera.position", s.position)?;
    let target = finite_vec("camera.target", s.target)?;
    let up = unit_vec("camera.up", s.up)?;
    let forward = (target - position)
        .try_normalize()
        .ok_or("camera.position and camera.target coincide")?;
    if forward.cross(up).length() < 1e-9 {
        return Err("camera.up is parallel to the viewing direction".into());
    }
    if !(s.fov_y_deg > 0.0 && s.fov_y_deg < 180.0) {
        return Err(format!(
            "camera.fov_y_deg = {} is outside (0, 180)",
            s.fov_y_deg
        ));
    }
    let mut camera = Camera {
        position,
        target,
        up,
        fov_y_deg: s.fov_y_deg,
        near: 0.0,
        far: 0.0,
    };
    camera.fit_clip_planes(lo, hi);
    Ok(camera)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_scene_loads() {
        let scene = load(&SceneSource::BuiltIn, &[]).unwrap();
        assert_eq!((scene.width, scene.height), (640, 480));
        assert_eq!(scene.meshes.len(), 2);
        assert_eq!(scene.lights.len(), 1);
    }

    #[test]
    fn overrides_reach_the_scene() {
        let sets = [
            "materials.ball.k_e=7".to_string(),
            "shading.mode=flat".to_string(),
            "lights.0.intensity=[1, 2, 3]".to_string(),
            "image.width=33".to_string(),
        ];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        let ball = scene.materials.iter().find(|m| m.name == "ball").unwrap();
        assert_eq!(ball.k_e, 7.0);
        assert_eq!(scene.shading, ShadingMode::Flat);
        assert_eq!(scene.width, 33);
        match &scene.lights[0] {
            Light::Point { intensity, .. } => assert_eq!(*intensity, Rgb::new(1.0, 2.0, 3.0)),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn shadow_keys_reach_the_scene() {
        let scene = load(&SceneSource::BuiltIn, &[]).unwrap();
        assert!(!scene.has_shadows());
        assert_eq!(scene.shadow_settings(0), ShadowSettings::default());
        let sets = [
            "lights.0.shadows=true".to_string(),
            "lights.0.shadow_map_size=1024".to_string(),
            "lights.0.shadow_filter=none".to_string(),
            "lights.0.shadow_bias=0.001".to_string(),
        ];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        assert!(scene.lights[0].casts_shadows());
        let s = scene.shadow_settings(0);
        assert_eq!(
            (s.map_size, s.filter, s.bias, s.slope_bias),
            (1024, ShadowFilter::None, 0.001, 0.0)
        );
        assert_eq!(
            s.normal_offset,
            ShadowSettings::default_normal_offset(ShadowFilter::None)
        );
        // `[shadows]` gives defaults; a light's own key wins.
        let sets = [
            "shadows.map_size=512".to_string(),
            "shadows.pcf_kernel=5".to_string(),
            "lights.0.shadow_normal_offset=3".to_string(),
        ];
        let s = load(&SceneSource::BuiltIn, &sets)
            .unwrap()
            .shadow_settings(0);
        assert_eq!(
            (s.map_size, s.filter, s.normal_offset),
            (512, ShadowFilter::Pcf { kernel: 5 }, 3.0)
        );
    }

    #[test]
    fn imported_lights_cast_shadows_when_asked() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/gltf/ShadowsDirectional/shadows-directional.gltf");
        let source = SceneSource::File(path);
        assert!(!load(&source, &[]).unwrap().has_shadows());
        let scene = load(
            &source,
            &[
                "shadows.imported_lights=true".into(),
                "shadows.filter=none".into(),
            ],
        )
        .unwrap();
        assert!(scene.lights.iter().all(Light::casts_shadows));
        assert_eq!(scene.shadow_settings(0).filter, ShadowFilter::None);
    }

    #[test]
    fn area_lights_expand_into_their_samples() {
        let light = "lights=[{kind = \"area\", shape = \"disk\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radius = 0.5, radiance = 2.0, samples = 9, shadows = true}]";
        let scene = load(&SceneSource::BuiltIn, &[light.into()]).unwrap();
        assert_eq!(scene.area_lights.len(), 1);
        assert_eq!(scene.lights.len(), 9);
        assert_eq!(scene.light_shadows.len(), 9);
        let area = std::f64::consts::PI * 0.25;
        for l in &scene.lights {
            match l {
                Light::AreaSample {
                    intensity,
                    area: 0,
                    shadows: true,
                    ..
                } => {
                    assert!((intensity.x - 2.0 * area / 9.0).abs() < 1e-12)
                }
                other => panic!("{other:?}"),
            }
        }
        let scene = load(
            &SceneSource::BuiltIn,
            &[light.into(), "lights.0.samples=64".into()],
        )
        .unwrap();
        assert_eq!(scene.lights.len(), 64);
        assert_eq!(scene.with_area_samples(4).lights.len(), 4);
        assert!(!scene.area_lights[0].shadow_per_sample);
        let sets = [light.into(), "lights.0.shadow_per_sample=true".into()];
        let scene = load(&SceneSource::BuiltIn, &sets).unwrap();
        assert!(scene.area_lights[0].shadow_per_sample);
        assert_eq!(
            crate::gpu::shadows::ShadowPlan::new(&scene).layers.len(),
            6 * 9
        );
        let rect = "lights=[{kind = \"area\", shape = \"rect\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], size = [1.0, 2.0], tangent = [1.0, 0.0, 0.0], radiance = 1.0}]";
        let scene = load(&SceneSource::BuiltIn, &[rect.into()]).unwrap();
        assert_eq!(scene.lights.len(), area_light::DEFAULT_SAMPLES as usize);
    }

    #[test]
    fn bad_shadow_and_area_keys_are_rejected() {
        let area = |extra: &str| {
            format!(
                "lights=[{{kind = \"area\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radiance = 1.0, {extra}}}]"
            )
        };
        for kv in [
            "lights.0.shadow_map_size=8".to_string(),
            "lights.0.shadow_map_size=100000".to_string(),
            "lights.0.shadow_pcf_kernel=4".to_string(),
            "lights.0.shadow_filter=soft".to_string(),
            "lights.0.shadow_bias=-1".to_string(),
            "lights.0.shadow_normal_offset=nan".to_string(),
            "shadows.map_size=1".to_string(),
            "shadows.imported=true".to_string(),
            area("shape = \"rect\", radius = 1.0"),
            area("shape = \"rect\", size = [1.0, 0.0]"),
            area("shape = \"disk\", radius = 1.0, samples = 0"),
            area("shape = \"disk\", radius = 1.0, samples = 5000"),
            area("shape = \"disk\", size = [1.0, 1.0]"),
            area("shape = \"square\", radius = 1.0"),
            area("shape = \"rect\", size = [1.0, 1.0], tangent = [0.0, 2.0, 0.0]"),
        ] {
            let err = load(&SceneSource::BuiltIn, std::slice::from_ref(&kv));
            assert!(err.is_err(), "{kv} accepted");
            assert_eq!(err.unwrap_err().exit_code(), 2, "{kv}");
        }
    }

    #[test]
    fn unknown_override_key_is_named() {
        let err = load(
            &SceneSource::BuiltIn,
            &["materials.ball.rougness=0.2".into()],
        )
        .unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("--set materials.ball.rougness=0.2"), "{msg}");
        assert!(msg.contains("rougness"), "{msg}");
        assert_eq!(err.exit_code(), 2);
    }

    #[test]
    fn bad_values_are_rejected() {
        for kv in [
            "materials.ball.k_d=nan",
            "materials.ball.k_d=-0.5",
            "materials.ball.k_e=2e6",
            "lights.0.intensity=-1",
            "image.width=0",
            "shading.mode=smooth",
            "materials.ball.model=cook-torrrance",
            "materials.ball.distribution=phong",
            "materials.ball.preset=unobtainium",
            "materials.ball.roughness=0",
            "materials.ball.kappa=-1",
            "lights.3.intensity=1",
        ] {
            assert!(
                load(&SceneSource::BuiltIn, &[kv.into()]).is_err(),
                "{kv} accepted"
            );
        }
    }
}
