//! The `f64` reference of every reflectance model: the truth the WGSL in
//! `shaders/brdf/` is checked against. Same families, same function names,
//! same argument order as the WGSL, so one grep finds both homes.
//!
//! [`eval`] is the CPU twin of the per-variant `brdf_*` functions that
//! `gpu::shader_gen` generates: the same terms, called in the same order.

pub mod fresnel;
pub mod lambert;
pub mod microfacet;
pub mod phong;
pub mod ward;

use super::{Distribution, Fresnel, Geometry, Material, ReflectanceModel};
use crate::base::Rgb;
pub use crate::base::frame::{SurfaceFrame, any_tangent};
use glam::DVec3;

/// Lower bound for the cosines the lecture's forms divide by (`I·N`):
/// cos θ = 1e-6 is θ = 89.99994°. It keeps `f_r` finite (≤ k_s · 10⁶) where
/// the formula as written diverges; `f_r · cos θ_i` is unaffected above it.
pub const COS_FLOOR: f64 = 1e-6;

/// `f_r` of `material` for `N·I > 0`, `N·V > 0` (checked by the caller,
/// [`Material::f_r`]). The mirror's Dirac lobe is not a function value:
/// only its diffuse part is returned here (see [`mirror_reflectance`]).
pub fn eval(m: &Material, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
    let n = frame.n;
    let diffuse = lambert::lambert(m.k_d);
    let specular = match m.model {
        ReflectanceModel::Lambert | ReflectanceModel::Mirror => return diffuse,
        ReflectanceModel::Phong => Rgb::splat(phong::phong_lecture(m.k_e, n, wi, wo)),
        ReflectanceModel::PhongNormalized => Rgb::splat(phong::phong_normalized(m.k_e, n, wi, wo)),
        ReflectanceModel::BlinnPhong => Rgb::splat(phong::blinn_phong_lecture(m.k_e, n, wi, wo)),
        ReflectanceModel::BlinnPhongNormalized => {
            Rgb::splat(phong::blinn_phong_normalized(m.k_e, n, wi, wo))
        }
        ReflectanceModel::Ward => Rgb::splat(ward::ward_isotropic(m.sigma_x, n, wi, wo)),
        ReflectanceModel::WardAnisotropic => Rgb::splat(ward::ward_anisotropic(
            m.sigma_x, m.sigma_y, n, frame.t, frame.b, wi, wo,
        )),
        ReflectanceModel::CookTorrance => cook_torrance(m, wi, wo, n),
    };
    diffuse + m.k_s * specular
}

/// The Cook-Torrance specular lobe `D·G·F / (c (N·V)(N·I))` (lecture:
/// "Cook-Torrance Specular Term"), terms chosen by the material.
pub fn cook_torrance(m: &Material, wi: DVec3, wo: DVec3, n: DVec3) -> Rgb {
    let h = microfacet::half_vector(wi, wo);
    let cos_i = n.dot(wi);
    let cos_o = n.dot(wo);
    let cos_h = n.dot(h);
    let sin2_h = microfacet::sin2_between(n, h);
    let cos_ih = wi.dot(h);
    let cos_oh = wo.dot(h);
    let d = distribution(m.distribution, m.roughness, cos_h, sin2_h);
    let g = geometry(
        m.geometry,
        m.distribution,
        m.roughness,
        cos_h,
        cos_i,
        cos_o,
        cos_ih,
        cos_oh,
    );
    let f = fresnel(m, cos_ih);
    microfacet::cook_torrance_specular(d, g, f, cos_i, cos_o, m.denominator.factor())
}

/// `D(θ_h)` of the chosen distribution, from `cos θ_h` and `sin² θ_h`.
pub fn distribution(d: Distribution, roughness: f64, cos_h: f64, sin2_h: f64) -> f64 {
    match d {
        Distribution::Beckmann => microfacet::d_beckmann(roughness, cos_h, sin2_h),
        Distribution::Blinn => {
            microfacet::d_blinn_lecture(microfacet::blinn_exponent(roughness), cos_h, sin2_h)
        }
        Distribution::BlinnNormalized => {
            microfacet::d_blinn_normalized(microfacet::blinn_exponent(roughness), cos_h, sin2_h)
        }
        Distribution::Gaussian => microfacet::d_gaussian_lecture(roughness, cos_h, sin2_h),
        Distribution::GaussianNormalized => microfacet::d_gaussian_normalized(
            roughness,
            cos_h,
            sin2_h,
            microfacet::gaussian_normalization(roughness),
        ),
        Distribution::Ggx => microfacet::d_ggx(roughness, cos_h, sin2_h),
    }
}

/// The Beckmann slope Smith's G1 uses for a distribution: GGX has its own
/// G1; Blinn and Gaussian use Beckmann's with a matched slope.
pub fn smith_beckmann_slope(d: Distribution, roughness: f64) -> f64 {
    match d {
        Distribution::Beckmann | Distribution::Ggx => roughness,
        Distribution::Blinn | Distribution::BlinnNormalized => {
            microfacet::beckmann_slope_of_blinn(microfacet::blinn_exponent(roughness))
        }
        Distribution::Gaussian | Distribution::GaussianNormalized => {
            microfacet::beckmann_slope_of_gaussian(roughness)
        }
    }
}

/// `G` of the chosen geometry term.
#[allow(clippy::too_many_arguments)]
pub fn geometry(
    g: Geometry,
    d: Distribution,
    roughness: f64,
    cos_h: f64,
    cos_i: f64,
    cos_o: f64,
    cos_ih: f64,
    cos_oh: f64,
) -> f64 {
    match g {
        Geometry::None => 1.0,
        Geometry::VGroove => microfacet::g_vgroove(cos_h, cos_o, cos_i, cos_oh),
        Geometry::Smith if d == Distribution::Ggx => {
            microfacet::g1_ggx(roughness, cos_i, cos_ih)
                * microfacet::g1_ggx(roughness, cos_o, cos_oh)
        }
        Geometry::Smith => {
            let slope = smith_beckmann_slope(d, roughness);
            microfacet::g1_beckmann(slope, cos_i, cos_ih)
                * microfacet::g1_beckmann(slope, cos_o, cos_oh)
        }
    }
}

/// `F(cos θ)` of the material's Fresnel choice, `cos θ = I·H` (or `V·N`
/// for the mirror).
pub fn fresnel(m: &Material, cos_theta: f64) -> Rgb {
    match m.fresnel {
        Fresnel::Conductor => fresnel::fresnel_conductor(cos_theta, m.eta, m.kappa),
        Fresnel::ConductorLecture => fresnel::fresnel_conductor_lecture(cos_theta, m.eta, m.kappa),
        Fresnel::Dielectric => Rgb::splat(fresnel::fresnel_dielectric(cos_theta, m.eta_i, m.eta_t)),
        Fresnel::Schlick => {
            fresnel::fresnel_schlick(cos_theta, fresnel::f0_conductor(m.eta, m.kappa))
        }
        Fresnel::None => Rgb::ONE,
    }
}

/// The ideal mirror's reflectance `ρ_s(θ) = k_s · F(cos θ)` (lecture:
/// "Mirror BRDF"), `cos θ = N·V`; zero below the horizon (one-sided).
pub fn mirror_reflectance(m: &Material, cos_theta: f64) -> Rgb {
    if cos_theta <= 0.0 {
        return Rgb::ZERO;
    }
    m.k_s * fresnel(m, cos_theta)
}
