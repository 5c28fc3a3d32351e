//! The command line: `gonio render`, a thin layer over the library.

use crate::cluster::render::ShardOutput;
use crate::frame::Frame;
use crate::gpu::timing::{Clock, Timings};
use crate::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use crate::output::{OutputFile, OutputFormat};
use crate::scene::limits::Limits;
use crate::scene::scene_file::{self, SceneSource};
use crate::scene::{Scene, ShadingMode};
use crate::{Error, Result, reference};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// gonio: a GPU renderer for looking at materials.
#[derive(Debug, Parser)]
#[command(name = "gonio", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene headlessly to a PNG or EXR file.
    Render(RenderArgs),
    /// Open the interactive viewer: the scene with a panel of every material and light setting.
    #[cfg(feature = "viewer")]
    View(ViewCommand),
    /// Explore a reflectance model: print f_r, plot slices and albedo, read gloss.
    Brdf(crate::explore::cli::BrdfArgs),
    /// Measure the speed/accuracy trade: time and error of every knob, Pareto front, floors.
    Bench(crate::bench::cli::BenchArgs),
    /// Fit reflectance models to a measured BRDF; --all ranks them on the 100 MERL materials.
    Fit(crate::fit::cli::FitArgs),
    /// Join the partial images of `gonio render --reference --shard` into the whole image.
    Merge(MergeArgs),
}

/// `gonio merge -o OUT.(exr|png) PART.exr...`
#[derive(Debug, clap::Args)]
#[command(
    long_about = "Join the partial images that `gonio render --reference --shard I/N` wrote into \
the image one `gonio render --reference` writes, bit for bit. The set must be one render's \
(the same scene, settings and shard count: each partial file's header carries a key of them) \
with every shard exactly once; otherwise the odd or missing part is named and nothing is written \
(docs/cluster.md)."
)]
pub struct MergeArgs {
    /// The partial images (any order), e.g. `parts/part-*.exr`.
    #[arg(required = true, value_name = "PART")]
    pub parts: Vec<PathBuf>,
    /// Output file; `.png` (sRGB, the scene's tone map) or `.exr` (linear float radiance).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// PNG exposure in stops, as for `gonio render`.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f64,
}

/// `gonio render [SCENE] -o OUT.(png|exr) ...`
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// A scene `.toml`, a `.gltf` or a `.glb`. Without it: the built-in
    /// scene (a sphere on a plane, one point light).
    pub scene: Option<PathBuf>,
    /// Output file; `.png` (sRGB, clamped) or `.exr` (linear float radiance).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Image width in pixels (overrides image.width).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (overrides image.height).
    #[arg(long)]
    pub height: Option<u32>,
    /// Shading mode: flat, gouraud or phong (overrides shading.mode).
    #[arg(long, value_name = "MODE")]
    pub shading: Option<ShadingMode>,
    /// Override any scene-file key by its dotted path, e.g.
    /// `--set materials.ball.k_e=80` or `--set lights.0.intensity=[5,5,5]`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Render with the CPU reference renderer (f64 ray casting) instead of the GPU.
    #[arg(long)]
    pub reference: bool,
    /// With --reference: render only shard I of N (image rows I-1, I-1+N,
    /// ...) into a partial .exr for `gonio merge`; `auto` (or `auto/N`)
    /// reads the shard from Slurm's SLURM_ARRAY_TASK_ID, Kubernetes'
    /// JOB_COMPLETION_INDEX or HyperQueue's HQ_TASK_ID. `{shard}` in -o
    /// becomes the shard's number. A shard whose file already exists
    /// complete is skipped.
    #[arg(long, value_name = "I/N|auto")]
    pub shard: Option<String>,
    /// PNG exposure in stops: the image is scaled by 2^EXPOSURE before encoding.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f64,
    /// GPU adapter to use: the first whose name contains this text
    /// (also GONIO_ADAPTER). Default: wgpu's pick on Vulkan.
    #[arg(long, value_name = "NAME")]
    pub adapter: Option<String>,
    /// Print the adapter, the scene summary and the shader features used.
    #[arg(short, long)]
    pub verbose: bool,
    /// Print the time of each step (GPU timestamp queries where available).
    #[arg(long)]
    pub timings: bool,
    /// Raise (or lower) a cap on what input files may hold, e.g.
    /// `--limit triangles=200M` or `--limit bytes=4Gi`. Keys: bytes (1Gi),
    /// vertices (50M), triangles (50M), nodes (1M), textures (4096),
    /// lights (1024), memory (8Gi: what the renderer allocates beyond the
    /// scene, checked before it starts).
    #[arg(long = "limit", value_name = "KEY=VALUE")]
    pub limits: Vec<String>,
    /// `--max-error E` and the results file it reads.
    #[command(flatten)]
    pub quality: MaxErrorArgs,
}

/// `gonio view [SCENE] ...`: the viewer's own arguments and `--max-error`,
/// which the command line resolves before the viewer starts.
#[cfg(feature = "viewer")]
#[derive(Debug, clap::Args)]
pub struct ViewCommand {
    #[command(flatten)]
    pub view: crate::ui::ViewArgs,
    /// `--max-error E`: open with the cheapest configuration `gonio bench`
    /// measured on this scene within relative error E (as `gonio render
    /// --max-error`); explicit --set still apply after it.
    #[command(flatten)]
    pub quality: MaxErrorArgs,
}

/// `--max-error E [--bench-results CSV]`, shared by `gonio render` and
/// `gonio view`: the cheapest configuration `gonio bench` measured within
/// a relative error, resolved here into `--set` overrides once, so the
/// renderers and the viewer never reach into the bench.
#[derive(Debug, Clone, clap::Args)]
pub struct MaxErrorArgs {
    /// Use the cheapest configuration `gonio bench` measured on this
    /// scene whose error (relative RMS against the truth image) is at
    /// most E, e.g. `--max-error 0.05`; explicit --set still apply after it.
    #[arg(long, value_name = "E")]
    pub max_error: Option<f64>,
    /// The results file --max-error reads (written by `gonio bench`).
    #[arg(long, value_name = "CSV", default_value = "gonio-bench/results.csv")]
    pub bench_results: PathBuf,
}

impl MaxErrorArgs {
    /// The chosen configuration's `--set` overrides for `scene` (none
    /// without `--max-error`); an input error when no measured
    /// configuration is accurate enough or the file holds none of `scene`.
    pub fn overrides(&self, scene: Option<&Path>, verbose: bool) -> Result<Vec<String>> {
        let Some(max_error) = self.max_error else {
            return Ok(Vec::new());
        };
        let choice = crate::bench::auto::cheapest_within(max_error, &self.bench_results, scene)?;
        if verbose {
            eprintln!(
                "--max-error {max_error}: `{}` (measured {:.3} ms, error {:.3e})",
                choice.label, choice.time_ms, choice.error
            );
        }
        Ok(choice.overrides)
    }
}

/// Parses the command line, runs it, and maps errors to exit status 2
/// (input the user can fix) with a one-paragraph message.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render(&args),
        #[cfg(feature = "viewer")]
        Command::View(ViewCommand { view, quality }) => quality
            .overrides(view.scene.as_deref(), view.verbose)
            .and_then(|chosen| crate::ui::run(view, chosen)),
        Command::Brdf(args) => crate::explore::cli::run(&args),
        Command::Bench(args) => crate::bench::run::run(&args),
        Command::Fit(args) => crate::fit::cli::run(&args),
        Command::Merge(args) => {
            crate::cluster::merge::run(&args.output, args.exposure, &args.parts)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gonio: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// `gonio render`.
pub fn render(args: &RenderArgs) -> Result<()> {
    let total = Instant::now();
    if !args.exposure.is_finite() {
        return Err(Error::argument(
            format!("--exposure {}", args.exposure),
            "the exposure must be a finite number of stops",
        ));
    }
    // EXR holds linear radiance; an exposure there would be ignored
    // without a word.
    if args.exposure != 0.0 && OutputFormat::from_path(&args.output)? == OutputFormat::Exr {
        return Err(Error::argument(
            format!("--exposure {}", args.exposure),
            format!(
                "{} is an EXR, which holds linear radiance without exposure or tone mapping; drop --exposure, or write a .png",
                args.output.display()
            ),
        ));
    }
    // Claim the destination first: a bad path fails before any work.
    let (output, shard) = match &args.shard {
        None => (Some(OutputFile::prepare(&args.output)?), None),
        Some(text) => (
            None,
            Some(ShardOutput::prepare(
                text,
                &args.output,
                args.reference,
                args.verbose,
            )?),
        ),
    };

    let mut overrides = args
        .quality
        .overrides(args.scene.as_deref(), args.verbose)?;
    overrides.extend(args.set.iter().cloned());
    if let Some(w) = args.width {
        overrides.push(format!("image.width={w}"));
    }
    if let Some(h) = args.height {
        overrides.push(format!("image.height={h}"));
    }
    if let Some(mode) = args.shading {
        overrides.push(format!("shading.mode=\"{mode}\""));
    }
    let source = match &args.scene {
        Some(path) => SceneSource::File(path.clone()),
        None => SceneSource::BuiltIn,
    };
    let mut timings = Timings::default();
    let start = Instant::now();
    let limits = Limits::from_assignments(&args.limits)
        .map_err(|(arg, problem)| Error::argument(format!("--limit {arg}"), problem))?;
    let (mut scene, notes) = scene_file::load_with_limits(&source, &overrides, limits)?;
    timings.push("load scene", start.elapsed(), Clock::Wall);
    warn_unsupported(&scene);
    for warning in notes.iter().filter(|n| n.starts_with(scene_file::WARNING)) {
        eprintln!("gonio: {warning}");
    }
    if args.verbose {
        for note in notes.iter().filter(|n| !n.starts_with(scene_file::WARNING)) {
            eprintln!("gonio: note: {note}");
        }
        eprintln!("{}", describe_scene(&scene));
    }

    check_memory(&scene, args.reference, &limits)?;
    // A knob of the GPU path: the truth is exact (nothing typed is
    // ignored without a word).
    if args.reference && scene.smith_beckmann == crate::material::SmithBeckmann::Rational {
        eprintln!(
            "gonio: warning: shading.smith_beckmann = \"rational\" is the GPU's approximation; the reference evaluates the exact erf form"
        );
    }
    if let Some(shard) = shard {
        let label = format!("reference render, shard {}", shard.shard());
        timings.wall(&label, || shard.render(&scene))?;
        timings.push("total", total.elapsed(), Clock::Wall);
        if args.timings {
            println!("{}", timings.report());
        }
        return Ok(());
    }
    let output = output.expect("claimed when not sharded");
    let frame: Frame = if args.reference {
        if args.verbose {
            eprintln!(
                "renderer: CPU reference (f64 ray casting, {} threads)",
                rayon::current_num_threads()
            );
        }
        let (frame, lost) =
            timings.wall("reference render", || reference::render_reporting(&scene));
        if let Some(w) = untraced_transmission_warning(lost) {
            eprintln!("gonio: {w}");
        }
        frame
    } else {
        if let Some(w) = gpu_transmission_warning(&scene) {
            eprintln!("gonio: {w}");
        }
        if let Some(note) = gpu_spectral_note(&scene) {
            eprintln!("gonio: note: {note}");
        }
        let choice = AdapterChoice::from_flag_or_env(args.adapter.as_deref());
        let start = Instant::now();
        let context = GpuContext::new(&choice)?;
        timings.push("open GPU device", start.elapsed(), Clock::Wall);
        if args.verbose {
            eprintln!("adapter: {}", context.describe());
            eprintln!(
                "shader: {}",
                crate::gpu::shader_gen::ShaderKey::new(
                    &scene,
                    &crate::gpu::shadows::ShadowPlan::new(&scene)
                )
                .describe()
            );
        }
        let mut renderer = GpuRenderer::new(context);
        // One frame: one pipeline to compile.
        renderer.set_one_pipeline(true);
        // GPU only: the f64 meshes are freed as they are uploaded
        // (nothing below reads them).
        let (frame, gpu_timings) = renderer.render_releasing_meshes(&mut scene).map_err(|e| {
            let file = match &source {
                SceneSource::File(p) => p.display().to_string(),
                SceneSource::BuiltIn => "the built-in scene".into(),
            };
            crate::gpu::shadow_maps::name_scene_file(e, &file)
        })?;
        timings.extend(gpu_timings);
        frame
    };

    let start = Instant::now();
    let path = output.path().to_path_buf();
    // A scene's tone map is for PNGs and the window; an EXR holds linear
    // radiance by contract, so it is not applied, with a word (a scene
    // file key describes the scene for every output, so this is a
    // warning, where --exposure, given for this output, is an error).
    if scene.tone_map != Default::default() && OutputFormat::from_path(&path)? == OutputFormat::Exr
    {
        eprintln!(
            "gonio: warning: image.tone_map = \"{}\" does not apply to {}: an EXR holds linear radiance; write a .png to see it tone-mapped",
            scene.tone_map,
            path.display()
        );
    }
    output.write_tone_mapped(&frame, args.exposure, scene.tone_map)?;
    timings.push("encode + write", start.elapsed(), Clock::Wall);
    timings.push("total", total.elapsed(), Clock::Wall);
    if args.timings {
        println!("{}", timings.report());
    }
    if args.verbose {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// The warning of a GPU render of a scene whose materials use light
/// through surfaces the GPU does not draw, one line naming every such
/// material (nothing the user typed is ignored without a word): with
/// `shading.transmission = "off"` every key of light through surfaces
/// (`transmission`, `thickness`, `attenuation_*`, `dispersion`,
/// `diffuse_transmission*`). The screen-space mode draws every key and
/// texture; its limits are the method's, named once in
/// docs/transmission.md.
pub fn gpu_transmission_warning(scene: &Scene) -> Option<String> {
    if scene.transmission.mode != crate::scene::TransmissionMode::Off {
        return None;
    }
    let mut names: Vec<String> = Vec::new();
    for m in &scene.materials {
        let name = format!("`{}`", m.name);
        if m.model == crate::material::ReflectanceModel::GltfPbr
            && m.layers.sets_transmission_keys()
            && !names.contains(&name)
        {
            names.push(name);
        }
    }
    if names.is_empty() {
        return None;
    }
    let one = names.len() == 1;
    let (s, verb_s, they, them) = if one {
        ("", "s", "it is", "it")
    } else {
        ("s", "", "they are", "them")
    };
    let names = names.join(", ");
    Some(format!(
        "warning: material{s} {names} use{verb_s} light through surfaces (transmission, volume, dispersion, diffuse transmission), which the GPU renderer does not draw with shading.transmission = \"off\": {they} drawn as if opaque; use \"screen\", or render with --reference to see the light through {them}"
    ))
}

/// The note of a GPU render of a scene with spectral metals (material key
/// `spectral_metal`), one line naming each: the GPU has three channels and
/// renders the metal's preset; the spectral Fresnel is the reference's.
pub fn gpu_spectral_note(scene: &Scene) -> Option<String> {
    let mut named: Vec<String> = Vec::new();
    for m in &scene.materials {
        if let Some(metal) = m.spectral_metal {
            let one = format!("`{}` ({metal}: preset `{}`)", m.name, metal.preset_name());
            if !named.contains(&one) {
                named.push(one);
            }
        }
    }
    if named.is_empty() {
        return None;
    }
    Some(format!(
        "spectral_metal: the GPU renderer evaluates the Fresnel term in three channels, so material{} {} {} drawn with the three-channel preset; render with --reference for the spectral Fresnel of the published table",
        if named.len() == 1 { "" } else { "s" },
        named.join(", "),
        if named.len() == 1 { "is" } else { "are" }
    ))
}

/// The warning of a reference render whose transmission paths were cut
/// with more than 10⁻³ of a pixel's light untraced (`lost`, per unit
/// radiance behind the surface).
pub fn untraced_transmission_warning(lost: f64) -> Option<String> {
    (lost > 1e-3).then(|| {
        format!(
            "warning: light through surfaces: up to {lost:.3} of a pixel's transmitted light (per unit radiance behind) was not traced: the paths end after {} crossings",
            reference::transmission::path::MAX_DEPTH
        )
    })
}

/// Refuses a render whose renderer would allocate more than
/// `--limit memory` (estimated from the scene before anything is built),
/// naming what makes it large and what would fit.
fn check_memory(scene: &Scene, reference: bool, limits: &Limits) -> Result<()> {
    let (bytes, what) = if reference {
        (
            reference::memory_estimate(scene),
            "the CPU reference's ray-casting hierarchy",
        )
    } else {
        (
            crate::gpu::prepared::host_memory_estimate(scene),
            "the GPU path's vertex stream and its staging window",
        )
    };
    if bytes <= limits.memory {
        return Ok(());
    }
    let triangles = scene.triangle_count() as u64;
    let per_triangle = bytes.div_ceil(triangles.max(1));
    let size = |b: u64| {
        if b >= 1 << 30 {
            format!("{:.1} GiB", b as f64 / f64::from(1u32 << 30))
        } else {
            format!("{:.0} MiB", b as f64 / f64::from(1u32 << 20))
        }
    };
    Err(Error::argument(
        "--limit memory",
        format!(
            "{what} for {triangles} triangles would take about {}, over the limit of {}: at most about {} triangles fit; use fewer `segments` (a sphere of n segments has about n²/2 triangles, a plane 2n²) or a smaller model, or raise the limit with `--limit memory=16Gi` if the machine has the memory",
            size(bytes),
            size(limits.memory),
            limits.memory / per_triangle.max(1),
        ),
    ))
}

/// Tells the user about requested features this build does not draw yet
/// (none at the moment: every light kind casts shadows).
fn warn_unsupported(_scene: &Scene) {}

fn describe_scene(scene: &Scene) -> String {
    let models: std::collections::BTreeSet<_> = scene
        .meshes
        .iter()
        .map(|m| scene.materials[m.material].model.name())
        .collect();
    format!(
        "scene: {}x{} px, {} meshes, {} triangles, {} materials ({}), {} lights, shading {}",
        scene.width,
        scene.height,
        scene.meshes.len(),
        scene.triangle_count(),
        scene.materials.len(),
        models.into_iter().collect::<Vec<_>>().join(", "),
        scene.lights.len(),
        scene.shading
    )
}

#[cfg(test)]
mod transmission_warning_tests {
    use super::gpu_transmission_warning;
    use crate::scene::scene_file::{self, SceneSource};

    fn warning(sets: &[&str]) -> Option<String> {
        let mut all = vec!["materials.ball.model=gltf-pbr".to_string()];
        all.extend(sets.iter().map(|s| s.to_string()));
        gpu_transmission_warning(&scene_file::load(&SceneSource::BuiltIn, &all).unwrap())
    }

    /// The GPU draws transmission, dispersion and diffuse transmission in
    /// screen space, their textures too: nothing is named; with
    /// `shading.transmission = "off"` every key of light through surfaces
    /// is.
    #[test]
    fn the_warning_names_only_what_the_gpu_leaves_out() {
        assert_eq!(warning(&["materials.ball.diffuse_transmission=0.5"]), None);
        assert_eq!(
            warning(&[
                "materials.ball.transmission=1",
                "materials.ball.thickness=1",
                "materials.ball.dispersion=1",
            ]),
            None
        );
        let checker = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/scenes/transmission/checker.png"
        );
        let textured = format!("materials.ball.diffuse_transmission_texture=\"{checker}\"");
        assert_eq!(
            warning(&["materials.ball.diffuse_transmission=0.5", &textured]),
            None
        );
        let off = warning(&["materials.ball.transmission=1", "shading.transmission=off"])
            .expect("off names the material");
        assert!(off.contains("drawn as if opaque"), "{off}");
    }
}

#[cfg(test)]
mod spectral_note_tests {
    use super::gpu_spectral_note;
    use crate::scene::scene_file::{self, SceneSource};

    fn note(sets: &[&str]) -> Option<String> {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        gpu_spectral_note(&scene_file::load(&SceneSource::BuiltIn, &sets).unwrap())
    }

    /// One note naming each spectral metal and its preset; none without.
    #[test]
    fn the_note_names_the_spectral_metals() {
        assert_eq!(note(&[]), None);
        let one = note(&[
            "materials.ball.model=cook-torrance",
            "materials.ball.spectral_metal=copper",
        ])
        .expect("a spectral metal is named");
        assert!(
            one.contains("material `ball` (copper: preset `copper-rgb`) is drawn"),
            "{one}"
        );
        assert!(one.contains("--reference"), "{one}");
    }
}
