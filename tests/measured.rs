//! Measured materials: the built-in networks against values
//! computed independently, MERL files made here from an analytic model read
//! back, bad files refused with exit 2, and the GPU's filtered tables
//! against the reference.

mod common;

use glam::DVec3;
use gonio::base::Rgb;
use gonio::material::brdf::SurfaceFrame;
use gonio::material::measured::merl::{self, MerlTable};
use gonio::material::measured::{self, coords};
use gonio::material::{Distribution, Material, ReflectanceModel};
use std::path::Path;

fn frame() -> SurfaceFrame {
    SurfaceFrame::new(DVec3::Z, DVec3::X)
}

fn direction(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn builtin(name: &str) -> Material {
    let mut m = Material::new(name, ReflectanceModel::Measured);
    m.measured = Some(measured::library::builtin(name).unwrap());
    m
}

/// `python3 scripts/nbrdf_reference.py`: the network evaluated from the
/// JSON in plain Python floats, the half/difference vectors from rotation
/// matrices (not gonio's code). (material, (θ_i, φ_i), (θ_o, φ_o)) in
/// degrees, RGB f_r in 1/sr.
#[allow(clippy::type_complexity)]
const PYTHON_VALUES: &[(&str, (f64, f64), (f64, f64), [f64; 3])] = &[
    (
        "gold-metallic-paint",
        (30.0, 0.0),
        (30.0, 180.0),
        [0.5333492233589758, 0.3839082870540853, 0.11674165835794792],
    ),
    (
        "gold-metallic-paint",
        (60.0, 10.0),
        (20.0, 200.0),
        [
            0.07381837509183153,
            0.047082988407409765,
            0.015723068216427105,
        ],
    ),
    (
        "chrome",
        (45.0, 0.0),
        (45.0, 180.0),
        [735.1619162742334, 872.1098832497236, 881.9516828623963],
    ),
    (
        "chrome",
        (45.0, 0.0),
        (40.0, 170.0),
        [
            0.01600786421500522,
            0.014900220567219069,
            0.016555459317402432,
        ],
    ),
    (
        "blue-fabric",
        (10.0, 0.0),
        (70.0, 90.0),
        [
            0.007401090750741135,
            0.008501512083038731,
            0.019444381575319136,
        ],
    ),
    (
        "blue-fabric",
        (0.0, 0.0),
        (0.0, 0.0),
        [
            0.009954953229273755,
            0.01063334640185376,
            0.023006779124776777,
        ],
    ),
    (
        "alum-bronze",
        (80.0, 30.0),
        (75.0, 250.0),
        [
            0.014584916766435141,
            0.01237574373474537,
            0.008863173267571689,
        ],
    ),
];

/// The same sums in another order and the angles by other formulas: the
/// inputs agree to a few ulp, and the network (weights of order 1, 21
/// terms per sum, `exp` at the end with |z| < 8) keeps that within 1e-12
/// relative; 1e-10 leaves a wide margin and still catches any wrong
/// weight, layout or coordinate.
#[test]
fn the_network_matches_independent_values() {
    for &(name, (ti, pi), (to, po), want) in PYTHON_VALUES {
        let got = builtin(name).f_r(direction(ti, pi), direction(to, po), &frame());
        for c in 0..3 {
            let rel = (got[c] - want[c]).abs() / want[c];
            assert!(
                rel < 1e-10,
                "{name} ({ti},{pi}) ({to},{po}): {got} vs {want:?}"
            );
        }
    }
}

#[test]
fn measured_is_zero_below_either_horizon() {
    let m = builtin("blue-fabric");
    let below = DVec3::new(0.3, 0.0, -0.1).normalize();
    let above = direction(30.0, 0.0);
    assert_eq!(m.f_r(below, above, &frame()), Rgb::ZERO);
    assert_eq!(m.f_r(above, below, &frame()), Rgb::ZERO);
    // Grazing, θ_d → 90°: finite and non-negative.
    let f = m.f_r(direction(89.99, 0.0), direction(89.99, 180.0), &frame());
    assert!(f.is_finite() && f.min_element() >= 0.0, "{f}");
    let f = m.f_r(direction(89.99, 0.0), direction(89.99, 0.5), &frame());
    assert!(f.is_finite() && f.min_element() >= 0.0, "{f}");
}

fn analytic() -> Material {
    let mut m = Material::new("ct", ReflectanceModel::CookTorrance);
    m.distribution = Distribution::Ggx;
    (m.roughness, m.k_d, m.k_s) = (0.25, Rgb::new(0.2, 0.1, 0.05), Rgb::ONE);
    m
}

/// A MERL-format file of an analytic model (samples below the horizon
/// marked missing, as in MERL's files), as gonio writes it.
fn analytic_file(dir: &Path, dims: [usize; 3]) -> std::path::PathBuf {
    let ct = analytic();
    let table = MerlTable::sample(dims, |th, td, pd| {
        let (wi, wo) = coords::directions(th, td, pd);
        if wi.z <= 0.0 || wo.z <= 0.0 {
            Rgb::splat(-1.0)
        } else {
            ct.f_r(wi, wo, &frame())
        }
    });
    let path = dir.join("ct.binary");
    std::fs::write(&path, table.encode()).unwrap();
    path
}

/// At its samples the file's look-up is the model's value: the trilinear
/// weights there are 0 and 1, up to the rounding of the angles
/// (≈ 1e-16 of an index step; near the GGX peak neighbouring samples
/// differ by < 100×, so 1e-9 relative is wide).
#[test]
fn a_merl_file_of_an_analytic_model_reads_back_at_its_samples() {
    let dir = tempfile::tempdir().unwrap();
    let dims = [30, 30, 60];
    analytic_file(dir.path(), dims);
    let m = measured::resolve("ct.binary", dir.path()).unwrap();
    let measured::Source::Table(t) = &m.source else {
        panic!("a file is a table")
    };
    assert_eq!(t.dims, dims);
    assert!(t.missing > 0, "samples below the horizon are marked");
    assert_eq!(t.known_as, None);
    let ct = analytic();
    let mut checked = 0;
    for ih in (0..dims[0]).step_by(3) {
        for id in (0..dims[1]).step_by(4) {
            for ip in (0..dims[2]).step_by(7) {
                let (th, td, pd) = merl::sample_angles(dims, ih, id, ip);
                let (wi, wo) = coords::directions(th, td, pd);
                let got = m.f_r(wi, wo, &frame());
                let want = if wi.z <= 0.0 || wo.z <= 0.0 {
                    Rgb::ZERO
                } else {
                    ct.f_r(wi, wo, &frame())
                };
                let err = (got - want).abs().max_element();
                assert!(
                    err <= 1e-9 * want.max_element() + 1e-12,
                    "sample ({ih}, {id}, {ip}): {got} vs {want}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 100);
}

/// Runs `gonio brdf` on a material with `measured = file` (relative to the
/// working directory `dir`).
fn brdf_with_file(dir: &Path, file: &str) -> std::process::Output {
    common::gonio()
        .current_dir(dir)
        .args(["brdf", "--model", "measured", "--set"])
        .arg(format!("measured={file}"))
        .output()
        .unwrap()
}

#[test]
fn bad_files_exit_2_with_one_paragraph_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = MerlTable::sample([4, 4, 8], |_, _, _| Rgb::splat(0.1)).encode();
    let mut nan = good.clone();
    nan[12 + 8 * 5..12 + 8 * 6].copy_from_slice(&f64::NAN.to_le_bytes());
    let mut header = good.clone();
    header[4..8].copy_from_slice(&0i32.to_le_bytes());
    let mut long = good.clone();
    long.extend([0; 8]);
    let cases: [(&str, &[u8], &str); 5] = [
        ("short.binary", &good[..10], "truncated"),
        ("cut.binary", &good[..good.len() - 3], "truncated"),
        ("header.binary", &header, "wrong header"),
        ("nan.binary", &nan, "NaN"),
        ("long.binary", &long, "wrong size"),
    ];
    for (name, bytes, problem) in cases {
        std::fs::write(dir.path().join(name), bytes).unwrap();
        let out = brdf_with_file(dir.path(), name);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(name) && err.contains(problem), "{name}: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{name}: one paragraph: {err}"
        );
    }
    let out = brdf_with_file(dir.path(), "missing.binary");
    assert_eq!(out.status.code(), Some(2));
    // The good file works.
    std::fs::write(dir.path().join("good.binary"), &good).unwrap();
    let out = brdf_with_file(dir.path(), "good.binary");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn keys_a_measured_material_does_not_read_are_refused() {
    let out = common::gonio()
        .args([
            "brdf",
            "--model",
            "measured",
            "--set",
            "measured=chrome",
            "--set",
            "k_d=0.5",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("k_d") && err.contains("does not apply"),
        "{err}"
    );
    let out = common::gonio()
        .args(["brdf", "--model", "measured", "--set", "measured=gold"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("gold-metallic-paint"),
        "lists the names: {err}"
    );
}

/// A 96×96 sphere of material `name` under a point light and a
/// directional one, GPU tables of `dims` samples.
fn sphere_scene(dir: &Path, name: &str, dims: [u32; 3]) -> gonio::scene::Scene {
    use gonio::scene::scene_file::{self, SceneSource};
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            r#"
[image]
width = 96
height = 96
[camera]
position = [0.0, 0.0, 4.0]
target = [0.0, 0.0, 0.0]
fov_y_deg = 30.0
[shading]
mode = "phong"
measured_table = [{}, {}, {}]
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
segments = 96
material = "m"
[materials.m]
model = "measured"
measured = "{name}"
[[lights]]
kind = "point"
position = [2.0, 3.0, 4.0]
intensity = [20.0, 20.0, 20.0]
[[lights]]
kind = "directional"
direction = [0.6, 0.3, -0.75]
irradiance = [1.0, 1.0, 1.0]
"#,
            dims[0], dims[1], dims[2]
        ),
    )
    .unwrap();
    scene_file::load(&SceneSource::File(path), &[]).expect("scene loads")
}

/// `scene` with each measured material replaced by the `f64` twin of its
/// GPU table: the MERL-format table of the same samples, looked up by the
/// same rule in `f64` (`MerlTable::f_r`).
fn with_table_twin(scene: &gonio::scene::Scene) -> gonio::scene::Scene {
    let mut twin = scene.clone();
    let dims = scene.measured_table.map(|n| n as usize);
    for m in &mut twin.materials {
        if let Some(brdf) = m.measured_brdf() {
            let table = gonio::gpu::measured_tables::as_merl_table(brdf, dims);
            m.measured = Some(Box::leak(Box::new(measured::MeasuredBrdf {
                name: format!("{} (table)", brdf.name),
                source: measured::Source::Table(table),
            })));
        }
    }
    twin
}

/// The GPU's table render against the reference of the same table in
/// `f64` (the filter's CPU twin), under the derived GPU-vs-reference
/// tolerance of tests/gpu_vs_cpu.rs: the light loop's 64ε, the look-up's
/// own rounding (the measured row's `f32_error`: eight samples rounded to
/// `f32`, seven lerps) and the sub-pixel jitter of the rasterizer, which
/// also covers the `f32` rounding of the half/difference angles (a shift of
/// the directions far smaller than 1/128 px of the view). The table's
/// distance from the network itself is `the_table_is_within_its_filter_bound`.
#[test]
fn gpu_tables_match_their_reference_twin() {
    let dir = tempfile::tempdir().unwrap();
    let mut gpu = common::gpu_renderer();
    for name in ["gold-metallic-paint", "chrome", "blue-fabric"] {
        let scene = sphere_scene(dir.path(), name, [45, 45, 90]);
        let (frame, _) = gpu.render(&scene).unwrap();
        let twin = with_table_twin(&scene);
        let (center, jittered) = common::reference_with_jitter(&twin);
        let c = common::compare_to_reference(&twin, &frame, &center, &jittered);
        common::assert_agrees(
            &format!("measured-{name}"),
            "GPU table vs its f64 twin",
            &c,
            &frame,
            &center,
        );
    }
}

/// The relative error bound of the WGSL network (`shading.measured_mode =
/// "network"`) against `Network::f_r` in `f64`, derived from the weights by
/// running-error analysis: every input is a unit vector's component
/// (|x| ≤ 1) computed in `f32` within 64 roundings (64u absolute, as the
/// equivalence test's K); a dot product of n terms plus a bias errs by at
/// most γ(n+1) = (n+1)u/(1 − (n+1)u) times the sum of the magnitudes of
/// its terms, and passes its inputs' errors on through |W|; ReLU adds
/// none. With `A` the magnitudes (the network run on |W|, |b| and |x| = 1)
/// and `e` the errors, the output `z` errs by `e3`, so `e^z` by a relative
/// `e3 + (3 + 2|z|)u` (Vulkan's `exp`), and `f_r = e^z − 1` by that times
/// `f_r + 1`, plus one rounding of the subtraction.
fn network_rel_bound(n: &measured::network::Network) -> f64 {
    const U: f64 = 1.0 / 16_777_216.0;
    let gamma = |k: f64| k * U / (1.0 - k * U);
    let dx = 64.0 * U;
    let (mut a1, mut e1) = ([0.0; 21], [0.0; 21]);
    for j in 0..21 {
        let sum_w: f64 = (0..6).map(|i| n.w1[i][j].abs()).sum();
        a1[j] = n.b1[j].abs() + sum_w;
        e1[j] = sum_w * dx + gamma(7.0) * a1[j];
    }
    let (mut a2, mut e2) = ([0.0; 21], [0.0; 21]);
    for j in 0..21 {
        a2[j] = n.b2[j].abs() + (0..21).map(|k| n.w2[k][j].abs() * a1[k]).sum::<f64>();
        e2[j] = (0..21).map(|k| n.w2[k][j].abs() * e1[k]).sum::<f64>() + gamma(22.0) * a2[j];
    }
    (0..3)
        .map(|c| {
            let z = n.b3[c].abs() + (0..21).map(|k| n.w3[k][c].abs() * a2[k]).sum::<f64>();
            let e3 = (0..21).map(|k| n.w3[k][c].abs() * e2[k]).sum::<f64>() + gamma(22.0) * z;
            e3 + (3.0 + 2.0 * z) * U + U
        })
        .fold(0.0, f64::max)
}

/// The Neural-BRDF network evaluated in WGSL (`shading.measured_mode =
/// "network"`) against the reference, which evaluates the same network in
/// `f64`: per pixel within the light loop's tolerance plus the network's
/// derived bound [`network_rel_bound`] `r`: `|ΔL| ≤ Σ_l |Δf_l| E_l cos θ_l
/// ≤ r (L + Σ_l E_l)`, the `(f_r + 1)` of the bound split into a relative
/// part and an absolute one, `Σ_l E_l` ≤ 2.04 W/m² on the sphere
/// (the point light of 20 W/sr at ≥ 4.385 m, 1.04; the directional 1).
#[test]
fn gpu_network_matches_the_f64_network() {
    use gonio::output::compare::{Tolerance, compare_with_jitter};
    use gonio::scene::scene_file::{self, SceneSource};
    let dir = tempfile::tempdir().unwrap();
    let mut gpu = common::gpu_renderer();
    for name in ["gold-metallic-paint", "chrome", "blue-fabric"] {
        sphere_scene(dir.path(), name, [16, 16, 32]);
        let path = dir.path().join(format!("{name}.toml"));
        let scene = scene_file::load(
            &SceneSource::File(path),
            &["shading.measured_mode=\"network\"".to_string()],
        )
        .expect("scene loads");
        assert!(scene.measured_network);
        let brdf = measured::library::builtin(name).unwrap();
        let measured::Source::Network(net) = &brdf.source else {
            panic!("a built-in material is a network");
        };
        let r = network_rel_bound(net);
        let (frame, _) = gpu.render(&scene).unwrap();
        let (center, jittered) = common::reference_with_jitter(&scene);
        let tolerance = Tolerance {
            rel: 64.0 * common::EPS + r,
            abs: 64.0 * common::EPS * center.max_radiance() as f64 + r * 2.04,
        };
        let c = compare_with_jitter(&frame, &center, &jittered, tolerance);
        eprintln!("network {name}: bound r = {r:.3e}; {}", c.summary());
        common::assert_agrees(
            &format!("measured-network-{name}"),
            "GPU network vs the f64 network",
            &c,
            &frame,
            &center,
        );
    }
}

/// The trilinear filter's error against the network. Linear
/// interpolation over a step `Δ` errs by at most `Δ²/8 · max|f''|` per
/// axis, and the three axes add: in index units (`Δ = 1`)
/// `|f − I f| ≤ ⅛ Σ_k max|∂²_k f|` (plus, past an axis' last sample where
/// the look-up clamps, the slope times the distance). The table itself
/// estimates `f''` by its second differences around the cell
/// (`MerlTable::second_difference_bound`), ×2 for curvature varying within
/// a cell. It is an estimate, not a bound: the network's curvature can
/// peak between samples (ReLU kinks; steep grazing θ_d; chrome's peak is
/// narrower than a θ_h step at 45 samples, where it errs by up to 8× the
/// estimate), so the test asks that it covers at least 98 % of random
/// direction pairs above both horizons (a wrong filter, coordinate or
/// sample position covers far fewer). The exact error of the GPU's
/// table against the network is the f64 twin's (`with_table_twin`):
/// GPU − network = (GPU − twin) + (twin − network), the first within the
/// f32 tolerance (`gpu_tables_match_their_reference_twin`), the second
/// exact in f64 and measured per resolution in docs/measured.md.
#[test]
fn the_table_is_within_its_filter_estimate() {
    use gonio::gpu::measured_tables::as_merl_table;
    let dims = [45, 45, 90];
    let mut rng = 0x2545F4914F6CDD1Du64;
    let mut uniform = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for name in ["gold-metallic-paint", "chrome", "blue-fabric"] {
        let brdf = measured::library::builtin(name).unwrap();
        let table = as_merl_table(brdf, dims);
        let (mut pairs, mut covered, mut worst_ratio, mut worst_rel) = (0, 0, 0f64, 0f64);
        while pairs < 2000 {
            let th = uniform().powi(2) * std::f64::consts::FRAC_PI_2;
            let td = uniform() * std::f64::consts::FRAC_PI_2;
            let pd = uniform() * std::f64::consts::PI;
            let (wi, wo) = coords::directions(th, td, pd);
            if wi.z <= 0.0 || wo.z <= 0.0 {
                continue; // never rendered (f_r = 0 below either horizon)
            }
            pairs += 1;
            let exact = brdf.f_r_half_diff(&coords::half_diff_of_angles(th, td, pd));
            let filtered = table.f_r(th, td, pd);
            let estimate = 2.0 * table.second_difference_bound(th, td, pd) + 1e-12;
            let err = (filtered - exact).abs();
            let ratio = (err / estimate).max_element();
            covered += (ratio <= 1.0) as usize;
            worst_ratio = worst_ratio.max(ratio);
            worst_rel = worst_rel.max((err / exact.max(Rgb::splat(1e-3))).max_element());
        }
        eprintln!(
            "{name}: {covered}/{pairs} within the estimate, worst error/estimate {worst_ratio:.2}, worst relative error {worst_rel:.3e} at {dims:?}"
        );
        assert!(covered * 100 >= pairs * 98, "{name}: {covered}/{pairs}");
    }
}

/// The table-resolution trade of `docs/measured.md` (not a check: it
/// prints, for each resolution, the CPU build time of one table, the GPU
/// render time and the image error against the network's reference):
/// `cargo test --release --test measured -- --ignored --nocapture resolution_trade`.
#[test]
#[ignore]
fn resolution_trade() {
    use std::time::Instant;
    let dir = tempfile::tempdir().unwrap();
    let mut gpu = common::gpu_renderer();
    println!(
        "| material | table (n_h, n_d, n_φ) | samples | table build [s] | GPU render [s] | max \\|ΔL\\|/max L | mean \\|ΔL\\|/mean L |"
    );
    println!("|---|---|---|---|---|---|---|");
    for name in ["gold-metallic-paint", "chrome", "blue-fabric"] {
        let base = sphere_scene(dir.path(), name, [90, 90, 180]);
        let reference = gonio::reference::render(&base);
        for dims in [
            [16, 16, 32],
            [32, 32, 64],
            [45, 45, 90],
            [90, 90, 180],
            [180, 90, 180],
        ] {
            let mut scene = base.clone();
            scene.measured_table = dims;
            let brdf = scene.materials[0].measured_brdf().unwrap();
            let t = Instant::now();
            let _ = gonio::gpu::measured_tables::build(brdf, dims.map(|n| n as usize));
            let build = t.elapsed().as_secs_f64();
            let _ = gpu.render(&scene).unwrap(); // table cached, pipeline compiled
            let t = Instant::now();
            let (frame, _) = gpu.render(&scene).unwrap();
            let render = t.elapsed().as_secs_f64();
            let (mut max_d, mut sum_d, mut max_l, mut sum_l) = (0f64, 0f64, 0f64, 0f64);
            for (a, b) in frame.radiance.iter().zip(&reference.radiance) {
                for c in 0..3 {
                    let (a, b) = (a[c] as f64, b[c] as f64);
                    max_d = max_d.max((a - b).abs());
                    sum_d += (a - b).abs();
                    max_l = max_l.max(b);
                    sum_l += b;
                }
            }
            println!(
                "| {name} | {dims:?} | {} | {build:.3} | {render:.3} | {:.2e} | {:.2e} |",
                dims.iter().product::<u32>(),
                max_d / max_l,
                sum_d / sum_l
            );
        }
    }
}

/// `measured = "file.binary"` in a scene file is relative to the scene
/// file (not the working directory); a bad one stops `gonio render` with
/// exit 2 and no output file.
#[test]
fn a_scene_files_table_path_is_relative_to_it() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("scenes");
    std::fs::create_dir(&sub).unwrap();
    analytic_file(&sub, [8, 8, 16]);
    std::fs::write(
        sub.join("s.toml"),
        "[image]\nwidth = 32\nheight = 24\n[[objects]]\nshape = \"sphere\"\nmaterial = \"m\"\n\
         [materials.m]\nmodel = \"measured\"\nmeasured = \"ct.binary\"\n\
         [[lights]]\nkind = \"point\"\nposition = [2.0, 3.0, 4.0]\nintensity = [20.0, 20.0, 20.0]\n",
    )
    .unwrap();
    let render = |out: &str| {
        common::gonio()
            .current_dir(dir.path())
            .args(["render", "scenes/s.toml", "--reference", "-o", out])
            .output()
            .unwrap()
    };
    let out = render("ok.png");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.path().join("ok.png").is_file());
    let bytes = std::fs::read(sub.join("ct.binary")).unwrap();
    std::fs::write(sub.join("ct.binary"), &bytes[..bytes.len() / 2]).unwrap();
    let out = render("bad.png");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("ct.binary") && err.contains("truncated"),
        "{err}"
    );
    assert!(!dir.path().join("bad.png").exists());
}

/// `shading.measured_mode`: a MERL file has no network, so network mode
/// refuses it naming the material; an unknown mode names both choices.
#[test]
fn network_mode_refuses_a_merl_file_and_unknown_modes() {
    let dir = tempfile::tempdir().unwrap();
    let file = analytic_file(dir.path(), [8, 8, 16]);
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        format!(
            "[shading]\nmeasured_mode = \"network\"\n[[objects]]\nshape = \"sphere\"\nmaterial = \"m\"\n[materials.m]\nmodel = \"measured\"\nmeasured = {:?}\n",
            file.display().to_string()
        ),
    )
    .unwrap();
    let out = common::gonio()
        .args(["render"])
        .arg(&scene)
        .args(["-o"])
        .arg(dir.path().join("x.png"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("measured_mode") && err.contains("`m`"),
        "{err}"
    );
    assert!(!dir.path().join("x.png").exists());
    let out = common::gonio()
        .args(["render", "--set", "shading.measured_mode=\"tabel\"", "-o"])
        .arg(dir.path().join("y.png"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("\"table\"") && err.contains("\"network\""),
        "{err}"
    );
}
