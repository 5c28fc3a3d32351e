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
//!
//! This file holds the choices the shader generator declares (it imports
//! nothing of `gpu/`); the bytes of each binding and the bind group
//! layouts are in src/gpu/bind_groups.rs.

/// Lights (area-light samples included) a uniform buffer holds (128 bytes
/// each: 32 KiB).
pub const UNIFORM_LIGHTS: usize = 256;
/// Shadow-map layers a uniform buffer holds (64 bytes each: 24 KiB; 64
/// cube maps).
pub const UNIFORM_SHADOW_VIEWS: usize = 384;
/// Rows of four caster indices: one index per shadow map, at most
/// `shadows::MAX_SHADOW_MAPS` (64; src/gpu/bind_groups.rs checks the two
/// agree when it compiles, so this file needs nothing of `gpu/`).
pub const CASTER_ROWS: usize = 16;

/// Which of the scene's arrays are in uniform buffers (`true`) rather
/// than storage buffers. Part of the [`super::shader_gen::ShaderKey`]:
/// it changes the WGSL declarations and the bind group layouts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct UniformArrays {
    pub lights: bool,
    pub shadow_views: bool,
    /// Not a uniform array: the scene has a measured material, so group 0
    /// has the measured tables' storage buffer at binding 3
    /// (src/gpu/measured_tables.rs).
    pub measured: bool,
    /// Not a scene array either: some material has a sheen (feature
    /// `layer_sheen`), so group 0 has the sheen's albedo table, a uniform
    /// buffer at binding 4 (shaders/brdf/gltf_layers/sheen_albedo.wgsl).
    pub sheen: bool,
}

impl UniformArrays {
    /// Uniform wherever the count fits the capacity.
    pub fn for_counts(lights: usize, shadow_views: usize) -> Self {
        UniformArrays {
            lights: lights <= UNIFORM_LIGHTS,
            shadow_views: shadow_views <= UNIFORM_SHADOW_VIEWS,
            measured: false,
            sheen: false,
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

/// The buffer usage of an array binding.
pub fn usage(uniform: bool) -> wgpu::BufferUsages {
    if uniform {
        wgpu::BufferUsages::UNIFORM
    } else {
        wgpu::BufferUsages::STORAGE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_past_a_capacity_stay_in_storage() {
        let a = UniformArrays::for_counts(UNIFORM_LIGHTS + 1, 6);
        assert!(!a.lights && a.shadow_views);
        assert_eq!(a.features().collect::<Vec<_>>(), ["uniform_shadow_views"]);
        let b = UniformArrays::for_counts(UNIFORM_LIGHTS, UNIFORM_SHADOW_VIEWS + 1);
        assert!(b.lights && !b.shadow_views);
    }
}
