// Material textures (bind group 2), in the module only when the scene has
// textures (feature `textures`): the lecture's spatially varying BRDF.
// Each material has up to MAX_TEXTURE_SLOTS slots; a slot is an image
// (a full mip-chain view, or level 0 alone for a sampler without
// mipmaps), its sampler, its UV set and KHR_texture_transform, and which
// Material fields it scales. f64 twin: src/reference/texture.rs (the
// sampler's filtering is the GPU's own; the twin reproduces Vulkan's
// rules). CPU side: src/gpu/textures.rs.

// One slot. CPU mirror: GpuTextureSlot.
struct TextureSlot {
    row_u: vec4<f32>,  // u' = dot(row_u.xyz, (u, v, 1)): KHR_texture_transform, first row
    row_v: vec4<f32>,  // v' = dot(row_v.xyz, (u, v, 1))
    fields: u32,       // bit mask of the Material fields it scales (material::texture::gpu_field_values order); 0: unused
    channel: u32,      // 4: RGB (a colour parameter); 0-3: the channel a scalar parameter reads
    tex_coord: u32,    // UV set (TEXCOORD_n)
    _pad: u32,
}

struct TextureSlots {
    slots: array<TextureSlot, MAX_TEXTURE_SLOTS>,
}

@group(2) @binding(0) var<uniform> texture_slots: TextureSlots;
@group(2) @binding(1) var slot_texture_0: texture_2d<f32>;
@group(2) @binding(2) var slot_texture_1: texture_2d<f32>;
@group(2) @binding(3) var slot_texture_2: texture_2d<f32>;
@group(2) @binding(4) var slot_texture_3: texture_2d<f32>;
@group(2) @binding(5) var slot_texture_4: texture_2d<f32>;
@group(2) @binding(6) var slot_texture_5: texture_2d<f32>;
@group(2) @binding(7) var slot_sampler_0: sampler;
@group(2) @binding(8) var slot_sampler_1: sampler;
@group(2) @binding(9) var slot_sampler_2: sampler;
@group(2) @binding(10) var slot_sampler_3: sampler;
@group(2) @binding(11) var slot_sampler_4: sampler;
@group(2) @binding(12) var slot_sampler_5: sampler;

// The UV sets at a shading point and their screen derivatives (zero at a
// vertex: level 0, magnification filter, as the reference's zero footprint).
struct SurfaceUv {
    uv0: vec2<f32>,
    uv1: vec2<f32>,
    ddx0: vec2<f32>,
    ddy0: vec2<f32>,
    ddx1: vec2<f32>,
    ddy1: vec2<f32>,
}

// Slot i's texel at uv with the footprint (ddx, ddy). Explicit gradients:
// the level of detail is the one the reference computes from the same
// derivatives (reference::texture::sample), and sampling is allowed
// outside uniform control flow.
fn slot_texel(i: u32, uv: vec2<f32>, ddx: vec2<f32>, ddy: vec2<f32>) -> vec4<f32> {
    switch i {
        case 0u: { return textureSampleGrad(slot_texture_0, slot_sampler_0, uv, ddx, ddy); }
        case 1u: { return textureSampleGrad(slot_texture_1, slot_sampler_1, uv, ddx, ddy); }
        case 2u: { return textureSampleGrad(slot_texture_2, slot_sampler_2, uv, ddx, ddy); }
        case 3u: { return textureSampleGrad(slot_texture_3, slot_sampler_3, uv, ddx, ddy); }
        case 4u: { return textureSampleGrad(slot_texture_4, slot_sampler_4, uv, ddx, ddy); }
        case 5u: { return textureSampleGrad(slot_texture_5, slot_sampler_5, uv, ddx, ddy); }
        default: { return vec4<f32>(1.0); }
    }
}

// Slot i's texel at level 0 (per-vertex shading).
fn slot_texel_level0(i: u32, uv: vec2<f32>) -> vec4<f32> {
    switch i {
        case 0u: { return textureSampleLevel(slot_texture_0, slot_sampler_0, uv, 0.0); }
        case 1u: { return textureSampleLevel(slot_texture_1, slot_sampler_1, uv, 0.0); }
        case 2u: { return textureSampleLevel(slot_texture_2, slot_sampler_2, uv, 0.0); }
        case 3u: { return textureSampleLevel(slot_texture_3, slot_sampler_3, uv, 0.0); }
        case 4u: { return textureSampleLevel(slot_texture_4, slot_sampler_4, uv, 0.0); }
        case 5u: { return textureSampleLevel(slot_texture_5, slot_sampler_5, uv, 0.0); }
        default: { return vec4<f32>(1.0); }
    }
}

// The Material fields of mask `fields` multiplied by f (colour fields
// channel by channel, scalar fields by f.x). Bits: the order of
// material::texture::gpu_field_values.
fn scale_fields(base: Material, fields: u32, f: vec3<f32>) -> Material {
    var m = base;
    if (fields & 1u) != 0u { m.k_a *= f; }
    if (fields & 2u) != 0u { m.k_d *= f; }
    if (fields & 4u) != 0u { m.k_s *= f; }
    if (fields & 8u) != 0u { m.k_e *= f.x; }
    if (fields & 16u) != 0u { m.roughness *= f.x; }
    if (fields & 32u) != 0u { m.sigma_x *= f.x; }
    if (fields & 64u) != 0u { m.sigma_y *= f.x; }
    if (fields & 128u) != 0u { m.eta *= f; }
    if (fields & 256u) != 0u { m.kappa *= f; }
    if (fields & 512u) != 0u { m.eta_i *= f.x; }
    if (fields & 1024u) != 0u { m.eta_t *= f.x; }
    if (fields & 2048u) != 0u { m.d_norm *= f.x; }
    if (fields & 4096u) != 0u { m.blinn_e *= f.x; }
    if (fields & 8192u) != 0u { m.lobe *= f.x; }
    if (fields & 16384u) != 0u { m.base_color *= f; }
    if (fields & 32768u) != 0u { m.metallic *= f.x; }
    if (fields & 65536u) != 0u { m.emission *= f; }
    return m;
}

// What a texel multiplies: RGB, or one channel for a scalar parameter.
fn slot_factor(slot: TextureSlot, texel: vec4<f32>) -> vec3<f32> {
    if slot.channel < 4u {
        return vec3<f32>(texel[slot.channel]);
    }
    return texel.rgb;
}

fn slot_uv(slot: TextureSlot, uv: vec2<f32>) -> vec2<f32> {
    let p = vec3<f32>(uv, 1.0);
    return vec2<f32>(dot(slot.row_u.xyz, p), dot(slot.row_v.xyz, p));
}

// A derivative through the transform (no offset).
fn slot_duv(slot: TextureSlot, d: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(dot(slot.row_u.xy, d), dot(slot.row_v.xy, d));
}

// The material at a pixel: every slot's texel multiplies its fields.
// f64 twin: reference::texture::textured.
fn textured_material(base: Material, s: SurfaceUv) -> Material {
    var m = base;
    for (var i = 0u; i < TEXTURE_SLOTS; i++) {
        let slot = texture_slots.slots[i];
        if slot.fields == 0u {
            continue;
        }
        var uv = s.uv0;
        var ddx = s.ddx0;
        var ddy = s.ddy0;
        if slot.tex_coord == 1u {
            uv = s.uv1;
            ddx = s.ddx1;
            ddy = s.ddy1;
        }
        let texel = slot_texel(i, slot_uv(slot, uv), slot_duv(slot, ddx), slot_duv(slot, ddy));
        m = scale_fields(m, slot.fields, slot_factor(slot, texel));
    }
    return m;
}

// The material at a vertex (flat and Gouraud shading): level 0.
fn textured_material_level0(base: Material, uv0: vec2<f32>, uv1: vec2<f32>) -> Material {
    var m = base;
    for (var i = 0u; i < TEXTURE_SLOTS; i++) {
        let slot = texture_slots.slots[i];
        if slot.fields == 0u {
            continue;
        }
        let uv = select(uv0, uv1, slot.tex_coord == 1u);
        let texel = slot_texel_level0(i, slot_uv(slot, uv));
        m = scale_fields(m, slot.fields, slot_factor(slot, texel));
    }
    return m;
}
