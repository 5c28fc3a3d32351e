//! The viewer's panel under Xvfb: a scripted run opens a
//! section and scrolls it into view (`--edit N:panel.show=Plots`), a
//! misspelt section gets the nearest name, a measured material with
//! every plot shown runs to its last frame, and draws its frames while
//! the panel's background jobs are held; the panel's θ_h × θ_d labels
//! keep apart and its texture notes name each texture's image, channel
//! and transform.

#![cfg(feature = "viewer")]

mod common;

use gonio::ui::plots::halfdiff::{AXIS_FONT, AxisLabel, axis_labels, grid, image_rects};
use std::path::Path;
use std::process::Output;

fn view(args: &[&str], screenshot: &Path) -> Output {
    common::xvfb()
        .arg(common::gonio().get_program())
        .arg("view")
        .args(["--size", "900x600", "--no-overlay", "--frames", "4"])
        .args(args)
        .arg("--screenshot")
        .arg(screenshot)
        .output()
        .expect("xvfb-run runs")
}

fn succeeded(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        out.status.success(),
        "gonio view failed ({:?}): {stderr}{}",
        out.status.code(),
        common::LAVAPIPE_TEST_HINT
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The panel (the screenshot's columns right of the 3D area, which ends
/// at `area_end`) as RGB bytes.
fn panel_pixels(shot: &Path, area_end: u32) -> Vec<u8> {
    let image = image::open(shot).unwrap().into_rgb8();
    let mut out = Vec::new();
    for y in 0..image.height() {
        for x in area_end.min(image.width())..image.width() {
            out.extend(image.get_pixel(x, y).0);
        }
    }
    out
}

#[test]
fn a_script_scrolls_the_panel_to_a_section() {
    let dir = tempfile::tempdir().unwrap();
    let measured = "materials.ball={model=\"measured\", measured=\"red-specular-plastic\"}";
    let top = dir.path().join("top.png");
    let stdout = succeeded(&view(&["--set", measured], &top));
    // `3D area x=X y=Y WxH`: the panel is right of it.
    let numbers: Vec<u32> = stdout
        .lines()
        .find_map(|l| l.split("3D area ").nth(1))
        .map(|a| {
            a.split(|c: char| !c.is_ascii_digit())
                .filter_map(|s| s.parse().ok())
                .collect()
        })
        .unwrap_or_else(|| panic!("no 3D area reported: {stdout}"));
    let area_x = numbers[0] + numbers[2];
    assert!(area_x < 800, "the panel is shown: {stdout}");
    let plots = dir.path().join("plots.png");
    succeeded(&view(
        &["--set", measured, "--edit", "1:panel.show=Plots"],
        &plots,
    ));
    assert_ne!(
        panel_pixels(&top, area_x),
        panel_pixels(&plots, area_x),
        "panel.show=Plots left the panel as it was"
    );
    let out = view(&["--edit", "1:panel.show=Plot"], &dir.path().join("x.png"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("did you mean `Plots`?"), "{stderr}");
}

/// Item 1: the window's frames do not wait on the panel's background
/// jobs (the plots' integrals). With `GONIO_HOLD_BACKGROUND` every job
/// holds every thread of the background pool for good, as a measured
/// material's albedo curve holds them for a minute; a scripted run with a
/// measured material (and one switching to it at frame 2) still draws its
/// frames and exits. When the jobs ran on rayon's global pool, the first
/// frame's parallel loops (the measured table's upload) waited for them:
/// with the jobs held, the run would never end, which `timeout` (a hang
/// detector, far above the run's time) reports as exit 124.
#[test]
fn frames_are_drawn_while_the_panels_background_jobs_are_held() {
    let dir = tempfile::tempdir().unwrap();
    let measured = "materials.ball={model=\"measured\", measured=\"red-specular-plastic\"}";
    for (case, args) in [
        ("at load", vec!["--set", measured]),
        (
            "switching",
            vec!["--edit", "2:materials.ball.model=measured"],
        ),
    ] {
        let out = common::xvfb()
            .args(["timeout", "900"])
            .arg(common::gonio().get_program())
            .arg("view")
            .args(["--size", "900x600", "--no-overlay", "--frames", "4"])
            .args(["--frame-times", "--warmup", "0"])
            .args(&args)
            .arg("--screenshot")
            .arg(dir.path().join("held.png"))
            .env(gonio::ui::background::HOLD_ENV, "1")
            .output()
            .expect("xvfb-run runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_ne!(
            out.status.code(),
            Some(124),
            "{case}: the viewer's frames waited on its held background jobs: {stderr}"
        );
        let stdout = succeeded(&out);
        assert!(
            stderr.contains("a background job is held"),
            "{case}: no background job was started, so none was held: {stderr}"
        );
        // Frame times are the intervals between frames: 4 frames give 3,
        // one more for each try whose surface was not ready.
        let intervals: usize = stdout
            .split("frame times over ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{case}: no frame times: {stdout}"));
        assert!(
            intervals >= 3 && stdout.contains("first frame"),
            "{case}: {stdout}"
        );
    }
}

/// Item 10: the panel's texture notes of a glTF material name, for each
/// texture, the parameter it multiplies, its image, the channel read and
/// its `KHR_texture_transform` (the panel showed only the factors).
#[test]
fn texture_notes_name_image_channel_and_transform() {
    use gonio::scene::scene_file::{self, SceneSource};
    let path = common::gltf_asset("MetalRoughSpheresTextured/MetalRoughSpheresTextured.gltf");
    let scene = scene_file::load(&SceneSource::File(path), &[]).unwrap();
    let images: Vec<&str> = scene.images.iter().map(|i| i.name.as_str()).collect();
    let m = scene
        .materials
        .iter()
        .find(|m| m.name == "mat_0")
        .unwrap_or_else(|| {
            panic!(
                "no mat_0 in {:?}",
                scene.materials.iter().map(|m| &m.name).collect::<Vec<_>>()
            )
        });
    let lines = gonio::ui::panels::material::texture_lines(m, &images);
    let line = |start: &str| {
        lines
            .iter()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no `{start}` in {lines:?}"))
            .clone()
    };
    // The glTF's metallicRoughness texture: roughness in G, metalness in B
    // (glTF 2.0, 3.9.2), both from the one image.
    let base = line("base_color × texture (RGB): ");
    let rough = line("roughness × texture (G): ");
    let metal = line("metallic × texture (B): ");
    let image_of = |l: &str| {
        images
            .iter()
            .find(|name| l.contains(&format!(": {name}, UV 0")))
            .copied()
            .unwrap_or_else(|| panic!("no image of {images:?} in `{l}`"))
    };
    assert_eq!(image_of(&rough), image_of(&metal));
    assert_ne!(image_of(&base), image_of(&rough));
    for l in [&base, &rough, &metal] {
        assert!(
            l.contains("offset (0.05322265625, 0.91650390625)") && l.contains("scale (0, 0)"),
            "the transform is missing in `{l}`"
        );
    }
}

/// The box a label's text takes: 0.6 em per character (generous for
/// egui's proportional font, whose digits are about 0.55 em), a row
/// of 1.2 em.
fn label_box(l: &AxisLabel) -> egui::Rect {
    let size = egui::vec2(
        l.text.chars().count() as f32 * 0.6 * AXIS_FONT,
        1.2 * AXIS_FONT,
    );
    l.align.anchor_size(l.at, size)
}

/// At every width the panel can have (300 to 1200 points) and for one
/// to six materials, no two axis labels of the images touch: boxes
/// side by side keep a space (a quarter em) between them, so that one
/// image's 90 and the next one's 0 do not read as "900", nor 60 and 90
/// as one number; and every image keeps its 0 and 90 labels.
#[test]
fn axis_labels_keep_apart_at_every_panel_width() {
    let space = 0.25 * AXIS_FONT;
    for panel in (300..=1200).step_by(10) {
        // The panel's margins and scroll bar, and show()'s 8 points.
        let width = panel as f32 - 24.0;
        for n in 1..=6 {
            let (cols, _, _) = grid(width, n);
            let rects = image_rects(egui::Pos2::ZERO, width, n);
            let labels: Vec<AxisLabel> = rects
                .iter()
                .enumerate()
                .flat_map(|(k, r)| {
                    let labels = axis_labels(*r, k % cols == 0);
                    let texts: Vec<&str> = labels.iter().map(|l| l.text.as_str()).collect();
                    assert!(texts.contains(&"90") && texts.contains(&"0"), "{texts:?}");
                    labels
                })
                .collect();
            for (i, a) in labels.iter().enumerate() {
                for b in &labels[i + 1..] {
                    let (ra, rb) = (label_box(a), label_box(b));
                    let apart = ra.expand2(egui::vec2(space / 2.0, 0.0));
                    let other = rb.expand2(egui::vec2(space / 2.0, 0.0));
                    assert!(
                        !apart.intersects(other) || apart.intersect(other).area() <= 0.0,
                        "panel {panel}, {n} images: `{}` at {ra:?} and `{}` at {rb:?}",
                        a.text,
                        b.text
                    );
                }
            }
        }
    }
}
