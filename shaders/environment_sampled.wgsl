// The environment integrated through the whole BRDF with N directions
// (environment.specular = "sampled"): cosine-weighted ones, ones from the
// material's BRDF lobe and ones from the map's light, combined by multiple
// importance sampling (the balance heuristic, multi-sample form: each
// sample weighted as one of the mixture n_c p_c + n_b p_b + n_m p_m). Only
// in shaders of scenes in that mode (feature `environment_sampled`), after
// environment.wgsl; uses brdf/phong.wgsl (composed whenever this file is).
// f64 twins: src/reference/environment/lobe.rs (the lobe_* functions),
// src/environment/importance.rs (the importance_* functions) and
// src/reference/environment/sampled.rs (the estimate), same functions,
// same order; the derivations are there.

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

// The map's distribution of directions (group 3, binding 4;
// ImportanceTable::gpu_entries): a width × height grid, per texel
// (the columns' cumulative probability within its row, its density
// [1/sr], the rows' cumulative probability at its row, 0).
struct EnvironmentImportance {
    // width, height, whether the map is drawn by (ImportanceTable::concentrated), 0
    header: vec4<u32>,
    entries: array<vec4<f32>>,
}

@group(3) @binding(4) var<storage, read> environment_importance: EnvironmentImportance;

// Entry i of a cumulative distribution in the table: the rows' (.z of
// each row's first texel) or one row's columns (.x from `start`).
fn importance_cdf(start: u32, rows: bool, i: u32) -> f32 {
    let w = environment_importance.header.x;
    let e = environment_importance.entries[select(start + i, i * w, rows)];
    return select(e.x, e.z, rows);
}

// A bin of a cumulative distribution and the variate's fraction in it.
struct ImportanceBin {
    index: u32,
    fraction: f32,
}

// The first of n entries above u, by bisection, and u's fraction within
// that bin's probability. Twin: importance::invert.
fn importance_invert(start: u32, rows: bool, n: u32, u: f32) -> ImportanceBin {
    var lo = 0u;
    var hi = n;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if importance_cdf(start, rows, mid) <= u {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    let i = min(lo, n - 1u);
    let below = select(0.0, importance_cdf(start, rows, max(i, 1u) - 1u), i > 0u);
    let width = importance_cdf(start, rows, i) - below;
    let f = select(0.5, clamp((u - below) / width, 0.0, 1.0), width > 0.0);
    return ImportanceBin(i, f);
}

// The direction (the map's frame) of the variates (u1, u2): the row by
// u1, cos θ uniform across it; the column by u2, φ uniform across it.
// Twin: ImportanceTable::direction.
fn importance_direction(u1: f32, u2: f32) -> vec3<f32> {
    let w = environment_importance.header.x;
    let h = environment_importance.header.y;
    let row = importance_invert(0u, true, h, u1);
    let col = importance_invert(row.index * w, false, w, u2);
    // latlong::row_cos_bounds
    let top = cos(PI * f32(row.index) / f32(h));
    let bottom = cos(PI * f32(row.index + 1u) / f32(h));
    let cos_t = top + (bottom - top) * row.fraction;
    let phi = 2.0 * PI * (f32(col.index) + col.fraction) / f32(w);
    // latlong::direction_phi_cos
    let sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    return vec3<f32>(sin_t * sin(phi), cos_t, -sin_t * cos(phi));
}

// The density [1/sr] of unit direction d (the map's frame): its texel's.
// Twin: ImportanceTable::pdf.
fn importance_pdf(d: vec3<f32>) -> f32 {
    let w = environment_importance.header.x;
    let h = environment_importance.header.y;
    let uv = latlong_uv(d);
    let col = min(u32(uv.x * f32(w)), w - 1u);
    let row = min(u32(uv.y * f32(h)), h - 1u);
    return environment_importance.entries[row * w + col].y;
}

// The world direction of direction d in the file's frame: R_y(θ) d, the
// inverse of environment_to_map. Twin: EnvironmentMap::from_map.
fn environment_from_map(d: vec3<f32>) -> vec3<f32> {
    let c = environment.rotation.x;
    let s = environment.rotation.y;
    return vec3<f32>(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// L_o = ∫ f_r L_env cos θ dω by N directions: Σ_k f_r L_env cos θ_k /
// (n_c p_c + n_b p_b + n_m p_m), the samples cosine-weighted, then from
// the lobe, then from the map, each strategy on the Hammersley set of its
// size. Twin: sampled::estimate.
fn environment_sampled(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    // The loop bound is a uniform, but group 3's, which every draw of a
    // frame shares (unlike the material's: UNIFORM_BRANCHES in
    // brdf/phong.wgsl), so lavapipe inlines it once per setting.
    let n = max(environment.samples, 1u);
    let l = sampled_lobe(m);
    // sampled::split
    let has_lobe = l.kind != LOBE_NONE;
    let by_map = environment_importance.header.z != 0u;
    let strategies = 1u + select(0u, 1u, has_lobe) + select(0u, 1u, by_map);
    let n_m = select(0u, n / strategies, by_map);
    let rest = n - n_m;
    let n_c = select(rest, (rest + 1u) / 2u, has_lobe);
    let n_b = rest - n_c;
    // The directions' frame from the normal alone (as sampled::estimate).
    let t = any_tangent(frame.n);
    let b = cross(frame.n, t);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < n; k++) {
        let from_lobe = k >= n_c && k < n_c + n_b;
        let from_map = k >= n_c + n_b;
        var j = k;
        var count = n_c;
        if from_lobe {
            j = k - n_c;
            count = n_b;
        }
        if from_map {
            j = k - n_c - n_b;
            count = n_m;
        }
        // sampled::hammersley
        let u1 = (f32(j) + 0.5) / f32(count);
        let u2 = f32(reverseBits(j)) * 2.3283064365386963e-10;
        var wi: vec3<f32>;
        if from_map {
            wi = environment_from_map(importance_direction(u1, u2));
        } else if from_lobe {
            wi = lobe_direction(l, u1, u2, wo, frame.n, t, b);
        } else {
            // sampled::local_direction (Malley's method)
            let r = sqrt(u1);
            let phi = 2.0 * PI * u2;
            wi = t * (r * cos(phi)) + b * (r * sin(phi)) + frame.n * sqrt(1.0 - u1);
        }
        let c = dot(frame.n, wi);
        let p_b = select(0.0, lobe_pdf(l, wi, wo, frame.n), n_b > 0u);
        // A branch, not a select: without map directions the texel lookup
        // (an atan2 and an acos) is not paid.
        var p_m = 0.0;
        if n_m > 0u {
            p_m = importance_pdf(environment_to_map(wi));
        }
        let mixture = f32(n_c) * max(c, 0.0) * FRAC_1_PI + f32(n_b) * p_b + f32(n_m) * p_m;
        let term = f_r(m, wi, wo, frame) * environment_map_radiance(wi) * (c / mixture);
        sum += select(vec3<f32>(0.0), term, c > 0.0 && mixture > 0.0);
    }
    return sum;
}
