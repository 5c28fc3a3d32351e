// One of the N point lights that stand in for an area light: it emits with
// the area light's cosine distribution, I(ω) = L·(A/N)·max(0, n_l·ω), ω from
// the sample towards the surface; E = I(ω)/d². `light.direction` holds n_l,
// `light.intensity` L·A/N. Twin: Light::AreaSample.
fn area_sample_incidence(light: Light, x: vec3<f32>) -> Incidence {
    let falloff = inverse_square(light.position - x, -1.0);
    let cosine = max(dot(light.direction, -falloff.xyz), 0.0);
    return Incidence(falloff.xyz, light.intensity * (falloff.w * cosine));
}
