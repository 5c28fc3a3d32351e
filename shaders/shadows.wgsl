// Shadow-map lookups: V_l in [0, 1] for the reflection equation
// (shaders/shading.wgsl). The CPU reference ray-traces the same V
// (reference::visibility); docs/shadows.md derives the offsets used here.
// Compiled only when a light casts shadows (feature `shadows`); each
// projection only when a light uses it (blocks `#if shadow_ortho`,
// `shadow_perspective`, `shadow_cube`), the PCF loop only when a light
// filters (`#if shadow_pcf`).
// The maps are written by shaders/shadow_pass.wgsl with reversed depth
// (larger = nearer the light).

// One layer of the shadow-map array. Mirror: GpuShadowView (src/gpu/layout.rs).
struct ShadowView {
    clip_from_world: mat4x4<f32>,
}

@group(1) @binding(0) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(1) var shadow_sampler: sampler_comparison; // nearest, GreaterEqual: 1 where lit
#if uniform_shadow_views
@group(1) @binding(2) var<uniform> shadow_views: array<ShadowView, SHADOW_VIEW_CAPACITY>;
#else
@group(1) @binding(2) var<storage, read> shadow_views: array<ShadowView>;
#endif
// One light per shadow map (for an area light, its first sample): the
// lights whose visibility `reflected_radiance` looks up, once each.
// Four to a row: a uniform array's stride is 16 bytes (src/gpu/bindings.rs).
@group(1) @binding(3) var<uniform> shadow_casters: array<vec4<u32>, CASTER_ROWS>;

// The light of shadow map s.
fn shadow_caster(s: u32) -> u32 {
    return shadow_casters[s / 4u][s % 4u];
}

// Most shadow maps a scene may have (src/gpu/shadows.rs: MAX_SHADOW_MAPS).
const MAX_SHADOW_MAPS: u32 = 64u;

// Fraction of the (2r+1)² nearest-texel depth comparisons around uv that
// find the receiver lit (one comparison without PCF).
// `texel`: one texel in array uv (Light.shadow_array_texel, from the CPU:
// textureDimensions per pixel cost lavapipe about a tenth of the lookup).
fn shadow_compare(uv: vec2<f32>, layer: i32, depth: f32, radius: u32, texel: f32) -> f32 {
    let d = max(depth, 0.0); // an empty texel (0) never shadows
    #if pcf_uniform
    let r = i32(PCF_RADIUS);
    #else
    let r = i32(radius);
    #endif
    #if shadow_pcf
    var lit = 0.0;
    for (var i = -r; i <= r; i++) {
        for (var j = -r; j <= r; j++) {
            let offset = vec2<f32>(f32(i), f32(j)) * texel;
            lit += textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + offset, layer, d);
        }
    }
    let side = f32(2 * r + 1);
    return lit / (side * side);
    #else
    return textureSampleCompareLevel(shadow_maps, shadow_sampler, uv, layer, d);
    #endif
}

// Where x reads the map of a light towards unit direction wi whose texel
// measures `texel` at x (n_g: the offset normal, any length and
// orientation): x moved normal_offset texels along the normal turned
// towards the light, then bias + slope_bias · texel · tanθ along wi (θ
// between that normal and wi; tanθ capped at 1000).
fn shadow_point(light: Light, x: vec3<f32>, n_g: vec3<f32>, wi: vec3<f32>, texel: f32) -> vec3<f32> {
    var n = normalize_or_zero(n_g);
    var c = dot(n, wi);
    if c < 0.0 {
        n = -n;
        c = -c;
    }
    let tan_theta = sqrt(max(1.0 - c * c, 0.0)) / max(c, 1e-3);
    return x + n * (light.shadow_normal_offset * texel)
        + wi * (light.shadow_bias + light.shadow_slope_bias * texel * tan_theta);
}

// V of the point with normalized device coordinates ndc on `layer`: its
// reversed depth against the map's.
fn shadow_read_ndc(light: Light, layer: i32, ndc: vec3<f32>) -> f32 {
    let uv = vec2<f32>(ndc.x, -ndc.y) * 0.5 + 0.5;
    return shadow_compare(uv * light.shadow_uv_scale, layer, ndc.z, light.shadow_pcf_radius, light.shadow_array_texel);
}

// V of the point p of a perspective `layer`.
#if shadow_projective
fn shadow_read(light: Light, layer: i32, p: vec3<f32>) -> f32 {
    let clip = shadow_views[layer].clip_from_world * vec4<f32>(p, 1.0);
    if clip.w <= 0.0 {
        return 1.0; // behind a perspective layer: outside the light's reach
    }
    return shadow_read_ndc(light, layer, clip.xyz / clip.w);
}
#endif

// Directional light: one orthographic map fitted to the scene bounds. Its
// clip w is exactly 1 (the view's last row is 0 0 0 1), so no divide.
// shadow_ortho_ndc is also what the vertex shader passes on when it computes
// the coordinates (`#if shadow_vertex`, ShaderKey::shadow_coords_per_vertex).
#if shadow_ortho
fn shadow_ortho_ndc(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> vec3<f32> {
    let p = shadow_point(light, x, n_g, -light.direction, light.shadow_texel);
    return (shadow_views[light.shadow_layer].clip_from_world * vec4<f32>(p, 1.0)).xyz;
}

fn shadow_ortho(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 {
    return shadow_read_ndc(light, light.shadow_layer, shadow_ortho_ndc(light, x, n_g));
}
#endif

// Spot light: one perspective map whose frustum holds the outer cone.
#if shadow_perspective
fn shadow_perspective(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 {
    let to_light = light.shadow_origin - x;
    let r = length(to_light);
    let p = shadow_point(light, x, n_g, to_light / max(r, 1e-30), light.shadow_texel * r);
    return shadow_read(light, light.shadow_layer, p);
}
#endif

#if shadow_vertex
#if shadow_perspective
// Spot light, coordinates per vertex (`#if shadow_vertex` with a
// perspective map: shading.shadow_coords = "vertex",
// ShaderKey::shadow_coords_per_vertex): the vertex shader passes on the
// clip coordinates of a corner's lookup point, the rasterizer interpolates
// them perspective-correctly, the fragment shader divides. Exact for the
// projection (clip_from_world is linear), approximate for the offsets of
// shadow_point, which scale with the distance to the light and turn with
// the direction to it: docs/shadows.md bounds the lookup point's
// displacement over a triangle.
fn shadow_perspective_clip(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> vec4<f32> {
    let to_light = light.shadow_origin - x;
    let r = length(to_light);
    let p = shadow_point(light, x, n_g, to_light / max(r, 1e-30), light.shadow_texel * r);
    return shadow_views[light.shadow_layer].clip_from_world * vec4<f32>(p, 1.0);
}

// V of interpolated clip coordinates on `layer`, as shadow_read.
fn shadow_read_clip(light: Light, layer: i32, clip: vec4<f32>) -> f32 {
    if clip.w <= 0.0 {
        return 1.0; // behind a perspective layer: outside the light's reach
    }
    return shadow_read_ndc(light, layer, clip.xyz / clip.w);
}
#endif
#endif
// Point light (and an area light's shared map): six perspective maps, the
// face chosen by the major axis of the direction from the light to the
// lookup point.
#if shadow_cube
fn shadow_cube(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 {
    let to_light = light.shadow_origin - x;
    let r = length(to_light);
    let p = shadow_point(light, x, n_g, to_light / max(r, 1e-30), light.shadow_texel * r);
    let v = p - light.shadow_origin;
    let a = abs(v);
    let face = shadow_cube_face(v, a);
    let layer = light.shadow_layer + face;
    // A skipped face's view is all zero (src/gpu/shadow_maps.rs): near 0
    // says so, as its clip w = 0 did, and it reads lit.
    let near = shadow_views[layer].clip_from_world[3].z;
    let clip = shadow_cube_clip(light, face, p, a, near);
    if clip.w <= 0.0 || near == 0.0 {
        return 1.0; // the point on the light (w = |v| = 0), or a skipped face
    }
    return shadow_read_ndc(light, layer, clip.xyz / clip.w);
}

// The face (CUBE_FACES order: +X −X +Y −Y +Z −Z) of the major axis of v,
// the direction from the light to the lookup point (a = |v|).
fn shadow_cube_face(v: vec3<f32>, a: vec3<f32>) -> i32 {
    var face = 0;
    if a.x >= a.y && a.x >= a.z {
        face = select(1, 0, v.x > 0.0);
    } else if a.y >= a.z {
        face = select(3, 2, v.y > 0.0);
    } else {
        face = select(5, 4, v.z > 0.0);
    }
    return face;
}

// The clip coordinates of p on cube face `face` (a = |p − origin|, near
// the face's near entry), written out from the face's view instead of
// read from shadow_views: a face's matrix (src/gpu/shadows.rs
// perspective_layer, faces CUBE_FACES) has one non-zero entry per row,
// ±s in x and y (s = shadow_cube_scale), ±1 in w, and its offsets are
// ±s·o in x and y (s·o = shadow_cube_offset, s times the f64 origin,
// rounded once), −(±o) in w and `near` in z. Each coordinate below is
// that row's product with (p, 1): the same f32 values, and on Mesa
// (lavapipe), whose SPIR-V front end builds a matrix product as col3·1
// plus a fused multiply-add per column, the same single rounding, so the
// lookup is the matrix's bit for bit there (the unit test
// cube_faces_are_their_sparse_form pins the matrices to this form,
// tests/shadow_cube_lookup.rs compares both on the GPU). A driver that
// sums a matrix product in another order may round the old product
// differently: x and y then differ from it by at most an ulp, which moves
// a tap to the next texel only at an exact texel edge. Why: the matrix
// of a per-pixel face is a gather of 16 values per pixel on a software
// rasterizer, its near entry one (docs/shadows.md). Face rows (right, up,
// forward): +X (+Z, +Y, +X), −X (−Z, +Y, −X), +Y (−Z, +X, +Y),
// −Y (+Z, +X, −Y), +Z (−X, +Y, +Z), −Z (+X, +Y, −Z).
fn shadow_cube_clip(light: Light, face: i32, p: vec3<f32>, a: vec3<f32>, near: f32) -> vec4<f32> {
    let s = light.shadow_cube_scale;
    let o = light.shadow_cube_offset;
    let axis = face / 2;
    let right = select(p.z, p.x, axis == 2);
    let right_offset = select(o.z, o.x, axis == 2);
    let right_sign = select(-1.0, 1.0, face == 0 || face == 3 || face == 5);
    let up = select(p.y, p.x, axis == 1);
    let up_offset = select(o.y, o.x, axis == 1);
    // Forward: (±1)·p + (∓o) along the face's axis, which is ±v there: |v|.
    let w = select(select(a.z, a.y, axis == 1), a.x, axis == 0);
    return vec4<f32>(right_sign * fma(s, right, -right_offset), fma(s, up, -up_offset), near, w);
}
#endif

// V_l at x (n_g: the offset normal).
fn shadow_visibility(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 {
    if light.shadow_layer < 0 {
        return 1.0;
    }
    switch light.shadow_projection {
        #if shadow_ortho
        case 0u: { return shadow_ortho(light, x, n_g); }
        #endif
        #if shadow_perspective
        case 1u: { return shadow_perspective(light, x, n_g); }
        #endif
        #if shadow_cube
        case 2u: { return shadow_cube(light, x, n_g); }
        #endif
        default: { return 1.0; }
    }
}
