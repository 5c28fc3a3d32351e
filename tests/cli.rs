//! The command line as a user runs it: the README's commands produce real
//! images of the requested size and format.

mod common;

#[test]
fn render_writes_png_exr_and_reference_images() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("gonio.png");
    let status = common::gonio()
        .args(["render", "-o"])
        .arg(&png)
        .args(["--width", "96", "--height", "64", "--timings"])
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let stdout = String::from_utf8_lossy(&status.stdout);
    assert!(stdout.contains("render pass"), "timings missing: {stdout}");
    let image = image::open(&png).unwrap().into_rgb8();
    assert_eq!(image.dimensions(), (96, 64));
    // The sphere is red: some pixel is clearly redder than it is green.
    assert!(
        image
            .pixels()
            .any(|p| p.0[0] as u16 > 2 * p.0[1] as u16 && p.0[0] > 100)
    );

    let exr = dir.path().join("model.exr");
    let model = common::gltf_asset("Suzanne/Suzanne.gltf");
    for reference in [false, true] {
        let mut cmd = common::gonio();
        cmd.arg("render").arg(&model).arg("-o").arg(&exr);
        cmd.args(["--shading", "gouraud", "--width", "64", "--height", "48"]);
        if reference {
            cmd.arg("--reference");
        }
        let out = cmd.output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let image = image::open(&exr).unwrap().into_rgb32f();
        assert_eq!(image.dimensions(), (64, 48));
        assert!(
            image.pixels().any(|p| p.0[0] > 0.0),
            "the model is not visible"
        );
    }
}

#[test]
fn verbose_names_the_adapter() {
    let dir = tempfile::tempdir().unwrap();
    let out = common::gonio()
        .args([
            "render",
            "--verbose",
            "--width",
            "32",
            "--height",
            "32",
            "-o",
        ])
        .arg(dir.path().join("v.png"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("adapter: "), "{stderr}");
    assert!(stderr.contains("shader: shading phong"), "{stderr}");
}

/// A key the material's model does not read is rendered without, with a
/// warning that names it and the model's parameters (`sigma_x`
/// on blinn-phong, `k_e` on lambert were once ignored without a word); keys
/// the model reads give no warning.
#[test]
fn keys_a_model_does_not_read_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let run = |sets: &[&str]| {
        let mut cmd = common::gonio();
        cmd.args(["render", "--width", "32", "--height", "24", "-o"])
            .arg(dir.path().join("w.png"));
        for s in sets {
            cmd.args(["--set", s]);
        }
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(
            out.status.success(),
            "{stderr}{}",
            common::LAVAPIPE_TEST_HINT
        );
        stderr
    };
    let stderr = run(&["materials.ball.sigma_x=0.3", "materials.floor.k_e=4"]);
    assert!(
        stderr.contains("materials.ball: `sigma_x` not read by model `blinn-phong` (its parameters: k_d, k_s, k_e)"),
        "{stderr}"
    );
    assert!(
        stderr.contains("materials.floor: `k_e` not read by model `lambert`"),
        "{stderr}"
    );
    let quiet = run(&["materials.ball.k_e=20"]);
    assert!(!quiet.contains("warning"), "{quiet}");
}

/// A glTF file's own material is addressable by its name in `--set`
/// (`--set materials.Suzanne.k_d` once failed): the edit changes the
/// render, a key its model does not read is named, a misspelt name gets
/// the nearest one.
#[test]
fn gltf_materials_are_edited_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let suzanne = common::gltf_asset("Suzanne/Suzanne.gltf");
    let render = |name: &str, sets: &[&str]| {
        let out_path = dir.path().join(name);
        let mut cmd = common::gonio();
        cmd.arg("render")
            .arg(&suzanne)
            .args(["--width", "64", "--height", "48", "-o"])
            .arg(&out_path);
        for s in sets {
            cmd.args(["--set", s]);
        }
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), stderr, std::fs::read(&out_path).ok())
    };
    let (code, stderr, plain) = render("plain.exr", &[]);
    assert_eq!(code, Some(0), "{stderr}{}", common::LAVAPIPE_TEST_HINT);
    let (code, stderr, edited) = render(
        "edited.exr",
        &[
            "materials.Suzanne.metallic=0",
            "materials.Suzanne.roughness=0.3",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert_ne!(plain, edited, "the edit did not change the render");
    let (code, stderr, _) = render("w.exr", &["materials.Suzanne.sigma_x=0.3"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("`sigma_x` not read by model `gltf-pbr`"),
        "{stderr}"
    );
    let (code, stderr, out) = render("typo.exr", &["materials.Suzane.metallic=0"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("no material `Suzane` (it has Suzanne); did you mean `Suzanne`?"),
        "{stderr}"
    );
    assert!(out.is_none());
}

/// A bare material shows its model (a `cook-torrance` with
/// `preset = "gold"` defaulted to `k_s = 0` and rendered as its diffuse
/// part only). The built-in scene's ball alone is lit (floor black), so
/// the image's brightest value is the ball's highlight.
#[test]
fn a_bare_material_shows_its_lobe() {
    let dir = tempfile::tempdir().unwrap();
    let render = |name: &str, ball: &str| {
        let exr = dir.path().join(format!("{name}.exr"));
        let out = common::gonio()
            .args(["render", "--width", "64", "--height", "48", "-o"])
            .arg(&exr)
            .args(["--set", &format!("materials.ball={{{ball}}}")])
            .args(["--set", "materials.floor={model = \"lambert\", k_d = 0}"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(
            out.status.success(),
            "{name}: {stderr}{}",
            common::LAVAPIPE_TEST_HINT
        );
        let image = image::open(&exr).unwrap().into_rgb32f();
        let peak = image.pixels().map(|p| p.0[0]).fold(0.0f32, f32::max);
        (image.into_raw(), peak, stderr)
    };
    // Gold: the defaults are a bare metal, the same image as k_d = 0,
    // k_s = 1 given (the same material, so the same GPU arithmetic).
    let (bare, bare_peak, _) = render("bare", r#"model = "cook-torrance", preset = "gold""#);
    let (given, _, _) = render(
        "given",
        r#"model = "cook-torrance", preset = "gold", k_d = 0, k_s = 1"#,
    );
    assert!(bare == given, "bare gold differs from k_d = 0, k_s = 1");
    // The lobe is lit: the point light (60 W/sr, about 4.8 m away)
    // reflected by gold's F0 = 0.85 at roughness 0.3 gives a radiance of
    // order 1 at the highlight; the diffuse-only ball, whose k_d is 0,
    // gives nothing at all (next).
    assert!(bare_peak > 0.5, "bare gold's highlight: {bare_peak}");
    // k_s = 0 given is honoured, and silently: diffuse only, here black.
    let (_, off_peak, off_stderr) = render(
        "off",
        r#"model = "cook-torrance", preset = "gold", k_s = 0"#,
    );
    assert_eq!(off_peak, 0.0);
    assert!(!off_stderr.contains("k_s"), "{off_stderr}");
    // Phong and Ward: half diffuse, half lobe. Their highlight rises well
    // above the brightest diffuse point of the same k_d = 0.5 (the
    // lecture's Phong peaks at k_s/(I·N) ≥ 0.5 /sr, Ward's lobe of σ = 0.2
    // at about 1/sr, Lambert's k_d/π = 0.16 /sr: at least 3×).
    let (_, diffuse_peak, _) = render("lambert", r#"model = "lambert", k_d = 0.5"#);
    for model in ["phong", "ward"] {
        let (_, peak, _) = render(model, &format!("model = \"{model}\""));
        assert!(
            peak > 2.0 * diffuse_peak,
            "{model}: peak {peak} vs diffuse {diffuse_peak}"
        );
    }
}
