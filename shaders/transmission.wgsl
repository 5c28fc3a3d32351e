// Light through a transmissive gltf-pbr surface in screen space: the
// method of the Khronos glTF Sample Renderer (source/Renderer/shaders/
// ibl.glsl, getIBLVolumeRefraction; functions.glsl, getVolumeTransmissionRay
// and applyVolumeAttenuation). The opaque scene is drawn first into a
// linear colour image with a mip chain (src/gpu/transmission.rs); a
// transmissive surface reads that image where the ray refracted into it
// (Snell, index `ior`) leaves after `thickness`, at a level of detail that
// grows with the roughness, attenuated by Beer–Lambert over that length,
// tinted by the base colour and weighted as the reference's smooth thin
// wall, (1 − m)(1 − max₃ F(μ_o)) T b (src/reference/transmission/thin.rs).
// A thin wall (thickness 0) reads the image straight behind the pixel:
// what the reference's straight ray sees. A volume's exit interface
// weighs the light once more (feature transmission_exit). Not drawn: what
// the image does not hold (what lies off screen, behind another
// transmissive surface of the same image, or behind the surface itself),
// the ray past the exit point, total internal reflection and internal
// reflections (docs/transmission.md, "The GPU renderer"). Dispersion reads
// the image once per channel (feature transmission_dispersion).
// Compiled only where a drawn material transmits and the scene's
// `shading.transmission` is "screen" (feature layer_transmission).

// The image of what lies behind (linear radiance, mip chain) and its
// trilinear sampler.
@group(4) @binding(0) var transmission_image: texture_2d<f32>;
@group(4) @binding(1) var transmission_sampler: sampler;

// How much the drawn object's glTF node scales lengths (Mesh::volume_scale),
// set by the raster stage from the draw's instance index: an object's
// batch is drawn with its first instance holding the scale's f32 bits
// (src/gpu/geometry.rs, Batch::instance), 0 meaning 1.
var<private> draw_volume_scale: f32 = 1.0;

fn set_draw_volume_scale(instance: u32) {
    draw_volume_scale = select(1.0, bitcast<f32>(instance), instance != 0u);
}

// The path inside a volume: the view ray refracted into the surface,
// normalize(refract(−V, N, 1/ior)) · thickness · s (getVolumeTransmissionRay;
// the thickness is in mesh space, `s` the node's length scale, as the
// sample renderer's modelScale). Zero for a thin wall.
fn volume_transmission_ray(n: vec3<f32>, wo: vec3<f32>, thickness: f32, ior: f32) -> vec3<f32> {
    let refracted = refract(-wo, n, 1.0 / max(ior, 1.0));
    return normalize_or_zero(refracted) * (thickness * draw_volume_scale);
}

// Beer–Lambert: attenuation_color^(distance / attenuation_distance),
// `rate` = 1 / attenuation_distance (0: none; then 1 exactly, also for a
// black colour). f64 twin: beer_lambert in
// src/reference/transmission/interface.rs.
fn volume_attenuation(color: vec3<f32>, distance: f32, rate: f32) -> vec3<f32> {
    let exponent = distance * rate;
    let attenuated = exp2(exponent * log2(max(color, vec3<f32>(1e-30))));
    return select(attenuated, vec3<f32>(1.0), exponent <= 0.0);
}

// The level of detail the roughness blurs the image to:
// log2(width) · r · clamp(2 ior − 2, 0, 1) (getTransmissionSample with
// applyIorToRoughness: at ior = 1 a rough surface does not blur).
fn transmission_lod(width: f32, roughness: f32, ior: f32) -> f32 {
    return log2(width) * roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0);
}

// 1 − max₃ F(μ_o): the share of the light an interface lets through.
fn interface_transmittance(layers: GltfLayers, cos_o: f32) -> f32 {
    let f = transmission_fresnel(layers, cos_o);
    return 1.0 - max(f.x, max(f.y, f.z));
}

// The weight of the straight-through light, (1 − m)(1 − max₃ F(μ_o)) T,
// times 1 − k F_c(μ_o) under a coat; the base colour multiplies it.
// f64 twin: lobe_weight in thin_samples (src/reference/transmission/thin.rs).
fn thin_wall_weight(m: Material, cos_o: f32) -> f32 {
    var s = (1.0 - m.metallic) * interface_transmittance(m.layers, cos_o);
    #if layer_clearcoat
    s *= 1.0 - m.layers.clearcoat * clearcoat_fresnel(cos_o);
    #endif
    return s * m.layers.transmission;
}

// What the image holds where the view ray, refracted into the surface at
// x with index `ior`, leaves after the thickness (projected by the
// camera), blurred by the roughness and attenuated over the path inside;
// 0 behind the camera.
fn seen_through(m: Material, x: vec3<f32>, n: vec3<f32>, wo: vec3<f32>, ior: f32) -> vec3<f32> {
    #if transmission_exit_traced
    // The ray traced out of the volume and on (transmission_traced.wgsl);
    // where it cannot be, the read below.
    let traced = seen_through_traced(m, x, n, wo, ior);
    if traced.a > 0.0 {
        return traced.rgb;
    }
    #endif
    let ray = volume_transmission_ray(n, wo, m.layers.thickness, ior);
    let clip = globals.clip_from_world * vec4<f32>(x + ray, 1.0);
    let ndc = clip.xy / clip.w;
    let uv = vec2<f32>(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y);
    let width = f32(textureDimensions(transmission_image).x);
    let lod = transmission_lod(width, m.roughness, ior);
    let behind = textureSampleLevel(transmission_image, transmission_sampler, uv, lod).rgb;
    let through = behind * volume_attenuation(m.layers.attenuation_color, length(ray), m.layers.attenuation_rate);
    return select(through, vec3<f32>(0.0), clip.w <= 0.0);
}

#if transmission_dispersion
// KHR_materials_dispersion as the sample renderer draws it (ibl.glsl,
// getIBLVolumeRefraction): one read per channel, red refracted with
// ior − s, green with ior, blue with ior + s, s = (ior − 1) · 0.025 ·
// dispersion, half the spread n_F − n_C of the specification's Cauchy
// form (dispersion = 20 / V_d; the reference evaluates that form per
// wavelength, dispersion_ior in src/material/brdf/gltf_layers/transmission.rs).
// A thin wall does not refract: the three reads coincide.
fn seen_through_dispersed(m: Material, x: vec3<f32>, n: vec3<f32>, wo: vec3<f32>) -> vec3<f32> {
    let ior = m.layers.ior;
    let s = (ior - 1.0) * 0.025 * m.layers.dispersion;
    let red = seen_through(m, x, n, wo, ior - s).r;
    let green = seen_through(m, x, n, wo, ior).g;
    let blue = seen_through(m, x, n, wo, ior + s).b;
    return vec3<f32>(red, green, blue);
}
#endif

// The light through the surface at x seen from wo: what the image holds
// behind it (seen_through), weighted. 0 where the surface faces away or
// does not transmit.
fn transmitted_radiance(m: Material, x: vec3<f32>, frame: SurfaceFrame, wo: vec3<f32>) -> vec3<f32> {
    let n = frame.n;
    let cos_o = dot(n, wo);
    #if transmission_dispersion
    let through = select(seen_through(m, x, n, wo, m.layers.ior), seen_through_dispersed(m, x, n, wo), m.layers.dispersion > 0.0);
    #else
    let through = seen_through(m, x, n, wo, m.layers.ior);
    #endif
    var weight = thin_wall_weight(m, cos_o);
    #if transmission_exit
    // A volume's light leaves through a second interface, whose
    // transmittance is the entry's for a slab or a sphere (reciprocity:
    // the angle inside is the entry's refracted one), so 1 − max₃ F(μ_o)
    // again (shading.transmission_exit; the reference follows the exit
    // exactly, and its internal reflections, which this leaves out).
    weight *= select(1.0, interface_transmittance(m.layers, cos_o), m.layers.thickness > 0.0);
    #endif
    weight = select(weight, 0.0, cos_o <= 0.0);
    return through * m.base_color * weight;
}
