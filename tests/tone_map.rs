//! `image.tone_map` through the binary: a PNG holds the
//! EXR's linear radiance mapped by the chosen operator (the f64 formulas
//! of `gonio::output::tone_map`, unit-tested there against their
//! sources), the default is the clamp, EXR output stays linear with a
//! warning, and a misspelt name is a one-paragraph error.
//!
//! The CPU reference renders (deterministic), so the PNG and the EXR of
//! one scene hold the same radiance and must agree byte for byte.

mod common;

use gonio::output::tone_map::ToneMap;
use gonio::output::write::pixel_to_srgb8;
use std::path::Path;

fn render(out: &Path, extra: &[&str]) -> std::process::Output {
    let o = common::gonio()
        .args(["render", "--reference", "--width", "64", "--height", "48"])
        .args(["--set", "lights.0.intensity=[300,300,300]"])
        .arg("-o")
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{extra:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

#[test]
fn each_tone_map_is_its_formula_on_the_linear_image() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("linear.exr");
    render(&exr, &[]);
    let linear = image::open(&exr).unwrap().into_rgb32f();
    let clipped = linear
        .pixels()
        .filter(|p| p.0.iter().any(|&c| c > 1.0))
        .count();
    assert!(
        clipped > 100,
        "the light must push pixels past 1 ({clipped})"
    );
    let default_png = dir.path().join("default.png");
    render(&default_png, &[]);
    let default_png = image::open(&default_png).unwrap().into_rgb8();
    for (t, exposure) in ToneMap::ALL.into_iter().flat_map(|t| [(t, 0.0), (t, -1.0)]) {
        let png = dir.path().join(format!("{t}{exposure}.png"));
        let set = format!("image.tone_map=\"{t}\"");
        let e = exposure.to_string();
        render(&png, &["--set", &set, "--exposure", &e]);
        let got = image::open(&png).unwrap().into_rgb8();
        for (p, q) in linear.pixels().zip(got.pixels()) {
            assert_eq!(pixel_to_srgb8(p.0, exposure, t), q.0, "{t} at {p:?}");
        }
        if t == ToneMap::Clamp && exposure == 0.0 {
            assert_eq!(got, default_png, "the default tone map is the clamp");
        } else {
            assert_ne!(
                got, default_png,
                "{t} at exposure {exposure} changed nothing"
            );
        }
    }
}

#[test]
fn exr_stays_linear_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let plain = dir.path().join("plain.exr");
    render(&plain, &[]);
    let mapped = dir.path().join("mapped.exr");
    let o = render(&mapped, &["--set", "image.tone_map=\"aces\""]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("image.tone_map = \"aces\" does not apply") && stderr.contains("EXR"),
        "{stderr}"
    );
    let a = image::open(&plain).unwrap().into_rgb32f();
    let b = image::open(&mapped).unwrap().into_rgb32f();
    assert_eq!(a, b);
}

#[test]
fn a_misspelt_tone_map_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = common::gonio()
        .args(["render", "--set", "image.tone_map=\"filmic\"", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("image.tone_map") && stderr.contains("pbr-neutral"),
        "{stderr}"
    );
    assert_eq!(
        stderr
            .lines()
            .filter(|l| l.starts_with("gonio: error"))
            .count(),
        1
    );
    assert!(!out.exists());
}
