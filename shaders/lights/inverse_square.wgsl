// Inverse-square falloff with glTF's optional range window.
// f64 twin: inverse_square in src/scene/light.rs.

// Returns (ω_i, 1/d² · window); a point at the light gets nothing.
fn inverse_square(to_light: vec3<f32>, range: f32) -> vec4<f32> {
    let d2 = dot(to_light, to_light);
    if d2 == 0.0 {
        return vec4<f32>(0.0, 1.0, 0.0, 0.0);
    }
    let d = sqrt(d2);
    var window = 1.0;
    if range > 0.0 {
        let q = d / range;
        let w = clamp(1.0 - q * q * q * q, 0.0, 1.0);
        window = w * w;
    }
    return vec4<f32>(to_light / d, window / d2);
}
