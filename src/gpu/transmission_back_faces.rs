//! What a volume's traced exit reads (`shading.transmission_exit_ray =
//! "traced"`, shaders/transmission_traced.wgsl): the nearest back face of
//! the transmissive volumes per pixel, and the opaque scene's depth.
//!
//! The back faces are drawn before the transmission images, in a pass of
//! their own over the batches of transmissive volumes (`thickness > 0`):
//! every face is rasterized, the fragments whose normal faces the eye are
//! discarded (so the mesh's winding does not matter), and the depth test
//! keeps the nearest of the rest. Each pixel holds the face's outward
//! world normal and its depth ([`FORMAT`]: f32, as the depth buffer, so
//! the march's comparisons lose nothing to the format); where there is
//! none, depth 1 (the far plane: no crossing). This is the second
//! interface of Wyman 2005, "An Approximate Image-Space Approach for
//! Interactive Refraction" (SIGGRAPH), which stores the back faces'
//! normals and depths the same way.
//!
//! The opaque scene's depth is the depth target of the transmission
//! image's layer 0, copied after that layer is drawn
//! ([`ExitImages::copy_scene_depth`]): the later layers draw the
//! transmissive objects into that target, and a pass may not read what
//! it draws into.

use super::formats::DEPTH_FORMAT;
use super::geometry::VertexLayout;

/// The back faces' image: outward normal (xyz) and depth (w).
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Group 4's entries the traced exit adds (after the image and its
/// sampler): the back faces at binding 2, the opaque scene's depth at 3.
pub fn group_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    [
        super::layout_entries::unfilterable_texture_2d(2, stage),
        wgpu::BindGroupLayoutEntry {
            binding: 3,
            visibility: stage,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Depth,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        },
    ]
}

/// The images of one frame size.
pub struct ExitImages {
    /// The back faces' normal and depth: drawn into, read by group 4.
    back_faces: wgpu::TextureView,
    /// The back-face pass's own depth target.
    back_depth: wgpu::TextureView,
    /// The opaque scene's depth, copied from layer 0's target.
    scene_depth: wgpu::Texture,
    scene_depth_view: wgpu::TextureView,
}

impl ExitImages {
    /// The images at `(width, height)`, the frame's.
    pub fn new(device: &wgpu::Device, (width, height): (u32, u32)) -> Self {
        let texture = |label, format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
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
        let read = wgpu::TextureUsages::TEXTURE_BINDING;
        let drawn = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let back_faces = texture("gonio transmission back faces", FORMAT, drawn | read);
        let back_depth = texture("gonio transmission back depth", DEPTH_FORMAT, drawn);
        let scene_depth = texture(
            "gonio transmission scene depth",
            DEPTH_FORMAT,
            read | wgpu::TextureUsages::COPY_DST,
        );
        ExitImages {
            back_faces: back_faces.create_view(&Default::default()),
            back_depth: back_depth.create_view(&Default::default()),
            scene_depth_view: scene_depth.create_view(&Default::default()),
            scene_depth,
        }
    }

    /// Group 4's entries over these images ([`group_entries`]).
    pub fn bind_entries(&self) -> [wgpu::BindGroupEntry<'_>; 2] {
        [
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&self.back_faces),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::TextureView(&self.scene_depth_view),
            },
        ]
    }

    /// Records the copy of layer 0's depth (`depth`, of the same size)
    /// into the opaque scene's depth.
    pub fn copy_scene_depth(&self, encoder: &mut wgpu::CommandEncoder, depth: &wgpu::Texture) {
        encoder.copy_texture_to_texture(
            depth.as_image_copy(),
            self.scene_depth.as_image_copy(),
            self.scene_depth.size(),
        );
    }

    /// Begins the back-face pass: normal 0 and depth 1 (none) everywhere,
    /// the depth target at the far plane.
    pub fn begin<'e>(&self, encoder: &'e mut wgpu::CommandEncoder) -> wgpu::RenderPass<'e> {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gonio transmission back faces"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.back_faces,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: 0.0,
                        g: 0.0,
                        b: 0.0,
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.back_depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }
}

/// The back-face pass's pipeline (shaders/transmission_back_faces.wgsl)
/// and its bind group: the scene's globals (the camera).
pub struct BackFacePass {
    pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
}

impl BackFacePass {
    /// The pass over the vertex stream of `layout` (position and normal,
    /// locations 0 and 1), reading the camera from `globals` (the scene's
    /// globals buffer: `clip_from_world` and `eye` first, 80 bytes).
    pub fn new(device: &wgpu::Device, layout: VertexLayout, globals: &wgpu::Buffer) -> Self {
        let group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gonio transmission back faces"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(CAMERA_BYTES),
                },
                count: None,
            }],
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio transmission back faces"),
            layout: &group_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: globals,
                    offset: 0,
                    size: wgpu::BufferSize::new(CAMERA_BYTES),
                }),
            }],
        });
        BackFacePass {
            pipeline: pipeline(device, &group_layout, layout),
            group,
        }
    }

    /// Binds the pipeline and the camera for the draws of the pass.
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
    }
}

/// The globals' first fields the pass reads: `clip_from_world` (64
/// bytes), `eye` and the `u32` after it (16).
const CAMERA_BYTES: u64 = 80;

/// Position and normal of the stream, every face, depth test, the
/// normal and depth written.
fn pipeline(
    device: &wgpu::Device,
    group: &wgpu::BindGroupLayout,
    layout: VertexLayout,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gonio transmission back faces"),
        source: wgpu::ShaderSource::Wgsl(
            super::shader_gen::sources::get("transmission_back_faces.wgsl").into(),
        ),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("gonio transmission back faces"),
        bind_group_layouts: &[Some(group)],
        immediate_size: 0,
    });
    let attributes: Vec<_> = layout
        .attributes()
        .into_iter()
        .filter(|a| a.shader_location < 2)
        .collect();
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("gonio transmission back faces"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_back_face"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: layout.stride(),
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attributes,
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
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
            entry_point: Some("fs_back_face"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: FORMAT,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
