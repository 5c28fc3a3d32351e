// Flat and Gouraud shading (lecture: "Shading Model"): the reflection
// equation is evaluated per vertex and the colour is interpolated.
// Flat: the vertex stream is de-indexed; every corner of a triangle carries
// the face normal, the triangle's tangent and the centroid as its shading
// point, so all three corners compute the same colour, passed without
// interpolation. Gouraud: the shading point is the vertex, the frame the
// vertex's, and colours are interpolated perspective-correctly.
// Blocks `#if FEATURE` ... `#endif` are kept only when the feature is on
// (src/gpu/shader_gen/features.rs): `flat`, `tangents`, `shadows`.

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    #if tangents
    @location(3) tangent: vec3<f32>,
    #endif
    #if flat
    @location(4) shading_point: vec3<f32>,
    #endif
    #if textures
    @location(6) uv0: vec2<f32>,
    @location(7) uv1: vec2<f32>,
    #endif
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    #if flat
    @location(0) @interpolate(flat) radiance: vec3<f32>,
    #else
    // At the centroid of the covered samples, not the pixel centre: with
    // MSAA the centre of a silhouette pixel may lie outside the triangle,
    // where the colour is extrapolated (negative radiance, issue 19); the
    // centroid is inside, so the value is a convex combination of the
    // vertices' (≥ 0). One sample per pixel: the centroid is the centre.
    @location(0) @interpolate(perspective, centroid) radiance: vec3<f32>,
    #endif
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    let n = normalize_or_zero(in.normal);
    #if tangents
    let frame = surface_frame(n, in.tangent);
    #else
    let frame = surface_frame(n, any_tangent(n));
    #endif
    #if flat
    let x = in.shading_point;
    #else
    let x = in.position;
    #endif
    #if textures
    // Textures: the material at the shading point (flat: the centroid's
    // UVs), level 0, shadowing the module's `material`.
    let material = textured_material_level0(material, in.uv0, in.uv1);
    #endif
    var out: VertexOut;
    out.clip = globals.clip_from_world * vec4<f32>(in.position, 1.0);
    // Shadows: looked up here, at the same shading point, offset along the
    // face normal (flat) or the vertex normal (gouraud), as the reference.
    #if shadows
    out.radiance = reflected_radiance(material, x, frame, n);
    #else
    out.radiance = reflected_radiance(material, x, frame);
    #endif
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    // Alpha 1 marks coverage.
    return target_output(in.radiance);
}
