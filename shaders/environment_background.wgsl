// The background (contract: camera rays that miss all geometry see
// scale · L_env(d)): one full-screen triangle at the far plane (z = w),
// drawn after the opaque geometry with the depth test LessEqual and no
// depth write, so every pixel the geometry leaves (its depth still the
// clear value 1) shows the map, and no other is shaded; alpha-BLEND
// geometry is drawn after it, over it. Its fragment's ray is the reference's (Camera::ray) through the
// pixel centre. Radiance targets get coverage 0 (alpha), as the clear.

struct BackgroundOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_background(@builtin(vertex_index) i: u32) -> BackgroundOut {
    // (−1, −1), (3, −1), (−1, 3): covers the viewport.
    let p = vec2<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, f32(i & 2u) * 2.0 - 1.0);
    var out: BackgroundOut;
    out.clip = vec4<f32>(p, 1.0, 1.0);
    out.ndc = p;
    return out;
}

@fragment
fn fs_background(in: BackgroundOut) -> @location(0) TargetTexel {
    let d = normalize(environment.forward + environment.right * in.ndc.x + environment.up * in.ndc.y);
    let radiance = environment_map_radiance(d);
    #if display
    return target_output(radiance);
    #else
    return target_texel(vec4<f32>(radiance, 0.0));
    #endif
}
