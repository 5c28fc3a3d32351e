// Shadow-map lookups: V_l in [0, 1] for the reflection equation
// (shaders/shading.wgsl). The CPU reference ray-traces the same V
// (reference::visibility); docs/shadows.md derives the biases used here.
// Compiled only when a light casts shadows (feature `shadows`); each
// projection only when a light uses it (`shadow_ortho`, `shadow_perspective`,
// `shadow_cube`), the PCF loop only when a light filters (`shadow_pcf`).
// The maps are written by shaders/shadow_pass.wgsl.

// One layer of the shadow-map array. Mirror: GpuShadowView (src/gpu/layout.rs).
struct ShadowView {
    clip_from_world: mat4x4<f32>,
    origin: vec3<f32>,   // the light (perspective and cube faces)
    depth_scale: f32,    // stored depth = radial distance · depth_scale (perspective and cube)
}

@group(1) @binding(0) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(1) var shadow_sampler: sampler_comparison; // nearest, LessEqual: 1 where lit
@group(1) @binding(2) var<storage, read> shadow_views: array<ShadowView>;

// The offset normal turned towards the light, and tanθ of the angle
// between them (capped at θ = 89.94°).
struct ShadowGeometry {
    n: vec3<f32>,
    tan_theta: f32,
}

fn shadow_geometry(n_g: vec3<f32>, wi: vec3<f32>) -> ShadowGeometry {
    var n = normalize_or_zero(n_g);
    var c = dot(n, wi);
    if c < 0.0 {
        n = -n;
        c = -c;
    }
    let s = sqrt(max(1.0 - c * c, 0.0));
    return ShadowGeometry(n, s / max(c, 1e-3));
}

// Fraction of the (2r+1)² nearest-texel depth comparisons around uv that
// find the receiver lit (one comparison without PCF).
fn shadow_compare(uv: vec2<f32>, layer: i32, depth: f32, radius: u32) -> f32 {
    let d = min(depth, 1.0); // never darker than the cleared (empty) map
    let texel = 1.0 / f32(textureDimensions(shadow_maps).x); // #if shadow_pcf
    let r = i32(radius); // #if shadow_pcf
    var lit = 0.0; // #if shadow_pcf
    for (var i = -r; i <= r; i++) { // #if shadow_pcf
        for (var j = -r; j <= r; j++) { // #if shadow_pcf
            let offset = vec2<f32>(f32(i), f32(j)) * texel; // #if shadow_pcf
            lit += textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + offset, layer, d); // #if shadow_pcf
        } // #if shadow_pcf
    } // #if shadow_pcf
    let side = f32(2 * r + 1); // #if shadow_pcf
    return lit / (side * side); // #if shadow_pcf
    return textureSampleCompareLevel(shadow_maps, shadow_sampler, uv, layer, d); // #if !shadow_pcf
}

// Clip-space xy of a layer to texture coordinates of the light's map (its
// top-left map_size² corner of the array layer).
fn shadow_uv(clip: vec4<f32>, light: Light) -> vec2<f32> {
    let ndc = clip.xy / clip.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * light.shadow_uv_scale;
}

// Directional light: orthographic map fitted to the scene bounds; stored
// depth is clip z (linear along the light).
fn shadow_ortho(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 { // #if shadow_ortho
    let geo = shadow_geometry(n_g, -light.direction); // #if shadow_ortho
    let texel = light.shadow_texel; // #if shadow_ortho
    let p = x + geo.n * (light.shadow_normal_offset * texel); // #if shadow_ortho
    let clip = shadow_views[light.shadow_layer].clip_from_world * vec4<f32>(p, 1.0); // #if shadow_ortho
    let bias = (light.shadow_bias + light.shadow_slope_bias * texel * geo.tan_theta) * light.shadow_depth_scale; // #if shadow_ortho
    return shadow_compare(shadow_uv(clip, light), light.shadow_layer, clip.z - bias, light.shadow_pcf_radius); // #if shadow_ortho
} // #if shadow_ortho

// Perspective map of `layer` around light.shadow_origin; stored depth is
// the radial distance times depth_scale. Texel size grows with distance.
fn shadow_radial(light: Light, x: vec3<f32>, n_g: vec3<f32>, layer: i32, p: vec3<f32>, geo: ShadowGeometry, texel: f32) -> f32 { // #if shadow_radial
    let clip = shadow_views[layer].clip_from_world * vec4<f32>(p, 1.0); // #if shadow_radial
    if clip.w <= 0.0 { // #if shadow_radial
        return 1.0; // #if shadow_radial
    } // #if shadow_radial
    let bias = light.shadow_bias + light.shadow_slope_bias * texel * geo.tan_theta; // #if shadow_radial
    let depth = (distance(p, light.shadow_origin) - bias) * light.shadow_depth_scale; // #if shadow_radial
    return shadow_compare(shadow_uv(clip, light), layer, depth, light.shadow_pcf_radius); // #if shadow_radial
} // #if shadow_radial

// Where a perspective or cube lookup reads: x moved along the offset
// normal by normal_offset texels of the map at x's distance.
struct RadialLookup { // #if shadow_radial
    p: vec3<f32>, // #if shadow_radial
    geo: ShadowGeometry, // #if shadow_radial
    texel: f32, // #if shadow_radial
} // #if shadow_radial

fn radial_lookup(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> RadialLookup { // #if shadow_radial
    let to_light = light.shadow_origin - x; // #if shadow_radial
    let r = length(to_light); // #if shadow_radial
    let geo = shadow_geometry(n_g, to_light / max(r, 1e-30)); // #if shadow_radial
    let texel = light.shadow_texel * r; // #if shadow_radial
    return RadialLookup(x + geo.n * (light.shadow_normal_offset * texel), geo, texel); // #if shadow_radial
} // #if shadow_radial

// Spot light: one perspective map whose cone covers the outer cone.
fn shadow_perspective(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 { // #if shadow_perspective
    let q = radial_lookup(light, x, n_g); // #if shadow_perspective
    return shadow_radial(light, x, n_g, light.shadow_layer, q.p, q.geo, q.texel); // #if shadow_perspective
} // #if shadow_perspective

// Point light (and an area light's shared map): six perspective maps, the
// face chosen by the major axis of the direction from the light.
fn shadow_cube(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 { // #if shadow_cube
    let q = radial_lookup(light, x, n_g); // #if shadow_cube
    let v = q.p - light.shadow_origin; // #if shadow_cube
    let a = abs(v); // #if shadow_cube
    var face = 0; // #if shadow_cube
    if a.x >= a.y && a.x >= a.z { // #if shadow_cube
        face = select(1, 0, v.x > 0.0); // #if shadow_cube
    } else if a.y >= a.z { // #if shadow_cube
        face = select(3, 2, v.y > 0.0); // #if shadow_cube
    } else { // #if shadow_cube
        face = select(5, 4, v.z > 0.0); // #if shadow_cube
    } // #if shadow_cube
    return shadow_radial(light, x, n_g, light.shadow_layer + face, q.p, q.geo, q.texel); // #if shadow_cube
} // #if shadow_cube

// V_l at x (n_g: the offset normal, any length and orientation).
fn shadow_visibility(light: Light, x: vec3<f32>, n_g: vec3<f32>) -> f32 {
    if light.shadow_layer < 0 {
        return 1.0;
    }
    switch light.shadow_projection {
        case 0u: { return shadow_ortho(light, x, n_g); } // #if shadow_ortho
        case 1u: { return shadow_perspective(light, x, n_g); } // #if shadow_perspective
        case 2u: { return shadow_cube(light, x, n_g); } // #if shadow_cube
        default: { return 1.0; }
    }
}
