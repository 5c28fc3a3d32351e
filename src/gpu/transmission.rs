//! The images transmissive surfaces read what lies behind them from
//! (shaders/transmission.wgsl): the Khronos glTF Sample Renderer's
//! screen-space method, with ordered layers.
//!
//! Layer 0 is the opaque scene (and the environment's background) drawn
//! first into an image of its own at the frame's size, in linear
//! radiance ([`TRANSMISSION_FORMAT`]), with a mip chain of 2 × 2 means
//! (shaders/transmission_mips.wgsl) that the roughness blurs by. With
//! `shading.transmission_layers = L > 1`, layer `k` starts as a copy of
//! layer `k − 1` and gets the transmissive objects that read layer
//! `k − 1` drawn over it, so an object that reads layer `k` sees the
//! glass behind it (the objects sorted back to front by their centres,
//! [`crate::scene::TransmissionSettings::layer_of`]). Each layer keeps
//! its own image because the main pass reads them all, each object its
//! own; they share one depth target, kept from layer to layer.
//!
//! Group 4 of a scene pipeline that draws transmission is a layer's
//! image and the trilinear sampler ([`group_layout`]); while layer 0 is
//! drawn, the pipelines read a 1 × 1 black image instead (an image may
//! not be read and drawn into by one pass). With the traced exit
//! (`shading.transmission_exit_ray = "traced"`), group 4 also holds the
//! back faces and the opaque scene's depth
//! (src/gpu/transmission_back_faces.rs).

use super::formats::{DEPTH_FORMAT, TRANSMISSION_FORMAT};
use super::transmission_back_faces::{self as back_faces, ExitImages};
use crate::{Error, Result};

/// The bind group index of the transmission image.
pub const GROUP: u32 = 4;

/// Group 4's layout: the image (filterable, read in the fragment or,
/// for vertex shading, the vertex stage) and its sampler; with `traced`,
/// the traced exit's images after them ([`back_faces::group_entries`]).
pub fn group_layout(device: &wgpu::Device, traced: bool) -> wgpu::BindGroupLayout {
    let mut entries = group_entries().to_vec();
    if traced {
        entries.extend(back_faces::group_entries());
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio transmission image"),
        entries: &entries,
    })
}

/// The entries of [`group_layout`].
pub fn group_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    [
        super::layout_entries::filterable_texture_2d(0, stage),
        super::layout_entries::filtering_sampler(1, stage),
    ]
}

/// Refuses a device that cannot bind group 4 (WebGPU guarantees 4
/// groups; Vulkan drivers, lavapipe included, offer 8).
pub fn check_limits(device: &wgpu::Device) -> Result<()> {
    let groups = device.limits().max_bind_groups;
    if groups > GROUP {
        return Ok(());
    }
    Err(Error::argument(
        "shading.transmission",
        format!(
            "the GPU binds at most {groups} bind groups and the transmission image needs a fifth; set shading.transmission = \"off\" (transmissive materials drawn as if opaque) or render with --reference"
        ),
    ))
}

/// Levels of a full mip chain of `width × height`: down to 1 × 1.
pub fn mip_levels(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// One layer's image: its mip chain, the views of each level (targets of
/// the passes) and the bind groups that read it.
struct LayerImage {
    texture: wgpu::Texture,
    /// Each level alone: level 0 is drawn into, level `i` from `i − 1`.
    levels: Vec<wgpu::TextureView>,
    /// Level `i` as the source of level `i + 1`'s pass.
    level_sources: Vec<wgpu::BindGroup>,
    /// The whole chain with the sampler: group 4 of the scene pipelines.
    group: wgpu::BindGroup,
}

/// The transmission images of one frame size, their depth target and the
/// mip pass.
pub struct TransmissionImages {
    /// `(width, height)` of level 0: the frame's.
    pub size: (u32, u32),
    layers: Vec<LayerImage>,
    depth_texture: wgpu::Texture,
    depth: wgpu::TextureView,
    /// The traced exit's images (`None` unless the scene traces it).
    exit: Option<ExitImages>,
    /// Group 4 over a black 1 × 1 image, bound while layer 0 is drawn.
    black: wgpu::BindGroup,
    mip_pipeline: wgpu::RenderPipeline,
}

impl TransmissionImages {
    /// `layers` images of `size` with their chains (`group` is
    /// [`group_layout`] of `traced`), and the traced exit's images with
    /// `traced`.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        group: &wgpu::BindGroupLayout,
        size: (u32, u32),
        (layers, traced): (u32, bool),
    ) -> Self {
        let (width, height) = (size.0.max(1), size.1.max(1));
        let exit = traced.then(|| ExitImages::new(device, (width, height)));
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("gonio transmission"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            address_mode_w: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let source_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gonio transmission mip source"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            }],
        });
        let group_of = |view: &wgpu::TextureView| {
            let mut entries = vec![
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
            ];
            if let Some(exit) = &exit {
                entries.extend(exit.bind_entries());
            }
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("gonio transmission image"),
                layout: group,
                entries: &entries,
            })
        };
        let levels = mip_levels(width, height);
        let images = (0..layers.max(1))
            .map(|_| {
                let texture = image(device, (width, height), levels);
                let level_views: Vec<_> = (0..levels)
                    .map(|level| {
                        texture.create_view(&wgpu::TextureViewDescriptor {
                            base_mip_level: level,
                            mip_level_count: Some(1),
                            ..Default::default()
                        })
                    })
                    .collect();
                let level_sources = level_views
                    .iter()
                    .map(|view| {
                        device.create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some("gonio transmission mip source"),
                            layout: &source_layout,
                            entries: &[wgpu::BindGroupEntry {
                                binding: 0,
                                resource: wgpu::BindingResource::TextureView(view),
                            }],
                        })
                    })
                    .collect();
                let group = group_of(&texture.create_view(&Default::default()));
                LayerImage {
                    texture,
                    levels: level_views,
                    level_sources,
                    group,
                }
            })
            .collect();
        let black_texture = image(device, (1, 1), 1);
        queue.write_texture(
            black_texture.as_image_copy(),
            &[0u8; 8],
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(8),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
        );
        let black = group_of(&black_texture.create_view(&Default::default()));
        // Copied from with the traced exit (the opaque scene's depth).
        let depth_texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("gonio transmission depth"),
            size: extent(width, height),
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        TransmissionImages {
            size: (width, height),
            layers: images,
            depth: depth_texture.create_view(&Default::default()),
            depth_texture,
            exit,
            black,
            mip_pipeline: mip_pipeline(device, &source_layout),
        }
    }

    /// Images this holds.
    pub fn layer_count(&self) -> usize {
        self.layers.len()
    }

    /// Group 4 reading layer `layer`'s image.
    pub fn group(&self, layer: usize) -> &wgpu::BindGroup {
        &self.layers[layer].group
    }

    /// Group 4 over a black image (while layer 0 is drawn).
    pub fn black_group(&self) -> &wgpu::BindGroup {
        &self.black
    }

    /// The traced exit's images, if the scene traces it.
    pub fn exit(&self) -> Option<&ExitImages> {
        self.exit.as_ref()
    }

    /// Records the copy of layer 0's depth (the opaque scene's) for the
    /// traced exit; nothing without it. Call after layer 0 is drawn.
    pub fn copy_scene_depth(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some(exit) = &self.exit {
            exit.copy_scene_depth(encoder, &self.depth_texture);
        }
    }

    /// Begins the pass that draws into level 0 of layer `layer`: layer 0
    /// cleared (colour to transparent black, depth to the far plane),
    /// a later one first copied from the layer before (colour; the depth
    /// is kept) and loaded.
    pub fn begin_layer<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        layer: usize,
    ) -> wgpu::RenderPass<'e> {
        if layer > 0 {
            encoder.copy_texture_to_texture(
                self.layers[layer - 1].texture.as_image_copy(),
                self.layers[layer].texture.as_image_copy(),
                extent(self.size.0, self.size.1),
            );
        }
        let first = layer == 0;
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("gonio transmission layer"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.layers[layer].levels[0],
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: if first {
                        wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                    } else {
                        wgpu::LoadOp::Load
                    },
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth,
                depth_ops: Some(wgpu::Operations {
                    load: if first {
                        wgpu::LoadOp::Clear(1.0)
                    } else {
                        wgpu::LoadOp::Load
                    },
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }

    /// Records the mip chain of layer `layer` from its level 0, one pass
    /// a level.
    pub fn encode_mips(&self, encoder: &mut wgpu::CommandEncoder, layer: usize) {
        let image = &self.layers[layer];
        for level in 1..image.levels.len() {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("gonio transmission mip"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &image.levels[level],
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
            pass.set_pipeline(&self.mip_pipeline);
            pass.set_bind_group(0, &image.level_sources[level - 1], &[]);
            pass.draw(0..3, 0..1);
        }
    }
}

fn extent(width: u32, height: u32) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    }
}

/// A transmission image of `levels` mip levels: drawn into, read, copied.
fn image(device: &wgpu::Device, (width, height): (u32, u32), levels: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("gonio transmission image"),
        size: extent(width, height),
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: TRANSMISSION_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// The pass that writes one mip level from the level above
/// (shaders/transmission_mips.wgsl).
fn mip_pipeline(device: &wgpu::Device, source: &wgpu::BindGroupLayout) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gonio transmission mips"),
        source: wgpu::ShaderSource::Wgsl(
            super::shader_gen::sources::get("transmission_mips.wgsl").into(),
        ),
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("gonio transmission mips"),
        bind_group_layouts: &[Some(source)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("gonio transmission mips"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_mip"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_mip"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: TRANSMISSION_FORMAT,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mip_chain_ends_at_one_texel() {
        assert_eq!(mip_levels(1, 1), 1);
        assert_eq!(mip_levels(2, 1), 2);
        assert_eq!(mip_levels(128, 96), 8);
        assert_eq!(mip_levels(129, 2), 8);
    }
}
