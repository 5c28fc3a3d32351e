// One level of a transmission image's mip chain (src/gpu/transmission.rs)
// from the level above it: the mean of the 2 × 2 texels it covers (a box
// filter, as a hardware mip chain; an odd size's last row or column is
// clamped onto the one before).

@group(0) @binding(0) var source: texture_2d<f32>;

// A triangle covering the target.
@vertex
fn vs_mip(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u);
    let y = f32(i & 2u);
    return vec4<f32>(2.0 * x - 1.0, 1.0 - 2.0 * y, 0.0, 1.0);
}

@fragment
fn fs_mip(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let last = vec2<i32>(textureDimensions(source)) - vec2<i32>(1);
    let s = 2 * vec2<i32>(p.xy);
    let a = textureLoad(source, min(s, last), 0);
    let b = textureLoad(source, min(s + vec2<i32>(1, 0), last), 0);
    let c = textureLoad(source, min(s + vec2<i32>(0, 1), last), 0);
    let d = textureLoad(source, min(s + vec2<i32>(1, 1), last), 0);
    return 0.25 * (a + b + c + d);
}
