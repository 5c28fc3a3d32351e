//! Alpha MASK in the shadow passes: light passes through what MASK cuts
//! out (glTF 2.0 §3.9.4), as the reference's shadow rays pass through it
//! (`reference::renderer`, `Shader::blocks`).
//!
//! Opaque and BLEND casters keep the depth-only pass (position only, no
//! fragment stage: `shaders/shadow_pass.wgsl`); the batches of MASK
//! materials are drawn by a second pipeline (`shaders/shadow_pass_masked.wgsl`)
//! that reads the UV sets and `COLOR_0` of the same stream and discards
//! fragments whose alpha (the factor's × `COLOR_0`'s A × the base colour
//! texture's A at level 0) is below the cutoff. BLEND casts as opaque
//! (docs/gltf-surfaces.md says why).

use super::geometry::VertexLayout;
use super::shader_gen::Feature;
use super::textures::SceneTextures;
use crate::material::{AlphaMode, Material};
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

/// `ShadowMask` of `shaders/shadow_pass_masked.wgsl` (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuShadowMask {
    pub row_u: [f32; 4],
    pub row_v: [f32; 4],
    pub alpha: f32,
    pub cutoff: f32,
    pub tex_coord: u32,
    pub _pad: u32,
}

/// The mask record of every material (index for index), `None` for
/// those that are not alpha MASK. `materials`: the effective ones.
pub fn records(materials: &[Material]) -> Vec<Option<GpuShadowMask>> {
    materials
        .iter()
        .map(|m| {
            let AlphaMode::Mask { cutoff } = m.alpha_mode else {
                return None;
            };
            let texture = m.textures.iter().find(|t| t.carries_alpha());
            let matrix = texture.map_or(glam::DMat3::IDENTITY, |t| t.transform.matrix());
            let row = |r: usize| {
                [
                    matrix.x_axis[r] as f32,
                    matrix.y_axis[r] as f32,
                    matrix.z_axis[r] as f32,
                    0.0,
                ]
            };
            Some(GpuShadowMask {
                row_u: row(0),
                row_v: row(1),
                alpha: m.alpha as f32,
                cutoff: cutoff as f32,
                tex_coord: texture.map_or(0, |t| t.tex_coord as u32),
                _pad: 0,
            })
        })
        .collect()
}

/// The masked shadow pipeline and each MASK material's group 1.
pub struct ShadowMasks {
    pipeline: wgpu::RenderPipeline,
    /// Per scene material: its group 1 if it is alpha MASK.
    groups: Vec<Option<wgpu::BindGroup>>,
    /// The records the groups hold ([`records`]).
    records: Vec<Option<GpuShadowMask>>,
}

impl ShadowMasks {
    /// The masked pass of `scene` over a stream of `layout`, reading the
    /// base colour textures of `textures`; `None` when no material the
    /// scene draws is alpha MASK (the depth-only pass then draws all).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        pass_group_layout: &wgpu::BindGroupLayout,
        layout: VertexLayout,
        scene: &Scene,
        textures: Option<&SceneTextures>,
    ) -> Option<Self> {
        let materials = scene.effective_materials();
        let records = records(&materials);
        let drawn = |m: usize| scene.meshes.iter().any(|mesh| mesh.material == m);
        if !records
            .iter()
            .enumerate()
            .any(|(m, r)| r.is_some() && drawn(m))
        {
            return None;
        }
        let group_layout = group_layout(device);
        let pipeline = pipeline(device, pass_group_layout, &group_layout, layout);
        let white = white_texel(device, queue);
        let white_sampler = device.create_sampler(&wgpu::SamplerDescriptor::default());
        let groups = records
            .iter()
            .enumerate()
            .map(|(m, record)| {
                let record = record.as_ref()?;
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("gonio shadow mask"),
                    contents: bytemuck::bytes_of(record),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let (view, sampler) = textures
                    .and_then(|t| t.alpha_texture(m))
                    .unwrap_or((&white, &white_sampler));
                Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("gonio shadow mask"),
                    layout: &group_layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: buffer.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::Sampler(sampler),
                        },
                    ],
                }))
            })
            .collect();
        Some(ShadowMasks {
            pipeline,
            groups,
            records,
        })
    }

    /// The records its groups hold ([`records`]): a material edit that
    /// changes them makes the pass anew.
    pub fn records(&self) -> &[Option<GpuShadowMask>] {
        &self.records
    }

    /// The masked pipeline.
    pub fn pipeline(&self) -> &wgpu::RenderPipeline {
        &self.pipeline
    }

    /// Group 1 of material `m` if it is alpha MASK.
    pub fn group(&self, m: u32) -> Option<&wgpu::BindGroup> {
        self.groups.get(m as usize).and_then(Option::as_ref)
    }
}

/// Group 1: the mask record, the texture, its sampler.
fn group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio shadow mask"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: stages,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
            super::layout_entries::filterable_texture_2d(1, stages),
            super::layout_entries::filtering_sampler(2, stages),
        ],
    })
}

/// The masked pass's source for a stream of `layout`: its UV sets and
/// colours only where the stream has them.
pub fn source(layout: VertexLayout) -> Result<String, String> {
    let mut features = Vec::new();
    if layout.tex_coords {
        features.push(Feature::Textures);
    }
    if layout.colors {
        features.push(Feature::VertexColors);
    }
    super::shader_gen::preprocess(
        "shadow_pass_masked.wgsl",
        super::shader_gen::sources::get("shadow_pass_masked.wgsl"),
        &features,
    )
}

/// The masked pipeline: the depth-only pass's state (reversed depth,
/// every face), the stream's position, UVs and colour, and the discard.
fn pipeline(
    device: &wgpu::Device,
    pass_group_layout: &wgpu::BindGroupLayout,
    group_layout: &wgpu::BindGroupLayout,
    layout: VertexLayout,
) -> wgpu::RenderPipeline {
    let wgsl = source(layout).expect("shaders/shadow_pass_masked.wgsl preprocesses");
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gonio masked shadow pass"),
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    let attributes: Vec<wgpu::VertexAttribute> = layout
        .attributes()
        .into_iter()
        .filter(|a| matches!(a.shader_location, 0 | 6 | 7 | 9))
        .collect();
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("gonio masked shadow pass"),
        bind_group_layouts: &[Some(pass_group_layout), Some(group_layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("gonio masked shadow pass"),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_shadow_masked"),
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
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(super::pipelines::shadow_depth_state()),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_shadow_masked"),
            compilation_options: Default::default(),
            targets: &[],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A 1×1 white texture view (a MASK material without a base colour
/// texture).
fn white_texel(device: &wgpu::Device, queue: &wgpu::Queue) -> wgpu::TextureView {
    let one = half::f16::ONE.to_bits();
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some("gonio white texel"),
                size: wgpu::Extent3d {
                    width: 1,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: super::textures::TEXTURE_FORMAT,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(&[one; 4]),
        )
        .create_view(&Default::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_record_mirrors_the_wgsl_and_each_stream_validates() {
        assert_eq!(size_of::<GpuShadowMask>(), 48);
        for (tex_coords, colors) in [(false, false), (true, false), (false, true), (true, true)] {
            let layout = VertexLayout {
                tangents: false,
                shading_point: false,
                face_normal: false,
                tex_coords,
                bitangent_signs: false,
                colors,
            };
            let wgsl = source(layout).unwrap();
            let module = super::super::shader_gen::validate(&wgsl).unwrap();
            let ty = module
                .types
                .iter()
                .find(|(_, t)| t.name.as_deref() == Some("ShadowMask"))
                .unwrap()
                .1;
            assert_eq!(ty.inner.size(module.to_ctx()), 48);
        }
    }
}
