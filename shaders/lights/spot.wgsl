// Spot light with glTF's cone falloff. Twins: Light::Spot, spot_attenuation.
fn spot_attenuation(cos_angle: f32, cos_inner: f32, cos_outer: f32) -> f32 {
    let scale = 1.0 / max(cos_inner - cos_outer, 0.001);
    let offset = -cos_outer * scale;
    let t = clamp(cos_angle * scale + offset, 0.0, 1.0);
    return t * t;
}

fn spot_incidence(light: Light, x: vec3<f32>) -> Incidence {
    let falloff = inverse_square(light.position - x, light.range);
    let cone = spot_attenuation(-dot(falloff.xyz, light.direction), light.cos_inner, light.cos_outer);
    return Incidence(falloff.xyz, light.intensity * (falloff.w * cone));
}
