//! The Markdown report and the CSV files.
//!
//! `results.csv` has one row per measured configuration and is what
//! `gonio render --max-error` reads: `scene, knob, value, overrides`
//! (every `--set` of the configuration, base included, separated by
//! `;`), the time (ms: median, first and third quartile, and the median
//! over the unlit floor) and the errors. Fields are quoted where they
//! hold commas or quotes (RFC 4180).

use super::BenchReport;
use super::ratios::{Ratio, miss};
use crate::gpu::timing::Clock;
use crate::output::plot::number;
use std::fmt::Write;

/// The header of `results.csv`.
pub const RESULTS_HEADER: [&str; 12] = [
    "scene",
    "knob",
    "value",
    "overrides",
    "time_ms",
    "time_q1_ms",
    "time_q3_ms",
    "time_over_unlit",
    "rel_rms_error",
    "max_rel_error",
    "on_front",
    "clock",
];

/// RFC 4180 quoting where needed.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Splits one CSV record (no embedded newlines) into fields.
pub fn parse_csv_line(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', true) => quoted = false,
            ('"', false) if field.is_empty() => quoted = true,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

fn clock_name(c: Clock) -> &'static str {
    match c {
        Clock::GpuTimestamp => "gpu-timestamp",
        Clock::Wall => "wall",
    }
}

/// `results.csv`.
pub fn results_csv(r: &BenchReport) -> String {
    let mut out = RESULTS_HEADER.join(",");
    out.push('\n');
    for row in &r.rows {
        let overrides: Vec<String> = r
            .base_overrides
            .iter()
            .chain(&row.config.overrides)
            .cloned()
            .collect();
        let fields = [
            csv_field(&r.scene),
            csv_field(&row.config.knob),
            csv_field(&row.config.value),
            csv_field(&overrides.join(";")),
            format!("{:.6}", row.time.median),
            format!("{:.6}", row.time.q1),
            format!("{:.6}", row.time.q3),
            format!("{:.6}", row.time.median / r.unlit.median),
            format!("{:.6e}", row.error),
            format!("{:.6e}", row.max_rel),
            row.on_front.to_string(),
            clock_name(r.clock).into(),
        ];
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    out
}

/// `scale.csv`: both sweeps.
pub fn scale_csv(r: &BenchReport) -> String {
    let mut out = String::from(
        "sweep,triangles,width,height,time_ms,time_q1_ms,time_q3_ms,mesh_bytes,scene_bytes,peak_rss_growth_bytes,load_rss_growth_bytes,frame_rss_growth_bytes\n",
    );
    if let Some(s) = &r.scale {
        let shadowed: Vec<_> = s.shadowed.iter().cloned().collect();
        for (name, points) in [
            ("triangles", &s.triangles),
            ("triangles-shadowed", &shadowed),
            ("pixels", &s.pixels),
        ] {
            for p in points {
                let bytes = |b: Option<u64>| b.map(|b| b.to_string()).unwrap_or_default();
                let _ = writeln!(
                    out,
                    "{name},{},{},{},{:.6},{:.6},{:.6},{},{},{},{},{}",
                    p.triangles,
                    p.width,
                    p.height,
                    p.time.median,
                    p.time.q1,
                    p.time.q3,
                    p.mesh_bytes,
                    p.scene_bytes,
                    bytes(p.peak_rss_bytes),
                    bytes(p.load_rss_bytes),
                    bytes(p.frame_rss_bytes),
                );
            }
        }
    }
    out
}

fn ms(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

/// Where the peak memory of the largest mesh goes, from the measured
/// columns.
fn memory_note(s: &super::scale::Scale) -> String {
    let Some(p) = s.triangles.last() else {
        return String::new();
    };
    let (Some(load), Some(peak), Some(frame)) =
        (p.load_rss_bytes, p.peak_rss_bytes, p.frame_rss_bytes)
    else {
        return "Memory: not measured (no /proc on this system).".into();
    };
    let mib = |b: u64| b as f64 / 1048576.0;
    let mut note = format!(
        "Memory at {} triangles: loading peaks at {:.1} MiB for a {:.1} MiB `f64` scene (72 bytes per vertex for position, normal and tangent, 12 per triangle, as counted here; the sphere's UVs come on top). Rendering it as `gonio render` without `--reference` does (GPU only) brings the peak to {:.1} MiB, of which the frame's fixed cost with an 8-segment sphere is {:.1} MiB: the {:.1} MiB `f32` vertex and index data is written straight from the meshes into its buffers (host memory on lavapipe) through 1 MiB chunks and a 4 MiB staging window (src/gpu/upload.rs), indices first, and each `f64` array is freed as soon as it is written (tangents and UVs the stream does not carry before the upload starts), so the `f64` scene and the buffers are never whole in memory at once. Above 20,000 triangles the scene pass and the shadow passes are drawn in parts, each submitted and finished before the next is recorded (src/gpu/scene_parts.rs): lavapipe bins a pass's triangles into scenes of up to 36 MiB and holds two or more of them for one huge draw (about 70 MiB at 10⁶ triangles drawn whole), in parts it holds one small one. What the peak holds beyond the fixed cost and the stream: {:.1} MiB (docs/bench/memory.md). A run that also renders the reference keeps the `f64` meshes, as do the viewer and the bench's timed renders.",
        p.triangles,
        mib(load),
        mib(p.scene_bytes),
        mib(peak),
        mib(frame),
        mib(p.mesh_bytes),
        mib(peak.saturating_sub(frame + p.mesh_bytes)),
    );
    if let Some(sh) = &s.shadowed
        && let (Some(peak), Some(frame)) = (sh.peak_rss_bytes, sh.frame_rss_bytes)
    {
        note.push_str(&format!(
            " With the point light casting shadows the peak is {:.1} MiB, of which {:.1} MiB is the frame's fixed cost (mostly the cube shadow map, whatever the mesh); the stream is the same indexed one (per-vertex shadow coordinates, which de-index the stream to three vertices per triangle, are for a single orthographic map only: a directional light).",
            mib(peak),
            mib(frame)
        ));
    }
    note
}

/// A fitted slope, or "–" where there was nothing to fit (all zero).
fn slope_text(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.2}")
    } else {
        "–".into()
    }
}

/// One row of the ratio table.
pub fn ratio_row(r: &Ratio) -> String {
    format!(
        "| {} | **{:.3}**{} | {} | {} | {} ms [{}–{}], n = {} | {} ms [{}–{}] |",
        r.name,
        r.value(),
        if r.rounds.n > 0 {
            format!(" [{:.3}–{:.3}]", r.rounds.q1, r.rounds.q3)
        } else {
            String::new()
        },
        r.target
            .map(|t| format!("≤ {t}"))
            .unwrap_or_else(|| "–".into()),
        match r.verdict().as_str() {
            "" => "–".to_string(),
            v => v.to_string(),
        },
        ms(r.num.median),
        ms(r.num.q1),
        ms(r.num.q3),
        r.num.n,
        ms(r.den.median),
        ms(r.den.q1),
        ms(r.den.q3),
    )
}

/// `report.md`.
pub fn markdown(r: &BenchReport) -> String {
    let mut o = String::new();
    let clock = match r.clock {
        Clock::GpuTimestamp => "GPU timestamp queries around the passes",
        Clock::Wall => "wall time of submit-and-wait (the adapter has no timestamp queries)",
    };
    let _ = writeln!(o, "# gonio bench: the speed/accuracy trade, measured\n");
    if r.smoke {
        let _ = writeln!(
            o,
            "> **Smoke run** (`--smoke`): one iteration at tiny sizes. It checks that every figure is produced; the numbers mean nothing.\n"
        );
    }
    let _ = writeln!(
        o,
        "Scene: **{}** ({}x{} px, {} triangles). Adapter: {}. Time: {clock}; {} timed frames per configuration after {} warm-up frames, reported as median [first–third quartile]. Whole run: {:.0} s.\n",
        r.scene, r.width, r.height, r.triangles, r.adapter, r.repeats, r.warmup, r.elapsed_s
    );
    if !r.base_overrides.is_empty() {
        let _ = writeln!(o, "Base scene overrides (`--set`):\n");
        for s in &r.base_overrides {
            let _ = writeln!(o, "- `{s}`");
        }
        o.push('\n');
    }
    let _ = writeln!(o, "## What \"error\" means\n");
    let _ = writeln!(
        o,
        "The error of a configuration is the relative RMS difference of its GPU image from the **truth**, `sqrt(Σ (L − L_truth)² / Σ L_truth²)` over the pixels and RGB channels covered in both (linear radiance, no tone mapping). The truth is {} (computed once, {:.1} s): the most exact configuration gonio has (exact Fresnel where the scene asks for it, shading at every pixel, exact visibility instead of shadow maps, many area-light samples). Each configuration changes one knob of the base scene; a configuration at another resolution is box-filtered (finer) or replicated (coarser) onto the truth's pixel grid first. The base configuration's own error is the GPU's remaining difference (area-light samples, shadow-map resolution, f32 arithmetic).\n",
        r.truth,
        r.truth_ms / 1e3
    );

    let _ = writeln!(o, "## Floors\n");
    let _ = writeln!(
        o,
        "Absolute times on a shared machine with a software rasterizer are noise; the figures below are ratios to floors measured in the same run.\n"
    );
    let _ = writeln!(
        o,
        "- **Unlit pass** over the base scene's vertex stream ({}x{}): {} ms [{}–{}]. The `× unlit` column divides by it.",
        r.width,
        r.height,
        ms(r.unlit.median),
        ms(r.unlit.q1),
        ms(r.unlit.q3)
    );
    if let Some(cold) = r.ratios.iter().find(|x| x.name.starts_with("cold")) {
        let _ = writeln!(
            o,
            "- **Minimal triangle-to-PNG program** (fresh process): {} ms [{}–{}].",
            ms(cold.den.median),
            ms(cold.den.q1),
            ms(cold.den.q3)
        );
    }
    let _ = writeln!(
        o,
        "- **Hand-minimal shader** (Lambert + one point light, written by hand): see the first target.\n"
    );

    let _ = writeln!(o, "## Targets\n");
    let _ = writeln!(
        o,
        "Each ratio's two sides are measured in the same run, interleaved frame by frame in rotating order; the value is the median [quartiles] of the ratio taken in each round (the two sides' frames of one round), the sides' times medians [quartiles] over n frames per side.\n\n| ratio | value | target | verdict | numerator | denominator |\n| --- | --- | --- | --- | --- | --- |"
    );
    for x in &r.ratios {
        let _ = writeln!(o, "{}", ratio_row(x));
    }
    if let Some(worst) = r.auto.iter().map(|a| a.ratio).reduce(f64::max) {
        let verdict = if worst <= 1.1 {
            "pass".to_string()
        } else {
            miss(worst, 1.1)
        };
        let _ = writeln!(
            o,
            "| `--max-error` pick / cheapest within the same error (worst over {} budgets) | **{worst:.3}** | ≤ 1.1 | {verdict} | see below | |",
            r.auto.len()
        );
    }
    if let Some(s) = &r.scale {
        let (ts, ps) = (s.triangle_slope(), s.pixel_slope());
        let _ = writeln!(
            o,
            "| growth of time with triangles (log-log slope) | **{ts:.2}** | ≤ 1 (linear) | {} | | |",
            if ts <= 1.1 { "pass" } else { "miss" }
        );
        let _ = writeln!(
            o,
            "| growth of time with pixels (log-log slope) | **{ps:.2}** | ≤ 1 (linear) | {} | | |",
            if ps <= 1.1 { "pass" } else { "miss" }
        );
        for p in s.triangles.last().into_iter().chain(&s.shadowed) {
            let (Some(peak), Some(mesh_peak)) = (p.peak_rss_bytes, p.mesh_peak_bytes()) else {
                continue;
            };
            // The verdict divides the mesh's share of the peak (less the
            // frame's fixed cost: targets, readback, shadow maps) by the
            // mesh as loaded (what the user asked to draw); the whole
            // peak and the GPU stream are shown too.
            let light = if p.shadows {
                ", point light with shadows"
            } else {
                ""
            };
            let mib = |b: u64| b as f64 / 1048576.0;
            let m = mesh_peak as f64 / p.scene_bytes as f64;
            let _ = writeln!(
                o,
                "| peak memory growth / mesh data as loaded (f64), {} triangles{light}, less the frame's fixed cost | **{m:.2}** | ≤ 1.5 | {} | {:.1} MiB | {:.1} MiB |",
                p.triangles,
                if m <= 1.5 {
                    "pass".to_string()
                } else {
                    miss(m, 1.5)
                },
                mib(mesh_peak),
                mib(p.scene_bytes)
            );
            let whole = peak as f64 / p.scene_bytes as f64;
            let _ = writeln!(
                o,
                "| whole peak memory growth / mesh data as loaded (f64), {} triangles{light} | **{whole:.2}** | – | – | {:.1} MiB | {:.1} MiB |",
                p.triangles,
                mib(peak),
                mib(p.scene_bytes)
            );
            let g = mesh_peak as f64 / p.mesh_bytes as f64;
            let _ = writeln!(
                o,
                "| peak memory growth / GPU mesh data (f32 stream), {} triangles{light}, less the frame's fixed cost | **{g:.2}** | – | – | {:.1} MiB | {:.1} MiB |",
                p.triangles,
                mib(mesh_peak),
                mib(p.mesh_bytes)
            );
        }
    }
    o.push('\n');
    for x in r.ratios.iter().filter(|x| !x.note.is_empty()) {
        let _ = writeln!(o, "- *{}*: {}", x.name, x.note);
    }
    o.push('\n');

    let _ = writeln!(o, "## Uber shader vs specialized\n");
    let _ = writeln!(
        o,
        "The uber shader compiles every reflectance model, every Cook-Torrance distribution, geometry term, Fresnel term and denominator (each once, not their 192 combinations: on Mesa 22.3 lavapipe a shader with more than about 75 variants compiles but draws without direct light) and every light kind into one shader and dispatches on the material's model and term codes (`FROM_MATERIAL`, shaders/brdf/variant.wgsl) and the light's kind at run time, as a renderer without specialization would. Both are drawn by the bench's own pass over the same buffers; ratios are in the table above.\n"
    );
    let _ = writeln!(
        o,
        "| pipeline | compile (shader module + pipeline + first draw) |\n| --- | --- |"
    );
    for (label, t) in &r.compile {
        let _ = writeln!(o, "| {label} | {} ms |", ms(*t));
    }
    o.push('\n');

    let _ = writeln!(o, "## Configurations\n");
    let _ = writeln!(
        o,
        "One knob changed from the base at a time. ★ marks the Pareto front (no other configuration is both at most as slow and at most as wrong). Plot: `pareto.svg` / `pareto.png`; data: `results.csv`.\n"
    );
    let _ = writeln!(
        o,
        "| knob | setting | GPU time [ms] | × unlit | error (rel. RMS) | max rel. error | front |\n| --- | --- | --- | --- | --- | --- | --- |"
    );
    for row in &r.rows {
        let _ = writeln!(
            o,
            "| {} | {} | {} [{}–{}] | {:.2} | {} | {} | {} |",
            row.config.knob,
            row.config.value,
            ms(row.time.median),
            ms(row.time.q1),
            ms(row.time.q3),
            row.time.median / r.unlit.median,
            number(row.error),
            number(row.max_rel),
            if row.on_front { "★" } else { "" }
        );
    }
    o.push('\n');
    layers(&mut o, r);
    if !r.not_measured.is_empty() {
        let _ = writeln!(o, "Not measured:\n");
        for s in &r.not_measured {
            let _ = writeln!(o, "- **{}**: {}", s.knob, s.reason);
        }
        o.push('\n');
    }

    let _ = writeln!(o, "## The Pareto front\n");
    let mut front: Vec<_> = r.rows.iter().filter(|x| x.on_front).collect();
    front.sort_by(|a, b| a.time.median.total_cmp(&b.time.median));
    for row in &front {
        let _ = writeln!(
            o,
            "- `{}`: {:.2} × unlit, error {}",
            row.config.label(),
            row.time.median / r.unlit.median,
            number(row.error)
        );
    }
    o.push('\n');

    let _ = writeln!(o, "## Auto quality: `--max-error`\n");
    let _ = writeln!(
        o,
        "`gonio render --max-error E` renders the cheapest configuration of `results.csv` whose error is at most E (always a point of the front). To see how close that lands to the best choice, every configuration was timed in two passes: the pick is made on the first pass and scored on the second, against the configuration that is cheapest within E on the second pass. A ratio above 1 means timing noise made the first pass pick a configuration that the second pass finds slower than another within E.\n"
    );
    let _ = writeln!(
        o,
        "| E | pick (pass 1) | cheapest within E (pass 2) | pass-2 time ratio | quartiles overlap |\n| --- | --- | --- | --- | --- |"
    );
    for a in &r.auto {
        let _ = writeln!(
            o,
            "| {} | `{}` | `{}` | {:.3} | {} |",
            number(a.max_error),
            r.rows[a.pick].config.label(),
            r.rows[a.best].config.label(),
            a.ratio,
            if a.pick == a.best {
                "–"
            } else if a.overlap {
                "yes"
            } else {
                "no"
            }
        );
    }
    o.push('\n');

    let misses: Vec<_> = r.auto.iter().filter(|a| a.ratio > 1.1).collect();
    if !misses.is_empty() {
        let _ = writeln!(
            o,
            "{} of {} budgets land more than 10% above the best choice; in {} of them the two configurations' second-pass quartiles overlap, i.e. their times are within this machine's noise of each other and the first pass could not tell which is cheaper. More repeats (`--repeats`) narrow that band; a quiet machine removes it.\n",
            misses.len(),
            r.auto.len(),
            misses.iter().filter(|a| a.overlap).count()
        );
    }

    if let Some(s) = &r.scale {
        let _ = writeln!(o, "## Scale\n");
        let _ = writeln!(
            o,
            "Scene pass time (GPU) of the built-in scene with the sphere tessellated finer (drawn at {}), and at growing resolution (8.5k triangles). Growth rate: least-squares slope of log time against log size (1 = linear). Memory: the vertex + index bytes uploaded, and the peak resident memory (VmHWM) of loading and rendering the point once (GPU only, as `gonio render` does) in a fresh process that has only opened the device and compiled the pipeline on a tiny mesh, over its resident memory before loading; lavapipe's buffers live in host memory, so they are part of it. The frame's fixed cost is the same growth for rendering the scene with an 8-segment sphere, measured just before; the last row has the light casting shadows.\n",
            s.triangles
                .first()
                .map(|p| format!("{}x{}", p.width, p.height))
                .unwrap_or_default()
        );
        let _ = writeln!(
            o,
            "| triangles | time [ms] | mesh data (GPU) [MiB] | scene (f64) [MiB] | peak memory growth [MiB] | of which loading [MiB] | frame's fixed cost [MiB] | (peak − fixed) / scene | (peak − fixed) / GPU mesh |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
        );
        for p in s.triangles.iter().chain(&s.shadowed) {
            let peak = p.peak_rss_bytes.map(|b| b as f64 / 1048576.0);
            let _ = writeln!(
                o,
                "| {}{} | {} [{}–{}] | {:.1} | {:.1} | {} | {} | {} | {} | {} |",
                p.triangles,
                if p.shadows { " (shadowed light)" } else { "" },
                ms(p.time.median),
                ms(p.time.q1),
                ms(p.time.q3),
                p.mesh_bytes as f64 / 1048576.0,
                p.scene_bytes as f64 / 1048576.0,
                peak.map(|m| format!("{m:.1}"))
                    .unwrap_or_else(|| "–".into()),
                p.load_rss_bytes
                    .map(|b| format!("{:.1}", b as f64 / 1048576.0))
                    .unwrap_or_else(|| "–".into()),
                p.frame_rss_bytes
                    .map(|b| format!("{:.1}", b as f64 / 1048576.0))
                    .unwrap_or_else(|| "–".into()),
                p.mesh_peak_bytes()
                    .map(|b| format!("{:.2}", b as f64 / p.scene_bytes as f64))
                    .unwrap_or_else(|| "–".into()),
                p.mesh_peak_bytes()
                    .map(|b| format!("{:.2}", b as f64 / p.mesh_bytes as f64))
                    .unwrap_or_else(|| "–".into()),
            );
        }
        let (a, b, r2) = s.triangle_fit();
        let _ = writeln!(
            o,
            "\nTime grows as triangles^**{}** (log-log slope); as a line, {} ms + {} ms per 10⁶ triangles (R² = {}): linear, plus the fixed cost of the pass.\n",
            slope_text(s.triangle_slope()),
            number(a),
            number(b * 1e6),
            slope_text(r2),
        );
        let _ = writeln!(o, "{}\n", memory_note(s));
        let _ = writeln!(
            o,
            "| resolution | pixels | time [ms] |\n| --- | --- | --- |"
        );
        for p in &s.pixels {
            let _ = writeln!(
                o,
                "| {}x{} | {} | {} [{}–{}] |",
                p.width,
                p.height,
                p.pixels(),
                ms(p.time.median),
                ms(p.time.q1),
                ms(p.time.q3)
            );
        }
        let (a, b, r2) = s.pixel_fit();
        let _ = writeln!(
            o,
            "\nTime grows as pixels^**{}** (log-log slope); as a line, {} ms + {} ms per megapixel (R² = {}).\n",
            slope_text(s.pixel_slope()),
            number(a),
            number(b * 1e6),
            slope_text(r2)
        );
    }

    let _ = writeln!(o, "## CPU side\n");
    let _ = writeln!(
        o,
        "`cargo bench --bench brdf` times the f64 reference `f_r` of every model; `cargo bench --bench reference` the reference renderer on a small built-in scene (criterion; not part of this report)."
    );
    o
}

/// The layer knobs (`configs::LAYERS`): each glTF layer's cost as a ratio
/// to the core gltf-pbr material, and its error against its own scene's
/// reference (`Config::own_truth`).
fn layers(o: &mut String, r: &BenchReport) {
    use super::configs::LAYER_KNOB;
    let rows: Vec<&super::Row> = r
        .rows
        .iter()
        .filter(|row| row.config.own_truth && row.config.knob.starts_with(LAYER_KNOB))
        .collect();
    let Some(core) = rows
        .iter()
        .find(|row| row.config.knob == format!("{LAYER_KNOB}core"))
    else {
        return;
    };
    let _ = writeln!(o, "### Layers of the glTF material\n");
    let _ = writeln!(
        o,
        "The bench's material as `gltf-pbr` ({}) with one layer of the contract's \"Layered glTF materials\" on (its keys: `configs::LAYERS`), or all of them. Time: over the core alone (`layer core`). Error: against the CPU reference of the same scene, made as the truth is (these configurations draw another material than the base, so the base's truth does not apply, and `--max-error` never picks them): what the GPU gets wrong about the layer (f32, the sheen's albedo table, the area light's samples as in the base).\n",
        super::configs::LAYER_CORE.join(", ")
    );
    let _ = writeln!(
        o,
        "| layer | GPU time [ms] | × core | error (rel. RMS) | max rel. error | front |\n| --- | --- | --- | --- | --- | --- |"
    );
    for row in rows.iter() {
        let _ = writeln!(
            o,
            "| {} | {} [{}–{}] | {:.2} | {} | {} | {} |",
            row.config.knob.trim_start_matches(LAYER_KNOB),
            ms(row.time.median),
            ms(row.time.q1),
            ms(row.time.q3),
            row.time.median / core.time.median,
            number(row.error),
            number(row.max_rel),
            if row.on_front { "★" } else { "" }
        );
    }
    o.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_round_trip() {
        let fields = [
            "plain",
            "with, comma",
            "with \"quotes\"",
            "lights=[{kind=\"point\", position=[1, 2, 3]}];shading.mode=flat",
            "",
        ];
        let line: Vec<String> = fields.iter().map(|f| csv_field(f)).collect();
        assert_eq!(parse_csv_line(&line.join(",")), fields);
    }
}
