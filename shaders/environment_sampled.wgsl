// The environment integrated through the whole BRDF with N directions
// (environment.specular = "sampled"): ⌈N/2⌉ cosine-weighted and the rest
// from the material's BRDF lobe, combined by multiple importance sampling
// (the balance heuristic, multi-sample form: each sample weighted as one
// of the mixture n_c p_c + n_b p_b). Only in shaders of scenes in that
// mode (feature `environment_sampled`), after environment.wgsl; uses
// brdf/phong.wgsl (composed whenever this file is).
// f64 twins: src/reference/environment/lobe.rs (the lobe_* functions) and
// src/reference/environment/sampled.rs (the estimate), same functions, same order;
// the derivations are there.

// Lobe kinds (lobe::Lobe's variants).
const LOBE_NONE: u32 = 0u;
const LOBE_GGX: u32 = 1u;
const LOBE_BECKMANN: u32 = 2u;
const LOBE_HALF_POWER: u32 = 3u;
const LOBE_MIRROR_POWER: u32 = 4u;

// A lobe::Lobe: its kind and its one parameter (α, m or s).
struct SampledLobe {
    kind: u32,
    param: f32,
}

// The lobe of m: selects on the model (UNIFORM_BRANCHES in
// brdf/phong.wgsl; WGSL selects scalars, so kind and parameter apart);
// each model's line only when the scene has it. Twin: lobe::lobe.
fn sampled_lobe(m: Material) -> SampledLobe {
    let model = brdf_model(m);
    var kind = LOBE_NONE;
    var param = 0.0;
    #if phong || phong-normalized
    let phong = model == MODEL_PHONG || model == MODEL_PHONG_NORMALIZED;
    kind = select(kind, LOBE_MIRROR_POWER, phong);
    param = select(param, m.k_e, phong);
    #endif
    #if blinn-phong
    kind = select(kind, LOBE_HALF_POWER, model == MODEL_BLINN_PHONG);
    param = select(param, m.k_e, model == MODEL_BLINN_PHONG);
    #endif
    #if blinn-phong-normalized
    kind = select(kind, LOBE_HALF_POWER, model == MODEL_BLINN_PHONG_NORMALIZED);
    param = select(param, m.k_e + 1.0, model == MODEL_BLINN_PHONG_NORMALIZED);
    #endif
    #if ward
    kind = select(kind, LOBE_BECKMANN, model == MODEL_WARD);
    param = select(param, m.sigma_x, model == MODEL_WARD);
    #endif
    #if ward-anisotropic
    kind = select(kind, LOBE_BECKMANN, model == MODEL_WARD_ANISOTROPIC);
    param = select(param, max(m.sigma_x, m.sigma_y), model == MODEL_WARD_ANISOTROPIC);
    #endif
    #if cook-torrance
    let d = brdf_distribution(m);
    let blinn = d == DISTRIBUTION_BLINN || d == DISTRIBUTION_BLINN_NORMALIZED;
    let gaussian = d == DISTRIBUTION_GAUSSIAN || d == DISTRIBUTION_GAUSSIAN_NORMALIZED;
    var ct_kind = select(LOBE_BECKMANN, LOBE_GGX, d == DISTRIBUTION_GGX);
    ct_kind = select(ct_kind, LOBE_HALF_POWER, blinn);
    var ct_param = select(m.roughness, m.blinn_e + 1.0, blinn);
    ct_param = select(ct_param, m.roughness / sqrt(LN_2), gaussian);
    let ct = model == MODEL_COOK_TORRANCE;
    kind = select(kind, ct_kind, ct);
    param = select(param, ct_param, ct);
    #endif
    #if abc
    kind = select(kind, LOBE_HALF_POWER, model == MODEL_ABC);
    param = select(param, m.lobe.x * m.lobe.y, model == MODEL_ABC);
    #endif
    // A zero k_s has no lobe (gltf-pbr does not read k_s).
    kind = select(kind, LOBE_NONE, all(m.k_s == vec3<f32>(0.0)));
    #if gltf-pbr
    kind = select(kind, LOBE_GGX, model == MODEL_GLTF_PBR);
    param = select(param, m.roughness * m.roughness, model == MODEL_GLTF_PBR);
    #endif
    return SampledLobe(kind, param);
}

// 1 − e^x for x ≤ 0: the series of −expm1 for |x| < 0.1 (truncation
// < 2e-9 relative), 1 − exp above. Twin: one_minus_exp.
fn lobe_one_minus_exp(x: f32) -> f32 {
    if x > -0.1 {
        return -x * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x * (1.0 / 24.0 + x * (1.0 / 120.0 + x / 720.0)))));
    }
    return 1.0 - exp(x);
}

// (cos²θ, sin²θ) of the lobe's polar angle for the variate u. Selects,
// not branches. Twin: lobe::polar.
fn lobe_polar(l: SampledLobe, u: f32) -> vec2<f32> {
    // GGX: tan²θ = α² u/(1 − u).
    let a = l.param * l.param * u;
    let dg = (1.0 - u) + a;
    let ggx = vec2<f32>((1.0 - u) / dg, a / dg);
    // Beckmann: tan²θ = −m² ln(1 − u).
    let t = l.param * l.param * neg_ln_1m(u);
    let beckmann = vec2<f32>(1.0 / (1.0 + t), t / (1.0 + t));
    // Powers: cos²θ = e^x, x = 2 ln(1 − u)/(s + 1).
    let x = -2.0 * neg_ln_1m(u) / (l.param + 1.0);
    let power = vec2<f32>(exp(x), lobe_one_minus_exp(x));
    var p = select(vec2<f32>(1.0, 0.0), power, l.kind >= LOBE_HALF_POWER);
    p = select(p, beckmann, l.kind == LOBE_BECKMANN);
    return select(p, ggx, l.kind == LOBE_GGX);
}

// Direction of the variates (u1, u2) under the lobe, for the view wo at
// the normal n (t, b: the sampling frame's tangents). Twin: lobe::direction.
fn lobe_direction(l: SampledLobe, u1: f32, u2: f32, wo: vec3<f32>, n: vec3<f32>, t: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    let cs = lobe_polar(l, u1);
    let cos_t = sqrt(cs.x);
    let sin_t = sqrt(cs.y);
    let phi = 2.0 * PI * u2;
    let r = mirror_direction(wo, n);
    let tr = any_tangent(r);
    let br = cross(r, tr);
    let about_r = tr * (sin_t * cos(phi)) + br * (sin_t * sin(phi)) + r * cos_t;
    let h = t * (sin_t * cos(phi)) + b * (sin_t * sin(phi)) + n * cos_t;
    let reflected = 2.0 * dot(wo, h) * h - wo;
    return select(reflected, about_r, l.kind == LOBE_MIRROR_POWER);
}

// (s+1)/(2π) cos^s θ from cos θ and sin²θ (0 for cos θ ≤ 0). Twin:
// power_density.
fn lobe_power_density(s: f32, cos_t: f32, sin2: f32) -> f32 {
    if cos_t <= 0.0 {
        return 0.0;
    }
    return (s + 1.0) * 0.5 * FRAC_1_PI * exp_cutoff(s * ln_cos(cos_t, sin2));
}

// The lobe's density at wi [1/sr]. Twin: lobe::pdf.
fn lobe_pdf(l: SampledLobe, wi: vec3<f32>, wo: vec3<f32>, n: vec3<f32>) -> f32 {
    let r = mirror_direction(wo, n);
    let mirror = lobe_power_density(l.param, dot(r, wi), min(sin2_between(r, wi), 1.0));
    let h = normalize_or_zero(wi + wo);
    let cos_h = dot(n, h);
    let sin2 = min(sin2_between(n, h), 1.0);
    let cos_oh = dot(wo, h);
    let cos2 = cos_h * cos_h;
    let a2 = l.param * l.param;
    let dg = a2 * cos2 + sin2;
    let ggx = a2 * FRAC_1_PI / (dg * dg) * cos_h;
    // Beckmann, cut off where the exponent is ≤ −80 (as d_beckmann).
    let beckmann = select(0.0, exp(-sin2 / (cos2 * a2)) * FRAC_1_PI / (a2 * cos2 * cos_h), sin2 < EXP_CUTOFF * cos2 * a2);
    var p_h = select(0.0, lobe_power_density(l.param, cos_h, sin2), l.kind == LOBE_HALF_POWER);
    p_h = select(p_h, beckmann, l.kind == LOBE_BECKMANN);
    p_h = select(p_h, ggx, l.kind == LOBE_GGX);
    let half = select(0.0, p_h / (4.0 * cos_oh), cos_h > 0.0 && cos_oh > 0.0);
    return select(half, mirror, l.kind == LOBE_MIRROR_POWER);
}

// L_o = ∫ f_r L_env cos θ dω by N directions: Σ_k f_r L_env cos θ_k /
// (n_c p_c + n_b p_b), samples 0..n_c cosine-weighted, the rest from the
// lobe, each strategy on the Hammersley set of its size. Twin:
// sampled::estimate.
fn environment_sampled(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    // The loop bound is a uniform, but group 3's, which every draw of a
    // frame shares (unlike the material's: UNIFORM_BRANCHES in
    // brdf/phong.wgsl), so lavapipe inlines it once per setting.
    let n = max(environment.samples, 1u);
    let l = sampled_lobe(m);
    // sampled::split
    let n_c = select((n + 1u) / 2u, n, l.kind == LOBE_NONE);
    let n_b = n - n_c;
    // The directions' frame from the normal alone (as sampled::estimate).
    let t = any_tangent(frame.n);
    let b = cross(frame.n, t);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < n; k++) {
        let from_lobe = k >= n_c;
        let j = select(k, k - n_c, from_lobe);
        let count = select(n_c, n_b, from_lobe);
        // sampled::hammersley
        let u1 = (f32(j) + 0.5) / f32(count);
        let u2 = f32(reverseBits(j)) * 2.3283064365386963e-10;
        // sampled::local_direction (Malley's method)
        let r = sqrt(u1);
        let phi = 2.0 * PI * u2;
        let cosine = t * (r * cos(phi)) + b * (r * sin(phi)) + frame.n * sqrt(1.0 - u1);
        let wi = select(cosine, lobe_direction(l, u1, u2, wo, frame.n, t, b), from_lobe);
        let c = dot(frame.n, wi);
        let p_b = select(0.0, lobe_pdf(l, wi, wo, frame.n), n_b > 0u);
        let mixture = f32(n_c) * max(c, 0.0) * FRAC_1_PI + f32(n_b) * p_b;
        let term = f_r(m, wi, wo, frame) * environment_map_radiance(wi) * (c / mixture);
        sum += select(vec3<f32>(0.0), term, c > 0.0 && mixture > 0.0);
    }
    return sum;
}
