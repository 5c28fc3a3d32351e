// The layer parameters of a gltf-pbr material (contract: "Layered glTF
// materials", keys; "Light through surfaces"), in an order that packs
// into 28 f32 (112 bytes); the
// CPU mirror is gpu::layout::GpuGltfLayers (same order), filled from
// src/material/layers.rs (GltfLayers): the anisotropy rotation ρ as its
// direction (cos ρ, sin ρ), computed in f64, and the coat's normal.
// Compiled when some material the scene draws has a layer (features
// layer_*); `Material.layers` holds it.
struct GltfLayers {
    specular_color: vec3<f32>,    // c_s
    ior: f32,                     // 0: specular-glossiness mode
    sheen_color: vec3<f32>,       // c_sh
    specular: f32,                // s_w
    clearcoat_normal: vec3<f32>,  // the coat's normal in the shading frame (t, b, n); (0, 0, 1): n
    clearcoat: f32,               // k
    anisotropy_direction: vec2<f32>, // (cos ρ, sin ρ) [an anisotropy texture turns it per pixel]
    clearcoat_roughness: f32,     // r_c (α_c = r_c²)
    sheen_roughness: f32,         // r_sh
    iridescence: f32,             // ι
    iridescence_ior: f32,         // η_f
    iridescence_thickness: f32,   // d [nm]
    anisotropy_strength: f32,     // s_a
    attenuation_color: vec3<f32>, // KHR_materials_volume: the colour kept after attenuation_distance
    transmission: f32,            // T: KHR_materials_transmission (read with feature layer_transmission)
    thickness: f32,               // the volume's thickness (0: thin-walled)
    attenuation_rate: f32,        // 1 / attenuation_distance (0: no attenuation)
    dispersion: f32,              // 20 / V_d: KHR_materials_dispersion (read with feature transmission_dispersion)
    diffuse_transmission: f32,    // D: KHR_materials_diffuse_transmission (read with feature layer_diffuse_transmission)
    diffuse_transmission_color: vec3<f32>, // c_dt
    _pad0: f32,
}
