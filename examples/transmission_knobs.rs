//! Error and cost of the GPU's transmission knobs on one scene
//! (docs/transmission.md, "The GPU renderer"): `cargo run --release
//! --example transmission_knobs -- SCENE FRAMES [KEY=VALUE ...]`. The
//! reference renders the scene once with its own settings (the same
//! environment estimator as the GPU, so the difference is the light
//! through surfaces and f32); then each knob setting is drawn FRAMES
//! times on the GPU. Prints a Markdown row per setting: relative RMS and
//! relative max error against the reference (`bench::measure::error`),
//! and the median wall time of the frame's passes and readback (the
//! transmission images are drawn outside the scene pass's timestamps).

use gonio::bench::measure::{Stats, error};
use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use gonio::scene::scene_file::{self, SceneSource};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (path, frames) = (PathBuf::from(&args[0]), args[1].parse::<usize>().unwrap());
    let overrides: Vec<String> = args[2..].to_vec();
    let load = |extra: &[&str]| {
        let mut all = overrides.clone();
        all.extend(extra.iter().map(|s| s.to_string()));
        scene_file::load(&SceneSource::File(path.clone()), &all).unwrap()
    };
    let start = std::time::Instant::now();
    let truth = gonio::reference::render(&load(&[]));
    eprintln!("reference: {:.1} s", start.elapsed().as_secs_f64());
    let ctx = GpuContext::new(&AdapterChoice::from_flag_or_env(None)).unwrap();
    let mut renderer = GpuRenderer::new(ctx);
    let settings: [(&str, &[&str]); 6] = [
        ("off", &["shading.transmission=\"off\""]),
        (
            "screen, 1 layer, one interface",
            &["shading.transmission_exit=false"],
        ),
        ("screen, 1 layer", &[]),
        ("screen, 2 layers", &["shading.transmission_layers=2"]),
        ("screen, 4 layers", &["shading.transmission_layers=4"]),
        (
            "screen, 1 layer, exit ray traced",
            &["shading.transmission_exit_ray=\"traced\""],
        ),
    ];
    println!("| setting | relative RMS | relative max | frame [ms] |");
    println!("| --- | --- | --- | --- |");
    for (name, sets) in settings {
        let scene = load(sets);
        // One frame to compile, then the timed ones.
        let (frame, _) = renderer.render(&scene).unwrap();
        let times: Vec<f64> = (0..frames)
            .map(|_| {
                let (_, timings) = renderer.render(&scene).unwrap();
                timings
                    .entries
                    .iter()
                    .find(|(n, ..)| n == "render pass + readback")
                    .map(|(_, d, _)| d.as_secs_f64() * 1e3)
                    .unwrap()
            })
            .collect();
        let (rms, max) = error(&frame, &truth);
        let t = Stats::of(&times);
        println!(
            "| {name} | {rms:.4} | {max:.3} | {:.1} [{:.1}, {:.1}] |",
            t.median, t.q1, t.q3
        );
    }
}
