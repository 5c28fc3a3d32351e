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
    _pad0: f32,
    env_zenith: vec3<f32>, // the environment a mirror reflects (scene::Environment)
    _pad1: f32,
    env_horizon: vec3<f32>,
    _pad2: f32,
    env_ground: vec3<f32>,
    _pad3: f32,
}

// One material, roughness floor already applied (Material::with_roughness_floor).
// `variant` indexes the scene's BRDF variants (the generated `eval_brdf` switch).
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
    _pad0: f32,
}

// One punctual light; `kind` is LIGHT_* (src/gpu/layout.rs).
struct Light {
    position: vec3<f32>,
    kind: u32,
    direction: vec3<f32>, // the way the light travels (directional, spot)
    range: f32,           // ≤ 0: no range
    intensity: vec3<f32>, // W/sr (point, spot) or irradiance W/m² (directional)
    cos_inner: f32,
    cos_outer: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

// Light arriving at a point: ω_i towards the light, irradiance facing it.
struct Incidence {
    wi: vec3<f32>,
    irradiance: vec3<f32>,
}

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var<storage, read> materials: array<Material>;
@group(0) @binding(2) var<storage, read> lights: array<Light>;

// normalize(v), or zero for a zero vector (normalize would give NaN). The
// CPU side uses glam's normalize_or_zero.
fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let len2 = dot(v, v);
    if len2 > 0.0 {
        return v * inverseSqrt(len2);
    }
    return vec3<f32>(0.0);
}
