// The reflection equation for punctual lights, summed (contract):
// L_o = L_e + k_a·L_a + Σ_l f_r(ω_l, ω_o) · E_l · cosθ_l · V_l
// plus, for the ideal mirror, ρ_s(θ_o) · L_env(R(V)),
// plus, with an environment map (`#if environment`), the diffuse term of
// every model lit by it, k_d/π · E(n), E by spherical harmonics
// (shaders/environment.wgsl), or (`#if environment_sampled`) the whole
// BRDF integrated over the map with N directions.
// An unlit material shows L_e + k_a·L_a + b (#if unlit, brdf/unlit.wgsl).
// The ambient occlusion m.occlusion multiplies the ambient term and every
// environment term (diffuse, specular, the mirror's), never direct light.
// f64 twin: reflected_radiance in src/reference/shading.rs.
// `eval_brdf` and `mirror_reflectance` (shaders/brdf/eval.wgsl) switch
// over the scene's models; `light_incidence` (shaders/lights/incidence.wgsl)
// over its light kinds. Blocks `#if mirror` exist only
// when the scene has a mirror, blocks
// `#if shadows` only when a light casts shadows: then V_l comes from
// the shadow-map lookup (shaders/shadows.wgsl) at the shading point x, with
// n_g the offset normal (geometric normal for phong and flat, the vertex
// normal for gouraud) (`#if shadow_pixel`), or, when the vertex shader
// computed the one map's coordinates (`#if shadow_vertex`,
// ShaderKey::shadow_coords_per_vertex), from those interpolated
// coordinates `shadow_ndc`.

#if mirror
// Radiance of the environment from unit direction d. Twin: Environment::radiance.
fn environment_radiance(d: vec3<f32>) -> vec3<f32> {
    #if environment
    return environment_map_radiance(d);
    #else
    let y = clamp(d.y, -1.0, 1.0);
    if y >= 0.0 {
        return globals.env_horizon + (globals.env_zenith - globals.env_horizon) * y;
    }
    return globals.env_horizon + (globals.env_ground - globals.env_horizon) * (-y);
    #endif
}
#endif

#if shadow_pixel
fn reflected_radiance(m: Material, x: vec3<f32>, given_frame: SurfaceFrame, n_g: vec3<f32>) -> vec3<f32> {
#elif shadow_vertex
#if shadow_ortho
fn reflected_radiance(m: Material, x: vec3<f32>, given_frame: SurfaceFrame, shadow_ndc: vec3<f32>) -> vec3<f32> {
#else
// A spot light's map (shading.shadow_coords = "vertex"): the interpolated
// clip coordinates `shadow_clip`, divided in shadow_read_clip.
fn reflected_radiance(m: Material, x: vec3<f32>, given_frame: SurfaceFrame, shadow_clip: vec4<f32>) -> vec3<f32> {
#endif
#else
fn reflected_radiance(m: Material, x: vec3<f32>, given_frame: SurfaceFrame) -> vec3<f32> {
#endif
    let wo = normalize_or_zero(globals.eye - x);
    // A glTF material's normal turned toward the viewer where it faces
    // away (surface.wgsl); every term below reads this one frame.
    #if facing_normals
    var frame = given_frame;
    if m.facing_normals == 1u {
        frame = facing_frame(given_frame, wo);
    }
    #else
    let frame = given_frame;
    #endif
    let n = frame.n;
    // Emission and ambient occlusion only where some material has them
    // (MaterialsKey::emission, ::occlusion): adding 0 and multiplying by 1
    // change no pixel, and cost about 6 % of a Lambert frame on lavapipe.
    #if occlusion
    let occlusion = m.occlusion;
    #else
    let occlusion = 1.0;
    #endif
    #if emission
    var radiance = m.emission + m.k_a * globals.ambient * occlusion;
    #else
    var radiance = m.k_a * globals.ambient * occlusion;
    #endif
    #if unlit
    // An unlit material (brdf/unlit.wgsl) shows its base colour over its
    // own terms; lights and environment add nothing (selected at the end:
    // UNIFORM_BRANCHES).
    let unlit = radiance + unlit_radiance(m.base_color);
    #endif
    // With shadows: V of every shadow map first, once each (the samples of
    // an area light share one map), in a loop of its own: a software
    // rasterizer runs both sides of every branch, so a lookup inside the
    // light loop would cost one per light.
    // LIGHT_COUNT and SHADOW_MAP_COUNT are generated constants (the
    // loops unroll; see LoopCounts in src/gpu/shader_gen/key.rs).
    #if shadows
    var visibility: array<f32, SHADOW_MAP_COUNT>;
    for (var s = 0u; s < SHADOW_MAP_COUNT; s++) {
        #if shadow_pixel
        visibility[s] = shadow_visibility(lights[shadow_caster(s)], x, n_g);
        #elif shadow_ortho
        visibility[s] = shadow_read_ndc(lights[shadow_caster(s)], lights[shadow_caster(s)].shadow_layer, shadow_ndc);
        #else
        visibility[s] = shadow_read_clip(lights[shadow_caster(s)], lights[shadow_caster(s)].shadow_layer, shadow_clip);
        #endif
    }
    #endif
    #if light_count
    for (var l = 0u; l < LIGHT_COUNT; l++) {
    #else
    for (var l = 0u; l < globals.light_count; l++) {
    #endif
        let light = lights[l];
        let incidence = light_incidence(light, x);
        let cos_theta_i = dot(n, incidence.wi);
        #if layer_diffuse_transmission
        // A light behind a diffusely transmitting wall shines through it
        // (shaders/brdf/gltf_layers/transmission.wgsl; 0 for the others).
        if cos_theta_i < 0.0 {
            #if shadows
            let map_behind = min(light.shadow_map, SHADOW_MAP_COUNT - 1u);
            let v_behind = select(1.0, visibility[map_behind], light.shadow_map < SHADOW_MAP_COUNT);
            #else
            let v_behind = 1.0;
            #endif
            radiance += diffuse_transmitted(m, n, incidence.wi, wo) * incidence.irradiance * (-cos_theta_i * v_behind);
        }
        #endif
        if cos_theta_i <= 0.0 {
            continue;
        }
        #if shadows
        let map = min(light.shadow_map, SHADOW_MAP_COUNT - 1u);
        let v = select(1.0, visibility[map], light.shadow_map < SHADOW_MAP_COUNT);
        radiance += f_r(m, incidence.wi, wo, frame) * incidence.irradiance * (cos_theta_i * v);
        #else
        radiance += f_r(m, incidence.wi, wo, frame) * incidence.irradiance * cos_theta_i;
        #endif
    }
    #if environment_sampled
    radiance += environment_sampled(m, wo, frame) * occlusion;
    #elif environment_prefiltered
    // The diffuse term plus the split-sum glossy term (Karis 2013).
    radiance += environment_prefiltered(m, wo, frame) * occlusion;
    #elif environment_sh
    // The diffuse term plus the Phong lobes by SH convolution.
    radiance += environment_sh(m, wo, frame) * occlusion;
    #elif environment
    radiance += environment_diffuse_albedo(m) * FRAC_1_PI * sh_irradiance(n) * occlusion;
    #endif
    #if layer_diffuse_transmission
    #if environment
    // The environment's light through a diffusely transmitting wall.
    radiance += diffuse_transmitted_environment(m, n, wo) * occlusion;
    #endif
    #endif
    #if layer_transmission
    // Light through the surface from the image of what lies behind
    // (shaders/transmission.wgsl; 0 for a material that does not transmit).
    radiance += transmitted_radiance(m, x, frame, wo);
    #endif
    #if mirror
    let reflected = mirror_direction(wo, n);
    radiance += mirror_reflectance(m, dot(n, wo)) * environment_radiance(reflected) * occlusion;
    #endif
    #if unlit
    return select(radiance, unlit, brdf_model(m) == MODEL_UNLIT);
    #else
    return radiance;
    #endif
}

#if environment
// The albedo the environment's SH irradiance lights: k_d; gltf-pbr's
// Lambert part (1 − m)·b (per pixel, after textures); 0 for a measured
// table. Selects, not branches (UNIFORM_BRANCHES in brdf/phong.wgsl).
// f64 twin: environment_diffuse_albedo in src/reference/environment/diffuse.rs.
fn environment_diffuse_albedo(m: Material) -> vec3<f32> {
    let model = brdf_model(m);
    #if layer_transmission || layer_diffuse_transmission
    let pbr = (1.0 - m.metallic) * reflected_diffuse_weight(m.layers) * m.base_color;
    #else
    let pbr = (1.0 - m.metallic) * m.base_color;
    #endif
    let albedo = select(m.k_d, pbr, model == MODEL_GLTF_PBR);
    return select(albedo, vec3<f32>(0.0), model == MODEL_MEASURED);
}
#endif
