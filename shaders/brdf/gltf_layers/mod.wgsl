// The layer parameters of a gltf-pbr material (contract: "Layered glTF
// materials", keys), in an order that packs into 16 f32 (64 bytes).
// f64 twin: src/material/brdf/gltf_layers/mod.rs (GltfLayers).
struct GltfLayers {
    specular_color: vec3<f32>,   // c_s
    ior: f32,                    // 0: specular-glossiness mode
    sheen_color: vec3<f32>,      // c_sh
    specular: f32,               // s_w
    clearcoat: f32,              // k
    clearcoat_roughness: f32,    // r_c (α_c = r_c²)
    sheen_roughness: f32,        // r_sh
    iridescence: f32,            // ι
    iridescence_ior: f32,        // η_f
    iridescence_thickness: f32,  // d [nm]
    anisotropy_strength: f32,    // s_a
    anisotropy_rotation: f32,    // ρ [rad]
}
