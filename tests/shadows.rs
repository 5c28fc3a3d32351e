//! Shadows and area lights, GPU (lavapipe) against the ray-traced
//! reference. Run with `--nocapture` to see the tables; docs/shadows.md
//! holds the derivations and the measured values.
//!
//! * (a) no shadow acne: a lone plane lit at incidence angles up to 85°
//!   renders exactly like the reference (which has nothing to occlude it)
//!   within the derived render tolerance;
//! * (b) shadow masks: the GPU's visibility (`V = L_shadows / L_no_shadows`
//!   with one light and no ambient light, `V ≥ ½` is lit) against the
//!   reference's ray-traced one, on the built-in sphere-on-plane and on a
//!   real glTF model, for map sizes 512-4096 and PCF none/3/5. The bound,
//!   derived in docs/shadows.md: a pixel can disagree only if the shadow
//!   boundary passes within `w = texel · (k/√2 + c)` (k the PCF kernel, c
//!   the normal offset, both in texels) of its point, measured across the
//!   light; on the receiver that is at most `w / cosθ`, in the image at
//!   most `w / cosθ · f / z` pixels (f the focal length in pixels, z the
//!   view depth), plus √2 px for the pixel grid. Every mismatch must lie in
//!   this band around the reference's boundary pixels;
//! * (c) shadowed regions receive exactly the ambient term and the other
//!   lights: outside the band the GPU frame matches the reference within
//!   the render tolerance, shadowed pixels included;
//! * (d) area lights: error vs N against the exact image, GPU and
//!   reference, decreasing; and the error of the GPU's shared shadow map.
//! * (f) alpha MASK cuts shadows; (g) a light's markers (emissive or
//!   BLEND geometry around it) cast none of its shadow.

mod common;

use glam::DVec3;
use gonio::frame::Frame;
use gonio::gpu::GpuRenderer;
use gonio::gpu::shadows::ShadowPlan;
use gonio::gpu::timing::Clock;
use gonio::reference;
use gonio::scene::bvh::Bvh;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Light, Scene, ShadingMode, mesh};
use std::time::Duration;

const WIDTH: u32 = 192;
const HEIGHT: u32 = 144;

fn load(source: SceneSource, extra: &[&str]) -> Scene {
    let mut sets = vec![
        format!("image.width={WIDTH}"),
        format!("image.height={HEIGHT}"),
        "shading.mode=phong".to_string(),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    scene_file::load(&source, &sets).unwrap_or_else(|e| panic!("scene loads: {e}"))
}

fn gltf_scene(extra: &[&str]) -> Scene {
    let mut sets = vec![
        "shadows.imported_lights=true",
        "image.width=256",
        "image.height=144",
    ];
    sets.extend_from_slice(extra);
    load(
        SceneSource::File(common::gltf_asset(
            "ShadowsDirectional/shadows-directional.gltf",
        )),
        &sets,
    )
}

fn gpu(renderer: &mut GpuRenderer, scene: &Scene) -> Frame {
    let (frame, _) = renderer.render(scene).expect("GPU render");
    assert!(
        frame.radiance.iter().flatten().all(|v| v.is_finite()),
        "NaN or Inf in the GPU frame"
    );
    frame
}

fn without_shadows(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    s.lights.iter_mut().for_each(|l| l.set_shadows(false));
    s
}

/// What the primary ray of a pixel (plus a sub-pixel offset) hits: the
/// mesh, the shading point (as the reference interpolates it) and the
/// geometric normal.
#[derive(Clone, Copy)]
struct Surface {
    mesh: u32,
    triangle: u32,
    x: DVec3,
    n_g: DVec3,
}

fn surfaces(scene: &Scene, bvh: &Bvh, dx: f64, dy: f64) -> Vec<Option<Surface>> {
    let camera = &scene.camera;
    let forward = camera.forward();
    let mut out = Vec::with_capacity((scene.width * scene.height) as usize);
    for i in 0..scene.height {
        for j in 0..scene.width {
            let ray = camera.ray(
                j as f64 + 0.5 + dx,
                i as f64 + 0.5 + dy,
                scene.width,
                scene.height,
            );
            let cos = ray.direction.dot(forward);
            let hit = bvh.intersect(&ray, camera.near / cos, camera.far / cos);
            out.push(hit.map(|h| {
                let m = &scene.meshes[h.id.mesh as usize];
                let [a, b, c] = m.triangle(h.id.triangle as usize);
                Surface {
                    mesh: h.id.mesh,
                    triangle: h.id.triangle,
                    x: a * (1.0 - h.u - h.v) + b * h.u + c * h.v,
                    n_g: mesh::face_normal([a, b, c]),
                }
            }));
        }
    }
    out
}

/// Per pixel: the visibility of the scene's one shadowed light, `None`
/// where it is undefined (uncovered, or the light does not reach the pixel
/// even unshadowed).
fn visibility(on: &Frame, off: &Frame) -> Vec<Option<f64>> {
    let sum = |p: [f32; 3]| p.iter().map(|&v| v as f64).sum::<f64>();
    let max = (0..off.len())
        .map(|k| sum(off.radiance[k]))
        .fold(0.0, f64::max);
    (0..off.len())
        .map(|k| {
            let l_off = sum(off.radiance[k]);
            (on.coverage[k] && off.coverage[k] && l_off > 1e-3 * max)
                .then(|| sum(on.radiance[k]) / l_off)
        })
        .collect()
}

/// The derived mismatch band of light `l` (see the module docs): true for
/// pixels within `w/cosθ · f/z + √2` px of a pixel where the reference's
/// mask changes.
fn band(
    scene: &Scene,
    l: usize,
    reference_v: &[Option<f64>],
    center: &[Option<Surface>],
) -> Vec<bool> {
    let plan = ShadowPlan::new(scene);
    let settings = scene.shadow_settings(l);
    let k = settings.filter.kernel() as f64;
    let c = settings.normal_offset;
    let (w, h) = (scene.width as i64, scene.height as i64);
    let focal = 0.5 * h as f64 / (0.5 * scene.camera.fov_y_deg.to_radians()).tan();
    // Boundary pixels: the reference's mask changes to a 4-neighbour, or
    // the neighbour shows no surface this light reaches (background, a
    // side facing away from the light: the shadow boundary can run on off
    // the lit surface) or a nearer mesh (it can run on hidden behind it).
    let lit = |k: usize| reference_v[k].map(|v| v >= 0.5);
    let depth = |k: usize| center[k].map_or(f64::INFINITY, |s| scene.camera.view_depth(s.x));
    let occludes = |n: usize, k: usize| {
        center[n].map(|s| s.mesh) != center[k].map(|s| s.mesh) && depth(n) < depth(k)
    };
    let boundary: Vec<bool> = (0..reference_v.len())
        .map(|idx| {
            let Some(here) = lit(idx) else { return false };
            let (i, j) = (idx as i64 / w, idx as i64 % w);
            [(0, 1), (0, -1), (1, 0), (-1, 0)].iter().any(|(di, dj)| {
                let (a, b) = (i + di, j + dj);
                if !((0..h).contains(&a) && (0..w).contains(&b)) {
                    return false;
                }
                let n = (a * w + b) as usize;
                lit(n) != Some(here) || occludes(n, idx)
            })
        })
        .collect();
    let light = &scene.lights[l];
    (0..reference_v.len())
        .map(|idx| {
            let Some(s) = center[idx] else { return false };
            let to_light = match light {
                Light::Directional { direction, .. } => -*direction,
                other => other.position().unwrap() - s.x,
            }
            .normalize();
            let cos = s.n_g.dot(to_light).abs().max(1e-3);
            let texel = plan.texel_at(l, s.x).expect("the light has a shadow map");
            let z = scene.camera.view_depth(s.x);
            let radius = (texel * (k / std::f64::consts::SQRT_2 + c) / cos * focal / z
                + std::f64::consts::SQRT_2)
                .min(64.0);
            let r = radius.ceil() as i64;
            let (i, j) = (idx as i64 / w, idx as i64 % w);
            (-r..=r).any(|di| {
                (-r..=r).any(|dj| {
                    let (a, b) = (i + di, j + dj);
                    ((di * di + dj * dj) as f64) <= radius * radius
                        && (0..h).contains(&a)
                        && (0..w).contains(&b)
                        && boundary[(a * w + b) as usize]
                })
            })
        })
        .collect()
}

/// Pixels whose jittered primary rays (±1/128 px) do not all hit the same
/// mesh: silhouettes, where GPU and reference may see different surfaces.
fn silhouettes(scene: &Scene, bvh: &Bvh, center: &[Option<Surface>]) -> Vec<bool> {
    let d = common::JITTER_PX;
    let shifted: Vec<_> = [(d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d)]
        .iter()
        .map(|&(dx, dy)| surfaces(scene, bvh, dx, dy))
        .collect();
    (0..center.len())
        .map(|k| {
            let id = center[k].map(|s| s.mesh);
            shifted.iter().any(|f| f[k].map(|s| s.mesh) != id)
        })
        .collect()
}

#[derive(Debug, Default)]
struct MaskReport {
    defined: usize,
    mismatched: usize,
    in_band: usize,
    outside_band: usize,
    band: usize,
}

impl MaskReport {
    fn pct(&self, n: usize) -> f64 {
        100.0 * n as f64 / self.defined.max(1) as f64
    }
}

/// The scene's geometry seen from the camera, computed once per scene.
struct View {
    center: Vec<Option<Surface>>,
    silhouette: Vec<bool>,
}

impl View {
    fn new(scene: &Scene) -> Self {
        let bvh = Bvh::new(&scene.meshes);
        let center = surfaces(scene, &bvh, 0.0, 0.0);
        let silhouette = silhouettes(scene, &bvh, &center);
        View { center, silhouette }
    }
}

/// GPU mask against the reference mask for light `l` (the scene's only
/// light, no ambient).
fn mask_report(
    scene: &Scene,
    l: usize,
    view: &View,
    gpu_v: &[Option<f64>],
    ref_v: &[Option<f64>],
) -> MaskReport {
    let band = band(scene, l, ref_v, &view.center);
    let mut r = MaskReport::default();
    for k in 0..ref_v.len() {
        let (Some(g), Some(c)) = (gpu_v[k], ref_v[k]) else {
            continue;
        };
        if view.silhouette[k] {
            continue;
        }
        r.defined += 1;
        r.band += band[k] as usize;
        if (g >= 0.5) != (c >= 0.5) {
            r.mismatched += 1;
            if band[k] {
                r.in_band += 1;
            } else {
                r.outside_band += 1;
                let s = view.center[k].unwrap();
                eprintln!(
                    "  outside the band: pixel (row {}, col {}), GPU V = {g:.3}, reference V = {c:.3}, x = {:.4}, n_g = {:.3}, mesh {}",
                    k as u32 / scene.width,
                    k as u32 % scene.width,
                    s.x,
                    s.n_g,
                    s.mesh
                );
            }
        }
    }
    r
}

/// One scene, its one light shadowed with each map size and filter: the
/// table of mismatched-pixel fractions. Returns the default row's report.
fn mask_table(label: &str, scene_for: &dyn Fn(&[&str]) -> Scene, prefix: &str) -> MaskReport {
    let mut renderer = common::gpu_renderer();
    let base = scene_for(&[]);
    let l = base
        .lights
        .iter()
        .position(Light::casts_shadows)
        .expect("a shadowed light");
    assert_eq!(base.lights.len(), 1, "{label}: one light");
    let view = View::new(&base);
    let ref_v = visibility(
        &reference::render(&base),
        &reference::render(&without_shadows(&base)),
    );
    let gpu_off = gpu(&mut renderer, &without_shadows(&base));
    eprintln!(
        "\n{label}: GPU shadow mask vs ray-traced mask ({} px with a defined mask)",
        {
            let gpu_v = visibility(&gpu(&mut renderer, &base), &gpu_off);
            mask_report(&base, l, &view, &gpu_v, &ref_v).defined
        }
    );
    eprintln!("| map size | filter | mismatched | band (bound) | mismatched outside band |");
    eprintln!("|---:|---|---:|---:|---:|");
    let mut default_report = None;
    for size in [512, 1024, 2048, 4096] {
        for (filter, kernel) in [("none", 1), ("pcf", 3), ("pcf", 5)] {
            let sets = [
                format!("{prefix}map_size={size}"),
                format!("{prefix}filter={filter}"),
                format!("{prefix}pcf_kernel={kernel}"),
            ];
            let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
            let scene = scene_for(&sets);
            let gpu_v = visibility(&gpu(&mut renderer, &scene), &gpu_off);
            let r = mask_report(&scene, l, &view, &gpu_v, &ref_v);
            let name = if filter == "none" {
                "none".to_string()
            } else {
                format!("pcf {kernel}")
            };
            eprintln!(
                "| {size} | {name} | {:.3} % ({}) | {:.3} % | {} |",
                r.pct(r.mismatched),
                r.mismatched,
                r.pct(r.band),
                r.outside_band
            );
            if size == 2048 && kernel == 3 {
                default_report = Some(r);
            }
        }
    }
    default_report.unwrap()
}

// ---------------------------------------------------------------------
// (a) No acne.

/// A lone 4 m plane lit by `light` with shadows on: GPU = reference
/// (which sees no occluder) within the render tolerance.
fn lone_plane(renderer: &mut GpuRenderer, label: &str, light: &str, extra: &[&str]) {
    let mut sets = vec![
        "objects=[{shape = \"plane\", size = 4.0, segments = 4, material = \"floor\"}]".to_string(),
        "camera.position=[0.0, 3.0, 4.0]".to_string(),
        "camera.target=[0.0, 0.0, 0.0]".to_string(),
        format!("lights=[{light}]"),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let scene = load(SceneSource::BuiltIn, &sets);
    assert!(scene.has_shadows());
    let frame = gpu(renderer, &scene);
    let (center, jittered) = common::reference_with_jitter(&scene);
    let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
    eprintln!("{label:<48} {}", c.summary());
    assert!(
        c.compared > (WIDTH * HEIGHT / 4) as usize,
        "{label}: too few pixels"
    );
    common::assert_agrees(label, "shadow acne or bias error", &c, &frame, &center);
}

#[test]
fn a_lit_plane_has_no_acne_up_to_85_degrees() {
    let mut renderer = common::gpu_renderer();
    eprintln!("\n(a) lone plane, shadows on, GPU vs reference:");
    for theta in [0.0f64, 30.0, 60.0, 75.0, 80.0, 85.0] {
        // A directional light whose incidence on the +Y plane is θ.
        let t = theta.to_radians();
        let dir = [t.sin(), -t.cos(), -0.3 * t.sin()];
        let dir = format!("[{}, {}, {}]", dir[0], dir[1], dir[2]);
        for filter in ["filter=\"none\"", "filter=\"pcf\""] {
            let light = format!(
                "{{kind = \"directional\", direction = {dir}, irradiance = 3.0, shadows = true, shadow_{filter}}}"
            );
            lone_plane(
                &mut renderer,
                &format!("directional θ = {theta}°, {filter}"),
                &light,
                &[],
            );
        }
    }
    // A point light low over one edge: incidence from 0° below it to
    // atan(4 / 0.35) ≈ 85° at the far edge; a spot light the same way.
    lone_plane(
        &mut renderer,
        "point light 0.35 m over the edge (θ up to 85°)",
        "{kind = \"point\", position = [0.0, 0.35, -2.0], intensity = 3.0, shadows = true}",
        &[],
    );
    lone_plane(
        &mut renderer,
        "spot light 0.35 m over the edge (θ up to 85°)",
        "{kind = \"spot\", position = [0.0, 0.35, -2.0], direction = [0.0, -0.1, 1.0], intensity = 3.0, outer_cone_deg = 55.0, shadows = true}",
        &[],
    );
    lone_plane(
        &mut renderer,
        "area light 0.4 m over the edge, 16 samples",
        "{kind = \"area\", shape = \"rect\", position = [0.0, 0.4, -2.1], normal = [0.0, -0.2, 1.0], size = [1.0, 0.3], tangent = [1.0, 0.0, 0.0], radiance = 20.0, samples = 16, shadows = true}",
        &[],
    );
    for mode in ["flat", "gouraud"] {
        lone_plane(
            &mut renderer,
            &format!("directional θ = 85°, {mode} shading"),
            "{kind = \"directional\", direction = [0.996, -0.087, 0.0], irradiance = 3.0, shadows = true}",
            &[&format!("shading.mode={mode}")],
        );
    }
}

// ---------------------------------------------------------------------
// (b) Shadow masks.

#[test]
fn b_sphere_on_plane_mask_matches_the_ray_traced_mask() {
    let scene_for = |extra: &[&str]| {
        let mut sets = vec!["lights.0.shadows=true", "ambient.radiance=0.0"];
        sets.extend_from_slice(extra);
        load(SceneSource::BuiltIn, &sets)
    };
    let r = mask_table(
        "(b) sphere on plane, point light (cube map)",
        &scene_for,
        "lights.0.shadow_",
    );
    assert!(r.defined > 10_000, "too few pixels: {r:?}");
    assert_eq!(
        r.outside_band, 0,
        "mismatches outside the derived band: {r:?}"
    );
}

#[test]
fn b_gltf_model_mask_matches_the_ray_traced_mask() {
    let scene_for = |extra: &[&str]| {
        let sets: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        gltf_scene(&sets)
    };
    let r = mask_table(
        "(b) ShadowsDirectional.gltf, directional light (orthographic map)",
        &scene_for,
        "shadows.",
    );
    assert!(r.defined > 4_000, "too few pixels: {r:?}");
    assert_eq!(
        r.outside_band, 0,
        "mismatches outside the derived band: {r:?}"
    );
}

#[test]
fn b_every_light_kind_and_shading_mode_casts_shadows() {
    let mut renderer = common::gpu_renderer();
    eprintln!("\n(b) every light kind, default settings (2048, pcf 3), built-in scene:");
    let kinds = [
        (
            "point",
            "{kind = \"point\", position = [3.0, 5.0, 3.0], intensity = 60.0, shadows = true}",
        ),
        (
            "spot",
            "{kind = \"spot\", position = [2.0, 4.0, 2.0], direction = [-0.4, -1.0, -0.4], intensity = 40.0, inner_cone_deg = 15.0, outer_cone_deg = 30.0, shadows = true}",
        ),
        (
            "wide spot (cube map)",
            "{kind = \"spot\", position = [2.0, 4.0, 2.0], direction = [-0.4, -1.0, -0.4], intensity = 40.0, outer_cone_deg = 75.0, shadows = true}",
        ),
        (
            "directional",
            "{kind = \"directional\", direction = [-0.5, -1.0, -0.3], irradiance = 3.0, shadows = true}",
        ),
    ];
    for (name, light) in kinds {
        let sets = [
            format!("lights=[{light}]"),
            "ambient.radiance=0.0".to_string(),
        ];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let scene = load(SceneSource::BuiltIn, &sets);
        let view = View::new(&scene);
        let off = without_shadows(&scene);
        let ref_v = visibility(&reference::render(&scene), &reference::render(&off));
        let gpu_v = visibility(&gpu(&mut renderer, &scene), &gpu(&mut renderer, &off));
        let r = mask_report(&scene, 0, &view, &gpu_v, &ref_v);
        let shadowed = ref_v.iter().flatten().filter(|&&v| v < 0.5).count();
        eprintln!(
            "{name:<22} shadowed {shadowed:>5} px, mismatched {:.3} % ({}), band {:.3} %, outside band {}",
            r.pct(r.mismatched),
            r.mismatched,
            r.pct(r.band),
            r.outside_band
        );
        assert!(shadowed > 500, "{name}: no shadow in the reference");
        assert_eq!(r.outside_band, 0, "{name}: {r:?}");
    }
    // Flat and Gouraud: visibility is evaluated at the centroid / the
    // vertices on both sides, so a triangle can differ only if one of its
    // shading points is within w of a shadow boundary (measured across the
    // light); such triangles flip as a whole and are skipped, everything
    // else must match within the render tolerance.
    for mode in [ShadingMode::Flat, ShadingMode::Gouraud] {
        let sets = [
            "lights.0.shadows=true".to_string(),
            format!("shading.mode={mode}"),
        ];
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let scene = load(SceneSource::BuiltIn, &sets);
        let frame = gpu(&mut renderer, &scene);
        let (center, jittered) = common::reference_with_jitter(&scene);
        let raw = common::compare_to_reference(&scene, &frame, &center, &jittered);
        let view = View::new(&scene);
        let bvh = Bvh::new(&scene.meshes);
        let plan = ShadowPlan::new(&scene);
        let mut stable = std::collections::HashMap::new();
        let mut masked = frame.clone();
        let mut skipped = 0;
        for k in 0..frame.len() {
            let Some(s) = view.center[k] else { continue };
            let m = &scene.meshes[s.mesh as usize];
            let t = s.triangle as usize;
            let points: Vec<(DVec3, DVec3)> = match mode {
                ShadingMode::Flat => vec![(
                    mesh::centroid(m.triangle(t)),
                    mesh::face_normal(m.triangle(t)),
                )],
                _ => m.indices[t]
                    .iter()
                    .map(|&v| (m.positions[v as usize], m.normals[v as usize]))
                    .collect(),
            };
            let ok = points.iter().all(|&(x, n)| {
                *stable
                    .entry((s.mesh, x.to_array().map(f64::to_bits)))
                    .or_insert_with(|| shading_point_is_stable(&scene, &bvh, &plan, 0, x, n))
            });
            if !ok {
                masked.radiance[k] = center.radiance[k];
                skipped += 1;
            }
        }
        let c = common::compare_to_reference(&scene, &masked, &center, &jittered);
        eprintln!(
            "{mode:<22} {} px differ in all; skipping {skipped} px of triangles with a shading point within w of a boundary: {}",
            raw.failing,
            c.summary()
        );
        common::assert_agrees(
            &format!("shadows-b-{mode}"),
            "GPU and traced shadows disagree",
            &c,
            &masked,
            &center,
        );
    }
}

/// Whether the ray-traced visibility of light `l` at shading point `x`
/// (offset normal `n`) is the same at every point of its tangent plane
/// whose position across the light is within `w = texel · (k/√2 + c)` of
/// x's (sampled: 16 directions at w, 8 at w/2). Only then can the shadow
/// map not disagree with the reference there.
fn shading_point_is_stable(
    scene: &Scene,
    bvh: &Bvh,
    plan: &ShadowPlan,
    l: usize,
    x: DVec3,
    n: DVec3,
) -> bool {
    let light = &scene.lights[l];
    let eps = reference::shadow_epsilon(scene);
    let settings = scene.shadow_settings(l);
    let w = plan.texel_at(l, x).unwrap()
        * (settings.filter.kernel() as f64 / std::f64::consts::SQRT_2 + settings.normal_offset);
    let here = reference::visibility(bvh, light, x, n, eps);
    let to_light = match light {
        Light::Directional { direction, .. } => -*direction,
        other => (other.position().unwrap() - x).normalize(),
    };
    if n.dot(to_light).abs() < 1e-3 {
        return false;
    }
    let (e1, e2) = to_light.any_orthonormal_pair();
    let samples = (0..16)
        .map(|k| (k, 1.0))
        .chain((0..8).map(|k| (2 * k, 0.5)));
    samples.into_iter().all(|(k, rho)| {
        let phi = std::f64::consts::TAU * k as f64 / 16.0;
        let o = (e1 * phi.cos() + e2 * phi.sin()) * (w * rho);
        // Back onto the tangent plane along the light's ray.
        let y = match light.position() {
            None => x + o - to_light * (n.dot(o) / n.dot(to_light)),
            Some(p) => {
                let q = x + o;
                p + (q - p) * (n.dot(x - p) / n.dot(q - p))
            }
        };
        reference::visibility(bvh, light, y, n, eps) == here
    })
}

// ---------------------------------------------------------------------
// (c) Shadowed regions receive only the ambient term and other lights.

#[test]
fn c_shadowed_regions_receive_ambient_and_other_lights_only() {
    let mut renderer = common::gpu_renderer();
    // The point light casts shadows; a second, unshadowed directional
    // light and the ambient light reach the shadow.
    let scene = load(
        SceneSource::BuiltIn,
        &[
            "lights.0.shadows=true",
            "ambient.radiance=[0.05, 0.05, 0.06]",
            "lights=[{kind = \"point\", position = [3.0, 5.0, 3.0], intensity = 60.0, shadows = true}, {kind = \"directional\", direction = [0.6, -1.0, 0.2], irradiance = 0.5}]",
        ],
    );
    let view = View::new(&scene);
    // The band of light 0, from its own mask.
    let only_point = {
        let mut s = scene.clone();
        s.lights.truncate(1);
        s.light_shadows.truncate(1);
        s.ambient = DVec3::ZERO;
        s
    };
    let ref_v = visibility(
        &reference::render(&only_point),
        &reference::render(&without_shadows(&only_point)),
    );
    let band = band(&only_point, 0, &ref_v, &view.center);
    let gpu_frame = gpu(&mut renderer, &scene);
    let (center, jittered) = common::reference_with_jitter(&scene);
    // Band pixels take the reference's value: they are (b)'s business.
    let mut masked = gpu_frame.clone();
    let mut shadowed = 0;
    for k in 0..masked.len() {
        if band[k] {
            masked.radiance[k] = center.radiance[k];
        } else if ref_v[k].is_some_and(|v| v < 0.5) && !view.silhouette[k] {
            shadowed += 1;
        }
    }
    let c = common::compare_to_reference(&scene, &masked, &center, &jittered);
    eprintln!(
        "\n(c) two lights + ambient, point light shadowed: {shadowed} shadowed px outside the band; {}",
        c.summary()
    );
    assert!(shadowed > 400, "too few shadowed pixels: {shadowed}");
    common::assert_agrees(
        "shadows-c",
        "GPU and traced shadows disagree",
        &c,
        &masked,
        &center,
    );
}

// ---------------------------------------------------------------------
// (d) Area lights.

fn area_scene(shape: &str, shadows: bool, extra: &[&str]) -> Scene {
    let light = match shape {
        "rect" => "{kind = \"area\", shape = \"rect\", position = [0.0, 2.2, 0.5], normal = [0.0, -1.0, -0.3], size = [2.0, 1.0], tangent = [1.0, 0.0, 0.0], radiance = 6.0, samples = 16, shadows = SH}",
        _ => "{kind = \"area\", shape = \"disk\", position = [0.5, 2.0, 0.5], normal = [-0.2, -1.0, 0.0], radius = 0.8, radiance = 6.0, samples = 16, shadows = SH}",
    }
    .replace("SH", if shadows { "true" } else { "false" });
    let mut sets = vec![
        format!("lights=[{light}]"),
        "ambient.radiance=0.0".to_string(),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    load(SceneSource::BuiltIn, &sets)
}

#[test]
fn d_area_light_error_falls_with_the_number_of_samples() {
    let mut renderer = common::gpu_renderer();
    let ns = [1u32, 4, 16, 64, 256];
    for shape in ["rect", "disk"] {
        // Lambert everywhere and no occlusion: the exact image is analytic.
        let scene = area_scene(
            shape,
            false,
            &[
                "materials.ball.model=lambert",
                "objects.0.center=[0.0, 1.0, -1.5]",
            ],
        );
        assert!(reference::area::exact_is_analytic(&scene));
        let exact = reference::area::render_exact(&scene);
        let reference_rows = reference::area::error_vs_samples(&scene, &ns);
        eprintln!(
            "\n(d) {shape} area light over Lambert surfaces: error vs N against the exact (analytic) image"
        );
        eprintln!("| N | reference rel. RMS | reference max | GPU rel. RMS | GPU max |");
        eprintln!("|---:|---:|---:|---:|---:|");
        let mut last = (f64::INFINITY, f64::INFINITY);
        for row in &reference_rows {
            let frame = gpu(&mut renderer, &scene.with_area_samples(row.samples));
            let (rms, max) = reference::area::frame_error(&frame, &exact);
            eprintln!(
                "| {} | {:.2e} | {:.2e} | {:.2e} | {:.2e} |",
                row.samples, row.rel_rms, row.max_rel, rms, max
            );
            assert!(
                row.rel_rms < last.0 && rms < last.1,
                "{shape}: the error did not fall at N = {}",
                row.samples
            );
            // The GPU's N samples are the reference's up to f32.
            assert!(
                (rms - row.rel_rms).abs() < 1e-3 + 0.05 * row.rel_rms,
                "{shape} N = {}: GPU {rms} vs reference {}",
                row.samples,
                row.rel_rms
            );
            last = (row.rel_rms, rms);
        }
        assert!(
            last.1 < 0.01,
            "{shape}: 256 samples still {:.3} off",
            last.1
        );
    }
}

#[test]
fn d_area_light_shadows_shared_and_per_sample_cube_maps() {
    let mut renderer = common::gpu_renderer();
    eprintln!(
        "\n(d) rect area light with shadows, sphere on plane, GPU vs reference (one shadow ray per sample):"
    );
    eprintln!("shared: one 2048² cube at the light's centre; per sample: one 512² cube per sample");
    eprintln!(
        "| N | shared rel. RMS | shared: px off > 5 % of max | per sample rel. RMS | per sample: px off > 5 % |"
    );
    eprintln!("|---:|---:|---:|---:|---:|");
    let error = |frame: &Frame, reference: &Frame| {
        let (rms, _) = reference::area::frame_error(frame, reference);
        let peak = reference.max_radiance() as f64;
        let off = (0..frame.len())
            .filter(|&k| frame.coverage[k] && reference.coverage[k])
            .filter(|&k| {
                (0..3).any(|ch| {
                    (frame.radiance[k][ch] - reference.radiance[k][ch]).abs() as f64 > 0.05 * peak
                })
            })
            .count();
        (rms, 100.0 * off as f64 / frame.len() as f64)
    };
    for n in [1u32, 4, 16, 64] {
        let shared = area_scene("rect", true, &[]).with_area_samples(n);
        let mut each =
            area_scene("rect", true, &["lights.0.shadow_map_size=512"]).with_area_samples(n);
        each.area_lights[0].shadow_per_sample = true;
        let reference = reference::render(&shared);
        let (rms_shared, off_shared) = error(&gpu(&mut renderer, &shared), &reference);
        let (rms_each, off_each) = error(&gpu(&mut renderer, &each), &reference);
        eprintln!(
            "| {n} | {rms_shared:.3e} | {off_shared:.2} % | {rms_each:.3e} | {off_each:.2} % |"
        );
        // One sample at the centre, or a map per sample: exact up to the
        // maps' resolution (the boundary band of (b)).
        assert!(rms_each < 0.02, "per sample, N = {n}: {rms_each}");
        if n == 1 {
            assert!(rms_shared < 0.02, "N = 1: {rms_shared}");
        }
    }
}

// ---------------------------------------------------------------------
// Cost.

#[test]
fn shadow_pass_cost_is_measured() {
    let mut renderer = common::gpu_renderer();
    eprintln!(
        "\nGPU time (timestamps, median of 5 after warm-up), built-in scene {WIDTH}x{HEIGHT}:"
    );
    eprintln!("| configuration | shadow passes | scene pass | sum |");
    eprintln!("|---|---:|---:|---:|");
    let configs: [(&str, &[&str]); 5] = [
        ("no shadows (no pass, no shadow code)", &[]),
        (
            "point light, cube 6 × 1024², pcf 3",
            &["lights.0.shadows=true", "lights.0.shadow_map_size=1024"],
        ),
        (
            "point light, cube 6 × 2048², pcf 3",
            &["lights.0.shadows=true"],
        ),
        (
            "point light, cube 6 × 2048², none",
            &["lights.0.shadows=true", "lights.0.shadow_filter=none"],
        ),
        (
            "directional, 2048², pcf 3",
            &[
                "lights=[{kind = \"directional\", direction = [-0.5, -1.0, -0.3], irradiance = 3.0, shadows = true}]",
            ],
        ),
    ];
    for (name, sets) in configs {
        let scene = load(SceneSource::BuiltIn, sets);
        let mut samples = Vec::new();
        for run in 0..6 {
            let (_, timings) = renderer.render(&scene).expect("render");
            let get = |prefix: &str| {
                timings
                    .entries
                    .iter()
                    .find(|(n, _, c)| n.starts_with(prefix) && *c == Clock::GpuTimestamp)
                    .map_or(Duration::ZERO, |e| e.1)
            };
            if run > 0 {
                samples.push((get("shadow passes"), get("render pass")));
            }
        }
        samples.sort_by_key(|s| s.0 + s.1);
        let (shadow, pass) = samples[samples.len() / 2];
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        eprintln!(
            "| {name} | {:.2} ms | {:.2} ms | {:.2} ms |",
            ms(shadow),
            ms(pass),
            ms(shadow + pass)
        );
    }
}

// ---------------------------------------------------------------------
// (e) Shadow-map coordinates per vertex (one orthographic map, Phong
// shading: ShaderKey::shadow_coords_per_vertex) against per pixel.
//
// The two compute the same affine function of the shading point, in a
// different order of f32 operations: the lookup coordinates differ by a
// few units in the last place, about δ = 10⁻⁶ of the map's [-1, 1] extent
// (ten roundings of 6·10⁻⁸ on values up to 1), i.e. δ·side/2 ≈ 10⁻³ texel
// at 2048 texels. A nearest-texel tap changes only when its sample point
// lies within that distance of a texel edge: per tap and axis a chance of
// 2·10⁻³; a 3×3 kernel crosses 3 column and 3 row edges, so at most about
// 1.2 % of the lit-or-shadowed receiver pixels may see one tap (1/9 of
// the light) change, and only by whole taps. Both are asserted: at most
// 1.5 % of the pixels differ, and every difference is a multiple of one
// tap's share of the direct light (within f32 rounding). Measured on
// lavapipe: no pixel differs on either scene.
#[test]
fn e_vertex_shadow_coordinates_match_per_pixel_ones() {
    let mut renderer = common::gpu_renderer();
    for (label, scene) in [
        (
            "ShadowsDirectional.gltf",
            gltf_scene(&["ambient.radiance=0.0"]),
        ),
        (
            "viewer-bench.toml",
            load(
                SceneSource::File(
                    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                        .join("assets/scenes/viewer-bench.toml"),
                ),
                &["ambient.radiance=0.0"],
            ),
        ),
    ] {
        renderer.vertex_shadow_coords = true;
        let per_vertex = gpu(&mut renderer, &scene);
        renderer.vertex_shadow_coords = false;
        let per_pixel = gpu(&mut renderer, &scene);
        renderer.vertex_shadow_coords = true;
        let unshadowed = gpu(&mut renderer, &without_shadows(&scene));
        let (mut covered, mut differ, mut not_whole_taps) = (0usize, 0usize, 0usize);
        for i in 0..per_pixel.radiance.len() {
            if !per_pixel.coverage[i] {
                continue;
            }
            covered += 1;
            let (a, b, full) = (
                per_vertex.radiance[i],
                per_pixel.radiance[i],
                unshadowed.radiance[i],
            );
            if (0..3).all(|c| (a[c] - b[c]).abs() <= 1e-5 * full[c].abs().max(1e-30)) {
                continue;
            }
            differ += 1;
            // V difference in taps of a 3×3 kernel: a whole number.
            let c = (0..3).max_by(|&p, &q| full[p].total_cmp(&full[q])).unwrap();
            let taps = 9.0 * (a[c] - b[c]) / full[c];
            if (taps - taps.round()).abs() > 1e-3 {
                not_whole_taps += 1;
            }
        }
        let fraction = differ as f64 / covered as f64;
        println!(
            "(e) {label}: {differ} of {covered} pixels differ ({:.3} %), {not_whole_taps} not by whole taps",
            100.0 * fraction
        );
        assert!(covered > 4_000, "{label}: too few pixels");
        assert!(
            fraction <= 0.015,
            "{label}: {differ} of {covered} pixels differ"
        );
        assert_eq!(
            not_whole_taps, 0,
            "{label}: differences other than whole taps"
        );
    }
}

// ---------------------------------------------------------------------
// (f) Alpha MASK cuts shadows.

/// A glTF (written to `dir`) of a 6 m floor (y = 0, gltf-pbr grey) and a
/// 2 m square 2.5 m above it, facing up, whose base colour texture is
/// 2×1 texels (NEAREST, CLAMP) of alpha 0 (x < 0) | 1 (x > 0), with
/// `alpha_mode` ("MASK": the left half is cut out; "OPAQUE": all of it
/// casts).
fn masked_caster(dir: &std::path::Path, alpha_mode: &str) -> std::path::PathBuf {
    use base64::Engine;
    let b64 = |bytes: &[u8]| base64::engine::general_purpose::STANDARD.encode(bytes);
    let mut png = Vec::new();
    image::RgbaImage::from_raw(2, 1, vec![255, 255, 255, 0, 255, 255, 255, 255])
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    // Per mesh: 4 positions, 4 normals, 4 UVs, 6 indices (u16) = 140 bytes.
    let square = |half: f32, y: f32| {
        let mut b = floats(&[
            -half, y, half, half, y, half, half, y, -half, -half, y, -half,
        ]);
        b.extend(floats(&[0.0, 1.0, 0.0].repeat(4)));
        b.extend(floats(&[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]));
        b.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
        b
    };
    let mut bin = square(3.0, 0.0);
    bin.extend(square(1.0, 2.5));
    let views: Vec<String> = (0..2)
        .flat_map(|m| {
            let o = 140 * m;
            [(o, 48), (o + 48, 48), (o + 96, 32), (o + 128, 12)]
        })
        .map(|(o, l)| format!(r#"{{"buffer":0,"byteOffset":{o},"byteLength":{l}}}"#))
        .collect();
    let accessors: Vec<String> = [(3.0, 0.0), (1.0, 2.5)]
        .iter()
        .enumerate()
        .flat_map(|(m, (h, y))| {
            let v = 4 * m;
            [
                format!(r#"{{"bufferView":{v},"componentType":5126,"count":4,"type":"VEC3","min":[-{h},{y},-{h}],"max":[{h},{y},{h}]}}"#),
                format!(r#"{{"bufferView":{},"componentType":5126,"count":4,"type":"VEC3"}}"#, v + 1),
                format!(r#"{{"bufferView":{},"componentType":5126,"count":4,"type":"VEC2"}}"#, v + 2),
                format!(r#"{{"bufferView":{},"componentType":5123,"count":6,"type":"SCALAR"}}"#, v + 3),
            ]
        })
        .collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],"nodes":[{{"mesh":0}},{{"mesh":1}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"material":0}}]}},{{"primitives":[{{"attributes":{{"POSITION":4,"NORMAL":5,"TEXCOORD_0":6}},"indices":7,"material":1}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.8,0.8,1.0],"metallicFactor":0.0,"roughnessFactor":1.0}}}},
{{"alphaMode":"{alpha_mode}","pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}},"metallicFactor":0.0,"roughnessFactor":1.0}}}}],
"images":[{{"uri":"data:image/png;base64,{}"}}],"samplers":[{{"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071}}],"textures":[{{"source":0,"sampler":0}}],
"accessors":[{}],"bufferViews":[{}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}}"#,
        b64(&png),
        accessors.join(","),
        views.join(","),
        bin.len(),
        b64(&bin)
    );
    let path = dir.join(format!("caster-{alpha_mode}.gltf"));
    std::fs::write(&path, json).unwrap();
    path
}

/// A MASK caster lets the light through its cut-out, in both renderers:
/// the floor under the cut-out half is lit where the same caster made
/// OPAQUE shadows it, the other half still shadows, and the GPU's mask
/// matches the ray-traced one outside the derived band (as (b)). The
/// caster is above the picture, so every pixel shows the floor.
#[test]
fn f_alpha_mask_cuts_shadows() {
    let dir = tempfile::tempdir().unwrap();
    let mut renderer = common::gpu_renderer();
    let sets = [
        "image.width=192".to_string(),
        "image.height=144".into(),
        "camera={position = [0.0, 1.5, 5.5], target = [0.0, 0.0, -0.5], up = [0.0, 1.0, 0.0], fov_y_deg = 40.0}".into(),
        "lights=[{kind = \"directional\", direction = [0.3, -1.0, 0.2], irradiance = [3.0, 3.0, 3.0], shadows = true}]".into(),
        "ambient.radiance=0.0".into(),
    ];
    let load = |mode: &str| {
        scene_file::load(&SceneSource::File(masked_caster(dir.path(), mode)), &sets)
            .expect("caster loads")
    };
    let (masked, opaque) = (load("MASK"), load("OPAQUE"));
    let view = View::new(&masked);
    assert!(
        view.center.iter().flatten().all(|s| s.mesh == 0),
        "the floor alone is in the picture"
    );
    let off = without_shadows(&masked);
    let ref_off = reference::render(&off);
    let gpu_off = gpu(&mut renderer, &off);
    let ref_v = visibility(&reference::render(&masked), &ref_off);
    let gpu_v = visibility(&gpu(&mut renderer, &masked), &gpu_off);
    let ref_opaque = visibility(&reference::render(&opaque), &ref_off);
    let gpu_opaque = visibility(&gpu(&mut renderer, &opaque), &gpu_off);
    for (name, v, v_opaque) in [
        ("reference", &ref_v, &ref_opaque),
        ("GPU", &gpu_v, &gpu_opaque),
    ] {
        let count = |f: &dyn Fn(f64, f64) -> bool| {
            (0..v.len())
                .filter(|&k| matches!((v[k], v_opaque[k]), (Some(a), Some(b)) if f(a, b)))
                .count()
        };
        let through = count(&|a, b| a >= 0.5 && b < 0.5);
        let shadowed = count(&|a, _| a < 0.5);
        let wrong = count(&|a, b| a < 0.5 && b >= 0.5);
        eprintln!(
            "(f) {name}: {through} px lit through the cut-out, {shadowed} px in the kept half's shadow, {wrong} px shadowed only when masked"
        );
        assert!(through > 500, "{name}: the cut-out lets no light through");
        assert!(shadowed > 500, "{name}: the kept half casts no shadow");
        assert_eq!(wrong, 0, "{name}: masking added shadow");
    }
    let r = mask_report(&masked, 0, &view, &gpu_v, &ref_v);
    eprintln!("(f) GPU vs reference mask: {r:?}");
    assert!(r.defined > 10_000, "too few pixels: {r:?}");
    assert_eq!(
        r.outside_band, 0,
        "mismatches outside the derived band: {r:?}"
    );
}

// ---------------------------------------------------------------------
// (g) A light's markers let its light through.

/// A glTF (written to `dir`) of a 6 m floor (y = 0, grey) and a closed
/// 0.5 m cube centred 1.5 m above it, emissive and alpha BLEND, around a
/// `KHR_lights_punctual` light of `kind` ("point", or "spot" pointing
/// down) at the cube's centre: a light's marker, as KHR's ShadowsSpot
/// sample draws its spot light.
fn lamp(dir: &std::path::Path, kind: &str) -> std::path::PathBuf {
    use base64::Engine;
    let b64 = |bytes: &[u8]| base64::engine::general_purpose::STANDARD.encode(bytes);
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    // Floor: 4 positions, 4 normals, 6 indices.
    let mut positions = vec![
        -3.0, 0.0, 3.0, 3.0, 0.0, 3.0, 3.0, 0.0, -3.0, -3.0, 0.0, -3.0,
    ];
    let mut normals = [0.0, 1.0, 0.0].repeat(4);
    let mut indices: Vec<u16> = vec![0, 1, 2, 0, 2, 3];
    // Cube: 6 outward faces of 4 vertices each, counter-clockwise.
    let (c, h) = ([0.0f32, 1.5, 0.0], 0.25f32);
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let n: [f32; 3] = std::array::from_fn(|k| if k == axis { sign } else { 0.0 });
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let base = (positions.len() / 3) as u16;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = c;
                p[axis] += sign * h;
                p[u] += a * h;
                p[v] += b * h * sign;
                positions.extend(p);
                normals.extend(n);
            }
            indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        }
    }
    let floor_indices = 6;
    let mut bin = floats(&positions);
    let normals_at = bin.len();
    bin.extend(floats(&normals));
    let indices_at = bin.len();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    let vertices = positions.len() / 3;
    let light = match kind {
        "spot" => {
            r#"{"type":"spot","intensity":200,"spot":{"innerConeAngle":0.6,"outerConeAngle":1.0}}"#
        }
        _ => r#"{"type":"point","intensity":200}"#,
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_lights_punctual"],
"extensions":{{"KHR_lights_punctual":{{"lights":[{light}]}}}},
"scene":0,"scenes":[{{"nodes":[0,1,2]}}],
"nodes":[{{"mesh":0}},{{"mesh":1}},{{"translation":[0.0,1.5,0.0],"rotation":[-0.70710678,0.0,0.0,0.70710678],"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1}},"indices":2,"material":0}}]}},{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1}},"indices":3,"material":1}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.8,0.8,0.8,1.0],"metallicFactor":0.0,"roughnessFactor":1.0}}}},
{{"alphaMode":"BLEND","emissiveFactor":[0.1,0.09,0.06],"pbrMetallicRoughness":{{"baseColorFactor":[1.0,1.0,1.0,0.5],"metallicFactor":0.0,"roughnessFactor":1.0}}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3","min":[-3.0,0.0,-3.0],"max":[3.0,1.75,3.0]}},
{{"bufferView":1,"componentType":5126,"count":{vertices},"type":"VEC3"}},
{{"bufferView":2,"componentType":5123,"count":{floor_indices},"type":"SCALAR"}},
{{"bufferView":2,"byteOffset":{},"componentType":5123,"count":{},"type":"SCALAR"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{normals_at}}},{{"buffer":0,"byteOffset":{normals_at},"byteLength":{normals_at}}},{{"buffer":0,"byteOffset":{indices_at},"byteLength":{}}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}}"#,
        floor_indices * 2,
        indices.len() - floor_indices,
        indices.len() * 2,
        bin.len(),
        b64(&bin)
    );
    let path = dir.join(format!("lamp-{kind}.gltf"));
    std::fs::write(&path, json).unwrap();
    path
}

/// A light's marker (emissive, BLEND, around the light) casts none of its
/// light's shadow by default, in both renderers: every floor pixel the
/// light reaches is lit, and the GPU's mask matches the ray-traced one
/// outside the derived band. With `shadows.markers = "cast"` the closed
/// marker shadows the whole floor in both, as it did before the rule.
#[test]
fn g_a_lights_marker_casts_none_of_its_shadow() {
    let dir = tempfile::tempdir().unwrap();
    let mut renderer = common::gpu_renderer();
    for kind in ["point", "spot"] {
        let sets = [
            "image.width=192".to_string(),
            "image.height=144".into(),
            "camera={position = [0.0, 3.0, 5.0], target = [0.0, 0.0, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = 50.0}".into(),
            "ambient.radiance=0.0".into(),
        ];
        let path = lamp(dir.path(), kind);
        let load = |extra: &[&str]| {
            let mut all = sets.to_vec();
            all.extend(extra.iter().map(|s| s.to_string()));
            scene_file::load(&SceneSource::File(path.clone()), &all).expect("lamp loads")
        };
        let (pass, cast) = (load(&[]), load(&["shadows.markers=cast"]));
        assert_eq!(pass.lights.len(), 1, "{kind}: the file's light");
        assert!(
            pass.lights[0].casts_shadows(),
            "{kind}: imported lights cast shadows"
        );
        let view = View::new(&pass);
        let off = without_shadows(&pass);
        let ref_off = reference::render(&off);
        let gpu_off = gpu(&mut renderer, &off);
        let on_floor = |v: Vec<Option<f64>>| -> Vec<Option<f64>> {
            v.into_iter()
                .zip(&view.center)
                .map(|(v, s)| v.filter(|_| s.is_some_and(|s| s.mesh == 0)))
                .collect()
        };
        let ref_v = on_floor(visibility(&reference::render(&pass), &ref_off));
        let gpu_v = on_floor(visibility(&gpu(&mut renderer, &pass), &gpu_off));
        let ref_cast = on_floor(visibility(&reference::render(&cast), &ref_off));
        let gpu_cast = on_floor(visibility(&gpu(&mut renderer, &cast), &gpu_off));
        for (name, v, v_cast) in [("reference", &ref_v, &ref_cast), ("GPU", &gpu_v, &gpu_cast)] {
            let floor = v.iter().flatten().count();
            let lit = v.iter().flatten().filter(|&&a| a >= 0.5).count();
            let lit_cast = v_cast.iter().flatten().filter(|&&a| a >= 0.5).count();
            eprintln!(
                "(g) {kind}, {name}: {lit} of {floor} floor px lit with markers passing, {lit_cast} with markers casting"
            );
            assert!(floor > 5_000, "{kind}, {name}: too few floor pixels");
            assert_eq!(lit, floor, "{kind}, {name}: the marker shadows its light");
            assert_eq!(
                lit_cast, 0,
                "{kind}, {name}: a closed caster around the light let it through"
            );
        }
        let r = mask_report(&pass, 0, &view, &gpu_v, &ref_v);
        eprintln!("(g) {kind}: GPU vs reference mask: {r:?}");
        assert_eq!(
            r.outside_band, 0,
            "{kind}: mismatches outside the band: {r:?}"
        );
    }
}
