// Ward's glossy lobe (lecture: "Ward Reflection Model"; Ward 1992),
// isotropic and anisotropic, as the lecture writes it: without ρ_s (k_s
// multiplies) and without the diffuse term (Lambert). Reciprocal.
// f64 twin: src/material/brdf/ward.rs (same names, same order).
// Uses phong.wgsl (COS_FLOOR, EXP_CUTOFF, exp_cutoff), nothing from microfacet.

// Isotropic Ward: exp(−tan²θ_h / σ²) / (4π σ² sqrt((I·N)(V·N))).
// sin²θ_h = |N×H|² (accurate in f32 for narrow lobes, unlike 1 − cos²);
// exponent tested against −80 before dividing (no tan² overflow as N·H → 0,
// no 0/0, no ∞·0; σ = 0 gives 0); cosines under the root floored at
// COS_FLOOR (the form diverges at grazing angles; ≤ 8e12 for σ = 1e-4).
fn ward_isotropic(sigma: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = normalize_or_zero(wi + wo); // 0 for I = −V: then N·H = 0
    let cos_h = dot(n, h);
    if cos_h <= 0.0 {
        return 0.0;
    }
    let n_x_h = cross(n, h);
    let sin2 = dot(n_x_h, n_x_h);
    let cos2 = cos_h * cos_h;
    let sigma2 = sigma * sigma;
    if sin2 >= EXP_CUTOFF * cos2 * sigma2 {
        return 0.0; // exponent ≤ −80 (also catches σ = 0 and cos² underflow)
    }
    let exponent = -sin2 / (cos2 * sigma2); // in (−80, 0]; cos2 * sigma2 > 0 here
    let root = sqrt(max(dot(n, wi), COS_FLOOR) * max(dot(n, wo), COS_FLOOR));
    return exp_cutoff(exponent) / (4.0 * PI * sigma2 * root);
}

// Anisotropic Ward (Ward 1992, eq. 5):
// exp(−((H·t/σx)² + (H·b/σy)²) / (H·n)²) / (4π σx σy sqrt((I·N)(V·N))),
// multiplied through by σx² σy² so no slope is divided by a small σ;
// same −80 test and COS_FLOOR as ward_isotropic. σx = σy: ward_isotropic.
fn ward_anisotropic(
    sigma_x: f32,
    sigma_y: f32,
    n: vec3<f32>,
    t: vec3<f32>,
    b: vec3<f32>,
    wi: vec3<f32>,
    wo: vec3<f32>,
) -> f32 {
    let h = normalize_or_zero(wi + wo); // 0 for I = −V: then N·H = 0
    let cos_h = dot(n, h);
    if cos_h <= 0.0 {
        return 0.0;
    }
    let h_t = dot(h, t);
    let h_b = dot(h, b);
    let cos2 = cos_h * cos_h;
    let sigma_x2 = sigma_x * sigma_x;
    let sigma_y2 = sigma_y * sigma_y;
    let slope2 = h_t * h_t * sigma_y2 + h_b * h_b * sigma_x2;
    let scale = cos2 * sigma_x2 * sigma_y2;
    if slope2 >= EXP_CUTOFF * scale {
        return 0.0; // exponent ≤ −80 (also catches σ = 0 and underflow of scale)
    }
    let exponent = -slope2 / scale; // in (−80, 0]; scale > 0 here
    let root = sqrt(max(dot(n, wi), COS_FLOOR) * max(dot(n, wo), COS_FLOOR));
    return exp_cutoff(exponent) / (4.0 * PI * sigma_x * sigma_y * root);
}
