// The reflection equation for punctual lights, summed (contract):
// L_o = k_a·L_a + Σ_l f_r(ω_l, ω_o) · E_l · cosθ_l · V_l
// f64 twin: reflected_radiance in src/shading.rs.
// `eval_brdf` and `light_incidence` are generated for the scene's models and
// light kinds (src/gpu/shader_gen.rs).

// One-sided f_r: zero where N·I ≤ 0 or N·V ≤ 0 (Material::f_r in Rust).
fn f_r(m: Material, wi: vec3<f32>, wo: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if dot(n, wi) <= 0.0 || dot(n, wo) <= 0.0 {
        return vec3<f32>(0.0);
    }
    return eval_brdf(m, wi, wo, n);
}

fn reflected_radiance(m: Material, x: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let wo = normalize_or_zero(globals.eye - x);
    var radiance = m.k_a * globals.ambient;
    for (var l = 0u; l < globals.light_count; l++) {
        let incidence = light_incidence(lights[l], x);
        let cos_theta_i = dot(n, incidence.wi);
        if cos_theta_i <= 0.0 {
            continue;
        }
        radiance += f_r(m, incidence.wi, wo, n) * incidence.irradiance * cos_theta_i;
    }
    return radiance;
}
