//! The GPU's image of a scene against the f64 reference's, for scenes no
//! test draws (the glTF samples of docs/gltf.md, "The layers against the
//! reference"): `cargo run --release --example gpu_vs_reference -- OUT.png
//! FILE... [-- KEY=VALUE ...]`. Each file is loaded with the overrides,
//! rendered by the reference (one sample per pixel, its own settings) and
//! by the GPU (an override after `gpu:` applies to the GPU's scene alone:
//! `gpu:environment.specular="none"`); prints a Markdown row per file (relative RMS and relative
//! max error, `bench::measure::error`, and the reference's time), and
//! writes OUT.png: one row per file, the reference on the left, the GPU
//! in the middle, and on the right `|GPU − reference|` per channel times
//! 4, each through the scene's own tone map.

use gonio::bench::measure::error;
use gonio::frame::Frame;
use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use gonio::output::write::pixel_to_srgb8;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::PathBuf;

/// How much the difference panel is brightened.
const DIFFERENCE_GAIN: f32 = 4.0;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--").unwrap_or(args.len());
    if split < 2 {
        eprintln!("usage: gpu_vs_reference OUT.png FILE... [-- KEY=VALUE ... gpu:KEY=VALUE ...]");
        std::process::exit(2);
    }
    let out = PathBuf::from(&args[0]);
    let files = &args[1..split];
    let all: Vec<String> = args.get(split + 1..).unwrap_or_default().to_vec();
    let overrides: Vec<String> = all
        .iter()
        .filter(|a| !a.starts_with("gpu:"))
        .cloned()
        .collect();
    let mut gpu_overrides = overrides.clone();
    gpu_overrides.extend(
        all.iter()
            .filter_map(|a| a.strip_prefix("gpu:").map(String::from)),
    );
    let ctx = GpuContext::new(&AdapterChoice::from_flag_or_env(None)).unwrap();
    let mut renderer = GpuRenderer::new(ctx);
    let mut rows: Vec<Vec<u8>> = Vec::new();
    let (mut width, mut height) = (0, 0);
    println!("| file | relative RMS | relative max | reference [s] |");
    println!("| --- | --- | --- | --- |");
    for file in files {
        let scene = scene_file::load(&SceneSource::File(file.into()), &overrides).unwrap();
        let start = std::time::Instant::now();
        let truth = gonio::reference::render(&scene);
        let seconds = start.elapsed().as_secs_f64();
        let gpu_scene = scene_file::load(&SceneSource::File(file.into()), &gpu_overrides).unwrap();
        let (gpu, _) = renderer.render(&gpu_scene).unwrap();
        let (rms, max) = error(&gpu, &truth);
        let name = PathBuf::from(file);
        let name = name.file_stem().unwrap().to_string_lossy();
        println!("| {name} | {rms:.4} | {max:.3} | {seconds:.1} |");
        (width, height) = (truth.width, truth.height);
        rows.push(row(&scene, &truth, &gpu));
    }
    let pixels: Vec<u8> = rows.concat();
    image::RgbImage::from_raw(3 * width, height * files.len() as u32, pixels)
        .unwrap()
        .save(&out)
        .unwrap();
}

/// One row of the picture: reference, GPU, difference (see the module
/// doc), as 8-bit sRGB rows.
fn row(scene: &Scene, truth: &Frame, gpu: &Frame) -> Vec<u8> {
    let encode = |p: [f32; 3]| pixel_to_srgb8(p, 0.0, scene.tone_map);
    let mut pixels = Vec::new();
    for y in 0..truth.height as usize {
        let line = |frame: &Frame| -> Vec<u8> {
            let w = frame.width as usize;
            frame.radiance[y * w..(y + 1) * w]
                .iter()
                .flat_map(|&p| encode(p))
                .collect()
        };
        pixels.extend(line(truth));
        pixels.extend(line(gpu));
        let w = truth.width as usize;
        for x in 0..w {
            let (a, b) = (truth.radiance[y * w + x], gpu.radiance[y * w + x]);
            let d = [0, 1, 2].map(|c| (a[c] - b[c]).abs() * DIFFERENCE_GAIN);
            pixels.extend(encode(d));
        }
    }
    pixels
}
