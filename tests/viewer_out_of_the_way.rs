//! The viewer's panel under Xvfb (issue 38): a scripted run opens a
//! section and scrolls it into view (`--edit N:panel.show=Plots`), a
//! misspelt section gets the nearest name, and a measured material with
//! every plot shown runs to its last frame.

#![cfg(feature = "viewer")]

mod common;

use std::path::Path;
use std::process::{Command, Output};

/// `xvfb-run` with a screen large enough for the windows below.
fn xvfb() -> Command {
    let found = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    assert!(
        found,
        "xvfb-run is missing: the viewer tests open a real window under Xvfb. Install it with `sudo apt-get install xvfb xauth` (or run ./setup.sh)"
    );
    let mut c = Command::new("xvfb-run");
    c.args(["-a", "-s", "-screen 0 1280x720x24"]);
    c
}

fn view(args: &[&str], screenshot: &Path) -> Output {
    xvfb()
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
