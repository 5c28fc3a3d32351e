// Lambert: ideal diffuse reflection (lecture: "Diffuse Reflection Model").
// f64 twin: src/material/brdf/lambert.rs.

// f_r = k_d / π with k_d the albedo.
fn lambert(k_d: vec3<f32>) -> vec3<f32> {
    return k_d * FRAC_1_PI;
}
