// The incidence of one light at x by its kind's function (this folder).
// f64 twin: Light::incidence in src/scene/light.rs. A light's kind is data
// (`Light.kind`, the `LIGHT_*` codes of LightKind::id), not a pipeline
// constant: with several kinds (`#if light_dispatch`) it is a `switch`
// with an arm per kind present (`#if light=KIND`); one kind calls its
// function directly.
fn light_incidence(light: Light, x: vec3<f32>) -> Incidence {
    #if light_dispatch
    switch light.kind {
        #if light=point
        case LIGHT_POINT: { return point_incidence(light, x); }
        #endif
        #if light=directional
        case LIGHT_DIRECTIONAL: { return directional_incidence(light, x); }
        #endif
        #if light=spot
        case LIGHT_SPOT: { return spot_incidence(light, x); }
        #endif
        #if light=area
        case LIGHT_AREA: { return area_sample_incidence(light, x); }
        #endif
        default: { return Incidence(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0)); }
    }
    #elif light=point
    return point_incidence(light, x);
    #elif light=directional
    return directional_incidence(light, x);
    #elif light=spot
    return spot_incidence(light, x);
    #elif light=area
    return area_sample_incidence(light, x);
    #else
    return Incidence(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0));
    #endif
}
