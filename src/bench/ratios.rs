//! The headline ratios, each measured in one run with its two sides
//! interleaved frame by frame (A, B, A, B, ...), so that a slow stretch of
//! a shared machine slows both sides alike. Each ratio is taken per round
//! (the two sides' frames of the same round, a few milliseconds apart) and
//! its median over the rounds is the reported value, with the quartiles
//! of the per-round ratios as its spread: a drift of the machine's load
//! over the run then cancels within each round, which a ratio of the two
//! sides' overall medians does not guarantee (the quick and full runs of
//! the same build gave 1.012 and 1.046 that way).

use super::floors;
use super::harness::{Harness, HarnessShader};
use super::measure::{self, Stats};
use crate::gpu::GpuRenderer;
use crate::scene::Scene;
use crate::scene::scene_file::{self, SceneSource};
use crate::{Error, Result};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// A measured ratio `numerator / denominator`, with its target.
#[derive(Clone, Debug)]
pub struct Ratio {
    pub name: String,
    pub numerator: String,
    pub denominator: String,
    pub num: Stats,
    pub den: Stats,
    /// The ratio of each interleaved round ([`per_round`]); `n = 0` where
    /// the sides are not paired round by round.
    pub rounds: Stats,
    /// The target: the ratio must be at most this.
    pub target: Option<f64>,
    /// What the reader needs to interpret it (why it misses, what else
    /// was checked).
    pub note: String,
}

impl Ratio {
    /// The median of the per-round ratios, or the ratio of the medians
    /// where the sides are not paired.
    pub fn value(&self) -> f64 {
        if self.rounds.n > 0 {
            self.rounds.median
        } else {
            self.num.median / self.den.median
        }
    }

    /// "pass", a miss in words ([`miss`]) or "" without a target.
    pub fn verdict(&self) -> String {
        match self.target {
            None => String::new(),
            Some(t) if self.value() <= t => "pass".into(),
            Some(t) => miss(self.value(), t),
        }
    }
}

/// A value over its target in words a reader takes in at once
/// (the former "miss by 749%" read badly): "miss: 12 % over the
/// target" up to twice the target (one decimal below 10 %), "miss: 8.5×
/// the target" beyond.
pub fn miss(value: f64, target: f64) -> String {
    let times = value / target;
    let pct = (times - 1.0) * 100.0;
    if times >= 2.0 {
        format!("miss: {times:.1}× the target")
    } else if pct < 10.0 {
        format!("miss: {pct:.1} % over the target")
    } else {
        format!("miss: {pct:.0} % over the target")
    }
}

/// How a time compares with another, `ratio = time / other`, in words
/// with no signed percentages ("-36% slower" read badly): "36 % faster",
/// "12 % slower", "2.4× as slow", "as fast" (within 0.5 %).
pub fn speed_words(ratio: f64) -> String {
    if ratio >= 2.0 {
        format!("{ratio:.1}× as slow")
    } else if ratio >= 1.005 {
        format!("{:.0} % slower", (ratio - 1.0) * 100.0)
    } else if ratio > 0.995 {
        "as fast".into()
    } else {
        format!("{:.0} % faster", (1.0 - ratio) * 100.0)
    }
}

/// Median and quartiles of `num[i] / den[i]`: the ratio of each
/// interleaved round (see the module docs).
pub fn per_round(num: &[f64], den: &[f64]) -> Stats {
    debug_assert_eq!(num.len(), den.len(), "sides of unequal rounds");
    let ratios: Vec<f64> = num.iter().zip(den).map(|(a, b)| a / b).collect();
    Stats::of(&ratios)
}

/// How much work a ratio measurement does.
#[derive(Clone, Copy, Debug)]
pub struct Effort {
    pub warmup: usize,
    pub repeats: usize,
    /// Rounds for the cheap 640x480 comparisons (specialization, uber):
    /// their sides differ by a few percent, which takes many frames to
    /// resolve on a shared machine.
    pub fine_repeats: usize,
    /// Image size of the "1080p" ratio (smaller for a smoke run).
    pub hd: (u32, u32),
    /// Size of the Lambert scene (the built-in's unless smoke).
    pub small: Option<(u32, u32)>,
    /// Process launches per side of the cold ratio.
    pub cold_runs: usize,
}

impl Effort {
    /// One frame of each at tiny sizes (`gonio bench --smoke`): checks
    /// that every ratio runs, measures nothing.
    pub const SMOKE: Effort = Effort {
        warmup: 0,
        repeats: 1,
        fine_repeats: 1,
        hd: (96, 54),
        small: Some((64, 48)),
        cold_runs: 1,
    };
}

fn builtin(overrides: &[String]) -> Result<Scene> {
    scene_file::load(&SceneSource::BuiltIn, overrides)
}

fn size_overrides(size: Option<(u32, u32)>) -> Vec<String> {
    size.map(|(w, h)| vec![format!("image.width={w}"), format!("image.height={h}")])
        .unwrap_or_default()
}

/// The order of `n` interleaved sides in round `i`: rotated by one each
/// round, so that every side is measured in every position equally often
/// (the pass right after a renderer frame, which also reads back and
/// unpacks on the CPU, runs measurably slower on a software rasterizer).
fn rotated(n: usize, i: usize) -> impl Iterator<Item = usize> {
    (0..n).map(move |k| (k + i) % n)
}

/// Two harness shaders on one scene, interleaved.
fn interleave_harness(
    renderer: &GpuRenderer,
    a: &Harness,
    b: &Harness,
    effort: Effort,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for i in 0..effort.warmup + effort.fine_repeats {
        let (mut x, mut y) = (0.0, 0.0);
        for side in rotated(2, i) {
            match side {
                0 => x = a.time_once(renderer.context())?.0,
                _ => y = b.time_once(renderer.context())?.0,
            }
        }
        if i >= effort.warmup {
            ta.push(x);
            tb.push(y);
        }
    }
    Ok((ta, tb))
}

/// Specialized vs hand-minimal, on the built-in scene with the sphere
/// made Lambertian (one unshadowed point light). Four sides interleaved:
/// the generated specialized shader and the hand-written one, both drawn
/// by the bench's pass (only the shader differs: the target), the
/// hand-written one with the generic light loop (to locate the gap), and
/// gonio's renderer itself.
pub fn specialization(renderer: &mut GpuRenderer, effort: Effort) -> Result<[Ratio; 3]> {
    let mut overrides = vec!["materials.ball.model=lambert".to_string()];
    overrides.extend(size_overrides(effort.small));
    let scene = builtin(&overrides)?;
    if !floors::is_lambert_one_point_light(&scene) {
        return Err(Error::Gpu(
            "the built-in scene is no longer Lambert with one point light; update the bench".into(),
        ));
    }
    let key = floors::specialized_key(&scene);
    let minimal = Harness::new(renderer, &scene, &floors::minimal_lambert(&scene))?;
    let looped = Harness::new(renderer, &scene, &floors::minimal_lambert_loop(&scene))?;
    let special = Harness::new(
        renderer,
        &scene,
        &HarnessShader::generated("specialized", key.clone()),
    )?;
    let (mut product, mut generated, mut hand, mut hand_loop) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..effort.warmup + effort.fine_repeats {
        let (mut timings, mut g, mut h, mut l) = (None, 0.0, 0.0, 0.0);
        for side in rotated(4, i) {
            match side {
                0 => timings = Some(renderer.render(&scene)?.1),
                1 => g = special.time_once(renderer.context())?.0,
                2 => h = minimal.time_once(renderer.context())?.0,
                _ => l = looped.time_once(renderer.context())?.0,
            }
        }
        let timings = timings.unwrap_or_default();
        if i >= effort.warmup {
            product.push(measure::render_pass_ms(&timings));
            generated.push(g);
            hand.push(h);
            hand_loop.push(l);
        }
    }
    // Same image? The hand-minimal shader must draw what the renderer does.
    let ours = renderer.render(&scene)?.0;
    let (diff, _) = measure::error(&minimal.frame(renderer.context())?, &ours);
    let (diff_special, _) = measure::error(&special.frame(renderer.context())?, &ours);
    let (diff_loop, _) = measure::error(&looped.frame(renderer.context())?, &ours);
    let shader_rounds = per_round(&generated, &hand);
    let loop_rounds = per_round(&hand_loop, &hand);
    let product_rounds = per_round(&product, &hand);
    let hand = Stats::of(&hand);
    let hand_loop = Stats::of(&hand_loop);
    let generated = Stats::of(&generated);
    let gap = shader_rounds.median - 1.0;
    let loop_gap = loop_rounds.median - 1.0;
    let shader = Ratio {
        name: "specialized scene / hand-minimal shader".into(),
        numerator: format!("generated shader ({})", key.describe()),
        denominator: "hand-written Lambert + one point light shader".into(),
        num: generated,
        den: hand,
        rounds: shader_rounds,
        target: Some(1.03),
        note: format!(
            "built-in scene with the sphere Lambertian, {}x{}; both drawn by the bench's pass over the renderer's vertex stream and buffers, so only the shader differs; images differ from the renderer's by {diff_special:.1e} (generated) and {diff:.1e} (hand-written) relative RMS. The generated shader is {}; the hand-written shader with the generated shader's generic light loop (every light read from the lights buffer in a loop over `light_count`, the inverse-square law with its optional range window and zero-distance guard) is {}{}",
            scene.width,
            scene.height,
            speed_words(1.0 + gap),
            speed_words(1.0 + loop_gap),
            if gap <= 0.03 {
                ": the generated shader has the scene's light count compiled in (`LoopCounts` in src/gpu/shader_gen/key.rs), so its loop unrolls like the hand-written one, and the range window and zero-distance guard only where a light has them (`LightsKey::range`, `guard`); the generic loop's cost is what that specialization saves"
            } else if loop_gap >= 0.5 * gap {
                ", so the light loop, not the BRDF code, is most of the gap: its light count, range window and zero-distance guard are specialized already (`LoopCounts`, `LightsKey::range`, `guard`), so look at what remains of the loop body"
            } else {
                ", so the light loop is not the main part of the gap"
            }
        ),
    };
    let whole = Ratio {
        name: "gonio's render pass (same scene) / hand-minimal shader".into(),
        numerator: "the renderer's own scene pass (GPU timestamps)".into(),
        denominator: "hand-written Lambert + one point light shader".into(),
        num: Stats::of(&product),
        den: hand,
        rounds: product_rounds,
        target: None,
        note: "the renderer's own pass: it allocates its colour and depth targets every frame, whose first touch falls inside the pass".into(),
    };
    let split = Ratio {
        name: "hand-minimal with the generic light loop / hand-minimal".into(),
        numerator: "hand-written Lambert, lights in a loop through `point_incidence`".into(),
        denominator: "hand-written Lambert + one point light shader".into(),
        num: hand_loop,
        den: hand,
        rounds: loop_rounds,
        target: None,
        note: format!(
            "how much of the specialization gap is the generic light loop alone (the rest: frame, f_r wrapper, dispatch); image differs from the renderer's by {diff_loop:.1e}"
        ),
    };
    Ok([shader, split, whole])
}

/// The uber shader (every variant and light kind compiled in) vs the
/// scene's specialized shader, both in the harness on the same scene.
/// Returns the ratio and the compile times (ms) of (specialized, uber).
pub fn uber_vs_specialized(
    renderer: &mut GpuRenderer,
    scene: &Scene,
    label: &str,
    effort: Effort,
) -> Result<(Ratio, f64, f64)> {
    let special_key = floors::specialized_key(scene);
    let uber_key = floors::uber_key(scene);
    let special = Harness::new(
        renderer,
        scene,
        &HarnessShader::generated("specialized", special_key.clone()),
    )?;
    let uber = Harness::new(
        renderer,
        scene,
        &HarnessShader::generated("uber", uber_key.clone()),
    )?;
    let (uber_ms, special_ms) = interleave_harness(renderer, &uber, &special, effort)?;
    let (diff, _) = measure::error(
        &uber.frame(renderer.context())?,
        &special.frame(renderer.context())?,
    );
    Ok((
        Ratio {
            name: format!("uber / specialized shader ({label})"),
            numerator: format!(
                "uber shader: {} BRDF variants, {} light kinds, run-time switch",
                uber_key.variants.len(),
                uber_key.lights.kinds.len()
            ),
            denominator: format!("specialized: {}", special_key.describe()),
            num: Stats::of(&uber_ms),
            den: Stats::of(&special_ms),
            rounds: per_round(&uber_ms, &special_ms),
            target: None,
            note: format!(
                "scene pass only, no shadow code in either; the images differ by {diff:.1e} relative RMS{}",
                if diff > 1e-3 {
                    " — NOT the same picture: the uber shader is miscompiled on this driver, its time means nothing"
                } else {
                    " (same picture)"
                }
            ),
        },
        special.compile_ms,
        uber.compile_ms,
    ))
}

/// The built-in scene at `hd` with a Cook-Torrance gold sphere (exact
/// conductor Fresnel) and four shadow-casting point lights.
pub fn ct_four_shadowed(hd: (u32, u32)) -> Result<Scene> {
    ct_four_shadowed_with(hd, &[])
}

/// [`ct_four_shadowed`] with `extra` overrides.
fn ct_four_shadowed_with(hd: (u32, u32), extra: &[&str]) -> Result<Scene> {
    let lights: Vec<String> = [
        [3.0, 5.0, 3.0],
        [-3.0, 5.0, 3.0],
        [3.0, 4.0, -3.0],
        [-3.0, 4.0, -3.0],
    ]
    .iter()
    .map(|p| {
        format!(
            "{{kind=\"point\", position=[{}, {}, {}], intensity=[20.0, 20.0, 20.0], shadows=true}}",
            p[0], p[1], p[2]
        )
    })
    .collect();
    let mut overrides: Vec<String> = [
        "materials.ball.model=cook-torrance",
        "materials.ball.preset=gold",
        "materials.ball.fresnel=conductor",
        "materials.ball.distribution=beckmann",
        "materials.ball.roughness=0.25",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    overrides.push(format!("lights=[{}]", lights.join(", ")));
    overrides.extend(size_overrides(Some(hd)));
    overrides.extend(extra.iter().map(|s| s.to_string()));
    builtin(&overrides)
}

/// The sides of the shadowed ratio: how the shadow maps are made.
#[derive(Clone, Copy, Debug, PartialEq)]
enum ShadowSide {
    /// The renderer's default: caster culling per layer, fixed sides.
    Culled,
    /// Every caster drawn into every layer (gonio before caster culling).
    Unculled,
    /// Caster culling and sides fitted to the screen at one texel per
    /// pixel (`shadows.resolution = "fit"`).
    Fitted,
    /// The same at half a texel per pixel (`shadows.texels_per_pixel =
    /// 0.5`): the bench's Pareto front puts it at about a third of the
    /// fixed maps' cost for about twice their error.
    FittedHalf,
    /// The default, on textures made for this render: the device's
    /// texture pool emptied first, as in a process's first render
    /// (src/gpu/texture_pool.rs), so the passes touch fresh memory.
    FreshTextures,
}

/// The 4-shadowed-light ratio whose half is the target: 29.4, measured
/// before caster culling, empty-face skipping and fitted sides.
const HEAVY_BEFORE: f64 = 29.4;

/// Cook-Torrance + exact Fresnel + four shadowed lights vs the unlit
/// floor on the same geometry, five sides interleaved: the default
/// renderer (caster culling, fixed 2048² faces, the textures of the
/// previous render reused), the same without caster culling (the
/// renderer before it), the same with sides fitted to the screen (at one
/// and at half a texel per pixel), the default on fresh textures (a
/// process's first render), and the unlit pass. Returns the ratios of
/// whole frames (shadow passes included) of the five, and that of the
/// scene pass alone; the notes give each frame's error against the
/// ray-traced truth.
pub fn heavy_vs_unlit(renderer: &mut GpuRenderer, effort: Effort) -> Result<Vec<Ratio>> {
    let scene = ct_four_shadowed(effort.hd)?;
    let fitted_scene = ct_four_shadowed_with(
        effort.hd,
        &["shadows.resolution=fit", "shadows.texels_per_pixel=1"],
    )?;
    let half_scene = ct_four_shadowed_with(
        effort.hd,
        &["shadows.resolution=fit", "shadows.texels_per_pixel=0.5"],
    )?;
    let unlit = Harness::new(renderer, &scene, &floors::unlit(&scene))?;
    let sides = [
        ShadowSide::Culled,
        ShadowSide::Unculled,
        ShadowSide::Fitted,
        ShadowSide::FittedHalf,
        ShadowSide::FreshTextures,
    ];
    let mut frames: [Vec<f64>; 5] = Default::default();
    let mut passes: [Vec<f64>; 5] = Default::default();
    let mut floor = Vec::new();
    let mut layers: [String; 5] = Default::default();
    let mut last: [Option<crate::frame::Frame>; 5] = Default::default();
    for i in 0..effort.warmup + effort.repeats {
        for side in rotated(sides.len() + 1, i) {
            let Some(&which) = sides.get(side) else {
                let ms = unlit.time_once(renderer.context())?.0;
                if i >= effort.warmup {
                    floor.push(ms);
                }
                continue;
            };
            renderer.cull_shadow_casters = which != ShadowSide::Unculled;
            let drawn = match which {
                ShadowSide::Fitted => &fitted_scene,
                ShadowSide::FittedHalf => &half_scene,
                ShadowSide::Culled | ShadowSide::Unculled | ShadowSide::FreshTextures => &scene,
            };
            if which == ShadowSide::FreshTextures {
                renderer.context().textures.clear();
            } else {
                // Once untimed first: timed on its own textures whatever
                // the side before it drew (a fitted side may have another
                // shape than the fixed maps).
                renderer.render(drawn)?;
            }
            let (frame, timings) = renderer.render(drawn)?;
            renderer.cull_shadow_casters = true;
            if i >= effort.warmup {
                frames[side].push(measure::frame_ms(&timings).0);
                passes[side].push(measure::render_pass_ms(&timings));
            }
            if let Some((name, ..)) = timings
                .entries
                .iter()
                .find(|(n, ..)| n.starts_with("shadow passes"))
            {
                layers[side] = name.clone();
            }
            last[side] = Some(frame);
        }
    }
    // The ray-traced truth of the same scene (the bench's truth: the CPU
    // reference, f64, one shadow ray per light and pixel).
    let truth = measure::truth(&scene, 1);
    let errors: Vec<f64> = last
        .iter()
        .map(|f| f.as_ref().map_or(f64::NAN, |f| measure::error(f, &truth).0))
        .collect();
    let sides_of = |plan: &crate::gpu::shadows::ShadowPlan| {
        let mut sides: Vec<u32> = plan
            .lights
            .iter()
            .flatten()
            .map(|s| s.settings.map_size)
            .collect();
        sides.dedup();
        sides
            .iter()
            .map(|s| format!("{s}²"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let fitted_sides = sides_of(&crate::gpu::shadows::ShadowPlan::new(&fitted_scene));
    let half_sides = sides_of(&crate::gpu::shadows::ShadowPlan::new(&half_scene));
    let (w, h) = effort.hd;
    let floor_ms = floor;
    let floor = Stats::of(&floor_ms);
    let shadow_ms: Vec<f64> = frames[0]
        .iter()
        .zip(&passes[0])
        .map(|(f, p)| f - p)
        .collect();
    let shadow = Stats::of(&shadow_ms);
    let pass_stats = Stats::of(&passes[0]);
    let ratio = |side: usize, name: String, target: Option<f64>, note: String| Ratio {
        name,
        numerator: format!("whole frame: {} + scene pass", layers[side]),
        denominator: "unlit pass over the same vertex stream".into(),
        num: Stats::of(&frames[side]),
        den: floor,
        rounds: per_round(&frames[side], &floor_ms),
        target,
        note,
    };
    let unculled = Stats::of(&frames[1]).median;
    let frame = ratio(
        0,
        format!("Cook-Torrance, exact Fresnel, 4 shadowed lights / unlit floor, {w}x{h}"),
        Some(2.5),
        format!(
            "four point lights cast shadows through cube maps (6 layers of 2048² each, 3x3 PCF); each face draws only the casters whose bounding boxes reach its frustum ({}): the shadow passes take {:.0} ms ({:.1}× the unlit pass) of the frame; the scene pass is the other {:.0} ms ({:.1}×). Like the unlit pass, each side is timed on textures it has drawn into before (rendered once untimed first; maps and targets are cleared by the passes); a process's first render, on fresh textures, is the row \"on fresh textures\" below. Error against the ray-traced shadows (relative RMS of the radiance): {:.4}. Without caster culling the frame takes {:.0} ms (ratio {:.2}, error {:.4}: the same image), measured interleaved; with sides fitted to the screen ({fitted_sides}) see the row below. A software rasterizer shades on the CPU, so a fragment's cost is its arithmetic: 4 lights × (Beckmann D, Smith G, complex-index Fresnel per channel, 9 shadow-map taps) against one constant store. The 2.5× target assumes a GPU, where rasterization and bandwidth, not ALU work, set the floor",
            layers[0],
            shadow.median,
            shadow.median / floor.median,
            pass_stats.median,
            pass_stats.median / floor.median,
            errors[0],
            unculled,
            unculled / floor.median,
            errors[1],
        ),
    );
    let before = ratio(
        1,
        format!("same, every caster drawn into every face (before caster culling), {w}x{h}"),
        None,
        format!("error against the ray-traced shadows {:.4}", errors[1]),
    );
    let fitted = ratio(
        2,
        format!("same, shadow_resolution = \"fit\" (one texel per pixel, at most 2048²), {w}x{h}"),
        None,
        format!(
            "each cube's side fitted to the screen footprint of the receivers its light reaches (src/gpu/shadow_fit.rs): {fitted_sides}; error against the ray-traced shadows {:.4} (fixed 2048²: {:.4})",
            errors[2], errors[0]
        ),
    );
    let pass = Ratio {
        name: format!("same, scene pass only (shadow lookups included), {w}x{h}"),
        numerator: "scene pass".into(),
        denominator: "unlit pass over the same vertex stream".into(),
        num: pass_stats,
        den: floor,
        rounds: per_round(&passes[0], &floor_ms),
        target: None,
        note: String::new(),
    };
    let half = ratio(
        3,
        format!("same, shadow_resolution = \"fit\", texels_per_pixel = 0.5, {w}x{h}"),
        Some(HEAVY_BEFORE / 2.0),
        format!(
            "the shadow target: half the {HEAVY_BEFORE} this ratio was before caster culling, empty faces skipped and fitted sides, at the error it reports. Sides fitted at half a texel per pixel: {half_sides}; error against the ray-traced shadows {:.4} (fixed 2048²: {:.4}); the fixed 2048² maps' frame is the first row",
            errors[3], errors[0]
        ),
    );
    let fresh_shadow: Vec<f64> = frames[4]
        .iter()
        .zip(&passes[4])
        .map(|(f, p)| f - p)
        .collect();
    let fresh = ratio(
        4,
        format!("same as the first row, on fresh textures (a process's first render), {w}x{h}"),
        None,
        format!(
            "the rows above reuse the previous render's shadow maps and targets (src/gpu/texture_pool.rs: a renderer that draws again keeps them); here the pool is emptied before each render, so the shadow passes' clears and the scene pass touch memory the kernel has not yet handed out, a 4 KiB page at a time, as `gonio render` does once per process: the shadow passes take {:.0} ms here against {:.0} ms on reused maps, the scene pass {:.0} ms against {:.0} ms. Error against the ray-traced shadows {:.4} (the same image)",
            Stats::of(&fresh_shadow).median,
            shadow.median,
            Stats::of(&passes[4]).median,
            pass_stats.median,
            errors[4],
        ),
    );
    Ok(vec![frame, before, fitted, half, fresh, pass])
}

/// Cold `gonio render` of the built-in scene to PNG vs the minimal
/// triangle-to-PNG program, both as fresh processes of this binary
/// (wall time from spawn to exit).
pub fn cold(dir: &Path, effort: Effort, adapter: Option<&str>) -> Result<Ratio> {
    let exe = std::env::current_exe()
        .map_err(|e| Error::Gpu(format!("cannot find the gonio executable: {e}")))?;
    let run = |args: &[&str]| -> Result<f64> {
        let mut command = Command::new(&exe);
        command.args(args);
        if let Some(a) = adapter {
            command.args(["--adapter", a]);
        }
        let start = Instant::now();
        let out = command
            .output()
            .map_err(|e| Error::Gpu(format!("cannot run {}: {e}", exe.display())))?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        if !out.status.success() {
            return Err(Error::Gpu(format!(
                "`gonio {}` failed: {}",
                args.join(" "),
                String::from_utf8_lossy(&out.stderr).trim()
            )));
        }
        Ok(ms)
    };
    let render_png = dir.join("cold-render.png");
    let triangle_png = dir.join("cold-triangle.png");
    let render_png = render_png.to_string_lossy().into_owned();
    let triangle_png = triangle_png.to_string_lossy().into_owned();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _ in 0..effort.cold_runs.max(1) {
        a.push(run(&["render", "-o", &render_png])?);
        b.push(run(&["bench", "--floor-triangle-png", &triangle_png])?);
    }
    Ok(Ratio {
        name: "cold `gonio render` (default scene) / minimal triangle-to-PNG".into(),
        numerator: "`gonio render -o out.png`, fresh process, wall time".into(),
        denominator: "one triangle to PNG (device, pipeline, draw, readback, encode, write), fresh process of the same binary".into(),
        num: Stats::of(&a),
        den: Stats::of(&b),
        rounds: per_round(&a, &b),
        // 1.5 with margin (it was 1.49 before the one
        // switching pipeline of a one-frame render).
        target: Some(1.3),
        note: "both pay process start, Vulkan instance and lavapipe device creation; the render adds scene building, shader generation and compilation, and 640x480 shading".into(),
    })
}

#[cfg(test)]
mod wording_tests {
    use super::{miss, speed_words};

    #[test]
    fn misses_read_as_multiples_or_percentages_over() {
        assert_eq!(miss(29.402, 2.5), "miss: 11.8× the target");
        assert_eq!(miss(1.100, 1.03), "miss: 6.8 % over the target");
        assert_eq!(miss(1.8, 1.5), "miss: 20 % over the target");
    }

    #[test]
    fn speeds_have_no_signed_percentages() {
        assert_eq!(speed_words(0.64), "36 % faster");
        assert_eq!(speed_words(1.12), "12 % slower");
        assert_eq!(speed_words(2.4), "2.4× as slow");
        assert_eq!(speed_words(1.001), "as fast");
    }
}

#[cfg(test)]
mod per_round_tests {
    use super::{Ratio, Stats, per_round};

    /// A load drift that moves both sides of each round alike leaves the
    /// per-round ratio alone, while the ratio of the sides' medians picks
    /// up whichever round the medians fall in.
    #[test]
    fn the_value_is_the_median_of_the_rounds_ratios() {
        let (num, den) = ([1.0, 2.2, 3.0], [1.0, 2.0, 3.3]);
        let rounds = per_round(&num, &den);
        assert_eq!((rounds.median, rounds.n), (1.0, 3));
        let ratio = Ratio {
            name: String::new(),
            numerator: String::new(),
            denominator: String::new(),
            num: Stats::of(&num),
            den: Stats::of(&den),
            rounds,
            target: Some(1.03),
            note: String::new(),
        };
        assert_eq!(ratio.value(), 1.0);
        assert_eq!(ratio.verdict(), "pass");
        let unpaired = Ratio {
            rounds: Stats::default(),
            ..ratio
        };
        assert!((unpaired.value() - 1.1).abs() < 1e-12);
    }
}
