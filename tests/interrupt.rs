//! Interrupted renders leave nothing behind: a real
//! render killed with SIGINT, SIGTERM or SIGHUP removes its temporary
//! file and dies of the signal; one killed with SIGKILL leaves it, and the
//! next write into that folder removes it and says so.

#![cfg(unix)]

mod common;

use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// A render of the built-in scene, long enough to be
/// interrupted on either renderer (the temporary file appears before the
/// render starts): the reference at 1600 × 1200 (about 3 s on two
/// cores), the GPU at 4096 × 4096 (a 256 MiB readback and EXR).
fn start_render(out: &Path, reference: bool) -> Child {
    let size = if reference {
        ["1600", "1200"]
    } else {
        ["4096", "4096"]
    };
    common::gonio()
        .args(["render", "--width", size[0], "--height", size[1]])
        .args(reference.then_some("--reference"))
        .args(["--set", "lights.0.shadows=true", "-o"])
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("gonio starts")
}

/// Both renderers, named for the messages.
const RENDERERS: [(&str, bool); 2] = [("reference", true), ("GPU", false)];

fn partial_files(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.to_string_lossy().ends_with(".partial"))
        .collect()
}

/// Waits until the render has claimed its temporary file (it does so
/// before rendering), then a little longer so the work is under way.
fn wait_for_partial(dir: &Path, child: &mut Child) {
    let start = Instant::now();
    while partial_files(dir).is_empty() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the render ended before it could be interrupted"
        );
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no temporary file appeared"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(150));
}

fn kill(child: &Child, signal: &str) {
    let ok = std::process::Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{signal} failed");
}

#[test]
fn a_caught_signal_removes_the_temporary_file() {
    let cases = RENDERERS
        .iter()
        .flat_map(|r| [("INT", 2), ("TERM", 15), ("HUP", 1)].map(|s| (*r, s)));
    for ((renderer, reference), (signal, number)) in cases {
        let signal_name = format!("{renderer}, SIG{signal}");
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("big.exr");
        let mut child = start_render(&out, reference);
        wait_for_partial(dir.path(), &mut child);
        kill(&child, signal);
        let status = child.wait().unwrap();
        assert_eq!(
            status.signal(),
            Some(number),
            "{signal_name}: gonio should die of the signal, got {status:?}"
        );
        assert!(
            partial_files(dir.path()).is_empty(),
            "{signal_name} left {:?}",
            partial_files(dir.path())
        );
        assert!(!out.exists(), "{signal_name} left an output file");
    }
}

#[test]
fn a_killed_renders_file_is_removed_by_the_next_write() {
    for (renderer, reference) in RENDERERS {
        eprintln!("{renderer}");
        killed_render_is_cleaned_up(reference);
    }
}

fn killed_render_is_cleaned_up(reference: bool) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.exr");
    let mut child = start_render(&out, reference);
    wait_for_partial(dir.path(), &mut child);
    kill(&child, "KILL");
    child.wait().unwrap();
    let left = partial_files(dir.path());
    assert_eq!(left.len(), 1, "SIGKILL cannot be caught: {left:?}");

    let small = common::gonio()
        .args(["render", "--width", "32", "--height", "24", "-o"])
        .arg(dir.path().join("small.png"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&small.stderr);
    assert!(
        small.status.success(),
        "{stderr}{}",
        common::LAVAPIPE_TEST_HINT
    );
    assert!(
        partial_files(dir.path()).is_empty(),
        "{:?}",
        partial_files(dir.path())
    );
    let name = left[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        stderr.contains(&name) && stderr.contains("interrupted"),
        "the removal is not named: {stderr}"
    );
}
