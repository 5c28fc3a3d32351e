//! Sharded reference renders (`gonio render --reference --shard`) and
//! `gonio merge`, as a batch system runs them: separate processes whose
//! merged parts equal one process's image byte for byte, restartable,
//! and a merge that refuses a set that is not one whole render.

mod common;

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Output;

/// The scheduler variables `--shard auto` reads: removed from every
/// child, so that a test run inside a Slurm job tests the same thing.
const SCHEDULER: [&str; 6] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_MAX",
    "SLURM_ARRAY_TASK_COUNT",
    "JOB_COMPLETION_INDEX",
    "HQ_TASK_ID",
];

fn gonio(args: &[OsString], env: &[(&str, &str)]) -> Output {
    let mut cmd = common::gonio();
    for v in SCHEDULER {
        cmd.env_remove(v);
    }
    cmd.args(args).envs(env.iter().copied());
    cmd.output().unwrap()
}

fn args(list: &[&dyn AsRef<std::ffi::OsStr>]) -> Vec<OsString> {
    list.iter().map(|a| a.as_ref().to_os_string()).collect()
}

/// Runs and asserts success; returns stderr.
fn ok(args: &[OsString], env: &[(&str, &str)]) -> String {
    let out = gonio(args, env);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "gonio {args:?}: {stderr}");
    stderr
}

/// Runs, asserts exit status 2 and no file at `not_written`; returns
/// stderr.
fn refused(args: &[OsString], env: &[(&str, &str)], not_written: &Path) -> String {
    let out = gonio(args, env);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "gonio {args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!not_written.exists(), "{} written", not_written.display());
    stderr
}

/// `render --reference SCENE_ARGS -o OUT`.
fn render(scene: &[OsString], extra: &[OsString], out: &Path) -> Vec<OsString> {
    let mut a = args(&[&"render", &"--reference", &"-o", &out]);
    a.extend(scene.iter().cloned());
    a.extend(extra.iter().cloned());
    a
}

/// Renders `shards` parts of `scene` into `dir`, merges them into `dir`
/// as EXR and PNG, and returns the parts.
fn shard_and_merge(scene: &[OsString], shards: usize, dir: &Path) -> Vec<PathBuf> {
    std::fs::create_dir_all(dir).unwrap();
    let pattern = dir.join("part-{shard}.exr");
    for i in 1..=shards {
        let shard: OsString = format!("{i}/{shards}").into();
        ok(&render(scene, &args(&[&"--shard", &shard]), &pattern), &[]);
    }
    let mut parts: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "exr"))
        .collect();
    parts.sort();
    assert_eq!(parts.len(), shards, "{parts:?}");
    for out in ["merged.exr", "merged.png"] {
        let mut a = args(&[&"merge", &"-o", &dir.join(out)]);
        // Any order: the headers say which rows each part holds.
        a.extend(parts.iter().rev().map(|p| p.as_os_str().to_owned()));
        ok(&a, &[]);
    }
    parts
}

/// The merged EXR and PNG are the single render's files, byte for byte,
/// for any number of shards (1, several, one row each), every shading
/// mode (flat and Gouraud precompute per triangle and per vertex before
/// any pixel), a glTF model, a tone map (the PNG's), an exposure, and
/// the environment's diffuse integration.
#[test]
fn merged_shards_equal_the_single_render_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let environment: OsString = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/environment.toml"
    )
    .into();
    let suzanne: OsString = common::gltf_asset("Suzanne/Suzanne.gltf").into();
    let cases: [(&str, Vec<OsString>, &[usize]); 4] = [
        (
            "built-in",
            args(&[&"--width", &"37", &"--height", &"23"]),
            &[1, 3, 23],
        ),
        (
            "flat, aces",
            args(&[
                &"--width",
                &"32",
                &"--height",
                &"24",
                &"--shading",
                &"flat",
                &"--set",
                &"image.tone_map=\"aces\"",
            ]),
            &[4],
        ),
        (
            "suzanne, gouraud",
            args(&[
                &suzanne,
                &"--width",
                &"40",
                &"--height",
                &"30",
                &"--shading",
                &"gouraud",
            ]),
            &[5],
        ),
        (
            "environment",
            args(&[&environment, &"--width", &"48", &"--height", &"24"]),
            &[3],
        ),
    ];
    for (k, (name, scene, counts)) in cases.iter().enumerate() {
        let single = dir.path().join(format!("single-{k}"));
        std::fs::create_dir_all(&single).unwrap();
        ok(&render(scene, &[], &single.join("image.exr")), &[]);
        ok(&render(scene, &[], &single.join("image.png")), &[]);
        for &n in *counts {
            let parts = dir.path().join(format!("parts-{k}-{n}"));
            shard_and_merge(scene, n, &parts);
            for ext in ["exr", "png"] {
                let a = std::fs::read(single.join(format!("image.{ext}"))).unwrap();
                let b = std::fs::read(parts.join(format!("merged.{ext}"))).unwrap();
                assert!(
                    a == b,
                    "{name}, {n} shards: the merged .{ext} differs from the single render"
                );
            }
        }
    }
    // An exposure applies to the merge's PNG as to the render's.
    let scene = &cases[0].1;
    let single = dir.path().join("exposed.png");
    ok(
        &render(scene, &args(&[&"--exposure", &"1.5"]), &single),
        &[],
    );
    let parts: Vec<OsString> = (1..=3)
        .map(|i| dir.path().join(format!("parts-0-3/part-{i}.exr")).into())
        .collect();
    let merged = dir.path().join("merged-exposed.png");
    let mut a = args(&[&"merge", &"--exposure", &"1.5", &"-o", &merged]);
    a.extend(parts);
    ok(&a, &[]);
    assert!(std::fs::read(&single).unwrap() == std::fs::read(&merged).unwrap());
}

/// A shard whose file is already there, complete and of this render, is
/// skipped (the file untouched); one of another render is replaced, with
/// a note.
#[test]
fn a_finished_shard_is_skipped_and_a_stale_one_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let part = dir.path().join("part-2.exr");
    let scene = args(&[&"--width", &"24", &"--height", &"16"]);
    let shard = args(&[&"--shard", &"2/3"]);
    ok(&render(&scene, &shard, &part), &[]);
    let before = std::fs::metadata(&part).unwrap().modified().unwrap();
    let bytes = std::fs::read(&part).unwrap();
    let stderr = ok(&render(&scene, &shard, &part), &[]);
    assert!(
        stderr.contains("skipped") && stderr.contains("shard 2/3"),
        "{stderr}"
    );
    assert_eq!(
        std::fs::metadata(&part).unwrap().modified().unwrap(),
        before
    );
    assert!(std::fs::read(&part).unwrap() == bytes);

    let mut other = scene.clone();
    other.extend(args(&[&"--set", &"materials.ball.k_d=[0.2,0.6,0.2]"]));
    let stderr = ok(&render(&other, &shard, &part), &[]);
    assert!(stderr.contains("replacing"), "{stderr}");
    assert!(std::fs::read(&part).unwrap() != bytes);
    let stderr = ok(&render(&other, &shard, &part), &[]);
    assert!(stderr.contains("skipped"), "{stderr}");
}

/// The merge names what is wrong with a set and writes nothing: a
/// missing shard, a shard given twice, a part of another render, a file
/// that is not a part at all.
#[test]
fn the_merge_refuses_an_incomplete_duplicated_or_mixed_set() {
    let dir = tempfile::tempdir().unwrap();
    let scene = args(&[&"--width", &"30", &"--height", &"20"]);
    let parts = shard_and_merge(&scene, 4, &dir.path().join("parts"));
    let out = dir.path().join("out.exr");
    let merge = |files: &[&Path]| {
        let mut a = args(&[&"merge", &"-o", &out]);
        a.extend(files.iter().map(|p| p.as_os_str().to_owned()));
        a
    };

    let e = refused(&merge(&[&parts[0], &parts[2]]), &[], &out);
    assert!(e.contains("incomplete") && e.contains("2/4, 4/4"), "{e}");

    let copy = dir.path().join("copy-of-3.exr");
    std::fs::copy(&parts[2], &copy).unwrap();
    let e = refused(
        &merge(&[&parts[0], &parts[1], &parts[2], &copy, &parts[3]]),
        &[],
        &out,
    );
    assert!(e.contains("copy-of-3.exr") && e.contains("twice"), "{e}");

    let odd = dir.path().join("odd-2.exr");
    let mut other = scene.clone();
    other.extend(args(&[&"--set", &"lights.0.intensity=[9,9,9]"]));
    ok(&render(&other, &args(&[&"--shard", &"2/4"]), &odd), &[]);
    let e = refused(&merge(&[&parts[0], &odd, &parts[2], &parts[3]]), &[], &out);
    assert!(
        e.contains("odd-2.exr") && e.contains("another render"),
        "{e}"
    );

    // Same scene, another shard count.
    let five = dir.path().join("five.exr");
    ok(&render(&scene, &args(&[&"--shard", &"1/5"]), &five), &[]);
    let e = refused(
        &merge(&[&parts[0], &parts[1], &parts[2], &parts[3], &five]),
        &[],
        &out,
    );
    assert!(e.contains("five.exr") && e.contains("shard 1/5"), "{e}");

    let plain = dir.path().join("plain.exr");
    ok(&render(&scene, &[], &plain), &[]);
    let e = refused(&merge(&[&plain]), &[], &out);
    assert!(
        e.contains("plain.exr") && e.contains("not a partial image"),
        "{e}"
    );
}

/// `--shard auto` takes the shard from a Slurm array task's variables
/// (and a Kubernetes index with the count given), and without any
/// scheduler names the variables it looked for; a shard is a reference
/// render into an EXR.
#[test]
fn auto_shards_read_the_scheduler_and_bad_shards_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scene = args(&[&"--width", &"24", &"--height", &"16"]);
    let pattern = dir.path().join("part-{shard}.exr");
    let slurm = [
        ("SLURM_ARRAY_TASK_ID", "3"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_MAX", "3"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
    ];
    ok(
        &render(
            &scene,
            &args(&[&"--shard", &"auto", &"--verbose"]),
            &pattern,
        ),
        &slurm,
    );
    let k8s = [("JOB_COMPLETION_INDEX", "0")];
    ok(
        &render(&scene, &args(&[&"--shard", &"auto/3"]), &pattern),
        &k8s,
    );
    let hq = [("HQ_TASK_ID", "2")];
    ok(
        &render(&scene, &args(&[&"--shard", &"auto/3"]), &pattern),
        &hq,
    );
    let merged = dir.path().join("merged.exr");
    let single = dir.path().join("single.exr");
    let mut a = args(&[&"merge", &"-o", &merged]);
    a.extend((1..=3).map(|i| dir.path().join(format!("part-{i}.exr")).into_os_string()));
    ok(&a, &[]);
    ok(&render(&scene, &[], &single), &[]);
    assert!(std::fs::read(&merged).unwrap() == std::fs::read(&single).unwrap());

    let nothing = dir.path().join("none-{shard}.exr");
    let e = refused(
        &render(&scene, &args(&[&"--shard", &"auto"]), &nothing),
        &[],
        &dir.path().join("none-1.exr"),
    );
    assert!(
        e.contains("SLURM_ARRAY_TASK_ID")
            && e.contains("JOB_COMPLETION_INDEX")
            && e.contains("HQ_TASK_ID"),
        "{e}"
    );

    let gpu = dir.path().join("gpu.exr");
    let mut a = args(&[&"render", &"-o", &gpu, &"--shard", &"1/2"]);
    a.extend(scene.clone());
    let e = refused(&a, &[], &gpu);
    assert!(e.contains("--reference"), "{e}");
    let png = dir.path().join("part.png");
    let e = refused(
        &render(&scene, &args(&[&"--shard", &"1/2"]), &png),
        &[],
        &png,
    );
    assert!(e.contains(".exr"), "{e}");
    let many = dir.path().join("many.exr");
    let e = refused(
        &render(&scene, &args(&[&"--shard", &"1/17"]), &many),
        &[],
        &many,
    );
    assert!(e.contains("16 rows"), "{e}");
}
