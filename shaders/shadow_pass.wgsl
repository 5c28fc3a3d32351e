// Depth-only shadow passes (src/gpu/shadows.rs): the scene's own vertex
// buffer, position attribute only, drawn once per shadow-map layer with the
// layer as the instance index; no fragment shader. Every layer stores
// reversed depth (1 nearest the light, 0 empty): orthographic layers
// linearly over the scene's extent along the light, perspective and cube
// layers near/z of an infinite reversed projection, whose f32 precision is
// relative and so the same at every distance.

struct ShadowView {
    clip_from_world: mat4x4<f32>,
}

@group(0) @binding(0) var<storage, read> shadow_views: array<ShadowView>;

@vertex
fn vs_shadow(@location(0) position: vec3<f32>, @builtin(instance_index) layer: u32) -> @builtin(position) vec4<f32> {
    return shadow_views[layer].clip_from_world * vec4<f32>(position, 1.0);
}
