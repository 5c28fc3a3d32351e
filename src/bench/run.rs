//! `gonio bench`: claims the outputs, loads the base scene and the
//! configurations, measures everything, and writes the report.

use super::cli::BenchArgs;
use super::configs::{self, BUILTIN_BASE, Config, Skipped, TRUTH_AREA_SAMPLES};
use super::harness::Harness;
use super::measure::{self, Stats};
use super::pareto::{self, Point};
use super::plot::ParetoPlot;
use super::ratios::{self, Effort};
use super::scale::{self, Plan};
use super::{AutoCheck, BenchReport, Row, floors, report};
use crate::gpu::timing::Clock;
use crate::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use crate::output::AtomicFile;
use crate::output::plot::PlotFile;
use crate::output::progress::Progress;
use crate::scene::Scene;
use crate::scene::scene_file::{self, SceneSource};
use crate::{Error, Result};
use std::path::Path;
use std::time::Instant;

/// How much `gonio bench` does.
#[derive(Clone, Debug)]
struct Budget {
    warmup: usize,
    /// Timed frames per configuration and pass (two passes of
    /// round-robin rounds).
    per_pass: usize,
    ratio: Effort,
    scale: Option<Plan>,
    truth_samples: u32,
    /// Image size forced on the base scene (smoke runs).
    base_size: Option<(u32, u32)>,
}

impl Budget {
    fn from_args(args: &BenchArgs) -> Result<Self> {
        if args.repeats == Some(0) {
            return Err(Error::argument(
                "--repeats 0",
                "at least one timed frame per configuration is needed",
            ));
        }
        let mut b = if args.smoke {
            Budget {
                warmup: 0,
                per_pass: 1,
                ratio: Effort::SMOKE,
                scale: Some(Plan::smoke()),
                truth_samples: 64,
                base_size: Some((64, 48)),
            }
        } else if args.quick {
            let mut plan = Plan::full();
            plan.triangles = vec![10_000, 100_000, 1_000_000];
            plan.resolutions = vec![(256, 256), (1024, 1024), (3840, 2160)];
            plan.warmup = 1;
            plan.repeats = 1;
            Budget {
                warmup: 1,
                per_pass: 2,
                ratio: Effort {
                    warmup: 1,
                    repeats: 5,
                    // Not fewer: the per-round ratios of the 640x480
                    // comparisons spread by several percent on a shared
                    // machine, and their median must resolve 1.03.
                    fine_repeats: 31,
                    hd: (1920, 1080),
                    small: None,
                    // A cold run's ratio spreads by ±10 % (1.17–1.44 in
                    // one quiet run of 12): the median needs several.
                    cold_runs: 5,
                },
                scale: Some(plan),
                truth_samples: TRUTH_AREA_SAMPLES,
                base_size: None,
            }
        } else {
            Budget {
                warmup: 2,
                per_pass: 6,
                ratio: Effort {
                    warmup: 2,
                    repeats: 15,
                    fine_repeats: 61,
                    hd: (1920, 1080),
                    small: None,
                    cold_runs: 9,
                },
                scale: Some(Plan::full()),
                truth_samples: TRUTH_AREA_SAMPLES,
                base_size: None,
            }
        };
        if let Some(n) = args.repeats {
            b.per_pass = n.div_ceil(2);
            b.ratio.repeats = n;
            b.ratio.fine_repeats = 4 * n;
        }
        if args.no_scale {
            b.scale = None;
        }
        Ok(b)
    }
}

/// The output files, claimed before any work so that a bad folder fails
/// first and nothing partial is ever left.
struct Outputs {
    report: AtomicFile,
    results: AtomicFile,
    scale: AtomicFile,
    svg: PlotFile,
    png: PlotFile,
}

impl Outputs {
    fn claim(dir: &Path) -> Result<Self> {
        if dir.exists() && !dir.is_dir() {
            return Err(Error::output(dir, "exists and is not a folder"));
        }
        std::fs::create_dir_all(dir)
            .map_err(|e| Error::output(dir, format!("cannot create the folder: {e}")))?;
        Ok(Outputs {
            report: AtomicFile::create(&dir.join("report.md"))?,
            results: AtomicFile::create(&dir.join("results.csv"))?,
            scale: AtomicFile::create(&dir.join("scale.csv"))?,
            svg: PlotFile::prepare(&dir.join("pareto.svg"))?,
            png: PlotFile::prepare(&dir.join("pareto.png"))?,
        })
    }
}

/// The scene label the CSV records and `--max-error` checks.
pub fn scene_label(scene: Option<&Path>) -> String {
    match scene {
        None => "built-in".into(),
        Some(p) => std::fs::canonicalize(p)
            .unwrap_or_else(|_| p.to_path_buf())
            .display()
            .to_string(),
    }
}

/// `gonio bench`.
/// `--shadow-ratio`: the shadowed Cook-Torrance rows alone, printed as
/// the report writes them.
fn shadow_ratio_only(args: &BenchArgs, effort: ratios::Effort) -> Result<()> {
    let context = GpuContext::new(&AdapterChoice::from_flag_or_env(args.adapter.as_deref()))?;
    context.require_float_radiance("gonio bench")?;
    let mut renderer = GpuRenderer::new(context);
    for r in ratios::heavy_vs_unlit(&mut renderer, effort)? {
        println!("{}", super::report::ratio_row(&r));
        if !r.note.is_empty() {
            println!("  note: {}", r.note);
        }
    }
    Ok(())
}

/// A shader's compile time (label, milliseconds), for the report.
type CompileTime = (String, f64);

/// The target ratios of the report (specialized scene against the
/// hand-minimal shader, uber against specialized on the Lambert and the
/// base scene, Cook-Torrance with 4 shadowed lights against unlit, a cold
/// `gonio render` against the minimal triangle-to-PNG program), and the
/// shader compile times measured on the way; one step of `bar` each.
fn target_ratios(
    renderer: &mut GpuRenderer,
    base: &Scene,
    effort: ratios::Effort,
    adapter: Option<&str>,
    bar: &mut Progress,
) -> Result<(Vec<ratios::Ratio>, Vec<CompileTime>)> {
    let mut ratio_list = Vec::new();
    let mut compile = Vec::new();
    bar.set_message("specialized vs hand-minimal");
    ratio_list.extend(ratios::specialization(renderer, effort)?);
    bar.inc(1);
    bar.set_message("uber vs specialized");
    let lambert = scene_file::load(
        &SceneSource::BuiltIn,
        &[effort.small, None]
            .into_iter()
            .flatten()
            .flat_map(|(w, h)| [format!("image.width={w}"), format!("image.height={h}")])
            .chain(["materials.ball.model=lambert".to_string()])
            .collect::<Vec<_>>(),
    )?;
    for (scene, label) in [(&lambert, "Lambert scene"), (base, "bench base scene")] {
        let (ratio, special_ms, uber_ms) =
            ratios::uber_vs_specialized(renderer, scene, label, effort)?;
        compile.push((format!("specialized shader, {label}"), special_ms));
        compile.push((format!("uber shader, {label}"), uber_ms));
        ratio_list.push(ratio);
        bar.inc(1);
    }
    bar.set_message("Cook-Torrance + 4 shadowed lights vs unlit");
    ratio_list.extend(ratios::heavy_vs_unlit(renderer, effort)?);
    bar.inc(1);
    bar.set_message("cold render vs triangle-to-PNG");
    let scratch = tempfile::tempdir().map_err(|e| {
        Error::output(
            std::env::temp_dir(),
            format!("cannot create a scratch folder: {e}"),
        )
    })?;
    ratio_list.push(ratios::cold(scratch.path(), effort, adapter)?);
    bar.inc(1);
    Ok((ratio_list, compile))
}

/// `--ratios`: the target ratios alone, printed as the report writes
/// them (an interleaved before/after of two builds,
/// scripts/compare-builds.sh).
fn ratios_only(args: &BenchArgs, base: &Scene, effort: ratios::Effort) -> Result<()> {
    let context = GpuContext::new(&AdapterChoice::from_flag_or_env(args.adapter.as_deref()))?;
    context.require_float_radiance("gonio bench")?;
    let mut renderer = GpuRenderer::new(context);
    let mut bar = Progress::new("bench ratios", 5);
    let (list, _) = target_ratios(
        &mut renderer,
        base,
        effort,
        args.adapter.as_deref(),
        &mut bar,
    )?;
    bar.finish();
    for r in &list {
        println!("{}", report::ratio_row(r));
    }
    Ok(())
}

pub fn run(args: &BenchArgs) -> Result<()> {
    if let Some(out) = &args.floor_triangle_png {
        return floors::triangle_to_png(out, args.adapter.as_deref());
    }
    if let Some(spec) = &args.probe_memory {
        return scale::probe_memory(spec, args.adapter.as_deref());
    }
    if args.merge {
        return super::shards::merge(&args.out);
    }
    let started = Instant::now();
    let budget = Budget::from_args(args)?;
    if args.shadow_ratio {
        return shadow_ratio_only(args, budget.ratio);
    }
    // A shard writes its own file only (super::shards).
    let (outputs, shard_file) = match &args.shard {
        // `--ratios` prints its rows and writes nothing.
        None if args.ratios => (None, None),
        None => (Some(Outputs::claim(&args.out)?), None),
        Some(text) => (
            None,
            Some(super::shards::ShardFile::claim(&args.out, text)?),
        ),
    };

    // The base scene: the user's (or the built-in with the bench's
    // additions), then the user's --set.
    let source = match &args.scene {
        Some(p) => SceneSource::File(p.clone()),
        None => SceneSource::BuiltIn,
    };
    let mut base_overrides: Vec<String> = match args.scene {
        None => BUILTIN_BASE.iter().map(|s| s.to_string()).collect(),
        Some(_) => Vec::new(),
    };
    if let Some((w, h)) = budget.base_size {
        base_overrides.push(format!("image.width={w}"));
        base_overrides.push(format!("image.height={h}"));
    }
    base_overrides.extend(args.set.iter().cloned());
    let base = scene_file::load(&source, &base_overrides)?;
    // An environment map lights the scene as lights do.
    if (base.lights.is_empty() && base.environment.map.is_none()) || base.meshes.is_empty() {
        return Err(Error::argument(
            scene_label(args.scene.as_deref()),
            "the scene has no geometry or no light (nor an environment map): there is nothing to measure",
        ));
    }
    if args.ratios {
        return ratios_only(args, &base, budget.ratio);
    }
    let (all, mut not_measured) = configs::configs(&base, args.smoke);
    let all = configs::whole_environment(
        all,
        configs::environment_section(&source, &base_overrides)?.as_ref(),
    );
    // The key of a sharded run: what decides every shard's measurements.
    let shard_key = super::shards::key(&(&base, &budget, &all));
    if let Some(file) = &shard_file
        && file.is_done(&shard_key)
    {
        eprintln!(
            "gonio bench: {} already holds shard {} of this run: skipped",
            file.path().display(),
            file.shard
        );
        return Ok(());
    }
    let mut measured: Vec<(Config, Scene)> = Vec::new();
    for config in all {
        let overrides: Vec<String> = base_overrides
            .iter()
            .chain(&config.overrides)
            .cloned()
            .collect();
        match scene_file::load(&source, &overrides) {
            Ok(scene) if config.knob != "base" && configs::draws_the_same(&scene, &base) => {
                not_measured.push(Skipped {
                    knob: config.label(),
                    reason: format!(
                        "`{}` changes nothing this scene draws",
                        config.overrides.join(" ")
                    ),
                })
            }
            Ok(scene) => measured.push((config, scene)),
            Err(e) => not_measured.push(Skipped {
                knob: config.label(),
                reason: match config.knob.as_str() {
                    "msaa" => format!(
                        "the renderer has no MSAA (the scene loader refuses `image.msaa`: {e})"
                    ),
                    _ => e.to_string(),
                },
            }),
        }
    }
    // A shard takes every N-th of the configurations that are measured
    // (the list every shard computes alike).
    let total_configs = measured.len();
    if let Some(file) = &shard_file {
        if file.shard.count > total_configs {
            return Err(Error::argument(
                format!("--shard {}", file.shard),
                format!(
                    "this run measures {total_configs} configurations, and a shard is at least one: use at most {total_configs} shards"
                ),
            ));
        }
        measured = measured
            .into_iter()
            .enumerate()
            .filter(|(k, _)| file.shard.takes(*k))
            .map(|(_, m)| m)
            .collect();
    }

    let context = GpuContext::new(&AdapterChoice::from_flag_or_env(args.adapter.as_deref()))?;
    context.require_float_radiance("gonio bench")?;
    let adapter = context.describe();
    let mut renderer = GpuRenderer::new(context);

    let scale_points = budget.scale.as_ref().map_or(0, Plan::len);
    // One step per configuration per round (the bulk of the run), one
    // per ratio and per scale point.
    let steps = 1 + (budget.warmup + 2 * budget.per_pass) * measured.len() + 1 + 5 + scale_points;
    let mut bar = Progress::new("bench", steps as u64);

    bar.set_message("truth image (CPU reference)");
    let start = Instant::now();
    let truth = measure::truth(&base, budget.truth_samples);
    let truth_ms = start.elapsed().as_secs_f64() * 1e3;
    // The configurations that draw another scene (the layer knobs) have
    // their own reference, made the same way.
    let own_truths: Vec<Option<crate::frame::Frame>> = measured
        .iter()
        .map(|(config, scene)| {
            config.own_truth.then(|| {
                bar.set_message(format!("truth image of {}", config.label()));
                measure::truth(scene, budget.truth_samples)
            })
        })
        .collect();
    bar.inc(1);

    // Round-robin: every round renders every configuration once, so a
    // slow stretch of a shared machine hits all of them alike instead of
    // whichever was being timed. The first `warmup` rounds compile the
    // pipelines and are not timed; the first timed frame of each
    // configuration gives its error (frames are deterministic). Even and
    // odd timed rounds form two passes: the `--max-error` check picks on
    // one and scores on the other.
    let mut times: [Vec<Vec<f64>>; 2] = [
        vec![Vec::new(); measured.len()],
        vec![Vec::new(); measured.len()],
    ];
    let mut errors = vec![(0.0, 0.0); measured.len()];
    let mut clock = Clock::Wall;
    let rounds = budget.warmup + 2 * budget.per_pass;
    for round in 0..rounds {
        for (k, (config, scene)) in measured.iter().enumerate() {
            bar.set_message(format!(
                "round {}/{rounds} ({}): {}",
                round + 1,
                if round < budget.warmup {
                    "warm-up"
                } else {
                    "timed"
                },
                config.label()
            ));
            // Timed as a `gonio render` process draws it, on textures made
            // for it (the device's pool emptied: src/gpu/texture_pool.rs),
            // which is the cost `--max-error` picks a configuration by;
            // and no configuration gains from the shape of the one before.
            renderer.context().textures.clear();
            let (frame, timings) = renderer.render(scene)?;
            let (ms, c) = measure::frame_ms(&timings);
            clock = c;
            if round == budget.warmup {
                errors[k] = measure::error(&frame, own_truths[k].as_ref().unwrap_or(&truth));
            }
            if round >= budget.warmup {
                times[(round - budget.warmup) % 2][k].push(ms);
            }
            bar.inc(1);
        }
    }
    let [times_a, times_b] = times;
    let mut rows: Vec<Row> = measured
        .iter()
        .zip(times_a.iter().zip(&times_b))
        .zip(&errors)
        .map(|(((config, _), (a, b)), &(error, max_rel))| Row {
            config: config.clone(),
            time: Stats::of(&[a.as_slice(), b.as_slice()].concat()),
            time_a: Stats::of(a),
            time_b: Stats::of(b),
            error,
            max_rel,
            on_front: false,
        })
        .collect();
    let points: Vec<Point> = rows
        .iter()
        .map(|r| Point {
            time: r.time.median,
            error: r.error,
        })
        .collect();
    for i in pareto::front(&points) {
        rows[i].on_front = true;
    }
    let auto = auto_checks(&rows);

    bar.set_message("unlit floor");
    let unlit = {
        let h = Harness::new(&mut renderer, &base, &floors::unlit(&base))?;
        let mut t = Vec::new();
        for _ in 0..budget.warmup + 2 * budget.per_pass {
            t.push(h.time_once(renderer.context())?.0);
        }
        Stats::of(&t[budget.warmup..])
    };
    bar.inc(1);

    if let Some(file) = shard_file {
        bar.finish();
        let path = file.path().to_path_buf();
        file.write(
            &shard_key,
            total_configs,
            &scene_label(args.scene.as_deref()),
            &base_overrides,
            &rows,
            unlit.median,
            &adapter,
            clock,
        )?;
        eprintln!(
            "gonio bench: wrote {} ({} configurations) in {:.0} s; `gonio bench --merge -o {}` joins the shards",
            path.display(),
            rows.len(),
            started.elapsed().as_secs_f64(),
            args.out.display()
        );
        return Ok(());
    }
    let outputs = outputs.expect("claimed when not sharded");
    let (ratio_list, compile) = target_ratios(
        &mut renderer,
        &base,
        budget.ratio,
        args.adapter.as_deref(),
        &mut bar,
    )?;

    let scale = match &budget.scale {
        Some(plan) => {
            bar.set_message("scale sweeps");
            Some(scale::run(
                &mut renderer,
                plan,
                args.adapter.as_deref(),
                || bar.inc(1),
            )?)
        }
        None => None,
    };
    bar.finish();

    let result = BenchReport {
        scene: scene_label(args.scene.as_deref()),
        adapter,
        clock,
        base_overrides,
        truth: format!(
            "the CPU reference renderer (f64 ray casting, ray-traced shadows) of the base scene with per-pixel (Phong) shading and every area light at {} samples, {}x{}",
            budget.truth_samples, base.width, base.height
        ),
        truth_ms,
        width: base.width,
        height: base.height,
        triangles: base.triangle_count(),
        warmup: budget.warmup,
        repeats: 2 * budget.per_pass,
        rows,
        not_measured,
        unlit,
        ratios: ratio_list,
        compile,
        auto,
        scale,
        elapsed_s: started.elapsed().as_secs_f64(),
        smoke: args.smoke,
    };
    let plot = ParetoPlot {
        rows: &result.rows,
        note: format!(
            "{} scene, {}x{}, {}; x: GPU time over the unlit pass ({:.3} ms)",
            result.scene,
            result.width,
            result.height,
            result.adapter_short(),
            result.unlit.median
        ),
        floor_ms: result.unlit.median,
    };
    // The five files appear together or not at all.
    let svg = outputs.svg.encode(&plot)?;
    let png = outputs.png.encode(&plot)?;
    crate::output::commit_all(vec![
        (outputs.svg.into_file(), svg),
        (outputs.png.into_file(), png),
        (outputs.results, report::results_csv(&result).into_bytes()),
        (outputs.scale, report::scale_csv(&result).into_bytes()),
        (outputs.report, report::markdown(&result).into_bytes()),
    ])?;
    eprintln!(
        "gonio bench: wrote {} (report.md, results.csv, scale.csv, pareto.svg, pareto.png) in {:.0} s",
        args.out.display(),
        result.elapsed_s
    );
    Ok(())
}

/// For budgets at each error of the first pass's front: the pick made on
/// the first pass, scored against the cheapest within budget on the
/// second.
fn auto_checks(rows: &[Row]) -> Vec<AutoCheck> {
    let pass = |f: fn(&Row) -> f64| -> Vec<Point> {
        rows.iter()
            .map(|r| Point {
                time: f(r),
                error: r.error,
            })
            .collect()
    };
    let a = pass(|r| r.time_a.median);
    let b = pass(|r| r.time_b.median);
    pareto::front(&a)
        .into_iter()
        .filter_map(|i| {
            let max_error = a[i].error;
            let pick = pareto::cheapest_within(&a, max_error)?;
            let best = pareto::cheapest_within(&b, max_error)?;
            let (p, q) = (&rows[pick].time_b, &rows[best].time_b);
            Some(AutoCheck {
                max_error,
                pick,
                best,
                ratio: b[pick].time / b[best].time,
                overlap: p.q1 <= q.q3 && q.q1 <= p.q3,
            })
        })
        .collect()
}

impl BenchReport {
    /// The adapter's name without the driver details.
    pub fn adapter_short(&self) -> &str {
        self.adapter.split(" (").next().unwrap_or(&self.adapter)
    }
}
