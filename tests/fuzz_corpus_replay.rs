//! Replays the committed fuzz corpus (`fuzz/corpus/<target>/*`) through the
//! same calls the cargo-fuzz targets make (`fuzz/fuzz_targets/harness.rs`),
//! each under a time limit and a panic check. This is what CI runs: the
//! fuzzers themselves need nightly Rust and libFuzzer, this needs neither.
//!
//! The seed files are generated from the sample models and a few
//! hand-written inputs by the ignored test `regenerate_seed_corpus`:
//! `cargo test --release --test fuzz_corpus_replay -- --ignored`
//! (the compressed-asset codecs' seeds by `regenerate_codec_seed_corpus`,
//! from assets/gltf-compressed).
//! Inputs the fuzzers found interesting can be added to the same folders.

#[path = "../fuzz/fuzz_targets/harness.rs"]
mod harness;

use base64::Engine as _;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Longest one input may take.
const TIME_LIMIT: Duration = Duration::from_secs(10);

fn corpus_dir(target: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target)
}

/// Every file of a target's corpus, in name order.
fn corpus_files(target: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus_dir(target))
        .unwrap_or_else(|e| panic!("fuzz/corpus/{target}: {e}"))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.is_file())
        .collect();
    files.sort();
    files
}

/// Runs `run` on the file's bytes on its own thread; an error describes a
/// panic or a hang.
fn replay(path: &Path, run: fn(&[u8])) -> Result<(), String> {
    let bytes = std::fs::read(path).unwrap();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let outcome = panic::catch_unwind(AssertUnwindSafe(|| run(&bytes)));
        let _ = send.send(outcome.is_ok());
    });
    match receive.recv_timeout(TIME_LIMIT) {
        Ok(true) => Ok(()),
        Ok(false) => Err(format!("{}: panicked", path.display())),
        Err(_) => Err(format!(
            "{}: took longer than {TIME_LIMIT:?}",
            path.display()
        )),
    }
}

fn replay_target(target: &str, run: fn(&[u8]), minimum: usize) {
    let files = corpus_files(target);
    assert!(
        files.len() >= minimum,
        "fuzz/corpus/{target} has {} files, expected at least {minimum}",
        files.len()
    );
    let failures: Vec<String> = files
        .iter()
        .filter_map(|path| replay(path, run).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn gltf_corpus_replays_without_panic_or_hang() {
    replay_target("gltf_load", harness::gltf_load, 10);
}

#[test]
fn scene_corpus_replays_without_panic_or_hang() {
    replay_target("scene_toml", harness::scene_toml, 5);
}

#[test]
fn texture_corpus_replays_without_panic_or_hang() {
    replay_target("texture_decode", harness::texture_decode, 5);
}

#[test]
fn merl_corpus_replays_without_panic_or_hang() {
    replay_target("merl_parse", harness::merl_parse, 4);
}

#[test]
fn environment_map_corpus_replays_without_panic_or_hang() {
    replay_target("environment_map", harness::environment_map, 6);
}

#[test]
fn draco_corpus_replays_without_panic_or_hang() {
    replay_target("draco_mesh", harness::draco_mesh, 4);
}

#[test]
fn meshopt_corpus_replays_without_panic_or_hang() {
    replay_target("meshopt_buffer", harness::meshopt_buffer, 4);
}

#[test]
fn ktx2_corpus_replays_without_panic_or_hang() {
    replay_target("ktx2_texture", harness::ktx2_texture, 4);
}

#[test]
fn webp_corpus_replays_without_panic_or_hang() {
    replay_target("webp_texture", harness::webp_texture, 3);
}

/// The generated seeds are valid and must load through the fuzz harness's
/// path (`load_from_bytes`): a seed that fails early would fuzz only the
/// first checks.
#[test]
fn generated_seeds_load() {
    let handwritten: Vec<&str> = handwritten_gltf_seeds().iter().map(|(n, _)| *n).collect();
    for path in corpus_files("gltf_load") {
        let name = path.file_name().unwrap().to_string_lossy();
        if !(name.starts_with("sample-") || handwritten.contains(&name.as_ref())) {
            continue;
        }
        let bytes = std::fs::read(&path).unwrap();
        let limits = harness::limits();
        gonio::scene::gltf_import::load_from_bytes(&bytes, harness::workspace(), &limits)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

// ---------------------------------------------------------------------------
// Seed generation

/// Sample models small enough to be good seeds, with external buffers
/// embedded as `data:` URIs so that a seed is one self-contained input.
const SAMPLES: [&str; 7] = [
    "Box/Box.gltf",
    "BoxInterleaved/BoxInterleaved.gltf",
    "Cameras/Cameras.gltf",
    "MultipleScenes/MultipleScenes.gltf",
    "SimpleMeshes/SimpleMeshes.gltf",
    "Triangle/Triangle.gltf",
    "TriangleWithoutIndices/TriangleWithoutIndices.gltf",
];

/// `text` with every `"uri": "<file next to the glTF>"` of a `.bin` file
/// replaced by the file's contents as a `data:` URI.
fn embed_buffers(text: &str, folder: &Path) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find(".bin\"") {
        let start = rest[..at].rfind('"').unwrap() + 1;
        let name = &rest[start..at + 4];
        let bytes = std::fs::read(folder.join(name)).unwrap();
        out += &rest[..start];
        out += "data:application/octet-stream;base64,";
        out += &base64::engine::general_purpose::STANDARD.encode(bytes);
        rest = &rest[at + 4..];
    }
    out + rest
}

/// A GLB of `json` and `bin` (chunks padded to 4 bytes as the spec asks).
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
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

/// Hand-written glTF seeds that reach code the samples do not: sparse
/// accessors, strips and fans, lights, a node tree, an external buffer.
fn handwritten_gltf_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let triangle = std::fs::read_to_string(harness::workspace().join("tri.gltf")).unwrap();
    let bin = std::fs::read(harness::workspace().join("tri.bin")).unwrap();
    let glb_json = triangle.replace("\"uri\": \"tri.bin\", ", "");
    let sparse = triangle.replace(
        "\"min\": [0, 0, 0]",
        "\"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 1, \"componentType\": 5123}, \"values\": {\"bufferView\": 0}}, \"min\": [0, 0, 0]",
    );
    let strip = triangle.replace("\"indices\": 1}", "\"indices\": 1, \"mode\": 5}");
    let fan = triangle.replace("\"indices\": 1}", "\"indices\": 1, \"mode\": 6}");
    let tree = triangle
        .replace(
            "\"scene\": 0,",
            "\"scene\": 0, \"extensionsUsed\": [\"KHR_lights_punctual\", \"KHR_materials_sheen\"], \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"spot\", \"spot\": {\"outerConeAngle\": 0.5}}, {\"type\": \"directional\"}]}},",
        )
        .replace(
            "\"nodes\": [{\"mesh\": 0}]",
            "\"nodes\": [{\"children\": [1, 2], \"rotation\": [0, 0.7071068, 0, 0.7071068]}, {\"mesh\": 0, \"scale\": [2, 2, 2]}, {\"translation\": [0, 3, 0], \"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}, \"children\": [3]}, {\"extensions\": {\"KHR_lights_punctual\": {\"light\": 1}}}]",
        );
    vec![
        ("external-buffer.gltf", triangle.clone().into_bytes()),
        (
            "subfolder-buffer.gltf",
            triangle.replace("tri.bin", "sub/tri.bin").into_bytes(),
        ),
        ("triangle.glb", glb(&glb_json, &bin)),
        ("sparse.gltf", sparse.into_bytes()),
        ("strip.gltf", strip.into_bytes()),
        ("fan.gltf", fan.into_bytes()),
        ("tree-lights.gltf", tree.into_bytes()),
    ]
}

/// Hand-written scene seeds: every section, every light kind, a glTF
/// object, and `--set` overrides after the separator.
fn handwritten_scene_seeds() -> Vec<(&'static str, String)> {
    let lights = r#"[image]
width = 64
height = 48

[[objects]]
gltf = "tri.gltf"

[[objects]]
shape = "plane"
size = 4.0
segments = 2
material = "m"

[materials.m]
model = "lambert"
k_d = 0.5

[[lights]]
kind = "point"
position = [0.0, 2.0, 2.0]
intensity = 5.0
range = 10.0
shadows = true

[[lights]]
kind = "directional"
direction = [0.0, -1.0, 0.0]
irradiance = [1.0, 1.0, 1.0]

[[lights]]
kind = "spot"
position = [0.0, 3.0, 0.0]
direction = [0.0, -1.0, 0.0]
intensity = 2.0
inner_cone_deg = 10.0
outer_cone_deg = 30.0

[ambient]
radiance = 0.1
"#;
    let overrides = format!(
        "[[objects]]\nshape = \"sphere\"\nsegments = 8\n{}image.width=32\nlights.0.intensity=[1, 2, 3]\nshading.mode=flat\n",
        harness::OVERRIDES_SEPARATOR
    );
    vec![
        ("lights-and-gltf.toml", lights.to_string()),
        ("overrides.toml", overrides),
        ("subfolder-gltf.toml", "[[objects]]\ngltf = \"sub/tri.gltf\"\n".to_string()),
        ("camera.toml", "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\nfov_y_deg = 45.0\n\n[[objects]]\nshape = \"sphere\"\nsegments = 6\n".to_string()),
    ]
}

/// Texture seeds: the project's PNGs, and small encoded images of each
/// kind the decoder has a path for (JPEG, 16-bit, grey with alpha), with
/// hostile variants (truncated, a header declaring 65535², not an image).
fn texture_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let checker = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/textured/checker.png");
    let checker = std::fs::read(checker).unwrap();
    let encode = |image: image::DynamicImage, format: image::ImageFormat| {
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write_to(&mut bytes, format).unwrap();
        bytes.into_inner()
    };
    let rgb = image::RgbImage::from_fn(8, 8, |x, y| image::Rgb([x as u8 * 30, y as u8 * 30, 128]));
    let jpeg = encode(rgb.into(), image::ImageFormat::Jpeg);
    let deep = image::ImageBuffer::<image::Rgba<u16>, _>::from_fn(4, 4, |x, y| {
        image::Rgba([x as u16 * 9000, y as u16 * 9000, 65535, 40000])
    });
    let deep = encode(deep.into(), image::ImageFormat::Png);
    let grey = image::GrayAlphaImage::from_fn(5, 3, |x, _| image::LumaA([x as u8 * 50, 200]));
    let grey = encode(grey.into(), image::ImageFormat::Png);
    // Width and height sit at bytes 16..24 of a PNG (the IHDR chunk).
    let mut bomb = checker.clone();
    bomb[16..24].copy_from_slice(&[0, 0, 0xff, 0xff, 0, 0, 0xff, 0xff]);
    let truncated = checker[..checker.len() / 2].to_vec();
    vec![
        ("checker.png", checker),
        ("small.jpg", jpeg),
        ("rgba16.png", deep),
        ("grey-alpha.png", grey),
        ("dimension-bomb.png", bomb),
        ("truncated.png", truncated),
        ("not-an-image.txt", b"P6 2 2 255 not a texture".to_vec()),
    ]
}

/// MERL seeds: a small table generated from a smooth function, one with
/// missing (negative) samples, and hostile variants (truncated, a wrong
/// header, a NaN value).
fn merl_seeds() -> Vec<(&'static str, Vec<u8>)> {
    use gonio::material::measured::merl::MerlTable;
    let smooth = MerlTable::sample([4, 3, 6], |h, d, p| {
        gonio::scene::Rgb::new(0.1 + h.cos(), 0.2 + d.cos(), 0.3 + p.sin().abs())
    })
    .encode();
    let mut missing = smooth.clone();
    missing[12..20].copy_from_slice(&(-1.0f64).to_le_bytes());
    let mut nan = smooth.clone();
    nan[20..28].copy_from_slice(&f64::NAN.to_le_bytes());
    let mut header = smooth.clone();
    header[0..4].copy_from_slice(&(-90i32).to_le_bytes());
    vec![
        ("smooth.binary", smooth.clone()),
        ("missing.binary", missing),
        ("nan.binary", nan),
        ("wrong-header.binary", header),
        ("truncated.binary", smooth[..smooth.len() - 5].to_vec()),
    ]
}

/// Environment-map seeds (first byte: even `.hdr`, odd `.exr`): a small
/// map in each format, and hostile variants (truncated, a header declaring
/// a huge map, a square image, a NaN texel, a negative one, a wrong magic).
fn environment_map_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let map = |w: u32, h: u32, texel: fn(u32, u32) -> [f32; 3]| {
        image::Rgb32FImage::from_fn(w, h, |x, y| image::Rgb(texel(x, y)))
    };
    let smooth = |x: u32, y: u32| [x as f32 * 0.25, y as f32 * 0.5, 1.0];
    // Encoded on their own, then prefixed: the OpenEXR writer places its
    // chunk table by absolute position, so writing after the selector
    // byte made every .exr seed unreadable.
    let encode = |image: image::Rgb32FImage, format: image::ImageFormat, selector: u8| {
        let mut bytes = std::io::Cursor::new(Vec::new());
        image::DynamicImage::from(image)
            .write_to(&mut bytes, format)
            .unwrap();
        [vec![selector], bytes.into_inner()].concat()
    };
    let hdr = encode(map(16, 8, smooth), image::ImageFormat::Hdr, 0);
    let exr = encode(map(16, 8, smooth), image::ImageFormat::OpenExr, 1);
    let square = encode(map(8, 8, smooth), image::ImageFormat::OpenExr, 1);
    let nan = encode(
        map(8, 4, |x, _| [if x == 3 { f32::NAN } else { 1.0 }, 0.5, 0.5]),
        image::ImageFormat::OpenExr,
        1,
    );
    let negative = encode(
        map(8, 4, |x, _| [1.0, if x == 5 { -2.0 } else { 0.5 }, 0.5]),
        image::ImageFormat::OpenExr,
        1,
    );
    let bomb = b"\0#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n".to_vec();
    let mut magic = exr.clone();
    magic[1] ^= 0xff;
    vec![
        ("small.hdr", hdr.clone()),
        ("small.exr", exr.clone()),
        ("truncated.hdr", hdr[..hdr.len() / 2].to_vec()),
        ("truncated.exr", exr[..exr.len() / 2].to_vec()),
        ("square.exr", square),
        ("nan-texel.exr", nan),
        ("negative-texel.exr", negative),
        ("dimension-bomb.hdr", bomb),
        ("wrong-magic.exr", magic),
    ]
}

#[test]
#[ignore = "writes the seed corpus; run by hand after changing it"]
fn regenerate_seed_corpus() {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let gltf_dir = corpus_dir("gltf_load");
    let scene_dir = corpus_dir("scene_toml");
    std::fs::create_dir_all(&gltf_dir).unwrap();
    std::fs::create_dir_all(&scene_dir).unwrap();
    for sample in SAMPLES {
        let path = assets.join("gltf").join(sample);
        let text = std::fs::read_to_string(&path).unwrap();
        let embedded = embed_buffers(&text, path.parent().unwrap());
        let name = format!("sample-{}", path.file_name().unwrap().to_string_lossy());
        std::fs::write(gltf_dir.join(name), embedded).unwrap();
    }
    std::fs::copy(
        assets.join("gltf/Box/Box.glb"),
        gltf_dir.join("sample-Box.glb"),
    )
    .unwrap();
    for (name, bytes) in handwritten_gltf_seeds() {
        std::fs::write(gltf_dir.join(name), bytes).unwrap();
    }
    std::fs::copy(
        assets.join("scenes/default.toml"),
        scene_dir.join("default.toml"),
    )
    .unwrap();
    for (name, text) in handwritten_scene_seeds() {
        std::fs::write(scene_dir.join(name), text).unwrap();
    }
    for (target, seeds) in [
        ("texture_decode", texture_seeds()),
        ("merl_parse", merl_seeds()),
        ("environment_map", environment_map_seeds()),
    ] {
        let dir = corpus_dir(target);
        std::fs::create_dir_all(&dir).unwrap();
        for (name, bytes) in seeds {
            std::fs::write(dir.join(name), bytes).unwrap();
        }
    }
}

// ---------------------------------------------------------------------------
// Seeds of the compressed-asset codecs

fn compressed_sample(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/gltf-compressed")
        .join(relative)
}

/// A GLB's JSON and BIN chunk.
fn glb_parts(bytes: &[u8]) -> (serde_json::Value, Vec<u8>) {
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    (json, bytes[20 + json_len + 8..].to_vec())
}

fn view_bytes(bin: &[u8], view: &serde_json::Value) -> Vec<u8> {
    let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    let length = view["byteLength"].as_u64().unwrap() as usize;
    bin[offset..offset + length].to_vec()
}

/// Draco seeds (`harness::draco_mesh`: vertex count, index count, stream):
/// the streams of the sample files with their real counts, and hostile
/// variants (truncated, scrambled, wrong counts).
fn draco_seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    let box_json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(compressed_sample("Box-Draco/Box.gltf")).unwrap())
            .unwrap();
    let box_bin = std::fs::read(compressed_sample("Box-Draco/Box.bin")).unwrap();
    let mut sources = vec![("box", box_json, box_bin)];
    for (name, file) in [
        ("suzanne", "Suzanne-Draco/Suzanne-Draco.glb"),
        (
            "suzanne-sequential",
            "Suzanne-Draco/Suzanne-Draco-Sequential.glb",
        ),
    ] {
        let (json, bin) = glb_parts(&std::fs::read(compressed_sample(file)).unwrap());
        sources.push((name, json, bin));
    }
    for (name, json, bin) in sources {
        let primitive = &json["meshes"][0]["primitives"][0];
        let extension = &primitive["extensions"]["KHR_draco_mesh_compression"];
        let view = &json["bufferViews"][extension["bufferView"].as_u64().unwrap() as usize];
        let stream = view_bytes(&bin, view);
        let count = |accessor: &serde_json::Value| {
            json["accessors"][accessor.as_u64().unwrap() as usize]["count"]
                .as_u64()
                .unwrap() as u32
        };
        let vertices = count(&primitive["attributes"]["POSITION"]);
        let indices = count(&primitive["indices"]);
        let seed = |counts: (u32, u32), stream: &[u8]| {
            [&counts.0.to_le_bytes()[..], &counts.1.to_le_bytes(), stream].concat()
        };
        seeds.push((format!("{name}.draco"), seed((vertices, indices), &stream)));
        seeds.push((
            format!("{name}-truncated.draco"),
            seed((vertices, indices), &stream[..stream.len() / 2]),
        ));
        let mut scrambled = stream.clone();
        let n = scrambled.len();
        for b in &mut scrambled[n / 3..n / 2] {
            *b = b.wrapping_mul(31).wrapping_add(7);
        }
        seeds.push((
            format!("{name}-scrambled.draco"),
            seed((vertices, indices), &scrambled),
        ));
        seeds.push((
            format!("{name}-wrong-counts.draco"),
            seed((vertices + 1, 3), &stream),
        ));
    }
    seeds
}

/// Meshopt seeds (`harness::meshopt_buffer`: extension, mode, filter,
/// stride, count, bytes): one view of each kind the sample files hold,
/// and hostile variants (truncated, zeroed).
fn meshopt_seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for (khr, file) in [
        (
            0u8,
            "MetalRoughSpheres-Meshopt/MetalRoughSpheres-EXT-Meshopt.glb",
        ),
        (
            1u8,
            "MetalRoughSpheres-Meshopt/MetalRoughSpheres-KHR-Meshopt.glb",
        ),
        (
            1u8,
            "MetalRoughSpheres-Meshopt/MetalRoughSpheres-KHR-Meshopt-Filters.glb",
        ),
    ] {
        let (json, bin) = glb_parts(&std::fs::read(compressed_sample(file)).unwrap());
        for view in json["bufferViews"].as_array().unwrap() {
            let Some(e) = view["extensions"]
                .get("EXT_meshopt_compression")
                .or_else(|| view["extensions"].get("KHR_meshopt_compression"))
            else {
                continue;
            };
            let mode = ["ATTRIBUTES", "TRIANGLES", "INDICES"]
                .iter()
                .position(|m| e["mode"] == *m)
                .unwrap() as u8;
            let filter = ["NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL", "COLOR"]
                .iter()
                .position(|f| e.get("filter").map_or(*f == "NONE", |v| v == *f))
                .unwrap() as u8;
            let stride = e["byteStride"].as_u64().unwrap() as u8;
            if !seen.insert((khr, mode, filter, stride)) {
                continue;
            }
            let count = e["count"].as_u64().unwrap() as u32;
            let data = view_bytes(&bin, e);
            let seed = |data: &[u8]| {
                [&[khr, mode, filter, stride][..], &count.to_le_bytes(), data].concat()
            };
            let name = format!(
                "{}-{}-{}-{stride}",
                if khr == 1 { "khr" } else { "ext" },
                e["mode"].as_str().unwrap().to_lowercase(),
                e.get("filter")
                    .and_then(|f| f.as_str())
                    .unwrap_or("NONE")
                    .to_lowercase()
            );
            seeds.push((format!("{name}.meshopt"), seed(&data)));
            seeds.push((
                format!("{name}-truncated.meshopt"),
                seed(&data[..data.len() / 2]),
            ));
            seeds.push((format!("{name}-zeroed.meshopt"), seed(&vec![0; data.len()])));
        }
    }
    seeds
}

/// KTX2 seeds: the four Basis files (ETC1S and UASTC + Zstandard, made
/// here and from the Khronos samples), and hostile variants (truncated, a
/// header declaring 65535², a scrambled level).
fn ktx2_seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    for file in [
        "BoxTextured-KTX2/CesiumLogoFlat-ETC1S.ktx2",
        "BoxTextured-KTX2/CesiumLogoFlat-UASTC-zstd.ktx2",
        "StainedGlassLamp-KTX2/StainedGlassLamp_hardware_basecolor.ktx2",
        "StainedGlassLamp-KTX2/StainedGlassLamp_bulbs_occlusion-rough-metal.ktx2",
    ] {
        let bytes = std::fs::read(compressed_sample(file)).unwrap();
        let name = Path::new(file)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        seeds.push((format!("{name}.ktx2"), bytes.clone()));
        if name.starts_with("CesiumLogoFlat") {
            seeds.push((
                format!("{name}-truncated.ktx2"),
                bytes[..bytes.len() / 2].to_vec(),
            ));
            // pixelWidth and pixelHeight at bytes 20..28 of the header.
            let mut bomb = bytes.clone();
            bomb[20..28].copy_from_slice(&[0xff, 0xff, 0, 0, 0xff, 0xff, 0, 0]);
            seeds.push((format!("{name}-dimension-bomb.ktx2"), bomb));
            let mut scrambled = bytes.clone();
            let n = scrambled.len();
            for b in &mut scrambled[n / 2..] {
                *b = b.wrapping_mul(17);
            }
            seeds.push((format!("{name}-scrambled.ktx2"), scrambled));
        }
    }
    seeds
}

/// WebP seeds: a lossless and a lossy image, and a truncated one.
fn webp_seeds() -> Vec<(String, Vec<u8>)> {
    let lossless = std::fs::read(compressed_sample(
        "BoxTextured-WebP/CesiumLogoFlat-lossless.webp",
    ))
    .unwrap();
    let lossy = std::fs::read(compressed_sample(
        "BoxTextured-WebP/CesiumLogoFlat-lossy.webp",
    ))
    .unwrap();
    vec![
        ("lossless.webp".to_string(), lossless.clone()),
        ("lossy.webp".to_string(), lossy.clone()),
        (
            "lossless-truncated.webp".to_string(),
            lossless[..lossless.len() / 2].to_vec(),
        ),
        (
            "lossy-truncated.webp".to_string(),
            lossy[..lossy.len() / 2].to_vec(),
        ),
    ]
}

/// The valid codec seeds must decode through their harness's path: a seed
/// that fails early would fuzz only the first checks.
#[test]
fn codec_seeds_decode() {
    use gonio::scene::texture::{Encoding, decode};
    for (name, bytes) in ktx2_seeds().into_iter().chain(webp_seeds()) {
        if name.contains("truncated") || name.contains("bomb") || name.contains("scrambled") {
            continue;
        }
        decode::decode(&bytes, Encoding::Srgb, 64 << 20).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
#[ignore = "writes the codec seed corpus; run by hand after changing it"]
fn regenerate_codec_seed_corpus() {
    for (target, seeds) in [
        ("draco_mesh", draco_seeds()),
        ("meshopt_buffer", meshopt_seeds()),
        ("ktx2_texture", ktx2_seeds()),
        ("webp_texture", webp_seeds()),
    ] {
        let dir = corpus_dir(target);
        std::fs::create_dir_all(&dir).unwrap();
        for (name, bytes) in seeds {
            std::fs::write(dir.join(name), bytes).unwrap();
        }
    }
}
