//! The environment map on the GPU (bind group 3, only for scenes with
//! `[environment] map`; other scenes' pipelines and images are unchanged):
//! the texels as an `Rgba32Float` texture, a uniform with the map's scale,
//! size and SH irradiance coefficients and the camera's ray basis, the
//! tables of the prefiltered and sampled modes (with the sheen stack
//! where a drawn sheen reads it), and the
//! background pass (shaders/environment_background.wgsl) that shows the
//! map where no geometry is.

use super::bind_groups::SceneLayouts;
use super::formats::DEPTH_FORMAT;
use super::layout_entries::{read_only_storage, unfilterable_texture_2d};
use super::shader_gen::{self, Output};
use crate::environment::importance::ImportanceTable;
use crate::environment::map::{MapData, Specular};
use crate::environment::prefiltered::{self, Prefiltered};
use crate::environment::prefiltered_zonal::ZonalStack;
use crate::environment::{EnvironmentMap, sh};
use crate::material::brdf::dfg;
use crate::scene::Scene;
use crate::scene::sheen_stack::sheen_stack;
use crate::{Error, Result};
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;

/// `EnvironmentUniform` in shaders/environment.wgsl (864 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuEnvironmentUniform {
    pub forward: [f32; 3],
    pub scale: f32,
    pub right: [f32; 3],
    pub width: u32,
    pub up: [f32; 3],
    pub height: u32,
    /// `scale · Â_l · L_lm`, RGB and a zero.
    pub sh: [[f32; 4]; sh::COUNT],
    /// `(cos θ, sin θ)` of `rotation_deg` (`EnvironmentMap::to_map`).
    pub rotation: [f32; 2],
    /// Directions per shading point of the sampled mode.
    pub samples: u32,
    /// A level's width of the prefiltered stack (prefiltered mode).
    pub prefilter_width: u32,
    /// `scale · L_lm` up to `sh_order`, RGB and a zero (the `"sh"`
    /// mode's Phong convolution, `EnvironmentMap::radiance_coefficients`).
    pub sh_radiance: [[f32; 4]; sh::COUNT],
}

impl GpuEnvironmentUniform {
    /// The values of `map` seen by `scene`'s camera: the ray basis of
    /// `Camera::ray` (forward, right · tan(fov/2) · aspect, up · tan(fov/2)).
    pub fn new(scene: &Scene, map: &EnvironmentMap) -> Self {
        let camera = &scene.camera;
        let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
        let aspect = scene.width as f64 / scene.height as f64;
        let f = |v: glam::DVec3| v.as_vec3().to_array();
        let c = map.irradiance_coefficients();
        GpuEnvironmentUniform {
            forward: f(camera.forward()),
            scale: map.settings.scale as f32,
            right: f(camera.right() * (tan_half * aspect)),
            width: map.data.width,
            up: f(camera.true_up() * tan_half),
            height: map.data.height,
            sh: std::array::from_fn(|i| {
                let v = c[i].as_vec3();
                [v.x, v.y, v.z, 0.0]
            }),
            rotation: {
                let (sin, cos) = map.settings.rotation_deg.to_radians().sin_cos();
                [cos as f32, sin as f32]
            },
            samples: map.settings.samples.max(1),
            prefilter_width: map.settings.prefilter_size,
            sh_radiance: {
                let c = map.radiance_coefficients();
                std::array::from_fn(|i| {
                    let v = c[i].as_vec3();
                    [v.x, v.y, v.z, 0.0]
                })
            },
        }
    }
}

/// The entries of group 3: the uniform, the map's texels, the
/// prefiltered stack, the DFG table and the importance table.
pub fn group_entries() -> [wgpu::BindGroupLayoutEntry; 6] {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    [
        wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: stage,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(size_of::<GpuEnvironmentUniform>() as u64),
            },
            count: None,
        },
        unfilterable_texture_2d(1, stage),
        // The prefiltered stack and the environment BRDF table: bound in
        // every mode, 1 × 1 where the mode does not read them.
        unfilterable_texture_2d(2, stage),
        unfilterable_texture_2d(3, stage),
        read_only_storage(4, stage, wgpu::BufferSize::new(IMPORTANCE_HEADER + 16)),
        // The sheen stack: bound in every mode, 1 × 1 where no drawn
        // sheen reads it.
        unfilterable_texture_2d(5, stage),
    ]
}

/// Bytes before the entries of `EnvironmentImportance`
/// (shaders/environment_sampled.wgsl): width, height, whether the sampled
/// mode draws by the map, a zero.
const IMPORTANCE_HEADER: u64 = 16;

/// The importance table of `map` in the sampled mode (bound at 4, with
/// the `Arc` uploaded), else a header of zeros and one zero entry.
fn importance_buffer(
    device: &wgpu::Device,
    map: &EnvironmentMap,
) -> (Option<Arc<ImportanceTable>>, wgpu::Buffer) {
    use wgpu::util::DeviceExt;
    let (table, header, entries) = if map.settings.specular == Specular::Sampled {
        let t = map.data.importance();
        let header = [t.width, t.height, t.concentrated() as u32, 0];
        let entries = t.gpu_entries();
        (Some(t), header, entries)
    } else {
        (None, [0; 4], vec![[0.0; 4]])
    };
    let mut bytes = Vec::with_capacity(IMPORTANCE_HEADER as usize + 16 * entries.len());
    bytes.extend_from_slice(bytemuck::cast_slice(&header));
    bytes.extend_from_slice(bytemuck::cast_slice(&entries));
    let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("gonio environment importance"),
        contents: &bytes,
        usage: wgpu::BufferUsages::STORAGE,
    });
    (table, buffer)
}

/// An `Rgba32Float` texture of `width × height` texels `rgba`, uploaded.
fn float_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    rgba: &[[f32; 4]],
) -> wgpu::TextureView {
    let size = wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(rgba),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(16 * width),
            rows_per_image: None,
        },
        size,
    );
    texture.create_view(&Default::default())
}

/// A stack of [`prefiltered::LEVELS`] levels of `width × height` RGB
/// texels (level k at rows k·height), uploaded.
fn stack_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    width: u32,
    height: u32,
    texels: &[[f32; 3]],
) -> wgpu::TextureView {
    let rgba: Vec<[f32; 4]> = texels.iter().map(|t| [t[0], t[1], t[2], 0.0]).collect();
    float_texture(
        device,
        queue,
        label,
        width,
        height * prefiltered::LEVELS,
        &rgba,
    )
}

/// The prefiltered stack and the environment BRDF table of `map` when its
/// mode reads them, else 1 × 1 stand-ins.
fn split_sum_textures(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    map: &EnvironmentMap,
) -> (
    Option<Arc<Prefiltered>>,
    wgpu::TextureView,
    wgpu::TextureView,
) {
    if map.settings.specular != Specular::Prefiltered {
        let zero = [[0.0f32; 4]];
        return (
            None,
            float_texture(device, queue, "gonio no prefiltered map", 1, 1, &zero),
            float_texture(device, queue, "gonio no DFG table", 1, 1, &zero),
        );
    }
    let p = map.prefiltered();
    let stack = stack_texture(
        device,
        queue,
        "gonio prefiltered map",
        p.width,
        p.height,
        &p.texels,
    );
    let table: Vec<[f32; 4]> = dfg::table()
        .entries
        .iter()
        .map(|e| [e[0], e[1], 0.0, 0.0])
        .collect();
    let size = dfg::SIZE as u32;
    let dfg = float_texture(device, queue, "gonio DFG table", size, size, &table);
    (Some(p), stack, dfg)
}

/// Whether `scene` reads the sheen stack: the prefiltered mode and a
/// drawn material with a sheen (the shader's `layer_sheen`).
fn reads_sheen_stack(scene: &Scene, map: &EnvironmentMap) -> bool {
    map.settings.specular == Specular::Prefiltered
        && scene
            .meshes
            .iter()
            .any(|m| scene.materials[m.material].gltf_layers_used().sheen)
}

/// The sheen stack of `map` when `scene` reads it (uploaded), else a
/// 1 × 1 stand-in.
fn sheen_stack_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &Scene,
    map: &EnvironmentMap,
) -> (Option<Arc<ZonalStack>>, wgpu::TextureView) {
    if !reads_sheen_stack(scene, map) {
        let zero = [[0.0f32; 4]];
        let view = float_texture(device, queue, "gonio no sheen stack", 1, 1, &zero);
        return (None, view);
    }
    let z = sheen_stack(map);
    let view = stack_texture(
        device,
        queue,
        "gonio sheen stack",
        z.width,
        z.height,
        &z.texels,
    );
    (Some(z), view)
}

/// Group 3's layout, and the background pass's pipeline layout (groups 0
/// and 3). Scene pipelines join it with their other groups
/// (`PipelineCache::compile_scene`).
pub struct EnvironmentLayouts {
    pub group: wgpu::BindGroupLayout,
    /// Groups 0 and 3.
    pub plain: wgpu::PipelineLayout,
}

impl EnvironmentLayouts {
    /// Group 3 and its layout over `scene`'s group 0.
    pub fn new(device: &wgpu::Device, scene: &SceneLayouts) -> Self {
        let group = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gonio environment"),
            entries: &group_entries(),
        });
        let plain = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gonio scene with environment"),
            bind_group_layouts: &[Some(&scene.scene_group), None, None, Some(&group)],
            immediate_size: 0,
        });
        EnvironmentLayouts { group, plain }
    }
}

/// The background pass's pipeline drawing into `format` with `samples`:
/// a full-screen triangle at the far plane, drawn after the opaque
/// geometry where the depth is still the clear value (test `LessEqual`,
/// no write): early depth testing skips the pixels the geometry covers.
pub fn background_pipeline(
    device: &wgpu::Device,
    layouts: &EnvironmentLayouts,
    format: wgpu::TextureFormat,
    samples: u32,
    tone_map: crate::output::tone_map::ToneMap,
) -> Result<wgpu::RenderPipeline> {
    let wgsl = shader_gen::compose_background(Output::for_format(format), tone_map);
    shader_gen::validate(&wgsl)
        .map_err(|e| Error::Gpu(format!("the background shader is invalid: {e}")))?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gonio background"),
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    Ok(
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("gonio background"),
            layout: Some(&layouts.plain),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_background"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: samples,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_background"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        }),
    )
}

/// A scene's environment map on the GPU.
pub struct GpuEnvironment {
    /// The texels uploaded (to tell a new map from new settings).
    data: Arc<MapData>,
    /// The prefiltered stack uploaded, if the mode reads one.
    prefiltered: Option<Arc<Prefiltered>>,
    /// The importance table uploaded, if the mode reads one.
    importance: Option<Arc<ImportanceTable>>,
    /// The sheen stack uploaded, if the scene reads it.
    sheen: Option<Arc<ZonalStack>>,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    background: wgpu::RenderPipeline,
}

impl GpuEnvironment {
    /// Uploads `scene`'s map (`None` without one), drawn in the background
    /// by `background` ([`background_pipeline`]).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &EnvironmentLayouts,
        background: wgpu::RenderPipeline,
        scene: &Scene,
    ) -> Result<Option<Self>> {
        let Some(map) = &scene.environment.map else {
            return Ok(None);
        };
        let data = &map.data;
        let max = device.limits().max_texture_dimension_2d;
        if data.width > max {
            return Err(Error::Scene(format!(
                "the environment map {} is {} × {} texels; this GPU takes textures of at most {max} a side",
                data.name, data.width, data.height
            )));
        }
        let size = wgpu::Extent3d {
            width: data.width,
            height: data.height,
            depth_or_array_layers: 1,
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("gonio environment map"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let rgba: Vec<[f32; 4]> = data
            .texels
            .iter()
            .map(|t| [t[0], t[1], t[2], 0.0])
            .collect();
        queue.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(&rgba),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(16 * data.width),
                rows_per_image: None,
            },
            size,
        );
        use wgpu::util::DeviceExt;
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("gonio environment"),
            contents: bytemuck::bytes_of(&GpuEnvironmentUniform::new(scene, map)),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let view = texture.create_view(&Default::default());
        let (prefiltered, stack, table) = split_sum_textures(device, queue, map);
        let (importance, importance_table) = importance_buffer(device, map);
        let (sheen, sheen_view) = sheen_stack_texture(device, queue, scene, map);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio environment"),
            layout: &layouts.group,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&stack),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&table),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: importance_table.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::TextureView(&sheen_view),
                },
            ],
        });
        Ok(Some(GpuEnvironment {
            data: data.clone(),
            prefiltered,
            importance,
            sheen,
            uniform,
            bind_group,
            background,
        }))
    }

    /// Whether `scene` has this map's texels and, in the prefiltered
    /// mode, this stack, in the sampled mode its importance table (so
    /// [`Self::write`] suffices).
    pub fn holds(&self, scene: &Scene) -> bool {
        scene.environment.map.as_ref().is_some_and(|m| {
            Arc::ptr_eq(&m.data, &self.data)
                && match (&self.prefiltered, m.settings.specular) {
                    (Some(p), Specular::Prefiltered) => Arc::ptr_eq(p, &m.prefiltered()),
                    (None, Specular::Prefiltered) => false,
                    (_, _) => true,
                }
                && (m.settings.specular != Specular::Sampled || self.importance.is_some())
                && (self.sheen.is_some() || !reads_sheen_stack(scene, m))
        })
    }

    /// Writes the settings and the camera of `scene` (which [`Self::holds`]).
    pub fn write(&self, queue: &wgpu::Queue, scene: &Scene) {
        if let Some(map) = &scene.environment.map {
            let u = GpuEnvironmentUniform::new(scene, map);
            queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&u));
        }
    }

    /// Binds group 3 (the map the scene pipelines light with) without
    /// drawing the background: a later part of a split scene pass
    /// (src/gpu/scene_parts.rs).
    pub fn bind(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(3, &self.bind_group, &[]);
    }

    /// Binds group 3 and draws the background (group 0 must be bound).
    pub fn encode_background(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.encode_background_with(pass, &self.background);
    }

    /// [`Self::encode_background`] with `pipeline`, a
    /// [`background_pipeline`] for another target (the transmission
    /// image's, src/gpu/transmission.rs).
    pub fn encode_background_with(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        pipeline: &wgpu::RenderPipeline,
    ) {
        self.bind(pass);
        pass.set_pipeline(pipeline);
        pass.draw(0..3, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_uniform_has_the_wgsl_layout() {
        // 3 × 16 bytes of vectors and scalars, 25 vec4, the rotation,
        // 25 vec4 (the radiance coefficients).
        assert_eq!(
            size_of::<GpuEnvironmentUniform>(),
            48 + 25 * 16 + 16 + 25 * 16
        );
    }
}
