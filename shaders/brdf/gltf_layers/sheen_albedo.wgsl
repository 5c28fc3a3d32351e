// The sheen's directional albedo E(μ, α_sh(r_sh)) for the albedo scaling of
// KHR_materials_sheen, as a table the GPU interpolates: the nodes are the
// exact quadrature of the f64 reference (src/material/brdf/gltf_layers/
// sheen_albedo.rs, sheen_albedo_table), rounded to f32
// (sheen_albedo_nodes.rs); the table's error against the exact integral is
// measured by tests/layer_equivalence.rs.
// A uniform buffer (group 0, binding 4), bound only when the sheen is
// compiled (layer_sheen; src/gpu/bind_groups.rs): as a `const` array of
// 1024 f32 indexed at run time it made lavapipe's LLVM (15) spend tens of
// minutes in its coroutine-splitting pass (measured 2026-12-04).
// f64 twin: src/material/brdf/gltf_layers/sheen_albedo.rs (sheen_albedo_lookup).

const SHEEN_ALBEDO_TABLE_SIZE: i32 = 32;

// E at (√μ, r_sh) = (i, j)/(N − 1), i the fast index; node k at [k / 4][k % 4].
@group(0) @binding(4) var<uniform> sheen_albedo_table: array<vec4<f32>, 256>;

fn sheen_albedo_node(i: i32, j: i32) -> f32 {
    let k = j * SHEEN_ALBEDO_TABLE_SIZE + i;
    return sheen_albedo_table[k / 4][k % 4];
}

// E(μ, α_sh(r_sh)), bilinear in (√μ, r_sh) between the nodes.
fn sheen_albedo_lookup(cos: f32, sheen_roughness: f32) -> f32 {
    let last = f32(SHEEN_ALBEDO_TABLE_SIZE - 1);
    let x = sqrt(clamp(cos, 0.0, 1.0)) * last;
    let y = clamp(sheen_roughness, 0.0, 1.0) * last;
    let x0 = min(floor(x), last - 1.0);
    let y0 = min(floor(y), last - 1.0);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let lo = sheen_albedo_node(i, j) * (1.0 - fx) + sheen_albedo_node(i + 1, j) * fx;
    let hi = sheen_albedo_node(i, j + 1) * (1.0 - fx) + sheen_albedo_node(i + 1, j + 1) * fx;
    return lo * (1.0 - fy) + hi * fy;
}
