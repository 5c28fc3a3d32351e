// A measured material: trilinear look-up in its table over Rusinkiewicz's
// half/difference angles, a MERL-format table (θ_h in square-root spacing)
// that the CPU built from the source (src/gpu/measured_tables.rs).
// f64 twins: src/material/measured/coords.rs (half_diff) and
// src/material/measured/merl.rs (MerlTable::f_r, same rule, same order).
// The tables of all the scene's measured materials are one array, bound
// only when the scene has a measured material; a material's `lobe` holds
// its table's first index (its bits) and its sample counts (n_h, n_d, n_φ),
// n_φ negative for a φ_d axis over 2π (a network's table) rather than π
// (MERL's fold).

#if measured
@group(0) @binding(3) var<storage, read> measured_tables: array<f32>;

const MEASURED_SIN_THETA_H_FLOOR: f32 = 1e-9;

// The half vector's polar angle (sin θ_h, cos θ_h) and ω_i in the
// half/difference frame (Rusinkiewicz 1998), for ω_i = wi, ω_o = wo in the
// frame (t, b, n): what the table look-up and the network both start from.
struct MeasuredHalfDiff {
    sin_h: f32,
    cos_h: f32,
    d: vec3<f32>,
}

fn measured_half_diff_frame(wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> MeasuredHalfDiff {
    let i = vec3<f32>(dot(wi, frame.t), dot(wi, frame.b), dot(wi, frame.n));
    let o = vec3<f32>(dot(wo, frame.t), dot(wo, frame.b), dot(wo, frame.n));
    let h = normalize(i + o);
    let sin_h = sqrt(h.x * h.x + h.y * h.y);
    let cos_h = h.z;
    var cos_phi_h = 1.0;
    var sin_phi_h = 0.0;
    if sin_h >= MEASURED_SIN_THETA_H_FLOOR {
        cos_phi_h = h.x / sin_h;
        sin_phi_h = h.y / sin_h;
    }
    let x = i.x * cos_phi_h + i.y * sin_phi_h;
    let y = -i.x * sin_phi_h + i.y * cos_phi_h;
    return MeasuredHalfDiff(sin_h, cos_h, vec3<f32>(x * cos_h - i.z * sin_h, y, x * sin_h + i.z * cos_h));
}

// (θ_h, θ_d, φ_d) of ω_i = wi, ω_o = wo in the frame (t, b, n).
fn measured_half_diff(wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let hd = measured_half_diff_frame(wi, wo, frame);
    let d = hd.d;
    return vec3<f32>(atan2(hd.sin_h, hd.cos_h), atan2(sqrt(d.x * d.x + d.y * d.y), d.z), atan2(d.y, d.x));
}

// The sample at (i_h, i_d, i_φ) of the table starting at `base`.
fn measured_sample(base: u32, dims: vec3<u32>, ih: u32, id: u32, ip: u32) -> vec3<f32> {
    let k = base + 3u * (ip + dims.z * (id + dims.y * ih));
    return vec3<f32>(measured_tables[k], measured_tables[k + 1u], measured_tables[k + 2u]);
}

#if measured_network
// The Neural-BRDF network (Sztrajman et al. 2021) evaluated per pixel
// (shading.measured_mode = "network"; f64 twin: Network::forward and
// Network::f_r in src/material/measured/network.rs, same order): the
// material's 675 weights from its first index, in Network::flat's order
// W1 (6×21, row by row), b1, W2 (21×21), b2, W3 (21×3), b3;
// a1 = relu(x·W1 + b1), a2 = relu(a1·W2 + b2), f_r = max(0, exp(a2·W3 + b3) − 1),
// x = (h, d) of coords::half_diff (h = (sin θ_h, 0, cos θ_h)).
const NBRDF_B1: u32 = 126u;
const NBRDF_W2: u32 = 147u;
const NBRDF_B2: u32 = 588u;
const NBRDF_W3: u32 = 609u;
const NBRDF_B3: u32 = 672u;

fn measured_f_r(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let base = bitcast<u32>(m.lobe.x);
    let hd = measured_half_diff_frame(wi, wo, frame);
    var input = array<f32, 6>(hd.sin_h, 0.0, hd.cos_h, hd.d.x, hd.d.y, hd.d.z);
    var a1: array<f32, 21>;
    for (var j = 0u; j < 21u; j = j + 1u) {
        var z = measured_tables[base + NBRDF_B1 + j];
        for (var k = 0u; k < 6u; k = k + 1u) {
            z = z + input[k] * measured_tables[base + k * 21u + j];
        }
        a1[j] = max(z, 0.0);
    }
    var a2: array<f32, 21>;
    for (var j = 0u; j < 21u; j = j + 1u) {
        var z = measured_tables[base + NBRDF_B2 + j];
        for (var k = 0u; k < 21u; k = k + 1u) {
            z = z + a1[k] * measured_tables[base + NBRDF_W2 + k * 21u + j];
        }
        a2[j] = max(z, 0.0);
    }
    var out = vec3<f32>(measured_tables[base + NBRDF_B3], measured_tables[base + NBRDF_B3 + 1u], measured_tables[base + NBRDF_B3 + 2u]);
    for (var k = 0u; k < 21u; k = k + 1u) {
        let w = base + NBRDF_W3 + 3u * k;
        out = out + a2[k] * vec3<f32>(measured_tables[w], measured_tables[w + 1u], measured_tables[w + 2u]);
    }
    return max(exp(out) - vec3<f32>(1.0), vec3<f32>(0.0));
}
#else
// f_r [1/sr]: the table's trilinear interpolation (MerlTable::f_r).
fn measured_f_r(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let base = bitcast<u32>(m.lobe.x);
    let dims = vec3<u32>(abs(m.lobe.yzw));
    let n = vec3<f32>(dims);
    let phi_period = select(PI, 2.0 * PI, m.lobe.w < 0.0);
    let a = measured_half_diff(wi, wo, frame);
    let u_h = clamp(sqrt(max(a.x, 0.0) / (0.5 * PI)) * n.x, 0.0, n.x - 1.0);
    let u_d = clamp(max(a.y, 0.0) / (0.5 * PI) * n.y, 0.0, n.y - 1.0);
    var phi = a.z;
    if phi < 0.0 {
        phi = phi + phi_period;
    }
    let u_p = min(phi / phi_period, 1.0) * n.z;
    let h0 = min(u32(floor(u_h)), dims.x - 1u);
    let d0 = min(u32(floor(u_d)), dims.y - 1u);
    let p_floor = floor(u_p);
    let th = u_h - f32(h0);
    let td = u_d - f32(d0);
    let tp = u_p - p_floor;
    let h1 = min(h0 + 1u, dims.x - 1u);
    let d1 = min(d0 + 1u, dims.y - 1u);
    let p0 = u32(p_floor) % dims.z;
    let p1 = (p0 + 1u) % dims.z;
    let a0 = mix(
        mix(measured_sample(base, dims, h0, d0, p0), measured_sample(base, dims, h0, d0, p1), tp),
        mix(measured_sample(base, dims, h0, d1, p0), measured_sample(base, dims, h0, d1, p1), tp),
        td,
    );
    let a1 = mix(
        mix(measured_sample(base, dims, h1, d0, p0), measured_sample(base, dims, h1, d0, p1), tp),
        mix(measured_sample(base, dims, h1, d1, p0), measured_sample(base, dims, h1, d1, p1), tp),
        td,
    );
    return mix(a0, a1, th);
}
#endif
#endif
