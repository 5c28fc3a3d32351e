//! Draws a [`Scene`] offscreen and reads the radiance back.
//!
//! The colour target is `Rgba32Float`: linear radiance in RGB and coverage
//! in alpha (cleared to 0, written as 1), read back exactly, with no
//! multisampling, so each pixel is the surface seen at its centre, as in
//! the CPU reference.

use super::GpuContext;
use super::geometry::{GeometryData, VertexLayout};
use super::layout::{GpuGlobals, GpuLight, GpuMaterial};
use super::shader_gen::{self, ShaderKey};
use super::timing::{Clock, Timings};
use crate::frame::Frame;
use crate::scene::Scene;
use crate::{Error, Result};
use std::collections::HashMap;
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
const BYTES_PER_PIXEL: u32 = 16;

/// A renderer bound to one device, caching one pipeline per [`ShaderKey`]
/// so re-rendering with new parameter values never recompiles.
pub struct GpuRenderer {
    ctx: GpuContext,
    bind_group_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    pipelines: HashMap<ShaderKey, wgpu::RenderPipeline>,
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
        let bind_group_layout =
            ctx.device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("gonio scene"),
                    entries: &[
                        entry(
                            0,
                            wgpu::BindingType::Buffer {
                                ty: wgpu::BufferBindingType::Uniform,
                                has_dynamic_offset: false,
                                min_binding_size: None,
                            },
                        ),
                        entry(1, storage),
                        entry(2, storage),
                    ],
                });
        let pipeline_layout = ctx
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("gonio scene"),
                bind_group_layouts: &[Some(&bind_group_layout)],
                immediate_size: 0,
            });
        GpuRenderer {
            ctx,
            bind_group_layout,
            pipeline_layout,
            pipelines: HashMap::new(),
        }
    }

    /// The device this renderer draws with.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// The pipeline for `key`, compiled on first use.
    fn pipeline(&mut self, key: &ShaderKey, layout: VertexLayout) -> Result<&wgpu::RenderPipeline> {
        if !self.pipelines.contains_key(key) {
            let attributes = layout.attributes();
            let wgsl = shader_gen::compose(key);
            // naga validation first: a failure here is a bug in gonio, and
            // this way it is an error message, not a device panic.
            shader_gen::validate(&wgsl).map_err(|e| {
                Error::Gpu(format!(
                    "generated shader for {} is invalid: {e}",
                    key.describe()
                ))
            })?;
            let device = &self.ctx.device;
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("gonio scene shader"),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            });
            let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("gonio scene"),
                layout: Some(&self.pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
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
            self.pipelines.insert(key.clone(), pipeline);
        }
        Ok(&self.pipelines[key])
    }

    /// Renders `scene`, returning the frame and the time of each step.
    pub fn render(&mut self, scene: &Scene) -> Result<(Frame, Timings)> {
        let mut timings = Timings::default();
        let (width, height) = (scene.width, scene.height);
        let max_side = self.ctx.device.limits().max_texture_dimension_2d;
        if width > max_side || height > max_side {
            return Err(Error::argument(
                format!("{width}x{height}"),
                format!(
                    "the image is larger than the GPU's maximum texture side of {max_side} pixels"
                ),
            ));
        }
        if scene.materials.is_empty() || scene.lights.is_empty() {
            return Err(Error::Gpu(
                "a scene needs at least one material and one light".into(),
            ));
        }

        let key = ShaderKey::for_scene(scene);
        let geometry = timings.wall("build vertex data", || GeometryData::new(scene, key.needs_tangents()));
        let start = Instant::now();
        self.pipeline(&key, geometry.layout)?;
        timings.push("create pipeline", start.elapsed(), Clock::Wall);

        let device = &self.ctx.device;
        let queue = &self.ctx.queue;
        let start = Instant::now();
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let vertex_buffer = init("vertices", bytemuck::cast_slice(&geometry.words), wgpu::BufferUsages::VERTEX);
        let index_buffer = geometry.indices.as_ref().map(|i| {
            init(
                "indices",
                bytemuck::cast_slice(i),
                wgpu::BufferUsages::INDEX,
            )
        });
        let globals = GpuGlobals::new(scene);
        let materials: Vec<GpuMaterial> = scene
            .effective_materials()
            .iter()
            .map(|m| GpuMaterial::new(m, &key))
            .collect();
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::from).collect();
        let globals_buffer = init(
            "globals",
            bytemuck::bytes_of(&globals),
            wgpu::BufferUsages::UNIFORM,
        );
        let materials_buffer = init(
            "materials",
            bytemuck::cast_slice(&materials),
            wgpu::BufferUsages::STORAGE,
        );
        let lights_buffer = init(
            "lights",
            bytemuck::cast_slice(&lights),
            wgpu::BufferUsages::STORAGE,
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio scene"),
            layout: &self.bind_group_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: materials_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: lights_buffer.as_entire_binding(),
                },
            ],
        });
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let target = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
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
        );
        let depth = target(
            "depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let padded_row =
            (width * BYTES_PER_PIXEL).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let queries = self.ctx.timestamps.then(|| {
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let read = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps read"),
                size: 16,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            (set, resolve, read)
        });
        timings.push("upload", start.elapsed(), Clock::Wall);

        let start = Instant::now();
        let pipeline = &self.pipelines[&key];
        let color_view = color.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("scene"),
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
                timestamp_writes: queries.as_ref().map(|(set, ..)| {
                    wgpu::RenderPassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.set_vertex_buffer(0, vertex_buffer.slice(..));
            match &index_buffer {
                Some(indices) => {
                    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..geometry.draw_count, 0, 0..1);
                }
                None => pass.draw(0..geometry.draw_count, 0..1),
            }
        }
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
        if let Some((set, resolve, read)) = &queries {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, read, 0, 16);
        }
        queue.submit([encoder.finish()]);
        let frame_bytes = map_read(device, &readback)?;
        timings.push("render pass + readback", start.elapsed(), Clock::Wall);
        if let Some((_, _, read)) = &queries {
            let bytes = map_read(device, read)?;
            let stamps: &[u64] = bytemuck::cast_slice(&bytes);
            let ns =
                stamps[1].saturating_sub(stamps[0]) as f64 * queue.get_timestamp_period() as f64;
            timings.push(
                "render pass",
                Duration::from_nanos(ns as u64),
                Clock::GpuTimestamp,
            );
        }

        let frame = timings.wall("unpack frame", || {
            unpack(&frame_bytes, width, height, padded_row)
        });
        Ok((frame, timings))
    }
}

/// Maps `buffer` for reading, waits, and copies its bytes out.
fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>> {
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
