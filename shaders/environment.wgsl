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
    _pad: u32,
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

// Bilinear lookup, texel centres at ((col + ½)/W, (row + ½)/H), u wraps,
// v clamps. Twin: MapData::lookup.
fn environment_lookup(d: vec3<f32>) -> vec3<f32> {
    let uv = latlong_uv(d);
    let w = i32(environment.width);
    let h = i32(environment.height);
    let x = uv.x * f32(w) - 0.5;
    let y = uv.y * f32(h) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let c0 = ((i32(x0) % w) + w) % w;
    let c1 = ((i32(x0) + 1) % w + w) % w;
    let r0 = clamp(i32(y0), 0, h - 1);
    let r1 = clamp(i32(y0) + 1, 0, h - 1);
    let top = environment_texel(c0, r0) * (1.0 - fx) + environment_texel(c1, r0) * fx;
    let bottom = environment_texel(c0, r1) * (1.0 - fx) + environment_texel(c1, r1) * fx;
    return top * (1.0 - fy) + bottom * fy;
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

// E(n) = Σ_i sh[i] · Y_i(n), the 25 real SH of bands 0-4 in the order and
// form of sh::basis (Sloan 2008), at the normal in the file's frame.
// Twin: EnvironmentMap::irradiance_sh.
fn sh_irradiance(world_n: vec3<f32>) -> vec3<f32> {
    let n = environment_to_map(world_n);
    let x = n.x;
    let y = n.y;
    let z = n.z;
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
    var e = vec3<f32>(0.0);
    for (var i = 0u; i < 25u; i++) {
        e += environment.sh[i].rgb * b[i];
    }
    return e;
}

#if environment_sampled
// L_o = ∫ f_r L_env cos θ dω by N cosine-weighted Hammersley directions:
// (π/N) Σ_k f_r(ω_k, ω_o) L_env(ω_k). Twin: sampled::estimate.
fn environment_sampled(m: Material, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    // The loop bound is a uniform, but group 3's, which every draw of a
    // frame shares (unlike the material's: UNIFORM_BRANCHES in
    // brdf/phong.wgsl), so lavapipe inlines it once per setting.
    let n = environment.samples;
    // The directions' frame from the normal alone (as sampled::estimate).
    let t = any_tangent(frame.n);
    let b = cross(frame.n, t);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < n; k++) {
        let u1 = (f32(k) + 0.5) / f32(n);
        let u2 = f32(reverseBits(k)) * 2.3283064365386963e-10;
        let r = sqrt(u1);
        let phi = 2.0 * PI * u2;
        let wi = t * (r * cos(phi)) + b * (r * sin(phi)) + frame.n * sqrt(1.0 - u1);
        sum += f_r(m, wi, wo, frame) * environment_map_radiance(wi);
    }
    return sum * (PI / f32(n));
}
#endif
