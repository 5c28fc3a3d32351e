//! The viewer's memory stays flat: a scripted run under Xvfb
//! repeats one cycle four times (every reflectance model, the Fresnel
//! and shading variants, a shadowed light, a resize, a good and a bad
//! dropped file) and the resident memory of `gonio view`, sampled from
//! /proc while it runs, must be in the last third of the measured run
//! within a few percent of the first third.
//!
//! Why a cycle repeated: the first pass (the warm-up, not measured: the
//! first 30 % of the samples, a quarter of the frames plus the pipeline
//! compilations) compiles a pipeline per variant and fills egui's caches,
//! memory the viewer keeps on purpose; the later passes draw the same
//! things, so anything that grows there grows per frame. Medians, not
//! peaks: the shadowed light's cube map (about 100 MiB) lives for a few
//! frames of each cycle, which 50 ms samples catch or miss. The leak
//! this guards against (Mesa 22.3's lavapipe compiling a shader per draw
//! for a branch on a material value, shaders/brdf/phong.wgsl
//! UNIFORM_BRANCHES) added 0.8 MiB a frame: hundreds of MiB over a third
//! of this run, against an allowance of 5 % + 8 MiB (allocator noise:
//! freed pages are not always returned to the system at once) plus one
//! shadow cube map (96 MiB), whose freed pages may stay resident once, at
//! a time that varies from run to run. The
//! allocator's own retention of freed large blocks (glibc's dynamic mmap
//! threshold: steps from 216 to 284 MiB that then stayed) is turned off
//! by the viewer itself, src/ui/memory.rs.

#![cfg(feature = "viewer")]

mod common;

use gonio::material::ReflectanceModel;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// Frames of one cycle; the run is four (one of warm-up).
const CYCLE: u32 = 330;
const CYCLES: u32 = 4;

/// The edits of one cycle, at frames relative to its start: every model
/// of the table on the sphere (with the terms that have their own code), the shading
/// modes, a shadowed light.
fn cycle_edits(measured: bool) -> Vec<(u32, String)> {
    // Every model of the table, so a model added later is soaked too.
    let mut edits: Vec<String> = ReflectanceModel::ALL
        .iter()
        .filter(|m| measured || **m != ReflectanceModel::Measured)
        .map(|m| format!("materials.ball.model=\"{}\"", m.name()))
        .collect();
    edits.extend(
        [
            r#"materials.ball.model="cook-torrance""#,
            r#"materials.ball.fresnel="dielectric""#,
            r#"materials.ball.fresnel="conductor""#,
            r#"materials.ball.geometry="smith-correlated""#,
            r#"materials.ball.model="blinn-phong""#,
            r#"shading.mode="gouraud""#,
            r#"shading.mode="flat""#,
            r#"shading.mode="phong""#,
            "lights.0.shadows=true",
            "lights.0.shadows=false",
        ]
        .map(String::from),
    );
    if measured {
        edits.extend(
            [
                r#"materials.ball.model="measured""#,
                r#"materials.ball.measured="blue-fabric""#,
                r#"materials.ball.model="blinn-phong""#,
            ]
            .map(String::from),
        );
    }
    // Every edit before the resize at frame 250.
    let step = 9;
    edits
        .into_iter()
        .enumerate()
        .map(|(i, e)| (5 + i as u32 * step, e))
        .collect()
}

/// The `gonio` process that `xvfb-run` (our child `parent`) started.
fn viewer_pid(parent: u32) -> Option<u32> {
    for entry in std::fs::read_dir("/proc").ok()?.flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(format!("/proc/{pid}/stat")) else {
            continue;
        };
        // pid (comm) state ppid ...: comm may hold spaces, so split after ')'.
        let Some((head, tail)) = stat.rsplit_once(')') else {
            continue;
        };
        let ppid: Option<u32> = tail.split_whitespace().nth(1).and_then(|p| p.parse().ok());
        if ppid == Some(parent) && head.contains("(gonio") {
            return Some(pid);
        }
    }
    None
}

/// Resident memory of `pid` in KiB (`VmRSS`), if it still runs.
fn resident_kib(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}

/// Samples the viewer's resident memory every 50 ms until `child` exits.
fn sample_until_exit(child: &mut Child) -> Vec<u64> {
    let mut samples = Vec::new();
    let mut pid = None;
    loop {
        if child.try_wait().expect("xvfb-run waits").is_some() {
            return samples;
        }
        if pid.is_none() {
            pid = viewer_pid(child.id());
        }
        if let Some(kib) = pid.and_then(resident_kib) {
            samples.push(kib);
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// With the panel: its plots and the background integrals of each
/// material. Measured materials are left to the run below: their
/// integrals (the network in f64, tens of seconds each on a loaded
/// 2-core machine) finish at times unrelated to the cycle, so a run's
/// thirds would compare different work, not the same work repeated.
#[test]
fn the_viewers_memory_is_flat_over_thousands_of_frames_of_edits() {
    soak(true, false);
}

/// Without the panel, every model including measured ones (tables built
/// once per material and kept, GPU buffers of 35 MB made and dropped on
/// each switch).
#[test]
fn the_viewers_memory_is_flat_over_edits_of_every_model_without_the_panel() {
    soak(false, true);
}

fn soak(panel: bool, measured: bool) {
    common::require_xvfb_run();
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken.toml");
    std::fs::write(&bad, "[[objects]\nshape = ").unwrap();
    let good = format!("{}/assets/scenes/default.toml", env!("CARGO_MANIFEST_DIR"));

    let gonio = common::gonio();
    let mut cmd = Command::new("xvfb-run");
    cmd.args(["-a", "-s", "-screen 0 1280x720x24"])
        .arg(gonio.get_program())
        .args(["view", "--no-vsync", "--size", "560x320"])
        .args(["--frames", &(CYCLES * CYCLE).to_string()]);
    if !panel {
        cmd.arg("--no-panel");
    }
    for c in 0..CYCLES {
        let start = c * CYCLE;
        for (at, edit) in cycle_edits(measured) {
            cmd.arg("--edit").arg(format!("{}:{edit}", start + at));
        }
        // A resize and back, a bad file (its error shown, the scene kept)
        // and a good one (the scene replaced, prepared anew).
        cmd.args([
            "--resize",
            &format!("{}:480x300", start + 250),
            "--resize",
            &format!("{}:560x320", start + 270),
        ]);
        cmd.arg("--drop")
            .arg(format!("{}:{}", start + 290, bad.display()));
        cmd.arg("--drop").arg(format!("{}:{good}", start + 305));
    }
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("xvfb-run starts");
    let samples = sample_until_exit(&mut child);
    let out = child.wait_with_output().expect("xvfb-run ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "gonio view failed ({:?}): {stderr}{}",
        out.status.code(),
        common::LAVAPIPE_TEST_HINT
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        samples.len() >= 30,
        "only {} memory samples: the run was too short to judge",
        samples.len()
    );
    let measured = &samples[samples.len() * 3 / 10..];
    let third = measured.len() / 3;
    let median = |s: &[u64]| {
        let mut s = s.to_vec();
        s.sort_unstable();
        s[s.len() / 2]
    };
    let first = median(&measured[..third]);
    let last = median(&measured[measured.len() - third..]);
    let mib = |k: u64| k as f64 / 1024.0;
    eprintln!(
        "viewer resident memory over {} frames ({} samples, {} after the warm-up): median {:.1} MiB in the first third, {:.1} MiB in the last (peak {:.1} MiB)",
        CYCLES * CYCLE,
        samples.len(),
        measured.len(),
        mib(first),
        mib(last),
        mib(*samples.iter().max().unwrap())
    );
    // One cube map's pages may stay resident once it has been freed
    // (kept by the driver or the allocator for the next one): a step of
    // its size, once, at a time that varies from run to run. Seen
    // 2026-12-05 in 1 of 3 runs of the binary of 072564d too: 181 MiB in
    // the first third, then 281 MiB and flat; other runs are at 279–281
    // MiB from the start. Allowed once on top of the noise; the per-frame
    // leak this test guards against (0.8 MiB a frame, about 250 MiB per
    // third of the measured run) still exceeds it.
    let side = u64::from(gonio::scene::ShadowSettings::DEFAULT_MAP_SIZE);
    let cube_map_kib = 6 * side * side * 4 / 1024;
    let allowed = first + first / 20 + 8 * 1024 + cube_map_kib;
    assert!(
        last <= allowed,
        "the viewer's resident memory grew from a median of {:.1} MiB in the first third of the measured run to {:.1} MiB in the last (allowed {:.1} MiB): something is allocated per frame",
        mib(first),
        mib(last),
        mib(allowed)
    );
}
