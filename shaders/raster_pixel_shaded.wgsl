// Phong shading (lecture: "Shading Model: Phong Shading"): the normal is
// interpolated (perspective-correct barycentrics), renormalized, and the
// reflection equation is evaluated at every pixel's interpolated position.
// Blocks `#if tangents` exist only when a model needs a tangent frame;
// `#if shadow_pixel` / `#elif shadow_vertex`: the shadow-map coordinates are
// computed here per pixel, or per vertex and interpolated
// (ShaderKey::shadow_coords_per_vertex).

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    #if tangents
    @location(3) tangent: vec3<f32>,
    #endif
    #if shadow_vertex
    @location(5) face_normal: vec3<f32>,
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
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    #if tangents
    @location(3) tangent: vec3<f32>,
    #endif
    #if shadow_vertex
    #if shadow_ortho
    @location(4) shadow_ndc: vec3<f32>,
    #else
    @location(4) shadow_clip: vec4<f32>,
    #endif
    #endif
    #if textures
    @location(5) uv0: vec2<f32>,
    @location(6) uv1: vec2<f32>,
    #endif
    #if normal_map
    @location(7) bitangent_sign: f32,
    #endif
    #if vertex_colors
    @location(8) color: vec4<f32>,
    #endif
    #if layer_transmission
    @location(9) @interpolate(flat) instance: u32,
    #endif
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = globals.clip_from_world * vec4<f32>(in.position, 1.0);
    out.world = in.position;
    out.normal = in.normal;
    #if tangents
    out.tangent = in.tangent;
    #endif
    #if textures
    out.uv0 = in.uv0;
    out.uv1 = in.uv1;
    #endif
    #if normal_map
    out.bitangent_sign = in.bitangent_sign;
    #endif
    #if vertex_colors
    out.color = in.color;
    #endif
    #if layer_transmission
    out.instance = in.instance;
    #endif
    // The one orthographic map's coordinates of this corner's lookup point
    // (ShaderKey::shadow_coords_per_vertex says why this is exact).
    #if shadow_vertex
    #if shadow_ortho
    out.shadow_ndc = shadow_ortho_ndc(lights[shadow_caster(0u)], in.position, in.face_normal);
    #else
    // Or the one perspective map's clip coordinates (shading.shadow_coords
    // = "vertex": approximate, docs/shadows.md bounds the displacement).
    out.shadow_clip = shadow_perspective_clip(lights[shadow_caster(0u)], in.position, in.face_normal);
    #endif
    #endif
    return out;
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) TargetTexel {
    #if layer_transmission
    set_draw_volume_scale(in.instance);
    #endif
    // Sides (Material.sides, glTF doubleSided): a back face of a
    // single-sided material is culled, one of a double-sided material is
    // lit with its frame flipped (normal, tangent and bitangent). The
    // condition varies per pixel (front_facing): UNIFORM_BRANCHES.
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
    let flip = select(1.0, -1.0, back == 2u);
    #else
    let flip = 1.0;
    #endif
    // Opposite normals can interpolate to zero: no direction, so only the
    // ambient term remains (the CPU reference does the same).
    // With shadows looked up here: the geometric normal (offset normal of
    // the lookup) from the derivatives of the interpolated position, which
    // lie in the triangle's plane.
    #if shadow_pixel
    let n_g = cross(dpdx(in.world), dpdy(in.world));
    #endif
    #if textures
    // Textures: the material at this pixel (shadowing the module's
    // `material`), read with the UVs' screen derivatives (per 2×2 quad).
    let surface_uv = SurfaceUv(in.uv0, in.uv1, dpdx(in.uv0), dpdy(in.uv0), dpdx(in.uv1), dpdy(in.uv1));
    // Vertex colours (interpolated) multiply the colours first.
    #if vertex_colors
    let textured = textured_surface(vertex_coloured(material, in.color), surface_uv);
    #else
    let textured = textured_surface(material, surface_uv);
    #endif
    #if layer_clearcoat
    var material = textured.material;
    #else
    let material = textured.material;
    #endif
    #elif vertex_colors
    let material = vertex_coloured(material, in.color);
    #endif
    #if alpha
    // Alpha (glTF alphaMode; Material.alpha_mode): the base colour's
    // alpha, textures and vertex colours applied above. MASK: a fragment
    // below the cutoff is discarded (the reference's ray goes on); the
    // condition varies per pixel (UNIFORM_BRANCHES), and the cutoff is 0
    // (never) for the other modes. BLEND: the alpha is the output's.
    let alpha = material.alpha;
    if alpha < material.alpha_cutoff {
        discard;
    }
    let opacity = select(1.0, alpha, material.alpha_mode == 2u);
    #endif
    let n = flip * normalize_or_zero(in.normal);
    #if tangents
    var frame = surface_frame(n, flip * in.tangent);
    #else
    var frame = surface_frame(n, any_tangent(n));
    #endif
    // A normal map: the frame turned to its normal (the sign's
    // interpolation is ±1 within a triangle: split vertices keep a
    // triangle's corners on one side of a mirror seam).
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
    #if shadow_pixel
    let radiance = reflected_radiance(material, in.world, frame, n_g);
    #elif shadow_vertex
    #if shadow_ortho
    let radiance = reflected_radiance(material, in.world, frame, in.shadow_ndc);
    #else
    let radiance = reflected_radiance(material, in.world, frame, in.shadow_clip);
    #endif
    #else
    let radiance = reflected_radiance(material, in.world, frame);
    #endif
    #if alpha
    return target_output_alpha(radiance, opacity);
    #else
    return target_output(radiance);
    #endif
}
