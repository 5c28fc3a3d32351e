// The Charlie sheen of KHR_materials_sheen (Conty & Kulla 2017) with its
// fitted Λ and the albedo scaling of the layer below (contract: "Layered
// glTF materials", "Sheen"; pinned choices 5, 6, 10).
// f64 twin: src/material/brdf/gltf_layers/sheen.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR, exp_cutoff, neg_ln_1m).

const SHEEN_ROUGHNESS_FLOOR: f32 = 1e-6;

// α_sh = max(r_sh, 10⁻⁶)².
fn sheen_alpha(sheen_roughness: f32) -> f32 {
    let r = max(sheen_roughness, SHEEN_ROUGHNESS_FLOOR);
    return r * r;
}

// ln sin²θ_h: the series of neg_ln_1m for small cos² (WGSL's log is only
// absolutely accurate near 1), log(sin²) above.
fn ln_sin2(cos2_h: f32, sin2_h: f32) -> f32 {
    if cos2_h < 0.5 {
        return -neg_ln_1m(cos2_h);
    }
    return log(sin2_h);
}

// D = (2 + 1/α) (sin²θ_h)^(1/(2α)) / (2π), through exp_cutoff; 0 for N·H ≤ 0.
fn d_charlie(alpha: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 || sin2_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = min(cos_h, 1.0);
    let exponent = ln_sin2(cos_hc * cos_hc, min(sin2_h, 1.0)) / (2.0 * alpha);
    return (2.0 + 1.0 / alpha) * exp_cutoff(exponent) / (2.0 * PI);
}

// l(x) = a/(1 + b x^c) + d x + e, coefficients mixed by q = (1 − α)².
fn sheen_lambda_fit(x: f32, alpha: f32) -> f32 {
    let q = (1.0 - alpha) * (1.0 - alpha);
    // (p₁ (1 − q) + p₀ q per coefficient; scalars, not `let` arrays: a
    // pipeline with overrides rejected the arrays' constant indexing.)
    let a = 21.5473 * (1.0 - q) + 25.3245 * q;
    let b = 3.82987 * (1.0 - q) + 3.32435 * q;
    let c = 0.19823 * (1.0 - q) + 0.16801 * q;
    let d = -1.97760 * (1.0 - q) + -1.27393 * q;
    let e = -4.32054 * (1.0 - q) + -4.85967 * q;
    let xc = select(0.0, pow(max(x, 1e-30), c), x > 0.0);
    return a / (1.0 + b * xc) + d * x + e;
}

// Λ(μ) = exp(l(μ)) for μ < 0.5, exp(2 l(0.5) − l(1 − μ)) otherwise.
fn sheen_lambda(cos: f32, alpha: f32) -> f32 {
    if cos < 0.5 {
        return exp(sheen_lambda_fit(cos, alpha));
    }
    return exp(2.0 * sheen_lambda_fit(0.5, alpha) - sheen_lambda_fit(1.0 - cos, alpha));
}

// V = 1 / ((1 + Λ(μ_o) + Λ(μ_i)) 4 μ_o μ_i), cosines floored at COS_FLOOR.
fn v_sheen(alpha: f32, cos_i: f32, cos_o: f32) -> f32 {
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return 0.0;
    }
    let ci = min(cos_i, 1.0);
    let co = min(cos_o, 1.0);
    let lambda = 1.0 + sheen_lambda(co, alpha) + sheen_lambda(ci, alpha);
    return 1.0 / (lambda * 4.0 * max(ci, COS_FLOOR) * max(co, COS_FLOOR));
}

// D_sh · V_sh without its colour.
fn sheen_lobe(alpha: f32, cos_h: f32, sin2_h: f32, cos_i: f32, cos_o: f32) -> f32 {
    return d_charlie(alpha, cos_h, sin2_h) * v_sheen(alpha, cos_i, cos_o);
}

// σ = max(0, min(1 − max₃(c_sh) E(μ_o), 1 − max₃(c_sh) E(μ_i))).
fn sheen_scaling(sheen_color: vec3<f32>, albedo_o: f32, albedo_i: f32) -> f32 {
    let c = max(sheen_color.x, max(sheen_color.y, sheen_color.z));
    return max(min(1.0 - c * albedo_o, 1.0 - c * albedo_i), 0.0);
}
