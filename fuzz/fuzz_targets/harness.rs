//! What the fuzz targets do with one input. Shared (through `#[path]`) by
//! the cargo-fuzz targets and by `tests/fuzz_corpus_replay.rs`, which runs
//! the committed corpus on stable Rust in CI, so both exercise exactly the
//! same calls.

// Each includer uses only some of these.
#![allow(dead_code)]

use gonio::scene::gltf_import::{self, Limits};
use gonio::scene::scene_file::{self, SceneSource};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Limits far below the desktop defaults: every input then stays fast and
/// well inside libFuzzer's 2 GiB memory cap, and the limit checks
/// themselves are exercised more often.
pub fn limits() -> Limits {
    Limits {
        bytes: 64 << 20,
        vertices: 1_000_000,
        triangles: 1_000_000,
        nodes: 100_000,
        textures: 1024,
        lights: 256,
        memory: 1 << 30,
    }
}

/// Bytes a fuzzed texture may decode to: a 64² image fits, the budget
/// check and the decoder's own allocation limit are reached often.
pub const TEXTURE_BUDGET: u64 = 4 << 20;

/// Decodes `data` as a PNG or JPEG texture (colour, so the sRGB path runs)
/// within [`TEXTURE_BUDGET`], and builds its mip chain as a load does.
pub fn texture_decode(data: &[u8]) {
    use gonio::scene::texture::{Encoding, decode, mips};
    if let Ok(image) = decode::decode(data, Encoding::Srgb, TEXTURE_BUDGET) {
        let texels = image.rgba.len();
        assert_eq!(texels, (image.width * image.height) as usize);
        let levels = mips::chain(image);
        assert!(!levels.is_empty());
    }
}

/// Parses `data` as a MERL `.binary` table; a table that parses is
/// evaluated at a few directions, which must give finite values.
pub fn merl_parse(data: &[u8]) {
    use gonio::material::measured::merl::MerlTable;
    if let Ok(table) = MerlTable::parse(data) {
        for (h, d, p) in [(0.0, 0.0, 0.0), (0.3, 1.0, 2.0), (1.5, 1.5, 3.0)] {
            let f = table.f_r(h, d, p);
            assert!(f.is_finite(), "f_r({h}, {d}, {p}) = {f:?}");
        }
    }
}

/// Texels a fuzzed environment map may declare: a 256 × 128 map fits, and
/// the header check before decoding is reached often.
pub const MAP_TEXELS: u64 = 1 << 15;

/// Decodes `data[1..]` as an environment map, a Radiance `.hdr` when
/// `data[0]` is even and an OpenEXR file when odd, within [`MAP_TEXELS`];
/// a map that loads must look up finite, non-negative radiance.
pub fn environment_map(data: &[u8]) {
    use gonio::environment::load::{Budget, decode, format_of};
    let Some((&selector, bytes)) = data.split_first() else {
        return;
    };
    let extension = if selector % 2 == 0 { "hdr" } else { "exr" };
    let format = format_of(extension).expect("a map format");
    if let Ok(map) = decode(bytes, format, "fuzz", MAP_TEXELS, Budget::UNLIMITED) {
        for d in [[0.0, 1.0, 0.0], [0.6, 0.0, -0.8], [0.0, -1.0, 0.0]] {
            let l = map.lookup(glam::DVec3::from(d));
            assert!(
                l.is_finite() && l.min_element() >= 0.0,
                "L_env({d:?}) = {l:?}"
            );
        }
    }
}

/// The line that separates a scene file from `--set` overrides in a
/// `scene_toml` input.
pub const OVERRIDES_SEPARATOR: &str = "\n--- set\n";

/// A folder of files that inputs may reference: `tri.bin` (the 44-byte
/// triangle buffer), `tri.gltf` (a glTF using it) and a subfolder `sub/`
/// with a copy of both. One per process: under cargo's scratch folder
/// for the replay test (`CARGO_TARGET_TMPDIR`, so test runs leave nothing
/// in the system's temporary folder), in the temporary folder under
/// libFuzzer.
pub fn workspace() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let parent = option_env!("CARGO_TARGET_TMPDIR")
            .map(PathBuf::from)
            .unwrap_or_else(std::env::temp_dir);
        let dir = parent.join(format!("gonio-fuzz-{}", std::process::id()));
        let sub = dir.join("sub");
        std::fs::create_dir_all(&sub).expect("fuzz workspace");
        for folder in [&dir, &sub] {
            std::fs::write(folder.join("tri.bin"), TRIANGLE_BIN).expect("tri.bin");
            std::fs::write(folder.join("tri.gltf"), TRIANGLE_GLTF).expect("tri.gltf");
        }
        dir
    })
}

/// The start of the message the loader's panic guard gives. Under
/// libFuzzer a panic aborts even inside `catch_unwind`; on stable (the
/// replay test) the guard would hide it, so the harness turns it back into
/// a panic: validation, not the guard, must stop every input.
const GUARD_MESSAGE: &str = "the glTF parser failed";

fn no_guarded_panic(result: gonio::Result<impl Sized>) {
    if let Err(e) = result {
        let message = e.to_string();
        assert!(!message.contains(GUARD_MESSAGE), "{message}");
    }
}

/// Loads `data` as a `.gltf` or `.glb` held in memory.
pub fn gltf_load(data: &[u8]) {
    no_guarded_panic(gltf_import::load_from_bytes(data, workspace(), &limits()));
}

/// Loads `data` as a scene `.toml`; any lines after [`OVERRIDES_SEPARATOR`]
/// are applied as `--set` overrides.
pub fn scene_toml(data: &[u8]) {
    let (text, sets) = split_overrides(data);
    // One file per thread: the replay test may run inputs in parallel.
    let path = workspace().join(format!("scene-{:?}.toml", std::thread::current().id()));
    if std::fs::write(&path, text).is_err() {
        return;
    }
    no_guarded_panic(scene_file::load_with_limits(
        &SceneSource::File(path),
        &sets,
        limits(),
    ));
}

fn split_overrides(data: &[u8]) -> (&[u8], Vec<String>) {
    let separator = OVERRIDES_SEPARATOR.as_bytes();
    match data.windows(separator.len()).position(|w| w == separator) {
        None => (data, Vec::new()),
        Some(at) => {
            let sets = String::from_utf8_lossy(&data[at + separator.len()..])
                .lines()
                .map(str::to_string)
                .collect();
            (&data[..at], sets)
        }
    }
}

/// Three `VEC3` float positions and three `u16` indices, padded to 44.
const TRIANGLE_BIN: &[u8] = &[
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, // (0, 0, 0)
    0, 0, 128, 63, 0, 0, 0, 0, 0, 0, 0, 0, // (1, 0, 0)
    0, 0, 0, 0, 0, 0, 128, 63, 0, 0, 0, 0, // (0, 1, 0)
    0, 0, 1, 0, 2, 0, 0, 0, // indices 0, 1, 2 and padding
];

const TRIANGLE_GLTF: &str = r#"{
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": "tri.bin", "byteLength": 44}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 6}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ]
}"#;

/// Decodes `data` as a KTX2 (Basis Universal) texture, as
/// [`texture_decode`] does; input without the KTX2 identifier gets it
/// prefixed, so mutations stay in the Basis transcoder.
pub fn ktx2_texture(data: &[u8]) {
    use gonio::scene::texture::ktx2::{MAGIC, is_ktx2};
    if is_ktx2(data) {
        texture_decode(data);
    } else {
        texture_decode(&[&MAGIC[..], data].concat());
    }
}

/// Decodes `data` as a WebP texture, as [`texture_decode`] does.
pub fn webp_texture(data: &[u8]) {
    texture_decode(data);
}

/// A GLB of `json` and `bin` (chunks padded to 4 bytes).
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut file = b"glTF".to_vec();
    file.extend_from_slice(&2u32.to_le_bytes());
    file.extend_from_slice(&((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    for (kind, data) in [(b"JSON", &json), (b"BIN\0", &bin)] {
        file.extend_from_slice(&(data.len() as u32).to_le_bytes());
        file.extend_from_slice(kind);
        file.extend_from_slice(data);
    }
    file
}

/// Loads a GLB whose one triangle-list primitive is the Draco stream
/// `data[8..]` (`KHR_draco_mesh_compression`, POSITION as Draco attribute
/// 0, NORMAL as 1), declaring `data[0..4]` vertices and `data[4..8]`
/// indices (u32, little-endian, each capped at 2²⁰), so seeds made from
/// real files reach the whole path past the decoder.
pub fn draco_mesh(data: &[u8]) {
    if data.len() < 8 {
        return;
    }
    let count =
        |at: usize| u32::from_le_bytes(data[at..at + 4].try_into().unwrap()).clamp(1, 1 << 20);
    let (vertices, indices) = (count(0), count(4));
    let stream = &data[8..];
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2,
    "extensions": {{"KHR_draco_mesh_compression": {{"bufferView": 0, "attributes": {{"POSITION": 0, "NORMAL": 1}}}}}}}}]}}],
  "buffers": [{{"byteLength": {len}}}],
  "bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [
    {{"componentType": 5126, "count": {vertices}, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]}},
    {{"componentType": 5126, "count": {vertices}, "type": "VEC3"}},
    {{"componentType": 5125, "count": {indices}, "type": "SCALAR"}}
  ]}}"#,
        len = stream.len().max(1),
    );
    let mut bin = stream.to_vec();
    bin.resize(bin.len().max(1), 0);
    no_guarded_panic(gltf_import::load_from_bytes(
        &glb(&json, &bin),
        workspace(),
        &limits(),
    ));
}

/// Loads a GLB with one `EXT_meshopt_compression` (`data[0]` odd:
/// `KHR_meshopt_compression`) buffer view: mode `data[1] % 3`
/// (ATTRIBUTES, TRIANGLES, INDICES), filter `data[2] % 5` (NONE,
/// OCTAHEDRAL, QUATERNION, EXPONENTIAL, COLOR), byteStride `data[3]`,
/// count `data[4..8]` (u32, capped at 2¹⁶), compressed bytes `data[8..]`;
/// the view is read as a triangle's positions when the shape allows.
pub fn meshopt_buffer(data: &[u8]) {
    if data.len() < 8 {
        return;
    }
    let name = if data[0] % 2 == 1 {
        "KHR_meshopt_compression"
    } else {
        "EXT_meshopt_compression"
    };
    let mode = ["ATTRIBUTES", "TRIANGLES", "INDICES"][usize::from(data[1] % 3)];
    let filter =
        ["NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL", "COLOR"][usize::from(data[2] % 5)];
    let stride = usize::from(data[3]).max(1);
    let count = u32::from_le_bytes(data[4..8].try_into().unwrap()).clamp(1, 1 << 16) as usize;
    let compressed = &data[8..];
    let decoded = count * stride;
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
  "extensionsUsed": ["{name}"], "extensionsRequired": ["{name}"],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
  "buffers": [{{"byteLength": {len}}}, {{"byteLength": {decoded}, "extensions": {{"{name}": {{"fallback": true}}}}}}],
  "bufferViews": [{{"buffer": 1, "byteLength": {decoded}, "extensions": {{"{name}": {{
    "buffer": 0, "byteLength": {clen}, "byteStride": {stride}, "count": {count}, "mode": "{mode}", "filter": "{filter}"}}}}}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]}}]}}"#,
        len = compressed.len().max(1),
        clen = compressed.len(),
    );
    let mut bin = compressed.to_vec();
    bin.resize(bin.len().max(1), 0);
    no_guarded_panic(gltf_import::load_from_bytes(
        &glb(&json, &bin),
        workspace(),
        &limits(),
    ));
}
