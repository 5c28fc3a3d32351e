//! Where the scene's arrays live on the GPU, and the bind group layouts
//! that follow from it.
//!
//! Materials, lights and shadow-map views go into **uniform buffers** of a
//! fixed capacity when they fit, and into storage buffers otherwise.
//! Why: lavapipe (Mesa 22.3's llvmpipe) loads every word of a storage
//! buffer lane by lane, each with its own bounds check, even at an index
//! that is the same for every pixel; a uniform buffer at such an index is
//! one scalar load. The shadow lookup reads a light and a 4×4 matrix per
//! pixel, so on the viewer's 1080p benchmark scene (one shadowed
//! directional light) the scene pass went from 44 to 34 ms with these
//! arrays in uniform buffers, the same code otherwise. A uniform binding
//! is limited to 64 KiB (WebGPU's default `maxUniformBufferBindingSize`),
//! hence the capacities; a scene with more keeps storage buffers, and the
//! shader is compiled for whichever it has (`#if uniform_*` features).
//!
//! The shadow casters' indices (at most `MAX_SHADOW_MAPS` of them) are
//! always in a uniform buffer, four to a 16-byte row (uniform arrays have
//! a 16-byte stride).

use super::layout::{GpuLight, GpuMaterial, GpuShadowView};
use super::shadows::MAX_SHADOW_MAPS;

/// Materials a uniform buffer holds (96 bytes each: 24 KiB).
pub const UNIFORM_MATERIALS: usize = 256;
/// Lights (area-light samples included) a uniform buffer holds (112 bytes
/// each: 28 KiB).
pub const UNIFORM_LIGHTS: usize = 256;
/// Shadow-map layers a uniform buffer holds (64 bytes each: 24 KiB; 64
/// cube maps).
pub const UNIFORM_SHADOW_VIEWS: usize = 384;
/// Rows of four caster indices: `MAX_SHADOW_MAPS` indices.
pub const CASTER_ROWS: usize = MAX_SHADOW_MAPS / 4;

/// Which of the scene's arrays are in uniform buffers (`true`) rather
/// than storage buffers. Part of the [`super::shader_gen::ShaderKey`]:
/// it changes the WGSL declarations and the bind group layouts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct UniformArrays {
    pub materials: bool,
    pub lights: bool,
    pub shadow_views: bool,
}

impl UniformArrays {
    /// Uniform wherever the count fits the capacity.
    pub fn for_counts(materials: usize, lights: usize, shadow_views: usize) -> Self {
        UniformArrays {
            materials: materials <= UNIFORM_MATERIALS,
            lights: lights <= UNIFORM_LIGHTS,
            shadow_views: shadow_views <= UNIFORM_SHADOW_VIEWS,
        }
    }

    /// The `#if` features of these choices (shaders/common.wgsl,
    /// shaders/shadows.wgsl).
    pub fn features(self) -> impl Iterator<Item = &'static str> {
        [
            (self.materials, "uniform_materials"),
            (self.lights, "uniform_lights"),
            (self.shadow_views, "uniform_shadow_views"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
    }

    /// The WGSL constants the uniform declarations size their arrays with.
    pub fn wgsl_capacities() -> String {
        format!(
            "const MATERIAL_CAPACITY: u32 = {UNIFORM_MATERIALS}u;\nconst LIGHT_CAPACITY: u32 = {UNIFORM_LIGHTS}u;\nconst SHADOW_VIEW_CAPACITY: u32 = {UNIFORM_SHADOW_VIEWS}u;\nconst CASTER_ROWS: u32 = {CASTER_ROWS}u;\n"
        )
    }
}

/// The bytes of a buffer bound as one array: `contents`, padded with
/// zeros to `capacity` elements of `element` bytes when the binding is a
/// uniform array (whose declared size the buffer must cover).
pub fn array_bytes(contents: &[u8], uniform: bool, capacity: usize, element: usize) -> Vec<u8> {
    let mut bytes = contents.to_vec();
    if uniform {
        debug_assert!(bytes.len() <= capacity * element);
        bytes.resize(capacity * element, 0);
    }
    bytes
}

/// [`array_bytes`] for materials.
pub fn material_bytes(materials: &[GpuMaterial], uniform: bool) -> Vec<u8> {
    array_bytes(
        bytemuck::cast_slice(materials),
        uniform,
        UNIFORM_MATERIALS,
        size_of::<GpuMaterial>(),
    )
}

/// [`array_bytes`] for lights.
pub fn light_bytes(lights: &[GpuLight], uniform: bool) -> Vec<u8> {
    array_bytes(
        bytemuck::cast_slice(lights),
        uniform,
        UNIFORM_LIGHTS,
        size_of::<GpuLight>(),
    )
}

/// [`array_bytes`] for shadow-map views.
pub fn shadow_view_bytes(views: &[GpuShadowView], uniform: bool) -> Vec<u8> {
    array_bytes(
        bytemuck::cast_slice(views),
        uniform,
        UNIFORM_SHADOW_VIEWS,
        size_of::<GpuShadowView>(),
    )
}

/// The caster indices as `CASTER_ROWS` rows of four.
pub fn caster_bytes(casters: &[u32]) -> Vec<u8> {
    array_bytes(bytemuck::cast_slice(casters), true, 4 * CASTER_ROWS, 4)
}

/// The buffer usage of an array binding.
pub fn usage(uniform: bool) -> wgpu::BufferUsages {
    if uniform {
        wgpu::BufferUsages::UNIFORM
    } else {
        wgpu::BufferUsages::STORAGE
    }
}

fn buffer_entry(binding: u32, uniform: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: if uniform {
                wgpu::BufferBindingType::Uniform
            } else {
                wgpu::BufferBindingType::Storage { read_only: true }
            },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Group 0 of a scene pipeline: globals, materials, lights.
pub fn scene_group_layout(device: &wgpu::Device, arrays: UniformArrays) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio scene"),
        entries: &[
            buffer_entry(0, true),
            buffer_entry(1, arrays.materials),
            buffer_entry(2, arrays.lights),
        ],
    })
}

/// Group 1 of a scene pipeline with shadows: maps, comparison sampler,
/// layer views, casters.
pub fn shadow_group_layout(device: &wgpu::Device, arrays: UniformArrays) -> wgpu::BindGroupLayout {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio shadow maps"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: stage,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Depth,
                    view_dimension: wgpu::TextureViewDimension::D2Array,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: stage,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                count: None,
            },
            buffer_entry(2, arrays.shadow_views),
            buffer_entry(3, true),
        ],
    })
}

/// The layouts of scene pipelines for one [`UniformArrays`] choice.
pub struct SceneLayouts {
    pub scene_group: wgpu::BindGroupLayout,
    pub shadow_group: wgpu::BindGroupLayout,
    /// Group 0 only.
    pub plain: wgpu::PipelineLayout,
    /// Groups 0 and 1.
    pub shadowed: wgpu::PipelineLayout,
}

impl SceneLayouts {
    pub fn new(device: &wgpu::Device, arrays: UniformArrays) -> Self {
        let scene_group = scene_group_layout(device, arrays);
        let shadow_group = shadow_group_layout(device, arrays);
        let plain = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gonio scene"),
            bind_group_layouts: &[Some(&scene_group)],
            immediate_size: 0,
        });
        let shadowed = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gonio scene with shadows"),
            bind_group_layouts: &[Some(&scene_group), Some(&shadow_group)],
            immediate_size: 0,
        });
        SceneLayouts {
            scene_group,
            shadow_group,
            plain,
            shadowed,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bytemuck::Zeroable;

    #[test]
    fn uniform_arrays_fit_a_uniform_binding() {
        // WebGPU's default maxUniformBufferBindingSize, which gonio requests.
        let limit = 64 << 10;
        assert!(UNIFORM_MATERIALS * size_of::<GpuMaterial>() <= limit);
        assert!(UNIFORM_LIGHTS * size_of::<GpuLight>() <= limit);
        assert!(UNIFORM_SHADOW_VIEWS * size_of::<GpuShadowView>() <= limit);
        // Uniform arrays have a 16-byte stride.
        for size in [
            size_of::<GpuMaterial>(),
            size_of::<GpuLight>(),
            size_of::<GpuShadowView>(),
        ] {
            assert_eq!(size % 16, 0);
        }
        assert_eq!(MAX_SHADOW_MAPS % 4, 0);
    }

    #[test]
    fn counts_past_a_capacity_stay_in_storage() {
        let a = UniformArrays::for_counts(UNIFORM_MATERIALS, UNIFORM_LIGHTS + 1, 6);
        assert!(a.materials && !a.lights && a.shadow_views);
        assert_eq!(
            a.features().collect::<Vec<_>>(),
            ["uniform_materials", "uniform_shadow_views"]
        );
    }

    #[test]
    fn uniform_arrays_are_padded_to_capacity() {
        let m = [GpuMaterial::zeroed(); 3];
        assert_eq!(
            material_bytes(&m, true).len(),
            UNIFORM_MATERIALS * size_of::<GpuMaterial>()
        );
        assert_eq!(
            material_bytes(&m, false).len(),
            3 * size_of::<GpuMaterial>()
        );
        assert_eq!(caster_bytes(&[1, 2]).len(), 4 * MAX_SHADOW_MAPS);
    }
}
