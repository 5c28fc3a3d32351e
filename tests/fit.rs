//! `gonio fit`: the fitter recovers the parameters of synthetic
//! "measurements" made from a model, within a tolerance derived from the
//! optimizer's stopping rule; bad input exits 2 with one paragraph and no
//! output file; the fitted scene file loads.
//!
//! # The tolerance
//!
//! The search stops when the standard deviation of the (relative) cost at
//! the simplex's `n + 1` vertices is below τ = `SD_TOLERANCE` (`n` the
//! searched numbers; under `ngan` the linear ones, `k_d`, `k_s`, `A`, are
//! solved at every point, `src/fit/linear.rs`), and stops
//! restarting when a restart gains less than τ. On exact synthetic data the
//! minimum cost is 0; a simplex collapsed onto it has vertex costs ≥ 0
//! whose population standard deviation is < τ, so each lies within
//! `sqrt(n) τ` of their mean and all are below `C = 2 sqrt(n + 1) τ` when
//! the best is at the minimum. The test asserts the fit's cost is below
//! `C` (else the search stalled), and then each parameter within the
//! largest deviation a cost of `C` allows near the minimum, where the cost
//! is the quadratic `½ δᵀ H δ`: `|δ_j| ≤ sqrt(2 C (H⁻¹)_jj)` (the maximum of
//! `δ_j` on the ellipsoid `½ δᵀ H δ = C`), with `H` the Hessian of the cost
//! at the truth by central differences.

mod common;

use common::gonio;
use glam::DVec3;
use gonio::base::Rgb;
use gonio::base::frame::SurfaceFrame;
use gonio::fit::problem::{SD_TOLERANCE, mean_of, searched};
use gonio::fit::samples::{Sample, samples_of};
use gonio::fit::terms::Terms;
use gonio::fit::{FitModel, Metric, fit};

/// The relative cost of `values` (what the search minimizes).
fn cost(model: &FitModel, values: &[f64], samples: &[Sample], metric: Metric) -> f64 {
    mean_of(&model.material(values), samples, metric) / metric.mean(samples, |_| Rgb::ZERO)
}

/// `H⁻¹` of a symmetric positive definite `h` (Gauss-Jordan).
fn inverse(h: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = h.len();
    let mut a: Vec<Vec<f64>> = h
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut r = r.clone();
            r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
            r
        })
        .collect();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .unwrap();
        a.swap(c, p);
        let d = a[c][c];
        assert!(
            d.abs() > 0.0,
            "singular Hessian: the parameters are not identifiable"
        );
        for v in a[c].iter_mut() {
            *v /= d;
        }
        for r in 0..n {
            if r != c {
                let f = a[r][c];
                let row = a[c].clone();
                for (v, w) in a[r].iter_mut().zip(row) {
                    *v -= f * w;
                }
            }
        }
    }
    a.into_iter().map(|r| r[n..].to_vec()).collect()
}

fn recovers(spec: &str, truth: &[f64]) {
    let metric = Metric::Ngan;
    let model = FitModel::parse(spec).unwrap();
    assert_eq!(model.free.len(), truth.len(), "{spec}");
    let m = model.material(truth);
    let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
    let samples = samples_of(|_, _, _, wi, wo| m.f_r(wi, wo, &frame));
    let r = fit(&model, &samples, metric);
    found_within_the_tolerance(spec, &model, truth, &r.values, |v| {
        cost(&model, v, &samples, metric)
    });
}

/// The module doc's checks of a fit's `values` against `truth` under
/// the relative `cost` the search minimized: the cost below `C` (else
/// the search stalled), then each number within `sqrt(2 C (H⁻¹)_jj)`.
fn found_within_the_tolerance(
    spec: &str,
    model: &FitModel,
    truth: &[f64],
    values: &[f64],
    cost: impl Fn(&[f64]) -> f64,
) {
    let n = truth.len();
    // The simplex's size: the searched numbers (the linear ones are
    // solved exactly at every point, so they add nothing to the cost's
    // excess over the minimum).
    let searched = searched(model, Metric::Ngan);
    let c_max = 2.0 * ((searched + 1) as f64).sqrt() * SD_TOLERANCE;
    let c = cost(values);
    assert!(
        c <= c_max,
        "{spec}: cost {c:e} > {c_max:e}: the search stalled ({values:?})"
    );
    // The Hessian at the truth, central differences with steps 1e-4 of
    // each value (cost is smooth there; the steps' error is O(h²)).
    let h: Vec<f64> = truth.iter().map(|v| 1e-4 * v.abs().max(1e-2)).collect();
    let at = |di: (usize, f64), dj: (usize, f64)| {
        let mut v = truth.to_vec();
        v[di.0] += di.1;
        v[dj.0] += dj.1;
        cost(&v)
    };
    let hess: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    (at((i, h[i]), (j, h[j]))
                        - at((i, h[i]), (j, -h[j]))
                        - at((i, -h[i]), (j, h[j]))
                        + at((i, -h[i]), (j, -h[j])))
                        / (4.0 * h[i] * h[j])
                })
                .collect()
        })
        .collect();
    let inv = inverse(&hess);
    for j in 0..n {
        let tol = (2.0 * c_max * inv[j][j]).sqrt();
        let key = model.free[j].param.key;
        assert!(
            (values[j] - truth[j]).abs() <= tol,
            "{spec}: {key}[{j}] = {} vs truth {} (tolerance {tol:e})",
            values[j],
            truth[j]
        );
    }
}

#[test]
fn ward_is_recovered() {
    recovers("ward", &[0.3, 0.2, 0.1, 0.2, 0.25, 0.3, 0.15]);
}

#[test]
fn normalized_blinn_phong_is_recovered() {
    recovers(
        "blinn-phong-normalized",
        &[0.5, 0.4, 0.3, 0.1, 0.2, 0.3, 50.0],
    );
}

#[test]
fn cook_torrance_ggx_dielectric_is_recovered() {
    recovers(
        "cook-torrance,distribution=ggx,fresnel=dielectric",
        &[0.2, 0.3, 0.4, 0.2, 0.6, 0.7, 0.8, 1.6],
    );
}

#[test]
fn gltf_pbr_is_recovered() {
    recovers("gltf-pbr", &[0.7, 0.4, 0.2, 0.3, 0.4]);
}

/// A coat over the base: base colour, metallic, roughness, then the coat's
/// weight and roughness (a narrow coat over a wide base, a paint).
#[test]
fn gltf_pbr_with_a_clearcoat_is_recovered() {
    recovers(
        "gltf-pbr,layers=clearcoat",
        &[0.6, 0.3, 0.2, 0.2, 0.6, 0.8, 0.2],
    );
}

/// A sheen over the base: base colour, metallic, roughness, then the
/// sheen's colour and roughness (a fabric's rim over a rough base). The
/// search reads the sheen's albedo from the GPU's table (`fit::terms`), so
/// the synthetic measurements and the cost here take it from there too:
/// what is checked is the search, on data it can fit exactly (the
/// table's own error is measured by `sheen_albedo_table_error`).
#[test]
fn gltf_pbr_with_a_sheen_is_recovered() {
    let spec = "gltf-pbr,layers=sheen";
    let truth = [0.5, 0.3, 0.2, 0.1, 0.7, 0.8, 0.6, 0.6, 0.4];
    let metric = Metric::Ngan;
    let model = FitModel::parse(spec).unwrap();
    assert_eq!(model.free.len(), truth.len());
    let mut samples = samples_of(|_, _, _, _, _| Rgb::ZERO);
    let terms = Terms::new(&samples);
    let f_of = |values: &[f64], samples: &[Sample]| {
        let mut f = Vec::new();
        terms.f_r(&model.material(values), samples, &mut f);
        f
    };
    let measured = f_of(&truth, &samples);
    for (s, f) in samples.iter_mut().zip(measured) {
        s.measured = f;
    }
    let norm = metric.mean(&samples, |_| Rgb::ZERO);
    let r = fit(&model, &samples, metric);
    found_within_the_tolerance(spec, &model, &truth, &r.values, |v| {
        let f = f_of(v, &samples);
        metric.mean(&samples, |i| f[i]) / norm
    });
}

/// Runs `gonio fit ARGS` and checks the one-paragraph exit-2 error.
fn fails_with_2(args: &[&str], names: &str) {
    let out = gonio().arg("fit").args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.starts_with("gonio: error: ") && err.trim_end().lines().count() == 1,
        "{err}"
    );
    assert!(err.contains(names), "{args:?}: `{names}` not in {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bad_input_exits_2_with_one_paragraph_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit.toml");
    let o = out.to_str().unwrap();
    fails_with_2(
        &["no-such-paint", "--model", "ward", "-o", o],
        "no-such-paint",
    );
    fails_with_2(&["chrome", "--model", "mirror", "-o", o], "mirror");
    fails_with_2(
        &["chrome", "--model", "ward,distribution=ggx", "-o", o],
        "ward",
    );
    fails_with_2(
        &[
            "chrome",
            "--model",
            "cook-torrance,distribution=gauss",
            "-o",
            o,
        ],
        "gauss",
    );
    fails_with_2(
        &["missing/file.binary", "--model", "ward", "-o", o],
        "missing/file.binary",
    );
    fails_with_2(&["chrome", "-o", o], "--model");
    fails_with_2(&["--all", "--shard", "0/3", "--out-dir", o], "--shard 0/3");
    assert!(!out.exists(), "no output file after an error");
}

#[test]
fn the_fitted_scene_file_loads_with_the_fitted_material() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fit.toml");
    let run = gonio()
        .args(["fit", "blue-fabric", "--model", "lambert", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        stdout.contains("blue-fabric, lambert, metric ngan: error "),
        "{stdout}"
    );
    let scene =
        gonio::scene::scene_file::load(&gonio::scene::scene_file::SceneSource::File(out), &[])
            .unwrap();
    let m = scene
        .materials
        .iter()
        .find(|m| m.name == "blue-fabric")
        .expect("the fitted material is in the scene");
    assert_eq!(m.model, gonio::material::ReflectanceModel::Lambert);
    // Blue fabric is blue.
    assert!(m.k_d.z > m.k_d.x && m.k_d.z > m.k_d.y, "{:?}", m.k_d);
}

/// abc (Löw et al. 2012) from a synthetic measurement of a moderate lobe
/// (A ≈ 4, B = 500, C = 1.2, η_t = 1.6, as the published glossy paints).
#[test]
fn abc_is_recovered() {
    recovers("abc", &[0.2, 0.1, 0.05, 5.0, 4.0, 3.0, 500.0, 1.2, 1.6]);
}

/// Shard files by hand: `(i, n, csv rows, toml text)` in `dir/shards`.
fn write_shards(dir: &std::path::Path, shards: &[(usize, usize, &str, Option<&str>)]) {
    let folder = dir.join("shards");
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    for (i, n, rows, toml) in shards {
        std::fs::write(
            folder.join(format!("shard-{i}-of-{n}.csv")),
            format!("material,model,metric,error,relative,evaluations,seconds\n{rows}"),
        )
        .unwrap();
        if let Some(t) = toml {
            std::fs::write(folder.join(format!("shard-{i}-of-{n}.toml")), t).unwrap();
        }
    }
}

/// `fit --merge` takes only a whole, sound set of
/// shards, names the missing shard or the bad file and line, and a
/// refused merge leaves the previous ranking as it was.
#[test]
fn merge_refuses_incomplete_mixed_and_bad_shards() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = d.to_str().unwrap();
    let row = |m: &str, e: &str| {
        format!("{m},ward,ngan,{e},0.5,10,0.1\n{m},lambert,ngan,2.0,0.9,10,0.1\n")
    };
    let toml = Some("[materials.x]\nmodel = \"ward\"\n");
    std::fs::write(d.join("ranking.csv"), "the previous ranking\n").unwrap();
    let merge = ["--merge", "--out-dir", o];
    // Shard 1 of 2 alone merged with exit 0 and ranked half the materials.
    write_shards(d, &[(1, 2, &row("a", "1.0"), toml)]);
    fails_with_2(&merge, "shard 2 of 2 is missing");
    // Shards of two runs.
    write_shards(
        d,
        &[
            (1, 2, &row("a", "1.0"), toml),
            (1, 3, &row("b", "1.0"), toml),
        ],
    );
    fails_with_2(&merge, "mixes runs");
    // A CSV whose TOML was never written (a full disk).
    write_shards(d, &[(1, 1, &row("a", "1.0"), None)]);
    fails_with_2(&merge, "shard-1-of-1.toml");
    // Non-finite and negative errors were ranked (NaN as rank 0.5).
    for bad in ["NaN", "inf", "-1.0"] {
        write_shards(d, &[(1, 1, &row("a", bad), toml)]);
        fails_with_2(&merge, "line 2");
        fails_with_2(&merge, "shard-1-of-1.csv");
    }
    // A shard TOML that is not TOML was copied into fits.toml.
    write_shards(
        d,
        &[(
            1,
            1,
            &row("a", "1.0"),
            Some("[materials.x]\nmodel = 1\n[[[ not toml\n"),
        )],
    );
    fails_with_2(&merge, "shard-1-of-1.toml");
    fails_with_2(&merge, "line 3");
    // No rows at all gave "mean rank: " and nothing.
    write_shards(d, &[(1, 1, "", toml)]);
    fails_with_2(&merge, "no fits");
    assert_eq!(
        std::fs::read_to_string(d.join("ranking.csv")).unwrap(),
        "the previous ranking\n"
    );
    assert!(!d.join("fits.toml").exists() && !d.join("ranking.md").exists());
    // A whole set merges, its files appearing together.
    write_shards(
        d,
        &[
            (1, 2, &row("a", "1.0"), toml),
            (2, 2, &row("b", "3.0"), toml),
        ],
    );
    let out = gonio().arg("fit").args(merge).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let ranking = std::fs::read_to_string(d.join("ranking.csv")).unwrap();
    assert_eq!(ranking.lines().count(), 5, "{ranking}");
    assert!(d.join("fits.toml").exists() && d.join("ranking.md").exists());
}

/// `--shard` without `--all` was once ignored without a word.
#[test]
fn shard_without_all_is_refused() {
    fails_with_2(&["chrome", "--model", "ward", "--shard", "1/2"], "--all");
}

/// `--shard auto` takes the shard from a Slurm array task's variables;
/// a shard whose files already hold this run's fits is skipped, and one
/// of another run (other models) is fitted again.
#[test]
fn fit_shards_read_slurm_and_restart() {
    let dir = tempfile::tempdir().unwrap();
    let run = |model: &str, env: &[(&str, &str)]| {
        let mut cmd = gonio();
        for v in [
            "SLURM_ARRAY_TASK_ID",
            "SLURM_ARRAY_TASK_MIN",
            "SLURM_ARRAY_TASK_MAX",
            "SLURM_ARRAY_TASK_COUNT",
            "JOB_COMPLETION_INDEX",
            "HQ_TASK_ID",
        ] {
            cmd.env_remove(v);
        }
        let out = cmd
            .args([
                "fit",
                "--all",
                "--materials",
                "chrome,blue-fabric,alum-bronze",
            ])
            .args(["--model", model, "--shard", "auto", "--out-dir"])
            .arg(dir.path())
            .envs(env.iter().copied())
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let slurm = [
        ("SLURM_ARRAY_TASK_ID", "2"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_MAX", "2"),
        ("SLURM_ARRAY_TASK_COUNT", "2"),
    ];
    let (code, err) = run("lambert", &slurm);
    assert_eq!(code, Some(0), "{err}");
    let csv = dir.path().join("shards/shard-2-of-2.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    // Shard 2 of 2 of three materials: the second only.
    assert!(
        text.contains("blue-fabric,lambert") && !text.contains("chrome"),
        "{text}"
    );
    let (code, err) = run("lambert", &slurm);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("skipped"), "{err}");
    let (code, err) = run("ward", &slurm);
    assert_eq!(code, Some(0), "{err}");
    assert!(!err.contains("skipped"), "{err}");
    assert!(
        std::fs::read_to_string(&csv)
            .unwrap()
            .contains("blue-fabric,ward")
    );
    let (code, err) = run("lambert", &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("SLURM_ARRAY_TASK_ID"), "{err}");
}
