//! How time and memory grow with triangles and pixels.
//!
//! Triangles: the built-in scene with its sphere tessellated from 10⁴ to
//! 10⁶ triangles, drawn at 256² so that the vertex work dominates.
//! Pixels: the built-in scene (8.5k triangles) from 256² to 3840×2160.
//! Time is the GPU time of the scene pass (median of the repeats); the
//! growth rate is the least-squares slope of log time against log size
//! (1 is linear).
//!
//! Memory: the bytes the renderer uploads for the mesh (vertex and index
//! buffers, the same [`GeometryData`] it builds) and the peak resident
//! memory (`VmHWM` of `/proc/self/status`) of loading and rendering the
//! point once in a fresh process that has only opened the device and
//! compiled the pipeline (on a tiny mesh), over
//! its resident memory before loading (the peak is reset first through
//! `/proc/self/clear_refs`, Linux ≥ 4.0). On lavapipe "GPU" buffers live
//! in host memory, so they are part of that peak.

use super::measure::{self, Stats};
use crate::Result;
use crate::gpu::GpuRenderer;
use crate::gpu::geometry::GeometryData;
use crate::gpu::shader_gen::ShaderKey;
use crate::scene::scene_file::{self, SceneSource};

/// One point of a sweep.
#[derive(Clone, Debug)]
pub struct ScalePoint {
    /// Triangles drawn.
    pub triangles: usize,
    pub width: u32,
    pub height: u32,
    /// Scene-pass time, ms.
    pub time: Stats,
    /// Vertex + index bytes uploaded.
    pub mesh_bytes: u64,
    /// Bytes of the `f64` scene meshes (positions, normals, tangents,
    /// indices) that both renderers start from.
    pub scene_bytes: u64,
    /// Growth of peak resident memory over the baseline, bytes (`None`
    /// where `/proc` cannot tell).
    pub peak_rss_bytes: Option<u64>,
    /// The same after loading the scene, before rendering it.
    pub load_rss_bytes: Option<u64>,
    /// The same for rendering the scene with an 8-segment sphere: what
    /// the frame costs whatever the mesh (targets, readback, shadow maps).
    pub frame_rss_bytes: Option<u64>,
    /// The scene's light casts shadows (a cube map: the mesh's stream is
    /// the unshadowed one, indexed).
    pub shadows: bool,
}

impl ScalePoint {
    pub fn pixels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    /// The mesh's share of the peak: the peak growth less the frame's
    /// fixed cost ([`ScalePoint::frame_rss_bytes`]).
    pub fn mesh_peak_bytes(&self) -> Option<u64> {
        Some(self.peak_rss_bytes?.saturating_sub(self.frame_rss_bytes?))
    }
}

/// Both sweeps and their fitted growth rates.
#[derive(Clone, Debug, Default)]
pub struct Scale {
    pub triangles: Vec<ScalePoint>,
    /// The largest triangle count again with the light casting shadows.
    pub shadowed: Option<ScalePoint>,
    pub pixels: Vec<ScalePoint>,
}

impl Scale {
    /// Log-log slope of time against triangles.
    pub fn triangle_slope(&self) -> f64 {
        slope(
            self.triangles
                .iter()
                .map(|p| (p.triangles as f64, p.time.median)),
        )
    }

    /// Log-log slope of time against pixels.
    pub fn pixel_slope(&self) -> f64 {
        slope(
            self.pixels
                .iter()
                .map(|p| (p.pixels() as f64, p.time.median)),
        )
    }

    /// Linear fit of time (ms) against triangles.
    pub fn triangle_fit(&self) -> (f64, f64, f64) {
        linear_fit(
            self.triangles
                .iter()
                .map(|p| (p.triangles as f64, p.time.median)),
        )
    }

    /// Linear fit of time (ms) against pixels.
    pub fn pixel_fit(&self) -> (f64, f64, f64) {
        linear_fit(
            self.pixels
                .iter()
                .map(|p| (p.pixels() as f64, p.time.median)),
        )
    }
}

/// Least-squares line `y = a + b·x`: `(a, b, R²)` (NaN with fewer than
/// two distinct x). R² near 1 with a > 0 is "linear plus a fixed cost",
/// which a log-log slope below 1 also shows.
pub fn linear_fit(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64, f64) {
    let pts: Vec<(f64, f64)> = points.collect();
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    if pts.len() < 2 || sxx == 0.0 {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let b = sxy / sxx;
    let r2 = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        1.0
    };
    (my - b * mx, b, r2)
}

/// Least-squares slope of `ln y` against `ln x` (NaN with fewer than two
/// distinct points).
pub fn slope(points: impl Iterator<Item = (f64, f64)>) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if pts.len() < 2 || sxx == 0.0 {
        return f64::NAN;
    }
    sxy / sxx
}

/// Sphere segments for about `triangles` triangles (a UV sphere of `s`
/// segments has `s · (s/2) · 2 − 2s ≈ s²` of them).
pub fn segments_for(triangles: usize) -> u32 {
    (triangles as f64).sqrt().round().max(4.0) as u32
}

/// What to sweep.
#[derive(Clone, Debug)]
pub struct Plan {
    pub triangles: Vec<usize>,
    pub triangle_image: (u32, u32),
    pub resolutions: Vec<(u32, u32)>,
    pub warmup: usize,
    pub repeats: usize,
}

impl Plan {
    pub fn full() -> Self {
        Plan {
            triangles: vec![10_000, 30_000, 100_000, 300_000, 1_000_000],
            triangle_image: (256, 256),
            resolutions: vec![
                (256, 256),
                (512, 512),
                (1024, 1024),
                (1920, 1080),
                (2048, 2048),
                (3840, 2160),
            ],
            warmup: 1,
            repeats: 3,
        }
    }

    pub fn smoke() -> Self {
        Plan {
            triangles: vec![1_000, 4_000],
            triangle_image: (32, 32),
            resolutions: vec![(32, 32), (64, 64)],
            warmup: 0,
            repeats: 1,
        }
    }

    /// Number of measured points (for the progress bar).
    pub fn len(&self) -> usize {
        self.triangles.len() + 1 + self.resolutions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Resets the process's peak RSS and returns the current RSS, bytes.
fn reset_peak() -> Option<u64> {
    std::fs::write("/proc/self/clear_refs", "5").ok()?;
    status_kib("VmRSS:").map(|k| k * 1024)
}

fn status_kib(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find(|l| l.starts_with(field))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}

/// One point: the built-in scene with `segments` on the sphere at `size`.
fn point(
    renderer: &mut GpuRenderer,
    (segments, shadows): (u32, bool),
    size: (u32, u32),
    plan: &Plan,
    adapter: Option<&str>,
) -> Result<ScalePoint> {
    let scene = scene_file::load(
        &SceneSource::BuiltIn,
        &point_overrides(segments, size, shadows),
    )?;
    let memory = memory_in_child(segments, size, shadows, adapter);
    let mut times = Vec::new();
    for i in 0..plan.warmup + plan.repeats {
        let (_, timings) = renderer.render(&scene)?;
        if i >= plan.warmup {
            times.push(measure::render_pass_ms(&timings));
        }
    }
    let key = ShaderKey::new(&scene, &crate::gpu::shadows::ShadowPlan::new(&scene));
    let (vertex_bytes, index_bytes) =
        GeometryData::byte_sizes(&scene, key.needs_tangents(), key.shadow_coords_per_vertex());
    let mesh_bytes = vertex_bytes + index_bytes;
    let scene_bytes = scene
        .meshes
        .iter()
        .map(|m| {
            24 * (m.positions.len() + m.normals.len() + m.tangents.len()) + 12 * m.indices.len()
        })
        .sum::<usize>() as u64;
    Ok(ScalePoint {
        scene_bytes,
        triangles: scene.triangle_count(),
        width: size.0,
        height: size.1,
        time: Stats::of(&times),
        mesh_bytes,
        peak_rss_bytes: memory.map(|m| m.1),
        load_rss_bytes: memory.map(|m| m.0),
        frame_rss_bytes: memory.map(|m| m.2),
        shadows,
    })
}

fn point_overrides(segments: u32, size: (u32, u32), shadows: bool) -> Vec<String> {
    vec![
        format!("objects.0.segments={segments}"),
        format!("image.width={}", size.0),
        format!("image.height={}", size.1),
        format!("lights.0.shadows={shadows}"),
    ]
}

/// The peak memory growth of loading and rendering one point, measured in
/// a fresh process (`gonio bench --probe-memory SEGMENTS,W,H`): in this
/// process the allocator would serve it from memory that earlier, larger
/// work freed, and the resident set would not show it.
/// Returns (growth after loading, growth after rendering, growth of
/// rendering the tiny mesh).
fn memory_in_child(
    segments: u32,
    size: (u32, u32),
    shadows: bool,
    adapter: Option<&str>,
) -> Option<(u64, u64, u64)> {
    let exe = std::env::current_exe().ok()?;
    let mut command = std::process::Command::new(exe);
    command.args([
        "bench",
        "--probe-memory",
        &format!("{segments},{},{},{}", size.0, size.1, shadows as u8),
    ]);
    if let Some(a) = adapter {
        command.args(["--adapter", a]);
    }
    let out = command.output().ok()?;
    if !out.status.success() {
        return None;
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let numbers: Vec<u64> = text
        .split_whitespace()
        .map(|w| w.parse::<u64>().ok())
        .collect::<Option<_>>()?;
    match numbers[..] {
        [load, total, frame] => Some((load, total, frame)),
        _ => None,
    }
}

/// `gonio bench --probe-memory SEGMENTS,W,H[,SHADOWS]`: opens the
/// device, renders a tiny scene of the same shader key (compiling the
/// pipeline), then loads and renders the point once as `gonio render`
/// does (GPU only: the meshes freed as they are uploaded) and prints the
/// growth of the peak resident memory over the resident memory before
/// loading, in bytes, after loading and after rendering; and third, the
/// same growth for rendering the tiny scene once more (the frame's fixed
/// cost: targets, readback, shadow maps).
pub fn probe_memory(spec: &str, adapter: Option<&str>) -> Result<()> {
    let bad = || {
        crate::Error::argument(
            format!("--probe-memory {spec}"),
            "expected SEGMENTS,WIDTH,HEIGHT[,SHADOWS (0 or 1)]",
        )
    };
    let v: Vec<u32> = spec
        .split(',')
        .map(|x| x.trim().parse().map_err(|_| bad()))
        .collect::<Result<_>>()?;
    let (segments, w, h, shadows) = match v[..] {
        [segments, w, h] => (segments, w, h, false),
        [segments, w, h, s @ (0 | 1)] => (segments, w, h, s == 1),
        _ => return Err(bad()),
    };
    let ctx = crate::gpu::GpuContext::new(&crate::gpu::AdapterChoice::from_flag_or_env(adapter))?;
    let mut renderer = GpuRenderer::new(ctx);
    // A tiny scene with the same shader key first: pipeline compilation
    // (the driver's JIT) is not what the mesh costs.
    renderer.render(&scene_file::load(
        &SceneSource::BuiltIn,
        &point_overrides(8, (w, h), shadows),
    )?)?;
    // Each measured render makes its own textures, as in a `gonio render`
    // process: none is left in the device's pool (src/gpu/texture_pool.rs)
    // to hide in the baseline.
    renderer.context().textures.clear();
    let baseline = reset_peak().ok_or_else(|| {
        crate::Error::Gpu("cannot read /proc/self/status to measure memory".into())
    })?;
    let peak = || {
        status_kib("VmHWM:")
            .map(|k| k * 1024)
            .ok_or_else(|| crate::Error::Gpu("cannot read VmHWM".into()))
    };
    let mut tiny = scene_file::load(&SceneSource::BuiltIn, &point_overrides(8, (w, h), shadows))?;
    renderer.render_releasing_meshes(&mut tiny)?;
    let frame = peak()?.saturating_sub(baseline);
    renderer.context().textures.clear();
    let baseline = reset_peak().ok_or_else(|| {
        crate::Error::Gpu("cannot read /proc/self/status to measure memory".into())
    })?;
    let mut scene = scene_file::load(
        &SceneSource::BuiltIn,
        &point_overrides(segments, (w, h), shadows),
    )?;
    let loaded = peak()?;
    // As `gonio render` without `--reference` does.
    renderer.render_releasing_meshes(&mut scene)?;
    let rendered = peak()?;
    println!(
        "{} {} {frame}",
        loaded.saturating_sub(baseline),
        rendered.saturating_sub(baseline)
    );
    Ok(())
}

/// Runs both sweeps on `renderer` (memory probes on `adapter`); `tick` is
/// called after each point.
pub fn run(
    renderer: &mut GpuRenderer,
    plan: &Plan,
    adapter: Option<&str>,
    mut tick: impl FnMut(),
) -> Result<Scale> {
    let mut scale = Scale::default();
    for &t in &plan.triangles {
        scale.triangles.push(point(
            renderer,
            (segments_for(t), false),
            plan.triangle_image,
            plan,
            adapter,
        )?);
        tick();
    }
    if let Some(&t) = plan.triangles.last() {
        scale.shadowed = Some(point(
            renderer,
            (segments_for(t), true),
            plan.triangle_image,
            plan,
            adapter,
        )?);
    }
    tick();
    for &size in &plan.resolutions {
        scale
            .pixels
            .push(point(renderer, (64, false), size, plan, adapter)?);
        tick();
    }
    Ok(scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_power_laws() {
        let linear = (1..5).map(|k| (10f64.powi(k), 3.0 * 10f64.powi(k)));
        assert!((slope(linear) - 1.0).abs() < 1e-12);
        let square = (1..5).map(|k| (k as f64, (k * k) as f64));
        assert!((slope(square) - 2.0).abs() < 1e-12);
        assert!(slope(std::iter::once((1.0, 1.0))).is_nan());
        let (a, b, r2) = linear_fit([(1.0, 5.0), (2.0, 7.0), (4.0, 11.0)].into_iter());
        assert!((a - 3.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12 && (r2 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn segments_give_about_the_asked_triangles() {
        for t in [10_000usize, 100_000, 1_000_000] {
            let s = segments_for(t);
            let mesh = crate::scene::primitives::uv_sphere(glam::DVec3::ZERO, 1.0, s, 0);
            let got = mesh.indices.len() as f64;
            assert!((got / t as f64 - 1.0).abs() < 0.05, "{t}: {got}");
        }
    }
}
