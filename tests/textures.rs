//! Textures (the contract's `PARAM_texture` keys): the GPU against the f64
//! reference on textured scenes, texel colours where they must be, and
//! bad images refused cleanly.
//!
//! Tolerance of the GPU-vs-reference comparison: both renderers read the
//! same f16 texels (`scene::texture::Image`), so a magnified texture
//! differs only by the filter's arithmetic: lavapipe blends the four
//! texels in f32 with weights from the f32 UV (an error in the UV of
//! |uv|·2⁻²⁴ moves the weights by size·|uv|·2⁻²⁴, below 2⁻¹⁴ for these
//! 64-texel images, times the largest texel step (1): ~6·10⁻⁵ relative),
//! which the geometric part of the derived tolerance (the reference
//! re-rendered at ±1/128 px, `common::tolerance`) already exceeds where
//! the texture changes, since a texel step spans several pixels here. The
//! arithmetic part is unchanged.
//!
//! Minified textures: the level of detail λ = log₂ ρ is where the two
//! renderers may legitimately differ. Vulkan lets an implementation
//! approximate each of ρ_x = |∂uv/∂x|, ρ_y by any f with
//! max(|∂u/∂x|, |∂v/∂x|) ≤ f ≤ |∂u/∂x| + |∂v/∂x| (the specification's
//! "Scale Factor Operation"), i.e. within a factor √2 either way of the
//! Euclidean length the reference uses: |Δλ| ≤ log₂ √2 = ½. The reference
//! is therefore rendered twice more with λ moved by ±½
//! (`reference::render_with_lod_bias`), and each pixel's tolerance gains
//! that spread, as it gains the jitter's (`compare_with_spreads`). It is
//! zero where the texture is magnified (λ ≤ −½ stays level 0) and where
//! the levels agree, and as large as the mip levels differ elsewhere.

mod common;

use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Scene, ShadingMode};
use std::path::{Path, PathBuf};

fn textured_scene() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/textured/textured.toml")
}

/// A glTF without lights is loaded under the directional default light,
/// not the studio: both renderers evaluate it exactly.
fn load(path: &Path, sets: &[&str]) -> Scene {
    let mut sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    sets.insert(0, "gltf.default_light=\"directional\"".into());
    scene_file::load(&SceneSource::File(path.to_path_buf()), &sets).expect("scene loads")
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

fn gpu_vs_reference(label: &str, scene: &Scene) {
    gpu_vs_reference_covering(label, scene, 10);
}

/// [`gpu_vs_reference`] asserting that at least 1/`fraction` of the
/// pixels were compared.
fn gpu_vs_reference_covering(label: &str, scene: &Scene, fraction: usize) {
    let frame = gpu(scene);
    let (center, jittered) = common::reference_with_jitter(scene);
    let c = common::compare_to_reference(scene, &frame, &center, &jittered);
    eprintln!("{label:<32} {}", c.summary());
    assert!(c.compared > (scene.width * scene.height) as usize / fraction);
    common::assert_agrees(label, "GPU and reference disagree", &c, &frame, &center);
}

#[test]
fn textured_scene_gpu_matches_reference_in_every_mode() {
    for mode in ShadingMode::ALL {
        let scene = load(&textured_scene(), &[&format!("shading.mode=\"{mode}\"")]);
        assert!(scene.has_textures());
        gpu_vs_reference(&format!("textured, {mode}"), &scene);
    }
}

/// The sRGB checker seen from above under a vertical sun, magnified: away
/// from the squares' edges every pixel is `k_d · texel / π · E` with the
/// texel's sRGB value decoded exactly (f16 keeps 2⁻¹¹ of it).
#[test]
fn magnified_checker_has_its_decoded_colours_where_the_squares_are() {
    let scene = load(
        &textured_scene(),
        &[
            "camera={position = [0.0, 9.0, 0.0], target = [0.0, 0.0, 0.0], up = [0.0, 0.0, -1.0], fov_y_deg = 40.0}",
            "lights=[{kind = \"directional\", direction = [0.0, -1.0, 0.0], irradiance = [3.0, 3.0, 3.0]}]",
            "ambient.radiance=[0.0, 0.0, 0.0]",
            "objects=[{shape = \"plane\", center = [0.0, 0.0, 0.0], size = 8.0, segments = 4, material = \"floor\"}]",
        ],
    );
    let srgb = |v: f64| ((v / 255.0 + 0.055) / 1.055).powf(2.4);
    let cream = [230.0, 220.0, 190.0].map(srgb);
    let red = [140.0, 30.0, 20.0].map(srgb);
    let frames = [
        ("GPU", gpu(&scene)),
        ("reference", gonio::reference::render(&scene)),
    ];
    let (w, h) = (scene.width, scene.height);
    let mut checked = 0;
    for i in (0..h).step_by(7) {
        for j in (0..w).step_by(7) {
            let ray = scene.camera.ray(j as f64 + 0.5, i as f64 + 0.5, w, h);
            let t = -ray.origin.y / ray.direction.y;
            let p = ray.origin + t * ray.direction;
            // UV = (x/8 + ½, z/8 + ½); texel = 64·UV; squares of 8 texels.
            let texel = [(p.x / 8.0 + 0.5) * 64.0, (p.z / 8.0 + 0.5) * 64.0];
            if texel
                .iter()
                .any(|&t| !(1.5..62.5).contains(&t) || (t % 8.0 - 4.0).abs() > 2.5)
            {
                continue;
            }
            let square = texel.map(|t| (t / 8.0) as i64);
            let colour = if (square[0] + square[1]) % 2 == 0 {
                cream
            } else {
                red
            };
            for (name, frame) in &frames {
                let got = frame.radiance[frame.index(i, j)];
                for c in 0..3 {
                    let want = 0.8 * colour[c] / std::f64::consts::PI * 3.0;
                    let err = (got[c] as f64 - want).abs();
                    assert!(
                        err <= 2e-3 * want,
                        "{name} pixel ({i}, {j}), square {square:?}, channel {c}: {} vs {want}",
                        got[c]
                    );
                }
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} pixels checked");
}

// ---------------------------------------------------------------------
// Bad images: exit 2, one paragraph naming the scene key and the image,
// no output file.

fn bad_image_case(dir: &Path, image: &[u8], extra: &[&str], names: &[&str]) {
    let scene_dir = dir.join("scene");
    std::fs::create_dir_all(&scene_dir).unwrap();
    let text = std::fs::read_to_string(textured_scene())
        .unwrap()
        .replace("\"checker.png\"", "\"bad.png\"");
    std::fs::write(scene_dir.join("t.toml"), text).unwrap();
    std::fs::copy(
        textured_scene().with_file_name("ramp.png"),
        scene_dir.join("ramp.png"),
    )
    .unwrap();
    if !image.is_empty() {
        std::fs::write(scene_dir.join("bad.png"), image).unwrap();
    }
    let out = dir.join("out.png");
    let result = common::gonio()
        .arg("render")
        .arg(scene_dir.join("t.toml"))
        .arg("-o")
        .arg(&out)
        .args(extra)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("gonio: error:"))
        .collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    for n in names {
        assert!(errors[0].contains(n), "`{n}` not named: {}", errors[0]);
    }
    assert!(!out.exists());
}

/// CRC-32 (ISO 3309, as PNG chunks use), bitwise.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

fn tiny_png() -> Vec<u8> {
    std::fs::read(textured_scene().with_file_name("checker.png")).unwrap()
}

#[test]
fn a_missing_image_is_named() {
    let dir = tempfile::tempdir().unwrap();
    bad_image_case(dir.path(), &[], &[], &["k_d_texture", "bad.png", "t.toml"]);
}

#[test]
fn a_corrupt_png_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let mut png = tiny_png();
    let n = png.len();
    png[n / 2..].iter_mut().for_each(|b| *b = 0x55);
    bad_image_case(dir.path(), &png, &[], &["bad.png", "corrupt"]);
}

#[test]
fn a_corrupt_jpeg_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let jpeg = [
        0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10, b'J', b'F', b'I', b'F', 0, 1, 2, 3,
    ];
    bad_image_case(dir.path(), &jpeg, &[], &["bad.png"]);
}

/// A PNG whose header declares 65535 × 65535 texels in a few hundred
/// bytes: refused from the header, before decoding.
#[test]
fn a_huge_declared_png_is_refused_before_decoding() {
    let dir = tempfile::tempdir().unwrap();
    let mut png = tiny_png();
    png[16..20].copy_from_slice(&65535u32.to_be_bytes());
    png[20..24].copy_from_slice(&65535u32.to_be_bytes());
    // A valid header: IHDR's CRC over its type and data (bytes 12..29).
    let crc = crc32(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
    assert!(png.len() < 1024);
    bad_image_case(dir.path(), &png, &[], &["bad.png", "65535×65535"]);
}

/// Decoded bytes count against `--limit bytes`.
#[test]
fn decoded_bytes_count_against_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    bad_image_case(
        dir.path(),
        &tiny_png(),
        &["--limit", "bytes=100k"],
        &["bad.png", "--limit bytes="],
    );
}

// ---------------------------------------------------------------------
// glTF textures.

fn gltf_scene(relative: &str) -> Scene {
    let sets = ["image.width=200", "image.height=150"];
    load(&common::gltf_asset(relative), &sets)
}

/// BoxTextured (Khronos, the glTF-Embedded variant): its base colour
/// texture reaches both renderers, and they agree.
#[test]
fn box_textured_gpu_matches_reference() {
    let scene = gltf_scene("BoxTextured/BoxTextured.gltf");
    assert!(scene.has_textures());
    gpu_vs_reference("BoxTextured", &scene);
    // The texture shows: the front face has both the image's blue and
    // its green (an untextured box is one grey).
    let frame = gpu(&scene);
    let (mut blue, mut green) = (0, 0);
    for k in 0..frame.len() {
        let [r, g, b] = frame.radiance[k];
        if frame.coverage[k] && b > 1.3 * r && b > 1.1 * g {
            blue += 1;
        }
        if frame.coverage[k] && g > 1.3 * r && g > 1.3 * b {
            green += 1;
        }
    }
    assert!(blue > 200 && green > 200, "blue {blue}, green {green}");
}

/// Suzanne's base colour texture, GPU against the reference.
#[test]
fn suzanne_textured_gpu_matches_reference() {
    let scene = gltf_scene("Suzanne/Suzanne.gltf");
    assert!(scene.has_textures());
    gpu_vs_reference("Suzanne textured", &scene);
}

// ---------------------------------------------------------------------
// Bad glTF images: the same one paragraph, naming the glTF and the image.

/// A one-triangle glTF with a base colour texture whose image is
/// `image` (a JSON object), and a buffer of `extra` bytes after the
/// triangle's 60 (positions, then UVs).
fn gltf_with_image(image: &str, extra: usize) -> String {
    use base64::Engine as _;
    let mut bin: Vec<u8> = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bin.extend(v.to_le_bytes());
    }
    for v in [0.0f32, 1.0, 1.0, 1.0, 0.0, 0.0] {
        bin.extend(v.to_le_bytes());
    }
    bin.extend(std::iter::repeat_n(0u8, extra));
    let data = base64::engine::general_purpose::STANDARD.encode(&bin);
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "material": 0}}]}}],
"materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],
"textures": [{{"source": 0}}], "images": [{image}],
"accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
  {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}}],
"bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 24}},
  {{"buffer": 0, "byteOffset": 60, "byteLength": {extra}}}],
"buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}]}}"#,
        len = bin.len()
    )
}

fn bad_gltf_case(gltf: &str, names: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let model_dir = dir.path().join("model");
    std::fs::create_dir_all(&model_dir).unwrap();
    std::fs::write(dir.path().join("outside.png"), tiny_png()).unwrap();
    let path = model_dir.join("m.gltf");
    std::fs::write(&path, gltf).unwrap();
    let out = dir.path().join("out.png");
    let result = common::gonio()
        .arg("render")
        .arg(&path)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("gonio: error:"))
        .collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    for n in ["m.gltf", "image 0"].iter().chain(names) {
        assert!(errors[0].contains(n), "`{n}` not named: {}", errors[0]);
    }
    assert!(!out.exists());
}

/// A well-formed image loads (the cases below fail for their one reason).
#[test]
fn a_gltf_image_beside_the_model_loads() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.png"), tiny_png()).unwrap();
    let path = dir.path().join("m.gltf");
    std::fs::write(&path, gltf_with_image(r#"{"uri": "t.png"}"#, 0)).unwrap();
    let scene = load(&path, &[]);
    assert!(scene.has_textures());
    assert_eq!(scene.images.len(), 1);
}

#[test]
fn a_gltf_image_outside_its_folder_is_refused() {
    bad_gltf_case(
        &gltf_with_image(r#"{"uri": "../outside.png"}"#, 0),
        &["leaves"],
    );
}

#[test]
fn a_missing_gltf_image_is_named() {
    bad_gltf_case(
        &gltf_with_image(r#"{"uri": "nothere.png"}"#, 0),
        &["nothere.png"],
    );
}

#[test]
fn a_gltf_image_view_past_its_buffer_is_refused() {
    // View 2, the image's, declares 800 bytes at offset 60 of a 68-byte
    // buffer.
    let gltf = gltf_with_image(r#"{"bufferView": 2, "mimeType": "image/png"}"#, 8).replace(
        r#""byteOffset": 60, "byteLength": 8"#,
        r#""byteOffset": 60, "byteLength": 800"#,
    );
    bad_gltf_case(&gltf, &["past the end"]);
}

#[test]
fn a_corrupt_gltf_image_is_named() {
    let gltf = gltf_with_image(r#"{"bufferView": 2, "mimeType": "image/png"}"#, 8);
    bad_gltf_case(&gltf, &["not a PNG, JPEG, WebP or KTX2"]);
}

/// `KHR_texture_transform` is read (offset, rotation, scale, texCoord)
/// and both renderers apply it alike; the rotation's sign is the
/// contract's (`material::texture` tests it on its matrix).
#[test]
fn khr_texture_transform_is_read_and_rendered_alike() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.png"), tiny_png()).unwrap();
    let gltf = gltf_with_image(r#"{"uri": "t.png"}"#, 0)
        .replace(
            r#""baseColorTexture": {"index": 0}"#,
            r#""baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 0.5, "scale": [3.0, 2.0]}}}"#,
        )
        .replace(
            r#"{"asset": {"version": "2.0"},"#,
            r#"{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_texture_transform"],"#,
        );
    let path = dir.path().join("m.gltf");
    std::fs::write(&path, gltf).unwrap();
    let scene = load(&path, &["image.width=160", "image.height=120"]);
    let t = &scene.materials[0].textures[0].transform;
    assert_eq!((t.offset.x, t.offset.y), (0.5, 0.25));
    assert_eq!(t.rotation, 0.5);
    assert_eq!((t.scale.x, t.scale.y), (3.0, 2.0));
    // One triangle covers about a tenth of the frame.
    gpu_vs_reference_covering("KHR_texture_transform", &scene, 20);
}
