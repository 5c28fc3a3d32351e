//! The `f64` reference of every reflectance model: the truth the WGSL in
//! `shaders/brdf/` is checked against. Same families, same function names,
//! same argument order as the WGSL, so one grep finds both homes.
//!
//! [`eval`] is the CPU twin of the per-variant `brdf_*` functions that
//! `gpu::shader_gen` generates: the same terms, called in the same order.

pub mod abc;
pub mod dfg;
pub mod energy;
pub mod fresnel;
pub mod fresnel_table;
pub mod gltf_layers;
pub mod gltf_pbr;
pub mod lambert;
pub mod microfacet;
pub mod oren_nayar;
pub mod phong;
pub mod unlit;
mod value;
pub mod ward;

pub use phong::COS_FLOOR;
pub use value::{
    Brdf, CookTorrance, DistributionTerm, FresnelTerm, GeometryTerm, ShaderParams, Specular,
    smith_beckmann_slope,
};

use super::Material;
use super::layers::LayerTerm;
use crate::base::Rgb;
pub use crate::base::frame::{SurfaceFrame, any_tangent};
use glam::DVec3;

impl Brdf {
    /// The BRDF `f_r(ω_i, ω_o)` [1/sr] in the shading frame `frame`, one
    /// sided (zero where `N·I ≤ 0` or `N·V ≤ 0`): what
    /// [`Material::f_r`] returns, from a value built once. Building it
    /// is not free (a normalized Gaussian sums a 1000-term series), so a
    /// loop over directions builds it once with [`Material::brdf`] and
    /// calls this.
    pub fn f_r(&self, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        if frame.n.dot(wi) <= 0.0 || frame.n.dot(wo) <= 0.0 {
            return Rgb::ZERO;
        }
        eval(self, wi, wo, frame)
    }

    /// One term of [`Self::f_r`] ([`eval_term`]), one-sided as it.
    pub fn f_r_term(&self, term: LayerTerm, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        if frame.n.dot(wi) <= 0.0 || frame.n.dot(wo) <= 0.0 {
            return Rgb::ZERO;
        }
        eval_term(self, term, wi, wo, frame)
    }
}

/// `f_r` of `brdf` for `N·I > 0`, `N·V > 0` (checked by the caller,
/// [`Material::f_r`]). The mirror's Dirac lobe is not a function value:
/// only its diffuse part is returned here (see [`mirror_reflectance`]).
///
/// One arm per model: a new model adds its [`Specular`] variant and its arm
/// here (see [`crate::material::table`]).
pub fn eval(brdf: &Brdf, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
    let n = frame.n;
    let diffuse = lambert::lambert(brdf.k_d);
    let specular = match brdf.specular {
        Specular::None | Specular::Mirror(_) => return diffuse,
        Specular::Phong { k_e } => Rgb::splat(phong::phong_lecture(k_e, n, wi, wo)),
        Specular::PhongNormalized { k_e } => Rgb::splat(phong::phong_normalized(k_e, n, wi, wo)),
        Specular::BlinnPhong { k_e } => Rgb::splat(phong::blinn_phong_lecture(k_e, n, wi, wo)),
        Specular::BlinnPhongNormalized { k_e } => {
            Rgb::splat(phong::blinn_phong_normalized(k_e, n, wi, wo))
        }
        Specular::Ward { sigma } => Rgb::splat(ward::ward_isotropic(sigma, n, wi, wo)),
        Specular::WardAnisotropic { sigma_x, sigma_y } => Rgb::splat(ward::ward_anisotropic(
            sigma_x, sigma_y, n, frame.t, frame.b, wi, wo,
        )),
        Specular::CookTorrance(ct) => {
            let ms = compensation_ratio(brdf, dfg::ggx_alpha(ct.d), n.dot(wo));
            cook_torrance(&ct, wi, wo, n) * energy::ms_factor(ct.f.eval(1.0), ms)
        }
        Specular::OrenNayar(t) => {
            return oren_nayar::oren_nayar_qualitative(
                brdf.k_d,
                &t,
                &oren_nayar::oren_nayar_angles(n, wi, wo),
            );
        }
        Specular::OrenNayarFull(t) => {
            return oren_nayar::oren_nayar_full(
                brdf.k_d,
                &t,
                &oren_nayar::oren_nayar_angles(n, wi, wo),
            );
        }
        Specular::Measured(m) => return m.f_r(wi, wo, frame),
        Specular::GltfPbr {
            base_color,
            metallic,
            roughness,
            layers,
        } => {
            let ms = compensation_ratio(brdf, roughness * roughness, n.dot(wo));
            return gltf_layers::stack::gltf_layered(
                base_color, metallic, roughness, ms, &layers, frame, wi, wo,
            );
        }
        Specular::Abc {
            a,
            b,
            c,
            eta_i,
            eta_t,
        } => a * abc::abc_specular(b, c, eta_i, eta_t, n, wi, wo),
        Specular::Unlit { .. } => return unlit::unlit_f_r(),
    };
    diffuse + brdf.k_s * specular
}

/// One term of `brdf`'s `f_r` ([`LayerTerm`]) for `N·I > 0`, `N·V > 0`:
/// a `gltf-pbr` material's layer apart
/// ([`gltf_layers::stack::gltf_layer_term`], the sheen scaled by the exact
/// albedos as in [`eval`]); every other model has no layers, so its base
/// is the whole and its sheen and clearcoat terms are 0. The explorer's
/// plots and albedo per layer (`crate::explore`).
pub fn eval_term(brdf: &Brdf, term: LayerTerm, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
    match (brdf.specular, term) {
        (
            Specular::GltfPbr {
                base_color,
                metallic,
                roughness,
                layers,
            },
            _,
        ) => {
            let n = frame.n;
            let ms = compensation_ratio(brdf, roughness * roughness, n.dot(wo));
            // Only the whole and the base read the sheen's albedos (its
            // scaling of the base): each is an integral.
            let (e_o, e_i) = match term {
                LayerTerm::All | LayerTerm::Base => {
                    gltf_layers::stack::sheen_albedos(&layers, n.dot(wi), n.dot(wo))
                }
                LayerTerm::Sheen | LayerTerm::Clearcoat => (0.0, 0.0),
            };
            gltf_layers::stack::gltf_layer_term(
                term, base_color, metallic, roughness, ms, &layers, e_o, e_i, frame, wi, wo,
            )
        }
        (_, LayerTerm::All | LayerTerm::Base) => eval(brdf, wi, wo, frame),
        (_, LayerTerm::Sheen | LayerTerm::Clearcoat) => Rgb::ZERO,
    }
}

/// `(1 − E)/E` of energy compensation at the lobe's GGX α and `N·V`
/// ([`energy::ms_ratio`]), 0 without it (the lobe is then exactly the
/// contract's). Twin: `ms_ratio` times the material's `lobe.x` in WGSL.
fn compensation_ratio(brdf: &Brdf, alpha: f64, cos_o: f64) -> f64 {
    if brdf.energy_compensation {
        energy::ms_ratio(alpha, cos_o)
    } else {
        0.0
    }
}

/// The Cook-Torrance specular lobe `D·G·F / (c (N·V)(N·I))` (lecture:
/// "Cook-Torrance Specular Term"), terms chosen by the material.
pub fn cook_torrance(ct: &CookTorrance, wi: DVec3, wo: DVec3, n: DVec3) -> Rgb {
    let h = microfacet::half_vector(wi, wo);
    let cos_i = n.dot(wi);
    let cos_o = n.dot(wo);
    let cos_h = n.dot(h);
    let sin2_h = microfacet::sin2_between(n, h);
    let cos_ih = wi.dot(h);
    let cos_oh = wo.dot(h);
    let d = ct.d.eval(cos_h, sin2_h);
    let g = ct.g.eval(cos_h, cos_i, cos_o, cos_ih, cos_oh);
    let f = ct.f.eval(cos_ih);
    microfacet::cook_torrance_specular(d, g, f, cos_i, cos_o, ct.denominator)
}

/// The ideal mirror's reflectance `ρ_s(θ) = k_s · F(cos θ)` (lecture:
/// "Mirror BRDF"), `cos θ = N·V`; zero below the horizon (one-sided) and
/// for every model but the mirror.
pub fn mirror_reflectance(m: &Material, cos_theta: f64) -> Rgb {
    if cos_theta <= 0.0 {
        return Rgb::ZERO;
    }
    match m.brdf() {
        Brdf {
            k_s,
            specular: Specular::Mirror(f),
            ..
        } => k_s * f.eval(cos_theta),
        _ => Rgb::ZERO,
    }
}
