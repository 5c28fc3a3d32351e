// Oren-Nayar: diffuse reflection from rough surfaces (Oren & Nayar,
// "Generalization of Lambert's Reflectance Model", SIGGRAPH 1994): the
// qualitative model (eq. 30) and the full model (eqs. 27–29), each under
// its own name. σ is the facets' slope-angle deviation in radians; the
// coefficients A, B, c3, l2 are derived from it once on the CPU
// (oren_nayar_terms). Reciprocal; Lambert at σ = 0.
// f64 twin: src/material/brdf/oren_nayar.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR).

// A = C1, B (factor of C2), c3 (factor of C3), l2 (factor of L2).
struct OrenNayarTerms {
    a: f32,
    b: f32,
    c3: f32,
    l2: f32,
}

// The coefficients as the CPU derived them (Material.lobe, filled by
// Brdf::shader_params): (A, B, c3, l2).
fn oren_nayar_terms(lobe: vec4<f32>) -> OrenNayarTerms {
    return OrenNayarTerms(lobe.x, lobe.y, lobe.z, lobe.w);
}

// sin and cos of α = max(θ_i, θ_o) and β = min(θ_i, θ_o), and cos Δφ.
struct OrenNayarAngles {
    sin_alpha: f32,
    cos_alpha: f32,
    sin_beta: f32,
    cos_beta: f32,
    cos_phi: f32,
}

// Sines from |N×I| (exact near the normal), cosines from N·I; cos Δφ from
// the Lagrange identity (N×I)·(N×V) = I·V − (N·I)(N·V), 0 where either
// projection vanishes (the azimuth is undefined and every term it enters
// vanishes with β).
fn oren_nayar_angles(n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> OrenNayarAngles {
    let n_x_i = cross(n, wi);
    let n_x_o = cross(n, wo);
    let sin_i = length(n_x_i);
    let sin_o = length(n_x_o);
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    let projections = sin_i * sin_o;
    var cos_phi = 0.0;
    if projections > 0.0 {
        cos_phi = clamp(dot(n_x_i, n_x_o) / projections, -1.0, 1.0);
    }
    // The larger angle has the smaller cosine.
    if cos_i < cos_o {
        return OrenNayarAngles(sin_i, cos_i, sin_o, cos_o, cos_phi);
    }
    return OrenNayarAngles(sin_o, cos_o, sin_i, cos_i, cos_phi);
}

// The qualitative model (eq. 30): k_d/π (A + B max(0, cos Δφ) sin α tan β),
// tan β = sin β / max(cos β, COS_FLOOR).
fn oren_nayar_qualitative(k_d: vec3<f32>, t: OrenNayarTerms, g: OrenNayarAngles) -> vec3<f32> {
    let tan_beta = g.sin_beta / max(g.cos_beta, COS_FLOOR);
    return k_d * (FRAC_1_PI * (t.a + t.b * max(g.cos_phi, 0.0) * g.sin_alpha * tan_beta));
}

// The full model (eqs. 27–29): L1 + L2 with
// L1 = k_d/π (C1 + cos Δφ C2 tan β + (1 − |cos Δφ|) C3 tan((α+β)/2)), clamped at 0,
// C2 = B sin α (cos Δφ ≥ 0) or B (sin α − (2β/π)³), C3 = c3 (4αβ/π²)²,
// L2 = l2 k_d²/π (1 − cos Δφ (2β/π)²);
// tan((α+β)/2) = (sin α + sin β) / (cos α + cos β), α and β from atan2.
fn oren_nayar_full(k_d: vec3<f32>, t: OrenNayarTerms, g: OrenNayarAngles) -> vec3<f32> {
    let alpha = atan2(g.sin_alpha, g.cos_alpha);
    let beta = atan2(g.sin_beta, g.cos_beta);
    let tan_beta = g.sin_beta / max(g.cos_beta, COS_FLOOR);
    let tan_half_sum = (g.sin_alpha + g.sin_beta) / max(g.cos_alpha + g.cos_beta, COS_FLOOR);
    let two_beta_over_pi = 2.0 * FRAC_1_PI * beta;
    var c2 = t.b * g.sin_alpha;
    if g.cos_phi < 0.0 {
        c2 = t.b * (g.sin_alpha - two_beta_over_pi * two_beta_over_pi * two_beta_over_pi);
    }
    let four_alpha_beta = 4.0 * FRAC_1_PI * FRAC_1_PI * alpha * beta;
    let c3 = t.c3 * four_alpha_beta * four_alpha_beta;
    let direct = max(
        t.a + g.cos_phi * c2 * tan_beta + (1.0 - abs(g.cos_phi)) * c3 * tan_half_sum,
        0.0,
    );
    let interreflection = t.l2 * (1.0 - g.cos_phi * two_beta_over_pi * two_beta_over_pi);
    return k_d * (FRAC_1_PI * direct) + k_d * k_d * (FRAC_1_PI * interreflection);
}
