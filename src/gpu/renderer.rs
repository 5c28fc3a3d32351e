//! Draws a [`Scene`] offscreen and reads the radiance back.
//!
//! The colour target is `Rgba32Float`: linear radiance in RGB and coverage
//! in alpha (cleared to 0, written as 1), read back exactly, with no
//! multisampling, so each pixel is the surface seen at its centre, as in
//! the CPU reference.
//!
//! When a light casts shadows, depth-only passes fill its shadow maps
//! first (one pass per array layer, [`super::shadows`]), and the scene
//! pipeline gets a second bind group with the maps; otherwise neither the
//! passes nor the bind group nor any shadow code exist.

use super::GpuContext;
use super::bindings::{SceneLayouts, UniformArrays};
use super::geometry::VertexLayout;
use super::prepared::{DEPTH_FORMAT, FrameTarget};
use super::shader_gen::{self, Output, ShaderKey};
use super::shadows::{self, ShadowPlan};
use super::timing::{Clock, Timings};
use crate::frame::Frame;
use crate::scene::Scene;
use crate::{Error, Result};
use std::collections::HashMap;
use std::time::{Duration, Instant};

/// The offscreen colour target: linear radiance and coverage, exact.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const BYTES_PER_PIXEL: u32 = 16;

/// What tells scene pipelines apart: features, colour format, samples
/// per pixel, and the BRDF variant a pipeline draws (`None`: any of the
/// key's, chosen per material at run time).
pub(super) type PipelineKey = (ShaderKey, wgpu::TextureFormat, u32, Option<u32>);

/// A renderer bound to one device, caching one pipeline per [`ShaderKey`]
/// so re-rendering with new parameter values never recompiles.
pub struct GpuRenderer {
    pub(super) ctx: GpuContext,
    /// Scene bind group and pipeline layouts, one set per choice of
    /// uniform or storage arrays (made on first use).
    pub(super) scene_layouts: HashMap<UniformArrays, SceneLayouts>,
    /// Keyed by features, target format, samples per pixel and the BRDF
    /// variant a pipeline is specialized to (`None`: all of the key's).
    pub(super) pipelines: HashMap<PipelineKey, wgpu::RenderPipeline>,
    /// Bytes between materials in the materials buffer (dynamic-offset
    /// alignment; src/gpu/bindings.rs).
    pub(super) material_stride: u64,
    /// Whether shadow-map coordinates may be computed per vertex
    /// ([`ShaderKey::shadow_coords_per_vertex`]); default true.
    pub vertex_shadow_coords: bool,
    /// One module per key and output; its pipelines differ by constants.
    modules: HashMap<(ShaderKey, Output), wgpu::ShaderModule>,
    pub(super) shadow_sampler: wgpu::Sampler,
    /// The depth-only passes: layers in group 0.
    pub(super) pass_bind_group_layout: wgpu::BindGroupLayout,
    pass_pipeline_layout: wgpu::PipelineLayout,
    /// One per vertex stride.
    pub(super) pass_pipelines: HashMap<u64, wgpu::RenderPipeline>,
}

impl GpuRenderer {
    /// A renderer on `ctx`.
    pub fn new(ctx: GpuContext) -> Self {
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty,
            count: None,
        };
        let storage = wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        // Nearest texel, hardware depth comparison: 1 where the receiver's
        // depth is ≤ the stored occluder depth (lit).
        let shadow_sampler = ctx.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("gonio shadow compare"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            address_mode_w: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Nearest,
            min_filter: wgpu::FilterMode::Nearest,
            // Reversed depth: lit where the receiver is at least as near
            // the light as the stored occluder.
            compare: Some(wgpu::CompareFunction::GreaterEqual),
            ..Default::default()
        });
        let pass_bind_group_layout =
            ctx.device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("gonio shadow pass"),
                    entries: &[entry(0, storage)],
                });
        let pass_pipeline_layout =
            ctx.device
                .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("gonio shadow pass"),
                    bind_group_layouts: &[Some(&pass_bind_group_layout)],
                    immediate_size: 0,
                });
        GpuRenderer {
            vertex_shadow_coords: true,
            material_stride: super::bindings::material_stride(&ctx.device),
            ctx,
            scene_layouts: HashMap::new(),
            modules: HashMap::new(),
            pipelines: HashMap::new(),
            shadow_sampler,
            pass_bind_group_layout,
            pass_pipeline_layout,
            pass_pipelines: HashMap::new(),
        }
    }

    /// The depth-only pipeline of the shadow passes for a vertex stream of
    /// `stride` bytes (position at offset 0): vertex shader only, reversed
    /// depth (the nearest surface has the largest depth).
    pub(super) fn pass_pipeline(&mut self, stride: u64) -> &wgpu::RenderPipeline {
        let device = &self.ctx.device;
        let layout = &self.pass_pipeline_layout;
        self.pass_pipelines.entry(stride).or_insert_with(|| {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("gonio shadow pass"),
                source: wgpu::ShaderSource::Wgsl(
                    shader_gen::sources::get("shadow_pass.wgsl").into(),
                ),
            });
            let attributes = [wgpu::VertexAttribute {
                format: wgpu::VertexFormat::Float32x3,
                offset: 0,
                shader_location: 0,
            }];
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gonio shadow pass"),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_shadow"),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: stride,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &attributes,
                    })],
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    front_face: wgpu::FrontFace::Ccw,
                    // Every face occludes, as for the reference's rays.
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: shadows::SHADOW_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: None,
                multiview_mask: None,
                cache: None,
            })
        })
    }

    /// The device this renderer draws with.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// The variants `key`'s pipelines are specialized to: each of its BRDF
    /// variants when it has several (each material's batch is drawn by the
    /// pipeline of its variant), else `None` (one pipeline, no switch).
    pub(super) fn specializations(key: &ShaderKey) -> Vec<Option<u32>> {
        key.specializations()
    }

    /// Every pipeline `key` draws with into `format` (one per
    /// [`Self::specializations`]), compiled on first use.
    pub(super) fn pipelines_for(
        &mut self,
        key: &ShaderKey,
        layout: VertexLayout,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<()> {
        for variant in Self::specializations(key) {
            self.pipeline(key, layout, format, samples, variant)?;
        }
        Ok(())
    }

    /// The WGSL module of `key` writing `output`, generated and checked on
    /// first use.
    fn module(&mut self, key: &ShaderKey, output: Output) -> Result<&wgpu::ShaderModule> {
        let module_key = (key.clone(), output);
        if !self.modules.contains_key(&module_key) {
            let wgsl = shader_gen::compose_for(key, output);
            // For reading what a scene compiles: GONIO_DUMP_WGSL=DIR writes
            // every generated module there.
            shader_gen::dump_if_asked(
                {
                    use std::hash::{Hash, Hasher};
                    let mut h = std::collections::hash_map::DefaultHasher::new();
                    module_key.hash(&mut h);
                    h.finish()
                },
                &wgsl,
            );
            // naga validation first: a failure here is a bug in gonio, and
            // this way it is an error message, not a device panic.
            shader_gen::validate(&wgsl).map_err(|e| {
                Error::Gpu(format!(
                    "generated shader for {} is invalid: {e}",
                    key.describe()
                ))
            })?;
            let module = self
                .ctx
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("gonio scene shader"),
                    source: wgpu::ShaderSource::Wgsl(wgsl.into()),
                });
            self.modules.insert(module_key.clone(), module);
        }
        Ok(&self.modules[&module_key])
    }

    /// The pipeline for `key` drawing into `format`, specialized to
    /// `variant` (see [`Self::specializations`]), compiled on first use.
    pub(super) fn pipeline(
        &mut self,
        key: &ShaderKey,
        layout: VertexLayout,
        format: wgpu::TextureFormat,
        samples: u32,
        variant: Option<u32>,
    ) -> Result<&wgpu::RenderPipeline> {
        let cache_key = (key.clone(), format, samples, variant);
        if !self.pipelines.contains_key(&cache_key) {
            let attributes = layout.attributes();
            let module = self.module(key, Output::for_format(format))?.clone();
            let constants = shader_gen::pipeline_constants(variant);
            let compilation_options = wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            };
            let device = &self.ctx.device;
            let layouts = self
                .scene_layouts
                .entry(key.arrays)
                .or_insert_with(|| SceneLayouts::new(device, key.arrays));
            let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gonio scene"),
                layout: Some(if key.shadows.any() {
                    &layouts.shadowed
                } else {
                    &layouts.plain
                }),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: compilation_options.clone(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: layout.stride(),
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &attributes,
                    })],
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    front_face: wgpu::FrontFace::Ccw,
                    // Both faces are drawn, as the reference's rays hit both;
                    // the one-sided BRDF leaves back faces to the ambient term.
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: samples,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options,
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            });
            self.pipelines.insert(cache_key.clone(), pipeline);
        }
        Ok(&self.pipelines[&cache_key])
    }

    /// Renders `scene` offscreen, returning the frame and the time of each
    /// step: [`GpuRenderer::prepare`] into an `Rgba32Float` target, one
    /// [`GpuRenderer::encode`], and a readback.
    pub fn render(&mut self, scene: &Scene) -> Result<(Frame, Timings)> {
        let mut timings = Timings::default();
        let (width, height) = (scene.width, scene.height);
        self.check_target_size(width, height)?;
        let samples = scene.msaa.max(1);
        if samples > 1 {
            self.check_msaa(samples)?;
        }
        let start = Instant::now();
        let mut prepared = self.prepare_with_samples(scene, COLOR_FORMAT, samples)?;
        timings.push(
            "build vertex data + pipeline + upload",
            start.elapsed(),
            Clock::Wall,
        );

        let start = Instant::now();
        let device = &self.ctx.device;
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let target = |label, format, usage, sample_count| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = target(
            "radiance",
            COLOR_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            1,
        );
        let depth = target(
            "depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            samples,
        );
        // With MSAA the pass draws into a multisampled target and resolves
        // (averages the samples) into `color`: radiance is the pixel's
        // mean, coverage the covered fraction.
        let multisampled = (samples > 1).then(|| {
            target(
                "radiance (multisampled)",
                COLOR_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
                samples,
            )
        });
        let padded_row =
            (width * BYTES_PER_PIXEL).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let queries = self.ctx.timestamps.then(|| PassTimestamps::new(device));
        timings.push("create targets", start.elapsed(), Clock::Wall);

        let start = Instant::now();
        let color_view = color.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let multisampled_view = multisampled
            .as_ref()
            .map(|t| t.create_view(&Default::default()));
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        let drawn = self.encode(
            &mut prepared,
            &mut encoder,
            &FrameTarget {
                color: multisampled_view.as_ref().unwrap_or(&color_view),
                resolve: multisampled_view.as_ref().map(|_| &color_view),
                depth: &depth_view,
                viewport: None,
                timestamps: queries.as_ref().map(|q| &q.set),
            },
        );
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &color,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            size,
        );
        if let Some(q) = &queries {
            q.resolve(&mut encoder);
        }
        self.ctx.queue.submit([encoder.finish()]);
        let frame_bytes = map_read(&self.ctx.device, &readback)?;
        timings.push("render pass + readback", start.elapsed(), Clock::Wall);
        if let Some(q) = &queries {
            let (scene_pass, shadow_passes) = q.read(&self.ctx)?;
            if drawn.shadow_layers > 0 {
                timings.push(
                    format!("shadow passes ({} layers)", drawn.shadow_layers),
                    shadow_passes,
                    Clock::GpuTimestamp,
                );
            }
            timings.push("render pass", scene_pass, Clock::GpuTimestamp);
        }

        let frame = timings.wall("unpack frame", || {
            unpack(&frame_bytes, width, height, padded_row)
        });
        Ok((frame, timings))
    }

    /// Refuses a sample count the device cannot draw offscreen radiance
    /// with, naming `image.msaa`.
    fn check_msaa(&self, samples: u32) -> Result<()> {
        let ctx = &self.ctx;
        let specific = ctx
            .device
            .features()
            .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES);
        let flags = ctx.adapter.get_texture_format_features(COLOR_FORMAT).flags;
        if specific
            && flags.sample_count_supported(samples)
            && flags.contains(wgpu::TextureFormatFeatureFlags::MULTISAMPLE_RESOLVE)
        {
            Ok(())
        } else {
            Err(Error::argument(
                format!("image.msaa = {samples}"),
                format!(
                    "the GPU adapter `{}` cannot multisample and resolve {COLOR_FORMAT:?} targets; use image.msaa = 1",
                    ctx.adapter_info.name
                ),
            ))
        }
    }

    /// Refuses a target the device cannot hold.
    pub fn check_target_size(&self, width: u32, height: u32) -> Result<()> {
        let max_side = self.ctx.device.limits().max_texture_dimension_2d;
        if width > max_side || height > max_side {
            return Err(Error::argument(
                format!("{width}x{height}"),
                format!(
                    "the image is larger than the GPU's maximum texture side of {max_side} pixels"
                ),
            ));
        }
        Ok(())
    }
}

/// Timestamp queries around the scene pass (0, 1) and all shadow passes
/// (2, 3) of one frame, and the buffers to read them.
pub struct PassTimestamps {
    pub set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
}

impl PassTimestamps {
    pub fn new(device: &wgpu::Device) -> Self {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 4,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps"),
            size: 32,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps read"),
            size: 32,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        PassTimestamps { set, resolve, read }
    }

    /// Records the resolve and the copy to the readable buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..4, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 32);
    }

    /// Waits for the submitted frame and returns (scene pass, shadow
    /// passes) durations.
    pub fn read(&self, ctx: &GpuContext) -> Result<(Duration, Duration)> {
        let bytes = map_read(&ctx.device, &self.read)?;
        let stamps: &[u64] = bytemuck::cast_slice(&bytes);
        let period = ctx.queue.get_timestamp_period() as f64;
        let span = |a: usize, b: usize| {
            Duration::from_nanos((stamps[b].saturating_sub(stamps[a]) as f64 * period) as u64)
        };
        Ok((span(0, 1), span(2, 3)))
    }
}

impl GpuRenderer {
    /// Refuses shadow maps the device cannot hold, naming the setting to
    /// lower.
    pub(super) fn check_shadow_limits(&self, plan: &ShadowPlan) -> Result<()> {
        if plan.is_empty() {
            return Ok(());
        }
        let limits = self.ctx.device.limits();
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
}

/// Maps `buffer` for reading, waits, and copies its bytes out.
pub fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| Error::Gpu(format!("waiting for the GPU failed: {e}")))?;
    rx.recv()
        .map_err(|e| Error::Gpu(format!("readback was dropped: {e}")))?
        .map_err(|e| Error::Gpu(format!("readback failed: {e}")))?;
    let bytes = slice
        .get_mapped_range()
        .map_err(|e| Error::Gpu(format!("readback mapping failed: {e}")))?
        .to_vec();
    buffer.unmap();
    Ok(bytes)
}

/// Rows of RGBA f32 (padded to the copy alignment) into a [`Frame`].
fn unpack(bytes: &[u8], width: u32, height: u32, padded_row: u32) -> Frame {
    let mut frame = Frame::new(width, height);
    for i in 0..height {
        let row = &bytes[(i * padded_row) as usize..][..(width * BYTES_PER_PIXEL) as usize];
        let texels: &[[f32; 4]] = bytemuck::cast_slice(row);
        for (j, t) in texels.iter().enumerate() {
            let k = frame.index(i, j as u32);
            frame.radiance[k] = [t[0], t[1], t[2]];
            frame.coverage[k] = t[3] > 0.5;
        }
    }
    frame
}
