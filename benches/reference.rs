//! The CPU reference renderer on a small built-in scene, per shading mode
//! and with ray-traced shadows.

use criterion::{Criterion, criterion_group, criterion_main};
use gonio::scene::scene_file::{SceneSource, load};
use std::hint::black_box;

fn reference(c: &mut Criterion) {
    let mut group = c.benchmark_group("reference render, built-in scene 160x120");
    group.sample_size(10);
    for (name, extra) in [
        ("phong", vec![]),
        ("gouraud", vec!["shading.mode=gouraud"]),
        ("flat", vec!["shading.mode=flat"]),
        ("phong, shadowed light", vec!["lights.0.shadows=true"]),
    ] {
        let overrides: Vec<String> = ["image.width=160", "image.height=120"]
            .into_iter()
            .chain(extra)
            .map(str::to_string)
            .collect();
        let scene = load(&SceneSource::BuiltIn, &overrides).expect("built-in scene");
        group.bench_function(name, |b| {
            b.iter(|| gonio::reference::render(black_box(&scene)))
        });
    }
    group.finish();
}

criterion_group!(benches, reference);
criterion_main!(benches);
