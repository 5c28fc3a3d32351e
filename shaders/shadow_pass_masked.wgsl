// The shadow pass of alpha MASK casters (src/gpu/shadow_masks.rs): as
// shaders/shadow_pass.wgsl (same views, same reversed depth), plus a
// fragment stage that discards what MASK cuts out, so light passes
// through it. Opaque and BLEND casters stay in the depth-only pass.
// `#if textures`: the stream has UV sets; `#if vertex_colors`: it has
// COLOR_0 (src/gpu/geometry.rs, VertexLayout).
// f64 twin: Shader::blocks in src/reference/renderer.rs (the same alpha
// at the same point: level 0, the magnification filter).

struct ShadowView {
    clip_from_world: mat4x4<f32>,
}

@group(0) @binding(0) var<storage, read> shadow_views: array<ShadowView>;

// One MASK material's alpha. CPU mirror: GpuShadowMask.
struct ShadowMask {
    row_u: vec4<f32>,  // its base colour texture's KHR_texture_transform, first row (TextureSlot.row_u)
    row_v: vec4<f32>,
    alpha: f32,        // baseColorFactor's alpha (Material.alpha)
    cutoff: f32,       // alphaCutoff
    tex_coord: u32,    // the texture's UV set
    _pad: u32,
}

@group(1) @binding(0) var<uniform> mask: ShadowMask;
// The base colour texture (level 0 is read), or a white texel without one.
@group(1) @binding(1) var mask_texture: texture_2d<f32>;
@group(1) @binding(2) var mask_sampler: sampler;

struct MaskedVertex {
    @builtin(position) clip: vec4<f32>,
    // The texture's UV, transformed per vertex: the transform is affine,
    // so interpolating its result is transforming the interpolated UV.
    @location(0) uv: vec2<f32>,
    // The factor's alpha times COLOR_0's A (a product with a constant:
    // interpolating it is interpolating the colour).
    @location(1) alpha: f32,
}

@vertex
fn vs_shadow_masked(
    @location(0) position: vec3<f32>,
#if textures
    @location(6) uv0: vec2<f32>,
    @location(7) uv1: vec2<f32>,
#endif
#if vertex_colors
    @location(9) color: vec4<f32>,
#endif
    @builtin(instance_index) layer: u32,
) -> MaskedVertex {
    var out: MaskedVertex;
    out.clip = shadow_views[layer].clip_from_world * vec4<f32>(position, 1.0);
    #if textures
    let p = vec3<f32>(select(uv0, uv1, mask.tex_coord == 1u), 1.0);
    out.uv = vec2<f32>(dot(mask.row_u.xyz, p), dot(mask.row_v.xyz, p));
    #else
    out.uv = vec2<f32>(0.0);
    #endif
    out.alpha = mask.alpha;
    #if vertex_colors
    out.alpha *= color.a;
    #endif
    return out;
}

// Absent below the cutoff (glTF 2.0 §3.9.4, alphaMode MASK). Level 0
// explicitly: λ = 0 is magnification, the reference's zero footprint.
@fragment
fn fs_shadow_masked(in: MaskedVertex) {
    let a = in.alpha * textureSampleLevel(mask_texture, mask_sampler, in.uv, 0.0).a;
    if a < mask.cutoff {
        discard;
    }
}
