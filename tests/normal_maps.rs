//! Normal and occlusion textures (glTF's `normalTexture`,
//! `occlusionTexture`; the scene file's `normal_texture`,
//! `occlusion_texture`): analytic radiance where the map is constant, the
//! GPU against the f64 reference on the Khronos NormalTangentTest (no
//! `TANGENT`: MikkTSpace tangents; an occlusion texture) and on Avocado
//! (its own `TANGENT`s, w included).
//!
//! The constant maps use texels 0 and 255 only, which decode exactly
//! (0 and 1, exact in f16): the only error left is the GPU's f32
//! arithmetic (a few ulps of the normal, ~10⁻⁶ relative), so the
//! analytic checks allow 10⁻⁴ relative.

mod common;

use gonio::frame::Frame;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Scene, ShadingMode};
use std::f64::consts::PI;
use std::path::Path;

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

/// A 2×2 PNG of one RGB colour.
fn write_png(path: &Path, rgb: [u8; 3]) {
    let img = image::RgbImage::from_pixel(2, 2, image::Rgb(rgb));
    img.save(path).unwrap();
}

/// A Lambert plane seen from above, `extra` keys on its material, one
/// directional light towards `-to_light`. The plane is small (2 wide,
/// seen from 6 above) so that the tilted normal (1, 1, 1)/√3 still faces
/// the camera at every vertex: f_r is one-sided in the shading normal,
/// and Gouraud shading interpolates the vertices' colours.
fn plane_scene(dir: &Path, extra: &str, to_light: [f64; 3], mode: ShadingMode) -> Scene {
    let text = format!(
        r#"
[image]
width = 64
height = 48

[camera]
position = [0.0, 6.0, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y_deg = 40.0

[shading]
mode = "{mode}"

[[objects]]
shape = "plane"
center = [0.0, 0.0, 0.0]
size = 2.0
segments = 2
material = "floor"

[materials.floor]
model = "lambert"
k_a = [1.0, 1.0, 1.0]
k_d = [0.8, 0.8, 0.8]
{extra}

[[lights]]
kind = "directional"
direction = [{}, {}, {}]
irradiance = [3.0, 3.0, 3.0]

[ambient]
radiance = [0.5, 0.5, 0.5]
"#,
        -to_light[0], -to_light[1], -to_light[2]
    );
    let path = dir.join("plane.toml");
    std::fs::write(&path, text).unwrap();
    scene_file::load(&SceneSource::File(path), &[]).expect("scene loads")
}

/// The middle pixel's radiance of both renderers.
fn middle(scene: &Scene) -> [(&'static str, f64); 2] {
    let (i, j) = (scene.height / 2, scene.width / 2);
    let at = |f: &Frame| {
        assert!(f.coverage[f.index(i, j)]);
        f.radiance[f.index(i, j)][1] as f64
    };
    [
        ("GPU", at(&gpu(scene))),
        ("reference", at(&gonio::reference::render(scene))),
    ]
}

/// Texel (255, 0, 255) is n_t = (1, −1, 1)/√3. The plane has N = +Y and
/// T = +X (u along +X), and v runs along +Z, down the image, so glTF's
/// B = N × T = −Z points up the image: n' = (T − B + N)/√3 = (1, 1, 1)/√3.
/// Lit from straight above, cos θ = 1/√3; lit along n' itself, 1; the
/// wrong bitangent (B = +Z) would give (1, 1, −1)/√3 and 1/3 there.
#[test]
fn a_constant_normal_map_tilts_the_normal_as_gltf_says() {
    let dir = tempfile::tempdir().unwrap();
    write_png(&dir.path().join("n.png"), [255, 0, 255]);
    let s3 = 3f64.sqrt();
    for mode in ShadingMode::ALL {
        for (to_light, cos) in [([0.0, 1.0, 0.0], 1.0 / s3), ([1.0, 1.0, 1.0], 1.0)] {
            let scene = plane_scene(dir.path(), "normal_texture = \"n.png\"", to_light, mode);
            // Ambient 0.5 · k_a 1 is not affected by the normal.
            let want = 0.8 / PI * 3.0 * cos + 0.5;
            for (name, got) in middle(&scene) {
                assert!(
                    (got - want).abs() <= 1e-4 * want,
                    "{mode}, light {to_light:?}, {name}: {got} vs {want}"
                );
            }
        }
    }
}

/// Occlusion R = 0 with strength 1 removes the ambient term and leaves
/// the direct light untouched.
#[test]
fn occlusion_scales_the_ambient_term_only() {
    let dir = tempfile::tempdir().unwrap();
    write_png(&dir.path().join("o.png"), [0, 255, 255]);
    for mode in ShadingMode::ALL {
        let scene = plane_scene(
            dir.path(),
            "occlusion_texture = \"o.png\"",
            [0.0, 1.0, 0.0],
            mode,
        );
        let want = 0.8 / PI * 3.0;
        for (name, got) in middle(&scene) {
            assert!(
                (got - want).abs() <= 1e-4 * want,
                "{mode}, {name}: {got} vs {want}"
            );
        }
    }
}

fn gpu_vs_reference(label: &str, scene: &Scene) {
    let frame = gpu(scene);
    let (center, jittered) = common::reference_with_jitter(scene);
    let c = common::compare_to_reference(scene, &frame, &center, &jittered);
    eprintln!("{label:<32} {}", c.summary());
    assert!(c.compared > (scene.width * scene.height) as usize / 10);
    common::assert_agrees(label, "GPU and reference disagree", &c, &frame, &center);
}

fn gltf(relative: &str, mode: ShadingMode) -> Scene {
    scene_file::load(
        &SceneSource::File(common::gltf_asset(relative)),
        &[
            format!("shading.mode=\"{mode}\""),
            "image.width=160".into(),
            "image.height=120".into(),
            // The directional default light, not the studio: both
            // renderers evaluate it exactly.
            "gltf.default_light=\"directional\"".into(),
        ],
    )
    .expect("glTF loads")
}

/// NormalTangentTest: a normal map without TANGENT (MikkTSpace) and an
/// occlusion texture; GPU = reference.
#[test]
fn normal_tangent_test_gpu_matches_reference() {
    let scene = gltf(
        "NormalTangentTest/NormalTangentTest.glb",
        ShadingMode::Phong,
    );
    assert!(
        scene
            .meshes
            .iter()
            .all(|m| m.tangents.len() == m.positions.len()
                && m.bitangent_signs.len() == m.positions.len()),
        "MikkTSpace tangents generated"
    );
    gpu_vs_reference("NormalTangentTest, phong", &scene);
}

/// Avocado: its own TANGENTs (w read); GPU = reference in every mode.
#[test]
fn avocado_gpu_matches_reference() {
    for mode in ShadingMode::ALL {
        let scene = gltf("Avocado/Avocado.gltf", mode);
        assert!(scene.meshes.iter().all(|m| !m.bitangent_signs.is_empty()));
        gpu_vs_reference(&format!("Avocado, {mode}"), &scene);
    }
}
