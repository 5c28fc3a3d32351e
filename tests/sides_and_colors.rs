//! glTF `doubleSided` and `COLOR_0`, on a quad written here: a
//! single-sided quad seen from behind is culled by both renderers; a
//! double-sided one seen from behind renders as the same quad facing the
//! camera (its frame flipped); `COLOR_0` (FLOAT VEC4, normalized UBYTE
//! VEC3 and USHORT VEC4) renders as the same colour given as
//! `baseColorFactor`. Each in every shading mode, GPU and reference.
//!
//! Equalities are exact up to f32 on the GPU (the two scenes differ only
//! in how the same numbers reach the shader: ~10⁻⁶ relative) and f64 in
//! the reference; 10⁻⁵ relative is allowed.

mod common;

use base64::Engine;
use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Scene, ShadingMode};
use std::path::Path;

/// How the quad's vertex colours are stored.
#[derive(Clone, Copy)]
enum Colors {
    None,
    FloatVec4([f32; 4]),
    UbyteVec3([u8; 3]),
    UshortVec4([u16; 4]),
}

/// A glTF of one 2×2 quad in z = 0, facing +Z (or −Z if `reversed`:
/// the other winding and normals), with the given material and colours.
fn quad_gltf(
    dir: &Path,
    reversed: bool,
    double_sided: bool,
    factor: [f64; 3],
    colors: Colors,
) -> std::path::PathBuf {
    let p = [
        [-1.0f32, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let nz = if reversed { -1.0f32 } else { 1.0 };
    let idx: [u16; 6] = if reversed {
        [0, 2, 1, 0, 3, 2]
    } else {
        [0, 1, 2, 0, 2, 3]
    };
    let mut bin = Vec::new();
    for v in p {
        for c in v {
            bin.extend(c.to_le_bytes());
        }
    }
    for _ in 0..4 {
        for c in [0.0f32, 0.0, nz] {
            bin.extend(c.to_le_bytes());
        }
    }
    for i in idx {
        bin.extend(i.to_le_bytes());
    }
    let color_offset = bin.len();
    let (color_accessor, color_len) = match colors {
        Colors::None => (None, 0),
        Colors::FloatVec4(c) => {
            for _ in 0..4 {
                for x in c {
                    bin.extend(x.to_le_bytes());
                }
            }
            (Some(("VEC4", 5126)), 64)
        }
        Colors::UbyteVec3(c) => {
            // Each element padded to 4 bytes (glTF's vertex alignment).
            for _ in 0..4 {
                bin.extend(c);
                bin.push(0);
            }
            (Some(("VEC3", 5121)), 16)
        }
        Colors::UshortVec4(c) => {
            for _ in 0..4 {
                for x in c {
                    bin.extend(x.to_le_bytes());
                }
            }
            (Some(("VEC4", 5123)), 32)
        }
    };
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let (color_attr, color_json) = match color_accessor {
        None => (String::new(), String::new()),
        Some((ty, component)) => {
            let stride = if matches!(colors, Colors::UbyteVec3(_)) {
                ",\"byteStride\":4"
            } else {
                ""
            };
            (
                ",\"COLOR_0\":3".to_string(),
                format!(
                    ",{{\"bufferView\":3,\"componentType\":{component},\"normalized\":{},\"count\":4,\"type\":\"{ty}\"}}",
                    component != 5126
                ) + &format!(
                    "|{{\"buffer\":0,\"byteOffset\":{color_offset},\"byteLength\":{color_len}{stride}}}"
                ),
            )
        }
    };
    let (color_acc, color_view) = match color_json.split_once('|') {
        Some((a, v)) => (a.to_string(), format!(",{v}")),
        None => (String::new(), String::new()),
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1{color_attr}}},"indices":2,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[{},{},{},1.0],"metallicFactor":0.0,"roughnessFactor":0.5}},"doubleSided":{double_sided}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"}},
{{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}{color_acc}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":48}},{{"buffer":0,"byteOffset":96,"byteLength":12}}{color_view}],
"buffers":[{{"byteLength":{},"uri":"{uri}"}}]}}"#,
        factor[0],
        factor[1],
        factor[2],
        bin.len()
    );
    let name = format!(
        "quad-{}-{}-{}.gltf",
        reversed,
        double_sided,
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    );
    let path = dir.join(name);
    std::fs::write(&path, json).unwrap();
    path
}

fn load(path: &Path, mode: ShadingMode) -> Scene {
    let sets = [
        format!("shading.mode=\"{mode}\""),
        "image.width=48".into(),
        "image.height=36".into(),
        "camera={position = [0.3, 0.2, 2.2], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 60.0}".into(),
        "lights=[{kind = \"point\", position = [1.0, 1.5, 2.0], intensity = [4.0, 4.0, 4.0]}]".into(),
        "ambient.radiance=[0.05, 0.05, 0.05]".into(),
    ];
    scene_file::load(&SceneSource::File(path.to_path_buf()), &sets).expect("quad loads")
}

fn both(scene: &Scene) -> [(&'static str, Frame); 2] {
    [
        (
            "GPU",
            common::gpu_renderer().render(scene).expect("GPU render").0,
        ),
        ("reference", gonio::reference::render(scene)),
    ]
}

/// Every pixel equal within 10⁻⁵ relative (coverage too); at least a
/// quarter of the image covered.
fn assert_same(label: &str, a: &Frame, b: &Frame) {
    assert_eq!(a.coverage, b.coverage, "{label}: coverage");
    let covered = a.coverage.iter().filter(|&&c| c).count();
    assert!(
        covered > a.coverage.len() / 4,
        "{label}: {covered} pixels covered"
    );
    for (k, (x, y)) in a.radiance.iter().zip(&b.radiance).enumerate() {
        for c in 0..3 {
            let (x, y) = (x[c] as f64, y[c] as f64);
            assert!(
                (x - y).abs() <= 1e-5 * x.abs().max(y.abs()) + 1e-9,
                "{label}: pixel {k} channel {c}: {x} vs {y}"
            );
        }
    }
}

#[test]
fn single_sided_back_faces_are_culled_and_double_sided_ones_flip() {
    let dir = tempfile::tempdir().unwrap();
    let b = [0.6, 0.5, 0.4];
    let front = quad_gltf(dir.path(), false, false, b, Colors::None);
    let back_single = quad_gltf(dir.path(), true, false, b, Colors::None);
    let back_double = quad_gltf(dir.path(), true, true, b, Colors::None);
    for mode in ShadingMode::ALL {
        let want = both(&load(&front, mode));
        for (name, f) in both(&load(&back_single, mode)) {
            assert!(
                f.coverage.iter().all(|&c| !c),
                "{mode} {name}: a single-sided back face drew"
            );
        }
        for ((name, got), (_, want)) in both(&load(&back_double, mode)).iter().zip(&want) {
            assert_same(
                &format!("{mode} {name}: double-sided back vs front"),
                got,
                want,
            );
        }
    }
}

#[test]
fn vertex_colors_multiply_the_base_colour_in_every_component_type() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (Colors::FloatVec4([0.5, 0.25, 1.0, 1.0]), [0.5, 0.25, 1.0]),
        (
            Colors::UbyteVec3([128, 64, 255]),
            [128.0 / 255.0, 64.0 / 255.0, 1.0],
        ),
        (
            Colors::UshortVec4([32768, 16384, 65535, 65535]),
            [32768.0 / 65535.0, 16384.0 / 65535.0, 1.0],
        ),
    ];
    for (colors, c) in cases {
        let coloured = quad_gltf(dir.path(), false, false, [1.0; 3], colors);
        let factored = quad_gltf(dir.path(), false, false, c, Colors::None);
        for mode in ShadingMode::ALL {
            for ((name, got), (_, want)) in both(&load(&coloured, mode))
                .iter()
                .zip(&both(&load(&factored, mode)))
            {
                assert_same(
                    &format!("{mode} {name}: COLOR_0 vs factor {c:?}"),
                    got,
                    want,
                );
            }
        }
    }
}

/// The GPU against the reference (the derived render tolerance of
/// `common`) on a double-sided quad seen from behind with vertex colours
/// (normalized UBYTE VEC3).
#[test]
fn double_sided_vertex_coloured_quad_gpu_matches_reference() {
    let dir = tempfile::tempdir().unwrap();
    let path = quad_gltf(
        dir.path(),
        true,
        true,
        [0.9, 0.8, 0.7],
        Colors::UbyteVec3([200, 90, 30]),
    );
    for mode in ShadingMode::ALL {
        let scene = load(&path, mode);
        let frame = common::gpu_renderer().render(&scene).expect("GPU render").0;
        let (center, jittered) = common::reference_with_jitter(&scene);
        let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
        eprintln!("quad, {mode}: {}", c.summary());
        assert!(c.compared > (scene.width * scene.height) as usize / 6);
        common::assert_agrees(
            &format!("quad {mode}"),
            "GPU and reference disagree",
            &c,
            &frame,
            &center,
        );
    }
}
