//! One timed render pass with a shader of the bench's choosing, on the
//! renderer's device and over the renderer's vertex stream.
//!
//! The floors (an unlit pass, a hand-written Lambert shader) and the
//! uber-shader comparison need pipelines the renderer does not build. They
//! are drawn here with the renderer's own vertex data
//! ([`GeometryData`]), its buffers and bindings ([`crate::gpu::bindings`])
//! and the same colour and depth formats, and timed with the same GPU
//! timestamp queries around the pass, so that the only difference between
//! two measurements is the shader. Shadows are not drawn here: the
//! harness measures the scene pass alone.

use crate::frame::Frame;
use crate::gpu::GpuContext;
use crate::gpu::bindings;
use crate::gpu::geometry::GeometryData;
use crate::gpu::layout::{GpuGlobals, GpuLight, GpuMaterial};
pub use crate::gpu::readback::map_read;
use crate::gpu::shader_gen::{self, ShaderKey};
use crate::gpu::timing::Clock;
use crate::scene::Scene;
use crate::{Error, Result};
use std::time::Instant;
use wgpu::util::DeviceExt;

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Which vertex attributes a harness shader reads (the stream always has
/// the scene's full layout; unread attributes are skipped by the stride).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inputs {
    /// `@location(0)` position only.
    Position,
    /// Position and normal (locations 0–1).
    PositionNormal,
    /// Everything the scene's layout has (a generated shader).
    All,
}

/// A shader for the harness: WGSL with `vs_main` / `fs_main` over the
/// bindings of `shaders/common.wgsl`, and the key whose variant indices
/// the material buffer uses.
pub struct HarnessShader {
    pub label: String,
    pub wgsl: String,
    pub inputs: Inputs,
    pub key: ShaderKey,
}

impl HarnessShader {
    /// The scene-specialized shader the renderer would build for `scene`
    /// (without shadows), or any other key's shader (the uber shader).
    pub fn generated(label: &str, key: ShaderKey) -> Self {
        HarnessShader {
            label: label.into(),
            wgsl: shader_gen::compose(&key),
            inputs: Inputs::All,
            key,
        }
    }
}

/// A pass ready to draw and time repeatedly on the device it was built
/// on (passed to each call, so the renderer that owns the device can
/// render in between).
pub struct Harness {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
    vertices: wgpu::Buffer,
    indices: Option<wgpu::Buffer>,
    /// One draw per material (its slot bound at this offset).
    batches: Vec<(u32, std::ops::Range<u32>)>,
    color: wgpu::Texture,
    depth: wgpu::Texture,
    width: u32,
    height: u32,
    /// Wall time of shader module + pipeline creation (compilation).
    pub compile_ms: f64,
}

impl Harness {
    /// Uploads `scene` and compiles `shader` for it.
    pub fn new(ctx: &GpuContext, scene: &Scene, shader: &HarnessShader) -> Result<Self> {
        let device = &ctx.device;
        shader_gen::validate(&shader.wgsl)
            .map_err(|e| Error::Gpu(format!("bench shader `{}` is invalid: {e}", shader.label)))?;
        let geometry = GeometryData::new(
            scene,
            shader.key.needs_tangents(),
            shader.key.shadow_coords_per_vertex(),
        );
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let vertices = init(
            "bench vertices",
            bytemuck::cast_slice(&geometry.words),
            wgpu::BufferUsages::VERTEX,
        );
        let indices = geometry.indices.as_ref().map(|i| {
            init(
                "bench indices",
                bytemuck::cast_slice(i),
                wgpu::BufferUsages::INDEX,
            )
        });
        let globals = GpuGlobals::new(scene);
        let materials: Vec<GpuMaterial> = scene
            .effective_materials()
            .iter()
            .map(|m| GpuMaterial::new(m, &shader.key))
            .collect();
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::from).collect();
        let globals = init(
            "bench globals",
            bytemuck::bytes_of(&globals),
            wgpu::BufferUsages::UNIFORM,
        );
        // The renderer's bindings for this key (src/gpu/bindings.rs): the
        // material bound per draw, lights as the key says.
        let arrays = shader.key.arrays;
        let material_stride = bindings::material_stride(device);
        let materials = init(
            "bench materials",
            &bindings::material_bytes(&materials, material_stride),
            wgpu::BufferUsages::UNIFORM,
        );
        let lights = init(
            "bench lights",
            &bindings::light_bytes(&lights, arrays.lights),
            bindings::usage(arrays.lights),
        );
        let bind_group_layout = bindings::scene_group_layout(device, arrays);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("bench scene"),
            layout: &bind_group_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: bindings::material_binding(&materials),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: lights.as_entire_binding(),
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("bench scene"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let attributes: Vec<wgpu::VertexAttribute> = geometry
            .layout
            .attributes()
            .into_iter()
            .filter(|a| match shader.inputs {
                Inputs::Position => a.shader_location == 0,
                Inputs::PositionNormal => a.shader_location <= 1,
                Inputs::All => true,
            })
            .collect();
        let start = Instant::now();
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&shader.label),
            source: wgpu::ShaderSource::Wgsl(shader.wgsl.as_str().into()),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&shader.label),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: geometry.layout.stride(),
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            // As the renderer: both faces, depth test, no blending.
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                front_face: wgpu::FrontFace::Ccw,
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
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: COLOR_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        // Pipeline creation is lazy on some drivers: one draw makes sure the
        // compile is inside `compile_ms`.
        let target = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: scene.width,
                    height: scene.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = target(
            "bench radiance",
            COLOR_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = target(
            "bench depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let mut harness = Harness {
            pipeline,
            bind_group,
            vertices,
            indices,
            batches: geometry
                .batches
                .iter()
                .map(|b| {
                    (
                        bindings::material_offset(b.material, material_stride),
                        b.range.clone(),
                    )
                })
                .collect(),
            color,
            depth,
            width: scene.width,
            height: scene.height,
            compile_ms: 0.0,
        };
        harness.time_once(ctx)?;
        harness.compile_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(harness)
    }

    /// Records the scene pass into `encoder`, with timestamps 0 and 1
    /// around it when `queries` is given.
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, queries: Option<&wgpu::QuerySet>) {
        let color_view = self.color.create_view(&Default::default());
        let depth_view = self.depth.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("bench scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: queries.map(|set| wgpu::RenderPassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: Some(0),
                end_of_pass_write_index: Some(1),
            }),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        if let Some(indices) = &self.indices {
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        }
        for (offset, range) in &self.batches {
            pass.set_bind_group(0, &self.bind_group, &[*offset]);
            match self.indices {
                Some(_) => pass.draw_indexed(range.clone(), 0, 0..1),
                None => pass.draw(range.clone(), 0..1),
            }
        }
    }

    /// Draws once and returns the pass time in milliseconds: GPU
    /// timestamps where the adapter has them, else the wall time of
    /// submit-and-wait.
    pub fn time_once(&self, ctx: &GpuContext) -> Result<(f64, Clock)> {
        let device = &ctx.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        if !ctx.timestamps {
            self.encode(&mut encoder, None);
            let start = Instant::now();
            ctx.queue.submit([encoder.finish()]);
            device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|e| Error::Gpu(format!("waiting for the GPU failed: {e}")))?;
            return Ok((start.elapsed().as_secs_f64() * 1e3, Clock::Wall));
        }
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("bench timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bench timestamps"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bench timestamps read"),
            size: 16,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        self.encode(&mut encoder, Some(&set));
        encoder.resolve_query_set(&set, 0..2, &resolve, 0);
        encoder.copy_buffer_to_buffer(&resolve, 0, &read, 0, 16);
        ctx.queue.submit([encoder.finish()]);
        let bytes = map_read(device, &read)?;
        let stamps: &[u64] = bytemuck::cast_slice(&bytes);
        let period = ctx.queue.get_timestamp_period() as f64;
        let ns = stamps[1].saturating_sub(stamps[0]) as f64 * period;
        Ok((ns * 1e-6, Clock::GpuTimestamp))
    }

    /// Draws once more and reads the radiance back (to check that a floor
    /// shader draws the image it claims to).
    pub fn frame(&self, ctx: &GpuContext) -> Result<Frame> {
        let device = &ctx.device;
        let padded_row = (self.width * 16).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bench readback"),
            size: padded_row as u64 * self.height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        self.encode(&mut encoder, None);
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.color,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
        ctx.queue.submit([encoder.finish()]);
        let bytes = map_read(device, &readback)?;
        let mut frame = Frame::new(self.width, self.height);
        for i in 0..self.height {
            let row = &bytes[(i * padded_row) as usize..][..(self.width * 16) as usize];
            let texels: &[[f32; 4]] = bytemuck::cast_slice(row);
            for (j, t) in texels.iter().enumerate() {
                let k = frame.index(i, j as u32);
                frame.radiance[k] = [t[0], t[1], t[2]];
                frame.coverage[k] = t[3] > 0.5;
            }
        }
        Ok(frame)
    }
}
