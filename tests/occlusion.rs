//! Ambient occlusion under an environment map (glTF's
//! `occlusionTexture` "on the ambient and environment terms only"), on a
//! quad written here: its occlusion map is `R = 0 | R = 255` (NEAREST,
//! CLAMP), read with `strength = s`, so the left half has
//! `o = 1 + s·(0 − 1) = 1 − s` and the right half `o = 1`, both exact in
//! f16 and f32. The quad is lit by a directional light, an ambient
//! radiance and the smooth `assets/environment/blobs.hdr` (the sky's sun
//! would make the derived lookup bounds loose), in the environment's
//! modes that light a gltf-pbr surface (`none`: SH diffuse; `sampled`
//! and `prefiltered`: the whole BRDF, its specular part included).
//!
//! With `L = D + o·N` (`D` the direct light and emission, `N` the ambient
//! and environment light), per pixel and in each renderer:
//! * right half: the frame with `s` equals the frame with `s = 0`;
//! * left half: `s = 1` (o = 0) equals the frame with the map and the
//!   ambient removed (`D` alone: direct light is not occluded), and
//!   `s = ½` is the mean of `s = 0` and `s = 1` (`o·N` is linear in the
//!   strength: glTF's `lerp(color, color·R, strength)`).
//!
//! Both halves must be present. Occlusion on the ambient term alone (as
//! before) fails the second check wherever the environment lights the
//! quad; occlusion on the direct light fails it too. Tolerance of these
//! checks: the frames differ only by factors 0, ½ and 1, which are exact,
//! so only the final sums round: 10⁻⁵ relative.
//!
//! Then the occluded frame (s = ½) on the GPU against the reference
//! (`environment.reference = "sh"`, the GPU's own SH, tables and
//! directions) within the derived render tolerance of tests/environment.rs
//! for each mode (the SH sum's; the prefiltered stack's; the sampled
//! directions' map lookups: each error is scaled by `o ≤ 1`, so the
//! unoccluded bounds hold).

mod common;

use base64::Engine;
use gonio::environment::EnvironmentMap;
use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Rgb, Scene};
use std::path::{Path, PathBuf};

/// A 2×1 RGB PNG as a data: URI.
fn png_uri(left: [u8; 3], right: [u8; 3]) -> String {
    let mut bytes = Vec::new();
    image::RgbImage::from_raw(2, 1, [left, right].concat())
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

/// A 2×2 quad in z = 0 facing +Z, gltf-pbr (metallic 0.3, roughness
/// 0.5), with the occlusion map `0 | 255` at `strength`.
fn quad(dir: &Path, strength: f64) -> PathBuf {
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut bin = floats(&[
        -1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0,
    ]);
    bin.extend(floats(&[0.0, 0.0, 1.0].repeat(4)));
    bin.extend(floats(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
    bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.7,0.6,1.0],"metallicFactor":0.3,"roughnessFactor":0.5}},"occlusionTexture":{{"index":0,"strength":{strength}}}}}],
"images":[{{"uri":"{}"}}],"samplers":[{{"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071}}],"textures":[{{"source":0,"sampler":0}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"}},{{"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"}},{{"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":48}},{{"buffer":0,"byteOffset":96,"byteLength":32}},{{"buffer":0,"byteOffset":128,"byteLength":12}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}}"#,
        png_uri([0, 0, 0], [255, 255, 255]),
        bin.len(),
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let path = dir.join(format!("quad-{strength}.gltf"));
    std::fs::write(&path, json).unwrap();
    path
}

/// The quad at `strength` under the blobs in `specular` mode.
fn scene(dir: &Path, strength: f64, specular: &str) -> Scene {
    let mut sets = vec![
        "image.width=48".to_string(),
        "image.height=36".into(),
        "camera={position = [0.3, 0.4, 3.0], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 45.0}".into(),
        "lights=[{kind = \"directional\", direction = [0.4, -0.5, -1.0], irradiance = [2.0, 2.0, 2.0]}]".into(),
        "ambient.radiance=[0.2, 0.2, 0.2]".into(),
        format!(
            "environment.map={}/assets/environment/blobs.hdr",
            env!("CARGO_MANIFEST_DIR")
        ),
        "environment.scale=0.5".into(),
        format!("environment.specular={specular}"),
        "environment.reference=sh".into(),
    ];
    if specular == "sampled" {
        sets.push("environment.samples=16".into());
    }
    scene_file::load(&SceneSource::File(quad(dir, strength)), &sets).expect("quad loads")
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    (0..3).all(|c| {
        let (x, y) = (a[c] as f64, b[c] as f64);
        (x - y).abs() <= 1e-5 * x.abs().max(y.abs()) + 1e-9
    })
}

/// The per-pixel checks of the module docs on frames for `s = 0, ½, 1`
/// and the direct-only frame; returns (left, right) pixel counts.
fn assert_occlusion_splits(label: &str, f: [&Frame; 3], direct: &Frame) -> (usize, usize) {
    let (mut left, mut right) = (0, 0);
    for k in 0..f[0].radiance.len() {
        if !f[0].coverage[k] {
            continue;
        }
        let [l0, l_half, l1] = [f[0].radiance[k], f[1].radiance[k], f[2].radiance[k]];
        if close(l1, l0) {
            assert!(
                close(l_half, l0),
                "{label}: pixel {k}, o = 1 at s = 1 but not at s = ½"
            );
            right += 1;
            continue;
        }
        assert!(
            close(l1, direct.radiance[k]),
            "{label}: pixel {k}: o = 0 leaves {l1:?}, the direct light alone is {:?}",
            direct.radiance[k]
        );
        let mean = [0, 1, 2].map(|c| 0.5 * (l0[c] + l1[c]));
        assert!(
            close(l_half, mean),
            "{label}: pixel {k}: s = ½ gives {l_half:?}, the mean of s = 0 and 1 is {mean:?}"
        );
        assert!(
            l0[1] > l1[1] * 1.05,
            "{label}: pixel {k}: the environment and ambient light too little to test"
        );
        left += 1;
    }
    assert!(
        left > 100 && right > 100,
        "{label}: {left} occluded and {right} unoccluded pixels"
    );
    (left, right)
}

/// The absolute tolerance `specular` mode adds (tests/environment.rs):
/// the SH sum (albedo ≤ 1) in every mode; the prefiltered stack's lookup
/// (split weight ≤ 1); for the sampled directions a map lookup times the
/// albedo bound 1.2. Only covered pixels are compared (no background, no
/// mirror here).
fn environment_tolerance(map: &EnvironmentMap, specular: &str) -> f64 {
    let sum: f64 = map
        .irradiance_coefficients()
        .iter()
        .map(|c| c.abs().max_element())
        .sum();
    let sh = 2.0 / std::f64::consts::PI * 31.0 * common::EPS * 2.6 * sum;
    let step_and_peak = |w: usize, rows: usize, h: usize, t: &dyn Fn(usize, usize) -> Rgb| {
        let (mut step, mut peak) = (0.0f64, 0.0f64);
        for r in 0..rows {
            for c in 0..w {
                peak = peak.max(t(c, r).max_element());
                step = step.max((t((c + 1) % w, r) - t(c, r)).abs().max_element());
                if (r + 1) % h != 0 {
                    step = step.max((t(c, r + 1) - t(c, r)).abs().max_element());
                }
            }
        }
        (step, peak)
    };
    match specular {
        "prefiltered" => {
            let p = map.prefiltered();
            let (w, h) = (p.width as usize, p.height as usize);
            let levels = gonio::environment::prefiltered::LEVELS as usize;
            let t = |c: usize, r: usize| Rgb::from(p.texels[r * w + c].map(f64::from));
            let (step, peak) = step_and_peak(w, h * levels, h, &t);
            sh + map.settings.scale * (w as f64 / 4096.0 * step + 16.0 * common::EPS * peak)
        }
        "sampled" => {
            let (w, h) = (map.data.width as usize, map.data.height as usize);
            let t = |c: usize, r: usize| Rgb::from(map.data.texels[r * w + c].map(f64::from));
            let (step, _) = step_and_peak(w, h, h, &t);
            let peak = map.data.lookup(glam::DVec3::Y).max_element();
            sh + 1.2 * map.settings.scale * (w as f64 / 4096.0 * step + 8.0 * common::EPS * peak)
        }
        _ => sh,
    }
}

#[test]
fn occlusion_darkens_ambient_and_environment_not_direct_light() {
    let dir = tempfile::tempdir().unwrap();
    for specular in ["none", "sampled", "prefiltered"] {
        let scenes = [0.0, 0.5, 1.0].map(|s| scene(dir.path(), s, specular));
        let mut direct_only = scenes[0].clone();
        direct_only.environment.map = None;
        direct_only.ambient = Rgb::ZERO;
        let gpu_frames = scenes.each_ref().map(gpu);
        let reference_frames = scenes.each_ref().map(gonio::reference::render);
        let (l, r) = assert_occlusion_splits(
            &format!("{specular}, GPU"),
            gpu_frames.each_ref(),
            &gpu(&direct_only),
        );
        assert_occlusion_splits(
            &format!("{specular}, reference"),
            reference_frames.each_ref(),
            &gonio::reference::render(&direct_only),
        );
        // GPU against the reference, occluded (s = ½).
        let s = &scenes[1];
        let (center, jittered) = common::reference_with_jitter(s);
        let mut tol = common::tolerance(s, &center);
        tol.abs += environment_tolerance(s.environment.map.as_ref().unwrap(), specular);
        let c =
            gonio::output::compare::compare_with_jitter(&gpu_frames[1], &center, &jittered, tol);
        eprintln!(
            "occlusion under the blobs, {specular}: {l} occluded, {r} not; {}",
            c.summary()
        );
        common::assert_agrees(
            &format!("occlusion {specular}"),
            "GPU and reference disagree",
            &c,
            &gpu_frames[1],
            &center,
        );
    }
}
