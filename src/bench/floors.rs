//! The floors every cost is divided by, measured in the same run:
//!
//! * an **unlit pass** over the scene's own vertex stream (transform and
//!   rasterize, write a constant): what any shading costs above nothing;
//! * a **hand-minimal shader** for a Lambert scene with one unshadowed
//!   point light: the least code that draws the same image, written by
//!   hand, to show that specialization leaves nothing on the table;
//! * a **minimal triangle-to-PNG program**: open the device, build one
//!   pipeline, draw one triangle, read it back, encode and write a PNG.
//!   It runs as `gonio bench --floor-triangle-png OUT` so that it pays the
//!   same process start-up and driver load as `gonio render`.
//!
//! Also here: the uber shader key (every model, every term, every light
//! kind compiled in) for the uber-vs-specialized comparison.

use super::harness::{HarnessShader, Inputs};
use crate::gpu::formats::COLOR_FORMAT;
use crate::gpu::readback::Readback;
use crate::gpu::shader_gen::{self, LightsKey, MaterialsKey, ShaderKey, sources};
use crate::gpu::shadows::ShadowPlan;
use crate::gpu::{AdapterChoice, GpuContext};
use crate::output::OutputFile;
use crate::scene::{LightKind, Scene};
use crate::{Error, Result};
use std::path::Path;

/// Transform and rasterize; the fragment writes a constant.
const UNLIT_WGSL: &str = r#"
@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return globals.clip_from_world * vec4<f32>(position, 1.0);
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return vec4<f32>(1.0);
}
"#;

/// Lambert with one point light and ambient, per pixel, written by hand:
/// `L_o = k_a·L_a + (k_d/π) · I/d² · cosθ`, one-sided as every gonio
/// model is (zero where N·I ≤ 0 or N·V ≤ 0).
const MINIMAL_LAMBERT_WGSL: &str = r#"
struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> Varyings {
    return Varyings(globals.clip_from_world * vec4<f32>(position, 1.0), position, normal);
}

@fragment
fn fs_main(in: Varyings) -> @location(0) vec4<f32> {
    let m = material; // the draw's (src/gpu/bindings.rs)
    let light = lights[0];
    let n = normalize_or_zero(in.normal);
    let to_light = light.position - in.world;
    let d2 = dot(to_light, to_light);
    let cos_i = dot(n, to_light) * inverseSqrt(d2);
    let lit = cos_i > 0.0 && dot(n, globals.eye - in.world) > 0.0;
    let direct = m.k_d * FRAC_1_PI * light.intensity * (select(0.0, cos_i, lit) / d2);
    return vec4<f32>(m.k_a * globals.ambient + direct, 1.0);
}
"#;

/// The hand-minimal shader with the generated shader's generic light
/// loop instead of its one inline light: every light read from the
/// lights buffer in a loop over `light_count`, through the shared
/// `point_incidence` (inverse-square law with the optional range window
/// and the zero-distance guard). Splits the specialization gap into "the
/// light loop" and "the rest".
const MINIMAL_LAMBERT_LOOP_WGSL: &str = r#"
struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> Varyings {
    return Varyings(globals.clip_from_world * vec4<f32>(position, 1.0), position, normal);
}

@fragment
fn fs_main(in: Varyings) -> @location(0) vec4<f32> {
    let m = material; // the draw's (src/gpu/bindings.rs)
    let n = normalize_or_zero(in.normal);
    let to_eye = globals.eye - in.world;
    var radiance = m.k_a * globals.ambient;
    for (var l = 0u; l < globals.light_count; l++) {
        let incidence = point_incidence(lights[l], in.world);
        let cos_i = dot(n, incidence.wi);
        if cos_i <= 0.0 || dot(n, to_eye) <= 0.0 {
            continue;
        }
        radiance += m.k_d * FRAC_1_PI * incidence.irradiance * cos_i;
    }
    return vec4<f32>(radiance, 1.0);
}
"#;

/// [`minimal_lambert`] with the generic light loop (see
/// `MINIMAL_LAMBERT_LOOP_WGSL`).
pub fn minimal_lambert_loop(scene: &Scene) -> HarnessShader {
    HarnessShader {
        label: "hand-minimal Lambert, generic light loop".into(),
        wgsl: format!(
            "{}{}{}{MINIMAL_LAMBERT_LOOP_WGSL}",
            common(scene),
            generic_inverse_square(),
            sources::get("lights/point.wgsl")
        ),
        inputs: Inputs::PositionNormal,
        key: specialized_key(scene),
    }
}

/// `shaders/lights/inverse_square.wgsl` as a generic light loop has it:
/// with the range window and the zero-distance guard (the features a
/// specialized key compiles only where a light needs them).
fn generic_inverse_square() -> String {
    let path = "lights/inverse_square.wgsl";
    shader_gen::preprocess(
        &format!("shaders/{path}"),
        sources::get(path),
        &[
            shader_gen::Feature::LightRange,
            shader_gen::Feature::LightGuard,
        ],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// `shaders/common.wgsl` with the bindings the harness gives `scene`
/// (those of its specialized key).
fn common(scene: &Scene) -> String {
    shader_gen::common(&specialized_key(scene).features())
}

/// The unlit floor for `scene`'s geometry.
pub fn unlit(scene: &Scene) -> HarnessShader {
    HarnessShader {
        label: "unlit floor".into(),
        wgsl: format!("{}{UNLIT_WGSL}", common(scene)),
        inputs: Inputs::Position,
        key: specialized_key(scene),
    }
}

/// The hand-minimal Lambert + one point light shader. Only meaningful for
/// a scene that is exactly that (see [`is_lambert_one_point_light`]).
pub fn minimal_lambert(scene: &Scene) -> HarnessShader {
    HarnessShader {
        label: "hand-minimal Lambert".into(),
        wgsl: format!("{}{MINIMAL_LAMBERT_WGSL}", common(scene)),
        inputs: Inputs::PositionNormal,
        key: specialized_key(scene),
    }
}

/// Whether `scene` is what the hand-minimal shader draws: per-pixel
/// shading, Lambert materials only, one point light without shadows or
/// range, no mirror.
pub fn is_lambert_one_point_light(scene: &Scene) -> bool {
    let key = ShaderKey::new(scene, &ShadowPlan::new(scene));
    scene.shading == crate::scene::ShadingMode::Phong
        && key
            .variants
            .iter()
            .all(|v| v.model == crate::material::ReflectanceModel::Lambert)
        && matches!(
            scene.lights.as_slice(),
            [crate::scene::Light::Point {
                range: None,
                shadows: false,
                ..
            }]
        )
}

/// The uber shader for `scene`: the scene's shading mode with every
/// reflectance model and every term of the configurable ones (each
/// Cook-Torrance distribution, geometry term, Fresnel term and
/// denominator, each mirror Fresnel) and every light kind, dispatched at
/// run time by `switch` (what a renderer without specialization would
/// ship), plus the scene's own variants. No shadow code (the harness
/// draws no shadow maps).
///
/// Not the full cross product of Cook-Torrance terms (192 variants): on
/// Mesa 22.3 lavapipe a generated shader with more than about 75 variants
/// compiles but draws without its direct lighting (found by this bench's
/// image check), so the uber shader takes each term once (25 variants).
pub fn uber_key(scene: &Scene) -> ShaderKey {
    let scene_key = ShaderKey::new(scene, &ShadowPlan::new(scene));
    let mut variants = scene_key.variants.clone();
    // A measured material needs its tables bound (group 0, binding 3),
    // which only a scene with one has: the uber shader takes it from the
    // scene's own variants only.
    variants.extend(
        crate::material::table::each_term_once()
            .iter()
            .filter(|m| m.model != crate::material::ReflectanceModel::Measured)
            .map(|m| m.variant()),
    );
    ShaderKey {
        shading: scene.shading,
        variants,
        // Any light may have a range or sit on a surface, as an uber
        // shader must allow.
        lights: LightsKey {
            kinds: LightKind::ALL.into(),
            ..Default::default()
        }
        .with_flags(true),
        // The same buffers as the specialized shader: only the code differs.
        arrays: scene_key.arrays,
        materials: MaterialsKey {
            // The buffer holds networks or tables, and the globals the
            // albedo table, as the scene says: the same measured and
            // compensation code as the specialized shader.
            measured_network: scene_key.materials.measured_network,
            energy_compensation: scene_key.materials.energy_compensation,
            // Any material may emit or be occluded, as an uber shader must
            // allow.
            emission: true,
            occlusion: true,
            // The same G1 form as the specialized shader.
            smith_beckmann_rational: scene_key.materials.smith_beckmann_rational,
            ..Default::default()
        },
        tone_map: scene.tone_map,
        // No shadow, environment or texture code; the light count read
        // at run time, as an uber shader must.
        ..Default::default()
    }
}

/// The scene's own specialized key without shadow, environment,
/// texture or transmission-image code (for the harness, which binds group 0 alone, as [`uber_key`]).
pub fn specialized_key(scene: &Scene) -> ShaderKey {
    let mut key = ShaderKey::new(scene, &ShadowPlan::new(scene));
    key.shadows.maps = Default::default();
    key.environment = Default::default();
    key.materials.texture_slots = 0;
    key.materials.texture_bindings = 0;
    // Nor the transmission image's read (bind group 4, which the harness
    // does not bind): a transmissive material's reflection alone.
    key.materials.layer_transmission = false;
    key.materials.transmission_exit = false;
    key.materials.transmission_dispersion = false;
    key.materials.transmission_exit_traced = false;
    key
}

/// The minimal triangle-to-PNG program (run by `gonio bench
/// --floor-triangle-png OUT`): the least a GPU program that writes an
/// image must do.
pub fn triangle_to_png(out: &Path, adapter: Option<&str>) -> Result<()> {
    let output = OutputFile::prepare(out)?;
    let ctx = GpuContext::new(&AdapterChoice::from_flag_or_env(adapter))?;
    ctx.require_float_radiance("gonio bench")?;
    let (width, height) = (640u32, 480u32);
    let device = &ctx.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("triangle"),
        source: wgpu::ShaderSource::Wgsl(
            r#"
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = array(vec2<f32>(-0.8, -0.8), vec2<f32>(0.8, -0.8), vec2<f32>(0.0, 0.8));
    return vec4<f32>(p[i], 0.0, 1.0);
}
@fragment
fn fs_main() -> @location(0) vec4<f32> {
    return vec4<f32>(0.8, 0.2, 0.1, 1.0);
}
"#
            .into(),
        ),
    });
    let format = COLOR_FORMAT;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("triangle"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let size = wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("triangle"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let readback = Readback::new(device, width, height);
    let view = texture.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("triangle"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.draw(0..3, 0..1);
    }
    readback.copy_from(&mut encoder, &texture);
    ctx.queue.submit([encoder.finish()]);
    let frame = readback.read(device)?;
    if !frame.coverage.iter().any(|&c| c) {
        return Err(Error::Gpu("the floor triangle drew nothing".into()));
    }
    output.write(&frame, 0.0)
}
