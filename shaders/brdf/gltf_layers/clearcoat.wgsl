// The coat of KHR_materials_clearcoat: IOR 1.5, isotropic GGX of
// α_c = r_c² (floored at the renderer's 1e-4; r_c = 0 is the mirror coat,
// whose Dirac lobe is not a function value: 0 here), weighted by
// F_c = 0.04 + 0.96 (1 − μ_o)⁵ (contract: "Layered glTF materials",
// "Clearcoat"; pinned choice 7).
// f64 twin: src/material/brdf/gltf_layers/clearcoat.rs (same names, same order).
// Uses gltf_pbr.wgsl (DIELECTRIC_F0, schlick_weight, vis_smith_ggx_correlated),
// microfacet.wgsl (half_vector, d_ggx), phong.wgsl (sin2_between).

// material::ROUGHNESS_FLOOR
const CLEARCOAT_ALPHA_FLOOR: f32 = 1e-4;

fn clearcoat_fresnel(cos_o: f32) -> f32 {
    return DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * schlick_weight(cos_o);
}

// 0 at r_c = 0 by a select, not a branch (UNIFORM_BRANCHES in
// brdf/phong.wgsl): the lobe at the floored α is finite there.
fn clearcoat_lobe(clearcoat_roughness: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> f32 {
    let alpha = max(clearcoat_roughness * clearcoat_roughness, CLEARCOAT_ALPHA_FLOOR);
    let h = half_vector(wi, wo);
    let lobe = d_ggx(alpha, dot(n, h), sin2_between(n, h))
        * vis_smith_ggx_correlated(alpha, dot(n, wi), dot(n, wo), dot(wi, h), dot(wo, h));
    return select(lobe, 0.0, clearcoat_roughness <= 0.0);
}

// n_c = x·t + y·b + z·n from the coat normal's coordinates in the
// shading frame; exactly n for (0, 0, 1).
fn coat_normal(frame: SurfaceFrame, coords: vec3<f32>) -> vec3<f32> {
    let turned = frame.t * coords.x + frame.b * coords.y + frame.n * coords.z;
    return select(turned, frame.n, all(coords == vec3<f32>(0.0, 0.0, 1.0)));
}

// (1 − k F_c) · below + k F_c · G_{α_c} about the coat normal n, F_c at
// max(n·V, 0).
fn clearcoat_over(below: vec3<f32>, clearcoat: f32, clearcoat_roughness: f32, n: vec3<f32>, wi: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let weight = clearcoat * clearcoat_fresnel(max(dot(n, wo), 0.0));
    return below * (1.0 - weight) + vec3<f32>(weight * clearcoat_lobe(clearcoat_roughness, n, wi, wo));
}
