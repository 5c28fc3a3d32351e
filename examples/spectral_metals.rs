//! The reference's spectral Fresnel of the metals against their
//! three-channel presets, in an image: `cargo run --release --example
//! spectral_metals -- OUT.png [SCENE] [-- KEY=VALUE ...]` (SCENE defaults
//! to assets/scenes/spectral_metals.toml: one sphere per metal, each
//! material a coloured preset `NAME-rgb`). Renders SCENE with the
//! reference as written (the presets) and with `spectral_metal = NAME`
//! added to every material whose η, κ are a metal's preset, each twice,
//! alternating; prints the times, the cost of one Fresnel evaluation (the
//! preset's, the spectral table's, the direct spectral integral's), and
//! per material (the covered pixels whose nearest projected object centre
//! is one of its objects) the mean and largest `|spectral − preset|` per
//! channel and the relative RMS `sqrt(Σ|Δ|² / Σ|spectral|²)`; writes
//! OUT.png: the presets on top, the spectral render in the middle, `|Δ|`
//! times 8 at the bottom (exposure −1, the scene's tone map).

use glam::DVec3;
use gonio::frame::Frame;
use gonio::material::brdf::fresnel::fresnel_conductor;
use gonio::material::conductors::Metal;
use gonio::output::write::pixel_to_srgb8;
use gonio::reference::spectral::conductors::spectral_conductor_rgb;
use gonio::reference::spectral::fresnel_tables;
use gonio::reference::spectral::metals;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};
use std::path::PathBuf;
use std::time::Instant;

/// How much the difference panel is brightened.
const DIFFERENCE_GAIN: f32 = 8.0;
/// The picture's exposure [stops]: the sun's highlight stays below white
/// on most of its area.
const EXPOSURE: f64 = -1.0;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--").unwrap_or(args.len());
    if !(1..=2).contains(&split) {
        eprintln!("usage: spectral_metals OUT.png [SCENE] [-- KEY=VALUE ...]");
        std::process::exit(2);
    }
    let out = PathBuf::from(&args[0]);
    let file = args
        .get(1)
        .filter(|_| split == 2)
        .cloned()
        .unwrap_or_else(|| {
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/assets/scenes/spectral_metals.toml"
            )
            .into()
        });
    let overrides: Vec<String> = args.get(split + 1..).unwrap_or_default().to_vec();
    let source = SceneSource::File(file.into());
    let preset_scene = scene_file::load(&source, &overrides).unwrap();
    let mut spectral_overrides = overrides.clone();
    for m in &preset_scene.materials {
        if let Some(metal) = Metal::ALL.into_iter().find(|metal| {
            let c = metal.coloured();
            m.eta.to_array() == c.eta && m.kappa.to_array() == c.kappa
        }) {
            spectral_overrides.push(format!("materials.{}.spectral_metal={metal}", m.name));
        }
    }
    let spectral_scene = scene_file::load(&source, &spectral_overrides).unwrap();
    fresnel_cost();
    // Each twice, alternating, the faster time of each: the first render
    // also pays for what the scene builds on first use.
    let (_, p1) = timed(&preset_scene);
    let (_, s1) = timed(&spectral_scene);
    let (preset, p2) = timed(&preset_scene);
    let (spectral, s2) = timed(&spectral_scene);
    println!(
        "reference render {}x{} on {} threads: presets {p1:.1} s, {p2:.1} s; spectral {s1:.1} s, {s2:.1} s",
        preset.width,
        preset.height,
        rayon::current_num_threads()
    );
    statistics(&spectral_scene, &preset, &spectral);
    let encode = |p: [f32; 3]| pixel_to_srgb8(p, EXPOSURE, preset_scene.tone_map);
    let mut pixels: Vec<u8> = Vec::new();
    for frame in [&preset, &spectral] {
        pixels.extend(frame.radiance.iter().flat_map(|&p| encode(p)));
    }
    for (a, b) in preset.radiance.iter().zip(&spectral.radiance) {
        let d = [0, 1, 2].map(|c| (a[c] - b[c]).abs() * DIFFERENCE_GAIN);
        pixels.extend(pixel_to_srgb8(d, 0.0, preset_scene.tone_map));
    }
    image::RgbImage::from_raw(preset.width, 3 * preset.height, pixels)
        .unwrap()
        .save(&out)
        .unwrap();
}

fn timed(scene: &Scene) -> (Frame, f64) {
    let start = Instant::now();
    let frame = gonio::reference::render(scene);
    (frame, start.elapsed().as_secs_f64())
}

/// The time of one Fresnel evaluation of gold: the preset's exact
/// conductor Fresnel in three channels, the spectral table, and the direct
/// integral over 81 wavelengths.
fn fresnel_cost() {
    let table = fresnel_tables::table(Metal::Gold);
    let gold = metals::of(Metal::Gold);
    let per = |n: usize, f: &dyn Fn(f64) -> DVec3| {
        let start = Instant::now();
        let mut sum = DVec3::ZERO;
        for k in 0..n {
            sum += f((k as f64 + 0.5) / n as f64);
        }
        std::hint::black_box(sum);
        start.elapsed().as_secs_f64() / n as f64
    };
    let c = Metal::Gold.coloured();
    let (eta, kappa) = (DVec3::from_array(c.eta), DVec3::from_array(c.kappa));
    let p = per(1_000_000, &|cos| fresnel_conductor(cos, eta, kappa));
    let t = per(1_000_000, &|cos| table.eval(cos));
    let d = per(10_000, &|cos| spectral_conductor_rgb(gold, cos));
    println!(
        "one Fresnel evaluation: the preset's three channels {:.1} ns, the spectral table {:.1} ns, the direct spectral integral {:.2} µs ({:.0}× the table)",
        p * 1e9,
        t * 1e9,
        d * 1e6,
        d / t
    );
}

/// Per material: mean and largest |Δ| per channel and the relative RMS
/// over the covered pixels nearest one of its objects' projected centres,
/// and the same over all covered pixels.
fn statistics(scene: &Scene, preset: &Frame, spectral: &Frame) {
    let (w, h) = (preset.width, preset.height);
    let centres: Vec<(f64, f64, usize)> = scene
        .meshes
        .iter()
        .map(|m| {
            let (lo, hi) = m.positions.iter().fold(
                (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
                |(lo, hi), &p| (lo.min(p), hi.max(p)),
            );
            let (x, y) = scene.camera.project(0.5 * (lo + hi), w, h);
            (x, y, m.material)
        })
        .collect();
    let mut groups: Vec<(String, Vec<usize>)> = scene
        .materials
        .iter()
        .map(|m| (m.name.clone(), Vec::new()))
        .collect();
    let mut all = Vec::new();
    for i in 0..h {
        for j in 0..w {
            let k = preset.index(i, j);
            if !preset.coverage[k] {
                continue;
            }
            let (x, y) = (j as f64 + 0.5, i as f64 + 0.5);
            let nearest = centres
                .iter()
                .min_by(|a, b| {
                    let d = |c: &&(f64, f64, usize)| (c.0 - x).powi(2) + (c.1 - y).powi(2);
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            groups[nearest.2].1.push(k);
            all.push(k);
        }
    }
    groups.push(("all spheres".into(), all));
    println!(
        "| material | pixels | mean R | mean G | mean B | max R | max G | max B | relative RMS |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, pixels) in groups.iter().filter(|(_, p)| !p.is_empty()) {
        let (mut sum, mut max) = (DVec3::ZERO, DVec3::ZERO);
        let (mut sq, mut truth) = (0.0, 0.0);
        for &k in pixels {
            let s = DVec3::from_array(spectral.radiance[k].map(f64::from));
            let p = DVec3::from_array(preset.radiance[k].map(f64::from));
            let d = (s - p).abs();
            sum += d;
            max = max.max(d);
            sq += d.length_squared();
            truth += s.length_squared();
        }
        let mean = sum / pixels.len() as f64;
        println!(
            "| {name} | {} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} |",
            pixels.len(),
            mean.x,
            mean.y,
            mean.z,
            max.x,
            max.y,
            max.z,
            (sq / truth).sqrt()
        );
    }
}
