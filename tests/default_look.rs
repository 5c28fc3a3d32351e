//! The default look of files as people have them: a glTF without lights is
//! shown in the built-in neutral studio, an environment map lights the
//! whole BRDF of every material unless the user asks for less
//! (`environment.specular = "auto"`, the contract's "Environment light"),
//! and glTF materials are energy-compensated by default.

mod common;

use gonio::environment::load::write_hdr;
use gonio::environment::map::Specular;
use gonio::environment::studio::STUDIO;
use gonio::frame::Frame;
use gonio::reference;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::Path;

fn load(source: &Path, sets: &[&str]) -> Scene {
    let overrides: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    scene_file::load(&SceneSource::File(source.to_path_buf()), &overrides).expect("scene loads")
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

/// Covered pixels whose brightest channel is below `level`, as a share of
/// the covered pixels.
fn dark_share(f: &Frame, level: f32) -> f64 {
    let covered: Vec<usize> = (0..f.len()).filter(|&k| f.coverage[k]).collect();
    assert!(
        covered.len() > 500,
        "the object covers {} pixels",
        covered.len()
    );
    let dark = covered
        .iter()
        .filter(|&&k| f.radiance[k].iter().all(|&c| c < level))
        .count();
    dark as f64 / covered.len() as f64
}

/// MetalRoughSpheresNoTextures (a grid of spheres from dielectric to
/// metal, smooth to rough) has no light: it gets the studio, with the
/// split sum for its gltf-pbr materials, and no sphere is dark, on the GPU
/// and in the reference. With `gltf.default_light = "directional"` the old
/// default light comes back and the metals facing away from it are black
/// (what the studio is for).
#[test]
fn a_gltf_without_lights_is_shown_in_the_studio() {
    let file = common::gltf_asset("MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb");
    let sets = ["image.width=160", "image.height=120"];
    let scene = load(&file, &sets);
    let map = scene.environment.map.as_ref().expect("the studio");
    assert_eq!(map.data.name, STUDIO);
    assert!(scene.lights.is_empty());
    assert_eq!(map.settings.specular, Specular::Prefiltered);
    for (label, frame) in [
        ("GPU", gpu(&scene)),
        ("reference", reference::render(&scene)),
    ] {
        let dark = dark_share(&frame, 0.02);
        assert!(
            dark < 0.01,
            "{label}: {:.1} % of the spheres are dark",
            100.0 * dark
        );
    }

    let mut directional = sets.to_vec();
    directional.push("gltf.default_light=directional");
    let lit = load(&file, &directional);
    assert!(lit.environment.map.is_none());
    assert_eq!(lit.lights.len(), 1);
    let dark = dark_share(&gpu(&lit), 0.02);
    assert!(dark > 0.1, "directional: only {:.1} % dark", 100.0 * dark);
}

/// glTF materials are compensated unless `gltf.energy_compensation =
/// false` says otherwise; scene-file materials never by default.
#[test]
fn gltf_materials_are_compensated_by_default() {
    let file = common::gltf_asset("MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb");
    let on = load(&file, &[]);
    assert!(on.materials.iter().all(|m| m.energy_compensation));
    let off = load(&file, &["gltf.energy_compensation=false"]);
    assert!(off.materials.iter().all(|m| !m.energy_compensation));
}

/// glTF materials turn a shading normal that faces away from the viewer
/// toward it unless `gltf.facing_normals = false`; scene-file materials
/// never do (the built-in scene's).
#[test]
fn gltf_materials_have_facing_normals_by_default() {
    let file = common::gltf_asset("MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb");
    let on = load(&file, &[]);
    assert!(on.materials.iter().all(|m| m.facing_normals));
    let off = load(&file, &["gltf.facing_normals=false"]);
    assert!(off.materials.iter().all(|m| !m.facing_normals));
    let built_in = scene_file::load(&SceneSource::BuiltIn, &[]).unwrap();
    assert!(built_in.materials.iter().all(|m| !m.facing_normals));
}

/// The white furnace with the defaults (no `specular` key): a gold
/// Cook-Torrance sphere and a normalized-Phong sphere under a uniform map
/// of radiance 1 show their directional albedo. The reference integrates
/// it; the GPU takes the mode "auto" picks (split sum for the gold,
/// SH convolution for Phong). The centre pixel (μ ≈ 1) is compared: the
/// split sum in a uniform map is the DFG table, whose interpolation and
/// quadrature error is at most 2.3e-3 + 5.9e-3 (src/environment/dfg.rs)
/// relative to `E`; SH of a constant map is exact, leaving f32 rounding.
#[test]
fn a_white_furnace_lights_the_whole_brdf_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let white = gonio::environment::test_maps::uniform(64, gonio::scene::Rgb::ONE);
    write_hdr(&white, &dir.path().join("white.hdr")).unwrap();
    for (material, mode, tolerance) in [
        (
            "{ model = \"cook-torrance\", preset = \"gold-rgb\", distribution = \"ggx\", geometry = \"smith\", roughness = 0.3 }",
            Specular::Prefiltered,
            2.3e-3 + 5.9e-3 + 1e-4,
        ),
        (
            "{ model = \"phong-normalized\", k_d = [0.3, 0.3, 0.3], k_s = [0.5, 0.5, 0.5], k_e = 20 }",
            Specular::Sh,
            1e-4,
        ),
    ] {
        std::fs::write(
            dir.path().join("furnace.toml"),
            format!(
                "[image]\nwidth = 33\nheight = 33\n\n[camera]\nposition = [0, 0, 3]\ntarget = [0, 0, 0]\nfov_y_deg = 40\n\n[materials]\nball = {material}\n\n[[objects]]\nshape = \"sphere\"\nmaterial = \"ball\"\n\n[environment]\nmap = \"white.hdr\"\n"
            ),
        )
        .unwrap();
        let scene = load(&dir.path().join("furnace.toml"), &[]);
        assert_eq!(
            scene.environment.map.as_ref().unwrap().settings.specular,
            mode
        );
        let centre = 16 * 33 + 16;
        let truth = reference::render(&scene).radiance[centre];
        let got = gpu(&scene).radiance[centre];
        if mode == Specular::Sh {
            // Normalized Phong's albedo at normal incidence is k_d + k_s
            // = 0.8 exactly: the SH convolution of a constant map gives it
            // to f32 rounding, the truth to its texel quadrature's error
            // (the 5e-3 bound of tests/environment.rs's SH furnace).
            for c in 0..3 {
                assert!((got[c] as f64 - 0.8).abs() < 1e-5, "GPU {got:?}");
                assert!((truth[c] as f64 - 0.8).abs() < 5e-3, "truth {truth:?}");
            }
            continue;
        }
        for c in 0..3 {
            let (t, g) = (truth[c] as f64, got[c] as f64);
            // Gold's blue is its darkest channel, F0 ≈ 0.3.
            assert!(
                t > 0.25,
                "{mode:?}: the truth is {t}: the environment lights the lobe"
            );
            assert!(
                (g - t).abs() <= tolerance * t,
                "{mode:?} channel {c}: GPU {g} vs truth {t}"
            );
        }
    }
}

/// `environment.specular = "none"` stays an explicit choice: the diffuse
/// term alone (a gold conductor has none: black on both renderers).
#[test]
fn specular_none_is_kept_when_asked_for() {
    let file = common::gltf_asset("MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb");
    let scene = load(&file, &["environment.specular=none"]);
    assert_eq!(
        scene.environment.map.as_ref().unwrap().settings.specular,
        Specular::None
    );
}
