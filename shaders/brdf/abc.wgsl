// The ABC microfacet model (Löw, Kronander, Ynnerman, Unger, ACM TOG 31(1)
// 2012) in the form of its published MERL fits (dj_brdf's abc::eval):
// f = k_d/π + k_s · F(I·H; η_i → η_t) · D · G / (π (N·V)(N·I)),
// D = A / (1 + B(1 − cos θ_h))^C, G the V-groove, F the exact dielectric.
// The GPU's m.k_s holds k_s·A (Brdf::shader_params), m.lobe = (B, C, 0, 0).
// f64 twin: src/material/brdf/abc.rs (same names, same order).
// Uses phong.wgsl (exp_cutoff, sin2_between), fresnel.wgsl
// (fresnel_dielectric), microfacet.wgsl (half_vector, g_vgroove,
// cook_torrance_specular).

// (1 + B(1 − cos θ_h))^−C, peak 1, with 1 − cos θ_h = sin²θ_h / (1 + cos θ_h)
// (cos_h rounds to 1 in f32 within the narrowest published lobes); as
// e^(−C ln(1 + B(1 − cos θ_h))) through exp_cutoff. 0 for cos_h ≤ 0.
fn d_abc_shape(b: f32, c: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let one_minus_cos = sin2_h / (1.0 + min(cos_h, 1.0));
    return exp_cutoff(-c * log(1.0 + b * one_minus_cos));
}

// F·D̂·G / (π (N·V)(N·I)) without A, for N·I > 0, N·V > 0.
fn abc_specular(b: f32, c: f32, eta_i: f32, eta_t: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = half_vector(wi, wo);
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    let cos_h = dot(n, h);
    let sin2_h = sin2_between(n, h);
    let cos_ih = dot(wi, h);
    let cos_oh = dot(wo, h);
    let d = d_abc_shape(b, c, cos_h, sin2_h);
    let g = g_vgroove(cos_h, cos_o, cos_i, cos_oh);
    let f = fresnel_dielectric(cos_ih, eta_i, eta_t);
    return cook_torrance_specular(d, g, vec3<f32>(f), cos_i, cos_o, PI).x;
}
