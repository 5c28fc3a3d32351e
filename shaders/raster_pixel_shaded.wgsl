// Phong shading (lecture: "Shading Model: Phong Shading"): the normal is
// interpolated (perspective-correct barycentrics), renormalized, and the
// reflection equation is evaluated at every pixel's interpolated position.
// Lines marked `#if tangents` exist only when a model needs a tangent frame;
// `#if shadow_pixel` / `#if shadow_vertex`: the shadow-map coordinates are
// computed here per pixel, or per vertex and interpolated
// (ShaderKey::shadow_coords_per_vertex).

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(3) tangent: vec3<f32>, // #if tangents
    @location(5) face_normal: vec3<f32>, // #if shadow_vertex
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(3) tangent: vec3<f32>, // #if tangents
    @location(4) shadow_ndc: vec3<f32>, // #if shadow_vertex
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = globals.clip_from_world * vec4<f32>(in.position, 1.0);
    out.world = in.position;
    out.normal = in.normal;
    out.tangent = in.tangent; // #if tangents
    // The one orthographic map's coordinates of this corner's lookup point
    // (ShaderKey::shadow_coords_per_vertex says why this is exact).
    out.shadow_ndc = shadow_ortho_ndc(lights[shadow_caster(0u)], in.position, in.face_normal); // #if shadow_vertex
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    // Opposite normals can interpolate to zero: no direction, so only the
    // ambient term remains (the CPU reference does the same).
    // With shadows looked up here: the geometric normal (offset normal of
    // the lookup) from the derivatives of the interpolated position, which
    // lie in the triangle's plane.
    let n_g = cross(dpdx(in.world), dpdy(in.world)); // #if shadow_pixel
    let n = normalize_or_zero(in.normal);
    let frame = surface_frame(n, in.tangent); // #if tangents
    let frame = surface_frame(n, any_tangent(n)); // #if !tangents
    return target_output(reflected_radiance(material, in.world, frame)); // #if !shadows
    return target_output(reflected_radiance(material, in.world, frame, n_g)); // #if shadow_pixel
    return target_output(reflected_radiance(material, in.world, frame, in.shadow_ndc)); // #if shadow_vertex
}
