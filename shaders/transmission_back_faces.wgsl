// The back faces of transmissive volumes (src/gpu/transmission_back_faces.rs):
// the scene's own vertex stream, position and normal (world space), drawn
// before the transmission images when `shading.transmission_exit_ray` is
// "traced". A fragment whose normal faces the eye is a front face and is
// discarded; the depth test keeps the nearest back face, whose outward
// normal and depth shaders/transmission_traced.wgsl marches against
// (Wyman 2005's second interface).

// The first fields of the scene's globals (shaders/common.wgsl).
struct Camera {
    clip_from_world: mat4x4<f32>,
    eye: vec3<f32>,
}

@group(0) @binding(0) var<uniform> camera: Camera;

struct BackFaceVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

@vertex
fn vs_back_face(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> BackFaceVertex {
    var out: BackFaceVertex;
    out.clip = camera.clip_from_world * vec4<f32>(position, 1.0);
    out.world = position;
    out.normal = normal;
    return out;
}

@fragment
fn fs_back_face(v: BackFaceVertex) -> @location(0) vec4<f32> {
    let n = normalize(v.normal);
    if dot(n, camera.eye - v.world) > 0.0 {
        discard;
    }
    return vec4<f32>(n, v.clip.z);
}
