//! The texture formats of gonio's render targets, named once: the passes
//! that draw into them, the device check that picks one and the readback
//! that copies them all agree on these.

/// The offscreen colour target: linear radiance and coverage, exact.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The fallback target holding the same f32 values as bits (see
/// [`GpuContext::radiance_format`](super::context::GpuContext::radiance_format)); read back as the same bytes.
pub const COLOR_BITS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Uint;

/// The depth format of scene passes.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The images a transmissive surface reads what lies behind it from
/// (src/gpu/transmission.rs): linear radiance at half precision (a
/// relative rounding of at most 2⁻¹¹), filterable, so their mip chains
/// are sampled trilinearly.
pub const TRANSMISSION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
