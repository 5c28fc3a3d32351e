// The layered glTF material: base → sheen → clearcoat (contract: "Layered
// glTF materials", "Composition"), each layer skipped when off.
// f64 twin: src/material/brdf/gltf_layers/stack.rs (same names, same order).
// Uses base_ior_specular.wgsl, sheen.wgsl, sheen_albedo.wgsl, clearcoat.wgsl.
// Each layer is compiled only where a material the scene draws has it
// (features layer_*, src/gpu/shader_gen/key_groups.rs): without the base's
// layers (ior/specular, iridescence, anisotropy) the base is the core
// gltf_pbr, which the defaults give to the bit.

#if layer_sheen
// c_sh · D_sh · V_sh + σ · below, the sheen albedos E(μ_o), E(μ_i) given.
fn sheen_over(below: vec3<f32>, layers: GltfLayers, albedo_o: f32, albedo_i: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let alpha = sheen_alpha(layers.sheen_roughness);
    let h = half_vector(wi, wo);
    let lobe = sheen_lobe(alpha, dot(n, h), sin2_between(n, h), dot(n, wi), dot(n, wo));
    return layers.sheen_color * lobe + below * sheen_scaling(layers.sheen_color, albedo_o, albedo_i);
}

fn has_sheen(layers: GltfLayers) -> bool {
    return any(layers.sheen_color != vec3<f32>(0.0));
}
#endif

// f_r for N·L > 0, N·V > 0 with the sheen albedos given.
fn gltf_layered_with_albedos(base_color: vec3<f32>, metallic: f32, roughness: f32, ms: f32, layers: GltfLayers, albedo_o: f32, albedo_i: f32, frame: SurfaceFrame, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let n = frame.n;
    #if layer_ior_specular || layer_iridescence || layer_anisotropy || layer_transmission || layer_diffuse_transmission
    var f = gltf_base(base_color, metallic, roughness, ms, layers, n, frame.t, frame.b, wi, wo);
    #else
    var f = gltf_pbr(base_color, metallic, roughness, ms, n, wi, wo);
    #endif
    // Each layer by a select, not a branch on the material's value
    // (UNIFORM_BRANCHES in brdf/phong.wgsl).
    #if layer_sheen
    f = select(f, sheen_over(f, layers, albedo_o, albedo_i, n, wi, wo), has_sheen(layers));
    #endif
    #if layer_clearcoat
    let n_c = coat_normal(frame, layers.clearcoat_normal);
    let coated = clearcoat_over(f, layers.clearcoat, layers.clearcoat_roughness, n_c, wi, wo);
    f = select(f, coated, layers.clearcoat > 0.0);
    #endif
    return f;
}

// The sheen albedos (E(μ_o), E(μ_i)) from the table (0 without sheen).
fn sheen_albedos(layers: GltfLayers, cos_i: f32, cos_o: f32) -> vec2<f32> {
    #if layer_sheen
    let e = vec2<f32>(sheen_albedo_lookup(cos_o, layers.sheen_roughness), sheen_albedo_lookup(cos_i, layers.sheen_roughness));
    return select(vec2<f32>(0.0), e, has_sheen(layers));
    #else
    return vec2<f32>(0.0);
    #endif
}

// f_r of the layered material, the sheen scaled by the table's albedos.
fn gltf_layered(base_color: vec3<f32>, metallic: f32, roughness: f32, ms: f32, layers: GltfLayers, frame: SurfaceFrame, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let e = sheen_albedos(layers, dot(frame.n, wi), dot(frame.n, wo));
    return gltf_layered_with_albedos(base_color, metallic, roughness, ms, layers, e.x, e.y, frame, wi, wo);
}
