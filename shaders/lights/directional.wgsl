// Directional light: irradiance E [W/m²] facing the light. Twin: Light::Directional.
fn directional_incidence(light: Light, x: vec3<f32>) -> Incidence {
    return Incidence(-light.direction, light.intensity);
}
