//! The host side of the scene's bindings: the bytes of each buffer
//! (materials one per aligned slot, lights and shadow-map views padded
//! to the uniform capacity, caster indices four to a row) and the bind
//! group and pipeline layouts that read them. Which arrays are uniform
//! and why: src/gpu/bindings.rs.

use super::bindings::{
    CASTER_ROWS, UNIFORM_LIGHTS, UNIFORM_SHADOW_VIEWS, UniformArrays, array_bytes,
};
use super::layout::{GpuLight, GpuMaterial, GpuShadowView};
use super::shadows::MAX_SHADOW_MAPS;

// The caster rows hold exactly one index per shadow map.
const _: () = assert!(CASTER_ROWS * 4 == MAX_SHADOW_MAPS);

/// Bytes between two materials' slots in the materials buffer: a record
/// rounded up to the device's dynamic-offset alignment.
pub fn material_stride(device: &wgpu::Device) -> u64 {
    let align = u64::from(device.limits().min_uniform_buffer_offset_alignment);
    (size_of::<GpuMaterial>() as u64).div_ceil(align) * align
}

/// The materials buffer: one record per `stride` bytes.
pub fn material_bytes(materials: &[GpuMaterial], stride: u64) -> Vec<u8> {
    let mut bytes = vec![0u8; materials.len() * stride as usize];
    for (slot, m) in bytes.chunks_exact_mut(stride as usize).zip(materials) {
        slot[..size_of::<GpuMaterial>()].copy_from_slice(bytemuck::bytes_of(m));
    }
    bytes
}

/// The dynamic offset that binds `material`'s slot.
pub fn material_offset(material: u32, stride: u64) -> u32 {
    (u64::from(material) * stride) as u32
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

/// A binding of the materials buffer that shows one record (the draw's).
pub fn material_binding(buffer: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: 0,
        size: wgpu::BufferSize::new(size_of::<GpuMaterial>() as u64),
    })
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

/// Group 0 of a scene pipeline: globals, the draw's material (dynamic
/// offset), lights, the measured tables if the scene has a measured
/// material, the sheen's albedo table if a material has a sheen.
pub fn scene_group_layout(device: &wgpu::Device, arrays: UniformArrays) -> wgpu::BindGroupLayout {
    let material = wgpu::BindGroupLayoutEntry {
        binding: 1,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(size_of::<GpuMaterial>() as u64),
        },
        count: None,
    };
    let mut entries = vec![
        buffer_entry(0, true),
        material,
        buffer_entry(2, arrays.lights),
    ];
    if arrays.measured {
        entries.push(buffer_entry(3, false));
    }
    if arrays.sheen {
        entries.push(buffer_entry(4, true));
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio scene"),
        entries: &entries,
    })
}

/// Group 1 of a scene pipeline with shadows: maps, comparison sampler,
/// layer views, casters.
pub fn shadow_group_layout(device: &wgpu::Device, arrays: UniformArrays) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio shadow maps"),
        entries: &shadow_group_entries(arrays),
    })
}

/// The entries of [`shadow_group_layout`].
pub fn shadow_group_entries(arrays: UniformArrays) -> [wgpu::BindGroupLayoutEntry; 4] {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    [
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
    ]
}

/// The bind group layouts of scene pipelines for one [`UniformArrays`]
/// choice (groups 0 and 1), and the pipeline layout of group 0 alone.
/// Scene pipelines join them with the material textures' group 2, sized
/// per scene, and the environment's and transmission's groups
/// (`PipelineCache::compile_scene`).
pub struct SceneLayouts {
    pub scene_group: wgpu::BindGroupLayout,
    pub shadow_group: wgpu::BindGroupLayout,
    /// Group 0 only.
    pub plain: wgpu::PipelineLayout,
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
        SceneLayouts {
            scene_group,
            shadow_group,
            plain,
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
    fn uniform_arrays_are_padded_to_capacity() {
        let l = [GpuLight::zeroed(); 3];
        assert_eq!(
            light_bytes(&l, true).len(),
            UNIFORM_LIGHTS * size_of::<GpuLight>()
        );
        assert_eq!(light_bytes(&l, false).len(), 3 * size_of::<GpuLight>());
        assert_eq!(caster_bytes(&[1, 2]).len(), 4 * MAX_SHADOW_MAPS);
    }

    #[test]
    fn each_material_has_its_own_aligned_slot() {
        let mut m = [GpuMaterial::zeroed(); 3];
        m[2].k_e = 7.0;
        // The record rounded up to the common 256-byte offset alignment.
        let stride = (size_of::<GpuMaterial>() as u64).div_ceil(256) * 256;
        let bytes = material_bytes(&m, stride);
        assert_eq!(bytes.len(), 3 * stride as usize);
        let at = material_offset(2, stride) as usize;
        let slot: &GpuMaterial = bytemuck::from_bytes(&bytes[at..at + size_of::<GpuMaterial>()]);
        assert_eq!(slot.k_e, 7.0);
    }
}
