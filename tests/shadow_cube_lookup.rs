//! The cube lookup's clip coordinates written out (`shadow_cube_clip` in
//! shaders/shadows.wgsl) are the face matrix's product with the lookup
//! point, bit for bit, on the GPU the tests run on.
//!
//! A compute shader runs the renderer's own `shadow_cube_face` and
//! `shadow_cube_clip` (shaders/shadows.wgsl as the renderer composes it,
//! included, not copied) and, beside them, `clip_from_world * (p, 1)` with
//! the face's matrix from the same uniform array the scene pass reads. The
//! lights and views are those `ShadowPlan` makes for shadowed point lights
//! at positions off the dyadic grid, with map sides whose margins give
//! different fields of view; the points surround each light in every
//! direction, from a millimetre to a hundred metres, with extra points a
//! few ulps either side of the faces' diagonal planes (where the face
//! choice flips). Every coordinate must have the same bits (±0 count as
//! equal: the matrix adds signed zero terms; only `w ≤ 0` reads a sign of
//! zero, and it reads both alike).

mod common;

use glam::{DVec3, Vec3};
use gonio::gpu::bindings::{UNIFORM_LIGHTS, UNIFORM_SHADOW_VIEWS, array_bytes};
use gonio::gpu::layout::{GpuLight, GpuShadowView};
use gonio::gpu::prepared::gpu_lights;
use gonio::gpu::shader_gen::{Feature, common as common_wgsl, preprocess, sources};
use gonio::gpu::shadows::ShadowPlan;
use gonio::scene::scene_file::{self, SceneSource};
use wgpu::util::DeviceExt;

/// Light positions: off the dyadic grid, near and far from the scene.
const LIGHTS: [[f64; 3]; 4] = [
    [2.5, 2.5, 2.0],
    [-0.3, 1.7, 0.1],
    [0.123456, 3.21, -2.6180339],
    [-7.77, 0.9, 5.5],
];

/// The compute shader: the renderer's shadow code, then an entry point
/// writing both clip vectors of every sample.
fn source() -> String {
    let features = [
        Feature::UniformLights,
        Feature::UniformShadowViews,
        Feature::Shadows,
        Feature::ShadowCube,
        Feature::ShadowProjective,
        Feature::ShadowPixel,
    ];
    let mut src = common_wgsl(&features);
    src.push_str(
        &preprocess(
            "shaders/shadows.wgsl",
            sources::get("shadows.wgsl"),
            &features,
        )
        .unwrap(),
    );
    src.push_str(
        r#"
const PCF_RADIUS: u32 = 1u;

struct CubeSample {
    p: vec3<f32>,
    light: u32,
}

@group(2) @binding(0) var<storage, read> cube_samples: array<CubeSample>;
@group(2) @binding(1) var<storage, read_write> cube_results: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&cube_samples) {
        return;
    }
    let s = cube_samples[i];
    let light = lights[s.light];
    let v = s.p - light.shadow_origin;
    let a = abs(v);
    let face = shadow_cube_face(v, a);
    let layer = light.shadow_layer + face;
    let near = shadow_views[layer].clip_from_world[3].z;
    cube_results[2u * i] = shadow_cube_clip(light, face, s.p, a, near);
    cube_results[2u * i + 1u] = shadow_views[layer].clip_from_world * vec4<f32>(s.p, 1.0);
}
"#,
    );
    src
}

/// Points around `origin`: Fibonacci-sphere directions at distances from
/// 10⁻³ to 10², and points a few ulps off the planes |x| = |y|, |y| = |z|,
/// |x| = |z| through the origin.
fn points_around(origin: Vec3) -> Vec<Vec3> {
    let mut points = Vec::new();
    let n = 4096;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for k in 0..n {
        let y = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
        let r = (1.0 - y * y).sqrt();
        let phi = golden * k as f64;
        let dir = DVec3::new(r * phi.cos(), y, r * phi.sin());
        for distance in [1e-3, 0.37, 1.0, 3.3, 12.5, 100.0] {
            points.push(origin + (dir * distance).as_vec3());
        }
    }
    for k in 0..512 {
        let t = 0.1 + 3.0 * k as f32 / 512.0;
        let signs = [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)];
        for (sa, sb) in signs {
            for ulps in -3i32..=3 {
                let b = f32::from_bits((t.to_bits() as i32 + ulps) as u32);
                let c = 0.5 * t;
                points.push(origin + Vec3::new(sa * t, sb * b, c));
                points.push(origin + Vec3::new(c, sa * t, sb * b));
                points.push(origin + Vec3::new(sa * t, c, sb * b));
            }
        }
    }
    points
}

#[test]
fn written_out_cube_coordinates_equal_the_face_matrix_product() {
    let renderer = common::gpu_renderer();
    let ctx = renderer.context();
    let mut compared = 0;
    for map_size in [16, 256, 1024] {
        let scene = scene_file::load(
            &SceneSource::BuiltIn,
            &[
                common::shadowed_point_lights(&LIGHTS),
                format!("shadows.map_size={map_size}"),
            ],
        )
        .unwrap();
        let plan = ShadowPlan::new(&scene);
        let lights: Vec<GpuLight> = gpu_lights(&scene, &plan);
        assert!(lights.iter().all(|g| g.shadow_projection == 2), "cubes");
        let views: Vec<GpuShadowView> = plan.gpu_views();
        let mut samples: Vec<[u32; 4]> = Vec::new();
        for (l, g) in lights.iter().enumerate() {
            for p in points_around(Vec3::from(g.shadow_origin)) {
                samples.push([p.x.to_bits(), p.y.to_bits(), p.z.to_bits(), l as u32]);
            }
        }
        let src = source();
        gonio::gpu::shader_gen::validate(&src).unwrap_or_else(|e| panic!("{e}"));
        let init = |contents: &[u8], usage| {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: None,
                    contents,
                    usage,
                })
        };
        // Uniform arrays cover their declared capacity (src/gpu/bindings.rs).
        let uniform_array = |contents: &[u8], capacity, element| {
            init(
                &array_bytes(contents, true, capacity, element),
                wgpu::BufferUsages::UNIFORM,
            )
        };
        let lights_buffer = uniform_array(
            bytemuck::cast_slice(&lights),
            UNIFORM_LIGHTS,
            size_of::<GpuLight>(),
        );
        let views_buffer = uniform_array(
            bytemuck::cast_slice(&views),
            UNIFORM_SHADOW_VIEWS,
            size_of::<GpuShadowView>(),
        );
        let samples_buffer = init(bytemuck::cast_slice(&samples), wgpu::BufferUsages::STORAGE);
        let results = common::compute_output(ctx, (samples.len() * 2 * 16) as u64);
        let bytes = common::run_compute(
            ctx,
            "shadow cube lookup",
            &src,
            &[
                (0, vec![(2, &lights_buffer)]),
                (1, vec![(2, &views_buffer)]),
                (2, vec![(0, &samples_buffer), (1, &results)]),
            ],
            samples.len(),
            &results,
        );
        let out: Vec<[f32; 4]> = bytemuck::cast_slice(&bytes).to_vec();
        let same = |a: f32, b: f32| a.to_bits() == b.to_bits() || (a == 0.0 && b == 0.0);
        for (k, pair) in out.chunks(2).enumerate() {
            let (written, product) = (pair[0], pair[1]);
            assert!(
                (0..4).all(|c| same(written[c], product[c])),
                "map {map_size}², sample {k} {:?}: written out {written:?}, matrix {product:?}",
                samples[k]
            );
            assert!(product[2] > 0.0, "a drawn face's near is positive");
        }
        compared += out.len() / 2;
    }
    println!("{compared} lookups compared, every coordinate equal");
    assert!(compared > 300_000);
}
