//! A/B timing of hand-edited WGSL variants of the bench's specialized
//! Lambert scene (issue 18 item 1: one change at a time in the generated
//! shader, interleaved): `cargo run --release --example ab_wgsl -- ROUNDS
//! [FILE.wgsl ...]`. Each variant is drawn by the bench's harness over the
//! renderer's vertex stream, so only the shader differs, and is checked
//! to draw the renderer's image bit for bit ("identical to renderer").
//! Side 0 is the hand-minimal shader, side 1 the generated one, then each
//! file. Prints, per side, the
//! median time and the median [quartiles] of the per-round ratio to the
//! hand-minimal one. With ROUNDS = 0 it writes the generated module to
//! /tmp/generated.wgsl and the hand-minimal to /tmp/minimal.wgsl.

use gonio::bench::floors;
use gonio::bench::harness::{Harness, HarnessShader, Inputs};
use gonio::bench::measure::Stats;
use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use gonio::scene::scene_file::{self, SceneSource};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let rounds: usize = args[0].parse().unwrap();
    let scene = scene_file::load(
        &SceneSource::BuiltIn,
        &["materials.ball.model=lambert".to_string()],
    )
    .unwrap();
    assert!(floors::is_lambert_one_point_light(&scene));
    let key = floors::specialized_key(&scene);
    let minimal = floors::minimal_lambert(&scene);
    let generated = HarnessShader::generated("generated", key.clone());
    if rounds == 0 {
        std::fs::write("/tmp/generated.wgsl", &generated.wgsl).unwrap();
        std::fs::write("/tmp/minimal.wgsl", &minimal.wgsl).unwrap();
        return;
    }
    let ctx = GpuContext::new(&AdapterChoice::from_flag_or_env(None)).unwrap();
    let mut renderer = GpuRenderer::new(ctx);
    let mut shaders = vec![minimal, generated];
    for f in &args[1..] {
        shaders.push(HarnessShader {
            label: f.clone(),
            wgsl: std::fs::read_to_string(f).unwrap(),
            inputs: Inputs::All,
            key: key.clone(),
        });
    }
    let harnesses: Vec<Harness> = shaders
        .iter()
        .map(|s| Harness::new(&mut renderer, &scene, s).unwrap())
        .collect();
    let ours = renderer.render(&scene).unwrap().0;
    for (s, h) in shaders.iter().zip(&harnesses) {
        let f = h.frame(renderer.context()).unwrap();
        let same = f.radiance == ours.radiance && f.coverage == ours.coverage;
        println!("{}: identical to renderer: {same}", s.label);
    }
    let n = harnesses.len();
    let mut times = vec![Vec::new(); n];
    for i in 0..rounds + 2 {
        let mut t = vec![0.0; n];
        for k in 0..n {
            let side = (k + i) % n;
            t[side] = harnesses[side].time_once(renderer.context()).unwrap().0;
        }
        if i >= 2 {
            for k in 0..n {
                times[k].push(t[k]);
            }
        }
    }
    for k in 0..n {
        let ratios: Vec<f64> = times[k].iter().zip(&times[0]).map(|(a, b)| a / b).collect();
        let r = Stats::of(&ratios);
        let t = Stats::of(&times[k]);
        println!(
            "{:>40}: {:.3} ms  ratio {:.4} [{:.4}-{:.4}]",
            shaders[k].label, t.median, r.median, r.q1, r.q3
        );
    }
}
