// The reflection equation for punctual lights, summed (contract):
// L_o = k_a·L_a + Σ_l f_r(ω_l, ω_o) · E_l · cosθ_l · V_l
// plus, for the ideal mirror, ρ_s(θ_o) · L_env(R(V)).
// f64 twin: reflected_radiance in src/shading.rs.
// `mirror_reflectance` and `light_incidence` are generated for the scene's
// BRDF variants and light kinds (src/gpu/shader_gen.rs); lines marked
// `#if mirror` exist only when the scene has a mirror, lines marked
// `#if shadows` only when a light casts shadows: then V_l comes from
// the shadow-map lookup (shaders/shadows.wgsl) at the shading point x, with
// n_g the offset normal (geometric normal for phong and flat, the vertex
// normal for gouraud), and the samples of one area light, which share one
// shadow map, read it once.

// Radiance of the environment from unit direction d. Twin: Environment::radiance. // #if mirror
fn environment_radiance(d: vec3<f32>) -> vec3<f32> { // #if mirror
    let y = clamp(d.y, -1.0, 1.0); // #if mirror
    if y >= 0.0 { // #if mirror
        return globals.env_horizon + (globals.env_zenith - globals.env_horizon) * y; // #if mirror
    } // #if mirror
    return globals.env_horizon + (globals.env_ground - globals.env_horizon) * (-y); // #if mirror
} // #if mirror

fn reflected_radiance(m: Material, x: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> { // #if !shadows
fn reflected_radiance(m: Material, x: vec3<f32>, frame: SurfaceFrame, n_g: vec3<f32>) -> vec3<f32> { // #if shadows
    let n = frame.n;
    let wo = normalize_or_zero(globals.eye - x);
    var radiance = m.k_a * globals.ambient;
    var cached_layer = -1; // #if shadows
    var cached_v = 1.0; // #if shadows
    for (var l = 0u; l < globals.light_count; l++) {
        let light = lights[l];
        let incidence = light_incidence(light, x);
        let cos_theta_i = dot(n, incidence.wi);
        if cos_theta_i <= 0.0 {
            continue;
        }
        var v = 1.0; // #if shadows
        if light.shadow_layer >= 0 { // #if shadows
            if light.shadow_layer != cached_layer { // #if shadows
                cached_v = shadow_visibility(light, x, n_g); // #if shadows
                cached_layer = light.shadow_layer; // #if shadows
            } // #if shadows
            v = cached_v; // #if shadows
        } // #if shadows
        if v <= 0.0 { // #if shadows
            continue; // #if shadows
        } // #if shadows
        radiance += f_r(m, incidence.wi, wo, frame) * incidence.irradiance * cos_theta_i; // #if !shadows
        radiance += f_r(m, incidence.wi, wo, frame) * incidence.irradiance * (cos_theta_i * v); // #if shadows
    }
    let reflected = mirror_direction(wo, n); // #if mirror
    radiance += mirror_reflectance(m, dot(n, wo)) * environment_radiance(reflected); // #if mirror
    return radiance;
}
