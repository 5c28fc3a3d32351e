//! `KHR_texture_transform` on the normal and occlusion textures,
//! on a quad written here: a 2×1 map (NEAREST, CLAMP) whose left
//! texel differs from its right one, read through `offset = [0.5, 0]`,
//! reads the right texel everywhere (u' = u + ½ ≥ ½, clamped), so it must
//! render exactly as the same quad with a map whose two texels are both
//! the right one and no transform. Ignoring the transform would show the
//! left texel on the left half. Both renderers; the two scenes differ only
//! in where the same texel comes from, so the frames agree to the
//! renderer's rounding (10⁻⁵ relative allowed). A rotation also turns a
//! normal map's normals (`a_rotated_normal_map_turns_its_normals_with_it`).

mod common;

use base64::Engine;
use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::{Path, PathBuf};

/// A 2×1 RGB PNG as a data: URI.
fn png_uri(left: [u8; 3], right: [u8; 3]) -> String {
    let mut bytes = Vec::new();
    let pixels = [left, right].concat();
    image::RgbImage::from_raw(2, 1, pixels)
        .unwrap()
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    )
}

/// A 2×2 quad in z = 0 facing +Z whose material has `slot`
/// (`normalTexture` or `occlusionTexture`) on the map `left | right`,
/// read through `offset = [0.5, 0]` if `transformed`.
fn quad(dir: &Path, name: &str, slot: &str, texels: [[u8; 3]; 2], transformed: bool) -> PathBuf {
    let transform = if transformed {
        r#"{"offset":[0.5,0.0]}"#
    } else {
        ""
    };
    quad_with(dir, name, slot, texels, transform)
}

/// [`quad`] with the `KHR_texture_transform` object `transform` (JSON;
/// empty: none).
fn quad_with(dir: &Path, name: &str, slot: &str, texels: [[u8; 3]; 2], transform: &str) -> PathBuf {
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut bin = floats(&[
        -1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0,
    ]);
    bin.extend(floats(&[0.0, 0.0, 1.0].repeat(4)));
    bin.extend(floats(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
    bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    let extension = if transform.is_empty() {
        String::new()
    } else {
        format!(r#","extensions":{{"KHR_texture_transform":{transform}}}"#)
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_texture_transform"],"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.7,0.6,1.0],"metallicFactor":0.0,"roughnessFactor":0.5}},"{slot}":{{"index":0{extension}}}}}],
"images":[{{"uri":"{}"}}],"samplers":[{{"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071}}],"textures":[{{"source":0,"sampler":0}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"}},{{"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"}},{{"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":48}},{{"buffer":0,"byteOffset":96,"byteLength":32}},{{"buffer":0,"byteOffset":128,"byteLength":12}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}}"#,
        png_uri(texels[0], texels[1]),
        bin.len(),
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, json).unwrap();
    path
}

fn scene(path: &Path) -> gonio::scene::Scene {
    let sets = [
        "image.width=40".to_string(),
        "image.height=30".into(),
        "camera={position = [0.2, 0.1, 3.0], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 50.0}".into(),
        "lights=[{kind = \"point\", position = [-1.5, 1.0, 1.5], intensity = [5.0, 5.0, 5.0]}]".into(),
        "ambient.radiance=[0.3, 0.3, 0.3]".into(),
    ];
    scene_file::load(&SceneSource::File(path.to_path_buf()), &sets).expect("quad loads")
}

fn renders(path: &Path) -> [(&'static str, Frame); 2] {
    let scene = scene(path);
    [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ]
}

fn assert_same(label: &str, a: &Frame, b: &Frame) {
    assert_eq!(a.coverage, b.coverage, "{label}: coverage");
    assert!(
        a.coverage.iter().filter(|&&c| c).count() > 400,
        "{label}: covered"
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
fn normal_and_occlusion_maps_follow_their_texture_transform() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("occlusionTexture", [51, 51, 51], [230, 230, 230]),
        ("normalTexture", [220, 128, 180], [128, 150, 240]),
    ];
    for (slot, left, right) in cases {
        let transformed = quad(dir.path(), &format!("{slot}-t"), slot, [left, right], true);
        let plain = quad(
            dir.path(),
            &format!("{slot}-p"),
            slot,
            [right, right],
            false,
        );
        let ignored = quad(dir.path(), &format!("{slot}-i"), slot, [left, right], false);
        let (got, want, differs) = (renders(&transformed), renders(&plain), renders(&ignored));
        for i in 0..2 {
            let name = got[i].0;
            assert_same(&format!("{slot} {name}"), &got[i].1, &want[i].1);
            // The map's left texel matters where it is read.
            assert!(
                got[i].1.radiance != differs[i].1.radiance,
                "{slot} {name}: the left texel changes nothing"
            );
        }
    }
}

/// A normal map read through a rotation r turns its normals with it
/// (`material::texture::rotated_normal`): at r = 90° a constant map of
/// texel (255, 0, 255), n = (1, −1, 1)/√3, must render exactly as the
/// unrotated map of its normal turned by hand, R·(1, −1) = (−1, −1):
/// texel (0, 0, 255). Both texels decode exactly, so the two differ only
/// by f32 rounding of cos and sin (10⁻⁵ relative allowed). Ignoring the
/// rotation renders the first map unrotated, which must differ. Then a
/// two-texel map at r = 30° (the transform moves the texels and turns
/// the frame): GPU = reference within the render tolerance.
#[test]
fn a_rotated_normal_map_turns_its_normals_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let quarter = format!(r#"{{"rotation":{}}}"#, std::f64::consts::FRAC_PI_2);
    let rotated = quad_with(
        dir.path(),
        "rot90",
        "normalTexture",
        [[255, 0, 255]; 2],
        &quarter,
    );
    let by_hand = quad_with(dir.path(), "hand", "normalTexture", [[0, 0, 255]; 2], "");
    let unrotated = quad_with(dir.path(), "plain", "normalTexture", [[255, 0, 255]; 2], "");
    let (got, want, ignored) = (renders(&rotated), renders(&by_hand), renders(&unrotated));
    for i in 0..2 {
        let name = got[i].0;
        assert_same(
            &format!("rotated normal map, {name}"),
            &got[i].1,
            &want[i].1,
        );
        assert!(
            got[i].1.radiance != ignored[i].1.radiance,
            "{name}: the rotation turns nothing"
        );
    }
    let thirty = format!(r#"{{"rotation":{}}}"#, 30f64.to_radians());
    let path = quad_with(
        dir.path(),
        "rot30",
        "normalTexture",
        [[220, 128, 180], [128, 150, 240]],
        &thirty,
    );
    let s = scene(&path);
    let frame = common::gpu_renderer().render(&s).unwrap().0;
    let (center, jittered) = common::reference_with_jitter(&s);
    let c = common::compare_to_reference(&s, &frame, &center, &jittered);
    eprintln!("normal map rotated 30°: {}", c.summary());
    common::assert_agrees(
        "normal map rotated 30",
        "GPU and reference disagree",
        &c,
        &frame,
        &center,
    );
}
