//! What got in a new user's way, through the binary: `--set`
//! composes with a scene as the same keys in the file do (partial camera
//! keys on a glTF, quoted dotted material names, switching the built-in
//! ball's model), files gonio writes read back without a warning, every
//! name typed gets the nearest name suggested, and the README's fit
//! example is the real fit.

mod common;

use gonio::scene::scene_file::{self, SceneSource};
use std::path::{Path, PathBuf};

/// Runs gonio with `args`: (exit code, stderr).
fn run(args: &[&str]) -> (Option<i32>, String) {
    let out = common::gonio().args(args).output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `gonio render SCENE --set ...` at a small size into `out`: (exit code,
/// stderr, the image's bytes).
fn render(scene: Option<&Path>, sets: &[&str], out: &Path) -> (Option<i32>, String, Vec<u8>) {
    let mut cmd = common::gonio();
    cmd.arg("render");
    if let Some(s) = scene {
        cmd.arg(s);
    }
    cmd.args(["--width", "48", "--height", "36", "-o"]).arg(out);
    for s in sets {
        cmd.args(["--set", s]);
    }
    let o = cmd.output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        std::fs::read(out).unwrap_or_default(),
    )
}

/// Item 2: camera keys given alone keep the rest of the automatic camera
/// (the glTF's own, or the framing one), through `--set` and in a file
/// alike (they failed with "missing field `target`").
#[test]
fn partial_camera_keys_compose_with_the_automatic_camera() {
    let dir = tempfile::tempdir().unwrap();
    let coords = common::gltf_asset("TextureCoordinateTest/TextureCoordinateTest.glb");
    let (code, stderr, _) = render(
        Some(&coords),
        &["camera.position=[0,0,-4]", "camera.target=[0,0,0]"],
        &dir.path().join("coords.png"),
    );
    assert_eq!(code, Some(0), "{stderr}{}", common::LAVAPIPE_TEST_HINT);

    let boxed = common::gltf_asset("Box/Box.gltf");
    let (code, stderr, plain) = render(Some(&boxed), &[], &dir.path().join("plain.png"));
    assert_eq!(code, Some(0), "{stderr}");
    let (code, stderr, narrow) = render(
        Some(&boxed),
        &["camera.fov_y_deg=30"],
        &dir.path().join("narrow.png"),
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert_ne!(plain, narrow, "the field of view did not change the image");
    // The same key in a scene file gives the same image.
    let file = dir.path().join("box.toml");
    std::fs::write(
        &file,
        format!(
            "[[objects]]\ngltf = {}\n\n[camera]\nfov_y_deg = 30\n",
            toml::Value::String(boxed.display().to_string())
        ),
    )
    .unwrap();
    let (code, stderr, from_file) = render(Some(&file), &[], &dir.path().join("file.png"));
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(from_file, narrow, "file and --set differ");
}

/// Every key path of the built-in scene file, given alone by `--set` to a
/// scene that lacks its section (a bare glTF), loads, and gives the scene
/// the same key gives in a file: sections merge key by key. Entries of
/// `[[arrays]]` and materials are added whole (a new material starts with
/// its model), which the messages say; they are checked apart.
#[test]
fn every_key_path_merges_into_a_gltf_scene_as_in_a_file() {
    let builtin: toml::Table = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/default.toml"),
    )
    .unwrap()
    .parse()
    .unwrap();
    let mut paths = Vec::new();
    leaf_paths(&builtin, &mut Vec::new(), &mut paths);
    let section_keys: Vec<&(Vec<String>, toml::Value)> = paths
        .iter()
        .filter(|(p, _)| !matches!(p[0].as_str(), "objects" | "lights" | "materials"))
        .collect();
    assert!(section_keys.len() >= 8, "{section_keys:?}");
    let dir = tempfile::tempdir().unwrap();
    let boxed = common::gltf_asset("Box/Box.gltf");
    for (path, value) in section_keys {
        let key = path.join(".");
        let set = format!("{key}={value}");
        let by_set = scene_file::load(
            &SceneSource::File(boxed.clone()),
            std::slice::from_ref(&set),
        )
        .unwrap_or_else(|e| panic!("--set {set}: {e}"));
        let file = dir.path().join("one-key.toml");
        let mut table = toml::Table::new();
        let mut object = toml::Table::new();
        object.insert("gltf".into(), boxed.display().to_string().into());
        table.insert("objects".into(), vec![toml::Value::Table(object)].into());
        scene_file::apply_override(&mut table, &set).unwrap();
        std::fs::write(&file, toml::to_string(&table).unwrap()).unwrap();
        let by_file = scene_file::load(&SceneSource::File(file), &[])
            .unwrap_or_else(|e| panic!("{key} in a file: {e}"));
        assert_eq!(
            format!("{:?}", by_set.camera),
            format!("{:?}", by_file.camera),
            "{key}"
        );
        assert_eq!(
            (by_set.width, by_set.height, by_set.shading, by_set.ambient),
            (
                by_file.width,
                by_file.height,
                by_file.shading,
                by_file.ambient
            ),
            "{key}"
        );
    }
}

fn leaf_paths(
    table: &toml::Table,
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, toml::Value)>,
) {
    for (k, v) in table {
        prefix.push(k.clone());
        match v {
            toml::Value::Table(t) => leaf_paths(t, prefix, out),
            other => out.push((prefix.clone(), other.clone())),
        }
        prefix.pop();
    }
}

/// A copy of Box.gltf whose one material is called `name` (or has no
/// name: the import calls it `material 0`).
fn box_with_material_name(dir: &Path, name: Option<&str>) -> PathBuf {
    let source = common::gltf_asset("Box/Box.gltf");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&source).unwrap()).unwrap();
    let material = &mut json["materials"][0];
    match name {
        Some(n) => material["name"] = n.into(),
        None => {
            material.as_object_mut().unwrap().remove("name");
        }
    }
    std::fs::copy(source.with_file_name("Box0.bin"), dir.join("Box0.bin")).unwrap();
    let path = dir.join("renamed.gltf");
    std::fs::write(&path, json.to_string()).unwrap();
    path
}

/// Whether the image (PNG bytes) has a clearly green pixel.
fn has_green(png: &[u8]) -> bool {
    let image = image::load_from_memory(png).unwrap().into_rgb8();
    image
        .pixels()
        .any(|p| p.0[1] > 60 && p.0[1] as u16 > 2 * p.0[0] as u16)
}

/// Item 3: a glTF material's name with dots (Blender's `Material.005`) or
/// a space (an unnamed one's `material 0`) is addressed quoted, as a TOML
/// file quotes it (the key was split inside the quotes).
#[test]
fn quoted_material_names_keep_their_dots() {
    let dir = tempfile::tempdir().unwrap();
    let dotted = box_with_material_name(dir.path(), Some("Material.005"));
    let (code, stderr, red) = render(Some(&dotted), &[], &dir.path().join("red.png"));
    assert_eq!(code, Some(0), "{stderr}{}", common::LAVAPIPE_TEST_HINT);
    assert!(!has_green(&red));
    for set in [
        "gltf_materials.\"Material.005\".base_color=[0,0.8,0]",
        "materials.\"Material.005\".base_color=[0,0.8,0]",
        "materials.'Material.005'.base_color=[0,0.8,0]",
    ] {
        let (code, stderr, green) = render(Some(&dotted), &[set], &dir.path().join("g.png"));
        assert_eq!(code, Some(0), "--set {set}: {stderr}");
        assert!(has_green(&green), "--set {set} did not turn the box green");
    }
    let unnamed_dir = dir.path().join("unnamed");
    std::fs::create_dir(&unnamed_dir).unwrap();
    let unnamed = box_with_material_name(&unnamed_dir, None);
    let (code, stderr, green) = render(
        Some(&unnamed),
        &["materials.\"material 0\".base_color=[0,0.8,0]"],
        &dir.path().join("u.png"),
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(has_green(&green));
}

/// Item 4 (and item 5's `--set`): switching the built-in ball's model by
/// `--set` does not inherit the built-in keys the new model does not read
/// (`measured` failed with "k_d does not apply … remove it"; cook-torrance
/// warned about the built-in `k_e`), while a key the user set is still
/// named.
#[test]
fn the_built_in_ball_switches_model_without_the_old_keys() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ball.png");
    let (code, stderr, _) = render(
        None,
        &[
            "materials.ball.model=measured",
            "materials.ball.measured=chrome",
        ],
        &out,
    );
    assert_eq!(code, Some(0), "{stderr}{}", common::LAVAPIPE_TEST_HINT);
    assert!(!stderr.contains("warning"), "{stderr}");
    for model in gonio::material::ReflectanceModel::ALL {
        if model == gonio::material::ReflectanceModel::Measured {
            continue;
        }
        let set = format!("materials.ball.model={model}");
        let loaded = scene_file::load_with_limits(
            &SceneSource::BuiltIn,
            std::slice::from_ref(&set),
            Default::default(),
        );
        let (_, notes) = loaded.unwrap_or_else(|e| panic!("--set {set}: {e}"));
        assert!(
            !notes.iter().any(|n| n.starts_with(scene_file::WARNING)),
            "--set {set}: {notes:?}"
        );
    }
    let (code, stderr, _) = render(
        None,
        &["materials.ball.k_e=20", "materials.ball.model=lambert"],
        &out,
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("`k_e` not read by model `lambert`"),
        "{stderr}"
    );
}

/// Item 5: the scene file `gonio fit -o` writes renders without a warning,
/// its numbers at most six significant digits (a fit wrote 8 keys the model
/// does not read and `k_d = [0.00000000022859258930196802, …]`).
#[test]
fn a_fitted_scene_renders_without_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let fitted = dir.path().join("f.toml");
    let fit = common::gonio()
        .args([
            "fit",
            "gold-metallic-paint",
            "--model",
            "cook-torrance,distribution=ggx,fresnel=conductor",
            "-o",
        ])
        .arg(&fitted)
        .output()
        .unwrap();
    assert!(
        fit.status.success(),
        "{}",
        String::from_utf8_lossy(&fit.stderr)
    );
    let text = std::fs::read_to_string(&fitted).unwrap();
    for number in text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .flat_map(|l| l.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-')))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_digit()))
    {
        let mantissa = number.split('e').next().unwrap();
        let digits = mantissa.trim_start_matches(['0', '.']).replace('.', "");
        assert!(digits.len() <= 6, "`{number}` in\n{text}");
    }
    let (code, stderr, _) = render(Some(&fitted), &[], &dir.path().join("f.png"));
    assert_eq!(code, Some(0), "{stderr}{}", common::LAVAPIPE_TEST_HINT);
    assert!(!stderr.contains("warning"), "{stderr}\n{text}");
}

/// Item 7: each name a user types is answered with the nearest one, and
/// the messages name the fix.
#[test]
fn typed_names_get_the_nearest_name_and_messages_name_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let out = out.to_str().unwrap();
    let expect = |args: &[&str], wanted: &[&str], unwanted: &[&str]| {
        let (code, stderr) = run(args);
        for w in wanted {
            assert!(stderr.contains(w), "{args:?}: `{w}` missing in {stderr}");
        }
        for u in unwanted {
            assert!(!stderr.contains(u), "{args:?}: `{u}` in {stderr}");
        }
        code
    };
    let render = |set: &str| {
        [
            "render", "--width", "16", "--height", "16", "-o", out, "--set",
        ]
        .into_iter()
        .chain([set])
        .map(str::to_string)
        .collect::<Vec<_>>()
    };
    let args = render("materials.ball.model=blinnphong");
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    assert_eq!(
        expect(&args, &["did you mean `blinn-phong`?"], &[]),
        Some(2)
    );
    assert_eq!(
        expect(
            &["fit", "chrome", "--model", "wrd"],
            &["did you mean `ward`?"],
            &[]
        ),
        Some(2)
    );
    let measured = [
        "render",
        "-o",
        out,
        "--set",
        "materials.ball.model=measured",
        "--set",
        "materials.ball.measured=chromee",
    ];
    assert_eq!(expect(&measured, &["did you mean `chrome`?"], &[]), Some(2));
    let args = render("materials.ball.k_e=abc");
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    assert_eq!(expect(&args, &["expected a number"], &["f64"]), Some(2));
    // An adapter name that matches none lists those there are, without
    // the advice to install one.
    let code = expect(
        &["render", "-o", out, "--adapter", "nosuch"],
        &["no GPU adapter matches `nosuch`", "available: "],
        &["apt-get"],
    );
    assert_ne!(code, Some(0));
    let metal = common::gonio()
        .args(["render", "-o", out])
        .env("WGPU_BACKEND", "metal")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&metal.stderr);
    assert_eq!(metal.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("WGPU_BACKEND=metal") && stderr.contains("it has vulkan"),
        "{stderr}"
    );
    // A misspelt key in a scene file is reported at its own line.
    let scene = dir.path().join("typo.toml");
    std::fs::write(
        &scene,
        "[image]\nwidth = 16\n\n[materials.ball]\nmodel = \"lambert\"\nk_a = 0.1\nk_dd = 0.5\n",
    )
    .unwrap();
    let scene = scene.to_str().unwrap();
    expect(
        &["render", scene, "-o", out],
        &["line 7, column 1 (`k_dd = 0.5`)", "did you mean `k_d`?"],
        &["line 4"],
    );
    // A `.hdr` that is not one is named as what it is.
    let fake = dir.path().join("sky.hdr");
    std::fs::write(&fake, "just text\n").unwrap();
    let map = format!(
        "environment.map={}",
        toml::Value::String(fake.display().to_string())
    );
    let args = render(&map);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    expect(
        &args,
        &["it is a text file, not a hdr image"],
        &["signature"],
    );
    // `gonio brdf` warns of a key the model does not read, as render does.
    expect(
        &["brdf", "--model", "lambert", "--set", "k_e=50"],
        &["`k_e` not read by model `lambert`"],
        &[],
    );
}

/// Item 9: the README's "measured material and a fit of it together" line
/// is the fit in `docs/fit/fits.toml`, to the three digits it shows (it
/// showed a made-up material: f_r 585 against the data's 36).
#[test]
fn the_readme_fit_example_is_the_real_fit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let spec = readme
        .split("--compare measured,measured=chrome --compare ")
        .nth(1)
        .and_then(|rest| rest.split('`').next())
        .expect("the README has the fit example");
    let shown = gonio::explore::spec::compare_spec(spec, &[])
        .unwrap()
        .material;
    let fits: toml::Table = std::fs::read_to_string(root.join("docs/fit/fits.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let entry: gonio::material::MaterialEntry = fits["materials"]["chrome--ct-ggx-conductor"]
        .clone()
        .try_into()
        .unwrap();
    let fitted = gonio::material::material_from_entry("fit", &entry).unwrap();
    let (a, b) = (
        gonio::material::material_table(&shown),
        gonio::material::material_table(&fitted),
    );
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (key, value) in &b {
        let numbers = |v: &toml::Value| -> Vec<f64> {
            match v {
                toml::Value::Float(x) => vec![*x],
                toml::Value::Array(xs) => xs.iter().filter_map(toml::Value::as_float).collect(),
                _ => Vec::new(),
            }
        };
        let (shown, fitted) = (numbers(&a[key]), numbers(value));
        if shown.is_empty() {
            assert_eq!(a[key], *value, "{key}");
        }
        for (s, f) in shown.iter().zip(&fitted) {
            // Three significant digits: within half a unit of the third.
            assert!(
                (s - f).abs() <= 5e-3 * f.abs() + 1e-12,
                "{key}: README {s}, fit {f}"
            );
        }
    }
}

/// A `<text>` of a plotters SVG: its estimated box (left, top, right,
/// bottom) in pixels, its font size and its text. The width is 0.6 em
/// per character (generous for sans-serif digits, about 0.55 em), the
/// height 1 em, placed by `text-anchor` and plotters' `dy` (0.76em: the
/// top at y; -0.5ex: the bottom at y; 0.5ex: centred on y).
fn svg_texts(svg: &str) -> Vec<([f64; 4], f64, String)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(tag[start..].split('"').next()?.to_string())
    };
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let (tag, after) = rest.split_once('>')?;
            let text = after.split("</text>").next()?.trim().to_string();
            let x: f64 = attr(tag, "x")?.parse().ok()?;
            let y: f64 = attr(tag, "y")?.parse().ok()?;
            let size: f64 = attr(tag, "font-size")?.parse().ok()?;
            let w = text.chars().count() as f64 * 0.6 * size;
            let (left, right) = match attr(tag, "text-anchor").as_deref() {
                Some("middle") => (x - w / 2.0, x + w / 2.0),
                Some("end") => (x - w, x),
                _ => (x, x + w),
            };
            let (top, bottom) = match attr(tag, "dy").as_deref() {
                Some("0.76em") => (y, y + size),
                Some("-0.5ex") => (y - size, y),
                Some("0.5ex") => (y - size / 2.0, y + size / 2.0),
                _ => (y - 0.8 * size, y + 0.2 * size),
            };
            Some(([left, top, right, bottom], size, text))
        })
        .collect()
}

/// Runs `gonio brdf ARGS` and returns the SVG it wrote to `out`.
fn brdf_svg(args: &[&str], out: &Path) -> String {
    let o = common::gonio()
        .arg("brdf")
        .args(args)
        .arg(out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "gonio brdf {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::read_to_string(out).unwrap()
}

/// Item 8: in `--plot-halfdiff` with images side by side, no two labels
/// touch: boxes on a common row keep a quarter em between them, so one
/// image's 90° and the next one's labels (or the corner's two 0°) do not
/// read as one number ("900").
#[test]
fn halfdiff_plot_labels_keep_apart() {
    let dir = tempfile::tempdir().unwrap();
    for compares in [
        &["phong", "ward"][..],
        &["phong", "ward", "cook-torrance", "blinn-phong"][..],
    ] {
        let mut args = vec!["--model", "lambert"];
        for c in compares {
            args.extend(["--compare", c]);
        }
        args.push("--plot-halfdiff");
        let svg = brdf_svg(&args, &dir.path().join("hd.svg"));
        let texts = svg_texts(&svg);
        let degrees = texts.iter().filter(|t| t.2.ends_with('°')).count();
        assert!(
            degrees >= 6 * (compares.len() + 1),
            "{degrees} degree labels: {texts:?}"
        );
        for (i, (a, size, ta)) in texts.iter().enumerate() {
            for (b, _, tb) in &texts[i + 1..] {
                let space = 0.25 * size;
                let rows_meet = a[1] < b[3] && b[1] < a[3];
                let columns_meet = a[0] < b[2] + space && b[0] < a[2] + space;
                assert!(
                    !(rows_meet && columns_meet),
                    "{compares:?}: `{ta}` at {a:?} and `{tb}` at {b:?}"
                );
            }
        }
    }
}

/// The points of every `<polyline>` of a plotters SVG with its stroke
/// width.
fn svg_polylines(svg: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|rest| {
            let tag = rest.split("/>").next()?;
            let width = tag
                .split("stroke-width=\"")
                .nth(1)?
                .split('"')
                .next()?
                .to_string();
            let points = tag
                .split("points=\"")
                .nth(1)?
                .split('"')
                .next()?
                .split_whitespace()
                .filter_map(|p| {
                    let (x, y) = p.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect();
            Some((width, points))
        })
        .collect()
}

/// Item 8: `brdf --plot-albedo`'s legend covers no curve and not the
/// ρ = 1 line, with curves near the top (a white Lambertian) and below
/// (it was fixed in the upper left, over the highest curve).
#[test]
fn the_albedo_legend_covers_no_curve() {
    let dir = tempfile::tempdir().unwrap();
    let svg = brdf_svg(
        &[
            "--model",
            "lambert",
            "--set",
            "k_d=[0.95,0.95,0.95]",
            "--compare",
            "phong",
            "--compare",
            "ward",
            "--compare",
            "cook-torrance",
            "--plot-albedo",
        ],
        &dir.path().join("albedo.svg"),
    );
    // The legend: the translucent white box.
    let legend = svg
        .split("<rect")
        .skip(1)
        .find(|r| r.contains("opacity=\"0.85\"") && r.contains("fill=\"#FFFFFF\""))
        .map(|r| {
            let n = |name: &str| -> f64 {
                r.split(&format!(" {name}=\""))
                    .nth(1)
                    .and_then(|v| v.split('"').next())
                    .and_then(|v| v.parse().ok())
                    .unwrap()
            };
            (n("x"), n("y"), n("x") + n("width"), n("y") + n("height"))
        })
        .expect("the plot has a legend box");
    let inside =
        |&(x, y): &(f64, f64)| x > legend.0 && x < legend.2 && y > legend.1 && y < legend.3;
    let lines = svg_polylines(&svg);
    // The curves: the polylines with a point per degree (the legend's
    // samples and the dashed ρ = 1 line's dashes have two points each).
    let curves: Vec<&Vec<(f64, f64)>> = lines
        .iter()
        .filter(|(_, p)| p.len() > 10)
        .map(|(_, p)| p)
        .collect();
    assert_eq!(curves.len(), 4, "{lines:?}");
    for curve in curves {
        assert!(
            !curve.iter().any(inside),
            "the legend {legend:?} covers a curve: {curve:?}"
        );
    }
    // The ρ = 1 line: dashes of width 2 at one height, across the plot.
    let dashes: Vec<f64> = lines
        .iter()
        .filter(|(w, p)| w == "2" && p.len() == 2 && p[0].1 == p[1].1)
        .map(|(_, p)| p[0].1)
        .collect();
    let rho_1 = dashes
        .iter()
        .copied()
        .max_by_key(|y| dashes.iter().filter(|d| *d == y).count())
        .expect("the ρ = 1 line is drawn");
    assert!(
        !(rho_1 > legend.1 && rho_1 < legend.3),
        "the legend {legend:?} covers the ρ = 1 line at y = {rho_1}"
    );
}

/// Item 8: every knob of the bench on the built-in base (those measured
/// and those skipped, which other bases measure) has its own colour and
/// marker in the Pareto plot (13 knobs had 10 colours: `base` and
/// `area_samples` were both blue dots).
#[test]
fn every_bench_knob_has_its_own_pareto_style() {
    use gonio::bench::configs::{BUILTIN_BASE, configs};
    let overrides: Vec<String> = BUILTIN_BASE.iter().map(|s| s.to_string()).collect();
    let base = scene_file::load(&SceneSource::BuiltIn, &overrides).unwrap();
    let (measured, skipped) = configs(&base, false);
    let mut knobs: Vec<&str> = Vec::new();
    for k in measured
        .iter()
        .map(|c| c.knob.as_str())
        .chain(skipped.iter().map(|s| s.knob.as_str()))
    {
        if !knobs.contains(&k) {
            knobs.push(k);
        }
    }
    assert!(knobs.len() >= 13, "{knobs:?}");
    let styles: Vec<_> = (0..knobs.len())
        .map(|k| {
            let (c, marker) = gonio::bench::plot::knob_style(k);
            (c.0, c.1, c.2, marker)
        })
        .collect();
    for (i, a) in styles.iter().enumerate() {
        if let Some(j) = styles[i + 1..].iter().position(|b| b == a) {
            panic!(
                "`{}` and `{}` share a colour and marker",
                knobs[i],
                knobs[i + 1 + j]
            );
        }
    }
}
