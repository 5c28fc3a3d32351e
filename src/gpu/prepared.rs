//! A scene uploaded once and drawn many times.
//!
//! `gonio render` draws a scene once; the viewer and the bench draw it
//! every frame. Both go through [`PreparedScene`]: the vertex stream,
//! the parameter buffers and the shadow maps live on the GPU between
//! frames, and [`GpuRenderer::update`] rewrites only what a change touches
//! (a camera move writes 144 bytes of globals; a new roughness writes the
//! material buffer; a light change re-plans and re-renders the shadow maps
//! once). The shadow maps are drawn only when they are stale, so orbiting
//! the camera costs one scene pass per frame.

use super::GpuRenderer;
use super::bindings::{self, UniformArrays};
use super::geometry::{Batch, GeometryData, VertexLayout};
use super::layout::{GpuGlobals, GpuLight, GpuMaterial};
use super::shader_gen::ShaderKey;
use super::shadows::ShadowPlan;
use crate::scene::Scene;
use crate::{Error, Result};
use wgpu::util::DeviceExt;

/// The depth format of scene passes.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

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
    layout: VertexLayout,
    vertex_buffer: wgpu::Buffer,
    index_buffer: Option<wgpu::Buffer>,
    draw_count: u32,
    /// The stream's material runs, and for each the variant it is drawn
    /// with and that pipeline (resolved when the scene changes, so a frame
    /// looks nothing up).
    batches: Vec<Batch>,
    batch_pipelines: Vec<(Option<u32>, wgpu::RenderPipeline)>,
    globals_buffer: wgpu::Buffer,
    materials_buffer: wgpu::Buffer,
    lights_buffer: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The light data last uploaded, to tell whether the maps are stale.
    lights: Vec<GpuLight>,
    plan: ShadowPlan,
    shadows: Option<ShadowResources>,
    /// The shadow maps must be drawn before the next scene pass.
    shadows_stale: bool,
}

/// The shadow-map array and the bind groups that read and fill it.
struct ShadowResources {
    layer_views: Vec<wgpu::TextureView>,
    scene_group: wgpu::BindGroup,
    pass_group: wgpu::BindGroup,
}

/// Where a scene pass draws.
pub struct FrameTarget<'a> {
    /// Colour attachment of the prepared scene's `format` and samples.
    pub color: &'a wgpu::TextureView,
    /// Where a multisampled `color` is resolved to.
    pub resolve: Option<&'a wgpu::TextureView>,
    /// Depth attachment ([`DEPTH_FORMAT`]) of the same size.
    pub depth: &'a wgpu::TextureView,
    /// `[x, y, width, height]` in pixels of the 3D area; `None`: all of it.
    /// The scene's camera aspect should be `width / height` of this area.
    pub viewport: Option<[f32; 4]>,
    /// Timestamps written around the scene pass (indices 0, 1) and around
    /// all shadow passes (2, 3), if given.
    pub timestamps: Option<&'a wgpu::QuerySet>,
}

/// What one [`GpuRenderer::encode`] drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Drawn {
    /// Shadow-map layers rendered (0 when the maps were current).
    pub shadow_layers: usize,
}

impl GpuRenderer {
    /// Uploads `scene` for drawing into targets of `format`
    /// (`Rgba32Float`: linear radiance; an 8-bit format: display).
    pub fn prepare(&mut self, scene: &Scene, format: wgpu::TextureFormat) -> Result<PreparedScene> {
        self.prepare_with_samples(scene, format, 1)
    }

    /// [`GpuRenderer::prepare`] for targets of `samples` samples per pixel.
    pub fn prepare_with_samples(
        &mut self,
        scene: &Scene,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<PreparedScene> {
        if scene.materials.is_empty() || scene.lights.is_empty() {
            return Err(Error::Scene(
                "it needs at least one material and one light".into(),
            ));
        }
        let (key, plan) = self.plan(scene)?;
        let geometry =
            GeometryData::new(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
        self.pipelines_for(&key, geometry.layout, format, samples)?;
        if !plan.is_empty() {
            self.pass_pipeline(geometry.layout.stride());
        }
        let device = &self.ctx.device;
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let vertex_buffer = init(
            "vertices",
            bytemuck::cast_slice(&geometry.words),
            wgpu::BufferUsages::VERTEX,
        );
        let index_buffer = geometry.indices.as_ref().map(|i| {
            init(
                "indices",
                bytemuck::cast_slice(i),
                wgpu::BufferUsages::INDEX,
            )
        });
        let geometry_bytes =
            4 * (geometry.words.len() + geometry.indices.as_ref().map_or(0, Vec::len)) as u64;
        let dynamic = wgpu::BufferUsages::COPY_DST;
        let globals_buffer = init(
            "globals",
            bytemuck::bytes_of(&GpuGlobals::new(scene)),
            wgpu::BufferUsages::UNIFORM | dynamic,
        );
        let arrays = key.arrays;
        let materials = gpu_materials(scene, &key);
        let materials_buffer = init(
            "materials",
            &bindings::material_bytes(&materials, self.material_stride),
            wgpu::BufferUsages::UNIFORM | dynamic,
        );
        let lights = gpu_lights(scene, &plan);
        let lights_buffer = init(
            "lights",
            &bindings::light_bytes(&lights, arrays.lights),
            bindings::usage(arrays.lights) | dynamic,
        );
        let bind_group =
            self.scene_bind_group(arrays, &globals_buffer, &materials_buffer, &lights_buffer);
        let shadows = self.shadow_resources(&plan, arrays);
        let batch_pipelines =
            self.batch_pipelines(&key, format, samples, &materials, &geometry.batches);
        Ok(PreparedScene {
            key,
            format,
            display_scale: 1.0,
            samples,
            triangles: scene.triangle_count() as u64,
            geometry_bytes,
            layout: geometry.layout,
            vertex_buffer,
            index_buffer,
            draw_count: geometry.draw_count,
            batch_pipelines,
            batches: geometry.batches,
            globals_buffer,
            materials_buffer,
            lights_buffer,
            bind_group,
            lights,
            shadows_stale: shadows.is_some(),
            plan,
            shadows,
        })
    }

    /// Brings `prepared` up to date with `scene`, which must have the same
    /// meshes as the scene it was prepared from (reload the file: prepare
    /// anew). Writes only what changed; a change of the shader features
    /// selects (or compiles, once) another cached pipeline; a change of
    /// the vertex stream (shading mode, tangents) rebuilds it.
    pub fn update(&mut self, prepared: &mut PreparedScene, scene: &Scene) -> Result<()> {
        if scene.materials.is_empty() || scene.lights.is_empty() {
            return Err(Error::Scene(
                "it needs at least one material and one light".into(),
            ));
        }
        let (key, plan) = self.plan(scene)?;
        if key.shading != prepared.key.shading
            || key.needs_tangents() != prepared.layout.tangents
            || key.shadow_coords_per_vertex() != prepared.layout.face_normal
        {
            let display_scale = prepared.display_scale;
            *prepared = self.prepare_with_samples(scene, prepared.format, prepared.samples)?;
            prepared.display_scale = display_scale;
            return Ok(());
        }
        self.pipelines_for(&key, prepared.layout, prepared.format, prepared.samples)?;
        if !plan.is_empty() {
            self.pass_pipeline(prepared.layout.stride());
        }
        let queue = &self.ctx.queue;
        let mut globals = GpuGlobals::new(scene);
        globals.display_scale = prepared.display_scale;
        queue.write_buffer(&prepared.globals_buffer, 0, bytemuck::bytes_of(&globals));

        let arrays = key.arrays;
        let materials = gpu_materials(scene, &key);
        let lights = gpu_lights(scene, &plan);
        let materials_bytes = bindings::material_bytes(&materials, self.material_stride);
        let lights_bytes = bindings::light_bytes(&lights, arrays.lights);
        let rebind = arrays != prepared.key.arrays
            || materials_bytes.len() as u64 != prepared.materials_buffer.size()
            || lights_bytes.len() as u64 != prepared.lights_buffer.size();
        if rebind {
            let device = &self.ctx.device;
            let init = |label, contents: &[u8], usage| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: usage | wgpu::BufferUsages::COPY_DST,
                })
            };
            prepared.materials_buffer =
                init("materials", &materials_bytes, wgpu::BufferUsages::UNIFORM);
            prepared.lights_buffer = init("lights", &lights_bytes, bindings::usage(arrays.lights));
            prepared.bind_group = self.scene_bind_group(
                arrays,
                &prepared.globals_buffer,
                &prepared.materials_buffer,
                &prepared.lights_buffer,
            );
        } else {
            queue.write_buffer(&prepared.materials_buffer, 0, &materials_bytes);
            queue.write_buffer(&prepared.lights_buffer, 0, &lights_bytes);
        }
        let lights_changed = bytemuck::cast_slice::<GpuLight, u8>(&prepared.lights)
            != bytemuck::cast_slice::<GpuLight, u8>(&lights);
        if lights_changed
            || plan != prepared.plan
            || key.shadows != prepared.key.shadows
            || arrays != prepared.key.arrays
        {
            prepared.shadows = self.shadow_resources(&plan, arrays);
            prepared.shadows_stale = prepared.shadows.is_some();
            prepared.plan = plan;
        }
        prepared.lights = lights;
        prepared.batch_pipelines = self.batch_pipelines(
            &key,
            prepared.format,
            prepared.samples,
            &materials,
            &prepared.batches,
        );
        prepared.key = key;
        Ok(())
    }

    /// Writes only the per-view values of `scene` (camera, image size,
    /// ambient, environment, exposure): what a camera move changes. The
    /// shadow maps do not depend on the camera, so they stay.
    pub fn update_view(&self, prepared: &PreparedScene, scene: &Scene) {
        let mut globals = GpuGlobals::new(scene);
        globals.display_scale = prepared.display_scale;
        self.ctx
            .queue
            .write_buffer(&prepared.globals_buffer, 0, bytemuck::bytes_of(&globals));
    }

    /// Records the shadow passes (if the maps are stale) and the scene
    /// pass of `prepared` into `encoder`. The scene pass clears the whole
    /// target to transparent black (coverage 0) and draws into the
    /// viewport.
    pub fn encode(
        &mut self,
        prepared: &mut PreparedScene,
        encoder: &mut wgpu::CommandEncoder,
        target: &FrameTarget,
    ) -> Drawn {
        let mut drawn = Drawn::default();
        let stride = prepared.layout.stride();
        if let (Some(shadows), true) = (&prepared.shadows, prepared.shadows_stale) {
            let last = shadows.layer_views.len() - 1;
            for (i, (layer, view)) in prepared
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
                pass.set_pipeline(&self.pass_pipelines[&stride]);
                pass.set_bind_group(0, &shadows.pass_group, &[]);
                prepared.draw(&mut pass, i as u32..i as u32 + 1);
            }
            drawn.shadow_layers = shadows.layer_views.len();
            prepared.shadows_stale = false;
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target.color,
                depth_slice: None,
                resolve_target: target.resolve,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: target.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: target
                .timestamps
                .map(|set| wgpu::RenderPassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                }),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some([x, y, w, h]) = target.viewport {
            pass.set_viewport(x, y, w, h, 0.0, 1.0);
        }
        if let Some(shadows) = &prepared.shadows {
            pass.set_bind_group(1, &shadows.scene_group, &[]);
        }
        prepared.bind_geometry(&mut pass);
        // Each material's batch with its material bound (src/gpu/bindings.rs)
        // and the pipeline of its BRDF variant (consecutive batches of one
        // variant share the bind).
        let mut bound = None;
        for (batch, (variant, pipeline)) in prepared.batches.iter().zip(&prepared.batch_pipelines) {
            if bound != Some(*variant) {
                pass.set_pipeline(pipeline);
                bound = Some(*variant);
            }
            let offset = bindings::material_offset(batch.material, self.material_stride);
            pass.set_bind_group(0, &prepared.bind_group, &[offset]);
            prepared.draw_range(&mut pass, batch.range.clone(), 0..1);
        }
        drawn
    }

    /// The shader key and shadow plan of `scene`, checked against the
    /// device's limits.
    fn plan(&self, scene: &Scene) -> Result<(ShaderKey, ShadowPlan)> {
        let plan = ShadowPlan::new(scene);
        let mut key = ShaderKey::new(scene, &plan);
        key.vertex_shadow_coords = self.vertex_shadow_coords;
        debug_assert_eq!(key.counts.shadow_maps as usize, plan.casters.len());
        self.check_shadow_limits(&plan)?;
        Ok((key, plan))
    }

    fn scene_bind_group(
        &self,
        arrays: UniformArrays,
        globals: &wgpu::Buffer,
        materials: &wgpu::Buffer,
        lights: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        let entries = [
            wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: bindings::material_binding(materials),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: lights.as_entire_binding(),
            },
        ];
        self.ctx
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("gonio scene"),
                layout: &self.scene_layouts[&arrays].scene_group,
                entries: &entries,
            })
    }

    /// The shadow-map array of `plan` with one view per layer to render
    /// into and the bind groups that read and fill it; `None` without
    /// shadowed lights.
    fn shadow_resources(
        &self,
        plan: &ShadowPlan,
        arrays: UniformArrays,
    ) -> Option<ShadowResources> {
        if plan.is_empty() {
            return None;
        }
        let device = &self.ctx.device;
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
            format: super::shadows::SHADOW_FORMAT,
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
            &bindings::shadow_view_bytes(&plan.gpu_views(), arrays.shadow_views),
            bindings::usage(arrays.shadow_views) | wgpu::BufferUsages::STORAGE,
        );
        let casters_buffer = init(
            "shadow casters",
            &bindings::caster_bytes(&plan.casters),
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
        let scene_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio shadow maps"),
            layout: &self.scene_layouts[&arrays].shadow_group,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&array_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.shadow_sampler),
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
            layout: &self.pass_bind_group_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: views_buffer.as_entire_binding(),
            }],
        });
        Some(ShadowResources {
            layer_views,
            scene_group,
            pass_group,
        })
    }
}

impl PreparedScene {
    /// Shadow-map layers this scene renders when its maps are stale.
    pub fn shadow_layers(&self) -> usize {
        self.plan.layers.len()
    }

    /// Marks the shadow maps stale (the bench re-renders them each frame
    /// to measure their cost).
    pub fn invalidate_shadows(&mut self) {
        self.shadows_stale = self.shadows.is_some();
    }

    /// Binds the vertex stream (and index buffer) for [`Self::draw_range`].
    fn bind_geometry(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        if let Some(indices) = &self.index_buffer {
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        }
    }

    /// Draws `range` of the bound stream (indices or vertices).
    fn draw_range(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        range: std::ops::Range<u32>,
        instances: std::ops::Range<u32>,
    ) {
        match self.index_buffer {
            Some(_) => pass.draw_indexed(range, 0, instances),
            None => pass.draw(range, instances),
        }
    }

    /// The whole scene in one draw call (all meshes share one stream).
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>, instances: std::ops::Range<u32>) {
        self.bind_geometry(pass);
        self.draw_range(pass, 0..self.draw_count, instances);
    }
}

impl GpuRenderer {
    /// The pipeline each batch is drawn with, compiled by
    /// [`GpuRenderer::pipelines_for`]: specialized to its material's
    /// variant when `key` has several ([`GpuRenderer::specializations`]).
    fn batch_pipelines(
        &self,
        key: &ShaderKey,
        format: wgpu::TextureFormat,
        samples: u32,
        materials: &[GpuMaterial],
        batches: &[Batch],
    ) -> Vec<(Option<u32>, wgpu::RenderPipeline)> {
        let specialized = Self::specializations(key).len() > 1;
        batches
            .iter()
            .map(|b| {
                let variant = specialized.then(|| materials[b.material as usize].variant);
                let pipeline = &self.pipelines[&(key.clone(), format, samples, variant)];
                (variant, pipeline.clone())
            })
            .collect()
    }
}

fn gpu_materials(scene: &Scene, key: &ShaderKey) -> Vec<GpuMaterial> {
    scene
        .effective_materials()
        .iter()
        .map(|m| GpuMaterial::new(m, key))
        .collect()
}

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
