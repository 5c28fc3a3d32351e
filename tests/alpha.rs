//! glTF `alphaMode` on quads written here, in both
//! renderers: MASK removes exactly the points whose alpha
//! (`baseColorFactor.a × baseColorTexture.a × COLOR_0.a`) is below the
//! cutoff, so the picture there is the scene without the quad and
//! elsewhere the scene with it opaque; BLEND is the "over" operator,
//! `L = a·L_quad + (1 − a)·L_behind`, the same whatever order the file
//! lists the quads in (the GPU sorts BLEND objects back to front).
//!
//! Equalities between renders of one renderer are exact up to its
//! arithmetic: f32 on the GPU (the blend adds two products, ~10⁻⁶
//! relative), f64 in the reference; 10⁻⁵ relative is allowed. GPU
//! against reference uses the derived render tolerance of `common`.

mod common;

use base64::Engine;
use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Scene, ShadingMode};
use std::path::{Path, PathBuf};

/// One square facing +Z, centred on the axis at depth `z`, `half` wide.
#[derive(Clone)]
struct Quad {
    z: f32,
    half: f32,
    /// glTF `alphaMode` and `alphaCutoff`.
    mode: &'static str,
    cutoff: Option<f32>,
    factor: [f32; 4],
    /// COLOR_0 (FLOAT VEC4) at every corner.
    color: Option<[f32; 4]>,
    /// A 2×1 base colour texture (white, alpha of the left and right
    /// texel, 8-bit), sampled NEAREST: u < ½ reads the left one.
    texture: Option<[u8; 2]>,
}

impl Quad {
    fn new(z: f32, half: f32, mode: &'static str, factor: [f32; 4]) -> Self {
        Quad {
            z,
            half,
            mode,
            cutoff: None,
            factor,
            color: None,
            texture: None,
        }
    }
}

/// A 2×1 RGBA PNG (white; the two alphas) as a data: URI.
fn png_uri(alphas: [u8; 2]) -> String {
    let mut bytes = Vec::new();
    let img = image::RgbaImage::from_raw(
        2,
        1,
        vec![255, 255, 255, alphas[0], 255, 255, 255, alphas[1]],
    )
    .unwrap();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )
    .unwrap();
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    )
}

/// A glTF of `quads`, one node, mesh and material each, in this order.
fn gltf(dir: &Path, name: &str, quads: &[Quad]) -> PathBuf {
    let mut bin: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut meshes, mut materials, mut nodes) =
        (vec![], vec![], vec![], vec![], vec![]);
    let (mut textures, mut images) = (vec![], vec![]);
    let mut view = |bin: &mut Vec<u8>, data: Vec<u8>| {
        let at = bin.len();
        bin.extend(&data);
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{at},"byteLength":{}}}"#,
            data.len()
        ));
        views.len() - 1
    };
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    for (i, q) in quads.iter().enumerate() {
        let h = q.half;
        let positions = [[-h, -h, q.z], [h, -h, q.z], [h, h, q.z], [-h, h, q.z]];
        let p = view(&mut bin, floats(positions.as_flattened()));
        accessors.push(format!(
            r#"{{"bufferView":{p},"componentType":5126,"count":4,"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}}"#,
            -h, -h, q.z, h, h, q.z
        ));
        let pos = accessors.len() - 1;
        let n = view(&mut bin, floats(&[0.0, 0.0, 1.0].repeat(4)));
        accessors.push(format!(
            r#"{{"bufferView":{n},"componentType":5126,"count":4,"type":"VEC3"}}"#
        ));
        let nor = accessors.len() - 1;
        // glTF's v points down: the top-left corner is (0, 0).
        let t = view(&mut bin, floats(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
        accessors.push(format!(
            r#"{{"bufferView":{t},"componentType":5126,"count":4,"type":"VEC2"}}"#
        ));
        let uv = accessors.len() - 1;
        let idx: Vec<u8> = [0u16, 1, 2, 0, 2, 3]
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        let ix = view(&mut bin, idx);
        accessors.push(format!(
            r#"{{"bufferView":{ix},"componentType":5123,"count":6,"type":"SCALAR"}}"#
        ));
        let ind = accessors.len() - 1;
        let color = q.color.map(|c| {
            let v = view(&mut bin, floats(&c.repeat(4)));
            accessors.push(format!(
                r#"{{"bufferView":{v},"componentType":5126,"count":4,"type":"VEC4"}}"#
            ));
            format!(r#","COLOR_0":{}"#, accessors.len() - 1)
        });
        meshes.push(format!(
            r#"{{"primitives":[{{"attributes":{{"POSITION":{pos},"NORMAL":{nor},"TEXCOORD_0":{uv}{}}},"indices":{ind},"material":{i}}}]}}"#,
            color.unwrap_or_default()
        ));
        let texture = q.texture.map(|alphas| {
            images.push(format!(r#"{{"uri":"{}"}}"#, png_uri(alphas)));
            textures.push(format!(r#"{{"source":{},"sampler":0}}"#, images.len() - 1));
            format!(r#","baseColorTexture":{{"index":{}}}"#, textures.len() - 1)
        });
        let [r, g, b, a] = q.factor;
        materials.push(format!(
            r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[{r},{g},{b},{a}],"metallicFactor":0.0,"roughnessFactor":0.6{}}},"alphaMode":"{}"{}}}"#,
            texture.unwrap_or_default(),
            q.mode,
            q.cutoff
                .map(|c| format!(r#","alphaCutoff":{c}"#))
                .unwrap_or_default()
        ));
        nodes.push(format!(r#"{{"mesh":{i}}}"#));
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let list = |v: &[String]| v.join(",");
    let node_ids: Vec<String> = (0..quads.len()).map(|i| i.to_string()).collect();
    let texturing = if images.is_empty() {
        String::new()
    } else {
        format!(
            r#""images":[{}],"textures":[{}],"samplers":[{{"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071}}],"#,
            list(&images),
            list(&textures)
        )
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{}]}}],"nodes":[{}],"meshes":[{}],"materials":[{}],{texturing}"accessors":[{}],"bufferViews":[{}],"buffers":[{{"byteLength":{},"uri":"{uri}"}}]}}"#,
        node_ids.join(","),
        list(&nodes),
        list(&meshes),
        list(&materials),
        list(&accessors),
        list(&views),
        bin.len()
    );
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, json).unwrap();
    path
}

fn load(path: &Path, mode: ShadingMode) -> Scene {
    let sets = [
        format!("shading.mode=\"{mode}\""),
        "image.width=48".into(),
        "image.height=36".into(),
        "camera={position = [0.0, 0.0, 3.0], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 50.0}".into(),
        "lights=[{kind = \"point\", position = [0.5, 1.0, 2.5], intensity = [6.0, 6.0, 6.0]}]".into(),
        "ambient.radiance=[0.05, 0.05, 0.05]".into(),
    ];
    scene_file::load(&SceneSource::File(path.to_path_buf()), &sets).expect("quads load")
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

/// The two renderers' frames of `path` in `mode`.
fn both(path: &Path, mode: ShadingMode) -> [(&'static str, Frame); 2] {
    let scene = load(path, mode);
    [
        ("GPU", gpu(&scene)),
        ("reference", gonio::reference::render(&scene)),
    ]
}

fn close(x: f32, y: f32) -> bool {
    let (x, y) = (x as f64, y as f64);
    (x - y).abs() <= 1e-5 * x.abs().max(y.abs()) + 1e-9
}

fn pixel_eq(a: &Frame, b: &Frame, k: usize) -> bool {
    (0..3).all(|c| close(a.radiance[k][c], b.radiance[k][c]))
}

/// An opaque back quad, dark red, wider than the front ones.
fn back() -> Quad {
    Quad::new(-0.6, 1.4, "OPAQUE", [0.7, 0.1, 0.1, 1.0])
}

/// MASK with a texture whose left texel's alpha (0.2) is below the cutoff
/// 0.5 and whose right one's (0.9) is above: left of the middle the
/// frame is that of the back quad alone, right of it that of the front
/// quad drawn opaque. Per pixel (Phong) in both renderers; every pixel
/// must be one of the two.
#[test]
fn mask_removes_what_is_below_the_cutoff() {
    let dir = tempfile::tempdir().unwrap();
    let mut front = Quad::new(0.0, 0.8, "MASK", [0.2, 0.5, 0.9, 1.0]);
    front.cutoff = Some(0.5);
    front.texture = Some([51, 230]);
    let masked = gltf(dir.path(), "masked", &[front.clone(), back()]);
    let behind = gltf(dir.path(), "behind", &[back()]);
    let opaque = gltf(
        dir.path(),
        "opaque",
        &[
            Quad {
                mode: "OPAQUE",
                cutoff: None,
                ..front
            },
            back(),
        ],
    );
    let mode = ShadingMode::Phong;
    let [m, b, o] = [&masked, &behind, &opaque].map(|p| both(p, mode));
    for i in 0..2 {
        let (name, got) = (&m[i].0, &m[i].1);
        let (behind, opaque) = (&b[i].1, &o[i].1);
        let (mut cut, mut kept) = (0, 0);
        for row in 0..got.height {
            for col in 0..got.width {
                let k = got.index(row, col);
                // Where the front quad is drawn (the opaque render differs
                // from the back alone), left of the middle with a margin.
                let front_here = !pixel_eq(opaque, behind, k);
                if front_here && col < got.width / 2 - 1 {
                    assert!(pixel_eq(got, behind, k), "{name} ({row}, {col}): not cut");
                    cut += 1;
                } else if front_here && col > got.width / 2 {
                    assert!(pixel_eq(got, opaque, k), "{name} ({row}, {col}): not kept");
                    kept += 1;
                } else {
                    assert!(
                        pixel_eq(got, behind, k) || pixel_eq(got, opaque, k),
                        "{name} ({row}, {col}): neither"
                    );
                }
            }
        }
        assert!(cut > 150 && kept > 150, "{name}: {cut} cut, {kept} kept");
    }
}

/// BLEND over an opaque quad, with alpha from the factor (0.4) or from
/// the factor times COLOR_0's alpha (0.8 × 0.5): every pixel is
/// `a·L_opaque + (1 − a)·L_behind`, with the front quad's own
/// `L_opaque` drawn opaque with the same colour, in every shading mode
/// and both renderers. Where nothing lies behind, coverage is `a < ½`:
/// not covered.
#[test]
fn blend_is_the_over_operator() {
    let dir = tempfile::tempdir().unwrap();
    // The front quad wider than the back one: some of it over nothing.
    let mut wide_back = back();
    wide_back.half = 0.7;
    let plain = Quad::new(0.0, 0.9, "BLEND", [0.2, 0.5, 0.9, 0.4]);
    let mut coloured = Quad::new(0.0, 0.9, "BLEND", [0.2, 0.5, 0.9, 0.8]);
    coloured.color = Some([1.0, 1.0, 1.0, 0.5]);
    for (label, front, a) in [("factor", plain, 0.4), ("COLOR_0", coloured, 0.4)] {
        let blended = gltf(
            dir.path(),
            &format!("blend-{label}"),
            &[front.clone(), wide_back.clone()],
        );
        let behind = gltf(dir.path(), "behind", &[wide_back.clone()]);
        let opaque_front = Quad {
            mode: "OPAQUE",
            factor: [0.2, 0.5, 0.9, 1.0],
            color: front.color.map(|_| [1.0; 4]),
            ..front.clone()
        };
        let opaque = gltf(dir.path(), "opaque", &[opaque_front, wide_back.clone()]);
        for mode in ShadingMode::ALL {
            let [g, b, o] = [&blended, &behind, &opaque].map(|p| both(p, mode));
            for i in 0..2 {
                let (name, got) = (&g[i].0, &g[i].1);
                let (behind, opaque) = (&b[i].1, &o[i].1);
                let (mut over, mut alone) = (0, 0);
                for k in 0..got.radiance.len() {
                    if !opaque.coverage[k] {
                        continue;
                    }
                    for c in 0..3 {
                        let want = a * opaque.radiance[k][c] as f64
                            + (1.0 - a) * behind.radiance[k][c] as f64;
                        assert!(
                            close(got.radiance[k][c], want as f32),
                            "{label} {mode} {name} pixel {k} channel {c}: {} vs {want}",
                            got.radiance[k][c]
                        );
                    }
                    assert_eq!(
                        got.coverage[k], behind.coverage[k],
                        "{label} {mode} {name}: coverage {k}"
                    );
                    if behind.coverage[k] {
                        over += 1;
                    } else {
                        alone += 1;
                    }
                }
                assert!(
                    over > 200 && alone > 100,
                    "{label} {mode} {name}: {over} over, {alone} alone"
                );
            }
        }
    }
}

/// BLEND over the environment's background: where the quad covers
/// nothing, the GPU's pixel is `a·L_opaque + (1 − a)·L_background`, the
/// background that of the render without the quad. The background is
/// drawn after the opaque geometry where the depth is still clear; a
/// BLEND surface writes no depth, so drawing it before the background
/// would leave the background alone there.
#[test]
fn blend_is_over_the_environment_background() {
    let dir = tempfile::tempdir().unwrap();
    let front = Quad::new(0.0, 0.9, "BLEND", [0.2, 0.5, 0.9, 0.4]);
    let opaque_front = Quad {
        mode: "OPAQUE",
        factor: [0.2, 0.5, 0.9, 1.0],
        ..front.clone()
    };
    let small_back = Quad::new(-0.6, 0.3, "OPAQUE", [0.7, 0.1, 0.1, 1.0]);
    let under_sky = |path: &Path| {
        let mut sets = vec![
            "image.width=48".to_string(),
            "image.height=36".into(),
            "camera={position = [0.0, 0.0, 3.0], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 50.0}".into(),
            "environment.map=\"sky\"".into(),
        ];
        sets.push("environment.specular=\"none\"".into());
        let scene =
            scene_file::load(&SceneSource::File(path.to_path_buf()), &sets).expect("quads load");
        gpu(&scene)
    };
    let got = under_sky(&gltf(
        dir.path(),
        "blend",
        &[front.clone(), small_back.clone()],
    ));
    let behind = under_sky(&gltf(
        dir.path(),
        "behind",
        std::slice::from_ref(&small_back),
    ));
    let opaque = under_sky(&gltf(dir.path(), "opaque", &[opaque_front, small_back]));
    let a = 0.4;
    let mut over_background = 0;
    for k in 0..got.radiance.len() {
        if !opaque.coverage[k] {
            continue;
        }
        for c in 0..3 {
            let want = a * opaque.radiance[k][c] as f64 + (1.0 - a) * behind.radiance[k][c] as f64;
            assert!(
                close(got.radiance[k][c], want as f32),
                "pixel {k} channel {c}: {} vs {want} (background {})",
                got.radiance[k][c],
                behind.radiance[k][c]
            );
        }
        over_background += usize::from(!behind.coverage[k]);
    }
    assert!(
        over_background > 300,
        "{over_background} pixels over the background"
    );
}

/// Two BLEND quads listed near first (drawn in file order they would
/// hide each other wrongly) over an opaque one: the GPU's back-to-front
/// order gives the reference's front-to-back composite, within the
/// derived tolerance, in every mode; and the middle pixel is
/// `a₁L₁ + (1 − a₁)(a₂L₂ + (1 − a₂)L_back)` computed from single renders.
#[test]
fn blended_objects_are_sorted_back_to_front() {
    let dir = tempfile::tempdir().unwrap();
    let near = Quad::new(0.3, 0.5, "BLEND", [0.1, 0.8, 0.2, 0.5]);
    let far = Quad::new(-0.2, 0.7, "BLEND", [0.1, 0.2, 0.9, 0.6]);
    let path = gltf(dir.path(), "stack", &[near.clone(), far.clone(), back()]);
    for mode in ShadingMode::ALL {
        let scene = load(&path, mode);
        let frame = gpu(&scene);
        let (center, jittered) = common::reference_with_jitter(&scene);
        let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
        eprintln!("stack, {mode}: {}", c.summary());
        assert!(c.compared > (scene.width * scene.height) as usize / 3);
        common::assert_agrees(
            &format!("alpha stack {mode}"),
            "GPU and reference disagree",
            &c,
            &frame,
            &center,
        );
    }
    // The middle pixel from renders of each quad alone, opaque.
    let opaque = |q: &Quad, name: &str| {
        let q = Quad {
            mode: "OPAQUE",
            factor: [q.factor[0], q.factor[1], q.factor[2], 1.0],
            ..q.clone()
        };
        let scene = load(&gltf(dir.path(), name, &[q]), ShadingMode::Phong);
        let f = gonio::reference::render(&scene);
        let k = f.index(f.height / 2, f.width / 2);
        f.radiance[k].map(f64::from)
    };
    let (l1, l2, lb) = (opaque(&near, "n"), opaque(&far, "f"), opaque(&back(), "b"));
    let scene = load(&path, ShadingMode::Phong);
    for (name, f) in [
        ("GPU", gpu(&scene)),
        ("reference", gonio::reference::render(&scene)),
    ] {
        let k = f.index(f.height / 2, f.width / 2);
        for c in 0..3 {
            let want = 0.5 * l1[c] + 0.5 * (0.6 * l2[c] + 0.4 * lb[c]);
            assert!(
                close(f.radiance[k][c], want as f32),
                "{name} channel {c}: {} vs {want}",
                f.radiance[k][c]
            );
        }
    }
}

/// GPU against reference, derived tolerance: a textured MASK quad (its
/// edge where the texture's alpha crosses the cutoff) and a vertex-
/// coloured BLEND one over an opaque quad, in every shading mode.
#[test]
fn alpha_gpu_matches_reference() {
    let dir = tempfile::tempdir().unwrap();
    let mut mask = Quad::new(0.2, 0.5, "MASK", [0.9, 0.6, 0.2, 1.0]);
    mask.cutoff = Some(0.5);
    mask.texture = Some([40, 250]);
    let mut blend = Quad::new(0.0, 0.8, "BLEND", [0.3, 0.4, 0.9, 0.9]);
    blend.color = Some([1.0, 0.8, 0.6, 0.7]);
    let path = gltf(dir.path(), "mixed", &[mask, blend, back()]);
    for mode in ShadingMode::ALL {
        let scene = load(&path, mode);
        let frame = gpu(&scene);
        let (center, jittered) = common::reference_with_jitter(&scene);
        let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
        eprintln!("mixed, {mode}: {}", c.summary());
        assert!(c.compared > (scene.width * scene.height) as usize / 3);
        common::assert_agrees(
            &format!("alpha mixed {mode}"),
            "GPU and reference disagree",
            &c,
            &frame,
            &center,
        );
    }
}

/// The import: MASK without `alphaCutoff` takes glTF's default 0.5, BLEND
/// and OPAQUE read as such with the factor's alpha; a negative cutoff is
/// an error naming it.
#[test]
fn alpha_modes_import_with_gltf_defaults() {
    use gonio::material::AlphaMode;
    let dir = tempfile::tempdir().unwrap();
    let path = gltf(
        dir.path(),
        "modes",
        &[
            Quad::new(0.0, 0.5, "MASK", [1.0, 1.0, 1.0, 0.3]),
            Quad::new(-0.2, 0.5, "BLEND", [1.0, 1.0, 1.0, 0.6]),
            Quad::new(-0.4, 0.5, "OPAQUE", [1.0, 1.0, 1.0, 0.1]),
        ],
    );
    let scene = load(&path, ShadingMode::Phong);
    let modes: Vec<_> = scene
        .materials
        .iter()
        .map(|m| (m.alpha_mode, m.alpha))
        .collect();
    assert_eq!(
        modes,
        [
            (AlphaMode::Mask { cutoff: 0.5 }, 0.30000001192092896),
            (AlphaMode::Blend, 0.6000000238418579),
            (AlphaMode::Opaque, 0.10000000149011612),
        ]
    );
    let mut bad = Quad::new(0.0, 0.5, "MASK", [1.0; 4]);
    bad.cutoff = Some(-0.5);
    let path = gltf(dir.path(), "bad", &[bad]);
    let err = scene_file::load(&SceneSource::File(path), &[]).unwrap_err();
    assert!(
        err.to_string().contains("alphaCutoff"),
        "the error names alphaCutoff: {err}"
    );
}
