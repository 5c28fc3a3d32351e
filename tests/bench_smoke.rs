//! `gonio bench --smoke`: the report is produced and well formed, and
//! every figure in it is a finite number. Not a timed test: nothing here
//! depends on how fast anything ran.

mod common;

use gonio::bench::report::{RESULTS_HEADER, parse_csv_line};

fn finite_fields(line: &str, skip: &[usize]) -> Vec<f64> {
    parse_csv_line(line)
        .iter()
        .enumerate()
        .filter(|(i, _)| !skip.contains(i))
        .map(|(i, f)| {
            let v: f64 = f
                .parse()
                .unwrap_or_else(|_| panic!("field {i} `{f}` of `{line}` is not a number"));
            assert!(v.is_finite(), "field {i} of `{line}` is not finite");
            v
        })
        .collect()
}

#[test]
fn smoke_bench_writes_a_well_formed_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let run = common::gonio()
        .args(["bench", "--smoke", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "gonio bench --smoke failed: {stderr}");
    // Without a terminal (a pipe here, as in CI) progress is plain lines
    // (a CI run once printed nothing): what, n of m, elapsed, ETA.
    let progress: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("bench: step "))
        .collect();
    assert!(progress.len() >= 3, "{stderr}");
    assert!(
        progress
            .iter()
            .all(|l| l.contains(", elapsed ") && l.contains("ETA")),
        "{stderr}"
    );
    assert!(
        progress.iter().any(|l| l.contains("truth image")),
        "{stderr}"
    );
    assert!(stderr.contains("bench: done, "), "{stderr}");
    assert!(
        !stderr.contains("GPU tests need") && !stderr.contains("no GPU adapter"),
        "{stderr}"
    );

    // results.csv: the header, then measured rows with finite numbers.
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(parse_csv_line(lines.next().unwrap()), RESULTS_HEADER);
    let rows: Vec<&str> = lines.collect();
    assert!(rows.len() >= 8, "too few configurations: {csv}");
    let mut knobs = std::collections::BTreeSet::new();
    let mut on_front = 0;
    for line in &rows {
        let f = parse_csv_line(line);
        assert_eq!(f.len(), RESULTS_HEADER.len(), "{line}");
        assert_eq!(f[0], "built-in");
        knobs.insert(f[1].clone());
        // Text columns: scene, knob, value, overrides, on_front, clock.
        let numbers = finite_fields(line, &[0, 1, 2, 3, 10, 11]);
        assert!(numbers.iter().all(|v| *v >= 0.0), "{line}");
        assert!(numbers[0] > 0.0, "zero frame time: {line}");
        on_front += (f[10] == "true") as usize;
        assert!(
            ["gpu-timestamp", "wall"].contains(&f[11].as_str()),
            "{line}"
        );
    }
    assert!(on_front >= 1, "no configuration on the front");
    for k in [
        "base",
        "shading",
        "model",
        "fresnel",
        "distribution",
        "smith_beckmann",
        "shadow_map_size",
        "shadow_filter",
        "area_samples",
        "resolution",
        "layer core",
        "layer ior/specular",
        "layer clearcoat",
        "layer sheen",
        "layer iridescence",
        "layer anisotropy",
        "layer all",
    ] {
        assert!(knobs.contains(k), "knob {k} not measured: {csv}");
    }

    // scale.csv: both sweeps, finite.
    let scale = std::fs::read_to_string(out.join("scale.csv")).unwrap();
    let scale_rows: Vec<&str> = scale.lines().skip(1).collect();
    assert!(scale_rows.iter().any(|l| l.starts_with("triangles,")));
    assert!(scale_rows.iter().any(|l| l.starts_with("pixels,")));
    for line in &scale_rows {
        finite_fields(line, &[0]);
    }

    // The report: every section, every ratio a finite number, MSAA
    // accounted for.
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    for section in [
        "## What \"error\" means",
        "## Floors",
        "## Targets",
        "## Uber shader vs specialized",
        "## Configurations",
        "### Layers of the glTF material",
        "## The Pareto front",
        "## Auto quality",
        "## Scale",
    ] {
        assert!(report.contains(section), "missing `{section}`");
    }
    for target in [
        "specialized scene / hand-minimal shader",
        "uber / specialized shader",
        "4 shadowed lights / unlit floor",
        "cold `gonio render`",
        "`--max-error` pick",
        "growth of time with triangles",
        "growth of time with pixels",
        "peak memory growth / mesh data as loaded",
        "peak memory growth / GPU mesh data",
    ] {
        let line = report
            .lines()
            .find(|l| l.starts_with('|') && l.contains(target))
            .unwrap_or_else(|| panic!("no row for `{target}` in the targets"));
        let value = line.split("**").nth(1).unwrap_or("");
        let v: f64 = value
            .parse()
            .unwrap_or_else(|_| panic!("`{target}`: `{value}` is not a number"));
        // Slopes may come out negative from one noisy iteration; ratios
        // of times and sizes cannot.
        assert!(
            v.is_finite() && (target.starts_with("growth") || v >= 0.0),
            "`{target}` = {v}"
        );
    }
    // The memory rows again with the light casting shadows.
    assert!(
        report.lines().any(|l| l.starts_with('|')
            && l.contains("peak memory growth / mesh data as loaded")
            && l.contains("point light with shadows")),
        "no shadowed memory row in the targets"
    );
    assert!(
        scale_rows
            .iter()
            .any(|l| l.starts_with("triangles-shadowed,")),
        "no shadowed row in scale.csv"
    );
    assert!(
        report.contains("msaa"),
        "MSAA is neither measured nor reported as not measured"
    );
    for bad in ["NaN", "**inf", "**-inf"] {
        assert!(!report.contains(bad), "`{bad}` in the report:\n{report}");
    }

    for plot in ["pareto.svg", "pareto.png"] {
        let bytes = std::fs::read(out.join(plot)).unwrap();
        assert!(bytes.len() > 1000, "{plot} is nearly empty");
    }
    let svg = std::fs::read_to_string(out.join("pareto.svg")).unwrap();
    assert!(svg.contains("Pareto front"));

    // --max-error picks from these results; an impossible budget is a
    // one-paragraph error with status 2 and no output file.
    let png = dir.path().join("auto.png");
    let results = out.join("results.csv");
    let ok = common::gonio()
        .args(["render", "--max-error", "1e9", "--bench-results"])
        .arg(&results)
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    assert!(png.exists());
    let bad_png = dir.path().join("bad.png");
    for budget in ["-1", "NaN"] {
        let bad = common::gonio()
            .args(["render", "--bench-results"])
            .arg(&results)
            .arg(format!("--max-error={budget}"))
            .arg("-o")
            .arg(&bad_png)
            .output()
            .unwrap();
        assert_eq!(bad.status.code(), Some(2), "--max-error {budget}");
        assert!(String::from_utf8_lossy(&bad.stderr).contains("--max-error"));
        assert!(!bad_png.exists());
    }
}

#[test]
fn bench_refuses_bad_input_without_output() {
    let dir = tempfile::tempdir().unwrap();
    // An out "folder" that is a file.
    let file = dir.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let run = common::gonio()
        .args(["bench", "--smoke", "-o"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("not a folder"), "{stderr}");
    // A bad --set: named, nothing written.
    let out = dir.path().join("out");
    let run = common::gonio()
        .args([
            "bench",
            "--smoke",
            "--set",
            "materials.ball.roughness=7",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("roughness"));
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "partial output: {left:?}");
    // A missing scene.
    let run = common::gonio()
        .args(["bench", "--smoke", "no-such-scene.toml", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("no-such-scene.toml"));
}

/// `gonio bench --shard I/N` measures a disjoint part of the
/// configurations each, `--merge` joins them into a `results.csv` with
/// every row once (in the run's order) and a front, a finished shard is
/// skipped, and a missing one is named.
#[test]
fn sharded_bench_merges_into_one_results_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let bench = |extra: &[&str]| {
        let run = common::gonio()
            .args(["bench", "-o"])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        (
            run.status.code(),
            String::from_utf8_lossy(&run.stderr).into_owned(),
        )
    };
    let (code, err) = bench(&["--smoke", "--shard", "2/2"]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = bench(&["--merge"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("1/2") && err.contains("missing"), "{err}");
    let (code, err) = bench(&["--smoke", "--shard", "1/2"]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = bench(&["--smoke", "--shard", "1/2"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("skipped"), "{err}");
    let (code, err) = bench(&["--merge"]);
    assert_eq!(code, Some(0), "{err}");

    let rows = |path: &std::path::Path, skip: usize| -> Vec<Vec<String>> {
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .skip(skip)
            .filter(|l| !l.is_empty())
            .map(parse_csv_line)
            .collect()
    };
    let shard = |i: usize| rows(&out.join(format!("shards/bench-shard-{i}-of-2.csv")), 2);
    let (one, two) = (shard(1), shard(2));
    let merged = rows(&out.join("results.csv"), 1);
    assert_eq!(merged.len(), one.len() + two.len());
    assert_eq!(merged[0][1], "base");
    let on_front = RESULTS_HEADER
        .iter()
        .position(|h| *h == "on_front")
        .unwrap();
    assert!(merged.iter().any(|r| r[on_front] == "true"));
    // Configuration k is shard (k mod 2) + 1's row k / 2.
    for (k, row) in merged.iter().enumerate() {
        let from = if k % 2 == 0 { &one } else { &two };
        assert_eq!(row[..on_front], from[k / 2][..on_front], "row {k}");
    }
    assert!(out.join("report.md").exists());
}

/// The target ratios' harness draws a scene whose materials transmit:
/// its specialized shader leaves out the transmission image's read (bind
/// group 4, which the harness does not bind), or wgpu's pipeline
/// validation fails there, at the end of a `gonio bench` run.
#[test]
fn the_ratio_harness_draws_a_transmissive_scene() {
    use gonio::bench::ratios::{Effort, uber_vs_specialized};
    use gonio::scene::scene_file::{self, SceneSource};
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes/transmission/glass.toml");
    let scene = scene_file::load(
        &SceneSource::File(path),
        &["image.width=64".to_string(), "image.height=40".to_string()],
    )
    .unwrap();
    let mut renderer = common::gpu_renderer();
    let (ratio, special_ms, uber_ms) =
        uber_vs_specialized(&mut renderer, &scene, "glass", Effort::SMOKE).unwrap();
    assert!(special_ms.is_finite() && uber_ms.is_finite());
    assert!(
        ratio.num.median > 0.0 && ratio.den.median > 0.0,
        "{ratio:?}"
    );
}
