// Flat and Gouraud shading (lecture: "Shading Model"): the reflection
// equation is evaluated per vertex and the colour is interpolated.
// Flat: the vertex stream is de-indexed; every corner of a triangle carries
// the face normal and the centroid as its shading point, so all three
// corners compute the same colour, passed without interpolation.
// Gouraud: the shading point is the vertex, the normal the vertex normal,
// and the colours are interpolated perspective-correctly.
// `VertexIn`, `shading_point` and `RADIANCE_INTERPOLATION` come from
// src/gpu/shader_gen.rs.

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) RADIANCE_INTERPOLATION radiance: vec3<f32>,
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    let m = materials[in.material];
    var out: VertexOut;
    out.clip = globals.clip_from_world * vec4<f32>(in.position, 1.0);
    out.radiance = reflected_radiance(m, shading_point(in), normalize_or_zero(in.normal));
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    // Alpha 1 marks coverage.
    return vec4<f32>(in.radiance, 1.0);
}
