// The base of the layered glTF material: glTF 2.0 Appendix B (mix form)
// with KHR_materials_ior, KHR_materials_specular and the anisotropic GGX
// lobe of KHR_materials_anisotropy (Burley 2012; Heitz 2014, eq. 99)
// (contract: "Layered glTF materials", "Anisotropic lobe", "Base").
// f64 twin: src/material/brdf/gltf_layers/base_ior_specular.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR, sin2_between), microfacet.wgsl (half_vector,
// d_ggx), energy.wgsl (ms_factor), gltf_pbr.wgsl (schlick_weight,
// vis_smith_ggx_correlated), iridescence.wgsl (iridescence_fresnel) and
// mod.wgsl (GltfLayers).

// ((ior − 1)/(ior + 1))² as (ior − 1)²/(ior + 1)²; 1 at ior = 0.
fn f0_from_ior(ior: f32) -> f32 {
    let num = ior - 1.0;
    let den = ior + 1.0;
    return (num * num) / (den * den);
}

// min(f0_ior · c_s, 1) per channel.
fn dielectric_f0(ior: f32, specular_color: vec3<f32>) -> vec3<f32> {
    return min(vec3<f32>(f0_from_ior(ior)) * specular_color, vec3<f32>(1.0));
}

#if layer_transmission || layer_diffuse_transmission
// The share of the base's diffuse part still reflected, (1 − T)(1 − D)
// (KHR_materials_transmission and _diffuse_transmission: each replaces
// its share of the diffuse lobe). f64 twin: reflected_diffuse_weight in
// src/material/brdf/gltf_layers/base_ior_specular.rs.
fn reflected_diffuse_weight(layers: GltfLayers) -> f32 {
    #if layer_diffuse_transmission
    return (1.0 - layers.transmission) * (1.0 - layers.diffuse_transmission);
    #else
    return 1.0 - layers.transmission;
    #endif
}

// The base's Fresnel term F_d = s_w (f0 + (1 − f0) w) at the half vector
// whose cosine with V is cos_oh (the thin wall's straight ray: N).
// f64 twin: transmission_fresnel in src/material/brdf/gltf_layers/transmission.rs.
fn transmission_fresnel(layers: GltfLayers, cos_oh: f32) -> vec3<f32> {
    let f0 = dielectric_f0(layers.ior, layers.specular_color);
    return (f0 + (vec3<f32>(1.0) - f0) * schlick_weight(cos_oh)) * layers.specular;
}
#endif

#if layer_anisotropy
// The anisotropy's (T, B) (a struct, not an array: a pipeline with
// overrides rejected the array's constant indexing).
struct AnisotropyFrame {
    t: vec3<f32>,
    b: vec3<f32>,
}

// T = cos ρ · t + sin ρ · b from direction = (cos ρ, sin ρ); B = N × T
// (pinned choice 8).
fn anisotropy_frame(direction: vec2<f32>, n: vec3<f32>, t: vec3<f32>, b: vec3<f32>) -> AnisotropyFrame {
    let dir = t * direction.x + b * direction.y;
    return AnisotropyFrame(dir, cross(n, dir));
}

// α_t = α + (1 − α) s_a².
fn anisotropic_alpha_t(alpha: f32, strength: f32) -> f32 {
    return alpha + (1.0 - alpha) * strength * strength;
}

// Burley's anisotropic GGX as (α_t α_b)³ / (π (α_b²(H·T)² + α_t²(H·B)² + α_t²α_b²(N·H)²)²).
fn d_ggx_anisotropic(alpha_t: f32, alpha_b: f32, cos_th: f32, cos_bh: f32, cos_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha_t * alpha_b;
    let f = vec3<f32>(alpha_b * cos_th, alpha_t * cos_bh, a2 * cos_h);
    let w2 = a2 / dot(f, f);
    return a2 * w2 * w2 / PI;
}

// ½ / (μ_i √(α_t²(T·V)² + α_b²(B·V)² + μ_o²) + μ_o √(α_t²(T·L)² + α_b²(B·L)² + μ_i²)),
// χ⁺(H·L) χ⁺(H·V), the front cosines floored at COS_FLOOR.
fn vis_ggx_anisotropic(alpha_t: f32, alpha_b: f32, cos_i: f32, cos_o: f32, cos_ti: f32, cos_bi: f32, cos_to: f32, cos_bo: f32, cos_ih: f32, cos_oh: f32) -> f32 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0;
    }
    let ci = min(cos_i, 1.0);
    let co = min(cos_o, 1.0);
    let root_o = length(vec3<f32>(alpha_t * cos_to, alpha_b * cos_bo, co));
    let root_i = length(vec3<f32>(alpha_t * cos_ti, alpha_b * cos_bi, ci));
    return 0.5 / (max(ci, COS_FLOOR) * root_o + max(co, COS_FLOOR) * root_i);
}
#endif

// S = D·Vis: the core's isotropic lobe at s_a = 0, the anisotropic one above.
fn base_lobe(alpha: f32, layers: GltfLayers, n: vec3<f32>, t: vec3<f32>, b: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = half_vector(wi, wo);
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    let cos_h = dot(n, h);
    let cos_ih = dot(wi, h);
    let cos_oh = dot(wo, h);
    let sin2_h = sin2_between(n, h);
    let isotropic = d_ggx(alpha, cos_h, sin2_h) * vis_smith_ggx_correlated(alpha, cos_i, cos_o, cos_ih, cos_oh);
    #if layer_anisotropy
    // Both lobes and a select, not a branch on the material's value
    // (UNIFORM_BRANCHES in brdf/phong.wgsl).
    let tb = anisotropy_frame(layers.anisotropy_direction, n, t, b);
    let alpha_t = anisotropic_alpha_t(alpha, layers.anisotropy_strength);
    let anisotropic = d_ggx_anisotropic(alpha_t, alpha, dot(tb.t, h), dot(tb.b, h), cos_h)
        * vis_ggx_anisotropic(alpha_t, alpha, cos_i, cos_o, dot(tb.t, wi), dot(tb.b, wi), dot(tb.t, wo), dot(tb.b, wo), cos_ih, cos_oh);
    return select(isotropic, anisotropic, layers.anisotropy_strength > 0.0);
    #else
    return isotropic;
    #endif
}

// The base material for N·L > 0, N·V > 0; the film mixed into the Fresnel
// terms when on (pinned choice 9); ms: energy compensation's (1 − E)/E.
fn gltf_base(base_color: vec3<f32>, metallic: f32, roughness: f32, ms: f32, layers: GltfLayers, n: vec3<f32>, t: vec3<f32>, b: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let alpha = roughness * roughness;
    let specular = base_lobe(alpha, layers, n, t, b, wi, wo);
    let w = schlick_weight(dot(wo, half_vector(wi, wo)));
    let f0 = dielectric_f0(layers.ior, layers.specular_color);
    var f_dielectric = (f0 + (vec3<f32>(1.0) - f0) * w) * layers.specular;
    var f_metal = base_color + (vec3<f32>(1.0) - base_color) * w;
    #if layer_iridescence
    // A select, not a branch (UNIFORM_BRANCHES in brdf/phong.wgsl).
    let film = layers.iridescence > 0.0 && layers.iridescence_thickness > 0.0;
    let iota = layers.iridescence;
    let cos_o = dot(n, wo);
    let film_dielectric = f_dielectric * (1.0 - iota)
        + iridescence_fresnel(cos_o, layers.iridescence_ior, layers.iridescence_thickness, f0 * layers.specular) * iota;
    let film_metal = f_metal * (1.0 - iota) + iridescence_fresnel(cos_o, layers.iridescence_ior, layers.iridescence_thickness, base_color) * iota;
    f_dielectric = select(f_dielectric, film_dielectric, film);
    f_metal = select(f_metal, film_metal, film);
    #endif
    #if layer_transmission || layer_diffuse_transmission
    // Transmission takes its share of the diffuse part (the light it lets
    // through is added by the transmission pass, shaders/transmission.wgsl).
    let diffuse_weight = reflected_diffuse_weight(layers);
    #else
    let diffuse_weight = 1.0;
    #endif
    let dielectric = base_color * ((1.0 - max(f_dielectric.x, max(f_dielectric.y, f_dielectric.z))) * diffuse_weight * FRAC_1_PI)
        + f_dielectric * specular * ms_factor(f0 * layers.specular, ms);
    let metal = f_metal * specular * ms_factor(base_color, ms);
    return dielectric * (1.0 - metallic) + metal * metallic;
}
