// Material textures (bind group 2), in the module only when the scene has
// textures (feature `textures`): the lecture's spatially varying BRDF.
// Each material has up to TEXTURE_BINDINGS reads and MAX_TEXTURE_SLOTS
// slots. A read is one texture as glTF counts it: an image (a full
// mip-chain view, or level 0 alone for a sampler without mipmaps) with its
// sampler, UV set and KHR_texture_transform, sampled once per pixel. A
// slot takes one read's texel and says which Material fields it scales,
// from which channel (a metallic-roughness texture is one read taken by
// two slots). f64 twin: src/reference/texture.rs (the sampler's filtering
// is the GPU's own; the twin reproduces Vulkan's rules). CPU side:
// src/gpu/textures/.

// One slot. CPU mirror: GpuTextureSlot.
struct TextureSlot {
    fields: u32,       // bit mask of the Material fields it scales (material::texture::gpu_field_values order); 0: unused
    channel: u32,      // 4: RGB (a colour parameter); 0-3: the channel a scalar parameter reads; 5: a normal map; 6: the coat's normal map; 7: the anisotropy map
    strength: f32,     // 1; occlusion: glTF's strength; normal map: glTF's scale
    alpha: u32,        // 1: the texel's A multiplies Material.alpha (the base colour's texture)
    texture: u32,      // the read whose texel it takes (TextureSlots.reads, binding slot_texture_<texture>)
    _pad: u32,
    rotation: vec2<f32>, // (cos r, sin r) of its read's KHR_texture_transform rotation: turns a normal map's normal
}

// One read. CPU mirror: GpuTextureRead.
struct TextureRead {
    row_u: vec4<f32>,  // u' = dot(row_u.xyz, (u, v, 1)): KHR_texture_transform, first row
    row_v: vec4<f32>,  // v' = dot(row_v.xyz, (u, v, 1))
    tex_coord: u32,    // UV set (TEXCOORD_n)
}

struct TextureSlots {
    slots: array<TextureSlot, MAX_TEXTURE_SLOTS>,
    reads: array<TextureRead, MAX_TEXTURE_SLOTS>,
}

@group(2) @binding(0) var<uniform> texture_slots: TextureSlots;
// Then TEXTURE_BINDINGS textures slot_texture_<i> (binding 1 + 2i) and
// samplers slot_sampler_<i> (binding 2 + 2i), read i's image and sampler,
// as many as the scene's most textured material reads, and the functions
// below, generated (src/gpu/textures/wgsl.rs, `wgsl_bindings`) since WGSL
// cannot index separate bindings and the count is the scene's:
//
// struct ReadTexels { t0: vec4<f32>, t1: vec4<f32>, … }: every read's texel.
// read_texels(s: SurfaceUv, zero: u32) -> ReadTexels: each binding sampled once, at
//   its read's UV with the footprint (read_footprint). Explicit gradients:
//   the level of detail is the one the reference computes from the same
//   derivatives (reference::texture::sample), and sampling is allowed
//   outside uniform control flow. `zero`: unseen_zero, added to the
//   indices into texture_slots.
// read_texels_level0(uv0, uv1, zero) -> ReadTexels: the same at level 0
//   (per-vertex shading).
// read_texel(t: ReadTexels, i: u32) -> vec4<f32>: read i's texel, by
//   selects. One sample per binding, not one per slot through a `switch`:
//   lavapipe runs every case of a switch whose value it cannot see, so a
//   switch per slot sampled every binding for every slot (35 samples for
//   DamagedHelmet's 7 slots and 5 bindings; 2026-12-05 the frame at 1080p
//   went from 236 to 110 ms without it).

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

// The Material fields of mask `fields` multiplied by f (colour fields
// channel by channel, scalar fields by f.x). Bits: the order of
// material::texture::gpu_field_values. Selects, not branches: the mask
// is a uniform (UNIFORM_BRANCHES in shaders/brdf/phong.wgsl).
fn scale_fields(base: Material, fields: u32, f: vec3<f32>) -> Material {
    var m = base;
    let one = vec3<f32>(1.0);
    m.k_a *= select(one, f, (fields & 1u) != 0u);
    m.k_d *= select(one, f, (fields & 2u) != 0u);
    m.k_s *= select(one, f, (fields & 4u) != 0u);
    m.k_e *= select(1.0, f.x, (fields & 8u) != 0u);
    m.roughness *= select(1.0, f.x, (fields & 16u) != 0u);
    m.sigma_x *= select(1.0, f.x, (fields & 32u) != 0u);
    m.sigma_y *= select(1.0, f.x, (fields & 64u) != 0u);
    m.eta *= select(one, f, (fields & 128u) != 0u);
    m.kappa *= select(one, f, (fields & 256u) != 0u);
    m.eta_i *= select(1.0, f.x, (fields & 512u) != 0u);
    m.eta_t *= select(1.0, f.x, (fields & 1024u) != 0u);
    m.d_norm *= select(1.0, f.x, (fields & 2048u) != 0u);
    m.blinn_e *= select(1.0, f.x, (fields & 4096u) != 0u);
    m.lobe *= select(1.0, f.x, (fields & 8192u) != 0u);
    m.base_color *= select(one, f, (fields & 16384u) != 0u);
    m.metallic *= select(1.0, f.x, (fields & 32768u) != 0u);
    m.emission *= select(one, f, (fields & 65536u) != 0u);
    m.occlusion *= select(1.0, f.x, (fields & 131072u) != 0u);
    #if gltf_layers
    // gltf-pbr's layers: bits 18-28 and 30-31 (29, the anisotropy
    // direction, is never set: a texture on the rotation is refused on
    // the CPU).
    m.layers.ior *= select(1.0, f.x, (fields & (1u << 18u)) != 0u);
    m.layers.specular *= select(1.0, f.x, (fields & (1u << 19u)) != 0u);
    m.layers.specular_color *= select(one, f, (fields & (1u << 20u)) != 0u);
    m.layers.clearcoat *= select(1.0, f.x, (fields & (1u << 21u)) != 0u);
    m.layers.clearcoat_roughness *= select(1.0, f.x, (fields & (1u << 22u)) != 0u);
    m.layers.sheen_color *= select(one, f, (fields & (1u << 23u)) != 0u);
    m.layers.sheen_roughness *= select(1.0, f.x, (fields & (1u << 24u)) != 0u);
    m.layers.iridescence *= select(1.0, f.x, (fields & (1u << 25u)) != 0u);
    m.layers.iridescence_ior *= select(1.0, f.x, (fields & (1u << 26u)) != 0u);
    m.layers.iridescence_thickness *= select(1.0, f.x, (fields & (1u << 27u)) != 0u);
    m.layers.anisotropy_strength *= select(1.0, f.x, (fields & (1u << 28u)) != 0u);
    // Light through surfaces: bits 30 and 31.
    m.layers.transmission *= select(1.0, f.x, (fields & (1u << 30u)) != 0u);
    m.layers.thickness *= select(1.0, f.x, (fields & (1u << 31u)) != 0u);
    // The diffuse transmission's share and colour share Ward's bits 5 and
    // 6 (texture_fields::SHARED_BITS: no model has parameters on both).
    m.layers.diffuse_transmission *= select(1.0, f.x, (fields & 32u) != 0u);
    m.layers.diffuse_transmission_color *= select(one, f, (fields & 64u) != 0u);
    #endif
    return m;
}

// What a texel multiplies: RGB, or one channel for a scalar parameter,
// with the slot's strength: 1 + s·(v − 1), exactly v at s = 1. Twin:
// TextureTarget::with_strength.
fn slot_factor(slot: TextureSlot, texel: vec4<f32>) -> vec3<f32> {
    let v = select(vec3<f32>(texel[min(slot.channel, 3u)]), texel.rgb, slot.channel >= 4u);
    return select(1.0 + slot.strength * (v - 1.0), v, slot.strength == 1.0);
}

// glTF's normal-texture decoding: normalize((2·rgb − 1) ⊙ (s, s, 1)),
// (0, 0, 1) for a zero vector. Twin: material::texture::decode_normal.
fn decoded_normal(texel: vec4<f32>, scale: f32) -> vec3<f32> {
    let n = (2.0 * texel.rgb - 1.0) * vec3<f32>(scale, scale, 1.0);
    let len2 = dot(n, n);
    return select(vec3<f32>(0.0, 0.0, 1.0), n * inverseSqrt(len2), len2 > 0.0);
}

// A normal map's normal in the mesh's tangent frame when the map is read
// through a rotation (cos r, sin r) = cs: (n_x, n_y) turned by the
// contract's R = [[cos r, sin r], [−sin r, cos r]]. Exact at r = 0
// (cs = (1, 0)). Twin: material::texture::rotated_normal.
fn rotated_normal(n: vec3<f32>, cs: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(cs.x * n.x + cs.y * n.y, -cs.y * n.x + cs.x * n.y, n.z);
}

fn read_uv(read: TextureRead, uv: vec2<f32>) -> vec2<f32> {
    let p = vec3<f32>(uv, 1.0);
    return vec2<f32>(dot(read.row_u.xyz, p), dot(read.row_v.xyz, p));
}

// A derivative through the transform (no offset).
fn read_duv(read: TextureRead, d: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(dot(read.row_u.xy, d), dot(read.row_v.xy, d));
}

// Where read `read` samples at a pixel: its UV set through its transform,
// and that UV's screen derivatives.
struct Footprint {
    uv: vec2<f32>,
    ddx: vec2<f32>,
    ddy: vec2<f32>,
}

fn read_footprint(read: TextureRead, s: SurfaceUv) -> Footprint {
    let second = read.tex_coord == 1u;
    let uv = select(s.uv0, s.uv1, second);
    let ddx = select(s.ddx0, s.ddx1, second);
    let ddy = select(s.ddy0, s.ddy1, second);
    return Footprint(read_uv(read, uv), read_duv(read, ddx), read_duv(read, ddy));
}

// Where read `read` samples at a vertex.
fn read_uv_level0(read: TextureRead, uv0: vec2<f32>, uv1: vec2<f32>) -> vec2<f32> {
    return read_uv(read, select(uv0, uv1, read.tex_coord == 1u));
}

// The material at a point, and its normal map's tangent-space normal
// ((0, 0, 1) without one); with the coat compiled, the coat's normal map's
// ((0, 0, 0) without one). f64 twin: reference::texture::Textured.
struct TexturedSurface {
    material: Material,
    normal: vec3<f32>,
    #if layer_clearcoat
    clearcoat_normal: vec3<f32>,
    #endif
}

#if layer_anisotropy
// KHR_materials_anisotropy's texture: the direction d = 2·rg − 1, turned
// by the slot's rotation cs as a normal map's normal is, normalized
// ((1, 0) for a zero d), multiplies (cos ρ, sin ρ) as a complex number
// (the angles add); B multiplies the strength. Twin:
// material::texture::decode_anisotropy (which adds the angles).
fn anisotropy_texel(layers: GltfLayers, texel: vec4<f32>, cs: vec2<f32>) -> GltfLayers {
    var out = layers;
    let d = rotated_normal(vec3<f32>(2.0 * texel.rg - 1.0, 0.0), cs).xy;
    let len2 = dot(d, d);
    let u = select(vec2<f32>(1.0, 0.0), d * inverseSqrt(len2), len2 > 0.0);
    let r = layers.anisotropy_direction;
    out.anisotropy_direction = vec2<f32>(r.x * u.x - r.y * u.y, r.x * u.y + r.y * u.x);
    out.anisotropy_strength *= texel.b;
    return out;
}
#endif

// One slot's texel applied: its fields scaled (none for a normal map,
// whose fields are 0), or its normal taken (channel 5); the base colour's
// A on the alpha (twin: reference::texture::alpha). Unused slots
// (fields 0, channel 0, alpha 0) change nothing, whatever texel they take.
fn apply_slot(s: TexturedSurface, slot: TextureSlot, texel: vec4<f32>) -> TexturedSurface {
    var out = s;
    out.material = scale_fields(s.material, slot.fields, slot_factor(slot, texel));
    out.material.alpha *= select(1.0, texel.a, slot.alpha != 0u);
    let n = rotated_normal(decoded_normal(texel, slot.strength), slot.rotation);
    out.normal = select(s.normal, n, slot.channel == 5u);
    #if layer_clearcoat
    out.clearcoat_normal = select(s.clearcoat_normal, n, slot.channel == 6u);
    #endif
    #if layer_anisotropy
    let turned = anisotropy_texel(out.material.layers, texel, slot.rotation);
    let anisotropy = slot.channel == 7u;
    out.material.layers.anisotropy_direction = select(out.material.layers.anisotropy_direction, turned.anisotropy_direction, anisotropy);
    out.material.layers.anisotropy_strength = select(out.material.layers.anisotropy_strength, turned.anisotropy_strength, anisotropy);
    #endif
    return out;
}

// material::ROUGHNESS_FLOOR.
const ROUGHNESS_FLOOR: f32 = 1e-4;

// The pixel footprint's roughness floor (globals.roughness_floor) on the
// lobe widths a texture multiplied, after texturing: widened first, a
// texel of 0 would take the floor away. The other widths had it on the
// CPU. f64 twin: Material::with_textured_widths_floored (the gltf-pbr
// roughness is perceptual: its α = r² is widened).
// `fields`: the slots' field masks ORed (what the textures multiplied).
fn textured_widths_floored(base: Material, fields: u32) -> Material {
    let f2 = globals.roughness_floor * globals.roughness_floor;
    var m = base;
    let pbr = brdf_model(m) == MODEL_GLTF_PBR;
    let a = select(m.roughness, m.roughness * m.roughness, pbr);
    let a_floored = max(sqrt(a * a + f2), ROUGHNESS_FLOOR);
    let r_floored = select(a_floored, sqrt(a_floored), pbr);
    m.roughness = select(m.roughness, r_floored, (fields & 16u) != 0u);
    m.sigma_x = select(m.sigma_x, max(sqrt(m.sigma_x * m.sigma_x + f2), ROUGHNESS_FLOOR), (fields & 32u) != 0u);
    m.sigma_y = select(m.sigma_y, max(sqrt(m.sigma_y * m.sigma_y + f2), ROUGHNESS_FLOOR), (fields & 64u) != 0u);
    return m;
}

// 0, from a value the compiler cannot see through (no UV is past 1e30),
// added to every index into texture_slots: its loads are then not at
// constant offsets. lavapipe 22.3 (Debian 12) recompiles a shader with
// the values of uniforms loaded at constant offsets that decide a branch
// ("inlining"), and its queue thread crashed doing so for this buffer (a
// segfault in its inline-uniform update, reading a constant buffer at a
// negative index): seen with the coat's normal map once each binding was
// sampled once (tests/layers_gpu.rs, 2026-12-05); with a single binding
// the same scene aborted it ("stack smashing detected").
fn unseen_zero(uv: vec2<f32>) -> u32 {
    return u32(uv.x > 1e30);
}

// The material at a pixel: every slot's texel applied.
// f64 twin: reference::texture::textured.
fn textured_surface(base: Material, s: SurfaceUv) -> TexturedSurface {
    #if layer_clearcoat
    var out = TexturedSurface(base, vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0));
    #else
    var out = TexturedSurface(base, vec3<f32>(0.0, 0.0, 1.0));
    #endif
    let zero = unseen_zero(s.uv0);
    let texels = read_texels(s, zero);
    var fields = 0u;
    for (var i = 0u; i < TEXTURE_SLOTS; i++) {
        let slot = texture_slots.slots[i + zero];
        fields |= slot.fields;
        out = apply_slot(out, slot, read_texel(texels, slot.texture));
    }
    out.material = textured_widths_floored(out.material, fields);
    return out;
}

// The material at a vertex (flat and Gouraud shading): level 0.
fn textured_surface_level0(base: Material, uv0: vec2<f32>, uv1: vec2<f32>) -> TexturedSurface {
    #if layer_clearcoat
    var out = TexturedSurface(base, vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0));
    #else
    var out = TexturedSurface(base, vec3<f32>(0.0, 0.0, 1.0));
    #endif
    let zero = unseen_zero(uv0);
    let texels = read_texels_level0(uv0, uv1, zero);
    var fields = 0u;
    for (var i = 0u; i < TEXTURE_SLOTS; i++) {
        let slot = texture_slots.slots[i + zero];
        fields |= slot.fields;
        out = apply_slot(out, slot, read_texel(texels, slot.texture));
    }
    out.material = textured_widths_floored(out.material, fields);
    return out;
}

#if normal_map
// The shading frame with a tangent-space normal n_t applied:
// n' = normalize(n_t.x·T + n_t.y·B + n_t.z·N), B = sign·N×T, then the
// frame rebuilt around n' with the same tangent. Twin:
// reference::texture::normal_mapped_frame.
fn normal_mapped_frame(frame: SurfaceFrame, sign: f32, n_t: vec3<f32>) -> SurfaceFrame {
    let b = sign * cross(frame.n, frame.t);
    let n = normalize_or_zero(frame.t * n_t.x + b * n_t.y + frame.n * n_t.z);
    return surface_frame(n, frame.t);
}

#if layer_clearcoat
// The coat's normal map applied: n_c from n_t in the mesh's frame
// vertex_frame (before the base's normal map), written in the coordinates
// of the shading frame `shading` (GltfLayers.clearcoat_normal); `keep`
// (the material's, (0, 0, 1)) where the material has no coat normal map
// (n_t = 0). Twin: reference::texture::clearcoat_normal_coords.
fn clearcoat_normal_coords(vertex_frame: SurfaceFrame, sign: f32, n_t: vec3<f32>, shading: SurfaceFrame, keep: vec3<f32>) -> vec3<f32> {
    if all(n_t == vec3<f32>(0.0)) {
        return keep;
    }
    let n_c = normal_mapped_frame(vertex_frame, sign, n_t).n;
    return vec3<f32>(dot(n_c, shading.t), dot(n_c, shading.b), dot(n_c, shading.n));
}
#endif
#endif
