// The sheen's directional albedo E(μ, α_sh(r_sh)) for the albedo scaling of
// KHR_materials_sheen, as a table the GPU interpolates: the nodes hold
// g = r_sh · E at μ_i = μ_min + (1 − μ_min) (i/(N − 1))⁴, r_sh = j/(N − 1),
// from the exact quadrature of the f64 reference (src/material/brdf/
// gltf_layers/sheen_albedo.rs, sheen_albedo_table, which says why this
// form and bounds its error, SHEEN_ALBEDO_TABLE_ERROR), rounded to f32
// (sheen_albedo_nodes.rs).
// A uniform buffer (group 0, binding 4), bound only when the sheen is
// compiled (layer_sheen; src/gpu/bind_groups.rs): as a `const` array of
// 1024 f32 indexed at run time it made lavapipe's LLVM (15) spend tens of
// minutes in its coroutine-splitting pass (measured 2026-12-04).
// f64 twin: src/material/brdf/gltf_layers/sheen_albedo.rs (sheen_albedo_lookup).

const SHEEN_ALBEDO_TABLE_SIZE: i32 = 64;
// The smallest μ of the table (θ = 89.994°): below, E(μ_min).
const SHEEN_ALBEDO_COS_MIN: f32 = 1e-4;

// g at node (i, j), i the fast index; node k at [k / 4][k % 4].
@group(0) @binding(4) var<uniform> sheen_albedo_table: array<vec4<f32>, 1024>;

fn sheen_albedo_node(i: i32, j: i32) -> f32 {
    let k = j * SHEEN_ALBEDO_TABLE_SIZE + i;
    return sheen_albedo_table[k / 4][k % 4];
}

// E(μ, α_sh(r_sh)): g bilinear in (u, r_sh), u = ((μ − μ_min)/(1 − μ_min))^¼,
// over r_sh (0 at r_sh = 0: a select, not a branch, UNIFORM_BRANCHES).
fn sheen_albedo_lookup(cos: f32, sheen_roughness: f32) -> f32 {
    let last = f32(SHEEN_ALBEDO_TABLE_SIZE - 1);
    let t = (clamp(cos, SHEEN_ALBEDO_COS_MIN, 1.0) - SHEEN_ALBEDO_COS_MIN) / (1.0 - SHEEN_ALBEDO_COS_MIN);
    let x = sqrt(sqrt(t)) * last;
    let r = clamp(sheen_roughness, 0.0, 1.0);
    let y = r * last;
    let x0 = min(floor(x), last - 1.0);
    let y0 = min(floor(y), last - 1.0);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let lo = sheen_albedo_node(i, j) * (1.0 - fx) + sheen_albedo_node(i + 1, j) * fx;
    let hi = sheen_albedo_node(i, j + 1) * (1.0 - fx) + sheen_albedo_node(i + 1, j + 1) * fx;
    let g = lo * (1.0 - fy) + hi * fy;
    return select(0.0, g / max(r, 1e-30), r > 0.0);
}
