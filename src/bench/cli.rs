//! `gonio bench [SCENE] [-o DIR] [--quick] [--repeats N] ...`

use std::path::PathBuf;

/// Where `gonio bench` writes and `gonio render --max-error` reads.
pub const DEFAULT_OUT: &str = "gonio-bench";

/// `gonio bench`: time and error of every knob, floors, ratios, scale.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// A scene `.toml`, `.gltf` or `.glb`. Without it: the built-in scene,
    /// with a Cook-Torrance gold sphere, a shadow-casting point light and
    /// an area light added so that every knob has something to act on.
    pub scene: Option<PathBuf>,
    /// Output folder: report.md, results.csv, scale.csv, pareto.svg,
    /// pareto.png (created if missing; files are replaced atomically).
    #[arg(short, long = "out", value_name = "DIR", default_value = DEFAULT_OUT)]
    pub out: PathBuf,
    /// Fewer repeats and a shorter scale sweep (every knob is still measured
    /// against its traced truth, which takes most of the run).
    #[arg(long)]
    pub quick: bool,
    /// One iteration at tiny sizes: checks that everything runs (CI).
    #[arg(long)]
    pub smoke: bool,
    /// Timed frames per configuration (split over two passes), after warm-up.
    #[arg(long, value_name = "N")]
    pub repeats: Option<usize>,
    /// Skip the triangle and resolution sweeps.
    #[arg(long)]
    pub no_scale: bool,
    /// Override a key of the base scene, as for `gonio render`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Measure only shard I of N of the configurations (configuration k
    /// by shard k mod N + 1) into DIR/shards/bench-shard-I-of-N.csv, for
    /// `--merge`; no target ratios, no scale sweeps. `auto` (or `auto/N`)
    /// reads Slurm's, Kubernetes' or HyperQueue's task variables. A shard
    /// whose file exists for the same run is skipped.
    #[arg(long, value_name = "I/N|auto", conflicts_with_all = ["merge", "shadow_ratio", "ratios", "probe_memory", "floor_triangle_png"])]
    pub shard: Option<String>,
    /// Join the shards in DIR/shards into DIR/results.csv and DIR/report.md.
    #[arg(long, conflicts_with_all = ["scene", "quick", "smoke", "repeats", "no_scale", "set"])]
    pub merge: bool,
    /// GPU adapter to use (also GONIO_ADAPTER).
    #[arg(long, value_name = "NAME")]
    pub adapter: Option<String>,
    /// Internal: measure the peak memory of one scale point
    /// (SEGMENTS,WIDTH,HEIGHT) in this fresh process, print it and exit.
    #[arg(long, value_name = "SPEC", hide = true)]
    pub probe_memory: Option<String>,
    /// Internal: measure only the shadowed Cook-Torrance ratios (the
    /// budget of --quick, --smoke or the full run), print their rows and
    /// notes, and exit (A/B timing of the shadow passes).
    #[arg(long, hide = true)]
    pub shadow_ratio: bool,
    /// Internal: measure only the report's target ratios (specialized
    /// against hand-minimal, uber against specialized, shadowed against
    /// unlit, cold render against triangle-to-PNG) with the budget of
    /// --quick, --smoke or the full run, print their rows and exit (an
    /// interleaved before/after of two builds).
    #[arg(long, hide = true)]
    pub ratios: bool,
    /// Internal: run the minimal triangle-to-PNG floor program and exit.
    #[arg(long, value_name = "OUT", hide = true)]
    pub floor_triangle_png: Option<PathBuf>,
}
