// Diffuse transmission (KHR_materials_diffuse_transmission, "BTDF"):
// Lambert on the far side, a share D of the diffuse part the specular
// transmission leaves, f_t = (1 − m)(1 − max₃ F(H))(1 − T) D c_dt/π,
// times 1 − k F_c(μ_o) under a coat; H the half vector of the mirrored
// light direction. f64 twin: the diffuse part of gltf_transmitted_parts
// in src/material/brdf/gltf_layers/transmission.rs, as the reference
// evaluates it: without the sheen's albedo scaling (the reference's thin
// wall passes no sheen albedos) and only on a thin wall (a volume's
// boundary refracts; the reference follows no diffuse light through it).
// Compiled only where a drawn gltf-pbr material transmits diffusely
// (feature layer_diffuse_transmission).

// The far side's weight without 1/π: (1 − m)(1 − max₃ F)(1 − T) D c_dt
// (times the coat's 1 − k F_c(μ_o)), with F at V·H = cos_oh; 0 for a
// volume's boundary.
fn diffuse_transmission_weight(m: Material, cos_o: f32, cos_oh: f32) -> vec3<f32> {
    let f = transmission_fresnel(m.layers, cos_oh);
    var s = (1.0 - m.metallic) * (1.0 - max(f.x, max(f.y, f.z))) * (1.0 - m.layers.transmission);
    #if layer_clearcoat
    s *= 1.0 - m.layers.clearcoat * clearcoat_fresnel(cos_o);
    #endif
    let volume = m.layers.thickness > 0.0 && m.layers.transmission > 0.0;
    return select(m.layers.diffuse_transmission_color * (m.layers.diffuse_transmission * s), vec3<f32>(0.0), volume);
}

// f_t's diffuse part for light arriving from wi on the far side
// (N·wi < 0) seen from wo (N·wo > 0); 0 elsewhere.
fn diffuse_transmitted(m: Material, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let cos_o = dot(n, wo);
    let mirrored = wi - 2.0 * dot(n, wi) * n;
    let sum = mirrored + wo;
    let h = select(n, normalize(sum), dot(sum, sum) > 0.0);
    let f_t = diffuse_transmission_weight(m, cos_o, dot(wo, h)) * FRAC_1_PI;
    return select(f_t, vec3<f32>(0.0), cos_o <= 0.0 || dot(n, wi) >= 0.0);
}

// The light of the environment through the wall: the irradiance on the
// far side (SH at −N) through f_t with F at N, as the reference's straight
// ray weighs the lobe (src/reference/transmission/thin.rs, lobe_weight).
// What lies behind the wall in the scene is not seen (the sample
// renderer's getDiffuseLight(−n) likewise).
#if environment
fn diffuse_transmitted_environment(m: Material, n: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let cos_o = dot(n, wo);
    let f_t = diffuse_transmission_weight(m, cos_o, cos_o) * FRAC_1_PI;
    return select(f_t * sh_irradiance(-n), vec3<f32>(0.0), cos_o <= 0.0);
}
#endif
