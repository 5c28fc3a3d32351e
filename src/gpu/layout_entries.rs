//! Bind group layout entries that several groups share: 2D float
//! textures (filterable or read texel by texel), the filtering sampler,
//! a read-only storage buffer.

/// A filterable 2D float texture at `binding`, seen by `visibility`.
pub fn filterable_texture_2d(
    binding: u32,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    float_texture_2d(binding, visibility, true)
}

/// A 2D float texture read with `textureLoad` only (`Rgba32Float`, which
/// is not filterable everywhere), at `binding`, seen by `visibility`.
pub fn unfilterable_texture_2d(
    binding: u32,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    float_texture_2d(binding, visibility, false)
}

fn float_texture_2d(
    binding: u32,
    visibility: wgpu::ShaderStages,
    filterable: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A read-only storage buffer of at least `min_size` bytes at `binding`,
/// seen by `visibility`.
pub fn read_only_storage(
    binding: u32,
    visibility: wgpu::ShaderStages,
    min_size: Option<wgpu::BufferSize>,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: min_size,
        },
        count: None,
    }
}

/// A filtering sampler at `binding`, seen by `visibility`.
pub fn filtering_sampler(
    binding: u32,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}
