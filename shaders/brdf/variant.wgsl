// Which BRDF a pipeline draws: a model and, for Cook-Torrance and the
// mirror, its terms, as pipeline-overridable constants. Each is either a
// code (MODEL_*, DISTRIBUTION_*, GEOMETRY_*, FRESNEL_*, DENOMINATOR_*,
// generated from the Rust enums' order by src/gpu/shader_gen/specialization.rs)
// or FROM_MATERIAL: then the material's packed `variant` decides at run
// time (an uber shader). Why constants: a software rasterizer runs every
// arm of a run-time `switch` for every pixel, so a scene of a glossy
// sphere on a Lambert floor paid for Cook-Torrance on every floor pixel;
// with a constant, the compiler keeps one arm. A module's defaults
// (BRDF_*_DEFAULT, generated) are its one variant when the scene has one,
// else FROM_MATERIAL; a scene of several variants draws each material's
// batch with a pipeline that sets all five (src/gpu/prepared.rs).
const FROM_MATERIAL: u32 = 0xffffffffu;

override BRDF_MODEL: u32 = BRDF_MODEL_DEFAULT;
override BRDF_DISTRIBUTION: u32 = BRDF_DISTRIBUTION_DEFAULT;
override BRDF_GEOMETRY: u32 = BRDF_GEOMETRY_DEFAULT;
override BRDF_FRESNEL: u32 = BRDF_FRESNEL_DEFAULT;
override BRDF_DENOMINATOR: u32 = BRDF_DENOMINATOR_DEFAULT;

// The material's model: bits 0-7 of `variant`.
fn brdf_model(m: Material) -> u32 {
    if BRDF_MODEL == FROM_MATERIAL {
        return m.variant & 0xffu;
    }
    return BRDF_MODEL;
}

// Cook-Torrance's D: bits 8-11.
fn brdf_distribution(m: Material) -> u32 {
    if BRDF_DISTRIBUTION == FROM_MATERIAL {
        return (m.variant >> 8u) & 0xfu;
    }
    return BRDF_DISTRIBUTION;
}

// Cook-Torrance's G: bits 12-15.
fn brdf_geometry(m: Material) -> u32 {
    if BRDF_GEOMETRY == FROM_MATERIAL {
        return (m.variant >> 12u) & 0xfu;
    }
    return BRDF_GEOMETRY;
}

// Cook-Torrance's and the mirror's F: bits 16-19.
fn brdf_fresnel(m: Material) -> u32 {
    if BRDF_FRESNEL == FROM_MATERIAL {
        return (m.variant >> 16u) & 0xfu;
    }
    return BRDF_FRESNEL;
}

// Cook-Torrance's denominator: bits 20-23.
fn brdf_denominator(m: Material) -> u32 {
    if BRDF_DENOMINATOR == FROM_MATERIAL {
        return (m.variant >> 20u) & 0xfu;
    }
    return BRDF_DENOMINATOR;
}
