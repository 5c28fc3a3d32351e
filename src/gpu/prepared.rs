//! A scene uploaded once and drawn many times.
//!
//! `gonio render` draws a scene once; the viewer and the bench draw it
//! every frame. Both go through [`PreparedScene`]: the vertex stream,
//! the parameter buffers and the shadow maps live on the GPU between
//! frames, and [`PreparedScene::update`] rewrites only what a change
//! touches (a camera move writes 144 bytes of globals; a new roughness
//! writes the material buffer; a light change re-plans and re-renders the
//! shadow maps once). The shadow maps are drawn only when they are stale,
//! so orbiting the camera costs one scene pass per frame.
//!
//! The scene's compiled code comes from the [`PipelineCache`] it is
//! given; the stream and the bind group are a [`SceneDraw`].

use super::bind_groups;
use super::bindings::{self, UniformArrays};
use super::context::GpuContext;
use super::draw::{self, FrameTarget, SceneDraw};
use super::geometry::GeometryData;
use super::layout::{GpuGlobals, GpuLight};
use super::pipelines::PipelineCache;
use super::shader_gen::ShaderKey;
use super::shadows::{self, ShadowPlan};
use crate::scene::Scene;
use crate::{Error, Result};
use wgpu::util::DeviceExt;

/// A scene's GPU resources, ready to draw into a colour target of
/// `format`.
pub struct PreparedScene {
    /// The features compiled for this scene.
    pub key: ShaderKey,
    /// The colour target format the pipeline writes (decides
    /// [`super::shader_gen::Output`]).
    pub format: wgpu::TextureFormat,
    /// `2^exposure`, applied by display targets only.
    pub display_scale: f32,
    /// Samples per pixel of the targets it draws into.
    pub samples: u32,
    /// Triangles drawn per scene pass.
    pub triangles: u64,
    /// Bytes of vertex and index data on the GPU.
    pub geometry_bytes: u64,
    /// The stream, its batches and the scene bind group.
    draw: SceneDraw,
    /// For each batch, the variant it is drawn with and that pipeline
    /// (resolved when the scene changes, so a frame looks nothing up).
    batch_pipelines: Vec<(Option<u32>, wgpu::RenderPipeline)>,
    /// The light data last uploaded, to tell whether the maps are stale.
    lights: Vec<GpuLight>,
    plan: ShadowPlan,
    shadows: Option<ShadowResources>,
    /// The shadow maps must be drawn before the next scene pass.
    shadows_stale: bool,
}

/// The shadow-map array and the bind groups that read and fill it, and
/// the depth-only pipeline that fills it.
struct ShadowResources {
    layer_views: Vec<wgpu::TextureView>,
    scene_group: wgpu::BindGroup,
    pass_group: wgpu::BindGroup,
    pass_pipeline: wgpu::RenderPipeline,
}

/// What one [`PreparedScene::encode`] drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Drawn {
    /// Shadow-map layers rendered (0 when the maps were current).
    pub shadow_layers: usize,
}

impl PreparedScene {
    /// Uploads `scene` for drawing into targets of `format` (`Rgba32Float`:
    /// linear radiance; an 8-bit format: display) with `samples` samples
    /// per pixel, compiling what it needs into `cache`.
    /// `vertex_shadow_coords`: see [`ShaderKey::shadow_coords_per_vertex`].
    pub fn new(
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &Scene,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<Self> {
        check_drawable(scene)?;
        let (key, plan) = plan(&ctx.device, vertex_shadow_coords, scene)?;
        let geometry =
            GeometryData::new(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
        cache.compile_scene(&key, geometry.layout, format, samples)?;
        let arrays = key.arrays;
        let materials = draw::gpu_materials(scene, &key);
        let lights = gpu_lights(scene, &plan);
        let draw = SceneDraw::new(
            &ctx.device,
            cache.scene_layouts(arrays),
            geometry,
            arrays,
            &GpuGlobals::new(scene),
            &materials,
            &lights,
        );
        let shadows = shadow_resources(&ctx.device, cache, &plan, arrays, draw.layout.stride());
        let batch_pipelines = batch_pipelines(cache, &key, format, samples, &materials, &draw);
        Ok(PreparedScene {
            key,
            format,
            display_scale: 1.0,
            samples,
            triangles: scene.triangle_count() as u64,
            geometry_bytes: draw.geometry_bytes,
            draw,
            batch_pipelines,
            lights,
            shadows_stale: shadows.is_some(),
            plan,
            shadows,
        })
    }

    /// Brings this scene up to date with `scene`, which must have the same
    /// meshes as the scene it was prepared from (reload the file: prepare
    /// anew). Writes only what changed; a change of the shader features
    /// selects (or compiles, once) another cached pipeline; a change of
    /// the vertex stream (shading mode, tangents) rebuilds it.
    pub fn update(
        &mut self,
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &Scene,
    ) -> Result<()> {
        check_drawable(scene)?;
        let (key, plan) = plan(&ctx.device, vertex_shadow_coords, scene)?;
        let layout = self.draw.layout;
        if key.shading != self.key.shading
            || key.needs_tangents() != layout.tangents
            || key.shadow_coords_per_vertex() != layout.face_normal
        {
            let display_scale = self.display_scale;
            *self = Self::new(
                ctx,
                cache,
                vertex_shadow_coords,
                scene,
                self.format,
                self.samples,
            )?;
            self.display_scale = display_scale;
            return Ok(());
        }
        cache.compile_scene(&key, layout, self.format, self.samples)?;
        self.update_view(ctx, scene);

        let arrays = key.arrays;
        let materials = draw::gpu_materials(scene, &key);
        let lights = gpu_lights(scene, &plan);
        self.draw.write_parameters(
            &ctx.device,
            &ctx.queue,
            cache.scene_layouts(arrays),
            arrays,
            &materials,
            &lights,
        );
        let lights_changed = bytemuck::cast_slice::<GpuLight, u8>(&self.lights)
            != bytemuck::cast_slice::<GpuLight, u8>(&lights);
        if lights_changed
            || plan != self.plan
            || key.shadows != self.key.shadows
            || arrays != self.key.arrays
        {
            self.shadows = shadow_resources(&ctx.device, cache, &plan, arrays, layout.stride());
            self.shadows_stale = self.shadows.is_some();
            self.plan = plan;
        }
        self.lights = lights;
        self.batch_pipelines = batch_pipelines(
            cache,
            &key,
            self.format,
            self.samples,
            &materials,
            &self.draw,
        );
        self.key = key;
        Ok(())
    }

    /// Writes only the per-view values of `scene` (camera, image size,
    /// ambient, environment, exposure): what a camera move changes. The
    /// shadow maps do not depend on the camera, so they stay.
    pub fn update_view(&self, ctx: &GpuContext, scene: &Scene) {
        let mut globals = GpuGlobals::new(scene);
        globals.display_scale = self.display_scale;
        self.draw.write_globals(&ctx.queue, &globals);
    }

    /// Records the shadow passes (if the maps are stale) and the scene
    /// pass into `encoder`. The scene pass clears the whole target to
    /// transparent black (coverage 0) and draws into the viewport.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, target: &FrameTarget) -> Drawn {
        let mut drawn = Drawn::default();
        if let (Some(shadows), true) = (&self.shadows, self.shadows_stale) {
            let last = shadows.layer_views.len() - 1;
            for (i, (layer, view)) in self
                .plan
                .layers
                .iter()
                .zip(&shadows.layer_views)
                .enumerate()
            {
                let timestamp_writes = target.timestamps.and_then(|set| {
                    (i == 0 || i == last).then_some(wgpu::RenderPassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: (i == 0).then_some(2),
                        end_of_pass_write_index: (i == last).then_some(3),
                    })
                });
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("shadow map"),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view,
                        depth_ops: Some(wgpu::Operations {
                            // Reversed depth: 0 is "nothing here".
                            load: wgpu::LoadOp::Clear(0.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                let size = layer.map_size as f32;
                pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
                pass.set_pipeline(&shadows.pass_pipeline);
                pass.set_bind_group(0, &shadows.pass_group, &[]);
                self.draw.draw_all(&mut pass, i as u32..i as u32 + 1);
            }
            drawn.shadow_layers = shadows.layer_views.len();
            self.shadows_stale = false;
        }
        let mut pass = draw::begin_scene_pass(encoder, target);
        if let Some(shadows) = &self.shadows {
            pass.set_bind_group(1, &shadows.scene_group, &[]);
        }
        self.draw.bind_geometry(&mut pass);
        // Each material's batch with its material bound (src/gpu/bindings.rs)
        // and the pipeline of its BRDF variant (consecutive batches of one
        // variant share the bind).
        let mut bound = None;
        for (batch, (variant, pipeline)) in self.draw.batches().iter().zip(&self.batch_pipelines) {
            if bound != Some(*variant) {
                pass.set_pipeline(pipeline);
                bound = Some(*variant);
            }
            self.draw.draw_batch(&mut pass, batch);
        }
        drawn
    }

    /// Shadow-map layers this scene renders when its maps are stale.
    pub fn shadow_layers(&self) -> usize {
        self.plan.layers.len()
    }

    /// Marks the shadow maps stale (the bench re-renders them each frame
    /// to measure their cost).
    pub fn invalidate_shadows(&mut self) {
        self.shadows_stale = self.shadows.is_some();
    }
}

/// A scene without a material or a light cannot be drawn.
fn check_drawable(scene: &Scene) -> Result<()> {
    if scene.materials.is_empty() || scene.lights.is_empty() {
        return Err(Error::Scene(
            "it needs at least one material and one light".into(),
        ));
    }
    Ok(())
}

/// The shader key and shadow plan of `scene`, checked against the
/// device's limits.
fn plan(
    device: &wgpu::Device,
    vertex_shadow_coords: bool,
    scene: &Scene,
) -> Result<(ShaderKey, ShadowPlan)> {
    let mut key = ShaderKey::for_scene(scene);
    key.vertex_shadow_coords = vertex_shadow_coords;
    let plan = if key.shadows.any() {
        ShadowPlan::new(scene)
    } else {
        ShadowPlan::default()
    };
    if plan.is_empty() {
        // Nothing to cast a shadow on (no geometry): no shadow code.
        key.shadows = Default::default();
        key.counts.shadow_maps = 0;
        key.counts.pcf_radius = None;
    }
    debug_assert_eq!(key.counts.shadow_maps as usize, plan.casters.len());
    check_shadow_limits(device, &plan)?;
    Ok((key, plan))
}

/// Refuses shadow maps the device cannot hold, naming the setting to
/// lower.
fn check_shadow_limits(device: &wgpu::Device, plan: &ShadowPlan) -> Result<()> {
    if plan.is_empty() {
        return Ok(());
    }
    let limits = device.limits();
    let problem = if plan.casters.len() > shadows::MAX_SHADOW_MAPS {
        Some(format!(
            "{} lights cast shadows through their own maps (an area light with shadow_per_sample counts each sample); at most {} can",
            plan.casters.len(),
            shadows::MAX_SHADOW_MAPS
        ))
    } else if plan.side > limits.max_texture_dimension_2d {
        Some(format!(
            "a shadow map of {0}x{0} texels is larger than the GPU's maximum texture side of {1}",
            plan.side, limits.max_texture_dimension_2d
        ))
    } else if plan.layers.len() as u32 > limits.max_texture_array_layers {
        Some(format!(
            "the shadow maps need {} layers (6 per point or area light, 1 per directional or spot light); the GPU allows {}",
            plan.layers.len(),
            limits.max_texture_array_layers
        ))
    } else if plan.bytes() > shadows::MAX_SHADOW_BYTES {
        Some(format!(
            "the shadow maps need {} MiB ({} layers of {}x{} texels, every layer as large as the largest map); at most {} MiB",
            plan.bytes() >> 20,
            plan.layers.len(),
            plan.side,
            plan.side,
            shadows::MAX_SHADOW_BYTES >> 20
        ))
    } else {
        None
    };
    match problem {
        Some(p) => Err(Error::argument(
            "shadow_map_size",
            format!("{p}; lower shadow_map_size or turn shadows off for some lights"),
        )),
        None => Ok(()),
    }
}

/// The shadow-map array of `plan` with one view per layer to render
/// into, the bind groups that read and fill it and the depth-only
/// pipeline for a stream of `stride` bytes; `None` without shadowed
/// lights.
fn shadow_resources(
    device: &wgpu::Device,
    cache: &mut PipelineCache,
    plan: &ShadowPlan,
    arrays: UniformArrays,
    stride: u64,
) -> Option<ShadowResources> {
    if plan.is_empty() {
        return None;
    }
    cache.compile_shadow_pass(stride);
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("shadow maps"),
        size: wgpu::Extent3d {
            width: plan.side,
            height: plan.side,
            depth_or_array_layers: plan.layers.len() as u32,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: shadows::SHADOW_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let init = |label, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    // The views are read by the scene pass (uniform or storage, as
    // `arrays` says) and by the depth passes (storage).
    let views_buffer = init(
        "shadow views",
        &bind_groups::shadow_view_bytes(&plan.gpu_views(), arrays.shadow_views),
        bindings::usage(arrays.shadow_views) | wgpu::BufferUsages::STORAGE,
    );
    let casters_buffer = init(
        "shadow casters",
        &bind_groups::caster_bytes(&plan.casters),
        wgpu::BufferUsages::UNIFORM,
    );
    let layer_views = (0..plan.layers.len() as u32)
        .map(|layer| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some("shadow layer"),
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: layer,
                array_layer_count: Some(1),
                ..Default::default()
            })
        })
        .collect();
    let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("shadow maps"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    let sampler = cache.shadow_sampler().clone();
    let scene_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("gonio shadow maps"),
        layout: &cache.scene_layouts(arrays).shadow_group,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&array_view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&sampler),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: views_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: casters_buffer.as_entire_binding(),
            },
        ],
    });
    let pass_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("gonio shadow pass"),
        layout: cache.shadow_pass_group_layout(),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: views_buffer.as_entire_binding(),
        }],
    });
    Some(ShadowResources {
        layer_views,
        scene_group,
        pass_group,
        pass_pipeline: cache.shadow_pass(stride).clone(),
    })
}

/// The pipeline each batch of `draw` is drawn with, compiled by
/// [`PipelineCache::compile_scene`]: specialized to its material's
/// variant when `key` has several ([`PipelineCache::specializations`]).
fn batch_pipelines(
    cache: &PipelineCache,
    key: &ShaderKey,
    format: wgpu::TextureFormat,
    samples: u32,
    materials: &[super::layout::GpuMaterial],
    draw: &SceneDraw,
) -> Vec<(Option<u32>, wgpu::RenderPipeline)> {
    let specialized = PipelineCache::specializations(key).len() > 1;
    draw.batches()
        .iter()
        .map(|b| {
            let variant = specialized.then(|| materials[b.material as usize].variant);
            let pipeline = cache.scene_pipeline(&(key.clone(), format, samples, variant));
            (variant, pipeline.clone())
        })
        .collect()
}

/// The lights of `scene` with their shadow maps as `plan` assigns them.
fn gpu_lights(scene: &Scene, plan: &ShadowPlan) -> Vec<GpuLight> {
    scene
        .lights
        .iter()
        .enumerate()
        .map(|(l, light)| {
            let mut g = GpuLight::from(light);
            plan.apply(l, &mut g);
            g
        })
        .collect()
}
