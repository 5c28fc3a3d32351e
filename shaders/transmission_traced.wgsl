// A volume's refracted ray traced in screen space past its exit
// (`shading.transmission_exit_ray = "traced"`; docs/transmission.md,
// "The GPU renderer"). The two interfaces of Wyman 2005 ("An Approximate
// Image-Space Approach for Interactive Refraction", SIGGRAPH): the
// volumes' back faces are drawn first (src/gpu/transmission_back_faces.rs)
// into an image of their outward normal and depth; the ray refracted in
// at the pixel's surface is marched in screen space against that depth
// to the back face it leaves through, refracted out at the back face's
// normal, then marched against the opaque scene's depth (the depth of
// the transmission image's layer 0) to what it meets, where the
// transmission image is read. Both marches step evenly in screen space
// with the depth interpolated linearly there (NDC depth is affine in
// screen space along a projected line), as McGuire & Mara 2014,
// "Efficient GPU Screen-Space Ray Tracing" (JCGT 3(4)), then bisect the
// step that crossed. Beer–Lambert is taken over the true length inside,
// |x2 − x1|. Where the ray finds no back face within twice the
// thickness, or is totally reflected at the exit, the caller falls back
// to the thickness read (seen_through). A ray past the exit that meets
// nothing on screen reads the image where it leaves the screen or, short
// of the edge, at the projection of a far point along it (its vanishing
// point): the background in that direction.
// Compiled only with feature transmission_exit_traced.

// The nearest back face of a volume per pixel: outward world normal
// (xyz) and depth (w, the depth buffer's [0, 1]; 1 where none).
@group(4) @binding(2) var transmission_back_faces: texture_2d<f32>;
// The opaque scene's depth (layer 0 of the transmission images).
@group(4) @binding(3) var transmission_scene_depth: texture_depth_2d;

// Steps of each march, evenly spaced in screen space, and the bisections
// of the step that crossed: a march over W pixels places its crossing
// within W / (32 · 2⁶) pixels, under a pixel for W < 2048.
const TRACE_STEPS: u32 = 32u;
const TRACE_BISECTIONS: u32 = 6u;
// How far past the exit the second march aims, in units of the exit's
// distance to the eye: far enough that its end projects within a pixel
// of the ray's vanishing point at the sizes rendered.
const TRACE_FAR: f32 = 1000.0;

// A world segment and its projection: NDC (x, y, depth) at both ends,
// 1/w at both ends (perspective-correct interpolation), the screen
// parameter where it leaves the frame, and whether it starts in front of
// the camera.
struct ScreenRay {
    start: vec3<f32>,
    stop: vec3<f32>,
    ndc0: vec3<f32>,
    ndc1: vec3<f32>,
    inv_w0: f32,
    inv_w1: f32,
    end: f32,
    valid: bool,
}

// The largest screen parameter in [0, 1] at which the segment a → b of
// NDC xy is still inside the frame [−1, 1]².
fn screen_exit(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let d = b - a;
    var t = 1.0;
    for (var k = 0; k < 2; k++) {
        if d[k] > 0.0 {
            t = min(t, (1.0 - a[k]) / d[k]);
        } else if d[k] < 0.0 {
            t = min(t, (-1.0 - a[k]) / d[k]);
        }
    }
    return clamp(t, 0.0, 1.0);
}

// The projection of the segment start → stop, its far end pulled in front
// of the camera (w ≥ 10⁻³ of the start's) where it passes behind.
fn screen_ray(start: vec3<f32>, stop: vec3<f32>) -> ScreenRay {
    var r: ScreenRay;
    let c0 = globals.clip_from_world * vec4<f32>(start, 1.0);
    var c1 = globals.clip_from_world * vec4<f32>(stop, 1.0);
    r.valid = c0.w > 0.0;
    r.start = start;
    r.stop = stop;
    let near = max(c0.w * 1e-3, 1e-6);
    if r.valid && c1.w < near {
        let s = (c0.w - near) / (c0.w - c1.w);
        r.stop = mix(start, stop, s);
        c1 = mix(c0, c1, s);
    }
    let w0 = select(1.0, c0.w, r.valid);
    r.ndc0 = c0.xyz / w0;
    r.ndc1 = c1.xyz / c1.w;
    r.inv_w0 = 1.0 / w0;
    r.inv_w1 = 1.0 / c1.w;
    r.end = screen_exit(r.ndc0.xy, r.ndc1.xy);
    return r;
}

// NDC (x, y, depth) at screen parameter a.
fn ray_ndc(r: ScreenRay, a: f32) -> vec3<f32> {
    return mix(r.ndc0, r.ndc1, a);
}

// The world point at screen parameter a (perspective-correct: 1/w is
// linear in screen space).
fn ray_point(r: ScreenRay, a: f32) -> vec3<f32> {
    let s = a * r.inv_w1 / mix(r.inv_w0, r.inv_w1, a);
    return mix(r.start, r.stop, s);
}

// The texel of the frame-sized images under NDC xy.
fn trace_texel(ndc: vec2<f32>) -> vec2<i32> {
    let size = vec2<f32>(textureDimensions(transmission_scene_depth));
    let uv = vec2<f32>(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y);
    return vec2<i32>(clamp(uv * size, vec2<f32>(0.0), size - 1.0));
}

// Whether the ray at screen parameter a lies behind the depth marched
// against (0: the back faces, 1: the opaque scene), where that holds a
// surface (depth < 1).
fn ray_behind(r: ScreenRay, a: f32, against: u32) -> bool {
    let p = ray_ndc(r, a);
    let texel = trace_texel(p.xy);
    var surface: f32;
    if against == 0u {
        surface = textureLoad(transmission_back_faces, texel, 0).w;
    } else {
        surface = textureLoad(transmission_scene_depth, texel, 0);
    }
    return surface < 1.0 && p.z >= surface;
}

// The screen parameter where the ray first passes behind the depth
// marched against, or −1 where it does not within the frame.
fn march(r: ScreenRay, against: u32) -> f32 {
    var before = 0.0;
    for (var i = 1u; i <= TRACE_STEPS; i++) {
        let a = r.end * f32(i) / f32(TRACE_STEPS);
        if ray_behind(r, a, against) {
            var lo = before;
            var hi = a;
            for (var j = 0u; j < TRACE_BISECTIONS; j++) {
                let mid = 0.5 * (lo + hi);
                if ray_behind(r, mid, against) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return hi;
        }
        before = a;
    }
    return -1.0;
}

// What the image holds along the view ray refracted into the volume at
// x (index `ior`), out through its back face and on to the opaque scene,
// blurred by the roughness and attenuated over the path inside: rgb, and
// a = 1 where traced, 0 where the caller falls back to the thickness
// read (a thin wall, no back face found, total internal reflection at
// the exit, x behind the camera).
fn seen_through_traced(m: Material, x: vec3<f32>, n: vec3<f32>, wo: vec3<f32>, ior: f32) -> vec4<f32> {
    let thickness = m.layers.thickness * draw_volume_scale;
    let t1 = normalize_or_zero(refract(-wo, n, 1.0 / max(ior, 1.0)));
    if thickness <= 0.0 || all(t1 == vec3<f32>(0.0)) {
        return vec4<f32>(0.0);
    }
    let inside = screen_ray(x, x + t1 * (2.0 * thickness));
    let exit = march(inside, 0u);
    if !inside.valid || exit < 0.0 {
        return vec4<f32>(0.0);
    }
    let x2 = ray_point(inside, exit);
    let back = textureLoad(transmission_back_faces, trace_texel(ray_ndc(inside, exit).xy), 0).xyz;
    let n2 = normalize_or_zero(back);
    // Out of the glass (index ior into 1): the normal turned against the
    // ray, as refract() takes it; 0 at total internal reflection.
    let t2 = refract(t1, select(n2, -n2, dot(n2, t1) > 0.0), max(ior, 1.0));
    if all(t2 == vec3<f32>(0.0)) || all(n2 == vec3<f32>(0.0)) {
        return vec4<f32>(0.0);
    }
    let far = TRACE_FAR * max(distance(x2, globals.eye), thickness);
    let past = screen_ray(x2, x2 + normalize(t2) * far);
    if !past.valid {
        return vec4<f32>(0.0);
    }
    let hit = march(past, 1u);
    let p = ray_ndc(past, select(past.end, hit, hit >= 0.0));
    let uv = vec2<f32>(0.5 + 0.5 * p.x, 0.5 - 0.5 * p.y);
    let width = f32(textureDimensions(transmission_image).x);
    let lod = transmission_lod(width, m.roughness, ior);
    let behind = textureSampleLevel(transmission_image, transmission_sampler, uv, lod).rgb;
    let inside_length = distance(x, x2);
    return vec4<f32>(behind * volume_attenuation(m.layers.attenuation_color, inside_length, m.layers.attenuation_rate), 1.0);
}
