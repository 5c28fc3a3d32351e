// Energy compensation of the microfacet lobes (Turquin 2019): a lobe of
// normal-incidence Fresnel F0 is scaled by 1 + F0·(1 − E(μ_o, α))/E(μ_o, α),
// E the directional albedo of GGX with height-correlated Smith (the table
// of src/material/brdf/dfg.rs, the same f32 nodes in globals.albedo, filled
// when some material has energy_compensation = true).
// f64 twin: src/material/brdf/energy.rs (same names, same order).
// Without the feature `energy_compensation` (no material of the scene has
// it) ms_ratio is 0 and every factor exactly 1: the table is not read.

// dfg::SIZE
const MS_TABLE_SIZE: i32 = 32;
// energy::E_FLOOR
const MS_E_FLOOR: f32 = 1e-4;

#if energy_compensation
fn ms_node(i: i32, j: i32) -> f32 {
    let k = j * MS_TABLE_SIZE + i;
    return globals.albedo[k / 4][k % 4];
}

// E(μ_o, α), bilinear in (√μ, √α) between the nodes. Twin: DfgTable::albedo.
fn ms_albedo(alpha: f32, cos_o: f32) -> f32 {
    let last = f32(MS_TABLE_SIZE - 1);
    let x = sqrt(clamp(cos_o, 0.0, 1.0)) * last;
    let y = sqrt(clamp(alpha, 0.0, 1.0)) * last;
    let x0 = min(floor(x), last - 1.0);
    let y0 = min(floor(y), last - 1.0);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let lo = ms_node(i, j) * (1.0 - fx) + ms_node(i + 1, j) * fx;
    let hi = ms_node(i, j + 1) * (1.0 - fx) + ms_node(i + 1, j + 1) * fx;
    return lo * (1.0 - fy) + hi * fy;
}
#endif

// (1 − E)/E at (μ_o, α) times the material's weight (lobe.x: 1 with
// compensation, 0 without; a product, not a branch: UNIFORM_BRANCHES).
fn ms_ratio(weight: f32, alpha: f32, cos_o: f32) -> f32 {
    #if energy_compensation
    let e = ms_albedo(alpha, cos_o);
    return weight * ((1.0 - e) / max(e, MS_E_FLOOR));
    #else
    return 0.0;
    #endif
}

// 1 + F0·ratio: exactly 1 with ratio 0.
fn ms_factor(f0: vec3<f32>, ratio: f32) -> vec3<f32> {
    return vec3<f32>(1.0) + f0 * ratio;
}

// The GGX α standing in for a Cook-Torrance distribution: its roughness
// (Beckmann's and the Gaussians' m, GGX's α), for Blinn's exponent e
// √(2/(e + 2)) (blinn_e is 0 for the others). Twin: prefiltered::ggx_alpha.
fn ms_ggx_alpha(m: Material) -> f32 {
    return select(m.roughness, sqrt(2.0 / (m.blinn_e + 2.0)), m.blinn_e > 0.0);
}
