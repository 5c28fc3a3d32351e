// glTF 2.0's metallic-roughness BRDF (glTF 2.0 Specification, Appendix B),
// the `mix` form the Khronos sample renderer evaluates:
// f = (1 − m)·[(1 − F_d)·b/π + F_d·D·Vis] + m·(b + (1 − b)·w)·D·Vis,
// w = (1 − |V·H|)⁵, F_d = 0.04 + 0.96·w, GGX D of α = r² (r: glTF's
// perceptual roughness), height-correlated Smith-GGX Vis.
// f64 twin: src/material/brdf/gltf_pbr.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR, sin2_between), microfacet.wgsl (half_vector, d_ggx),
// energy.wgsl (ms_factor).

const DIELECTRIC_F0: f32 = 0.04;

// Vis = ½ / (N·L √(N·V² (1 − α²) + α²) + N·V √(N·L² (1 − α²) + α²)) · χ⁺(H·L) χ⁺(H·V),
// the roots as √(cos² + α² sin²); the cosines in front floored at COS_FLOOR
// (both grazing: the denominator tends to 0).
fn vis_smith_ggx_correlated(alpha: f32, cos_i: f32, cos_o: f32, cos_ih: f32, cos_oh: f32) -> f32 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺ = 0
    }
    let ci = min(cos_i, 1.0); // rounding can pass 1
    let co = min(cos_o, 1.0);
    let alpha2 = alpha * alpha;
    let root_o = sqrt(co * co + alpha2 * (1.0 - co * co));
    let root_i = sqrt(ci * ci + alpha2 * (1.0 - ci * ci));
    return 0.5 / (max(ci, COS_FLOOR) * root_o + max(co, COS_FLOOR) * root_i);
}

// Schlick's weight w = (1 − |V·H|)⁵ by multiplications (pow would go through log).
fn schlick_weight(cos_oh: f32) -> f32 {
    let x = 1.0 - min(abs(cos_oh), 1.0);
    let x2 = x * x;
    return x2 * x2 * x;
}

// f_r for N·I > 0, N·V > 0 (the caller's one-sided test); α = roughness².
// ms: energy compensation's (1 − E)/E (energy.wgsl; 0 without it): the
// dielectric's lobe times 1 + 0.04·ms, the metal's times 1 + b·ms.
fn gltf_pbr(base_color: vec3<f32>, metallic: f32, roughness: f32, ms: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let alpha = roughness * roughness;
    let h = half_vector(wi, wo);
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    let cos_h = dot(n, h);
    let sin2_h = sin2_between(n, h);
    let cos_ih = dot(wi, h);
    let cos_oh = dot(wo, h);
    let specular = d_ggx(alpha, cos_h, sin2_h) * vis_smith_ggx_correlated(alpha, cos_i, cos_o, cos_ih, cos_oh);
    let w = schlick_weight(cos_oh);
    let f_dielectric = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * w;
    let dielectric = base_color * ((1.0 - f_dielectric) * FRAC_1_PI)
        + vec3<f32>(f_dielectric * specular) * ms_factor(vec3<f32>(DIELECTRIC_F0), ms);
    let metal = (base_color + (vec3<f32>(1.0) - base_color) * w) * specular * ms_factor(base_color, ms);
    return dielectric * (1.0 - metallic) + metal * metallic;
}
