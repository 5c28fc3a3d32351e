// Phong and Blinn-Phong lobes as the lecture writes them.
// f64 twin: src/material/brdf/phong.rs (same names, same order).

// Floor of the cosines the lecture's forms divide by (COS_FLOOR in Rust).
const COS_FLOOR: f32 = 1e-6;

// c^k_e, zero for c ≤ 0, 1 for k_e = 0 (WGSL's pow(0, 0) is undefined).
fn cos_power(c: f32, k_e: f32) -> f32 {
    if c <= 0.0 {
        return 0.0;
    }
    if k_e == 0.0 {
        return 1.0;
    }
    return pow(c, k_e);
}

// R(I) = −I + 2 (I·N) N
fn mirror_direction(wi: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return -wi + 2.0 * dot(wi, n) * n;
}

// Lecture Phong lobe: (R(I)·V)^k_e / (I·N).
fn phong_lecture(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    return cos_power(dot(mirror_direction(wi, n), wo), k_e) / max(dot(n, wi), COS_FLOOR);
}

// Lecture Blinn-Phong lobe: (H·N)^k_e / (I·N), H = (I + V) / |I + V|.
fn blinn_phong_lecture(k_e: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let h = normalize(wi + wo);
    return cos_power(dot(h, n), k_e) / max(dot(n, wi), COS_FLOOR);
}
