//! `gonio fit`: the command-line face of [`crate::fit`]. `src/cli.rs`
//! only holds the subcommand variant.

use super::models::{ALL, FitModel};
use super::problem::{fit_from, score};
use super::report::{self, Row};
use super::samples::samples;
use super::{Metric, fit, published};
use crate::material::material_table;
use crate::material::measured::{self, MeasuredBrdf, library};
use crate::output::progress::Progress;
use crate::output::{AtomicFile, commit_all};
use crate::scene::default_scene::DEFAULT_SCENE_TOML;
use crate::{Error, Result};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `gonio fit MATERIAL --model MODEL [--metric M] [-o FILE]`, or
/// `gonio fit --all [--shard I/N] [--out-dir DIR]`, or `gonio fit --merge`.
#[derive(Debug, clap::Args)]
#[command(
    about = "Fit reflectance models to a measured BRDF; --all ranks every model on the 100 MERL materials",
    long_about = "Fit a model's parameters to a measured material (a built-in MERL name or a MERL \
.binary file) on a fixed grid of MERL half/difference directions, by Nelder-Mead from several \
starts within the parameters' ranges. Prints the error and the fitted material as a scene file \
that `gonio render` renders (or writes it with -o). --all fits every model to every built-in \
material and writes the ranking (docs/measured.md)."
)]
pub struct FitArgs {
    /// A built-in measured material (a MERL name, e.g. gold-metallic-paint)
    /// or a MERL `.binary` file.
    #[arg(required_unless_present_any = ["all", "merge"])]
    pub material: Option<String>,
    /// The model: lambert, phong, phong-normalized, blinn-phong,
    /// blinn-phong-normalized, ward, gltf-pbr, `gltf-pbr,layers=clearcoat`
    /// (a KHR_materials_clearcoat coat over the base), `gltf-pbr,layers=sheen`
    /// (a KHR_materials_sheen sheen over it), `gltf-pbr,layers=clearcoat+sheen`,
    /// abc (Löw et al. 2012),
    /// `abc,start=published` (also started from the published parameters),
    /// abc-published (the published ABC parameters, scored, not fitted), or
    /// `cook-torrance[,distribution=D][,fresnel=F][,geometry=G]`
    /// (default beckmann, conductor, smith). With --all: the models to
    /// rank (repeat; default: all of them).
    #[arg(long = "model", value_name = "MODEL")]
    pub models: Vec<String>,
    /// The error metric minimized and reported.
    #[arg(long, value_enum, default_value = "ngan")]
    pub metric: Metric,
    /// Write the fitted material (in a scene file) here instead of printing it.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Fit every model to every built-in material and write the ranking.
    #[arg(long, conflicts_with_all = ["material", "output", "merge"])]
    pub all: bool,
    /// With --all: only these built-in materials (comma-separated).
    #[arg(long, value_name = "NAMES", value_delimiter = ',', requires = "all")]
    pub materials: Vec<String>,
    /// With --all: run shard I of N (1-based; materials I, I+N, ...) and
    /// write only its files; `--merge` joins the shards. `auto` (or
    /// `auto/N`) reads the shard from Slurm's SLURM_ARRAY_TASK_ID,
    /// Kubernetes' JOB_COMPLETION_INDEX or HyperQueue's HQ_TASK_ID.
    #[arg(long, value_name = "I/N|auto", requires = "all")]
    pub shard: Option<String>,
    /// Merge the shards in --out-dir into the ranking.
    #[arg(long, conflicts_with_all = ["material", "output"])]
    pub merge: bool,
    /// Where --all and --merge write (shards in DIR/shards).
    #[arg(long, value_name = "DIR", default_value = "docs/fit")]
    pub out_dir: PathBuf,
}

/// Runs `gonio fit`.
pub fn run(args: &FitArgs) -> Result<()> {
    // clap's `requires = "all"` is met by the flag's default `false`: a
    // shard of a single fit was ignored without a word.
    if !args.all {
        let given = [
            ("--shard", args.shard.is_some()),
            ("--materials", !args.materials.is_empty()),
        ];
        if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
            return Err(Error::argument(
                *flag,
                "applies to --all (it picks the fits of a ranking run); add --all, or drop it for a single fit",
            ));
        }
    }
    if args.merge {
        let summary = report::merge(&args.out_dir, None)?;
        println!("{summary}");
        return Ok(());
    }
    if args.all {
        return run_all(args);
    }
    let text = args.material.as_deref().unwrap_or_default();
    let brdf = resolve_material(text)?;
    let spec = match args.models.as_slice() {
        [one] => one.as_str(),
        [] => {
            return Err(Error::argument(
                "--model",
                "give the model to fit, e.g. --model ward",
            ));
        }
        _ => {
            return Err(Error::argument(
                "--model",
                "one fit takes one model (--all ranks several)",
            ));
        }
    };
    let model = FitModel::parse(spec).map_err(|p| Error::argument(format!("--model {spec}"), p))?;
    // Claimed before the fit: a bad destination fails first.
    let output = args.output.as_deref().map(AtomicFile::create).transpose()?;
    let start = Instant::now();
    let name = material_name(brdf);
    let result = if model.is_published() {
        let m = published::abc(&name).ok_or_else(|| {
            Error::argument(
                format!("--model {spec}"),
                format!(
                    "`{name}` has no published ABC fit: the table (data/measured/merl100_abc_fits.csv) has the 100 MERL materials by name"
                ),
            )
        })?;
        score(&m, &samples(brdf), args.metric)
    } else if model.starts_from_published() {
        let m = published::abc(&name).ok_or_else(|| {
            Error::argument(
                format!("--model {spec}"),
                format!("`{name}` has no published ABC fit to start from"),
            )
        })?;
        fit_from(&model, &samples(brdf), args.metric, Some(&m))
    } else {
        fit(&model, &samples(brdf), args.metric)
    };
    let mut m = result.material.clone();
    m.name = name.clone();
    let summary = format!(
        "{name}, {}, metric {}: error {:.6e}{} (relative {:.4}), {} evaluations, {:.1} s",
        model.spec,
        args.metric.name(),
        result.error,
        if args.metric == Metric::Ngan {
            " 1/sr"
        } else {
            ""
        },
        result.relative,
        result.evaluations,
        start.elapsed().as_secs_f64()
    );
    let scene = scene_text(&m, &summary);
    match output {
        Some(file) => {
            file.commit(scene.as_bytes())?;
            println!("{summary}");
        }
        None => {
            eprintln!("{summary}");
            print!("{scene}");
        }
    }
    Ok(())
}

/// The measured BRDF `text` names (a built-in name or a MERL file).
fn resolve_material(text: &str) -> Result<&'static MeasuredBrdf> {
    measured::resolve(text, Path::new(".")).map_err(|p| {
        let looks_like_file = text.contains('/') || text.ends_with(".binary");
        if looks_like_file {
            Error::input(text, p)
        } else {
            Error::argument(format!("material `{text}`"), p)
        }
    })
}

/// A TOML-friendly name: the built-in name, or the file's stem.
fn material_name(brdf: &MeasuredBrdf) -> String {
    let stem = Path::new(&brdf.name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| brdf.name.clone());
    stem.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// The built-in scene with its sphere in the fitted material `m` (a
/// `[materials.NAME]` table), headed by `summary` as a comment.
pub fn scene_text(m: &crate::material::Material, summary: &str) -> String {
    let mut scene: toml::Table = DEFAULT_SCENE_TOML
        .parse()
        .expect("the built-in scene parses");
    if let Some(toml::Value::Array(objects)) = scene.get_mut("objects")
        && let Some(toml::Value::Table(sphere)) = objects.first_mut()
    {
        sphere.insert("material".into(), toml::Value::String(m.name.clone()));
    }
    if let Some(toml::Value::Table(materials)) = scene.get_mut("materials") {
        materials.remove("ball");
        let mut table = material_table(m);
        super::text_numbers::tidy(&mut table);
        materials.insert(m.name.clone(), toml::Value::Table(table));
    }
    format!(
        "# gonio fit: {summary}\n# The built-in scene with its sphere in the fitted material [materials.{}].\n\n{}",
        m.name,
        toml::to_string(&scene).expect("a TOML table serializes")
    )
}

/// Whether a shard's files are there and its CSV holds exactly the fits
/// this run would make (material, model and metric, in order): a
/// restarted array job skips it. Both files are written whole or not at
/// all (the CSV first), and a fit is deterministic, so they are this
/// run's.
fn shard_is_done(
    csv: &Path,
    toml: &Path,
    materials: &[&MeasuredBrdf],
    models: &[FitModel],
    args: &FitArgs,
) -> bool {
    let Ok(text) = std::fs::read_to_string(csv) else {
        return false;
    };
    let Ok(rows) = report::parse_csv(csv, &text) else {
        return false;
    };
    let metric = args.metric.name();
    let expected = materials.iter().flat_map(|m| {
        models
            .iter()
            .map(move |model| (m.name.clone(), model.label()))
    });
    toml.exists()
        && rows.len() == materials.len() * models.len()
        && rows.iter().zip(expected).all(|(r, (material, model))| {
            r.material == material && r.model == model && r.metric == metric
        })
}

/// `gonio fit --all`.
fn run_all(args: &FitArgs) -> Result<()> {
    let start = Instant::now();
    let specs: Vec<&str> = if args.models.is_empty() {
        ALL.to_vec()
    } else {
        args.models.iter().map(String::as_str).collect()
    };
    let models: Vec<FitModel> = specs
        .iter()
        .map(|s| FitModel::parse(s).map_err(|p| Error::argument(format!("--model {s}"), p)))
        .collect::<Result<_>>()?;
    let mut materials: Vec<&'static MeasuredBrdf> = if args.materials.is_empty() {
        library::all().iter().collect()
    } else {
        args.materials
            .iter()
            .map(|n| {
                library::builtin(n).map_err(|p| Error::argument(format!("--materials {n}"), p))
            })
            .collect::<Result<_>>()?
    };
    let crate::cluster::Shard {
        index: shard,
        count: of,
    } = match &args.shard {
        Some(s) => {
            let (shard, source) = crate::cluster::Shard::from_arg(s)?;
            if let Some(source) = source {
                eprintln!("gonio fit: --shard {s}: shard {shard} ({source})");
            }
            shard
        }
        None => crate::cluster::Shard::WHOLE,
    };
    materials = materials
        .into_iter()
        .enumerate()
        .filter(|(k, _)| k % of == shard - 1)
        .map(|(_, m)| m)
        .collect();
    // The shard's two files, claimed before the fits (a bad folder fails
    // first) and written together; a shard whose files already hold this
    // run's fits is skipped (a restarted array job).
    let (csv_path, toml_path) = report::shard_paths(&args.out_dir, shard, of);
    if args.shard.is_some() && shard_is_done(&csv_path, &toml_path, &materials, &models, args) {
        eprintln!(
            "gonio fit: {} already holds shard {shard}/{of} ({} fits of this run): skipped",
            csv_path.display(),
            materials.len() * models.len()
        );
        return Ok(());
    }
    let shards_dir = csv_path.parent().expect("a shard file is in a folder");
    std::fs::create_dir_all(shards_dir)
        .map_err(|e| Error::output(shards_dir, format!("cannot create the folder: {e}")))?;
    let csv_file = AtomicFile::create(&csv_path)?;
    let toml_file = AtomicFile::create(&toml_path)?;
    // A bar on a terminal, a line every few seconds in a log (the subject
    // `fits` stays, so two materials in parallel do not print per fit).
    let bar = std::sync::Mutex::new(Progress::new(
        "fit",
        (materials.len() * models.len()) as u64,
    ));
    let per_material: Vec<(Vec<Row>, String)> = materials
        .par_iter()
        .map(|brdf| {
            let s = samples(brdf);
            let mut rows = Vec::new();
            let mut tables = String::new();
            for model in &models {
                let t0 = Instant::now();
                let r = if model.is_published() {
                    let m = published::abc(&brdf.name).expect(
                        "every built-in material has a published ABC row (test in published.rs)",
                    );
                    score(&m, &s, args.metric)
                } else if model.starts_from_published() {
                    let m = published::abc(&brdf.name).expect(
                        "every built-in material has a published ABC row (test in published.rs)",
                    );
                    fit_from(model, &s, args.metric, Some(&m))
                } else {
                    fit(model, &s, args.metric)
                };
                let label = model.label();
                let mut m = r.material.clone();
                m.name = format!("{}--{label}", brdf.name);
                let mut t = toml::Table::new();
                let mut table = material_table(&m);
                super::text_numbers::tidy(&mut table);
                t.insert(m.name.clone(), toml::Value::Table(table));
                let mut outer = toml::Table::new();
                outer.insert("materials".into(), toml::Value::Table(t));
                tables.push_str(&format!(
                    "# {} {label}: {} error {:.6e} (relative {:.4})\n{}\n",
                    brdf.name,
                    args.metric.name(),
                    r.error,
                    r.relative,
                    toml::to_string(&outer).expect("serializes")
                ));
                rows.push(Row {
                    material: brdf.name.clone(),
                    model: label,
                    metric: args.metric.name().into(),
                    error: r.error,
                    relative: r.relative,
                    evaluations: r.evaluations,
                    seconds: t0.elapsed().as_secs_f64(),
                });
                if let Ok(mut bar) = bar.lock() {
                    bar.set_message(format!("fits: {} {}", brdf.name, model.label()));
                    bar.inc(1);
                }
            }
            (rows, tables)
        })
        .collect();
    if let Ok(mut bar) = bar.into_inner() {
        bar.finish();
    }
    let rows: Vec<Row> = per_material.iter().flat_map(|(r, _)| r.clone()).collect();
    let tables: String = per_material.iter().map(|(_, t)| t.as_str()).collect();
    commit_all(vec![
        (csv_file, report::csv(&rows).into_bytes()),
        (toml_file, tables.into_bytes()),
    ])?;
    let wall = start.elapsed().as_secs_f64();
    eprintln!(
        "wrote {} ({} fits in {wall:.0} s on {} threads)",
        csv_path.display(),
        rows.len(),
        rayon::current_num_threads()
    );
    if args.shard.is_none() {
        let summary = report::merge(&args.out_dir, Some((wall, rayon::current_num_threads())))?;
        println!("{summary}");
    }
    Ok(())
}
