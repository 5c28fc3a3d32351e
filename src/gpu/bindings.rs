//! Where the scene's data live on the GPU, and the bind group layouts
//! that follow from it.
//!
//! Why it matters: lavapipe (Mesa 22.3's llvmpipe) loads every word of a
//! storage buffer lane by lane, each with its own bounds check, even at an
//! index that is the same for every pixel; a uniform buffer at such an
//! index is one scalar load, and at an index that varies per pixel (a flat
//! varying) a gather. Measured on the viewer's 1080p benchmark scene (a
//! glossy sphere on a Lambert floor, one shadowed directional light):
//!
//! * Lights and shadow-map views go into **uniform buffers** of a fixed
//!   capacity when they fit, storage buffers otherwise: the shadow lookup
//!   reads a light and a 4×4 matrix per pixel, and the scene pass went
//!   from 44 to 34 ms (the lights and materials moved together; same code
//!   otherwise). A uniform binding is limited to 64 KiB (WebGPU's default
//!   `maxUniformBufferBindingSize`), hence the capacities; a scene with
//!   more keeps storage buffers, and the shader is compiled for whichever
//!   it has (`#if uniform_*` features).
//! * The **material** is bound per draw: each material's triangles are
//!   one batch (src/gpu/geometry.rs), drawn with the materials buffer
//!   bound at that material's slot (a dynamic offset), so the shader reads
//!   one `Material` at an index the compiler knows is the same for every
//!   pixel, where a per-vertex material index made it a gather.
//!
//! The shadow casters' indices (at most `MAX_SHADOW_MAPS` of them) are
//! always in a uniform buffer, four to a 16-byte row (uniform arrays have
//! a 16-byte stride).

use super::layout::{GpuLight, GpuMaterial, GpuShadowView};
use super::shadows::MAX_SHADOW_MAPS;

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
    pub lights: bool,
    pub shadow_views: bool,
}

impl UniformArrays {
    /// Uniform wherever the count fits the capacity.
    pub fn for_counts(lights: usize, shadow_views: usize) -> Self {
        UniformArrays {
            lights: lights <= UNIFORM_LIGHTS,
            shadow_views: shadow_views <= UNIFORM_SHADOW_VIEWS,
        }
    }

    /// The `#if` features of these choices (shaders/common.wgsl,
    /// shaders/shadows.wgsl).
    pub fn features(self) -> impl Iterator<Item = &'static str> {
        [
            (self.lights, "uniform_lights"),
            (self.shadow_views, "uniform_shadow_views"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
    }

    /// The WGSL constants the uniform declarations size their arrays with.
    pub fn wgsl_capacities() -> String {
        format!(
            "const LIGHT_CAPACITY: u32 = {UNIFORM_LIGHTS}u;\nconst SHADOW_VIEW_CAPACITY: u32 = {UNIFORM_SHADOW_VIEWS}u;\nconst CASTER_ROWS: u32 = {CASTER_ROWS}u;\n"
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

/// The buffer usage of an array binding.
pub fn usage(uniform: bool) -> wgpu::BufferUsages {
    if uniform {
        wgpu::BufferUsages::UNIFORM
    } else {
        wgpu::BufferUsages::STORAGE
    }
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
/// offset), lights.
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
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio scene"),
        entries: &[
            buffer_entry(0, true),
            material,
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
        let a = UniformArrays::for_counts(UNIFORM_LIGHTS + 1, 6);
        assert!(!a.lights && a.shadow_views);
        assert_eq!(a.features().collect::<Vec<_>>(), ["uniform_shadow_views"]);
        let b = UniformArrays::for_counts(UNIFORM_LIGHTS, UNIFORM_SHADOW_VIEWS + 1);
        assert!(b.lights && !b.shadow_views);
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
        let stride = 256;
        let bytes = material_bytes(&m, stride);
        assert_eq!(bytes.len(), 3 * 256);
        let at = material_offset(2, stride) as usize;
        let slot: &GpuMaterial = bytemuck::from_bytes(&bytes[at..at + size_of::<GpuMaterial>()]);
        assert_eq!(slot.k_e, 7.0);
    }
}
