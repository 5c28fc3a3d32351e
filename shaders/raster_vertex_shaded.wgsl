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
    #if normal_map
    @location(8) bitangent_sign: f32,
    #endif
    #if vertex_colors
    @location(9) color: vec4<f32>,
    #endif
    #if layer_transmission
    // The object's length scale, in the draw's first instance
    // (set_draw_volume_scale).
    @builtin(instance_index) instance: u32,
    #endif
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    #if flat
    @location(0) @interpolate(flat) radiance: vec3<f32>,
    #else
    // At the centroid of the covered samples, not the pixel centre: with
    // MSAA the centre of a silhouette pixel may lie outside the triangle,
    // where the colour is extrapolated (negative radiance); the
    // centroid is inside, so the value is a convex combination of the
    // vertices' (≥ 0). One sample per pixel: the centroid is the centre.
    @location(0) @interpolate(perspective, centroid) radiance: vec3<f32>,
    #endif
    #if two_sided
    #if flat
    @location(1) @interpolate(flat) radiance_back: vec3<f32>,
    #else
    @location(1) radiance_back: vec3<f32>,
    #endif
    #endif
    // The alpha (glTF alphaMode), per vertex as the colour.
    #if alpha
    #if flat
    @location(2) @interpolate(flat) alpha: f32,
    #else
    @location(2) @interpolate(perspective, centroid) alpha: f32,
    #endif
    #endif
}

#if alpha
// The base colour's alpha at a vertex (flat: the centroid's UVs and the
// corners' mean colour), textures at level 0, as its radiance reads
// them. Twin: reference::renderer's `alpha`.
fn vertex_alpha(in: VertexIn) -> f32 {
    #if vertex_colors
    let coloured = vertex_coloured(material, in.color);
    #else
    let coloured = material;
    #endif
    #if textures
    return textured_surface_level0(coloured, in.uv0, in.uv1).material.alpha;
    #else
    return coloured.alpha;
    #endif
}
#endif

// The radiance of a vertex's front (flip 1) or back (flip −1: the frame
// turned over, for double-sided materials).
fn vertex_radiance(in: VertexIn, flip: f32) -> vec3<f32> {
    let n = flip * normalize_or_zero(in.normal);
    #if tangents
    var frame = surface_frame(n, flip * in.tangent);
    #else
    var frame = surface_frame(n, any_tangent(n));
    #endif
    #if flat
    let x = in.shading_point;
    #else
    let x = in.position;
    #endif
    #if textures
    // Textures: the material at the shading point (flat: the centroid's
    // UVs), level 0, shadowing the module's `material`.
    // Vertex colours (flat: the corners' mean) multiply the colours first.
    #if vertex_colors
    let textured = textured_surface_level0(vertex_coloured(material, in.color), in.uv0, in.uv1);
    #else
    let textured = textured_surface_level0(material, in.uv0, in.uv1);
    #endif
    #if layer_clearcoat
    var material = textured.material;
    #else
    let material = textured.material;
    #endif
    #elif vertex_colors
    let material = vertex_coloured(material, in.color);
    #endif
    // A normal map (flat: the triangle's first corner's sign at every
    // corner, as the reference).
    #if normal_map
    #if layer_clearcoat
    let vertex_frame = frame;
    #endif
    frame = normal_mapped_frame(frame, flip * select(1.0, -1.0, in.bitangent_sign < 0.0), textured.normal);
    // The coat's normal map, in the mesh's frame, in the shading frame's
    // coordinates.
    #if layer_clearcoat
    material.layers.clearcoat_normal = clearcoat_normal_coords(vertex_frame, flip * select(1.0, -1.0, in.bitangent_sign < 0.0), textured.clearcoat_normal, frame, material.layers.clearcoat_normal);
    #endif
    #endif
    // Shadows: looked up here, at the same shading point, offset along the
    // face normal (flat) or the vertex normal (gouraud), as the reference.
    #if shadows
    return reflected_radiance(material, x, frame, n);
    #else
    return reflected_radiance(material, x, frame);
    #endif
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var out: VertexOut;
    #if layer_transmission
    set_draw_volume_scale(in.instance);
    #endif
    out.clip = globals.clip_from_world * vec4<f32>(in.position, 1.0);
    out.radiance = vertex_radiance(in, 1.0);
    // Double-sided materials in the scene: both sides shaded here, the
    // fragment picks by its facing (OpenGL's two-sided lighting).
    #if two_sided
    out.radiance_back = vertex_radiance(in, -1.0);
    #endif
    #if alpha
    out.alpha = vertex_alpha(in);
    #endif
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) TargetTexel {
    // Sides (Material.sides, glTF doubleSided): a back face of a
    // single-sided material is culled; a double-sided one shows its back's
    // radiance. The condition varies per pixel (front_facing):
    // UNIFORM_BRANCHES.
    // Compiled only when some material is single-sided (`culling`) or
    // double-sided (`two_sided`).
    #if culling || two_sided
    let back = select(0u, material.sides, !front_facing);
    #endif
    #if culling
    if back == 1u {
        discard;
    }
    #endif
    #if two_sided
    let radiance = select(in.radiance, in.radiance_back, back == 2u);
    #else
    let radiance = in.radiance;
    #endif
    // Alpha (as in raster_pixel_shaded.wgsl): MASK discards below the
    // cutoff (a per-pixel condition), BLEND outputs it; else alpha 1
    // marks coverage.
    #if alpha
    if in.alpha < material.alpha_cutoff {
        discard;
    }
    return target_output_alpha(radiance, select(1.0, in.alpha, material.alpha_mode == 2u));
    #else
    return target_output(radiance);
    #endif
}
