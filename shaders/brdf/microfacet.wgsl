// Microfacet terms of Cook-Torrance (lecture: "Microfacet Distribution
// Functions", "Geometric Attenuation Factor", "Cook-Torrance Specular
// Term"; Cook & Torrance 1982; Walter et al. 2007).
// f64 twin: src/material/brdf/microfacet.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR, LN_2, EXP_CUTOFF, exp_cutoff, cos_power).
// Distributions take (roughness, cos_h = N·H, sin2_h = |N × H|²), are 0
// for cos_h ≤ 0 and clamp cos_h to ≤ 1 (rounding of unit vectors).
// sin2_h keeps small angles that cos_h, rounded to 1 in f32, loses.

// H = (I + V) / |I + V|, or the zero vector for I = −V (undefined): then
// N·H = I·H = V·H = 0, so D = 0, G1 = 0 and the lobe is 0.
fn half_vector(wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    return normalize_or_zero(wi + wo);
}

// Beckmann: exp(−tan²α / m²) / (π m² cos⁴α), normalized, tan² from
// sin2_h = |N × H|² (cos_h rounds to 1 within 3.5e-4 rad of the peak).
// Exponent tested against −80 before dividing (no tan² overflow, no ∞·0 as
// cos_h → 0); past the test cos² > 1/81, value ≤ 1/(π m²) = 3.2e7 at m = 1e-4.
fn d_beckmann(m: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = min(cos_h, 1.0); // rounding can pass 1
    let cos2 = cos_hc * cos_hc;
    let m2 = m * m;
    if sin2_h >= EXP_CUTOFF * cos2 * m2 {
        return 0.0; // exponent ≤ −80
    }
    let exponent = -sin2_h / (cos2 * m2); // in (−80, 0]; cos2 * m2 > 0 here
    return exp_cutoff(exponent) / (PI * m2 * cos2 * cos2);
}

// GGX / Trowbridge-Reitz (Walter 2007): α² / (π ((α² − 1) cos² + 1)²), the
// bracket as α² cos² + sin2_h (in f32, α² − 1 rounds to −1 for α < 2.4e-4
// and the bracket would be 0 at cos = 1). Bracket ≥ about min(α², 1).
fn d_ggx(alpha: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = min(cos_h, 1.0); // rounding can pass 1
    let cos2 = cos_hc * cos_hc;
    let alpha2 = alpha * alpha;
    let d = alpha2 * cos2 + sin2_h; // = (α² − 1) cos² + 1
    return alpha2 / (PI * d * d);
}

// The lecture's Blinn: cos^(−ln 2 / ln cos m) α, peak 1, ½ at α = m (m an
// angle); not normalized. As exp(e · ½ ln(1 − sin²α)) from sin2_h: e
// reaches 1.4e8 at m = 1e-4 where cos has no precision left in f32.
// 0 for cos_h ≤ 0, cut off below e^−80.
// Takes e = blinn_exponent(m), computed once on the CPU in f64 and passed
// in the material buffer (blinn_e): WGSL's sin is accurate to only 2^-11.
fn d_blinn_lecture(e: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    return exp_cutoff(e * ln_cos(cos_h, min(sin2_h, 1.0)));
}


// Blinn normalized: ((e + 2) / (2π)) cos^e α. ≤ 2.2e7 at m = 1e-4.
fn d_blinn_normalized(e: f32, cos_h: f32, sin2_h: f32) -> f32 {
    return (e + 2.0) * 0.5 * FRAC_1_PI * d_blinn_lecture(e, cos_h, sin2_h);
}

// The lecture's Gaussian: exp(−ln 2 (α/m)²), α = atan2(|N × H|, N·H)
// (accurate near the peak, where acos(cos_h) is not), peak 1, ½ at α = m;
// not normalized. Cut off below e^−80.
fn d_gaussian_lecture(m: f32, cos_h: f32, sin2_h: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let alpha = atan2(sqrt(max(sin2_h, 0.0)), cos_h);
    let ratio = alpha / m;
    return exp_cutoff(-LN_2 * ratio * ratio);
}

// The Gaussian normalized: norm · exp(−ln 2 (α/m)²). `norm` is
// gaussian_normalization(m), computed on the CPU in f64 (Rust only; it is
// not a WGSL function) and passed in the material buffer (d_norm).
fn d_gaussian_normalized(m: f32, cos_h: f32, sin2_h: f32, norm: f32) -> f32 {
    return norm * d_gaussian_lecture(m, cos_h, sin2_h);
}


// erfc(x) for x ≥ 0, Abramowitz & Stegun 7.1.26 (after Hastings):
// t = 1/(1 + p x), erfc ≈ t (a1 + t (a2 + t (a3 + t (a4 + t a5)))) e^{−x²},
// |error| ≤ 1.5e-7 absolute (ERFC_F32_ERROR in the f64 twin, which calls
// musl's erfc).
fn erfc(x: f32) -> f32 {
    let t = 1.0 / (1.0 + 0.3275911 * x);
    let poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
    return poly * exp(-x * x);
}

const SQRT_PI: f32 = 1.7724538509055159;

// Past a = 1/(m tanθ_v) ≥ 6, Λ < Λ(6) = 1.1e-17: G1 = 1, Λ = 0 (also keeps a
// finite at normal incidence).
const BECKMANN_A_CUTOFF: f32 = 6.0;

// Smith G1 for Beckmann, exact (Walter et al. 2007, eq. 25, 27): 1/(1 + Λ(a)),
// a = 1/(m tanθ_v), Λ = (erf(a) − 1)/2 + e^{−a²}/(2a√π), with the erfc
// above: G1 within 7.5e-8 + Vulkan's exp allowance of the f64 truth
// (G1_BECKMANN_F32_ERROR). No division by a: s = 2a√π,
// 2a√π Λ = e^{−a²} − (s/2) erfc(a) (clamped ≥ 0: the approximate erfc could
// push G1 past 1), G1 = s / (s + 2a√π Λ), → 0 at grazing. 0 when cos_v ≤ 0
// (one-sided) or cos_vh ≤ 0 (χ⁺). a ≥ 6 tested as cos ≥ 6 m sin; past it
// m sin > cos / 6 > 0. The default; g1_beckmann_rational is the knob.
fn g1_beckmann(m: f32, cos_v: f32, cos_vh: f32) -> f32 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let sin_v = sqrt(1.0 - cos_vc * cos_vc);
    if cos_vc >= BECKMANN_A_CUTOFF * m * sin_v {
        return 1.0; // a ≥ 6: Λ < 1.1e-17
    }
    let a = cos_vc / (m * sin_v);
    let s = 2.0 * SQRT_PI * a;
    let s_lambda = max(exp(-a * a) - 0.5 * s * erfc(a), 0.0); // 2a√π Λ
    return s / (s + s_lambda);
}

// Smith G1 for Beckmann, Walter et al. 2007's rational approximation (as
// Mitsuba): a = 1/(m tanθ_v); a ≥ 1.6 → 1; else
// (3.535a + 2.181a²)/(1 + 2.276a + 2.577a²); up to 0.313 % above the exact
// G1 (at a ≈ 1.34). The knob shading.smith_beckmann = "rational". 0 when
// cos_v ≤ 0 or cos_vh ≤ 0. a ≥ 1.6 tested as cos ≥ 1.6 m sin (no division;
// normal incidence gives 1); past it m sin > cos / 1.6 > 0.
fn g1_beckmann_rational(m: f32, cos_v: f32, cos_vh: f32) -> f32 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let sin_v = sqrt(1.0 - cos_vc * cos_vc);
    if cos_vc >= 1.6 * m * sin_v {
        return 1.0; // a ≥ 1.6
    }
    let a = cos_vc / (m * sin_v);
    let a2 = a * a;
    return (3.535 * a + 2.181 * a2) / (1.0 + 2.276 * a + 2.577 * a2);
}

// Smith G1 for GGX (Walter 2007): 2 / (1 + sqrt(1 + α² tan²θ_v)) · χ⁺, as
// 2 cos / (cos + sqrt(cos² + α² sin²)): no tan² to overflow; denominator ≥ cos > 0.
fn g1_ggx(alpha: f32, cos_v: f32, cos_vh: f32) -> f32 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let cos2 = cos_vc * cos_vc;
    let sin2 = 1.0 - cos2;
    return 2.0 * cos_vc / (cos_vc + sqrt(cos2 + alpha * alpha * sin2));
}

// Smith's Λ for Beckmann, exact (Walter 2007, eq. 27): the Λ of g1_beckmann,
// (e^{−a²} − a√π erfc(a)) / (2a√π) (numerator clamped ≥ 0); a ≥ 6 → 0.
// Needs cos_v > 0 (the caller's χ⁺ test); ~1/(2a√π) towards grazing.
fn lambda_beckmann(m: f32, cos_v: f32) -> f32 {
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let sin_v = sqrt(1.0 - cos_vc * cos_vc);
    if cos_vc >= BECKMANN_A_CUTOFF * m * sin_v {
        return 0.0; // a ≥ 6: Λ < 1.1e-17
    }
    let a = cos_vc / (m * sin_v);
    let s = 2.0 * SQRT_PI * a;
    return max(exp(-a * a) - 0.5 * s * erfc(a), 0.0) / s;
}

// Smith's Λ for Beckmann, Walter 2007's rational form (the Λ of
// g1_beckmann_rational; the knob): a ≥ 1.6 → 0; else
// (1 − 1.259a + 0.396a²)/(3.535a + 2.181a²). Needs cos_v > 0.
fn lambda_beckmann_rational(m: f32, cos_v: f32) -> f32 {
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let sin_v = sqrt(1.0 - cos_vc * cos_vc);
    if cos_vc >= 1.6 * m * sin_v {
        return 0.0; // a ≥ 1.6
    }
    let a = cos_vc / (m * sin_v);
    let a2 = a * a;
    return (1.0 - 1.259 * a + 0.396 * a2) / (3.535 * a + 2.181 * a2);
}

// Smith's Λ for GGX (Heitz 2014): (sqrt(1 + α² tan²) − 1)/2, as
// α² sin² / (2 cos (cos + sqrt(cos² + α² sin²))) (no cancellation). cos_v > 0.
fn lambda_ggx(alpha: f32, cos_v: f32) -> f32 {
    let cos_vc = min(cos_v, 1.0); // rounding can pass 1
    let cos2 = cos_vc * cos_vc;
    let a2s2 = alpha * alpha * (1.0 - cos2);
    return a2s2 / (2.0 * cos_vc * (cos_vc + sqrt(cos2 + a2s2)));
}

// Height-correlated Smith (Heitz 2014, eq. 99): χ⁺(I·H) χ⁺(V·H) / (1 + Λ(I) + Λ(V));
// 0 below either horizon. In [0, 1].
fn g_smith_correlated(lambda_i: f32, lambda_o: f32, cos_i: f32, cos_o: f32, cos_ih: f32, cos_oh: f32) -> f32 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺ = 0
    }
    return 1.0 / (1.0 + lambda_i + lambda_o);
}

// Beckmann slope matching the lecture's Blinn of angle m: sqrt(2 / (e + 2))
// (equal peaks of the normalized lobes; Walter 2007's e = 2/m_b² − 2).
fn beckmann_slope_of_blinn(e: f32) -> f32 {
    return sqrt(2.0 / (e + 2.0));
}

// Beckmann slope matching the lecture's Gaussian of angle m: m / sqrt(ln 2)
// (small angles: exp(−α²/m_b²) = exp(−ln 2 α²/m²)).
fn beckmann_slope_of_gaussian(m: f32) -> f32 {
    return m / sqrt(LN_2);
}

// The lecture's "Final" V-groove G: min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·I)/(V·H)),
// the smaller fraction compared with V·H before dividing (V·H → 0 gives 1);
// a cosine ≤ 0 (below the horizon, or H = 0) gives 0. G ∈ [0, 1].
fn g_vgroove(cos_h: f32, cos_o: f32, cos_i: f32, cos_oh: f32) -> f32 {
    let num = 2.0 * cos_h * min(cos_o, cos_i);
    if num <= 0.0 {
        return 0.0; // below the horizon, or H = 0
    }
    if num >= cos_oh {
        return 1.0; // min(1, …) = 1; includes V·H → 0
    }
    return num / cos_oh; // cos_oh > num > 0 here
}

// Cook-Torrance specular: D G F / (denominator (N·V)(N·I)), denominator 4
// (microfacet standard) or π (the lecture). Cosines floored at COS_FLOOR
// (the form diverges at grazing angles; ≤ 8e18, finite in f32).
fn cook_torrance_specular(d: f32, g: f32, f: vec3<f32>, cos_i: f32, cos_o: f32, denominator: f32) -> vec3<f32> {
    return f * (d * g / (denominator * max(cos_o, COS_FLOOR) * max(cos_i, COS_FLOOR)));
}
