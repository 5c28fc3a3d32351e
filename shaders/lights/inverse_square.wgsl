// Inverse-square falloff with glTF's optional range window.
// f64 twin: inverse_square in src/scene/light.rs.
// The zero-distance guard is compiled only when some light may sit on a
// shaded point (`#if light_guard`), the range window only when some light
// has a range (`#if light_range`): LightsKey::guard / range.
// Without them the same arithmetic remains (the window is 1: 1/d² is
// window/d² exactly), so leaving them out changes no pixel; on a software
// rasterizer both sides of every branch are paid per pixel and light.

// Returns (ω_i, 1/d² · window); a point at the light gets nothing.
fn inverse_square(to_light: vec3<f32>, range: f32) -> vec4<f32> {
    let d2 = dot(to_light, to_light);
    #if light_guard
    if d2 == 0.0 {
        return vec4<f32>(0.0, 1.0, 0.0, 0.0);
    }
    #endif
    let d = sqrt(d2);
    #if light_range
    var window = 1.0;
    if range > 0.0 {
        let q = d / range;
        let w = clamp(1.0 - q * q * q * q, 0.0, 1.0);
        window = w * w;
    }
    return vec4<f32>(to_light / d, window / d2);
    #else
    return vec4<f32>(to_light / d, 1.0 / d2);
    #endif
}
