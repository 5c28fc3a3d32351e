// gonio: shared declarations of every generated shader.
// CPU mirrors of these structs: src/gpu/layout.rs (same order, explicit padding).

const PI: f32 = 3.141592653589793;
const FRAC_1_PI: f32 = 0.3183098861837907;

// Per-frame values. `clip_from_world` is computed in f64 on the CPU.
struct Globals {
    clip_from_world: mat4x4<f32>,
    eye: vec3<f32>,
    light_count: u32,
    ambient: vec3<f32>,   // L_a: constant incoming ambient radiance
    display_scale: f32,   // 2^exposure, read only by display targets (target_output)
    env_zenith: vec3<f32>, // the environment a mirror reflects (scene::Environment)
    tone_map: u32,        // image.tone_map (ToneMap::code); display modules use the constant TONE_MAP
    env_horizon: vec3<f32>,
    roughness_floor: f32, // Scene::roughness_floor, for textured lobe widths (textures.wgsl)
    env_ground: vec3<f32>,
    _pad3: f32,
    // E(μ, α) of energy compensation at the 32 × 32 nodes of dfg::table,
    // four to a row (node k at [k / 4][k % 4]); zeros when no material
    // of the scene has energy_compensation (read only then: brdf/energy.wgsl).
    albedo: array<vec4<f32>, 256>,
}

// One material, roughness floor already applied (Material::with_roughness_floor).
// `variant` packs the material's model and Cook-Torrance terms (model in bits
// 0-7, distribution 8-11, geometry 12-15, Fresnel 16-19, denominator 20-23;
// shaders/brdf/variant.wgsl reads it when a pipeline does not fix them).
struct Material {
    k_a: vec3<f32>,
    variant: u32,
    k_d: vec3<f32>,       // albedo; Lambert f_r = k_d / π
    k_e: f32,
    k_s: vec3<f32>,
    roughness: f32,
    eta: vec3<f32>,       // conductor η + iκ
    sigma_x: f32,
    kappa: vec3<f32>,
    sigma_y: f32,
    eta_i: f32,           // dielectric
    eta_t: f32,
    d_norm: f32,          // gaussian-normalized: gaussian_normalization(roughness), from the CPU
    blinn_e: f32,         // blinn, blinn-normalized: blinn_exponent(roughness), from the CPU
    lobe: vec4<f32>,      // a model's own constants, derived on the CPU (ShaderParams::lobe): its WGSL twin says what each is
    base_color: vec3<f32>, // gltf-pbr: base colour b (textures and vertex colours multiply it per pixel)
    metallic: f32,         // gltf-pbr: metallic m (its perceptual roughness r is `roughness`)
    emission: vec3<f32>,   // emitted radiance W/(m²·sr), added to L_o (every model)
    sides: u32,            // 0: both faces, lit as the front; 1: back faces culled; 2: back faces lit with the flipped normal (material::Sides)
    alpha: f32,            // base colour alpha (textures and vertex colours multiply it per pixel)
    alpha_cutoff: f32,     // AlphaMode::cutoff: fragments of lower alpha are discarded (0: none)
    alpha_mode: u32,       // AlphaMode::code: 0 opaque, 1 mask, 2 blend (its alpha is the output's)
    occlusion: f32,        // ambient occlusion o: multiplies the ambient and environment terms, never direct light (an occlusion texture's slot scales it per pixel)
    facing_normals: u32,   // 1: the shading normal turns toward the viewer where it faces away (facing_frame in surface.wgsl; glTF materials)
    #if gltf_layers
    layers: GltfLayers,    // gltf-pbr's layers (shaders/brdf/gltf_layers/mod.wgsl), declared only where a drawn material has one
    #endif
}

// One punctual light; `kind` is LightKind::id (0 point, 1 directional,
// 2 spot, 3 area sample). The shadow_* fields describe its shadow map
// (src/gpu/shadows.rs; read only by shaders/shadows.wgsl).
struct Light {
    position: vec3<f32>,
    kind: u32,
    direction: vec3<f32>, // the way the light travels (directional, spot); an area sample's emitter normal
    range: f32,           // ≤ 0: no range
    intensity: vec3<f32>, // W/sr (point, spot), L·A/N (area sample) or irradiance W/m² (directional)
    cos_inner: f32,
    shadow_origin: vec3<f32>, // centre of the perspective / cube shadow map
    cos_outer: f32,
    shadow_layer: i32,        // first layer in the shadow-map array; < 0: no shadows
    shadow_projection: u32,   // 0 orthographic, 1 perspective, 2 cube (six layers)
    shadow_texel: f32,        // world size of a texel: orthographic, or per metre of distance
    shadow_bias: f32,         // world units
    shadow_slope_bias: f32,   // texels · tanθ
    shadow_normal_offset: f32, // texels
    shadow_pcf_radius: u32,   // (kernel − 1) / 2
    shadow_uv_scale: f32,     // map size / array side
    shadow_map: u32,          // index of its map in shadow_casters (≥ MAX_SHADOW_MAPS: none)
    shadow_array_texel: f32,  // 1 / array side: one texel in array uv (PCF steps)
    _pad1: u32,
    _pad2: u32,
    shadow_cube_offset: vec3<f32>, // cube: s × the f64 origin (rounded once), the faces' clip x/y offsets up to sign
    shadow_cube_scale: f32,        // cube: s, the faces' clip x/y scale (1 / tan of the half field of view)
}

// Light arriving at a point: ω_i towards the light, irradiance facing it.
struct Incidence {
    wi: vec3<f32>,
    irradiance: vec3<f32>,
}

@group(0) @binding(0) var<uniform> globals: Globals;
// The material of this draw: each material's triangles are one draw, bound
// at its slot of the materials buffer (a dynamic offset), so every pixel
// reads the same record (src/gpu/bindings.rs says why that matters).
@group(0) @binding(1) var<uniform> material: Material;
// Lights: a uniform buffer of a fixed capacity when they fit, a storage
// buffer otherwise (src/gpu/bindings.rs: lavapipe loads storage buffers
// lane by lane).
#if uniform_lights
@group(0) @binding(2) var<uniform> lights: array<Light, LIGHT_CAPACITY>;
#else
@group(0) @binding(2) var<storage, read> lights: array<Light>;
#endif

// normalize(v), or zero for a zero vector (normalize would give NaN). The
// CPU side uses glam's normalize_or_zero.
fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let len2 = dot(v, v);
    if len2 > 0.0 {
        return v * inverseSqrt(len2);
    }
    return vec3<f32>(0.0);
}

// What the fragment writes. Offscreen targets (Rgba32Float) hold linear
// radiance and coverage 1, read back exactly; where the adapter cannot
// render into Rgba32Float (`#if radiance_bits`), an Rgba32Uint target holds
// the same f32 values as bits, read back as the same bytes. Display targets (8-bit
// window surfaces, `#if display`) get what `gonio render` writes to a PNG:
// radiance · 2^exposure tone-mapped to [0, 1] (`tone_map`, default the
// clamp), sRGB-encoded (IEC 61966-2-1, as src/output/write.rs
// `srgb_encode`), rounded by the unorm store.
fn srgb_encode(linear: vec3<f32>) -> vec3<f32> {
    let low = 12.92 * linear;
    let high = 1.055 * pow(linear, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, linear <= vec3<f32>(0.0031308));
}

#if radiance_bits
alias TargetTexel = vec4<u32>;
#else
alias TargetTexel = vec4<f32>;
#endif

// `value` as the target stores it.
fn target_texel(value: vec4<f32>) -> TargetTexel {
    #if radiance_bits
    return bitcast<vec4<u32>>(value);
    #else
    return value;
    #endif
}

#if display
// Twin of src/output/tone_map.rs `ToneMap::apply` (its doc cites the
// formulas): 0 clamp, 1 Reinhard, 2 ACES (Narkowicz 2016), 3 Khronos PBR
// Neutral. `code` is the generated constant TONE_MAP (the scene's
// `image.tone_map`, src/gpu/shader_gen/key.rs), so the compiler keeps the
// chosen operator only; the branches inside PBR Neutral are `select`s.
fn tone_map(scaled: vec3<f32>, code: u32) -> vec3<f32> {
    let c = max(scaled, vec3<f32>(0.0));
    let reinhard = c / (1.0 + c);
    let aces = c * (2.51 * c + 0.03) / (c * (2.43 * c + 0.59) + 0.14);
    let x = min(c.r, min(c.g, c.b));
    let f = select(0.04, x - x * x / 0.16, x <= 0.08);
    let shifted = c - f;
    let p = max(shifted.r, max(shifted.g, shifted.b));
    let ks = 0.76;
    let pn = 1.0 - (1.0 - ks) * (1.0 - ks) / (p + 1.0 - 2.0 * ks);
    let g = 1.0 / (0.15 * (p - pn) + 1.0);
    let compressed = shifted * (pn / max(p, 1e-30)) * g + pn * (1.0 - g);
    let neutral = select(compressed, shifted, p <= ks);
    var out = c;
    out = select(out, reinhard, code == 1u);
    out = select(out, aces, code == 2u);
    out = select(out, neutral, code == 3u);
    return clamp(out, vec3<f32>(0.0), vec3<f32>(1.0));
}
#endif

#if alpha
// A fragment of opacity `alpha` (alpha BLEND; the pipeline blends
// SRC_ALPHA, ONE_MINUS_SRC_ALPHA over what is drawn, so the alpha channel
// becomes the coverage 1 − Π(1 − a)). Display targets blend their encoded
// values (as the Khronos sample viewer blends its sRGB output); offscreen
// targets blend linear radiance, as the reference composites.
fn target_output_alpha(radiance: vec3<f32>, alpha: f32) -> TargetTexel {
    #if display
    return vec4<f32>(srgb_encode(tone_map(radiance * globals.display_scale, TONE_MAP)), alpha);
    #else
    return target_texel(vec4<f32>(radiance, alpha));
    #endif
}
#endif

fn target_output(radiance: vec3<f32>) -> TargetTexel {
    #if display
    return vec4<f32>(srgb_encode(tone_map(radiance * globals.display_scale, TONE_MAP)), 1.0);
    #else
    return target_texel(vec4<f32>(radiance, 1.0));
    #endif
}
