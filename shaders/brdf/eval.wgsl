// A material's BRDF: its model's lobe over the Lambert base, the
// Cook-Torrance terms it chose, the mirror's reflectance.
// f64 twin: src/material/brdf/mod.rs (same functions, same arms, same order).
// Each model's arm (and its helpers) is compiled only when the scene uses
// the model (`#if MODEL`), each term's arm only when some material uses
// the term (`#if distribution=ggx`, ...): the compiler reads no unused
// function. Which arm and which terms run are the pipeline constants of
// shaders/brdf/variant.wgsl.

fn eval_brdf(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    let n = frame.n;
    switch brdf_model(m) {
        #if lambert
        case MODEL_LAMBERT: { return lambert(m.k_d); }
        #endif
        #if mirror
        case MODEL_MIRROR: { return lambert(m.k_d); }
        #endif
        #if phong
        case MODEL_PHONG: { return lambert(m.k_d) + m.k_s * phong_lecture(m.k_e, n, wi, wo); }
        #endif
        #if phong-normalized
        case MODEL_PHONG_NORMALIZED: { return lambert(m.k_d) + m.k_s * phong_normalized(m.k_e, n, wi, wo); }
        #endif
        #if blinn-phong
        case MODEL_BLINN_PHONG: { return lambert(m.k_d) + m.k_s * blinn_phong_lecture(m.k_e, n, wi, wo); }
        #endif
        #if blinn-phong-normalized
        case MODEL_BLINN_PHONG_NORMALIZED: { return lambert(m.k_d) + m.k_s * blinn_phong_normalized(m.k_e, n, wi, wo); }
        #endif
        #if ward
        case MODEL_WARD: { return lambert(m.k_d) + m.k_s * ward_isotropic(m.sigma_x, n, wi, wo); }
        #endif
        #if ward-anisotropic
        case MODEL_WARD_ANISOTROPIC: { return lambert(m.k_d) + m.k_s * ward_anisotropic(m.sigma_x, m.sigma_y, n, frame.t, frame.b, wi, wo); }
        #endif
        #if cook-torrance
        case MODEL_COOK_TORRANCE: {
            var specular = cook_torrance(m, wi, wo, n);
            // Energy compensation (brdf/energy.wgsl): F(1) is computed
            // only in scenes that use it.
            #if energy_compensation
            specular *= ms_factor(fresnel(m, 1.0), ms_ratio(m.lobe.x, ms_ggx_alpha(m), dot(n, wo)));
            #endif
            return lambert(m.k_d) + m.k_s * specular;
        }
        #endif
        #if oren-nayar
        case MODEL_OREN_NAYAR: { return oren_nayar_qualitative(m.k_d, oren_nayar_terms(m.lobe), oren_nayar_angles(n, wi, wo)); }
        #endif
        #if oren-nayar-full
        case MODEL_OREN_NAYAR_FULL: { return oren_nayar_full(m.k_d, oren_nayar_terms(m.lobe), oren_nayar_angles(n, wi, wo)); }
        #endif
        #if measured
        case MODEL_MEASURED: { return measured_f_r(m, wi, wo, frame); }
        #endif
        #if gltf-pbr
        case MODEL_GLTF_PBR: {
            let ms = ms_ratio(m.lobe.x, m.roughness * m.roughness, dot(n, wo));
            #if gltf_layers
            // The layers (shaders/brdf/gltf_layers/), where a drawn
            // material has one; the core otherwise.
            return gltf_layered(m.base_color, m.metallic, m.roughness, ms, m.layers, frame, wi, wo);
            #else
            return gltf_pbr(m.base_color, m.metallic, m.roughness, ms, n, wi, wo);
            #endif
        }
        #endif
        #if abc
        case MODEL_ABC: { return lambert(m.k_d) + m.k_s * abc_specular(m.lobe.x, m.lobe.y, m.eta_i, m.eta_t, n, wi, wo); }
        #endif
        #if unlit
        case MODEL_UNLIT: { return unlit_f_r(); }
        #endif
        default: { return vec3<f32>(0.0); }
    }
}

#if cook-torrance
// The Cook-Torrance specular lobe D·G·F / (c (N·V)(N·I)) (lecture:
// "Cook-Torrance Specular Term"), terms chosen by the material.
fn cook_torrance(m: Material, wi: vec3<f32>, wo: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let h = half_vector(wi, wo);
    let cos_i = dot(n, wi);
    let cos_o = dot(n, wo);
    let cos_h = dot(n, h);
    let sin2_h = sin2_between(n, h);
    let cos_ih = dot(wi, h);
    let cos_oh = dot(wo, h);
    let d = distribution(m, cos_h, sin2_h);
    let g = geometry(m, cos_h, cos_i, cos_o, cos_ih, cos_oh);
    let f = fresnel(m, cos_ih);
    return cook_torrance_specular(d, g, f, cos_i, cos_o, denominator(m));
}

// D(θ_h) of the chosen distribution, from cos θ_h and sin² θ_h. The Blinn
// exponent and the Gaussian normalization come from the CPU (blinn_e,
// d_norm: see d_blinn_lecture).
fn distribution(m: Material, cos_h: f32, sin2_h: f32) -> f32 {
    switch brdf_distribution(m) {
        #if distribution=beckmann
        case DISTRIBUTION_BECKMANN: { return d_beckmann(m.roughness, cos_h, sin2_h); }
        #endif
        #if distribution=blinn
        case DISTRIBUTION_BLINN: { return d_blinn_lecture(m.blinn_e, cos_h, sin2_h); }
        #endif
        #if distribution=blinn-normalized
        case DISTRIBUTION_BLINN_NORMALIZED: { return d_blinn_normalized(m.blinn_e, cos_h, sin2_h); }
        #endif
        #if distribution=gaussian
        case DISTRIBUTION_GAUSSIAN: { return d_gaussian_lecture(m.roughness, cos_h, sin2_h); }
        #endif
        #if distribution=gaussian-normalized
        case DISTRIBUTION_GAUSSIAN_NORMALIZED: { return d_gaussian_normalized(m.roughness, cos_h, sin2_h, m.d_norm); }
        #endif
        #if distribution=ggx
        case DISTRIBUTION_GGX: { return d_ggx(m.roughness, cos_h, sin2_h); }
        #endif
        default: { return 0.0; }
    }
}

// The Beckmann slope Smith's G1 uses for a distribution: GGX has its own
// G1; Blinn and Gaussian use Beckmann's with a matched slope.
fn smith_beckmann_slope(m: Material) -> f32 {
    switch brdf_distribution(m) {
        #if distribution=blinn || distribution=blinn-normalized
        case DISTRIBUTION_BLINN, DISTRIBUTION_BLINN_NORMALIZED: { return beckmann_slope_of_blinn(m.blinn_e); }
        #endif
        #if distribution=gaussian || distribution=gaussian-normalized
        case DISTRIBUTION_GAUSSIAN, DISTRIBUTION_GAUSSIAN_NORMALIZED: { return beckmann_slope_of_gaussian(m.roughness); }
        #endif
        case DISTRIBUTION_BECKMANN, DISTRIBUTION_GGX, default: { return m.roughness; }
    }
}

// G of the chosen geometry term.
fn geometry(m: Material, cos_h: f32, cos_i: f32, cos_o: f32, cos_ih: f32, cos_oh: f32) -> f32 {
    switch brdf_geometry(m) {
        #if geometry=v-groove
        case GEOMETRY_V_GROOVE: { return g_vgroove(cos_h, cos_o, cos_i, cos_oh); }
        #endif
        #if geometry=smith
        case GEOMETRY_SMITH: {
            #if distribution=ggx
            if brdf_distribution(m) == DISTRIBUTION_GGX {
                return g1_ggx(m.roughness, cos_i, cos_ih) * g1_ggx(m.roughness, cos_o, cos_oh);
            }
            #endif
            let slope = smith_beckmann_slope(m);
            #if smith_beckmann_rational
            return g1_beckmann_rational(slope, cos_i, cos_ih) * g1_beckmann_rational(slope, cos_o, cos_oh);
            #else
            return g1_beckmann(slope, cos_i, cos_ih) * g1_beckmann(slope, cos_o, cos_oh);
            #endif
        }
        #endif
        #if geometry=smith-correlated
        case GEOMETRY_SMITH_CORRELATED: {
            #if distribution=ggx
            if brdf_distribution(m) == DISTRIBUTION_GGX {
                return g_smith_correlated(lambda_ggx(m.roughness, cos_i), lambda_ggx(m.roughness, cos_o), cos_i, cos_o, cos_ih, cos_oh);
            }
            #endif
            let slope = smith_beckmann_slope(m);
            #if smith_beckmann_rational
            return g_smith_correlated(lambda_beckmann_rational(slope, cos_i), lambda_beckmann_rational(slope, cos_o), cos_i, cos_o, cos_ih, cos_oh);
            #else
            return g_smith_correlated(lambda_beckmann(slope, cos_i), lambda_beckmann(slope, cos_o), cos_i, cos_o, cos_ih, cos_oh);
            #endif
        }
        #endif
        case GEOMETRY_NONE, default: { return 1.0; }
    }
}

// The denominator's factor c: 4 (microfacet standard) or π (the lecture).
fn denominator(m: Material) -> f32 {
    switch brdf_denominator(m) {
        case DENOMINATOR_LECTURE: { return PI; }
        case DENOMINATOR_MICROFACET, default: { return 4.0; }
    }
}
#endif

#if cook-torrance || mirror
// F(cos θ) of the material's Fresnel choice, cos θ = I·H (or V·N for the
// mirror).
fn fresnel(m: Material, cos_theta: f32) -> vec3<f32> {
    switch brdf_fresnel(m) {
        #if fresnel=conductor
        case FRESNEL_CONDUCTOR: { return fresnel_conductor(cos_theta, m.eta, m.kappa); }
        #endif
        #if fresnel=conductor-lecture
        case FRESNEL_CONDUCTOR_LECTURE: { return fresnel_conductor_lecture(cos_theta, m.eta, m.kappa); }
        #endif
        #if fresnel=dielectric
        case FRESNEL_DIELECTRIC: { return vec3<f32>(fresnel_dielectric(cos_theta, m.eta_i, m.eta_t)); }
        #endif
        #if fresnel=schlick
        case FRESNEL_SCHLICK: { return fresnel_schlick(cos_theta, f0_conductor(m.eta, m.kappa)); }
        #endif
        case FRESNEL_NONE, default: { return vec3<f32>(1.0); }
    }
}
#endif

#if mirror
// The ideal mirror's reflectance ρ_s(θ) = k_s · F(cos θ) (lecture: "Mirror
// BRDF"), cos θ = N·V; zero below the horizon (one-sided), and zero for
// every other model (they reflect no environment).
fn mirror_reflectance(m: Material, cos_theta: f32) -> vec3<f32> {
    if brdf_model(m) != MODEL_MIRROR {
        return vec3<f32>(0.0);
    }
    if cos_theta <= 0.0 {
        return vec3<f32>(0.0);
    }
    return m.k_s * fresnel(m, cos_theta);
}
#endif
