//! The viewer in a real window under Xvfb (lavapipe draws it): it opens,
//! renders, screenshots and exits 0; its 3D area matches `gonio render` of
//! the same scene and state; scripted panel edits reach the shader.
//!
//! Tolerance, derived: the viewer and `render` run the same generated
//! shader on the same rasterizer with the same f32 camera matrix; only the
//! last step differs: the viewer encodes sRGB in f32 in the shader
//! (`target_output`, WGSL `pow`, a few ULP) and the unorm store rounds,
//! where `render` encodes in f64 and rounds on the CPU. An error of a few
//! ULP (≈ 10⁻⁶ of full scale, 3·10⁻⁴ of a level) can only move a value
//! across a rounding boundary: every channel may differ by at most 1 level
//! of 255, and only rarely (asserted: under 1 % of the pixels).

#![cfg(feature = "viewer")]

mod common;

use std::path::Path;

/// Runs `gonio view ARGS --screenshot PATH`; returns the 3D area
/// `(x, y, w, h)` it reports.
fn view(args: &[&str], screenshot: &Path) -> (u32, u32, u32, u32) {
    view_with_output(args, screenshot).0
}

/// [`view`], with what it printed.
fn view_with_output(args: &[&str], screenshot: &Path) -> ((u32, u32, u32, u32), String) {
    let gonio = common::gonio();
    let out = common::xvfb()
        .arg(gonio.get_program())
        .arg("view")
        .args(args)
        .arg("--screenshot")
        .arg(screenshot)
        .output()
        .expect("xvfb-run runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "gonio view {args:?} failed ({:?}): {stderr}{}",
        out.status.code(),
        common::LAVAPIPE_TEST_HINT
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let line = stdout
        .lines()
        .find(|l| l.contains("3D area"))
        .unwrap_or_else(|| panic!("no 3D area reported: {stdout}"));
    let area = line.split("3D area ").nth(1).unwrap();
    let nums: Vec<u32> = area
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    ((nums[0], nums[1], nums[2], nums[3]), stdout.into_owned())
}

fn render(args: &[&str], width: u32, height: u32, out: &Path) {
    let result = common::gonio()
        .arg("render")
        .args(args)
        .args([
            "--width",
            &width.to_string(),
            "--height",
            &height.to_string(),
        ])
        .arg("-o")
        .arg(out)
        .output()
        .expect("gonio runs");
    assert!(
        result.status.success(),
        "gonio render failed: {}",
        String::from_utf8_lossy(&result.stderr)
    );
}

/// Largest channel difference and the fraction of pixels that differ,
/// between `shot`'s area `(x, y, w, h)` and `reference`.
fn difference(shot: &Path, area: (u32, u32, u32, u32), reference: &Path) -> (u8, f64) {
    let shot = image::open(shot).unwrap().to_rgb8();
    let reference = image::open(reference).unwrap().to_rgb8();
    let (x, y, w, h) = area;
    assert_eq!(reference.dimensions(), (w, h));
    let (mut max, mut differing) = (0u8, 0usize);
    for j in 0..h {
        for i in 0..w {
            let a = shot.get_pixel(x + i, y + j).0;
            let b = reference.get_pixel(i, j).0;
            let d = (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap();
            max = max.max(d);
            differing += (d > 0) as usize;
        }
    }
    (max, differing as f64 / (w * h) as f64)
}

fn assert_matches(shot: &Path, area: (u32, u32, u32, u32), reference: &Path, what: &str) {
    let (max, fraction) = difference(shot, area, reference);
    eprintln!(
        "{what}: max difference {max} levels, {:.3} % of the pixels differ",
        100.0 * fraction
    );
    if max <= 1 && fraction < 0.01 {
        return;
    }
    let dir = save_failure(shot, area, reference, what);
    panic!(
        "{what}: the viewer's 3D area differs from `gonio render` by up to {max} levels in {:.3} % of the pixels (allowed: 1 level, under 1 %)\nactual, expected and difference images in {}",
        100.0 * fraction,
        dir.display()
    );
}

/// Saves the screenshot's 3D area (`actual.png`), the render
/// (`expected.png`) and their difference scaled so that the largest is
/// white (`difference.png`) for a failed comparison; returns the folder.
fn save_failure(
    shot: &Path,
    (x, y, w, h): (u32, u32, u32, u32),
    reference: &Path,
    what: &str,
) -> std::path::PathBuf {
    let dir = common::failure_dir(&format!("viewer-{what}"));
    std::fs::create_dir_all(&dir).unwrap();
    let actual =
        image::imageops::crop_imm(&image::open(shot).unwrap().to_rgb8(), x, y, w, h).to_image();
    let expected = image::open(reference).unwrap().to_rgb8();
    let max = actual
        .pixels()
        .zip(expected.pixels())
        .flat_map(|(a, b)| (0..3).map(move |c| a.0[c].abs_diff(b.0[c])))
        .max()
        .unwrap_or(0)
        .max(1);
    let difference = image::RgbImage::from_fn(w, h, |i, j| {
        let (a, b) = (actual.get_pixel(i, j).0, expected.get_pixel(i, j).0);
        image::Rgb([0, 1, 2].map(|c| (a[c].abs_diff(b[c]) as u32 * 255 / max as u32) as u8))
    });
    actual.save(dir.join("actual.png")).unwrap();
    expected.save(dir.join("expected.png")).unwrap();
    difference.save(dir.join("difference.png")).unwrap();
    dir
}

#[test]
fn the_viewer_screenshot_matches_render() {
    let dir = tempfile::tempdir().unwrap();
    let bench_scene = format!(
        "{}/assets/scenes/viewer-bench.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    // The window filled by the 3D view, and a window with the panel.
    for (name, args) in [
        (
            "full",
            vec![
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
            ],
        ),
        (
            "panel",
            vec!["--size", "720x400", "--frames", "3", "--no-overlay"],
        ),
        (
            "gouraud-shadows",
            vec![
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
                "--set",
                "shading.mode=\"gouraud\"",
                "--set",
                "lights.0.shadows=true",
            ],
        ),
        (
            // Phong with one shadowed directional light: the shadow-map
            // coordinates are computed per vertex (de-indexed stream).
            "directional-shadows",
            vec![
                bench_scene.as_str(),
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
            ],
        ),
        // Each tone map in the window as in a PNG, with
        // a light bright enough that the clamp would clip the ball and
        // the floor (the operators' f32 twin in common.wgsl against the
        // f64 one in src/output/tone_map.rs: a few ULP, as the encoding).
        (
            "reinhard",
            vec![
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
                "--set",
                "image.tone_map=\"reinhard\"",
                "--set",
                "lights.0.intensity=[400,400,400]",
            ],
        ),
        (
            "aces",
            vec![
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
                "--set",
                "image.tone_map=\"aces\"",
                "--set",
                "lights.0.intensity=[400,400,400]",
            ],
        ),
        (
            "pbr-neutral",
            vec![
                "--size",
                "320x240",
                "--no-panel",
                "--frames",
                "3",
                "--no-overlay",
                "--set",
                "image.tone_map=\"pbr-neutral\"",
                "--set",
                "lights.0.intensity=[400,400,400]",
            ],
        ),
    ] {
        let shot = dir.path().join(format!("{name}.png"));
        let (x, y, w, h) = view(&args, &shot);
        assert!(w >= 100 && h >= 100, "{name}: 3D area {w}x{h}");
        let scene = args.iter().copied().filter(|a| a.ends_with(".toml"));
        let sets: Vec<&str> = scene
            .chain(
                args.windows(2)
                    .filter(|p| p[0] == "--set")
                    .flat_map(|p| ["--set", p[1]]),
            )
            .collect();
        let reference = dir.path().join(format!("{name}-render.png"));
        render(&sets, w, h, &reference);
        assert_matches(&shot, (x, y, w, h), &reference, name);
    }
}

/// Edits made at frame 3 (after the scene is on the GPU) go through the
/// panel's path: a value change (buffer write), a model change (another
/// pipeline), a light change (reload, shadow maps re-planned). The result
/// must equal `render` with the same values set, and differ from the
/// unedited image.
#[test]
fn scripted_panel_edits_reach_the_shader() {
    let dir = tempfile::tempdir().unwrap();
    let edits = [
        "materials.ball.k_d=[0.1, 0.2, 0.9]",
        "materials.floor.model=\"phong\"",
        "lights.0.shadows=true",
        // The tone map is compiled in (the constant TONE_MAP): a new one
        // takes another pipeline.
        "image.tone_map=\"aces\"",
    ];
    let mut args = vec![
        "--size",
        "320x240",
        "--no-panel",
        "--no-overlay",
        "--frames",
        "6",
    ];
    // Frame 5 moves the shadowed light after its maps were drawn: the maps
    // keep their array and take the new views (src/gpu/shadow_maps.rs
    // `write_plan`), and must show the moved light's shadows.
    let moved = "lights.0.position=[-2.0, 4.0, 2.5]";
    let mut scripted: Vec<String> = edits.iter().map(|e| format!("3:{e}")).collect();
    scripted.push(format!("5:{moved}"));
    for e in &scripted {
        args.extend(["--edit", e.as_str()]);
    }
    let shot = dir.path().join("edited.png");
    let area = view(&args, &shot);
    let sets: Vec<&str> = edits
        .iter()
        .chain([&moved])
        .flat_map(|e| ["--set", *e])
        .collect();
    let edited = dir.path().join("edited-render.png");
    render(&sets, area.2, area.3, &edited);
    assert_matches(&shot, area, &edited, "edited");
    let plain = dir.path().join("plain-render.png");
    render(&[], area.2, area.3, &plain);
    let (max, fraction) = difference(&shot, area, &plain);
    assert!(
        max > 50 && fraction > 0.05,
        "the edits changed too little: {max} levels in {:.1} % of the pixels",
        100.0 * fraction
    );
}

/// A broken file dropped on the window: the viewer says why and keeps the
/// scene it shows (untrusted input in the viewer).
#[test]
fn a_bad_file_dropped_on_the_window_keeps_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("dropped.glb");
    std::fs::write(&broken, b"glTF\x02\x00\x00\x00\xff\xff\xff\xff").unwrap();
    let drop = format!("2:{}", broken.display());
    let shot = dir.path().join("after-drop.png");
    let gonio = common::gonio();
    let out = common::xvfb()
        .arg(gonio.get_program())
        .arg("view")
        .args([
            "--size",
            "320x240",
            "--no-panel",
            "--no-overlay",
            "--frames",
            "5",
        ])
        .args(["--drop", &drop, "--screenshot"])
        .arg(&shot)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stderr.contains("gonio view: ") && stderr.contains("dropped.glb"),
        "the drop's error is not reported: {stderr}"
    );
    let reference = dir.path().join("scene.png");
    render(&[], 320, 240, &reference);
    assert_matches(&shot, (0, 0, 320, 240), &reference, "after a bad drop");
}

/// Resizing (to a sliver and back) and minimizing never panic; the last
/// frame still matches `render` at the final size.
#[test]
fn resizing_and_minimizing_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("resized.png");
    let area = view(
        &[
            "--size",
            "320x240",
            "--no-panel",
            "--no-overlay",
            "--frames",
            "14",
            "--resize",
            "2:16x16",
            "--resize",
            "4:0x0",
            "--resize",
            "6:400x200",
            "--resize",
            "9:300x220",
        ],
        &shot,
    );
    let reference = dir.path().join("resized-render.png");
    render(&[], area.2, area.3, &reference);
    assert_matches(&shot, area, &reference, "resized");
}

/// Bad input to the viewer: one paragraph, exit 2, no window needed.
#[test]
fn the_viewer_refuses_bad_input_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("broken.gltf");
    std::fs::write(&broken, "{ not json").unwrap();
    for args in [
        vec![broken.to_str().unwrap().to_string()],
        vec!["--set".into(), "materials.ball.roughness=-1".into()],
        vec![
            "--frames".into(),
            "2".into(),
            "--edit".into(),
            "1:materials.nope.k_d=1".into(),
        ],
        vec!["--exit-when-idle".into(), "0".into()],
        vec![
            "--exit-when-idle".into(),
            "1".into(),
            "--frames".into(),
            "5".into(),
        ],
        // A glTF without lights has no [[lights]] entry to move.
        vec![
            format!("{}/assets/gltf/Box/Box.gltf", env!("CARGO_MANIFEST_DIR")),
            "--frames".into(),
            "2".into(),
            "--spin-lights".into(),
            "1".into(),
        ],
    ] {
        let out = common::xvfb()
            .arg(common::gonio().get_program())
            .arg("view")
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        let errors: Vec<_> = stderr
            .lines()
            .filter(|l| l.starts_with("gonio: error:"))
            .collect();
        assert_eq!(errors.len(), 1, "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// A material key its model does not read is named as `render` names it
/// (`image.msaa = 4`, once refused with a word, is drawn now:
/// `the_viewer_draws_msaa`).
#[test]
fn the_viewer_says_what_it_does_not_apply() {
    let gonio = common::gonio();
    let out = common::xvfb()
        .arg(gonio.get_program())
        .args(["view", "--frames", "2", "--size", "320x200"])
        .args(["--set", "image.msaa=4", "--set", "materials.floor.k_e=4"])
        .output()
        .expect("xvfb-run runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{stderr}{}",
        common::LAVAPIPE_TEST_HINT
    );
    assert!(!stderr.contains("image.msaa"), "{stderr}");
    assert!(
        stderr.contains("materials.floor: `k_e` not read by model `lambert`"),
        "{stderr}"
    );
}

/// The viewer draws only when something changes. With no
/// input, `--exit-when-idle 1` ends the run once a full second passed
/// without a frame and the panel's background plots are done and shown
/// (so the worker's result must have woken the window); a viewer that
/// kept drawing (60 frames a second before this change) never gets there
/// and fails after 60 s. The frames before the idle spell are the start:
/// egui's first passes, the first plots, the worker's result; far fewer
/// than one second of continuous drawing.
#[test]
fn the_idle_viewer_draws_no_frames() {
    let gonio = common::gonio();
    for extra in [
        vec![],
        vec!["--no-panel"],
        // A narrow anisotropic lobe: the albedo worker takes longest.
        vec![
            "--set",
            "materials.ball.model=\"ward-anisotropic\"",
            "--set",
            "materials.ball.sigma_x=0.02",
            "--set",
            "materials.ball.sigma_y=0.4",
        ],
    ] {
        let out = common::xvfb()
            .arg(gonio.get_program())
            .args(["view", "--size", "800x500", "--exit-when-idle", "1"])
            .args(&extra)
            .output()
            .expect("xvfb-run runs");
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success(),
            "{extra:?}: {stdout}{stderr}{}",
            common::LAVAPIPE_TEST_HINT
        );
        let line = stdout
            .lines()
            .find(|l| l.starts_with("idle: "))
            .unwrap_or_else(|| panic!("{extra:?}: no idle report: {stdout}"));
        let frames: u64 = line
            .split_whitespace()
            .nth(1)
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{line}"));
        assert!(
            (1..=30).contains(&frames),
            "{extra:?}: {frames} frames before the idle spell: {line}"
        );
        let quiet: f64 = line
            .rsplit("none for ")
            .next()
            .and_then(|t| t.trim_end_matches(" s").parse().ok())
            .unwrap_or_else(|| panic!("{line}"));
        assert!(quiet >= 1.0, "{line}");
    }
}

/// The environment map's keys go the panel's way
/// too. `--edit 3:environment.sh_order=4` on a scene loaded at order 0
/// redraws with the new SH irradiance (the same image as `render` at order
/// 4, and visibly not the order-0 one: the sky's sun lights the Lambert
/// sphere from one side only from band 1 up); a `.hdr` dropped on the
/// window becomes the map (as `render --set environment.map=...`); and
/// `environment.enabled=false` switches it off (as the file without its
/// `[environment]`, which then gets the default light).
#[test]
fn environment_edits_and_drops_reach_the_shader() {
    let dir = tempfile::tempdir().unwrap();
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let scene = root.join("assets/scenes/environment.toml");
    let scene = scene.to_str().unwrap();
    let base = [
        scene,
        "--set",
        "environment.sh_order=0",
        "--size",
        "320x240",
        "--no-panel",
        "--no-overlay",
        "--frames",
        "6",
    ];
    let shot = dir.path().join("order4.png");
    let mut args = base.to_vec();
    args.extend(["--edit", "3:environment.sh_order=4"]);
    let area = view(&args, &shot);
    let order4 = dir.path().join("order4-render.png");
    render(
        &[scene, "--set", "environment.sh_order=4"],
        area.2,
        area.3,
        &order4,
    );
    assert_matches(&shot, area, &order4, "environment sh_order edit");
    let order0 = dir.path().join("order0-render.png");
    render(
        &[scene, "--set", "environment.sh_order=0"],
        area.2,
        area.3,
        &order0,
    );
    let (max, fraction) = difference(&shot, area, &order0);
    eprintln!(
        "order 4 against order 0: {max} levels in {:.1} % of the pixels",
        100.0 * fraction
    );
    assert!(
        max > 20 && fraction > 0.02,
        "the SH order changed too little: {max} levels in {:.1} % of the pixels",
        100.0 * fraction
    );

    let blobs = root.join("assets/environment/blobs.hdr");
    let drop = format!("3:{}", blobs.display());
    let shot = dir.path().join("dropped.png");
    let mut args = base.to_vec();
    args.extend(["--drop", drop.as_str()]);
    let area = view(&args, &shot);
    let set = format!("environment.map=\"{}\"", blobs.display());
    let dropped = dir.path().join("dropped-render.png");
    render(
        &[scene, "--set", "environment.sh_order=0", "--set", &set],
        area.2,
        area.3,
        &dropped,
    );
    assert_matches(&shot, area, &dropped, "environment map dropped");

    let shot = dir.path().join("off.png");
    let mut args = base.to_vec();
    args.extend(["--edit", "3:environment.enabled=false"]);
    let area = view(&args, &shot);
    let off = dir.path().join("off-render.png");
    let no_map = dir.path().join("no-map.toml");
    let text = std::fs::read_to_string(scene).unwrap();
    let text = text.split("\n[environment]").next().unwrap().to_string();
    std::fs::write(&no_map, text).unwrap();
    render(&[no_map.to_str().unwrap()], area.2, area.3, &off);
    assert_matches(&shot, area, &off, "environment map switched off");
}

/// Lights added and retyped through the panel's path
/// (`--edit lights.add=KIND`, `lights.N.kind=KIND`) reach the GPU, shadow
/// maps included. A narrow shadowed spot added at frame 3 and aimed at the
/// floor left of the ball: the image equals `render` with that light
/// written in the file; the floor at the spot's aim point brightens and
/// the floor to the right of the ball, outside the cone, does not change.
/// Retyped to a point light at frame 5 (same place and intensity): equals
/// `render` with a point light there; the aim point, inside the inner
/// cone where the spot gave its full intensity, keeps its value (to one
/// level: another shader sums the same terms), and the floor outside the
/// cone now brightens.
#[test]
fn lights_added_and_retyped_in_the_viewer_reach_the_shader() {
    use glam::{DVec2, DVec3};
    use gonio::ui::lights::projection::ScreenProjection;
    let dir = tempfile::tempdir().unwrap();
    let (position, aim) = (DVec3::new(-2.0, 2.5, 2.5), DVec3::new(-1.5, 0.0, 1.5));
    let outside = DVec3::new(1.5, 0.0, 1.5);
    let direction = aim - position;
    let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
    let spot_keys = [
        format!("position={}", v(position)),
        format!("direction={}", v(direction)),
        "intensity=[20.0, 20.0, 20.0]".to_string(),
        "inner_cone_deg=10.0".to_string(),
        "outer_cone_deg=14.0".to_string(),
        "shadows=true".to_string(),
    ];
    let base = [
        "--size",
        "320x240",
        "--no-panel",
        "--no-overlay",
        "--frames",
        "8",
    ];
    let mut edits = vec!["3:lights.add=spot".to_string()];
    edits.extend(spot_keys.iter().map(|k| format!("3:lights.1.{k}")));
    let with_edits = |edits: &[String]| {
        let mut args: Vec<&str> = base.to_vec();
        for e in edits {
            args.extend(["--edit", e.as_str()]);
        }
        args.iter().map(|s| s.to_string()).collect::<Vec<String>>()
    };
    let point = "{kind = \"point\", position = [3.0, 5.0, 3.0], intensity = [60.0, 60.0, 60.0]}";
    let lights = |second: String| format!("lights=[{point}, {second}]");
    let spot_file = lights(format!(
        "{{kind = \"spot\", position = {}, direction = {}, intensity = [20.0, 20.0, 20.0], inner_cone_deg = 10.0, outer_cone_deg = 14.0, shadows = true}}",
        v(position),
        v(direction)
    ));
    let point_file = lights(format!(
        "{{kind = \"point\", position = {}, intensity = [20.0, 20.0, 20.0], shadows = true}}",
        v(position)
    ));

    let spot_shot = dir.path().join("spot.png");
    let args = with_edits(&edits);
    let area = view(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
        &spot_shot,
    );
    let spot_render = dir.path().join("spot-render.png");
    render(&["--set", &spot_file], area.2, area.3, &spot_render);
    assert_matches(&spot_shot, area, &spot_render, "spot added");

    edits.push("5:lights.1.kind=point".to_string());
    let point_shot = dir.path().join("point.png");
    let args = with_edits(&edits);
    let area2 = view(
        &args.iter().map(String::as_str).collect::<Vec<_>>(),
        &point_shot,
    );
    assert_eq!(area, area2);
    let point_render = dir.path().join("point-render.png");
    render(&["--set", &point_file], area.2, area.3, &point_render);
    assert_matches(&point_shot, area, &point_render, "spot retyped to point");

    let plain = dir.path().join("plain-render.png");
    render(&[], area.2, area.3, &plain);
    // Mean of a 5 × 5 patch around the screen point of `p`.
    let camera = gonio::ui::document::Document::load(
        gonio::scene::scene_file::SceneSource::BuiltIn,
        vec![],
        gonio::scene::limits::Limits::default(),
    )
    .unwrap()
    .scene
    .camera;
    let proj = ScreenProjection::new(
        &camera,
        DVec2::ZERO,
        DVec2::new(area.2 as f64, area.3 as f64),
    );
    let patch = |png: &Path, offset: (u32, u32), p: DVec3| -> f64 {
        let img = image::open(png).unwrap().to_luma8();
        let s = proj.project(p).unwrap();
        let (cx, cy) = (s.x as i64, s.y as i64);
        let mut sum = 0.0;
        for dy in -2..=2 {
            for dx in -2..=2 {
                let px = (cx + dx) as u32 + offset.0;
                let py = (cy + dy) as u32 + offset.1;
                sum += img.get_pixel(px, py).0[0] as f64;
            }
        }
        sum / 25.0
    };
    let at = (area.0, area.1);
    let (plain_aim, plain_out) = (patch(&plain, (0, 0), aim), patch(&plain, (0, 0), outside));
    let (spot_aim, spot_out) = (patch(&spot_shot, at, aim), patch(&spot_shot, at, outside));
    let (point_aim, point_out) = (patch(&point_shot, at, aim), patch(&point_shot, at, outside));
    eprintln!(
        "aim point: {plain_aim:.1} → spot {spot_aim:.1} → point {point_aim:.1}; outside the cone: {plain_out:.1} → {spot_out:.1} → {point_out:.1}"
    );
    assert!(
        spot_aim > plain_aim + 40.0,
        "the spot's pool did not brighten"
    );
    assert!(
        (spot_out - plain_out).abs() <= 1.0,
        "the spot lit outside its cone"
    );
    assert!(
        (point_aim - spot_aim).abs() <= 1.0,
        "inside the cone the point light differs"
    );
    assert!(
        point_out > spot_out + 8.0,
        "the point light did not light outside the cone"
    );
}

/// Largest channel difference and the fraction of differing pixels between
/// the `(w, h)` rectangles of `a` at `pa` and `b` at `pb`.
fn region_difference(
    a: &image::RgbImage,
    pa: (u32, u32),
    b: &image::RgbImage,
    pb: (u32, u32),
    (w, h): (u32, u32),
) -> (u8, f64) {
    let (mut max, mut differing) = (0u8, 0usize);
    for j in 0..h {
        for i in 0..w {
            let p = a.get_pixel(pa.0 + i, pa.1 + j).0;
            let q = b.get_pixel(pb.0 + i, pb.1 + j).0;
            let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap();
            max = max.max(d);
            differing += (d > 0) as usize;
        }
    }
    (max, differing as f64 / (w * h) as f64)
}

/// Compare mode: `--compare SPEC` splits the 3D view. Its left
/// half is the scene as `gonio render` draws it, its right half the scene
/// with the selected material (the ball) replaced by the compared one,
/// both within the viewer's derived tolerance (1 level, under 1 % of the
/// pixels); an `--edit` of the compared material changes its half and
/// leaves the other's pixels exactly as they were.
#[test]
fn compare_mode_splits_the_view_and_an_edit_changes_only_its_half() {
    let dir = tempfile::tempdir().unwrap();
    let base = [
        "--size",
        "320x240",
        "--no-panel",
        "--no-overlay",
        "--frames",
        "6",
        "--compare",
        "lambert,k_d=[0.8, 0.8, 0.8]",
    ];
    let plain = dir.path().join("split.png");
    let area = view(&base, &plain);
    let edited = dir.path().join("split-edited.png");
    let mut args = base.to_vec();
    args.extend(["--edit", "3:compare.0.k_d=[0.1, 0.2, 0.9]"]);
    assert_eq!(view(&args, &edited), area);
    let (x, y, w, h) = area;
    let half = w / 2;
    let (left, right) = (
        ((x, y), (0, 0), (half, h)),
        ((x + half, y), (half, 0), (w - half, h)),
    );
    let plain = image::open(&plain).unwrap().to_rgb8();
    let edited = image::open(&edited).unwrap().to_rgb8();

    let (max, _) = region_difference(&plain, left.0, &edited, left.0, left.2);
    assert_eq!(
        max, 0,
        "the edit of the compared material changed the left half"
    );
    let (max, fraction) = region_difference(&plain, right.0, &edited, right.0, right.2);
    eprintln!(
        "right half, before and after the edit: {max} levels in {:.1} % of its pixels",
        100.0 * fraction
    );
    assert!(
        max > 50 && fraction > 0.05,
        "the edit changed the right half too little: {max} levels in {:.1} % of the pixels",
        100.0 * fraction
    );

    let scene_a = dir.path().join("a.png");
    render(&[], w, h, &scene_a);
    let scene_a = image::open(&scene_a).unwrap().to_rgb8();
    let scene_b = dir.path().join("b.png");
    render(
        &[
            "--set",
            "materials.ball={model = \"lambert\", k_d = [0.1, 0.2, 0.9]}",
        ],
        w,
        h,
        &scene_b,
    );
    let scene_b = image::open(&scene_b).unwrap().to_rgb8();
    for (what, shot, reference, (at, from, size)) in [
        ("left half", &plain, &scene_a, left),
        ("right half", &edited, &scene_b, right),
    ] {
        let (max, fraction) = region_difference(shot, at, reference, from, size);
        eprintln!(
            "{what} against gonio render: {max} levels, {:.3} % of the pixels differ",
            100.0 * fraction
        );
        assert!(
            max <= 1 && fraction < 0.01,
            "{what}: {max} levels in {:.3} % of the pixels (allowed: 1 level, under 1 %)",
            100.0 * fraction
        );
    }
}

/// `--compare-fit` needs a measured first material, and names the fix.
#[test]
fn compare_fit_of_an_unmeasured_material_is_refused() {
    let out = common::gonio()
        .args(["view", "--compare-fit", "ward", "--frames", "1"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("not measured") && stderr.contains("materials.ball.model=measured"),
        "{stderr}"
    );
    let out = common::gonio()
        .args(["view", "--compare-fit", "phonk", "--frames", "1"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("ct-ggx-conductor"), "{stderr}");
}

/// `image.msaa = 4` in the viewer (once ignored): the scene
/// pass draws four samples and resolves them into the window. Against the
/// one-sample screenshot, every pixel whose 3×3 neighbourhood there is
/// flat (within 1 level: no edge crosses it, so all four samples see the
/// same surface and the shading at the pixel centre) is unchanged within
/// the 1 level of rounding, and the silhouettes change (antialiased: at
/// least 100 pixels by more than 1 level).
#[test]
fn the_viewer_draws_msaa() {
    let dir = tempfile::tempdir().unwrap();
    let shot = |msaa: u32| {
        let path = dir.path().join(format!("msaa{msaa}.png"));
        let set = format!("image.msaa={msaa}");
        let args = [
            "--size",
            "320x240",
            "--no-panel",
            "--frames",
            "3",
            "--no-overlay",
            "--set",
            &set,
        ];
        let area = view(&args, &path);
        let img = image::open(&path).unwrap().to_rgb8();
        (area, img)
    };
    let ((x, y, w, h), one) = shot(1);
    let (area4, four) = shot(4);
    assert_eq!(area4, (x, y, w, h));
    let level = |img: &image::RgbImage, i: u32, j: u32, c: usize| {
        i32::from(img.get_pixel(x + i, y + j).0[c])
    };
    let (mut flat_changed, mut edges_changed) = (0, 0);
    for j in 1..h - 1 {
        for i in 1..w - 1 {
            let d = (0..3)
                .map(|c| (level(&one, i, j, c) - level(&four, i, j, c)).abs())
                .max()
                .unwrap();
            let flat = (0..3).all(|c| {
                let centre = level(&one, i, j, c);
                (-1..=1).all(|dj: i32| {
                    (-1..=1).all(|di: i32| {
                        let v = level(
                            &one,
                            i.wrapping_add_signed(di),
                            j.wrapping_add_signed(dj),
                            c,
                        );
                        (v - centre).abs() <= 1
                    })
                })
            });
            if flat && d > 1 {
                flat_changed += 1;
            }
            if !flat && d > 1 {
                edges_changed += 1;
            }
        }
    }
    eprintln!(
        "msaa 4 vs 1: {edges_changed} edge pixels changed, {flat_changed} flat pixels changed"
    );
    assert_eq!(flat_changed, 0, "MSAA changed pixels away from edges");
    assert!(
        edges_changed >= 100,
        "MSAA left the silhouettes as they were ({edges_changed} pixels changed)"
    );
}

/// The θ_h × θ_d image in the panel: with a pinned readout point
/// (`plots.probe`, at a φ_d other than the default), the viewer prints
/// per material, once its image is current, f_r at that point and the
/// image's value in the cell holding it. Both must be the f64 functions
/// of `gonio brdf --plot-halfdiff` (explore::halfdiff) bit for bit: the
/// same code on the same inputs (the test parses the same degrees and
/// converts them as the viewer does). The run ends by `--exit-when-idle`,
/// so only after the images were computed and shown.
#[test]
fn the_halfdiff_image_reads_out_f_r_where_the_parameterization_says() {
    use gonio::explore::halfdiff::{cell_centre, directions, f_r_at};
    let specs = [
        "cook-torrance,k_d=0.1,k_s=1,roughness=0.2,preset=gold-rgb",
        "ward,k_d=0.2,k_s=0.3,sigma_x=0.1,sigma_y=0.3",
    ];
    let (th, td, pd) = (20.25_f64, 40.5_f64, 60.0_f64);
    let out = common::xvfb()
        .arg(common::gonio().get_program())
        .args(["view", "--size", "900x700", "--exit-when-idle", "0.5"])
        .args(["--compare", specs[0], "--compare", specs[1]])
        .args(["--edit", &format!("0:plots.probe={th},{td}")])
        .args(["--edit", &format!("0:plots.phi_d={pd}")])
        .output()
        .expect("xvfb-run runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{stdout}{stderr}{}",
        common::LAVAPIPE_TEST_HINT
    );
    let numbers = |line: &str, key: &str| -> Vec<f64> {
        let rest = line.split(&format!(" {key}=")).nth(1).unwrap();
        let rest = rest.trim_start_matches(['[', '(']);
        let end = rest.find([']', ')']).unwrap();
        rest[..end]
            .split(',')
            .map(|v| v.trim().parse().unwrap())
            .collect()
    };
    for (k, spec) in specs.iter().enumerate() {
        let series = k + 1;
        let line = stdout
            .lines()
            .find(|l| l.starts_with(&format!("halfdiff probe {series}:")))
            .unwrap_or_else(|| panic!("no readout of series {series}: {stdout}{stderr}"));
        let m = gonio::explore::spec::compare_spec(spec, &[])
            .unwrap()
            .material
            .with_roughness_floor(0.0);
        let f = f_r_at(&m, th.to_radians(), td.to_radians(), pd.to_radians());
        assert_eq!(numbers(line, "f_r"), vec![f.x, f.y, f.z], "{line}");
        let cell = numbers(line, "cell");
        let (i, j) = (cell[0] as usize, cell[1] as usize);
        assert_eq!((i, j), (20, 40), "{line}");
        let (wi, wo) = directions(cell_centre(i), cell_centre(j), pd.to_radians());
        let c = m.f_r(wi, wo, &gonio::explore::frame());
        assert_eq!(numbers(line, "cell_f_r"), vec![c.x, c.y, c.z], "{line}");
        assert_ne!(c, f, "the cell's centre is not the probed point");
    }
    assert!(stdout.contains("halfdiff probe 0:"), "{stdout}");
}

/// The material variant chosen in the viewer (`--edit N:gltf.variant=NAME`,
/// the panel's combo box: the scene loaded again in that variant) is drawn
/// as `gonio render --set gltf.variant=NAME` draws it, and not as the
/// file's own material; a variant the file does not have is refused with
/// exit 2, naming the file's variants.
#[test]
fn a_material_variant_chosen_in_the_viewer_is_drawn() {
    let dir = tempfile::tempdir().unwrap();
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/variants/variants.toml"
    );
    let shot = dir.path().join("variant.png");
    let choice = "gltf.variant=\"red coat\"";
    let edit = format!("3:{choice}");
    let area = view(
        &[
            scene,
            "--size",
            "320x240",
            "--no-panel",
            "--no-overlay",
            "--frames",
            "6",
            "--edit",
            &edit,
        ],
        &shot,
    );
    let chosen = dir.path().join("chosen-render.png");
    render(&[scene, "--set", choice], area.2, area.3, &chosen);
    assert_matches(&shot, area, &chosen, "variant");
    let own = dir.path().join("own-render.png");
    render(&[scene], area.2, area.3, &own);
    let (max, fraction) = difference(&shot, area, &own);
    assert!(
        max > 50 && fraction > 0.2,
        "the variant changed too little: {max} levels in {:.1} % of the pixels",
        100.0 * fraction
    );
    let out = common::xvfb()
        .arg(common::gonio().get_program())
        .arg("view")
        .args([scene, "--frames", "3", "--edit", "1:gltf.variant=green"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("\"green\"") && stderr.contains("\"red coat\", \"blue\""),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// `(calls, bytes)` of kind `kind` in the later frames' uploads that
/// `gonio view --frame-times` prints (`uploads: … later frames …: geometry
/// 0 (0 B), …`), and the later frames' total calls.
fn later_uploads(stdout: &str, kind: &str) -> ((u64, u64), u64) {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("uploads:"))
        .unwrap_or_else(|| panic!("no uploads line: {stdout}"));
    let later = line.split("later frames ").nth(1).unwrap();
    let total: u64 = later.split(' ').next().unwrap().parse().unwrap();
    let kinds = later.split_once(": ").unwrap().1;
    let entry = kinds
        .split(", ")
        .find(|e| e.starts_with(&format!("{kind} ")))
        .unwrap_or_else(|| panic!("no kind `{kind}` in {line}"));
    let numbers: Vec<u64> = entry
        .split(|c: char| !c.is_ascii_digit())
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect();
    ((numbers[0], numbers[1]), total)
}

/// A material slider on a textured glTF with a shadowed light writes that
/// material's record (one call, under a kilobyte) and nothing else: not
/// the vertex stream, not the 2048² textures (134 MB as half floats), no
/// shadow map drawn again; and the image is `gonio render`'s with the same
/// value. A light move writes the lights and the shadow views and draws
/// the map again, nothing of the geometry or the textures; a shading-mode
/// switch (another vertex stream) does upload the geometry, so the count
/// is not blind.
#[test]
fn a_material_edit_on_a_textured_gltf_uploads_only_its_record() {
    let dir = tempfile::tempdir().unwrap();
    let avocado = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/gltf/Avocado/Avocado.gltf"
    );
    let light = "lights=[{kind = \"directional\", direction = [-0.4, -1.0, -0.3], irradiance = [3.0, 3.0, 3.0], shadows = true}]";
    let run = |edit: &str, shot: &Path| {
        let scripted = format!("3:{edit}");
        view_with_output(
            &[
                avocado,
                "--set",
                light,
                "--size",
                "320x240",
                "--no-panel",
                "--no-overlay",
                "--frames",
                "6",
                "--warmup",
                "1",
                "--frame-times",
                "--edit",
                &scripted,
            ],
            shot,
        )
    };
    let roughness = "materials.2256_Avocado_d.roughness=0.35";
    let shot = dir.path().join("material.png");
    let (area, out) = run(roughness, &shot);
    let ((calls, bytes), total) = later_uploads(&out, "materials");
    assert_eq!((calls, total), (1, 1), "{out}");
    assert!(bytes > 0 && bytes < 1024, "{out}");
    for kind in ["geometry", "textures", "shadow layers drawn", "lights"] {
        assert_eq!(later_uploads(&out, kind).0, (0, 0), "{kind}: {out}");
    }
    let rendered = dir.path().join("material-render.png");
    render(
        &[avocado, "--set", light, "--set", roughness],
        area.2,
        area.3,
        &rendered,
    );
    assert_matches(&shot, area, &rendered, "avocado-roughness");

    let (_, out) = run(
        "lights.0.direction=[-0.3, -1.0, -0.4]",
        &dir.path().join("light.png"),
    );
    assert_eq!(later_uploads(&out, "shadow layers drawn").0.0, 1, "{out}");
    assert_eq!(later_uploads(&out, "lights").0.0, 1, "{out}");
    for kind in ["geometry", "textures", "materials"] {
        assert_eq!(later_uploads(&out, kind).0, (0, 0), "{kind}: {out}");
    }

    let (_, out) = run("shading.mode=flat", &dir.path().join("flat.png"));
    assert!(later_uploads(&out, "geometry").0.1 > 0, "{out}");
}
