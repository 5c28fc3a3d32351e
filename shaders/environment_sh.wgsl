// Glossy reflection of the lecture's Phong lobes by spherical-harmonic
// convolution, a zonal product (environment.specular = "sh"; Ramamoorthi
// & Hanrahan 2002), read at the mirror direction. Only in shaders of
// scenes in that mode (feature `environment_sh`), after environment.wgsl.
// f64 twin: src/environment/sh_phong.rs (same functions, same order; the
// derivation is there).

// 2π I_l(s), bands 0-4: the zonal coefficients of (R·ω)₊^s,
// I_0 = 1/(s+1), I_1 = 1/(s+2), I_l = (s−l+2)/(s+l+1)·I_{l−2}.
// Twin: phong_weights.
fn sh_phong_weights(s: f32) -> array<f32, 5> {
    let i0 = 1.0 / (s + 1.0);
    let i1 = 1.0 / (s + 2.0);
    let i2 = i0 * s / (s + 3.0);
    let i3 = i1 * (s - 1.0) / (s + 4.0);
    let i4 = i2 * (s - 2.0) / (s + 5.0);
    let tau = 2.0 * PI;
    return array<f32, 5>(tau * i0, tau * i1, tau * i2, tau * i3, tau * i4);
}

// Σ_i w_band(i) · sh_radiance[i] · Y_i(d), d in the file's frame (not
// necessarily unit: sh_convolved_derivative). Twin: convolved.
fn sh_convolved(w: array<f32, 5>, d: vec3<f32>) -> vec3<f32> {
    let b = sh_basis(d);
    // Constant indices only (sh_sum in environment.wgsl says why).
    let weighted = array<f32, 25>(
        w[0] * b[0],
        w[1] * b[1],
        w[1] * b[2],
        w[1] * b[3],
        w[2] * b[4],
        w[2] * b[5],
        w[2] * b[6],
        w[2] * b[7],
        w[2] * b[8],
        w[3] * b[9],
        w[3] * b[10],
        w[3] * b[11],
        w[3] * b[12],
        w[3] * b[13],
        w[3] * b[14],
        w[3] * b[15],
        w[4] * b[16],
        w[4] * b[17],
        w[4] * b[18],
        w[4] * b[19],
        w[4] * b[20],
        w[4] * b[21],
        w[4] * b[22],
        w[4] * b[23],
        w[4] * b[24],
    );
    return sh_sum(environment.sh_radiance, weighted);
}

#if phong-normalized || blinn-phong-normalized
// t·∇F(d) for t ⊥ d: the five-point central difference, exact for the
// degree-4 polynomials of the basis (h = ½). Twin: tangent_derivative.
fn sh_convolved_derivative(w: array<f32, 5>, d: vec3<f32>, t: vec3<f32>) -> vec3<f32> {
    let h = 0.5;
    let near = sh_convolved(w, d + t * h) - sh_convolved(w, d + t * (-h));
    let far = sh_convolved(w, d + t * (2.0 * h)) - sh_convolved(w, d + t * (-2.0 * h));
    return (near * 8.0 - far) * (1.0 / (12.0 * h));
}
#endif

#if phong || phong-normalized || blinn-phong || blinn-phong-normalized
// The glossy term without k_s at the mirror direction r (world frame):
// the lecture's lobe F_n(R), or normalized Phong's
// (n+2)/(2π) [μ F_{n+1}(R) + t·∇F_{n+1}(R)/(n+1)], μ = N·R, t = N − μR.
// A select between them (UNIFORM_BRANCHES in brdf/phong.wgsl).
// Twin: glossy.
fn environment_sh_glossy(k_e: f32, normalized: bool, r: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let s = select(k_e, k_e + 1.0, normalized);
    let w = sh_phong_weights(s);
    let rm = environment_to_map(r);
    let f = sh_convolved(w, rm);
    var g = f;
    #if phong-normalized || blinn-phong-normalized
    let mu = dot(n, r);
    let t = environment_to_map(n - r * mu);
    let along_r = f * mu;
    let across = sh_convolved_derivative(w, rm, t) * (1.0 / (k_e + 1.0));
    g = select(g, (along_r + across) * ((k_e + 2.0) * 0.5 * FRAC_1_PI), normalized);
    #endif
    return g;
}
#endif

// The SH diffuse term plus, for the Phong models, k_s times the convolved
// lobe at the mirror direction of wo (the lecture's Blinn-Phong as the
// mirror lobe of exponent n/4, the normalized one as normalized Phong of
// exponent n/4: approximations). Twin: estimate (and lobe).
fn environment_sh(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let n = frame.n;
    let diffuse = environment_diffuse_albedo(m) * FRAC_1_PI * sh_irradiance(n);
    #if phong || phong-normalized || blinn-phong || blinn-phong-normalized
    let model = brdf_model(m);
    var lecture = false;
    var normalized = false;
    var k_e = m.k_e;
    #if phong
    lecture = model == MODEL_PHONG;
    #endif
    #if blinn-phong
    let blinn = model == MODEL_BLINN_PHONG;
    lecture = lecture || blinn;
    k_e = select(k_e, 0.25 * k_e, blinn);
    #endif
    #if phong-normalized
    normalized = model == MODEL_PHONG_NORMALIZED;
    #endif
    #if blinn-phong-normalized
    let blinn_normalized = model == MODEL_BLINN_PHONG_NORMALIZED;
    normalized = normalized || blinn_normalized;
    k_e = select(k_e, 0.25 * k_e, blinn_normalized);
    #endif
    let r = mirror_direction(wo, n);
    let glossy = m.k_s * environment_sh_glossy(k_e, normalized, r, n);
    return diffuse + select(vec3<f32>(0.0), glossy, (lecture || normalized) && dot(n, wo) > 0.0);
    #else
    return diffuse;
    #endif
}
