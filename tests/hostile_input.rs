//! Hostile input: a corpus of malformed and malicious glTF, GLB and scene
//! files, generated here at test time (no binary blobs in the repository),
//! each loaded in-process under a time limit. Every case must end in an
//! input error of the expected kind, never a panic or a hang; a few cases
//! that must load (deep but valid hierarchies, degenerate triangles) are
//! checked to load. A handful also go through the real binary: exit status
//! 2, one paragraph on stderr, no output file.

mod common;

use base64::Engine as _;
use gonio::scene::gltf_import::{self, GltfLoader, Limits};
use gonio::scene::scene_file::{self, SceneSource};
use std::fmt::Write as _;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Longest any one input may take to be refused (or loaded).
const TIME_LIMIT: Duration = Duration::from_secs(10);

/// The loader's own panic guard; no case may need it.
const GUARD_MESSAGE: &str = "the glTF parser failed";

/// How a case is loaded.
#[derive(Clone)]
enum Load {
    /// `gltf_import::load` of the file.
    Gltf(PathBuf),
    /// `scene_file::load` of the file (a scene `.toml`, `.gltf` or `.glb`).
    Scene(PathBuf),
    /// The built-in scene with these `--set` overrides.
    Overrides(Vec<String>),
    /// `scene_file::load_with_limits` of the file.
    SceneWithLimits(PathBuf, Limits),
}

/// What a case must produce.
#[derive(Clone)]
enum Expect {
    /// An error whose message contains every one of these.
    Error(Vec<String>),
    /// A successful load (of a hostile-looking but valid input).
    Loads,
}

#[derive(Clone)]
struct Case {
    class: &'static str,
    name: String,
    load: Load,
    expect: Expect,
}

/// Builds the corpus in one temporary folder.
struct Corpus {
    dir: PathBuf,
    cases: Vec<Case>,
}

impl Corpus {
    fn new(dir: &Path) -> Self {
        Corpus {
            dir: dir.to_path_buf(),
            cases: Vec::new(),
        }
    }

    /// Writes `bytes` as `name` (a path relative to the corpus folder) and
    /// returns its path.
    fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let path = self.dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, bytes).unwrap();
        path
    }

    fn add(&mut self, class: &'static str, name: &str, load: Load, expect: Expect) {
        self.cases.push(Case {
            class,
            name: name.to_string(),
            load,
            expect,
        });
    }

    /// A glTF/GLB case: written as `<class>/<name>`, loaded by the glTF
    /// loader, expected to fail with `needles` in the message.
    fn gltf(&mut self, class: &'static str, name: &str, bytes: impl AsRef<[u8]>, needles: &[&str]) {
        let path = self.write(&format!("{class}/{name}"), bytes);
        self.add(class, name, Load::Gltf(path), errors(needles));
    }

    /// A scene `.toml` case.
    fn scene(&mut self, class: &'static str, name: &str, text: impl AsRef<[u8]>, needles: &[&str]) {
        let path = self.write(&format!("{class}/{name}"), text);
        self.add(class, name, Load::Scene(path), errors(needles));
    }
}

fn errors(needles: &[&str]) -> Expect {
    Expect::Error(needles.iter().map(|s| s.to_string()).collect())
}

// ---------------------------------------------------------------------------
// Building blocks

/// A one-triangle glTF whose buffer 0 has the given URI and 44 bytes (three
/// VEC3 positions at 0, three u16 indices at 36, 2 bytes padding). Cases
/// edit the text to break one thing at a time.
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

fn triangle_bytes(positions: [[f32; 3]; 3], indices: [u16; 3]) -> Vec<u8> {
    let mut bytes = Vec::new();
    for c in positions.iter().flatten() {
        bytes.extend_from_slice(&c.to_le_bytes());
    }
    for i in indices {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes.extend_from_slice(&[0, 0]);
    bytes
}

const TRIANGLE: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

fn data_uri(bytes: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// The triangle with its buffer embedded, edited by `edit`.
fn embedded(edit: impl FnOnce(String) -> String) -> String {
    edit(triangle_gltf(&data_uri(&triangle_bytes(
        TRIANGLE,
        [0, 1, 2],
    ))))
}

/// Replaces `from` (which must occur) with `to`.
fn swap(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "corpus bug: `{from}` not in the text");
    text.replacen(from, to, 1)
}

/// Inserts top-level members after `"scene": 0,`.
fn with_top_level(text: &str, members: &str) -> String {
    swap(text, "\"scene\": 0,", &format!("\"scene\": 0, {members},"))
}

/// A GLB from raw chunks `(type, data)`, with a correct header length.
fn glb_raw(chunks: &[(&[u8; 4], &[u8])]) -> Vec<u8> {
    let mut body = Vec::new();
    for (kind, data) in chunks {
        body.extend_from_slice(&(data.len() as u32).to_le_bytes());
        body.extend_from_slice(*kind);
        body.extend_from_slice(data);
    }
    let mut file = b"glTF".to_vec();
    file.extend_from_slice(&2u32.to_le_bytes());
    file.extend_from_slice(&((body.len() + 12) as u32).to_le_bytes());
    file.extend(body);
    file
}

/// The triangle as a GLB: JSON (buffer without uri) and BIN chunks.
fn triangle_glb_json() -> String {
    swap(
        &triangle_gltf("x"),
        "{\"uri\": \"x\", \"byteLength\": 44}",
        "{\"byteLength\": 44}",
    )
}

fn triangle_glb() -> Vec<u8> {
    let json = triangle_glb_json();
    let bin = triangle_bytes(TRIANGLE, [0, 1, 2]);
    glb_raw(&[(b"JSON", json.as_bytes()), (b"BIN\0", &bin)])
}

/// A glTF whose nodes are given as JSON text (scene roots: `roots`), each
/// drawing the triangle if it says `"mesh": 0`.
fn with_nodes(nodes: &str, roots: &str) -> String {
    let text = embedded(|t| t);
    let text = swap(
        &text,
        "\"nodes\": [{\"mesh\": 0}]",
        &format!("\"nodes\": [{nodes}]"),
    );
    swap(
        &text,
        "\"scenes\": [{\"nodes\": [0]}]",
        &format!("\"scenes\": [{{\"nodes\": [{roots}]}}]"),
    )
}

fn repeat_joined(item: &str, count: usize) -> String {
    let mut out = String::with_capacity((item.len() + 1) * count);
    for i in 0..count {
        if i > 0 {
            out.push(',');
        }
        out.push_str(item);
    }
    out
}

// ---------------------------------------------------------------------------
// The corpus, class by class

fn glb_container(c: &mut Corpus) {
    const CLASS: &str = "glb-container";
    let good = triangle_glb();
    let json = triangle_glb_json();
    let bin = triangle_bytes(TRIANGLE, [0, 1, 2]);
    c.gltf(CLASS, "empty.glb", [], &["the file is empty"]);
    c.gltf(
        CLASS,
        "text.glb",
        "{}",
        &["invalid GLB file", "starts with `{}`"],
    );
    c.gltf(
        CLASS,
        "header-cut.glb",
        &good[..7],
        &["invalid GLB file", "12-byte header"],
    );
    let mut magic = good.clone();
    magic[..4].copy_from_slice(b"glTX");
    c.gltf(CLASS, "bad-magic.glb", &magic, &["not the magic `glTF`"]);
    let mut version = good.clone();
    version[4] = 1;
    c.gltf(CLASS, "version-1.glb", &version, &["version 1"]);
    let mut version = good.clone();
    version[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
    c.gltf(CLASS, "version-max.glb", &version, &["version 4294967295"]);
    let mut long = good.clone();
    long[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    c.gltf(
        CLASS,
        "length-past-end.glb",
        &long,
        &["declares a length of 4294967295"],
    );
    let mut short = good.clone();
    short[8..12].copy_from_slice(&5u32.to_le_bytes());
    c.gltf(
        CLASS,
        "length-below-header.glb",
        &short,
        &["invalid GLB file", "no JSON chunk"],
    );
    c.gltf(
        CLASS,
        "truncated-half.glb",
        &good[..good.len() / 2],
        &["truncated"],
    );
    let mut chunk = good.clone();
    chunk[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    c.gltf(
        CLASS,
        "json-chunk-length-overflow.glb",
        &chunk,
        &["`JSON` chunk", "4294967295 bytes"],
    );
    let mut chunk = good.clone();
    let bin_header = 12 + 8 + json.len();
    chunk[bin_header..bin_header + 4].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
    c.gltf(
        CLASS,
        "bin-chunk-length-overflow.glb",
        &chunk,
        &["`BIN` chunk", "4294967280 bytes"],
    );
    let bin_first = glb_raw(&[(b"BIN\0", &bin), (b"JSON", json.as_bytes())]);
    c.gltf(
        CLASS,
        "json-not-first.glb",
        bin_first,
        &["must be the JSON chunk"],
    );
    let no_bin = glb_raw(&[(b"JSON", json.as_bytes())]);
    c.gltf(
        CLASS,
        "missing-bin.glb",
        no_bin,
        &["buffer 0", "no BIN chunk"],
    );
    let short_bin = glb_raw(&[(b"JSON", json.as_bytes()), (b"BIN\0", &bin[..40])]);
    c.gltf(
        CLASS,
        "bin-shorter-than-buffer.glb",
        short_bin,
        &["40 bytes", "byteLength 44"],
    );
    let twice = glb_raw(&[(b"JSON", json.as_bytes()), (b"JSON", json.as_bytes())]);
    c.gltf(
        CLASS,
        "two-json-chunks.glb",
        twice,
        &["second `JSON` chunk"],
    );
    c.gltf(CLASS, "no-chunks.glb", glb_raw(&[]), &["no JSON chunk"]);
    let mut cut = glb_raw(&[(b"JSON", json.as_bytes())]);
    cut.extend_from_slice(&[9, 0, 0]);
    let len = cut.len() as u32;
    cut[8..12].copy_from_slice(&len.to_le_bytes());
    c.gltf(CLASS, "chunk-header-cut.glb", cut, &["cut off"]);
    let garbage: Vec<u8> = (0..64u8).map(|b| b.wrapping_mul(37)).collect();
    let garbage = glb_raw(&[(b"JSON", &garbage)]);
    c.gltf(
        CLASS,
        "json-chunk-garbage.glb",
        garbage,
        &["invalid glTF", "malformed"],
    );
}

fn bad_json(c: &mut Corpus) {
    const CLASS: &str = "bad-json";
    let good = embedded(|t| t);
    c.gltf(CLASS, "empty.gltf", "", &["the file is empty"]);
    c.gltf(CLASS, "whitespace.gltf", "  \n", &["invalid glTF", "EOF"]);
    c.gltf(
        CLASS,
        "truncated.gltf",
        &good[..good.len() / 2],
        &["invalid glTF"],
    );
    c.gltf(CLASS, "top-level-array.gltf", "[1, 2]", &["invalid glTF"]);
    let deep = format!(
        "{{\"asset\": {}{}}}",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    c.gltf(
        CLASS,
        "nested-100000.gltf",
        deep,
        &["invalid glTF", "recursion limit"],
    );
    let mut latin1 = good.clone().into_bytes();
    latin1.splice(20..20, [b'"', 0xff, 0xfe, b'"', b':', b'1', b',']);
    c.gltf(CLASS, "not-utf8.gltf", latin1, &["invalid glTF"]);
    let no_asset = swap(&good, "\"asset\": {\"version\": \"2.0\"},", "");
    c.gltf(
        CLASS,
        "missing-asset.gltf",
        no_asset,
        &["invalid glTF", "asset"],
    );
    let wrong_type = swap(&good, "\"nodes\": [{\"mesh\": 0}]", "\"nodes\": 5");
    c.gltf(CLASS, "nodes-not-array.gltf", wrong_type, &["invalid glTF"]);
    c.gltf(
        CLASS,
        "trailing-garbage.gltf",
        format!("{good} }}"),
        &["invalid glTF", "trailing"],
    );
    let negative = swap(
        &good,
        "\"count\": 3, \"type\": \"VEC3\"",
        "\"count\": -3, \"type\": \"VEC3\"",
    );
    c.gltf(CLASS, "negative-count.gltf", negative, &["invalid glTF"]);
    let huge_number = swap(
        &good,
        "\"count\": 3, \"type\": \"VEC3\"",
        "\"count\": 1e400, \"type\": \"VEC3\"",
    );
    c.gltf(CLASS, "count-1e400.gltf", huge_number, &["invalid glTF"]);
}

fn out_of_range(c: &mut Corpus) {
    const CLASS: &str = "out-of-range";
    let good = embedded(|t| t);
    let cases: [(&str, &str, &str, &[&str]); 11] = [
        ("scene.gltf", "\"scene\": 0,", "\"scene\": 7,", &["scene"]),
        (
            "scene-node.gltf",
            "\"scenes\": [{\"nodes\": [0]}]",
            "\"scenes\": [{\"nodes\": [9]}]",
            &["scenes[0].nodes[0]"],
        ),
        (
            "node-mesh.gltf",
            "{\"mesh\": 0}",
            "{\"mesh\": 9}",
            &["nodes[0].mesh"],
        ),
        (
            "node-child.gltf",
            "{\"mesh\": 0}",
            "{\"mesh\": 0, \"children\": [9]}",
            &["nodes[0].children[0]"],
        ),
        (
            "position-accessor.gltf",
            "\"POSITION\": 0",
            "\"POSITION\": 99",
            &["POSITION", "accessor 99 does not exist"],
        ),
        (
            "indices-accessor.gltf",
            "\"indices\": 1",
            "\"indices\": 99",
            &["indices"],
        ),
        (
            "accessor-view.gltf",
            "{\"bufferView\": 0,",
            "{\"bufferView\": 9,",
            &["accessors[0].bufferView"],
        ),
        (
            "view-buffer.gltf",
            "{\"buffer\": 0, \"byteOffset\": 0,",
            "{\"buffer\": 9, \"byteOffset\": 0,",
            &["bufferViews[0].buffer"],
        ),
        (
            "material.gltf",
            "\"indices\": 1}",
            "\"indices\": 1, \"material\": 9}",
            &["material"],
        ),
        (
            "camera.gltf",
            "{\"mesh\": 0}",
            "{\"mesh\": 0, \"camera\": 4}",
            &["nodes[0].camera"],
        ),
        (
            "light.gltf",
            "{\"mesh\": 0}",
            "{\"mesh\": 0, \"extensions\": {\"KHR_lights_punctual\": {\"light\": 3}}}",
            &["light"],
        ),
    ];
    for (name, from, to, needles) in cases {
        c.gltf(CLASS, name, swap(&good, from, to), needles);
    }
    let index = embedded(|_| triangle_gltf(&data_uri(&triangle_bytes(TRIANGLE, [0, 1, 7]))));
    c.gltf(
        CLASS,
        "vertex-index.gltf",
        index,
        &["accessor 1 (indices)", "index 7", "out of range"],
    );
    let index = embedded(|_| triangle_gltf(&data_uri(&triangle_bytes(TRIANGLE, [0, 1, u16::MAX]))));
    c.gltf(CLASS, "vertex-index-max.gltf", index, &["index 65535"]);
}

fn offsets_and_strides(c: &mut Corpus) {
    const CLASS: &str = "offsets-strides";
    let good = embedded(|t| t);
    let accessor1 = "{\"bufferView\": 1, ";
    let cases: [(&str, &str, &str, &[&str]); 10] = [
        (
            "accessor-offset-u64.gltf",
            accessor1,
            "{\"bufferView\": 1, \"byteOffset\": 18446744073709551610, ",
            &["accessor 1 (indices)", "do not fit"],
        ),
        (
            "accessor-offset-u32.gltf",
            accessor1,
            "{\"bufferView\": 1, \"byteOffset\": 4294967295, ",
            &["accessor 1 (indices)", "do not fit"],
        ),
        (
            "view-offset-u64.gltf",
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 18446744073709551608, \"byteLength\": 16",
            &["buffer view 1", "does not fit in buffer 0"],
        ),
        (
            "view-past-buffer.gltf",
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 40, \"byteLength\": 6",
            &["buffer view 1", "does not fit"],
        ),
        (
            "view-length-u64.gltf",
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 36, \"byteLength\": 18446744073709551615",
            &["does not fit"],
        ),
        (
            "stride-too-small.gltf",
            "\"byteOffset\": 0, \"byteLength\": 36}",
            "\"byteOffset\": 0, \"byteLength\": 36, \"byteStride\": 4}",
            &["byteStride"],
        ),
        (
            "stride-252.gltf",
            "\"byteOffset\": 0, \"byteLength\": 36}",
            "\"byteOffset\": 0, \"byteLength\": 36, \"byteStride\": 252}",
            &["accessor 0 (POSITION)", "stride 252", "do not fit"],
        ),
        (
            "stride-u32.gltf",
            "\"byteOffset\": 0, \"byteLength\": 36}",
            "\"byteOffset\": 0, \"byteLength\": 36, \"byteStride\": 4294967295}",
            &["byteStride"],
        ),
        (
            "count-past-view.gltf",
            "\"count\": 3, \"type\": \"VEC3\"",
            "\"count\": 4, \"type\": \"VEC3\"",
            &["accessor 0 (POSITION)", "do not fit"],
        ),
        (
            "count-zero.gltf",
            "\"count\": 3, \"type\": \"VEC3\"",
            "\"count\": 0, \"type\": \"VEC3\"",
            &["count"],
        ),
    ];
    for (name, from, to, needles) in cases {
        c.gltf(CLASS, name, swap(&good, from, to), needles);
    }
    let types: [(&str, &str, &str, &[&str]); 4] = [
        (
            "position-u16.gltf",
            "\"componentType\": 5126",
            "\"componentType\": 5123",
            &["accessor 0 (POSITION)", "expected VEC3 of FLOAT"],
        ),
        (
            "position-vec2.gltf",
            "\"count\": 3, \"type\": \"VEC3\"",
            "\"count\": 3, \"type\": \"VEC2\"",
            &["expected VEC3 of FLOAT"],
        ),
        (
            "component-9999.gltf",
            "\"componentType\": 5126",
            "\"componentType\": 9999",
            &["componentType"],
        ),
        (
            "indices-float.gltf",
            "\"componentType\": 5123",
            "\"componentType\": 5126",
            &["accessor 1 (indices)", "SCALAR of UNSIGNED"],
        ),
    ];
    for (name, from, to, needles) in types {
        c.gltf(CLASS, name, swap(&good, from, to), needles);
    }
    let two = swap(
        &good,
        "\"componentType\": 5123, \"count\": 3",
        "\"componentType\": 5123, \"count\": 2",
    );
    c.gltf(
        CLASS,
        "list-not-multiple-of-3.gltf",
        two,
        &["multiple of 3"],
    );
    // Sparse data pointing past its view.
    let sparse = swap(
        &good,
        "\"min\": [0, 0, 0]",
        "\"sparse\": {\"count\": 3, \"indices\": {\"bufferView\": 1, \"byteOffset\": 4, \"componentType\": 5123}, \"values\": {\"bufferView\": 0}}, \"min\": [0, 0, 0]",
    );
    c.gltf(
        CLASS,
        "sparse-indices-past-view.gltf",
        sparse,
        &["sparse indices", "do not fit"],
    );
    let sparse = swap(
        &good,
        "\"min\": [0, 0, 0]",
        "\"sparse\": {\"count\": 9, \"indices\": {\"bufferView\": 1, \"componentType\": 5123}, \"values\": {\"bufferView\": 0}}, \"min\": [0, 0, 0]",
    );
    c.gltf(
        CLASS,
        "sparse-count-above-count.gltf",
        sparse,
        &["sparse count 9"],
    );
}

fn huge_counts(c: &mut Corpus) {
    const CLASS: &str = "huge-counts";
    let good = embedded(|t| t);
    let big = swap(
        &good,
        "\"count\": 3, \"type\": \"VEC3\"",
        "\"count\": 2147483648, \"type\": \"VEC3\"",
    );
    c.gltf(
        CLASS,
        "positions-2e31.gltf",
        big,
        &["vertices", "2147483648", "--limit vertices=N"],
    );
    let big = swap(
        &good,
        "\"componentType\": 5123, \"count\": 3",
        "\"componentType\": 5123, \"count\": 2147483646",
    );
    c.gltf(
        CLASS,
        "indices-2e31.gltf",
        big,
        &["triangles", "--limit triangles=N"],
    );
    let big = swap(&good, "\"byteLength\": 44", "\"byteLength\": 1099511627776");
    c.gltf(
        CLASS,
        "buffer-1TiB.gltf",
        big,
        &["buffer 0", "--limit bytes=N"],
    );
    // Sparse without a view: a declared count with no data at all.
    let sparse_only = swap(
        &good,
        "{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3,",
        "{\"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 1, \"componentType\": 5123}, \"values\": {\"bufferView\": 0}}, \"componentType\": 5126, \"count\": 2000000000,",
    );
    c.gltf(
        CLASS,
        "sparse-without-view-2e9.gltf",
        sparse_only,
        &["vertices", "2000000000"],
    );
    // One mesh of 1000 triangles instanced by 100 000 nodes: 100 million
    // triangles from a 2 MB file.
    let mut indices = Vec::new();
    for _ in 0..1000 {
        indices.extend_from_slice(&[0u16, 1, 2]);
    }
    let mut bytes = triangle_bytes(TRIANGLE, [0, 1, 2])[..36].to_vec();
    for i in &indices {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let instanced = triangle_gltf(&data_uri(&bytes))
        .replace(
            "\"byteLength\": 44",
            &format!("\"byteLength\": {}", bytes.len()),
        )
        .replace(
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 36, \"byteLength\": 6000",
        )
        .replace(
            "\"componentType\": 5123, \"count\": 3",
            "\"componentType\": 5123, \"count\": 3000",
        );
    let roots: Vec<String> = (0..100_000).map(|i| i.to_string()).collect();
    let instanced = swap(
        &instanced,
        "\"nodes\": [{\"mesh\": 0}]",
        &format!("\"nodes\": [{}]", repeat_joined("{\"mesh\": 0}", 100_000)),
    );
    let instanced = swap(
        &instanced,
        "\"scenes\": [{\"nodes\": [0]}]",
        &format!("\"scenes\": [{{\"nodes\": [{}]}}]", roots.join(",")),
    );
    c.gltf(
        CLASS,
        "instancing-bomb.gltf",
        instanced,
        &["triangles to draw", "100000000"],
    );
    let nodes = with_nodes(&repeat_joined("{}", 1_100_000), "0");
    c.gltf(
        CLASS,
        "nodes-1.1M.gltf",
        nodes,
        &["number of nodes", "1100000", "--limit nodes=N"],
    );
    // Three million empty accessors: 9 MB of text, gigabytes once parsed.
    let accessors = swap(
        &good,
        "\"accessors\": [",
        &format!("\"accessors\": [{},", repeat_joined("{}", 3_000_000)),
    );
    c.gltf(
        CLASS,
        "json-amplification.gltf",
        accessors,
        &["parsed JSON", "--limit bytes=N"],
    );
    let images = with_top_level(
        &good,
        &format!(
            "\"images\": [{}]",
            repeat_joined("{\"uri\": \"a.png\"}", 5000)
        ),
    );
    c.gltf(
        CLASS,
        "images-5000.gltf",
        images,
        &["images and textures", "5000"],
    );
    let lights = with_top_level(
        &good,
        "\"extensionsUsed\": [\"KHR_lights_punctual\"], \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\"}]}}",
    );
    let lit_nodes = repeat_joined(
        "{\"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}",
        2000,
    );
    let lights = swap(
        &lights,
        "\"nodes\": [{\"mesh\": 0}]",
        &format!("\"nodes\": [{{\"mesh\": 0}}, {lit_nodes}]"),
    );
    let roots: Vec<String> = (0..=2000).map(|i| i.to_string()).collect();
    let lights = swap(
        &lights,
        "\"scenes\": [{\"nodes\": [0]}]",
        &format!("\"scenes\": [{{\"nodes\": [{}]}}]", roots.join(",")),
    );
    c.gltf(
        CLASS,
        "lights-2000.gltf",
        lights,
        &["number of lights", "2000"],
    );
}

fn hierarchies(c: &mut Corpus) {
    const CLASS: &str = "hierarchy";
    const DEEP: usize = 100_000;
    // A valid chain of 100 000 nodes with the mesh at the bottom: loads.
    let mut chain = String::new();
    for i in 0..DEEP - 1 {
        write!(
            chain,
            "{{\"children\": [{}], \"translation\": [0.00001, 0, 0]}},",
            i + 1
        )
        .unwrap();
    }
    chain += "{\"mesh\": 0}";
    let path = c.write(&format!("{CLASS}/deep-chain.gltf"), with_nodes(&chain, "0"));
    c.add(CLASS, "deep-chain.gltf", Load::Gltf(path), Expect::Loads);
    // The same chain closed into a cycle that no scene reaches.
    let mut ring = String::new();
    for i in 0..DEEP {
        write!(ring, "{{\"children\": [{}]}},", (i + 1) % DEEP).unwrap();
    }
    ring += "{\"mesh\": 0}";
    c.gltf(
        CLASS,
        "unreachable-cycle-100000.gltf",
        with_nodes(&ring, &DEEP.to_string()),
        &["cycle", "100000 nodes"],
    );
    let pair = "{\"mesh\": 0, \"children\": [1]}, {\"children\": [0]}";
    c.gltf(
        CLASS,
        "cycle-2.gltf",
        with_nodes(pair, "0"),
        &["cycle", "node 0 → node 1 → node 0"],
    );
    c.gltf(
        CLASS,
        "self-child.gltf",
        with_nodes("{\"mesh\": 0, \"children\": [0]}", "0"),
        &["node 0 is its own child"],
    );
    let shared = "{\"children\": [2]}, {\"children\": [2]}, {\"mesh\": 0}";
    c.gltf(
        CLASS,
        "two-parents.gltf",
        with_nodes(shared, "0, 1"),
        &["node 2 has two parents"],
    );
    c.gltf(
        CLASS,
        "child-twice.gltf",
        with_nodes("{\"children\": [1, 1]}, {\"mesh\": 0}", "0"),
        &["lists child 1 twice"],
    );
    // Each node has the next two as children: 2^60 paths to the last one
    // for a walk without a visited set.
    let mut dag = String::new();
    for i in 0..60 {
        write!(dag, "{{\"children\": [{}, {}]}},", i + 1, i + 2).unwrap();
    }
    dag += "{\"mesh\": 0}, {\"mesh\": 0}";
    c.gltf(
        CLASS,
        "exponential-dag.gltf",
        with_nodes(&dag, "0"),
        &["two parents"],
    );
    c.gltf(
        CLASS,
        "root-twice.gltf",
        with_nodes("{\"mesh\": 0}", "0, 0"),
        &["scene 0 lists node 0 twice"],
    );
    let child_root = "{\"children\": [1]}, {\"mesh\": 0}";
    c.gltf(
        CLASS,
        "child-as-root.gltf",
        with_nodes(child_root, "0, 1"),
        &["node 1 as a root", "child of node 0"],
    );
}

fn path_escapes(c: &mut Corpus) {
    const CLASS: &str = "path-escape";
    let bin = triangle_bytes(TRIANGLE, [0, 1, 2]);
    c.write("outside.bin", &bin);
    c.write(&format!("{CLASS}/sub/inside.bin"), &bin);
    let cases: [(&str, &str, &[&str]); 13] = [
        (
            "dotdot.gltf",
            "../outside.bin",
            &["leaves the glTF's folder"],
        ),
        (
            "sub-dotdot.gltf",
            "sub/../../outside.bin",
            &["leaves the glTF's folder"],
        ),
        (
            "percent-dotdot.gltf",
            "%2e%2e/outside.bin",
            &["leaves the glTF's folder"],
        ),
        (
            "percent-slash.gltf",
            "%2E%2E%2Foutside.bin",
            &["leaves the glTF's folder"],
        ),
        ("absolute.gltf", "/etc/passwd", &["absolute path"]),
        ("dev-zero.gltf", "/dev/zero", &["absolute path"]),
        ("file-uri.gltf", "file:///etc/passwd", &["URI scheme"]),
        ("file-relative.gltf", "file:outside.bin", &["URI scheme"]),
        ("http.gltf", "http://127.0.0.1/tri.bin", &["URI scheme"]),
        ("drive.gltf", "C:/outside.bin", &["URI scheme"]),
        ("backslash.gltf", "..\\\\outside.bin", &["backslash"]),
        ("nul.gltf", "inside%00.bin", &["NUL"]),
        (
            "bad-escape.gltf",
            "sub/%zz.bin",
            &["malformed percent escape"],
        ),
    ];
    for (name, uri, needles) in cases {
        let mut needles = needles.to_vec();
        needles.push("buffer 0");
        c.gltf(CLASS, name, triangle_gltf(uri), &needles);
    }
    c.gltf(
        CLASS,
        "missing.gltf",
        triangle_gltf("sub/missing.bin"),
        &["buffer 0", "cannot be opened"],
    );
    c.gltf(
        CLASS,
        "directory.gltf",
        triangle_gltf("sub"),
        &["buffer 0", "not a regular file"],
    );
    c.write(&format!("{CLASS}/short.bin"), &bin[..40]);
    c.gltf(
        CLASS,
        "short-file.gltf",
        triangle_gltf("short.bin"),
        &["40 bytes", "byteLength 44"],
    );
    #[cfg(unix)]
    special_files(c, CLASS);
}

/// FIFOs and devices, as buffers and as the glTF or scene file itself.
/// Opening a FIFO blocks until a writer appears, so a loader that opens
/// one hangs: the time limit catches that.
#[cfg(unix)]
fn special_files(c: &mut Corpus, class: &'static str) {
    use std::os::unix::fs::symlink;
    let dir = c.dir.join(class);
    let fifo = |name: &str| {
        let status = std::process::Command::new("mkfifo")
            .arg(dir.join(name))
            .status()
            .expect("mkfifo runs");
        assert!(status.success(), "mkfifo {name}");
    };
    fifo("pipe.bin");
    c.gltf(
        class,
        "fifo-buffer.gltf",
        triangle_gltf("pipe.bin"),
        &["buffer 0", "not a regular file"],
    );
    symlink(c.dir.join("outside.bin"), dir.join("link-out.bin")).unwrap();
    c.gltf(
        class,
        "symlink-out.gltf",
        triangle_gltf("link-out.bin"),
        &["buffer 0", "outside the glTF's folder"],
    );
    symlink("/dev/zero", dir.join("zero.bin")).unwrap();
    c.gltf(
        class,
        "symlink-dev-zero.gltf",
        triangle_gltf("zero.bin"),
        &["buffer 0", "outside the glTF's folder"],
    );
    symlink("/dev/zero", dir.join("zero.gltf")).unwrap();
    c.add(
        class,
        "gltf-is-dev-zero",
        Load::Gltf(dir.join("zero.gltf")),
        errors(&["zero.gltf", "not a regular file"]),
    );
    fifo("pipe.gltf");
    c.add(
        class,
        "gltf-is-fifo",
        Load::Gltf(dir.join("pipe.gltf")),
        errors(&["pipe.gltf", "not a regular file"]),
    );
    std::fs::create_dir(dir.join("folder.glb")).unwrap();
    c.add(
        class,
        "gltf-is-directory",
        Load::Gltf(dir.join("folder.glb")),
        errors(&["folder.glb", "not a regular file"]),
    );
    fifo("pipe.toml");
    c.add(
        class,
        "scene-is-fifo",
        Load::Scene(dir.join("pipe.toml")),
        errors(&["pipe.toml", "not a regular file"]),
    );
    symlink("/dev/zero", dir.join("zero.toml")).unwrap();
    c.add(
        class,
        "scene-is-dev-zero",
        Load::Scene(dir.join("zero.toml")),
        errors(&["zero.toml", "not a regular file"]),
    );
    let scene = "[[objects]]\ngltf = \"pipe.gltf\"\n";
    c.scene(
        class,
        "scene-objects-fifo.toml",
        scene,
        &["pipe.gltf", "not a regular file"],
    );
}

fn data_uris(c: &mut Corpus) {
    const CLASS: &str = "data-uri";
    let cases: [(&str, &str, &[&str]); 5] = [
        (
            "bad-char.gltf",
            "data:application/octet-stream;base64,AAAA*AAA",
            &["invalid base64"],
        ),
        (
            "bad-length.gltf",
            "data:application/octet-stream;base64,A",
            &["invalid base64"],
        ),
        (
            "not-base64.gltf",
            "data:application/octet-stream,plain",
            &["without base64"],
        ),
        (
            "too-short.gltf",
            "data:application/octet-stream;base64,AAAA",
            &["decodes to 3 bytes", "byteLength 44"],
        ),
        ("empty.gltf", "data:", &["without base64"]),
    ];
    for (name, uri, needles) in cases {
        let mut needles = needles.to_vec();
        needles.push("buffer 0");
        c.gltf(CLASS, name, triangle_gltf(uri), &needles);
    }
}

fn non_finite(c: &mut Corpus) {
    const CLASS: &str = "non-finite";
    for (name, value) in [
        ("nan", f32::NAN),
        ("inf", f32::INFINITY),
        ("neg-inf", f32::NEG_INFINITY),
    ] {
        let mut positions = TRIANGLE;
        positions[1][2] = value;
        let text = triangle_gltf(&data_uri(&triangle_bytes(positions, [0, 1, 2])));
        c.gltf(
            CLASS,
            &format!("position-{name}.gltf"),
            text,
            &["accessor 0 (POSITION)", "vertex 1", "not finite"],
        );
    }
    // NORMAL as accessor 2 over a second copy of the positions.
    let mut bytes = triangle_bytes(TRIANGLE, [0, 1, 2]);
    for c in [0.0f32, 0.0, 1.0, f32::NAN, 0.0, 1.0, 0.0, 0.0, 1.0] {
        bytes.extend_from_slice(&c.to_le_bytes());
    }
    let normals = triangle_gltf(&data_uri(&bytes))
        .replace("\"byteLength\": 44}", "\"byteLength\": 80}")
        .replace("\"POSITION\": 0}", "\"POSITION\": 0, \"NORMAL\": 2}")
        .replace(
            "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}",
            "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}, {\"buffer\": 0, \"byteOffset\": 44, \"byteLength\": 36}",
        )
        .replace(
            "\"type\": \"SCALAR\"}",
            "\"type\": \"SCALAR\"}, {\"bufferView\": 2, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"}",
        );
    c.gltf(
        CLASS,
        "normal-nan.gltf",
        normals,
        &["accessor 2 (NORMAL)", "normal 1", "not finite"],
    );
    // Finite in f64 but beyond f32, which the GPU draws in.
    let far = with_nodes(
        "{\"scale\": [1e30, 1e30, 1e30], \"children\": [1]}, {\"mesh\": 0, \"scale\": [1e30, 1, 1]}",
        "0",
    );
    c.gltf(
        CLASS,
        "scale-beyond-f32.gltf",
        far,
        &["node 1", "beyond ±1e18"],
    );
    // Within f32 but too far to frame: squared distances overflow
    // (±3e38 coordinates once exited 0 with a blank image).
    let framing = with_nodes(
        "{\"scale\": [1e10, 1e10, 1e10], \"children\": [1]}, {\"mesh\": 0, \"scale\": [1e10, 1, 1]}",
        "0",
    );
    c.gltf(
        CLASS,
        "scale-beyond-framing.gltf",
        framing,
        &["node 1", "beyond ±1e18", "scale it down"],
    );
    let chain = "{\"matrix\": [1e38,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], \"children\": [1]}, {\"mesh\": 0, \"matrix\": [1e38,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}";
    c.gltf(
        CLASS,
        "matrix-product-beyond-f32.gltf",
        with_nodes(chain, "0"),
        &["node 1", "beyond"],
    );
    let projective = embedded(|t| {
        swap(
            &t,
            "{\"mesh\": 0}",
            "{\"mesh\": 0, \"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1e38]}",
        )
    });
    c.gltf(
        CLASS,
        "matrix-projective.gltf",
        projective,
        &["node 0", "must be affine"],
    );
    let rotation = embedded(|t| {
        swap(
            &t,
            "{\"mesh\": 0}",
            "{\"mesh\": 0, \"rotation\": [0, 0, 0, 0]}",
        )
    });
    c.gltf(
        CLASS,
        "rotation-zero.gltf",
        rotation,
        &["node 0", "quaternion"],
    );
    let light = with_top_level(
        &embedded(|t| t),
        "\"extensionsUsed\": [\"KHR_lights_punctual\"], \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\", \"intensity\": 1e39}]}}",
    );
    let light = swap(
        &light,
        "{\"mesh\": 0}",
        "{\"mesh\": 0, \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}",
    );
    c.gltf(
        CLASS,
        "light-intensity-inf.gltf",
        light,
        &["light 0", "not a finite"],
    );
    // Zero-area triangles are not an error: they draw nothing.
    let degenerate = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]];
    let text = triangle_gltf(&data_uri(&triangle_bytes(degenerate, [0, 1, 2])));
    let path = c.write(&format!("{CLASS}/degenerate.gltf"), text);
    c.add(CLASS, "degenerate.gltf", Load::Gltf(path), Expect::Loads);
}

fn extensions(c: &mut Corpus) {
    const CLASS: &str = "extensions";
    // Draco, meshopt and KHR_texture_basisu are read now
    // (tests/compressed_gltf.rs); an extension gonio lacks is refused.
    for (name, needle) in [
        ("EXT_mesh_gpu_instancing", "EXT_mesh_gpu_instancing"),
        ("VENDOR_made_up", "VENDOR_made_up"),
    ] {
        let text = with_top_level(
            &embedded(|t| t),
            &format!("\"extensionsUsed\": [\"{name}\"], \"extensionsRequired\": [\"{name}\"]"),
        );
        c.gltf(
            CLASS,
            &format!("{name}.gltf"),
            text,
            &[name, needle, "does not support"],
        );
    }
    let many: Vec<String> = (0..50).map(|i| format!("\"X_{i}\"")).collect();
    let text = with_top_level(
        &embedded(|t| t),
        &format!(
            "\"extensionsUsed\": [{0}], \"extensionsRequired\": [{0}]",
            many.join(",")
        ),
    );
    c.gltf(CLASS, "fifty-required.gltf", text, &["X_0", "X_49"]);
}

fn scene_files(c: &mut Corpus) {
    const CLASS: &str = "scene-toml";
    let camera = "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n";
    c.scene(
        CLASS,
        "unknown-key.toml",
        format!("{camera}fov = 45.0\n"),
        &["unknown field `fov`", "did you mean `fov_y_deg`?", "line 4"],
    );
    let typo = "[camera]\npositon = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n";
    c.scene(
        CLASS,
        "misspelt-key.toml",
        typo,
        &["positon", "did you mean `position`?"],
    );
    c.scene(
        CLASS,
        "misspelt-section.toml",
        "[camra]\nposition = [0.0, 0.0, 3.0]\n",
        &["camra", "did you mean `camera`?"],
    );
    let spot = "[[lights]]\nkind = \"spto\"\nposition = [0.0, 1.0, 0.0]\n";
    c.scene(
        CLASS,
        "misspelt-variant.toml",
        spot,
        &["spto", "did you mean `spot`?"],
    );
    c.scene(
        CLASS,
        "wrong-type.toml",
        "[image]\nwidth = \"wide\"\n",
        &[
            "line 2, column 9",
            "width = \"wide\"",
            "expected a whole number ≥ 0",
        ],
    );
    c.scene(
        CLASS,
        "u32-overflow.toml",
        "[image]\nwidth = 4294967296\n",
        &["line 2"],
    );
    let sphere = "[[objects]]\nshape = \"sphere\"\n";
    c.scene(
        CLASS,
        "nan.toml",
        format!("{sphere}{camera}fov_y_deg = nan\n"),
        &["fov_y_deg", "NaN"],
    );
    c.scene(
        CLASS,
        "inf.toml",
        format!("{sphere}{camera}fov_y_deg = inf\n"),
        &["fov_y_deg", "inf"],
    );
    c.scene(
        CLASS,
        "huge-image.toml",
        "[image]\nwidth = 100000\nheight = 100000\n",
        &["image.width = 100000"],
    );
    c.scene(CLASS, "syntax.toml", "[image\nwidth = 1\n", &["line 1"]);
    let deep_inline = format!("x = {}1{}\n", "{a = ".repeat(10_000), "}".repeat(10_000));
    c.scene(
        CLASS,
        "deep-inline-tables.toml",
        deep_inline,
        &["line 1", "recurse"],
    );
    let deep_arrays = format!("x = {}{}\n", "[".repeat(100_000), "]".repeat(100_000));
    c.scene(
        CLASS,
        "deep-arrays.toml",
        deep_arrays,
        &["line 1", "recurse"],
    );
    let deep_header = format!("[{}]\nx = 1\n", vec!["a"; 10_000].join("."));
    c.scene(
        CLASS,
        "deep-table-header.toml",
        deep_header,
        &["recursion limit"],
    );
    let long = format!("[shading]\nmode = \"{}\"\n", "x".repeat(1_000_000));
    c.scene(CLASS, "megabyte-string.toml", long, &["shading.mode"]);
    c.scene(
        CLASS,
        "not-utf8.toml",
        b"[image]\nwidth = \"\xff\xfe\"\n",
        &["not UTF-8"],
    );
    c.scene(CLASS, "bom-garbage.toml", b"\x00\x00\x00\x00", &["line 1"]);
    let big = format!("# {}\n", "x".repeat(17 << 20));
    c.scene(CLASS, "seventeen-mib.toml", big, &["at most 16777216"]);
    c.scene(
        CLASS,
        "gltf-missing.toml",
        "[[objects]]\ngltf = \"nope.gltf\"\n",
        &["nope.gltf", "cannot read"],
    );
    c.scene(
        CLASS,
        "gltf-absolute-dev-zero.toml",
        "[[objects]]\ngltf = \"/dev/zero\"\n",
        &["/dev/zero", "not a regular file"],
    );
    // A scene may name a model outside its own folder: that is the user's
    // choice (confinement is for what a glTF references).
    c.write("shared-model.gltf", embedded(|t| t));
    let path = c.write(
        &format!("{CLASS}/up/outside-model.toml"),
        "[[objects]]\ngltf = \"../../shared-model.gltf\"\n",
    );
    c.add(
        CLASS,
        "outside-model.toml",
        Load::Scene(path),
        Expect::Loads,
    );
    // Generated shapes and the scene's own lights share the budget.
    let spheres = "[[objects]]\nshape = \"sphere\"\nsegments = 64\n".repeat(3);
    let path = c.write(&format!("{CLASS}/three-spheres.toml"), spheres);
    let limits = Limits {
        triangles: 10_000,
        ..Limits::default()
    };
    c.add(
        CLASS,
        "three-spheres.toml",
        Load::SceneWithLimits(path, limits),
        errors(&["objects[2]", "--limit triangles=N"]),
    );
    // A 4096-division plane is 33.5 M triangles: refused from its declared
    // size, before a byte of it is built (this case would take seconds and
    // gigabytes otherwise, and the per-case time limit would catch it).
    let path = c.write(
        &format!("{CLASS}/fine-plane.toml"),
        "[[objects]]\nshape = \"plane\"\nsegments = 4096\n",
    );
    c.add(
        CLASS,
        "fine-plane.toml",
        Load::SceneWithLimits(path, limits),
        errors(&[
            "objects[0]",
            "33554432 more triangles",
            "--limit triangles=N",
        ]),
    );
    let light = "[[lights]]\nkind = \"point\"\nposition = [0.0, 1.0, 0.0]\nintensity = 1.0\n";
    c.scene(
        CLASS,
        "lights-1025.toml",
        format!("{sphere}{}", light.repeat(1025)),
        &["lights", "--limit lights=N"],
    );
    let deep_key = format!("{}=1", vec!["a"; 60_000].join("."));
    c.add(
        CLASS,
        "set-deep-key",
        Load::Overrides(vec![deep_key]),
        errors(&["60000 parts", "at most 16"]),
    );
    c.add(
        CLASS,
        "set-misspelt",
        Load::Overrides(vec!["camera.fov=30".into()]),
        errors(&["--set camera.fov=30", "did you mean `fov_y_deg`?"]),
    );
    c.add(
        CLASS,
        "set-nan",
        Load::Overrides(vec!["image.width=nan".into()]),
        errors(&["--set image.width=nan"]),
    );
}

/// Inputs the fuzzers found, reduced to what triggers them. Each was a
/// panic inside the `gltf` crate that the loader now prevents by a check.
fn fuzz_findings(c: &mut Corpus) {
    const CLASS: &str = "fuzz-found";
    // `Camera::projection` unwraps the object its `type` names.
    for (kind, other) in [
        ("perspective", "orthographic"),
        ("orthographic", "perspective"),
    ] {
        let camera = format!(
            "\"cameras\": [{{\"type\": \"{kind}\", \"{other}\": {{\"xmag\": 1, \"ymag\": 1, \"zfar\": 100, \"znear\": 0.01, \"yfov\": 0.7}}}}]"
        );
        let text = with_top_level(&embedded(|t| t), &camera);
        let text = swap(&text, "{\"mesh\": 0}", "{\"mesh\": 0, \"camera\": 0}");
        let needle = format!("cameras[0] has type \"{kind}\" but no `{kind}` object");
        c.gltf(
            CLASS,
            &format!("camera-{kind}-without-object.gltf"),
            text,
            &[&needle],
        );
    }
}

/// Environment maps a scene file points at: truncated, a header declaring
/// a huge map (refused before decoding), not 2 : 1, NaN and negative
/// texels, a wrong magic number, a header that would make the decoder
/// allocate gigabytes, an image of another kind.
fn environment_maps(c: &mut Corpus) {
    const CLASS: &str = "environment-map";
    let map = |w: u32, h: u32, texel: fn(u32, u32) -> [f32; 3]| {
        image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb(texel(x, y)))
    };
    let encode = |image: image::Rgb32FImage, format: image::ImageFormat| {
        let mut bytes = std::io::Cursor::new(Vec::new());
        image::DynamicImage::from(image)
            .write_to(&mut bytes, format)
            .unwrap();
        bytes.into_inner()
    };
    let smooth = |x: u32, y: u32| [x as f32 * 0.25, y as f32 * 0.5, 1.0];
    let hdr = encode(map(16, 8, smooth), image::ImageFormat::Hdr);
    let exr = encode(map(16, 8, smooth), image::ImageFormat::OpenExr);
    let mut magic = exr.clone();
    magic[0] ^= 0xff;
    // Found by the environment_map fuzz target (its first byte picks the
    // format): 719 bytes that made the `exr` crate allocate 1.7 GB.
    let tile_allocation = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fuzz/corpus/environment_map/fuzz-found-tile-allocation.exr"),
    )
    .unwrap()[1..]
        .to_vec();
    let cases: [(&str, Vec<u8>, &[&str]); 9] = [
        (
            "truncated.hdr",
            hdr[..hdr.len() / 2].to_vec(),
            &["truncated.hdr", "not a readable hdr image"],
        ),
        (
            "truncated.exr",
            exr[..exr.len() / 2].to_vec(),
            &["truncated.exr", "not a readable exr image"],
        ),
        (
            "bomb.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n".to_vec(),
            &["bomb.hdr", "200000 × 100000", "largest side"],
        ),
        (
            "square.exr",
            encode(map(8, 8, smooth), image::ImageFormat::OpenExr),
            &["square.exr", "twice as wide as high", "8 × 8"],
        ),
        (
            "nan.exr",
            encode(
                map(8, 4, |x, _| [if x == 3 { f32::NAN } else { 1.0 }, 0.5, 0.5]),
                image::ImageFormat::OpenExr,
            ),
            &["nan.exr", "column 3, row 0", "finite and non-negative"],
        ),
        (
            "negative.exr",
            encode(
                map(8, 4, |x, _| [1.0, if x == 5 { -2.0 } else { 0.5 }, 0.5]),
                image::ImageFormat::OpenExr,
            ),
            &["negative.exr", "column 5, row 0", "finite and non-negative"],
        ),
        ("magic.exr", magic, &["magic.exr", "OpenEXR's magic number"]),
        (
            "tile-allocation.exr",
            tile_allocation,
            &["tile-allocation.exr", "attribute `s\\u{3}` has no type"],
        ),
        (
            "png-named.hdr",
            std::fs::read(
                Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/textured/checker.png"),
            )
            .unwrap(),
            &["png-named.hdr", "it is a PNG image, not a hdr image"],
        ),
    ];
    for (name, bytes, needles) in cases {
        c.write(&format!("{CLASS}/{name}"), bytes);
        let mut needles = needles.to_vec();
        needles.push("environment.map");
        c.scene(
            CLASS,
            &format!("{name}.toml"),
            format!("[environment]\nmap = \"{name}\"\n"),
            &needles,
        );
    }
}

/// Environment maps and MERL tables under the rules glTF files already
/// had: special files refused as "not a regular file" (a FIFO
/// hung `render`, `/dev/zero` read 4 GB), every radiance and reflectance
/// held to the one range rule (a finite value past f32's range gave Inf
/// and NaN pixels with exit 0), maps counted against `--limit bytes` from
/// their header.
fn maps_and_tables(c: &mut Corpus) {
    const CLASS: &str = "maps-and-tables";
    let dir = c.dir.join(CLASS);
    std::fs::create_dir_all(&dir).unwrap();
    let object = "[[objects]]\nshape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n";
    let measured = |file: &str| {
        format!("{object}[materials.m]\nmodel = \"measured\"\nmeasured = \"{file}\"\n")
    };
    let with_map = |file: &str| format!("[environment]\nmap = \"{file}\"\n");
    #[cfg(unix)]
    {
        use std::os::unix::fs::symlink;
        for name in ["pipe.hdr", "pipe.exr", "pipe.binary"] {
            let status = std::process::Command::new("mkfifo")
                .arg(dir.join(name))
                .status()
                .expect("mkfifo runs");
            assert!(status.success(), "mkfifo {name}");
        }
        for name in ["zero.hdr", "zero.exr", "zero.binary"] {
            symlink("/dev/zero", dir.join(name)).unwrap();
        }
        for name in ["pipe.hdr", "pipe.exr", "zero.hdr", "zero.exr"] {
            c.scene(
                CLASS,
                &format!("map-{name}.toml"),
                with_map(name),
                &["environment.map", name, "not a regular file"],
            );
        }
        for name in ["pipe.binary", "zero.binary"] {
            c.scene(
                CLASS,
                &format!("merl-{name}.toml"),
                measured(name),
                &[name, "not a regular file"],
            );
        }
    }
    // RGBE exponent 255: 0.5 · 2¹²⁷ = 8.5e37 per channel, finite in f32.
    let mut rgbe = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n".to_vec();
    for _ in 0..32 {
        rgbe.extend([128, 128, 128, 255]);
    }
    c.write(&format!("{CLASS}/exponent-255.hdr"), &rgbe);
    c.scene(
        CLASS,
        "map-exponent-255.toml",
        with_map("exponent-255.hdr"),
        &["exponent-255.hdr", "at most 1e20"],
    );
    let exr = |value: f32| {
        let image = image::Rgb32FImage::from_pixel(8, 4, image::Rgb([value, 1.0, 1.0]));
        let mut bytes = std::io::Cursor::new(Vec::new());
        image::DynamicImage::from(image)
            .write_to(&mut bytes, image::ImageFormat::OpenExr)
            .unwrap();
        bytes.into_inner()
    };
    c.write(&format!("{CLASS}/3e38.exr"), exr(3e38));
    c.scene(
        CLASS,
        "map-3e38.toml",
        with_map("3e38.exr"),
        &["3e38.exr", "at most 1e20"],
    );
    // Each factor within the rule, their product past it.
    c.write(&format!("{CLASS}/1e19.exr"), exr(1e19));
    c.scene(
        CLASS,
        "map-times-scale.toml",
        format!("{}scale = 100.0\n", with_map("1e19.exr")),
        &["environment.scale", "largest texel", "over 1e20"],
    );
    c.add(
        CLASS,
        "sky-scale-1e39",
        Load::Overrides(vec![
            "environment.map=\"sky\"".into(),
            "environment.scale=1e39".into(),
        ]),
        errors(&["environment.scale", "1e39", "at most 1e20"]),
    );
    // A map over `--limit bytes`, refused from its header: 64 × 32 texels
    // are 24 KiB as f32 RGB.
    let mut small = std::io::Cursor::new(Vec::new());
    image::DynamicImage::from(image::Rgb32FImage::from_pixel(
        64,
        32,
        image::Rgb([1.0, 1.0, 1.0]),
    ))
    .write_to(&mut small, image::ImageFormat::Hdr)
    .unwrap();
    c.write(&format!("{CLASS}/64x32.hdr"), small.into_inner());
    let limited = c.write(&format!("{CLASS}/map-limit.toml"), with_map("64x32.hdr"));
    c.add(
        CLASS,
        "map-over-limit-bytes",
        Load::SceneWithLimits(
            limited,
            Limits {
                bytes: 16 << 10,
                ..Limits::default()
            },
        ),
        errors(&["64x32.hdr", "--limit bytes=N"]),
    );
    // A MERL table of 1e300 values (`fit` reported "error inf").
    let mut merl = Vec::new();
    for n in [2i32, 2, 2] {
        merl.extend(n.to_le_bytes());
    }
    for _ in 0..3 * 8 {
        merl.extend(1e300f64.to_le_bytes());
    }
    c.write(&format!("{CLASS}/1e300.binary"), &merl);
    c.scene(
        CLASS,
        "merl-1e300.toml",
        measured("1e300.binary"),
        &["1e300.binary", "1e300", "at most f_r = 1e17"],
    );
    // A texture JPEG cut short (a cut PNG was already refused).
    // Cut in its scan data, past the header: zune-jpeg alone decoded it.
    let mut jpeg = std::io::Cursor::new(Vec::new());
    image::RgbImage::from_fn(64, 64, |x, y| {
        image::Rgb([(x * 4) as u8, (y * 4) as u8, (x ^ y) as u8 * 4])
    })
    .write_to(&mut jpeg, image::ImageFormat::Jpeg)
    .unwrap();
    let jpeg = jpeg.into_inner();
    c.write(&format!("{CLASS}/cut.jpg"), &jpeg[..jpeg.len() * 3 / 4]);
    c.scene(
        CLASS,
        "texture-cut-jpeg.toml",
        format!("{object}[materials.m]\nmodel = \"lambert\"\nk_d_texture = \"cut.jpg\"\n"),
        &["k_d_texture", "cut.jpg", "truncated"],
    );
    // glTF images the `gltf` crate unwraps (it panicked on `[{}]`).
    c.gltf(
        CLASS,
        "image-without-source.gltf",
        with_top_level(&embedded(|t| t), r#""images": [{}]"#),
        &["image 0", "neither a uri nor a bufferView"],
    );
    c.gltf(
        CLASS,
        "image-view-without-mime-type.gltf",
        with_top_level(&embedded(|t| t), r#""images": [{"bufferView": 0}]"#),
        &["image 0", "no mimeType"],
    );
}

fn corpus(dir: &Path) -> Vec<Case> {
    let mut c = Corpus::new(dir);
    glb_container(&mut c);
    bad_json(&mut c);
    out_of_range(&mut c);
    offsets_and_strides(&mut c);
    huge_counts(&mut c);
    hierarchies(&mut c);
    path_escapes(&mut c);
    data_uris(&mut c);
    non_finite(&mut c);
    extensions(&mut c);
    scene_files(&mut c);
    environment_maps(&mut c);
    maps_and_tables(&mut c);
    fuzz_findings(&mut c);
    c.cases
}

// ---------------------------------------------------------------------------
// Running

/// What a load did: its error message, or success.
type Outcome = Result<(), String>;

fn run_load(load: &Load) -> Outcome {
    match load {
        Load::Gltf(path) => gltf_import::load(path).map(drop),
        Load::Scene(path) => scene_file::load(&SceneSource::File(path.clone()), &[]).map(drop),
        Load::Overrides(sets) => scene_file::load(&SceneSource::BuiltIn, sets).map(drop),
        Load::SceneWithLimits(path, limits) => {
            scene_file::load_with_limits(&SceneSource::File(path.clone()), &[], *limits).map(drop)
        }
    }
    .map_err(|e| e.to_string())
}

/// Runs the load on its own thread, catching panics, and waits at most
/// [`TIME_LIMIT`]. The thread gets the default 2 MiB stack of spawned
/// threads, a quarter of the main thread's: deep inputs are tested on the
/// smaller stack.
fn run_with_limits(case: &Case) -> Result<Outcome, String> {
    let (send, receive) = mpsc::channel();
    let load = case.load.clone();
    std::thread::Builder::new()
        .name(case.name.clone())
        .spawn(move || {
            let result = panic::catch_unwind(AssertUnwindSafe(|| run_load(&load)));
            let _ = send.send(result);
        })
        .expect("spawn");
    match receive.recv_timeout(TIME_LIMIT) {
        Ok(Ok(outcome)) => Ok(outcome),
        Ok(Err(_)) => Err("panicked".into()),
        Err(_) => Err(format!("took longer than {TIME_LIMIT:?} (hang?)")),
    }
}

fn check(case: &Case) -> Result<(), String> {
    let outcome = run_with_limits(case)?;
    // `GONIO_SHOW_CORPUS=1 cargo test --test hostile_input` lists every
    // message, to review them as a user would read them.
    if std::env::var_os("GONIO_SHOW_CORPUS").is_some() {
        eprintln!("[{}] {}: {outcome:?}", case.class, case.name);
    }
    match (&case.expect, outcome) {
        (Expect::Loads, Ok(())) => Ok(()),
        (Expect::Loads, Err(e)) => Err(format!("should load, failed: {e}")),
        (Expect::Error(_), Ok(())) => Err("was accepted".into()),
        (Expect::Error(needles), Err(message)) => {
            let missing: Vec<&String> = needles.iter().filter(|n| !message.contains(*n)).collect();
            if !missing.is_empty() {
                return Err(format!("message lacks {missing:?}: {message}"));
            }
            if message.contains(GUARD_MESSAGE) {
                return Err(format!("needed the panic guard: {message}"));
            }
            if message.contains('\n') {
                return Err(format!("message is not one paragraph: {message}"));
            }
            if message.chars().count() > 2000 {
                return Err(format!(
                    "message is {} characters long",
                    message.chars().count()
                ));
            }
            Ok(())
        }
    }
}

#[test]
fn every_hostile_input_is_refused_in_time_without_panic() {
    let dir = tempfile::tempdir().unwrap();
    let cases = corpus(dir.path());
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            check(case)
                .err()
                .map(|e| format!("[{}] {}: {e}", case.class, case.name))
        })
        .collect();
    let classes: std::collections::BTreeSet<_> = cases.iter().map(|c| c.class).collect();
    eprintln!(
        "hostile corpus: {} cases in {} classes",
        cases.len(),
        classes.len()
    );
    assert!(
        cases.len() >= 50,
        "the corpus has only {} cases",
        cases.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn optional_unknown_extensions_are_noted_not_refused() {
    let dir = tempfile::tempdir().unwrap();
    let c = Corpus::new(dir.path());
    let text = with_top_level(
        &embedded(|t| t),
        "\"extensionsUsed\": [\"KHR_animation_pointer\", \"EXT_meshopt_compression\"]",
    );
    let path = c.write("optional.gltf", text);
    let scene = gltf_import::load(&path).unwrap();
    // EXT_meshopt_compression is read: only the animation pointer (which
    // gonio does not read) is named, in a warning (shown without
    // --verbose).
    assert_eq!(scene.notes.len(), 1, "{:?}", scene.notes);
    assert!(
        scene.notes[0].starts_with("warning: ")
            && scene.notes[0].contains("KHR_animation_pointer")
            && !scene.notes[0].contains("EXT_meshopt_compression"),
        "{:?}",
        scene.notes
    );
    // Application-specific attributes are allowed, and ignored.
    let custom = embedded(|t| swap(&t, "\"POSITION\": 0}", "\"POSITION\": 0, \"_BATCHID\": 0}"));
    let custom = gltf_import::load(&c.write("custom-attribute.gltf", custom)).unwrap();
    assert!(
        custom.notes[0].contains("vertex attribute"),
        "{:?}",
        custom.notes
    );
    // Through a scene, each note names its file.
    let mut loader = GltfLoader::new(Limits::default());
    loader.load(&path).unwrap();
    assert!(
        loader.notes()[0].starts_with(&format!("warning: {}", path.display())),
        "{:?}",
        loader.notes()
    );
}

#[test]
fn one_budget_covers_every_model_of_a_scene() {
    let dir = tempfile::tempdir().unwrap();
    let c = Corpus::new(dir.path());
    let path = c.write("one-triangle.gltf", embedded(|t| t));
    let limits = Limits {
        triangles: 2,
        ..Limits::default()
    };
    let mut loader = GltfLoader::new(limits);
    loader.load(&path).unwrap();
    loader.load(&path).unwrap();
    let err = loader.load(&path).unwrap_err().to_string();
    assert!(
        err.contains("triangles to draw is 1, over the limit of 0"),
        "{err}"
    );
    // Lower limits apply to a single load as well.
    let tiny = Limits {
        bytes: 100,
        ..Limits::default()
    };
    let err = gltf_import::load_with_limits(&path, &tiny)
        .unwrap_err()
        .to_string();
    assert!(err.contains("--limit bytes=N"), "{err}");
}

#[test]
fn loading_from_bytes_confines_buffers_to_the_base_folder() {
    let dir = tempfile::tempdir().unwrap();
    let c = Corpus::new(dir.path());
    c.write("inner/tri.bin", triangle_bytes(TRIANGLE, [0, 1, 2]));
    let inner = dir.path().join("inner");
    let limits = Limits::default();
    let ok = gltf_import::load_from_bytes(triangle_gltf("tri.bin").as_bytes(), &inner, &limits);
    assert_eq!(ok.unwrap().meshes.len(), 1);
    let err = gltf_import::load_from_bytes(
        triangle_gltf("../inner/../x.bin").as_bytes(),
        &inner,
        &limits,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("<memory>") && err.contains("leaves"), "{err}");
    let glb = gltf_import::load_from_bytes(&triangle_glb(), &inner, &limits).unwrap();
    assert_eq!(glb.meshes.len(), 1);
}

// ---------------------------------------------------------------------------
// Through the binary

/// Runs `gonio render ARGS -o out.png` in `dir`; returns the exit status
/// and stderr, and checks that no output file was left.
fn render(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = dir.join("out.png");
    let _ = std::fs::remove_file(&out);
    let result = common::gonio()
        .arg("render")
        .args(args)
        .arg("-o")
        .arg(&out)
        .args(["--width", "32", "--height", "24"])
        .env("XDG_RUNTIME_DIR", dir)
        .output()
        .expect("gonio runs");
    let stderr = String::from_utf8_lossy(&result.stderr).into_owned();
    if result.status.code() != Some(0) {
        assert!(
            !out.exists(),
            "{args:?}: an output file was written despite: {stderr}"
        );
    }
    (result.status.code(), stderr)
}

fn assert_refused(dir: &Path, args: &[&str], needle: &str) {
    let (code, stderr) = render(dir, args);
    assert_eq!(code, Some(2), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("gonio: error:"))
        .collect();
    assert_eq!(
        errors.len(),
        1,
        "{args:?}: expected one error paragraph: {stderr}"
    );
    assert!(
        errors[0].contains(needle),
        "{args:?}: `{needle}` not in {}",
        errors[0]
    );
}

#[test]
fn the_binary_refuses_hostile_files_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Corpus::new(dir.path());
    glb_container(&mut c);
    hierarchies(&mut c);
    path_escapes(&mut c);
    scene_files(&mut c);
    non_finite(&mut c);
    let path_of = |name: &str| -> String {
        let case = c
            .cases
            .iter()
            .find(|k| k.name == name)
            .unwrap_or_else(|| panic!("{name}"));
        match &case.load {
            Load::Gltf(p) | Load::Scene(p) => p.display().to_string(),
            Load::Overrides(_) | Load::SceneWithLimits(..) => unreachable!(),
        }
    };
    let d = dir.path();
    assert_refused(d, &[&path_of("bad-magic.glb")], "bad-magic.glb");
    assert_refused(
        d,
        &[&path_of("json-chunk-length-overflow.glb")],
        "4294967295",
    );
    assert_refused(d, &[&path_of("cycle-2.gltf")], "cycle");
    assert_refused(d, &[&path_of("dotdot.gltf")], "leaves the glTF's folder");
    assert_refused(
        d,
        &[&path_of("unknown-key.toml")],
        "did you mean `fov_y_deg`?",
    );
    assert_refused(d, &[&path_of("deep-arrays.toml")], "deep-arrays.toml");
    // ±3e38 coordinates once exited 0 with a blank image.
    assert_refused(d, &[&path_of("scale-beyond-framing.gltf")], "scale it down");
    #[cfg(unix)]
    {
        assert_refused(d, &[&path_of("fifo-buffer.gltf")], "not a regular file");
        assert_refused(d, &[&path_of("scene-is-fifo")], "not a regular file");
        // A FIFO named as the glTF itself: refused as a special file, not
        // reported as missing.
        assert_refused(d, &[&path_of("gltf-is-fifo")], "not a regular file");
    }
    let deep_key = format!("{}=1", vec!["a"; 60_000].join("."));
    assert_refused(d, &["--set", &deep_key], "at most 16");
    let model = c.write("model.gltf", embedded(|t| t));
    let model = model.display().to_string();
    assert_refused(
        d,
        &[&model, "--limit", "triangles=0"],
        "--limit triangles=N",
    );
    assert_refused(
        d,
        &[&model, "--limit", "triangels=9"],
        "unknown limit `triangels`",
    );
}

/// Through the binary: a glTF image without a source is refused
/// with no panic text on stderr (the crate's panic message reached the
/// user), a FIFO environment map and MERL table are refused at once.
#[test]
fn the_binary_refuses_maps_tables_and_sourceless_images_without_panic_text() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Corpus::new(dir.path());
    maps_and_tables(&mut c);
    let path_of = |name: &str| -> String {
        let case = c
            .cases
            .iter()
            .find(|k| k.name == name)
            .unwrap_or_else(|| panic!("{name}"));
        match &case.load {
            Load::Gltf(p) | Load::Scene(p) | Load::SceneWithLimits(p, _) => p.display().to_string(),
            Load::Overrides(_) => unreachable!(),
        }
    };
    let d = dir.path();
    assert_refused(
        d,
        &[&path_of("image-without-source.gltf")],
        "neither a uri nor a bufferView",
    );
    let (_, stderr) = render(d, &[&path_of("image-without-source.gltf")]);
    assert!(
        !stderr.contains("panicked") && !stderr.contains("gltf-1."),
        "{stderr}"
    );
    #[cfg(unix)]
    {
        assert_refused(d, &[&path_of("map-pipe.hdr.toml")], "not a regular file");
        assert_refused(
            d,
            &[&path_of("merl-pipe.binary.toml")],
            "not a regular file",
        );
    }
    assert_refused(
        d,
        &[&path_of("map-over-limit-bytes"), "--limit", "bytes=16Ki"],
        "--limit bytes=N",
    );
    assert_refused(
        d,
        &[
            "--set",
            "environment.map=\"sky\"",
            "--set",
            "environment.scale=1e39",
        ],
        "environment.scale",
    );
}

/// Degenerate triangles and a deep hierarchy draw (nothing, or the one
/// triangle) with both renderers, without panicking.
#[test]
fn the_binary_renders_degenerate_and_deep_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let mut c = Corpus::new(dir.path());
    hierarchies(&mut c);
    non_finite(&mut c);
    // A visible triangle plus zero-area ones (a point, a line).
    let mut bytes = Vec::new();
    for c in [
        [0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 2.0, 0.0],
    ] {
        for v in c {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 3, 3, 3, 0, 3, 3] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes.extend_from_slice(&[0, 0]);
    let mixed = triangle_gltf(&data_uri(&bytes))
        .replace("\"byteLength\": 44}", "\"byteLength\": 68}")
        .replace(
            "\"byteOffset\": 0, \"byteLength\": 36",
            "\"byteOffset\": 0, \"byteLength\": 48",
        )
        .replace(
            "\"byteOffset\": 36, \"byteLength\": 6",
            "\"byteOffset\": 48, \"byteLength\": 18",
        )
        .replace(
            "\"count\": 3, \"type\": \"VEC3\"",
            "\"count\": 4, \"type\": \"VEC3\"",
        )
        .replace("\"max\": [1, 1, 0]", "\"max\": [2, 2, 0]")
        .replace(
            "\"componentType\": 5123, \"count\": 3",
            "\"componentType\": 5123, \"count\": 9",
        );
    let mixed = c.write("mixed.gltf", mixed).display().to_string();
    let degenerate = c
        .dir
        .join("non-finite/degenerate.gltf")
        .display()
        .to_string();
    let deep = c
        .dir
        .join("hierarchy/deep-chain.gltf")
        .display()
        .to_string();
    for model in [&mixed, &degenerate, &deep] {
        for renderer in [&[][..], &["--reference"][..]] {
            let mut args = vec![model.as_str()];
            args.extend_from_slice(renderer);
            let (code, stderr) = render(dir.path(), &args);
            assert_eq!(code, Some(0), "{args:?}: {stderr}");
            assert!(dir.path().join("out.png").is_file(), "{args:?}");
        }
    }
}

/// What was once accepted without a word. A texture on a
/// parameter a measured material does not read is refused as the
/// parameter is; one on a parameter a model ignores (`k_e_texture` on
/// Lambert) warns as the parameter does; a glTF texture reading a UV set
/// its primitive lacks (invalid glTF) warns.
#[test]
fn inconsistent_textures_are_refused_or_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let c = Corpus::new(dir.path());
    let png = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/textured/checker.png"),
    )
    .unwrap();
    c.write("checker.png", &png);
    let object = "[[objects]]\nshape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n";
    let load = |name: &str, text: String| {
        let path = c.write(name, text);
        scene_file::load_with_limits(&SceneSource::File(path), &[], Limits::default())
    };
    let err = match load(
        "measured.toml",
        format!(
            "{object}[materials.m]\nmodel = \"measured\"\nmeasured = \"chrome\"\nk_d_texture = \"checker.png\"\n"
        ),
    ) {
        Ok(_) => panic!("k_d_texture on a measured material loaded"),
        Err(e) => e.to_string(),
    };
    assert!(
        err.contains("k_d_texture") && err.contains("measured"),
        "{err}"
    );
    let (_, notes) = load(
        "lambert.toml",
        format!("{object}[materials.m]\nmodel = \"lambert\"\nk_e_texture = \"checker.png\"\n"),
    )
    .unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with(scene_file::WARNING) && n.contains("`k_e_texture`")),
        "{notes:?}"
    );
    // A base colour texture on TEXCOORD_1 of a primitive with no UVs.
    let gltf = with_top_level(
        &embedded(|t| swap(&t, r#"{"attributes""#, r#"{"material": 0, "attributes""#)),
        &format!(
            r#""materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0, "texCoord": 1}}}}}}],
  "textures": [{{"source": 0}}],
  "images": [{{"uri": "{}"}}]"#,
            format_args!(
                "data:image/png;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&png)
            )
        ),
    );
    let gltf = c.write("uv1.gltf", gltf);
    let (_, notes) =
        scene_file::load_with_limits(&SceneSource::File(gltf), &[], Limits::default()).unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with(scene_file::WARNING) && n.contains("TEXCOORD_1")),
        "{notes:?}"
    );
}
