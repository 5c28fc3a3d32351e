// The environment map (group 3; only in shaders of scenes with
// `[environment] map`, feature `environment`). CPU twins: the lat-long
// convention src/environment/latlong.rs, the lookup MapData::lookup
// (src/environment/map.rs), the SH basis and sum src/environment/sh.rs.
// CPU mirror of the struct: GpuEnvironmentUniform (src/gpu/environment.rs).

struct EnvironmentUniform {
    // The camera's ray basis, as Camera::ray builds it: a pixel at
    // normalized device coordinates (x, y) looks along
    // normalize(forward + right·x + up·y) (the background pass).
    forward: vec3<f32>,
    scale: f32,            // environment.scale
    right: vec3<f32>,      // camera right · tan(fov_y/2) · aspect
    width: u32,            // the map's texels
    up: vec3<f32>,         // camera up · tan(fov_y/2)
    height: u32,
    // scale · Â_l · L_lm (rgb), bands 0-4, zero above environment.sh_order:
    // E(n) = Σ sh[i] · Y_i(n) (EnvironmentMap::irradiance_coefficients).
    sh: array<vec4<f32>, 25>,
    // (cos θ, sin θ) of environment.rotation_deg.
    rotation: vec2<f32>,
    samples: u32,          // environment.samples (sampled mode)
    prefilter_width: u32,  // a level's width (prefiltered mode; height half)
    // scale · L_lm (rgb), zero above environment.sh_order: the "sh" mode's
    // Phong convolution (shaders/environment_sh.wgsl).
    sh_radiance: array<vec4<f32>, 25>,
}

@group(3) @binding(0) var<uniform> environment: EnvironmentUniform;
// Linear radiance, Rgba32Float (not filterable: the bilinear filter is
// done here, as on the CPU, on the same f32 texels).
@group(3) @binding(1) var environment_texels: texture_2d<f32>;

// (u, v) of unit direction d: u = atan2(d.x, −d.z)/(2π) wrapped into
// [0, 1), v = acos(d.y)/π (the contract's convention). Twin: latlong::uv.
fn latlong_uv(d: vec3<f32>) -> vec2<f32> {
    var u = atan2(d.x, -d.z) / (2.0 * PI);
    if u < 0.0 {
        u += 1.0;
    }
    if u >= 1.0 {
        u -= 1.0;
    }
    return vec2<f32>(u, acos(clamp(d.y, -1.0, 1.0)) / PI);
}

fn environment_texel(col: i32, row: i32) -> vec3<f32> {
    return textureLoad(environment_texels, vec2<i32>(col, row), 0).rgb;
}

// The four texels around (u, v) on a W × H lat-long grid and their
// bilinear weights: texel centres at ((col + ½)/W, (row + ½)/H), u
// wraps, v clamps. Twin: the index arithmetic of MapData::lookup and of
// bilinear in src/environment/prefiltered.rs.
struct LatLongTexels {
    c0: i32,
    c1: i32,
    r0: i32,
    r1: i32,
    fx: f32,
    fy: f32,
}

fn latlong_texels(uv: vec2<f32>, w: i32, h: i32) -> LatLongTexels {
    let x = uv.x * f32(w) - 0.5;
    let y = uv.y * f32(h) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    // u is in [0, 1), so x0 is in [−1, w − 1]: the wrap is a select, not
    // the remainder rem_euclid takes on the CPU. An integer % is scalar on
    // lavapipe (no vector division), and four of them per lookup cost
    // about 9 ms of a 1080p frame under a map (2026-12-06). The clamp only
    // keeps a NaN direction's texels in bounds.
    let c = clamp(i32(x0), -1, w - 1);
    return LatLongTexels(
        select(c, w - 1, c < 0),
        select(c + 1, 0, c + 1 >= w),
        clamp(i32(y0), 0, h - 1),
        clamp(i32(y0) + 1, 0, h - 1),
        x - x0,
        y - y0,
    );
}

// Bilinear lookup of d. Twin: MapData::lookup.
fn environment_lookup(d: vec3<f32>) -> vec3<f32> {
    let q = latlong_texels(latlong_uv(d), i32(environment.width), i32(environment.height));
    let top = environment_texel(q.c0, q.r0) * (1.0 - q.fx) + environment_texel(q.c1, q.r0) * q.fx;
    let bottom = environment_texel(q.c0, q.r1) * (1.0 - q.fx) + environment_texel(q.c1, q.r1) * q.fx;
    return top * (1.0 - q.fy) + bottom * q.fy;
}

// The direction in the file's frame of world direction d: R_y(−θ) d.
// Twin: EnvironmentMap::to_map.
fn environment_to_map(d: vec3<f32>) -> vec3<f32> {
    let c = environment.rotation.x;
    let s = environment.rotation.y;
    return vec3<f32>(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// scale · L_env(d). Twin: EnvironmentMap::radiance.
fn environment_map_radiance(d: vec3<f32>) -> vec3<f32> {
    return environment.scale * environment_lookup(environment_to_map(d));
}

// The 25 real SH of bands 0-4 at d in the order and form of sh::basis
// (Sloan 2008): polynomials in (x, y, z), also off the unit sphere
// (environment_sh.wgsl differentiates them). Twin: sh::basis.
fn sh_basis(d: vec3<f32>) -> array<f32, 25> {
    let x = d.x;
    let y = d.y;
    let z = d.z;
    let x2 = x * x;
    let y2 = y * y;
    let z2 = z * z;
    var b: array<f32, 25>;
    b[0] = 0.2820947917738781;
    b[1] = 0.4886025119029199 * y;
    b[2] = 0.4886025119029199 * z;
    b[3] = 0.4886025119029199 * x;
    b[4] = 1.092548430592079 * x * y;
    b[5] = 1.092548430592079 * y * z;
    b[6] = 0.31539156525252005 * (3.0 * z2 - 1.0);
    b[7] = 1.092548430592079 * x * z;
    b[8] = 0.5462742152960395 * (x2 - y2);
    b[9] = 0.5900435899266435 * y * (3.0 * x2 - y2);
    b[10] = 2.890611442640554 * x * y * z;
    b[11] = 0.4570457994644658 * y * (5.0 * z2 - 1.0);
    b[12] = 0.3731763325901154 * z * (5.0 * z2 - 3.0);
    b[13] = 0.4570457994644658 * x * (5.0 * z2 - 1.0);
    b[14] = 1.445305721320277 * z * (x2 - y2);
    b[15] = 0.5900435899266435 * x * (x2 - 3.0 * y2);
    b[16] = 2.503342941796705 * x * y * (x2 - y2);
    b[17] = 1.770130769779931 * y * z * (3.0 * x2 - y2);
    b[18] = 0.946174695757560 * x * y * (7.0 * z2 - 1.0);
    b[19] = 0.669046543557289 * y * z * (7.0 * z2 - 3.0);
    b[20] = 0.105785546915204 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);
    b[21] = 0.669046543557289 * x * z * (7.0 * z2 - 3.0);
    b[22] = 0.473087347878780 * (x2 - y2) * (7.0 * z2 - 1.0);
    b[23] = 1.770130769779931 * x * z * (x2 - 3.0 * y2);
    b[24] = 0.625835735449176 * (x2 * x2 - 6.0 * x2 * y2 + y2 * y2);
    return b;
}

// E(n) = max(Σ_i sh[i] · Y_i(n), 0) at the normal in the file's frame
// (the expansion rings negative opposite a sun; the truth never is).
// Twin: EnvironmentMap::irradiance_sh.
fn sh_irradiance(world_n: vec3<f32>) -> vec3<f32> {
    return max(sh_sum(environment.sh, sh_basis(environment_to_map(world_n))), vec3<f32>(0.0));
}

// Σ_i c_i · b_i over the 25 coefficients, in index order. Written out, not
// a loop: lavapipe keeps a function-local array indexed by a loop counter
// in memory, lane by lane, and such a loop here took about 40 % of a
// textured frame (DamagedHelmet at 1080p, 2026-12-05: 438 → 244 ms);
// indexed by constants the array stays in registers. Twin: sh::evaluate.
fn sh_sum(c: array<vec4<f32>, 25>, b: array<f32, 25>) -> vec3<f32> {
    return c[0].rgb * b[0] +
        c[1].rgb * b[1] +
        c[2].rgb * b[2] +
        c[3].rgb * b[3] +
        c[4].rgb * b[4] +
        c[5].rgb * b[5] +
        c[6].rgb * b[6] +
        c[7].rgb * b[7] +
        c[8].rgb * b[8] +
        c[9].rgb * b[9] +
        c[10].rgb * b[10] +
        c[11].rgb * b[11] +
        c[12].rgb * b[12] +
        c[13].rgb * b[13] +
        c[14].rgb * b[14] +
        c[15].rgb * b[15] +
        c[16].rgb * b[16] +
        c[17].rgb * b[17] +
        c[18].rgb * b[18] +
        c[19].rgb * b[19] +
        c[20].rgb * b[20] +
        c[21].rgb * b[21] +
        c[22].rgb * b[22] +
        c[23].rgb * b[23] +
        c[24].rgb * b[24];
}

#if environment_prefiltered
// Glossy reflection by the split-sum approximation (Karis 2013):
// L̃(R, α) · (F0·A(μ, α) + B(μ, α)), the map prefiltered by GGX lobes
// (LEVELS lat-long levels stacked in one texture, level k at √α = k/5)
// and the environment BRDF table. Twins: src/environment/prefiltered.rs
// and src/material/brdf/dfg.rs (tables made there, on the CPU).

// prefiltered::LEVELS
const PREFILTER_LEVELS: i32 = 6;
// dfg::SIZE
const DFG_SIZE: i32 = 32;

// Levels stacked by rows, Rgba32Float (filtered here, as on the CPU).
@group(3) @binding(2) var environment_prefiltered_texels: texture_2d<f32>;
// [A, B] at nodes (√μ, √α) = (i, j)/(DFG_SIZE − 1), in .xy.
@group(3) @binding(3) var environment_dfg_table: texture_2d<f32>;

// Bilinear lookup in level k at the texels q (the levels share one grid:
// the rows of level k start at k·h). Twin: Prefiltered::level_lookup.
// (`prefiltered_zonal_level_lookup` is the same on the sheen stack: a
// texture passed as an argument is not portable to every backend.)
fn prefiltered_level_lookup(q: LatLongTexels, k: i32) -> vec3<f32> {
    let base = k * (i32(environment.prefilter_width) / 2);
    let t = environment_prefiltered_texels;
    let top = textureLoad(t, vec2<i32>(q.c0, base + q.r0), 0).rgb * (1.0 - q.fx) + textureLoad(t, vec2<i32>(q.c1, base + q.r0), 0).rgb * q.fx;
    let bottom = textureLoad(t, vec2<i32>(q.c0, base + q.r1), 0).rgb * (1.0 - q.fx) + textureLoad(t, vec2<i32>(q.c1, base + q.r1), 0).rgb * q.fx;
    return top * (1.0 - q.fy) + bottom * q.fy;
}

// The two levels around √α, k and k + 1, and the weight t of the upper
// one. Twin: prefiltered::level_blend.
struct StackLevels {
    k: i32,
    t: f32,
}

fn stack_levels(alpha: f32) -> StackLevels {
    let f = sqrt(clamp(alpha, 0.0, 1.0)) * f32(PREFILTER_LEVELS - 1);
    let k = min(floor(f), f32(PREFILTER_LEVELS - 2));
    return StackLevels(i32(k), f - k);
}

// L̃(d, α) (d in the file's frame), linear between the levels around √α;
// d's texels found once for both levels. Twin: Prefiltered::lookup.
fn prefiltered_lookup(d: vec3<f32>, alpha: f32) -> vec3<f32> {
    let b = stack_levels(alpha);
    let w = i32(environment.prefilter_width);
    let q = latlong_texels(latlong_uv(d), w, w / 2);
    return prefiltered_level_lookup(q, b.k) * (1.0 - b.t) + prefiltered_level_lookup(q, b.k + 1) * b.t;
}

#if layer_sheen
// The sheen stack (scene::sheen_stack: the map averaged by the Charlie
// lobe seen along the normal, environment::prefiltered_zonal), levels of
// ZONAL_WIDTH × ZONAL_WIDTH/2 texels stacked by rows, Rgba32Float.
@group(3) @binding(5) var environment_sheen_texels: texture_2d<f32>;
// prefiltered_zonal::ZONAL_WIDTH
const ZONAL_WIDTH: i32 = 64;

// Bilinear lookup in level k of the sheen stack. Twin:
// ZonalStack::level_lookup.
fn prefiltered_zonal_level_lookup(q: LatLongTexels, k: i32) -> vec3<f32> {
    let base = k * (ZONAL_WIDTH / 2);
    let t = environment_sheen_texels;
    let top = textureLoad(t, vec2<i32>(q.c0, base + q.r0), 0).rgb * (1.0 - q.fx) + textureLoad(t, vec2<i32>(q.c1, base + q.r0), 0).rgb * q.fx;
    let bottom = textureLoad(t, vec2<i32>(q.c0, base + q.r1), 0).rgb * (1.0 - q.fx) + textureLoad(t, vec2<i32>(q.c1, base + q.r1), 0).rgb * q.fx;
    return top * (1.0 - q.fy) + bottom * q.fy;
}

// L̃_sh(d, α) (d in the file's frame), linear between the levels around
// √α. Twin: ZonalStack::lookup.
fn prefiltered_zonal_lookup(d: vec3<f32>, alpha: f32) -> vec3<f32> {
    let b = stack_levels(alpha);
    let q = latlong_texels(latlong_uv(d), ZONAL_WIDTH, ZONAL_WIDTH / 2);
    return prefiltered_zonal_level_lookup(q, b.k) * (1.0 - b.t) + prefiltered_zonal_level_lookup(q, b.k + 1) * b.t;
}
#endif

// The direction L̃ is read in: normalize(mix(n, r, s (√s + α))),
// s = 1 − α, the lobe's dominant direction (Lagarde & de Rousiers 2014,
// §4.9.3). Twin: dominant::dominant_direction.
fn prefiltered_direction(r: vec3<f32>, n: vec3<f32>, alpha: f32) -> vec3<f32> {
    let s = clamp(1.0 - alpha, 0.0, 1.0);
    let w = s * (sqrt(s) + alpha);
    let d = n * (1.0 - w) + r * w;
    let len2 = dot(d, d);
    return select(n, d * inverseSqrt(max(len2, 1e-30)), len2 > 0.0);
}

// [A, B] at (μ, α), bilinear in (√μ, √α) between the nodes. Twin:
// DfgTable::lookup.
fn environment_dfg(mu: f32, alpha: f32) -> vec2<f32> {
    let last = f32(DFG_SIZE - 1);
    let x = sqrt(clamp(mu, 0.0, 1.0)) * last;
    let y = sqrt(clamp(alpha, 0.0, 1.0)) * last;
    let x0 = min(floor(x), last - 1.0);
    let y0 = min(floor(y), last - 1.0);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let t = environment_dfg_table;
    let lo = textureLoad(t, vec2<i32>(i, j), 0).xy * (1.0 - fx) + textureLoad(t, vec2<i32>(i + 1, j), 0).xy * fx;
    let hi = textureLoad(t, vec2<i32>(i, j + 1), 0).xy * (1.0 - fx) + textureLoad(t, vec2<i32>(i + 1, j + 1), 0).xy * fx;
    return lo * (1.0 - fy) + hi * fy;
}

struct PrefilteredTerms {
    alpha: f32,
    f0: vec3<f32>,
    weight: vec3<f32>,
}

// (α, F0, weight) of the split for m: Cook-Torrance as GGX of a matched α (prefiltered::ggx_alpha),
// F0 = F(1), weight
// k_s·4/c; 0 for the other models. Selects (UNIFORM_BRANCHES in
// brdf/phong.wgsl). Twin: prefiltered::specular_terms.
fn prefiltered_terms(m: Material) -> PrefilteredTerms {
    let model = brdf_model(m);
    var t = PrefilteredTerms(0.0, vec3<f32>(0.0), vec3<f32>(0.0));
    #if cook-torrance
    let ct = model == MODEL_COOK_TORRANCE;
    // Blinn's exponent as a Beckmann slope √(2/(e + 2)) (blinn_e is 0
    // for the other distributions, whose roughness is their m or α).
    let ct_alpha = select(m.roughness, sqrt(2.0 / (m.blinn_e + 2.0)), m.blinn_e > 0.0);
    t.alpha = select(t.alpha, ct_alpha, ct);
    t.f0 = select(t.f0, fresnel(m, 1.0), ct);
    t.weight = select(t.weight, m.k_s * (4.0 / denominator(m)), ct);
    #endif
    return t;
}

#if gltf-pbr
#if layer_anisotropy
// The normal the base lobe's L̃ is read about: Filament's bent normal,
// towards (B × V) × B by 1 − (1 − s_a (1 − r))⁴, B the less rough
// direction; n without anisotropy (a select: UNIFORM_BRANCHES in
// brdf/phong.wgsl). Twin: prefiltered_layers::bent_normal.
fn prefiltered_bent_normal(m: Material, frame: SurfaceFrame, wo: vec3<f32>) -> vec3<f32> {
    let l = m.layers;
    let af = anisotropy_frame(l.anisotropy_direction, frame.n, frame.t, frame.b);
    let grain = cross(cross(af.b, wo), af.b);
    let bend = 1.0 - l.anisotropy_strength * (1.0 - m.roughness);
    let bend4 = (bend * bend) * (bend * bend);
    let bent = grain * (1.0 - bend4) + frame.n * bend4;
    let len2 = dot(bent, bent);
    let usable = l.anisotropy_strength > 0.0 && len2 > 0.0;
    return select(frame.n, bent * inverseSqrt(max(len2, 1e-30)), usable);
}
#endif

// gltf-pbr and its layers by the split sum, for μ_o = n·wo > 0: the
// dielectric's s_w (f0·A + B) and the metal's b·A + B, each mixed with the
// thin film's F_ir (A + B); the diffuse term weighted by
// 1 − max₃ of the dielectric's; the sheen's albedo E(μ_o) times the sheen
// stack read at n over σ_o times the rest; the coat's k F_c L̃(R_c, α_c)
// (A + B) over (1 − k F_c) times the rest. Layers absent from the scene
// are not compiled; present ones are selects (UNIFORM_BRANCHES).
// Twin: prefiltered_layers::estimate.
fn environment_prefiltered_gltf(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let n = frame.n;
    let cos_o = dot(n, wo);
    let b = m.base_color;
    let metallic = m.metallic;
    let alpha = m.roughness * m.roughness;
    let ab = environment_dfg(cos_o, alpha);
    let lobe_albedo = ab.x + ab.y;
    var s_w = 1.0;
    var f0 = vec3<f32>(0.04);
    #if layer_ior_specular
    s_w = m.layers.specular;
    f0 = dielectric_f0(m.layers.ior, m.layers.specular_color) * s_w;
    #endif
    var dielectric = f0 * ab.x + s_w * ab.y;
    var metal = b * ab.x + ab.y;
    #if layer_iridescence
    let film = m.layers.iridescence > 0.0 && m.layers.iridescence_thickness > 0.0;
    let iota = m.layers.iridescence;
    let film_d = iridescence_fresnel(cos_o, m.layers.iridescence_ior, m.layers.iridescence_thickness, f0);
    let film_m = iridescence_fresnel(cos_o, m.layers.iridescence_ior, m.layers.iridescence_thickness, b);
    dielectric = select(dielectric, dielectric * (1.0 - iota) + film_d * (iota * lobe_albedo), film);
    metal = select(metal, metal * (1.0 - iota) + film_m * (iota * lobe_albedo), film);
    #endif
    #if layer_transmission || layer_diffuse_transmission
    // Transmission takes its share of the diffuse part, as in the BRDF.
    let diffuse_weight = max(1.0 - max(dielectric.x, max(dielectric.y, dielectric.z)), 0.0) * reflected_diffuse_weight(m.layers);
    #else
    let diffuse_weight = max(1.0 - max(dielectric.x, max(dielectric.y, dielectric.z)), 0.0);
    #endif
    var normal = n;
    #if layer_anisotropy
    normal = prefiltered_bent_normal(m, frame, wo);
    #endif
    let r = prefiltered_direction(mirror_direction(wo, normal), n, alpha);
    let radiance = environment.scale * prefiltered_lookup(environment_to_map(r), alpha);
    let f0_mix = f0 * (1.0 - metallic) + b * metallic;
    var specular = (dielectric * (1.0 - metallic) + metal * metallic) * radiance;
    #if energy_compensation
    specular *= ms_factor(f0_mix, ms_ratio(m.lobe.x, alpha, cos_o));
    #endif
    let irradiance = sh_irradiance(n);
    var l = b * ((1.0 - metallic) * diffuse_weight * FRAC_1_PI) * irradiance + specular;
    #if layer_sheen
    let c_sh = m.layers.sheen_color;
    let e_o = sheen_albedo_lookup(cos_o, m.layers.sheen_roughness);
    let scaling = max(1.0 - max(c_sh.x, max(c_sh.y, c_sh.z)) * e_o, 0.0);
    let sheen_alpha = m.layers.sheen_roughness * m.layers.sheen_roughness;
    let sheen_radiance = environment.scale * prefiltered_zonal_lookup(environment_to_map(n), sheen_alpha);
    l = select(l, c_sh * e_o * sheen_radiance + l * scaling, any(c_sh != vec3<f32>(0.0)));
    #endif
    #if layer_clearcoat
    let n_c = coat_normal(frame, m.layers.clearcoat_normal);
    let cos_c = max(dot(n_c, wo), 0.0);
    let weight = m.layers.clearcoat * clearcoat_fresnel(cos_c);
    let alpha_c = m.layers.clearcoat_roughness * m.layers.clearcoat_roughness;
    let ab_c = environment_dfg(cos_c, alpha_c);
    let r_c = prefiltered_direction(mirror_direction(wo, n_c), n_c, alpha_c);
    let coat = environment.scale * prefiltered_lookup(environment_to_map(r_c), alpha_c) * (weight * (ab_c.x + ab_c.y));
    l = select(l, l * (1.0 - weight) + coat, m.layers.clearcoat > 0.0);
    #endif
    return l;
}
#endif

// Diffuse by SH plus the prefiltered specular. Twin: prefiltered::estimate.
fn environment_prefiltered(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let n = frame.n;
    let diffuse = environment_diffuse_albedo(m) * FRAC_1_PI * sh_irradiance(n);
    let cos_o = dot(n, wo);
    #if gltf-pbr
    // gltf-pbr (with or without layers) has its own split (a select:
    // UNIFORM_BRANCHES). Twin: the GltfPbr arm of prefiltered::estimate.
    let pbr = brdf_model(m) == MODEL_GLTF_PBR;
    let pbr_l = select(diffuse, environment_prefiltered_gltf(m, wo, frame), cos_o > 0.0);
    #endif
    let t = prefiltered_terms(m);
    let ab = environment_dfg(cos_o, t.alpha);
    let r = prefiltered_direction(mirror_direction(wo, n), n, t.alpha);
    let l = environment.scale * prefiltered_lookup(environment_to_map(r), t.alpha);
    var specular = t.weight * (t.f0 * ab.x + ab.y) * l;
    // Energy compensation: the lobe times the factor of brdf/energy.wgsl,
    // with the split's F0 (lobe.x is the material's weight: 0 for the
    // models without it).
    #if cook-torrance
    specular *= ms_factor(t.f0, ms_ratio(m.lobe.x, t.alpha, cos_o));
    #endif
    let other = diffuse + select(vec3<f32>(0.0), specular, cos_o > 0.0);
    #if gltf-pbr
    return select(other, pbr_l, pbr);
    #else
    return other;
    #endif
}
#endif
