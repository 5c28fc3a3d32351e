//! `gonio brdf` as a user runs it: values, plots, the albedo table, and
//! one-paragraph errors with exit status 2.

mod common;

use std::f64::consts::FRAC_1_PI;
use std::process::Output;

fn brdf(args: &[&str]) -> Output {
    common::gonio().arg("brdf").args(args).output().unwrap()
}

fn stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "gonio brdf failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The `[r, g, b]` after `LABEL: f_r = ` in the printout.
fn f_r(text: &str, label: &str) -> [f64; 3] {
    let prefix = format!("{label}: f_r = [");
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no `{prefix}` in {text}"));
    let numbers: Vec<f64> = line
        .split(']')
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    [numbers[0], numbers[1], numbers[2]]
}

#[test]
fn lambert_prints_k_d_over_pi_exactly() {
    let out = brdf(&[
        "--model",
        "lambert",
        "--set",
        "k_d=[0.2, 0.5, 0.9]",
        "--theta-i",
        "10",
        "--theta-o",
        "70",
        "--phi-o",
        "33",
    ]);
    let text = stdout(&out);
    let value = f_r(&text, "lambert");
    for (v, k_d) in value.into_iter().zip([0.2, 0.5, 0.9]) {
        // The printout round-trips f64; Lambert is k_d · (1/π), which is
        // k_d/π to the last bit or within one ulp of it.
        assert_eq!(v, k_d * FRAC_1_PI, "{text}");
        assert!((v - k_d / std::f64::consts::PI).abs() <= f64::EPSILON * v);
    }
    assert!(text.contains("θ_o = 70°"), "{text}");
}

#[test]
fn several_models_and_the_default_mirror_direction() {
    let out = brdf(&[
        "--model",
        "phong-normalized",
        "--compare",
        "phong,k_e=10,k_d=0",
        "--set",
        "k_s=1",
        "--set",
        "k_d=0.8",
        "--set",
        "k_e=50",
        "--theta-i",
        "40",
        "--albedo",
        "--gloss",
    ]);
    let text = stdout(&out);
    assert!(text.contains("(mirror direction)"), "{text}");
    // At the mirror direction normalized Phong is k_d/π + k_s (k_e+2)/(2π).
    let v = f_r(&text, "phong-normalized")[0];
    assert!((v - (0.8 * FRAC_1_PI + 52.0 / (2.0 * std::f64::consts::PI))).abs() < 1e-12);
    // The lecture's Phong at its peak: k_s / cos θ_i.
    let v = f_r(&text, "phong k_e=10 k_d=0")[0];
    assert!((v - 1.0 / 40f64.to_radians().cos()).abs() < 1e-12, "{text}");
    assert!(text.contains("albedo ρ(θ_i = 40°)"), "{text}");
    assert!(text.contains("20°:") && text.contains("GU"), "{text}");
}

#[test]
fn writes_slice_and_albedo_plots_as_png_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["png", "svg"] {
        let slice = dir.path().join(format!("slice.{ext}"));
        let albedo = dir.path().join(format!("albedo.{ext}"));
        let out = common::gonio()
            .args([
                "brdf",
                "--model",
                "lambert",
                "--compare",
                "mirror,preset=gold",
            ])
            .args(["--compare", "cook-torrance,roughness=0.2,k_s=1,k_d=0"])
            .arg("--plot-slice")
            .arg(&slice)
            .arg("--plot-albedo")
            .arg(&albedo)
            .output()
            .unwrap();
        stdout(&out);
        for path in [&slice, &albedo] {
            if ext == "png" {
                let image = image::open(path).unwrap().into_rgb8();
                assert_eq!(image.dimensions(), (960, 600));
                // Something is drawn: not every pixel is white.
                assert!(image.pixels().any(|p| p.0 != [255, 255, 255]));
            } else {
                let text = std::fs::read_to_string(path).unwrap();
                assert!(text.starts_with("<svg"), "{}", &text[..text.len().min(80)]);
                assert!(text.contains("cook-torrance"), "legend missing");
            }
        }
    }
    // Nothing but the four plots: no temporary files left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
}

#[test]
fn bad_input_exits_2_with_one_paragraph() {
    let dir = tempfile::tempdir().unwrap();
    let bad_plot = dir.path().join("slice.jpg");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--model", "phonk"],
            "unknown reflectance model `phonk`",
        ),
        (
            vec!["--model", "phong", "--set", "rougness=0.2"],
            "--set rougness=0.2",
        ),
        (
            vec!["--model", "phong", "--set", "k_e=2e6"],
            "k_e = 2000000 is outside",
        ),
        (
            vec!["--compare", "cook-torrance,distribution=phong"],
            "unknown distribution",
        ),
        (
            vec!["--model", "lambert", "--theta-i", "200"],
            "--theta-i 200",
        ),
        (vec![], "name at least one material"),
        (
            vec![
                "--model",
                "lambert",
                "--plot-slice",
                bad_plot.to_str().unwrap(),
            ],
            ".png or .svg",
        ),
    ];
    for (args, expected) in cases {
        let out = brdf(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(expected), "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one paragraph: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Generates the albedo table of `docs/brdf-models.md`:
/// `cargo test --release --test brdf_cli -- --nocapture print_albedo_table`
/// (the same as `gonio brdf --albedo-table`). Checks the energy balance the
/// docs state: the normalized forms never exceed 1 beyond their bound at
/// the angles of the table, the lecture's Phong does.
#[test]
fn print_albedo_table() {
    let text = stdout(&brdf(&["--albedo-table"]));
    println!("{text}");
    let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("| `")).collect();
    assert!(rows.len() > 30, "{text}");
    let row = |prefix: &str| *rows.iter().find(|r| r.starts_with(prefix)).unwrap();
    assert!(row("| `lambert` |").contains("| 1.0000 | 1.0000 | 1.0000 | 1.0000 | 1.0000 |"));
    assert!(
        row("| `phong` | k_e=1 |").contains("**"),
        "the lecture's Phong exceeds 1"
    );
    for r in rows
        .iter()
        .filter(|r| r.starts_with("| `phong-normalized`"))
    {
        assert!(!r.contains("**"), "normalized Phong above 1: {r}");
    }
}

/// A measured material and a fit of it on one slice plot (the
/// measured and fitted slices together), and a bare `measured` plots the
/// viewer's default material, saying so (the same values as naming it).
#[test]
fn measured_and_fitted_slices_together_and_the_default_measured() {
    let dir = tempfile::tempdir().unwrap();
    let slice = dir.path().join("slice.svg");
    let out = common::gonio()
        .args(["brdf", "--compare", "measured,measured=chrome"])
        .args([
            "--compare",
            "cook-torrance,distribution=ggx,fresnel=conductor,roughness=0.01,k_s=1,k_d=0",
        ])
        .arg("--plot-slice")
        .arg(&slice)
        .output()
        .unwrap();
    let text = stdout(&out);
    assert!(f_r(&text, "measured measured=chrome")[0] > 100.0, "{text}");
    let svg = std::fs::read_to_string(&slice).unwrap();
    assert!(svg.contains("measured=chrome") && svg.contains("cook-torrance"));

    let bare = brdf(&["--compare", "measured"]);
    let named = brdf(&["--compare", "measured,measured=gold-metallic-paint"]);
    let note = String::from_utf8_lossy(&bare.stderr).into_owned();
    assert!(note.contains("measured=gold-metallic-paint"), "{note}");
    assert_eq!(
        f_r(&stdout(&bare), "measured"),
        f_r(&stdout(&named), "measured measured=gold-metallic-paint")
    );
}

/// `--plot-halfdiff`: the θ_h × θ_d image of each
/// material, written where asked; the glossy panel's first column (θ_h
/// near 0, the specular peak) is brighter on the colour scale than a cell
/// at θ_h = 60° of the same row, and the PNG holds the colours the plot's
/// layout puts there. A bad extension is the usual one-paragraph exit 2.
#[test]
fn halfdiff_image_shows_the_specular_peak_at_theta_h_zero() {
    use gonio::explore::halfdiff::half_diff_image;
    use gonio::explore::halfdiff_plot::{colour, layout};
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("hd.png");
    let glossy = "cook-torrance,k_d=0.1,k_s=1,roughness=0.15";
    stdout(&brdf(&[
        "--compare",
        glossy,
        "--compare",
        "lambert,k_d=0.5",
        "--plot-halfdiff",
        png.to_str().unwrap(),
    ]));
    let image = image::open(&png).unwrap().into_rgb8();
    let (w, h) = image.dimensions();
    let panels = layout(w, h, 2);
    let m = gonio::explore::spec::compare_spec(glossy, &[]).unwrap();
    let values = half_diff_image(&m.material, gonio::explore::Channel::Mean).values;
    let peak = values[45][0];
    assert!(peak > 10.0 * values[45][60], "{peak} vs {}", values[45][60]);
    // The scale's top is the glossy image's largest value (Lambert's 0.16
    // is far below it); its bottom at most 6 decades lower.
    let hi = values
        .iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(*v))
        .log10();
    let lo = values
        .iter()
        .flatten()
        .chain(std::iter::once(&(0.5 / std::f64::consts::PI)))
        .fold(f64::INFINITY, |a, v| a.min(v.log10()))
        .max(hi - 6.0);
    for (i, j) in [(0, 45), (60, 45)] {
        let (x, y) = panels[0].cell_centre(i, j);
        let p = image.get_pixel(x as u32, y as u32).0;
        let want = colour(values[j][i], lo, hi);
        assert_eq!(p, [want.0, want.1, want.2], "cell θ_h {i}, θ_d {j}");
    }
    let bad = dir.path().join("hd.jpg");
    let out = brdf(&[
        "--model",
        "lambert",
        "--plot-halfdiff",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(".png or .svg"));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// Below the roughness floor (1e-4) `gonio brdf`
/// evaluates what the renderers render, says so, and prints the same
/// values as at the floor. Before, a roughness of 1e-6 at 89.999° made the
/// albedo quadrature (sized for the floor) take 150 s, and Ward with
/// σ_x = 1e-6 took 191 s. No time is asserted (a shared machine): the
/// equality with the floored material is what could fail.
#[test]
fn roughness_below_the_floor_is_evaluated_at_the_floor_and_said() {
    for (below, at, key) in [
        (
            "cook-torrance,k_d=0,k_s=1,roughness=1e-06",
            "cook-torrance,k_d=0,k_s=1,roughness=1e-04",
            "roughness = 1e-6",
        ),
        (
            "ward-anisotropic,sigma_x=1e-6,sigma_y=1",
            "ward-anisotropic,sigma_x=1e-4,sigma_y=1",
            "sigma_x = 1e-6",
        ),
    ] {
        let args = |m: &str| {
            vec![
                "--compare".to_string(),
                m.to_string(),
                "--theta-i".into(),
                "89.999".into(),
                "--albedo".into(),
            ]
        };
        let run = |m: &str| {
            let a = args(m);
            brdf(&a.iter().map(String::as_str).collect::<Vec<_>>())
        };
        let (low, floor) = (run(below), run(at));
        let note = String::from_utf8_lossy(&low.stderr);
        assert!(
            note.contains(key) && note.contains("below the roughness floor"),
            "{below}: {note}"
        );
        // The values after each label agree (the labels differ).
        let values = |out: &Output| -> Vec<String> {
            stdout(out)
                .lines()
                .filter_map(|l| l.split_once(": ").map(|(_, v)| v.to_string()))
                .collect()
        };
        assert_eq!(values(&low), values(&floor), "{below}");
    }
}

/// `--phi-d` (as BRDF Explorer's image slice has a φ_d control):
/// the PNG holds the colours of the image at that φ_d, which differs from
/// the default 90° one for a Cook-Torrance lobe (its Fresnel and shadowing
/// depend on φ_d through the directions), and `--phi-d` without the image
/// is refused rather than ignored.
#[test]
fn halfdiff_image_follows_phi_d() {
    use gonio::explore::Channel;
    use gonio::explore::halfdiff::{half_diff_image, half_diff_image_at};
    use gonio::explore::halfdiff_plot::{colour, layout};
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("hd30.png");
    let spec = "cook-torrance,k_d=0,k_s=1,roughness=0.3";
    stdout(&brdf(&[
        "--compare",
        spec,
        "--plot-halfdiff",
        png.to_str().unwrap(),
        "--phi-d",
        "30",
    ]));
    let m = gonio::explore::spec::compare_spec(spec, &[])
        .unwrap()
        .material;
    let at30 = half_diff_image_at(&m, Channel::Mean, 30f64.to_radians()).values;
    let at90 = half_diff_image(&m, Channel::Mean).values;
    assert!(
        (at30[80][40] - at90[80][40]).abs() > 1e-3 * at90[80][40],
        "φ_d changes nothing: {} vs {}",
        at30[80][40],
        at90[80][40]
    );
    let image = image::open(&png).unwrap().into_rgb8();
    let (w, h) = image.dimensions();
    let panel = layout(w, h, 1)[0];
    let logs = at30
        .iter()
        .flatten()
        .filter(|v| **v > 0.0)
        .map(|v| v.log10());
    let hi = logs.clone().fold(f64::NEG_INFINITY, f64::max);
    let lo = logs.fold(f64::INFINITY, f64::min).max(hi - 6.0);
    for (i, j) in [(0, 45), (40, 80)] {
        let (x, y) = panel.cell_centre(i, j);
        let p = image.get_pixel(x as u32, y as u32).0;
        let want = colour(at30[j][i], lo, hi);
        assert_eq!(p, [want.0, want.1, want.2], "cell θ_h {i}, θ_d {j}");
    }
    let out = brdf(&["--model", "lambert", "--phi-d", "30"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--phi-d 30") && stderr.contains("--plot-halfdiff"),
        "{stderr}"
    );
}

/// The albedo after `LABEL: albedo ρ(θ_i = …°) = ` and its bound.
fn albedo(text: &str, label: &str) -> ([f64; 3], [f64; 3]) {
    numbers_after(text, &format!("{label}: albedo"))
}

/// The `[r, g, b] ± [r, g, b]` of the line starting with `prefix`.
fn numbers_after(text: &str, prefix: &str) -> ([f64; 3], [f64; 3]) {
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix(prefix))
        .unwrap_or_else(|| panic!("no `{prefix}` in {text}"));
    let numbers: Vec<f64> = line
        .split('=')
        .next_back()
        .unwrap()
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
        .filter(|s| !s.is_empty() && *s != "e")
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(numbers.len(), 6, "{line}");
    (
        [numbers[0], numbers[1], numbers[2]],
        [numbers[3], numbers[4], numbers[5]],
    )
}

/// `--layer`: the layer keys reach `gonio brdf` (`--set clearcoat=…`), and
/// each layer's term is shown apart. The clearcoat term's albedo equals
/// the albedo of a material that is the coat alone (a black base with no
/// specular lobe: `f_r = (1 − k F_c)·0 + k F_c G`, computed by the whole
/// BRDF), and the terms' albedos sum to the whole's, within the rounding
/// of the printout.
#[test]
fn each_layer_term_is_shown_apart_and_the_terms_sum_to_the_whole() {
    let coat = ["--set", "clearcoat=0.8", "--set", "clearcoat_roughness=0.2"];
    let base = [
        "--model",
        "gltf-pbr",
        "--set",
        "base_color=[0.8, 0.05, 0.05]",
        "--set",
        "roughness=0.6",
        "--theta-i",
        "40",
        "--albedo",
    ];
    let args: Vec<&str> = base
        .iter()
        .chain(&coat)
        .copied()
        .chain(["--layer", "each"])
        .collect();
    let text = stdout(&brdf(&args));
    let (whole, _) = albedo(&text, "gltf-pbr");
    let (under, _) = albedo(&text, "gltf-pbr [base]");
    let (coat_term, _) = albedo(&text, "gltf-pbr [clearcoat]");
    let (sum, _) = numbers_after(&text, "gltf-pbr: sum of the terms");
    assert!(!text.contains("[sheen]"), "no sheen on: {text}");
    // Each printed number is rounded to 4 significant digits: off by up
    // to 5·10⁻⁴ of itself (the quadrature's bounds, ~10⁻¹¹, are far below).
    let rounding = |v: &[f64]| 5e-4 * v.iter().map(|x| x.abs()).sum::<f64>();
    let close = |a: f64, b: f64| (a - b).abs() <= rounding(&[a, b]);
    for c in 0..3 {
        let terms = [under[c], coat_term[c], whole[c]];
        assert!(
            (under[c] + coat_term[c] - whole[c]).abs() <= rounding(&terms),
            "{text}"
        );
        assert!(close(sum[c], whole[c]), "{text}");
        assert!(
            coat_term[c] > 0.02 && under[c] > coat_term[c] * 0.5,
            "{text}"
        );
    }
    // The coat alone, as a whole material.
    let alone: Vec<&str> = [
        "--model",
        "gltf-pbr",
        "--set",
        "base_color=[0, 0, 0]",
        "--set",
        "specular=0",
        "--theta-i",
        "40",
        "--albedo",
    ]
    .iter()
    .chain(&coat)
    .copied()
    .collect();
    let (direct, _) = albedo(&stdout(&brdf(&alone)), "gltf-pbr");
    for c in 0..3 {
        assert!(
            close(direct[c], coat_term[c]),
            "{direct:?} vs {coat_term:?}"
        );
    }
    // One term alone, and its f_r at the mirror direction.
    let one: Vec<&str> = base
        .iter()
        .chain(&coat)
        .copied()
        .chain(["--layer", "clearcoat"])
        .collect();
    let text = stdout(&brdf(&one));
    let (alone_term, _) = albedo(&text, "gltf-pbr [clearcoat]");
    assert_eq!(alone_term, coat_term);
    assert!(!text.contains("gltf-pbr: "), "only the term: {text}");
}

/// `--layer` naming a layer no material has is refused (nothing but
/// zeros would be shown), naming the key that switches it on; a material
/// without the layer among others that have it gets a note.
#[test]
fn a_layer_no_material_has_is_refused() {
    let out = brdf(&["--model", "gltf-pbr", "--layer", "sheen"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--layer sheen") && stderr.contains("sheen_color"),
        "{stderr}"
    );
    let out = brdf(&["--model", "phong", "--layer", "clearcot"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("clearcoat"));
    let out = brdf(&[
        "--model",
        "lambert",
        "--compare",
        "gltf-pbr,clearcoat=1,clearcoat_roughness=0.3",
        "--layer",
        "clearcoat",
    ]);
    let text = stdout(&out);
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("lambert has no clearcoat layer"),
        "{text}"
    );
    assert_eq!(f_r(&text, "lambert [clearcoat]"), [0.0; 3]);
    // k F_c G at the mirror direction, θ_i = 30°: 0.04 · D·Vis of α = 0.09,
    // about 0.5.
    let coat = f_r(
        &text,
        "gltf-pbr clearcoat=1 clearcoat_roughness=0.3 [clearcoat]",
    );
    assert!(coat[0] > 0.3, "{text}");
}
