//! The material key `spectral_metal` in a reference render: a gold sphere
//! rendered with the spectral Fresnel of Johnson & Christy's table against
//! the same sphere with the three-channel preset `gold-rgb`.
//!
//! The one point light stands at the camera, so every visible point is
//! lit along its view direction: `ω_i = ω_o`, `H = ω_o`, and the Fresnel
//! angle `I·H` is 0° at every pixel. The two renders then differ only in
//! `F(cos θ = 1)` (same geometry, same D and G, no diffuse, ambient or
//! environment term), so every pixel's ratio spectral / preset is, per
//! channel, the ratio of the two normal-incidence reflectances: the error
//! table's 0° row (docs/spectral.md, "(b) The coloured conductors").
//! Gold's red is the preset's gamut clip, 1.0376 → 0.9752 (0.0623 in the
//! table, the preset 6.0 % lower); green and blue agree to the preset's
//! 10⁻⁴ rounding.
//!
//! Tolerance of the ratio: both frames store f32 (relative rounding
//! ≤ 2⁻²⁴ each, so ≤ 2⁻²³ on the ratio); in f64 the light's `cos θ` is 1
//! within a few ulp, where `|dF/dcos θ| < 1`, and the table reproduces
//! its node at `cos θ = 1` exactly: 10⁻¹² covers that part.

mod common;

use gonio::base::Rgb;
use gonio::material::brdf::fresnel::fresnel_conductor;
use gonio::material::conductors::Metal;
use gonio::reference::spectral::conductors::spectral_conductor_rgb;
use gonio::reference::spectral::metals;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::Path;

/// A 48×32 sphere lit from the camera; `keys` are the ball's metal keys.
fn scene_text(keys: &str) -> String {
    format!(
        r#"[image]
width = 48
height = 32

[camera]
position = [0.0, 0.0, 3.0]
target = [0.0, 0.0, 0.0]
fov_y_deg = 45.0

[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
segments = 48
material = "ball"

[materials.ball]
model = "cook-torrance"
distribution = "ggx"
geometry = "smith"
roughness = 0.3
{keys}

[[lights]]
kind = "point"
position = [0.0, 0.0, 3.0]
intensity = [5.0, 5.0, 5.0]

[ambient]
radiance = [0.0, 0.0, 0.0]
"#
    )
}

fn render(dir: &Path, name: &str, keys: &str) -> gonio::frame::Frame {
    let path = dir.join(name);
    std::fs::write(&path, scene_text(keys)).unwrap();
    let scene = scene_file::load(&SceneSource::File(path), &[]).expect("scene loads");
    gonio::reference::render(&scene)
}

#[test]
fn spectral_gold_differs_from_its_preset_by_the_normal_incidence_error() {
    let dir = tempfile::tempdir().unwrap();
    let spectral = render(dir.path(), "spectral.toml", "spectral_metal = \"gold\"");
    let preset = render(dir.path(), "preset.toml", "preset = \"gold-rgb\"");
    let c = Metal::Gold.coloured();
    let truth = spectral_conductor_rgb(metals::of(Metal::Gold), 1.0);
    let rendered = fresnel_conductor(1.0, Rgb::from_array(c.eta), Rgb::from_array(c.kappa));
    let predicted = truth / rendered;
    println!("F(0°): spectral {truth:.5}, preset {rendered:.5}, ratio {predicted:.6}");
    // The error table's 0° row: red 0.0623 (the clip), green and blue
    // within the preset's rounding (10⁻⁴).
    assert!((truth.x - rendered.x - 0.0623).abs() < 5e-5);
    assert!(
        (truth.y - rendered.y)
            .abs()
            .max((truth.z - rendered.z).abs())
            < 1e-4
    );
    let tolerance = 2f64.powi(-23) + 1e-12;
    let mut lit = 0;
    let mut worst: f64 = 0.0;
    for (s, p) in spectral.radiance.iter().zip(&preset.radiance) {
        if p.iter().all(|&v| v == 0.0) {
            assert!(
                s.iter().all(|&v| v == 0.0),
                "{s:?} where the preset is black"
            );
            continue;
        }
        lit += 1;
        for ch in 0..3 {
            let ratio = f64::from(s[ch]) / f64::from(p[ch]);
            worst = worst.max((ratio / predicted[ch] - 1.0).abs());
        }
    }
    println!("{lit} lit pixels; largest relative departure from the predicted ratio {worst:.2e}");
    assert!(lit > 400, "{lit} lit pixels");
    assert!(worst <= tolerance, "{worst:e} > {tolerance:e}");
    // The preset's red is 6.0 % below the spectral red.
    assert!(
        (1.0 - 1.0 / predicted.x - 0.060).abs() < 5e-4,
        "{predicted}"
    );
}

/// A bad metal, in a scene file and by `--set`: exit 2, one paragraph
/// naming where and the metals allowed, no output.
#[test]
fn a_bad_metal_is_refused_naming_the_allowed_ones() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(&scene, scene_text("spectral_metal = \"platinum\"")).unwrap();
    let out = dir.path().join("out.png");
    for args in [
        vec![scene.to_str().unwrap(), "--reference"],
        vec![
            "--set",
            "materials.ball.model=\"cook-torrance\"",
            "--set",
            "materials.ball.spectral_metal=platinum",
        ],
        vec![scene.to_str().unwrap()],
    ] {
        let result = common::gonio()
            .arg("render")
            .args(&args)
            .args(["-o", out.to_str().unwrap()])
            .env("XDG_RUNTIME_DIR", dir.path())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains("spectral_metal")
                && stderr.contains("platinum")
                && stderr.contains("gold, silver, copper, aluminium, iron"),
            "{stderr}"
        );
        if args[0].ends_with("bad.toml") {
            assert!(stderr.contains("bad.toml"), "{stderr}");
        }
        assert!(!out.exists());
    }
}
