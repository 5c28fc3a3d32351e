// Phong and Blinn-Phong lobes (lecture: "Phong Glossy Reflection Model",
// "Blinn-Phong Glossy Reflection"): as the lecture writes them, then the
// reciprocal, energy-conserving normalized forms.
// f64 twin: src/material/brdf/phong.rs (same names, same order).
// The helpers here (cos_power, mirror_direction, exp_cutoff) are shared by
// the later BRDF files (ward.wgsl, microfacet.wgsl).

// Floor of the cosines the lecture's forms divide by (COS_FLOOR in Rust):
// cos θ = 1e-6 keeps f_r finite where the formula as written diverges.
const COS_FLOOR: f32 = 1e-6;

// ln 2 (std::f64::consts::LN_2 in Rust), for microfacet.wgsl.
const LN_2: f32 = 0.6931471805599453;

// The exponentials of the lobes are cut off at e^−80 ≈ 1.8e-35, inside
// f32's normal range (e^−87.3): below it exp would be flushed or lose its
// precision while prefactors up to ~1e13 would show the CPU's f64 value.
const EXP_CUTOFF: f32 = 80.0;

// UNIFORM_BRANCHES: no `if` whose condition is a material (uniform) value
// alone, in any shader file: Mesa 22.3's lavapipe "inlines" such uniforms,
// compiling a new variant of the shader at every draw and never freeing
// the old one (lvp_execute.c, update_inline_shader_state; cached from
// Mesa 23.1). The viewer grew by 0.8 MiB a frame with Blinn-Phong.
// Such a test is a select(); both sides are computed anyway on a
// software rasterizer. tests/viewer_soak.rs keeps the memory flat.

// e^x − e^−80 for x > −80, else 0: continuous at the cut (no jump between
// CPU and GPU), changes exp(x) by < 1.8e-35; max(…, 0) absorbs exp's
// rounding just above the cut.
fn exp_cutoff(x: f32) -> f32 {
    if x <= -EXP_CUTOFF {
        return 0.0;
    }
    return max(exp(x) - exp(-EXP_CUTOFF), 0.0);
}

// c^k_e, zero for c ≤ 0, 1 for k_e = 0 (WGSL's pow(0, 0) is undefined).
// As e^(k_e ln c) through exp_cutoff: 0 below e^−80 like the CPU (pow
// underflows in f32 there). Near c = 1 (u = c − 1 > −1/16, exact) ln c is
// the series u − u²/2 + … − u⁶/6 (truncation < 1e-8 relative): WGSL's log
// (and pow) is only absolutely accurate (2^-21) near 1, which k_e up to 1e6
// would amplify. (Rust: ln_1p.) c ≤ 1 (clamped): a cosine of unit vectors
// exceeds 1 only by rounding.
// k_e = 0 is a select, not a branch: see UNIFORM_BRANCHES below.
fn cos_power(c: f32, k_e: f32) -> f32 {
    if c <= 0.0 {
        return 0.0;
    }
    let u = min(c, 1.0) - 1.0; // exact for c ≥ 0.5 (Sterbenz)
    var ln_c: f32;
    if u > -0.0625 {
        ln_c = u * (1.0 + u * (-0.5 + u * (1.0 / 3.0 + u * (-0.25 + u * (0.2 - u / 6.0)))));
    } else {
        ln_c = log(c);
    }
    return select(exp_cutoff(k_e * ln_c), 1.0, k_e == 0.0);
}

// R(I) = −I + 2 (I·N) N
fn mirror_direction(wi: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return -wi + 2.0 * dot(wi, n) * n;
}

// Lecture Phong lobe: (R(I)·V)^k_e / (I·N).
fn phong_lecture(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    return cos_power(dot(mirror_direction(wi, n), wo), k_e) / max(dot(n, wi), COS_FLOOR);
}

// Lecture Blinn-Phong lobe: (H·N)^k_e / (I·N), H = (I + V) / |I + V|
// (H = 0 for I = −V, where the lobe is 0; normalize would give NaN).
fn blinn_phong_lecture(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = normalize_or_zero(wi + wo);
    return cos_power_precise(dot(n, h), sin2_between(n, h), k_e) / max(dot(n, wi), COS_FLOOR);
}

// Normalized Phong (Lewis 1994): ((k_e + 2) / (2π)) (R(I)·V)^k_e.
// Reciprocal; albedo 1 at normal incidence, less elsewhere. ≤ 1.6e5.
fn phong_normalized(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    return (k_e + 2.0) * 0.5 * FRAC_1_PI * cos_power(dot(mirror_direction(wi, n), wo), k_e);
}

// Normalized Blinn-Phong as a microfacet lobe (Ashikhmin & Shirley 2000's
// form, Walter et al. 2007's normalized Blinn D):
// D(H) / (4 (I·H) max(N·I, N·V)), D = ((k_e + 2) / (2π)) (N·H)^k_e.
// Reciprocal, albedo ≤ 1 for all k_e (docs/brdf-math-notes.md).
// I·H and the max floored at COS_FLOOR: finite for I = −V and grazing
// pairs (≤ 1.6e5 / 4e-12 = 4e16).
fn blinn_phong_normalized(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = normalize_or_zero(wi + wo);
    let d = (k_e + 2.0) * 0.5 * FRAC_1_PI * cos_power_precise(dot(n, h), sin2_between(n, h), k_e);
    let cos_ih = max(dot(wi, h), COS_FLOOR); // I·H = V·H ≥ 0; 0 only for I = −V
    let cos_max = max(max(dot(n, wi), dot(n, wo)), COS_FLOOR); // both grazing
    return d / (4.0 * cos_ih * cos_max);
}

// sin²θ = |N × H|², accurate for small angles. Twin: sin2_between.
fn sin2_between(n: vec3<f32>, h: vec3<f32>) -> f32 {
    let c = cross(n, h);
    return dot(c, c);
}

// −ln(1 − x) for x in [0, 1]: the series x + x²/2 + … + x⁸/8 below 0.1
// (truncation < 1.2e-9 relative), log above. (Rust: ln_1p.)
fn neg_ln_1m(x: f32) -> f32 {
    if x < 0.1 {
        return x * (1.0 + x * (0.5 + x * (1.0 / 3.0 + x * (0.25 + x * (0.2 + x * (1.0 / 6.0 + x * (1.0 / 7.0 + x * 0.125)))))));
    }
    return -log(1.0 - x);
}

// ln cos θ: ½ ln(1 − sin²θ) for small angles, log(cos θ) for large ones.
fn ln_cos(cos: f32, sin2: f32) -> f32 {
    if sin2 < 0.5 {
        return -0.5 * neg_ln_1m(sin2);
    }
    return log(cos);
}

// cos^k_e θ from cos θ and sin²θ (ln_cos): accurate near the peak.
fn cos_power_precise(cos: f32, sin2: f32, k_e: f32) -> f32 {
    if cos <= 0.0 {
        return 0.0;
    }
    return select(exp_cutoff(k_e * ln_cos(cos, min(sin2, 1.0))), 1.0, k_e == 0.0);
}
