//! `gonio bench`: the speed/accuracy trade, measured.
//!
//! The data flow: [`configs`] turns each knob (shading mode, reflectance
//! model, Fresnel, distribution, shadow-map size and filter, area-light
//! samples, MSAA, resolution) into `--set` overrides on a base scene;
//! [`measure`] renders every configuration on the GPU, times it with the
//! renderer's timestamp queries and measures its error against the truth
//! image of the CPU reference; [`floors`] and [`harness`] draw the floors
//! (an unlit pass, a hand-minimal shader, a triangle-to-PNG program) and
//! the uber shader that costs are compared with; [`ratios`] measures the
//! target ratios; [`scale`] sweeps triangles and pixels;
//! [`pareto`] finds the front and the `--max-error` pick ([`auto`]);
//! [`report`] and [`plot`] write the Markdown report, the CSV and the
//! plots. [`run`] ties it together; [`cli`] is the command line.

pub mod auto;
pub mod cli;
pub mod configs;
pub mod floors;
pub mod harness;
pub mod measure;
pub mod pareto;
pub mod plot;
pub mod ratios;
pub mod report;
pub mod run;
pub mod scale;
pub mod shards;

use crate::gpu::timing::Clock;
use configs::{Config, Skipped};
use measure::Stats;
use ratios::Ratio;

/// One measured configuration.
#[derive(Clone, Debug)]
pub struct Row {
    pub config: Config,
    /// All repeats of both passes.
    pub time: Stats,
    /// First and second pass over all configurations (the `--max-error`
    /// check picks on one and scores on the other).
    pub time_a: Stats,
    pub time_b: Stats,
    /// Relative RMS error against the truth.
    pub error: f64,
    /// Largest |error| over the largest truth value.
    pub max_rel: f64,
    pub on_front: bool,
}

/// How a `--max-error` pick made on the first pass fares on the second.
#[derive(Clone, Debug)]
pub struct AutoCheck {
    pub max_error: f64,
    /// Row picked from the first pass's front.
    pub pick: usize,
    /// The cheapest row within the budget on the second pass.
    pub best: usize,
    /// Second-pass time of the pick over that of the best (≥ 1).
    pub ratio: f64,
    /// The two configurations' second-pass interquartile ranges overlap:
    /// their times cannot be told apart on this machine.
    pub overlap: bool,
}

/// Everything `gonio bench` measured.
#[derive(Clone, Debug)]
pub struct BenchReport {
    /// "built-in" or the scene path.
    pub scene: String,
    pub adapter: String,
    pub clock: Clock,
    pub base_overrides: Vec<String>,
    /// What the truth image is.
    pub truth: String,
    pub truth_ms: f64,
    pub width: u32,
    pub height: u32,
    pub triangles: usize,
    pub warmup: usize,
    pub repeats: usize,
    pub rows: Vec<Row>,
    pub not_measured: Vec<Skipped>,
    /// Unlit pass over the base scene's geometry.
    pub unlit: Stats,
    pub ratios: Vec<Ratio>,
    /// (label, ms) of pipeline compilations.
    pub compile: Vec<(String, f64)>,
    pub auto: Vec<AutoCheck>,
    pub scale: Option<scale::Scale>,
    pub elapsed_s: f64,
    pub smoke: bool,
}
