// Depth-only shadow passes (src/gpu/shadows.rs): the scene's own vertex
// buffer, position attribute only, drawn once per shadow-map layer with
// the layer as the instance index. Orthographic layers (directional
// lights) store clip z; perspective and cube layers store the radial
// distance to the light times depth_scale, which is what shaders/shadows.wgsl
// compares against.

struct ShadowView {
    clip_from_world: mat4x4<f32>,
    origin: vec3<f32>,
    depth_scale: f32,
}

@group(0) @binding(0) var<storage, read> shadow_views: array<ShadowView>;

struct RadialOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) @interpolate(flat) layer: u32,
}

@vertex
fn vs_ortho(@location(0) position: vec3<f32>, @builtin(instance_index) layer: u32) -> @builtin(position) vec4<f32> {
    return shadow_views[layer].clip_from_world * vec4<f32>(position, 1.0);
}

@vertex
fn vs_radial(@location(0) position: vec3<f32>, @builtin(instance_index) layer: u32) -> RadialOut {
    var out: RadialOut;
    out.clip = shadow_views[layer].clip_from_world * vec4<f32>(position, 1.0);
    out.world = position;
    out.layer = layer;
    return out;
}

@fragment
fn fs_radial(in: RadialOut) -> @builtin(frag_depth) f32 {
    let view = shadow_views[in.layer];
    return min(distance(in.world, view.origin) * view.depth_scale, 1.0);
}
