// Point light: radiant intensity I [W/sr], E = I / d². Twin: Light::Point.
fn point_incidence(light: Light, x: vec3<f32>) -> Incidence {
    let falloff = inverse_square(light.position - x, light.range);
    return Incidence(falloff.xyz, light.intensity * falloff.w);
}
