// The thin-film Fresnel of KHR_materials_iridescence (Belcour & Barla 2017,
// in the Khronos Sample Renderer's XYZ-Fourier form; contract: "Layered
// glTF materials", "Iridescence"; pinned choices 1-3). Lengths in nm.
// f64 twin: src/material/brdf/gltf_layers/iridescence.rs (same names, same order).
// Uses gltf_pbr.wgsl (schlick_weight).

const XYZ_TO_REC709: mat3x3<f32> = mat3x3<f32>(
    vec3<f32>(3.2404542, -0.9692660, 0.0556434),
    vec3<f32>(-1.5371385, 1.8760108, -0.2040259),
    vec3<f32>(-0.4985314, 0.0415560, 1.0572252),
); // columns: M · xyz with M's rows (3.2404542, −1.5371385, −0.4985314), …
const SENSITIVITY_V: vec3<f32> = vec3<f32>(5.4856e-13, 4.4201e-13, 5.2481e-13);
const SENSITIVITY_P: vec3<f32> = vec3<f32>(1.6810e6, 1.7953e6, 2.2084e6);
const SENSITIVITY_SIGMA: vec3<f32> = vec3<f32>(4.3278e9, 9.3046e9, 6.6121e9);
const SENSITIVITY_X2: vec3<f32> = vec3<f32>(9.7470e-14, 2.2399e6, 4.5282e9);
const SENSITIVITY_NORM: f32 = 1.0685e-7;
const THIN_FILM_BLEND_NM: f32 = 0.03;
const TAU: f32 = 6.283185307179586;

// cos x with x reduced to [−π, π] first: Vulkan bounds cos (2⁻¹¹ absolute)
// only there.
fn cos_wrapped(x: f32) -> f32 {
    return cos(x - TAU * round(x / TAU));
}

// 𝒮(x, φ) in linear Rec.709: the Fourier term of path difference x [nm],
// phase shift φ_k on XYZ component k.
fn eval_sensitivity(opd: f32, shift: vec3<f32>) -> vec3<f32> {
    let phase = TAU * opd * 1e-9;
    let amplitude = SENSITIVITY_V * sqrt(TAU * SENSITIVITY_SIGMA);
    let arg = SENSITIVITY_P * phase + shift;
    var xyz = amplitude * vec3<f32>(cos_wrapped(arg.x), cos_wrapped(arg.y), cos_wrapped(arg.z))
        * exp(-phase * phase * SENSITIVITY_SIGMA);
    xyz.x += SENSITIVITY_X2.x * sqrt(TAU * SENSITIVITY_X2.z) * cos_wrapped(SENSITIVITY_X2.y * phase + shift.x)
        * exp(-SENSITIVITY_X2.z * phase * phase);
    return XYZ_TO_REC709 * (xyz / SENSITIVITY_NORM);
}

// ((n_a − n_b)/(n_a + n_b))².
fn ior_to_f0(n_a: f32, n_b: f32) -> f32 {
    let r = (n_a - n_b) / (n_a + n_b);
    return r * r;
}

// (1 + √f)/(1 − √f), f clamped to [0, 0.9999] (pinned choice 3).
fn f0_to_ior(f: f32) -> f32 {
    let s = sqrt(clamp(f, 0.0, 0.9999));
    return (1.0 + s) / (1.0 - s);
}

// F_ir(f): a film of index eta_f, thickness [nm], on a base of
// normal-incidence reflectance base_f0, seen at cos θ₁ = cos_o.
fn iridescence_fresnel(cos_o: f32, eta_f: f32, thickness: f32, base_f0: vec3<f32>) -> vec3<f32> {
    let x = clamp(thickness / THIN_FILM_BLEND_NM, 0.0, 1.0);
    let n2 = 1.0 + (eta_f - 1.0) * (x * x * (3.0 - 2.0 * x));
    let cos1 = clamp(cos_o, 0.0, 1.0);
    let cos2 = sqrt(1.0 - (1.0 - cos1 * cos1) / (n2 * n2));
    let r0 = ior_to_f0(n2, 1.0);
    let r12 = r0 + (1.0 - r0) * schlick_weight(cos1);
    let t121 = 1.0 - r12;
    let opd = 2.0 * n2 * thickness * cos2;
    var r23 = vec3<f32>(0.0);
    var phi = vec3<f32>(0.0);
    for (var c = 0; c < 3; c++) {
        let n3 = f0_to_ior(base_f0[c]);
        let r1 = ior_to_f0(n3, n2);
        r23[c] = r1 + (1.0 - r1) * schlick_weight(cos2);
        phi[c] = PI + select(0.0, PI, n3 < n2);
    }
    let r123 = clamp(r23 * r12, vec3<f32>(1e-5), vec3<f32>(0.9999));
    let r = sqrt(r123);
    let rs = r23 * (t121 * t121) / (vec3<f32>(1.0) - r123);
    var out = rs + r12;
    var cm = rs - t121;
    for (var m = 1; m <= 2; m++) {
        cm *= r;
        out += cm * eval_sensitivity(f32(m) * opd, phi * f32(m)) * 2.0;
    }
    return max(out, vec3<f32>(0.0));
}
