//! `shading.shadow_coords = "vertex"` against `"exact"` on a spot-lit
//! scene: the pixels that differ lie within the band docs/shadows.md
//! derives ("Coordinates per vertex for a spot light").
//!
//! The per-vertex path reads the map at `p̃ = Σ λ_i p(x_i)` instead of
//! `p(x)`. With the default offsets (normal offset only) `p̃ − p(x)` lies
//! along the face normal `n`, between 0 and the bound
//! `δ = shadow_coords::displacement_bound` (`c·τ·S₂/(2·r_min)`), so `p̃`
//! is on the segment `[p, p + δ·n]`, whose image in the map has length
//! `Δ` texels (a segment projects to a segment). A `k×k` PCF lookup at a
//! map point reads texel centres within `k/2` texels per axis of it; if
//! every centre the two lookups read lies on one side of the caster's
//! outline, both find the same fraction lit (the floor is acne-free with
//! the default offset, and the per-vertex point is only farther along
//! the normal). So a pixel that differs has its exact lookup point within
//! `Δ + k/√2` map texels of the outline. In angles seen from the light
//! (the map is a gnomonic projection, whose inverse shrinks distances: a
//! map distance of `D` texels spans at most `D·τ` radians, `τ` the texel
//! at unit distance on the axis), its direction is within `(Δ + k/√2)·τ`
//! of the sphere's tangent cone. The tessellated sphere's outline lies
//! between the cones of its inscribed and circumscribed spheres; the
//! remaining slack (0.01 texel) covers the f32 map coordinates (about
//! 10⁻³ texel at 2048 texels, tests/shadows.rs (e)).

mod common;

use glam::{DVec3, DVec4};
use gonio::frame::Frame;
use gonio::gpu::shadows::ShadowPlan;
use gonio::scene::bvh::Bvh;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::shadow_coords::{LookupOffsets, displacement_bound, lookup_point};
use gonio::scene::{Scene, ShadowCoords};

fn spot_scene() -> Scene {
    let path =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/spot-bench.toml");
    let sets: Vec<String> = [
        "image.width=480",
        "image.height=270",
        "ambient.radiance=0.0",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    scene_file::load(&SceneSource::File(path), &sets).unwrap_or_else(|e| panic!("{e}"))
}

fn render(renderer: &mut gonio::gpu::GpuRenderer, scene: &Scene) -> Frame {
    let (frame, _) = renderer.render(scene).expect("GPU render");
    assert!(frame.radiance.iter().flatten().all(|v| v.is_finite()));
    frame
}

#[test]
fn vertex_shadow_coords_differ_only_within_the_derived_band() {
    let mut renderer = common::gpu_renderer();
    let mut scene = spot_scene();
    assert_eq!(scene.shadow_coords, ShadowCoords::Exact);
    let exact = render(&mut renderer, &scene);
    scene.shadow_coords = ShadowCoords::Vertex;
    let vertex = render(&mut renderer, &scene);
    let mut unshadowed_scene = scene.clone();
    unshadowed_scene
        .lights
        .iter_mut()
        .for_each(|l| l.set_shadows(false));
    let unshadowed = render(&mut renderer, &unshadowed_scene);

    // The one map: the spot light's perspective layer.
    let plan = ShadowPlan::new(&scene);
    let shadow = plan.lights[0].expect("the spot light casts shadows");
    let settings = shadow.settings;
    assert_eq!((settings.bias, settings.slope_bias), (0.0, 0.0));
    let kernel = settings.filter.kernel() as f64;
    let layer = plan.layers[shadow.first_layer as usize];
    let size = layer.map_size as f64;
    let offsets = LookupOffsets {
        normal_offset: settings.normal_offset,
        bias: settings.bias,
        slope_bias: settings.slope_bias,
        texel: shadow.texel,
    };
    let light = shadow.origin;
    let uv = |q: DVec3| {
        let clip: DVec4 = layer.clip_from_world * q.extend(1.0);
        assert!(clip.w > 0.0);
        let ndc = clip.truncate() / clip.w;
        glam::DVec2::new(ndc.x * 0.5 + 0.5, -ndc.y * 0.5 + 0.5) * size
    };

    // The caster: the sphere (the mesh with the most triangles), its
    // tangent cones from the light for the inscribed and the
    // circumscribed sphere of the tessellation.
    let sphere = scene.meshes.iter().max_by_key(|m| m.indices.len()).unwrap();
    let (lo, hi) = gonio::scene::mesh::bounds(sphere.positions.iter().copied()).unwrap();
    let centre = 0.5 * (lo + hi);
    let radius = sphere
        .positions
        .iter()
        .map(|p| (*p - centre).length())
        .fold(0.0, f64::max);
    let inscribed = sphere
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| sphere.positions[i as usize]);
            let n = (b - a).cross(c - a).normalize();
            n.dot(a - centre).abs()
        })
        .fold(f64::MAX, f64::min);
    let to_centre = centre - light;
    let cone_in = (inscribed / to_centre.length()).asin();
    let cone_out = (radius / to_centre.length()).asin();

    let bvh = Bvh::new(&scene.meshes);
    let rays = scene.camera.rays(scene.width, scene.height);
    let slack = 0.01;
    let (mut covered, mut differ, mut not_whole_taps, mut outside) = (0, 0, 0, Vec::new());
    let (mut beyond_kernel, mut widest) = (0usize, 0.0f64);
    for i in 0..exact.radiance.len() {
        if !exact.coverage[i] {
            continue;
        }
        covered += 1;
        let (a, b, full) = (
            vertex.radiance[i],
            exact.radiance[i],
            unshadowed.radiance[i],
        );
        if (0..3).all(|c| (a[c] - b[c]).abs() <= 1e-5 * full[c].abs().max(1e-30)) {
            continue;
        }
        differ += 1;
        // V differs by whole taps of the k×k kernel.
        let c = (0..3).max_by(|&p, &q| full[p].total_cmp(&full[q])).unwrap();
        let taps = kernel * kernel * f64::from(a[c] - b[c]) / f64::from(full[c]);
        if (taps - taps.round()).abs() > 1e-3 {
            not_whole_taps += 1;
        }
        // The pixel's point, triangle and barycentrics.
        let (row, col) = (i as u32 / scene.width, i as u32 % scene.width);
        let ray = rays.ray(col as f64 + 0.5, row as f64 + 0.5);
        let hit = bvh
            .intersect(&ray, 0.0, f64::INFINITY)
            .expect("covered pixel");
        let mesh = &scene.meshes[hit.id.mesh as usize];
        let corners = mesh.indices[hit.id.triangle as usize].map(|k| mesh.positions[k as usize]);
        let lambda = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let x = lambda[0] * corners[0] + lambda[1] * corners[1] + lambda[2] * corners[2];
        let mut n = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize();
        if n.dot(light - x) < 0.0 {
            n = -n;
        }
        let p = lookup_point(&offsets, light, x, n);
        let Some(delta) = displacement_bound(&offsets, light, corners, lambda) else {
            continue; // grazing: no bound claimed
        };
        let shift = (uv(p + n * delta) - uv(p)).length();
        let band = (shift + kernel / std::f64::consts::SQRT_2 + slack) * shadow.texel;
        let angle = (p - light).angle_between(to_centre);
        let off = (cone_in - angle).max(angle - cone_out).max(0.0);
        widest = widest.max(shift);
        if off > (kernel / std::f64::consts::SQRT_2 + slack) * shadow.texel {
            beyond_kernel += 1;
        }
        if off > band {
            outside.push((row, col, off / shadow.texel, band / shadow.texel));
        }
    }
    println!(
        "spot-bench 480x270: {differ} of {covered} pixels differ, {not_whole_taps} not by whole taps, \
         {beyond_kernel} farther from the outline than the kernel alone allows, \
         {} outside the band; widest Δ {widest:.3} texels",
        outside.len()
    );
    assert!(covered > 50_000, "too few pixels: {covered}");
    // Not vacuous: the approximation shows on this scene.
    assert!(differ >= 20, "only {differ} pixels differ");
    assert_eq!(not_whole_taps, 0, "differences other than whole taps");
    assert!(
        outside.is_empty(),
        "{} differing pixels outside the band (row, col, distance, band in texels): {:?}",
        outside.len(),
        &outside[..outside.len().min(10)]
    );
}
