//! A material's BRDF as a typed value: per model exactly the parameters it
//! reads, and the constants derived from them (Blinn's exponent, the
//! normalization of the Gaussian, the Beckmann slope Smith's G matches to
//! a distribution, Schlick's F0) computed once, in `f64`.
//!
//! [`Material::brdf`](crate::material::Material::brdf) builds it (through
//! the model's row in [`crate::material::table`]); both the CPU reference
//! ([`super::eval`]) and the GPU upload ([`Brdf::shader_params`], read by
//! `gpu::layout::GpuMaterial::new`) consume it, so neither decides per
//! model what a material's fields mean.

use super::fresnel_table::FresnelTable;
use super::oren_nayar::OrenNayarTerms;
use super::{fresnel, microfacet};
use crate::base::Rgb;
use crate::material::measured::MeasuredBrdf;
use crate::material::{Denominator, Distribution, Fresnel, Geometry};

/// The BRDF `k_d/π + k_s · specular` of one material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brdf {
    /// Diffuse albedo (the Lambert term `k_d/π`, every model has it).
    pub k_d: Rgb,
    /// Weight of the specular term (the mirror's reflectance).
    pub k_s: Rgb,
    pub specular: Specular,
    /// Energy compensation of the microfacet lobes (`super::energy`; the
    /// material key `energy_compensation`): read by the gltf-pbr and
    /// Cook-Torrance arms only.
    pub energy_compensation: bool,
}

/// The specular term of each model, with what it reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Specular {
    /// Lambert: none.
    None,
    /// The lecture's Phong lobe (`phong::phong_lecture`).
    Phong { k_e: f64 },
    /// Normalized Phong (`phong::phong_normalized`).
    PhongNormalized { k_e: f64 },
    /// The lecture's Blinn-Phong lobe (`phong::blinn_phong_lecture`).
    BlinnPhong { k_e: f64 },
    /// Normalized Blinn-Phong (`phong::blinn_phong_normalized`).
    BlinnPhongNormalized { k_e: f64 },
    /// Ward, isotropic (`ward::ward_isotropic`).
    Ward { sigma: f64 },
    /// Ward, anisotropic (`ward::ward_anisotropic`).
    WardAnisotropic { sigma_x: f64, sigma_y: f64 },
    /// Cook-Torrance with its chosen terms.
    CookTorrance(CookTorrance),
    /// The ideal mirror: a Dirac lobe of reflectance `k_s · F(cos θ)`, not
    /// a function value ([`super::mirror_reflectance`]).
    Mirror(FresnelTerm),
    /// Oren-Nayar, qualitative (`oren_nayar::oren_nayar_qualitative`): it
    /// replaces the Lambert term (k_s is not read).
    OrenNayar(OrenNayarTerms),
    /// Oren-Nayar, full (`oren_nayar::oren_nayar_full`): it replaces the
    /// Lambert term.
    OrenNayarFull(OrenNayarTerms),
    /// A measured BRDF (`crate::material::measured`): it replaces the whole
    /// BRDF (k_d, k_s are not read).
    Measured(&'static MeasuredBrdf),
    /// glTF 2.0's metallic-roughness BRDF (`gltf_pbr::gltf_pbr`): the whole
    /// `f_r` (k_d and k_s are not read). `roughness` is glTF's perceptual
    /// roughness r; the GGX α is r², squared by the twins themselves (so a
    /// per-pixel roughness on the GPU is squared the same way).
    /// Its layers (`gltf_layers`: ior, specular, clearcoat, sheen,
    /// iridescence, anisotropy; all off at their defaults).
    GltfPbr {
        base_color: Rgb,
        metallic: f64,
        roughness: f64,
        layers: crate::material::layers::GltfLayers,
    },
    /// The ABC model (`abc::abc_specular`, Löw et al. 2012): `a` is the
    /// distribution's peak `A` per channel, `b`, `c` its shape, the
    /// dielectric Fresnel `η_i → η_t`.
    Abc {
        a: Rgb,
        b: f64,
        c: f64,
        eta_i: f64,
        eta_t: f64,
    },
    /// Unlit (`unlit::unlit_radiance`): no reflection (`f_r = 0`), the
    /// surface shows `base_color` as radiance.
    Unlit { base_color: Rgb },
}

/// Cook-Torrance's `D·G·F / (denominator (N·V)(N·I))` (lecture:
/// "Cook-Torrance Specular Term").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CookTorrance {
    pub d: DistributionTerm,
    pub g: GeometryTerm,
    pub f: FresnelTerm,
    /// The constant in front of `(N·V)(N·I)`: 4 or π ([`Denominator::factor`]).
    pub denominator: f64,
}

impl CookTorrance {
    pub fn new(
        distribution: Distribution,
        geometry: Geometry,
        fresnel: FresnelTerm,
        denominator: Denominator,
        roughness: f64,
    ) -> Self {
        CookTorrance {
            d: DistributionTerm::new(distribution, roughness),
            g: GeometryTerm::new(geometry, distribution, roughness),
            f: fresnel,
            denominator: denominator.factor(),
        }
    }
}

/// The microfacet distribution `D` with its parameter and derived constant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DistributionTerm {
    /// Beckmann, RMS slope `m`.
    Beckmann { m: f64 },
    /// The lecture's Blinn, by its exponent `e = blinn_exponent(m)`.
    Blinn { e: f64 },
    /// Blinn normalized, exponent `e`.
    BlinnNormalized { e: f64 },
    /// The lecture's Gaussian, angle `m`.
    Gaussian { m: f64 },
    /// The Gaussian normalized: angle `m`, `norm = gaussian_normalization(m)`.
    GaussianNormalized { m: f64, norm: f64 },
    /// GGX / Trowbridge-Reitz, `α`.
    Ggx { alpha: f64 },
}

impl DistributionTerm {
    /// `distribution` at `roughness` (see `Material::roughness`).
    pub fn new(distribution: Distribution, roughness: f64) -> Self {
        match distribution {
            Distribution::Beckmann => DistributionTerm::Beckmann { m: roughness },
            Distribution::Blinn => DistributionTerm::Blinn {
                e: microfacet::blinn_exponent(roughness),
            },
            Distribution::BlinnNormalized => DistributionTerm::BlinnNormalized {
                e: microfacet::blinn_exponent(roughness),
            },
            Distribution::Gaussian => DistributionTerm::Gaussian { m: roughness },
            Distribution::GaussianNormalized => DistributionTerm::GaussianNormalized {
                m: roughness,
                norm: microfacet::gaussian_normalization(roughness),
            },
            Distribution::Ggx => DistributionTerm::Ggx { alpha: roughness },
        }
    }

    /// `D(θ_h)` from `cos θ_h` and `sin² θ_h`.
    pub fn eval(self, cos_h: f64, sin2_h: f64) -> f64 {
        match self {
            DistributionTerm::Beckmann { m } => microfacet::d_beckmann(m, cos_h, sin2_h),
            DistributionTerm::Blinn { e } => microfacet::d_blinn_lecture(e, cos_h, sin2_h),
            DistributionTerm::BlinnNormalized { e } => {
                microfacet::d_blinn_normalized(e, cos_h, sin2_h)
            }
            DistributionTerm::Gaussian { m } => microfacet::d_gaussian_lecture(m, cos_h, sin2_h),
            DistributionTerm::GaussianNormalized { m, norm } => {
                microfacet::d_gaussian_normalized(m, cos_h, sin2_h, norm)
            }
            DistributionTerm::Ggx { alpha } => microfacet::d_ggx(alpha, cos_h, sin2_h),
        }
    }
}

/// Geometric attenuation `G`, Smith's matched to the distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeometryTerm {
    /// `G = 1`.
    None,
    /// The lecture's V-groove.
    VGroove,
    /// Smith with GGX's own `G1`, `α`.
    SmithGgx { alpha: f64 },
    /// Smith with Beckmann's `G1` at the slope matched to the distribution
    /// ([`smith_beckmann_slope`]).
    SmithBeckmann { slope: f64 },
    /// Height-correlated Smith with GGX's own Λ, `α`.
    SmithCorrelatedGgx { alpha: f64 },
    /// Height-correlated Smith with Beckmann's Λ at the matched slope.
    SmithCorrelatedBeckmann { slope: f64 },
}

impl GeometryTerm {
    pub fn new(geometry: Geometry, distribution: Distribution, roughness: f64) -> Self {
        match geometry {
            Geometry::None => GeometryTerm::None,
            Geometry::VGroove => GeometryTerm::VGroove,
            Geometry::Smith if distribution == Distribution::Ggx => {
                GeometryTerm::SmithGgx { alpha: roughness }
            }
            Geometry::Smith => GeometryTerm::SmithBeckmann {
                slope: smith_beckmann_slope(distribution, roughness),
            },
            Geometry::SmithCorrelated if distribution == Distribution::Ggx => {
                GeometryTerm::SmithCorrelatedGgx { alpha: roughness }
            }
            Geometry::SmithCorrelated => GeometryTerm::SmithCorrelatedBeckmann {
                slope: smith_beckmann_slope(distribution, roughness),
            },
        }
    }

    /// `G` from the cosines between N, H, I (`_i`) and V (`_o`).
    pub fn eval(self, cos_h: f64, cos_i: f64, cos_o: f64, cos_ih: f64, cos_oh: f64) -> f64 {
        match self {
            GeometryTerm::None => 1.0,
            GeometryTerm::VGroove => microfacet::g_vgroove(cos_h, cos_o, cos_i, cos_oh),
            GeometryTerm::SmithGgx { alpha } => {
                microfacet::g1_ggx(alpha, cos_i, cos_ih) * microfacet::g1_ggx(alpha, cos_o, cos_oh)
            }
            GeometryTerm::SmithBeckmann { slope } => {
                microfacet::g1_beckmann(slope, cos_i, cos_ih)
                    * microfacet::g1_beckmann(slope, cos_o, cos_oh)
            }
            GeometryTerm::SmithCorrelatedGgx { alpha } => microfacet::g_smith_correlated(
                microfacet::lambda_ggx(alpha, cos_i),
                microfacet::lambda_ggx(alpha, cos_o),
                cos_i,
                cos_o,
                cos_ih,
                cos_oh,
            ),
            GeometryTerm::SmithCorrelatedBeckmann { slope } => microfacet::g_smith_correlated(
                microfacet::lambda_beckmann(slope, cos_i),
                microfacet::lambda_beckmann(slope, cos_o),
                cos_i,
                cos_o,
                cos_ih,
                cos_oh,
            ),
        }
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

/// The Fresnel term `F(cos θ)` with the indices it reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelTerm {
    /// Exact conductor, `η + iκ`.
    Conductor { eta: Rgb, kappa: Rgb },
    /// The lecture's conductor approximation.
    ConductorLecture { eta: Rgb, kappa: Rgb },
    /// Exact dielectric `η_i → η_t`.
    Dielectric { eta_i: f64, eta_t: f64 },
    /// Schlick with `f0 = f0_conductor(η, κ)` (the GPU derives it from η, κ).
    Schlick { eta: Rgb, kappa: Rgb, f0: Rgb },
    /// A conductor's `F(cos θ)` from a table ([`super::fresnel_table`]):
    /// the reference's spectral metal (`crate::reference::brdf`), never
    /// built from a material's own fields. `η`, `κ` are the metal's
    /// three-channel preset, what the GPU twin reads in its place.
    Tabulated {
        eta: Rgb,
        kappa: Rgb,
        table: &'static FresnelTable,
    },
    /// `F = 1`.
    None,
}

impl FresnelTerm {
    /// `fresnel` with the material's indices.
    pub fn new(fresnel: Fresnel, eta: Rgb, kappa: Rgb, eta_i: f64, eta_t: f64) -> Self {
        match fresnel {
            Fresnel::Conductor => FresnelTerm::Conductor { eta, kappa },
            Fresnel::ConductorLecture => FresnelTerm::ConductorLecture { eta, kappa },
            Fresnel::Dielectric => FresnelTerm::Dielectric { eta_i, eta_t },
            Fresnel::Schlick => FresnelTerm::Schlick {
                eta,
                kappa,
                f0: fresnel::f0_conductor(eta, kappa),
            },
            Fresnel::None => FresnelTerm::None,
        }
    }

    /// `F(cos θ)`, `cos θ = I·H` (or `V·N` for the mirror).
    pub fn eval(self, cos_theta: f64) -> Rgb {
        match self {
            FresnelTerm::Conductor { eta, kappa } => {
                fresnel::fresnel_conductor(cos_theta, eta, kappa)
            }
            FresnelTerm::ConductorLecture { eta, kappa } => {
                fresnel::fresnel_conductor_lecture(cos_theta, eta, kappa)
            }
            FresnelTerm::Dielectric { eta_i, eta_t } => {
                Rgb::splat(fresnel::fresnel_dielectric(cos_theta, eta_i, eta_t))
            }
            FresnelTerm::Schlick { f0, .. } => fresnel::fresnel_schlick(cos_theta, f0),
            FresnelTerm::Tabulated { table, .. } => table.eval(cos_theta),
            FresnelTerm::None => Rgb::ONE,
        }
    }
}

/// What the WGSL twins read of a material (`Material` in
/// `shaders/common.wgsl`), in `f64`; what a model does not read stays 0.
/// `gpu::layout::GpuMaterial::new` rounds it to `f32` field by field.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShaderParams {
    pub k_d: Rgb,
    pub k_s: Rgb,
    pub k_e: f64,
    pub roughness: f64,
    pub sigma_x: f64,
    pub sigma_y: f64,
    pub eta: Rgb,
    pub kappa: Rgb,
    pub eta_i: f64,
    pub eta_t: f64,
    /// `gaussian_normalization(roughness)` (gaussian-normalized).
    pub d_norm: f64,
    /// `blinn_exponent(roughness)` (blinn, blinn-normalized): WGSL's `sin`
    /// is not accurate enough to derive it on the GPU (see
    /// `microfacet::d_blinn_lecture`).
    pub blinn_e: f64,
    /// A model's own constants, derived from its parameters once on the
    /// CPU, for a model the named fields above do not cover: the model's
    /// arm of [`Brdf::shader_params`] fills them and its WGSL twin reads
    /// `m.lobe` (and says what each component is), so a new model needs
    /// no change of the GPU layout.
    pub lobe: [f64; 4],
    /// gltf-pbr's base colour and metallic (its perceptual roughness is in
    /// `roughness`): named fields, not `lobe` constants, because textures
    /// and vertex colours multiply them per pixel on the GPU.
    pub base_color: Rgb,
    pub metallic: f64,
    /// gltf-pbr's layers (`gltf_layers`; the glTF defaults, all off, for
    /// every other model): named fields too, because textures multiply
    /// them per pixel.
    pub layers: crate::material::layers::GltfLayers,
}

impl Brdf {
    /// Whether it has a Dirac lobe ([`super::mirror_reflectance`]) beside
    /// its function value.
    pub fn is_dirac(&self) -> bool {
        matches!(self.specular, Specular::Mirror(_))
    }

    /// `lobe.x` of gltf-pbr and Cook-Torrance (which have no other lobe
    /// constants): 1 with energy compensation, 0 without; the WGSL
    /// multiplies `ms_ratio` by it (a select, not a branch: UNIFORM_BRANCHES
    /// in shaders/brdf/phong.wgsl).
    fn compensation_weight(&self) -> f64 {
        if self.energy_compensation { 1.0 } else { 0.0 }
    }

    /// The values the GPU twin of this BRDF reads.
    pub fn shader_params(&self) -> ShaderParams {
        let mut p = ShaderParams {
            k_d: self.k_d,
            k_s: self.k_s,
            ..ShaderParams::default()
        };
        match self.specular {
            Specular::None => {}
            Specular::Phong { k_e }
            | Specular::PhongNormalized { k_e }
            | Specular::BlinnPhong { k_e }
            | Specular::BlinnPhongNormalized { k_e } => p.k_e = k_e,
            Specular::Ward { sigma } => p.sigma_x = sigma,
            Specular::WardAnisotropic { sigma_x, sigma_y } => {
                (p.sigma_x, p.sigma_y) = (sigma_x, sigma_y);
            }
            Specular::CookTorrance(ct) => {
                match ct.d {
                    DistributionTerm::Beckmann { m } | DistributionTerm::Gaussian { m } => {
                        p.roughness = m
                    }
                    DistributionTerm::Ggx { alpha } => p.roughness = alpha,
                    DistributionTerm::Blinn { e } | DistributionTerm::BlinnNormalized { e } => {
                        p.blinn_e = e
                    }
                    DistributionTerm::GaussianNormalized { m, norm } => {
                        (p.roughness, p.d_norm) = (m, norm)
                    }
                }
                ct.f.write_params(&mut p);
                p.lobe[0] = self.compensation_weight();
            }
            Specular::Mirror(f) => f.write_params(&mut p),
            Specular::OrenNayar(t) | Specular::OrenNayarFull(t) => p.lobe = [t.a, t.b, t.c3, t.l2],
            // The table's place in the measured buffer is the GPU's
            // (`gpu::measured_tables`), written into `lobe` there.
            Specular::Measured(_) => {}
            // The layers' WGSL twins are shaders/brdf/gltf_layers/,
            // compiled where a drawn material uses a layer.
            Specular::GltfPbr {
                base_color,
                metallic,
                roughness,
                layers,
            } => {
                (p.base_color, p.metallic, p.roughness) = (base_color, metallic, roughness);
                p.layers = layers;
                p.lobe[0] = self.compensation_weight();
            }
            // The GPU's k_s is the lobe's whole weight k_s·A (a k_s texture
            // multiplies it per pixel as it multiplies k_s on the CPU);
            // lobe = (B, C, 0, 0).
            Specular::Abc {
                a,
                b,
                c,
                eta_i,
                eta_t,
            } => {
                p.k_s = self.k_s * a;
                p.lobe = [b, c, 0.0, 0.0];
                (p.eta_i, p.eta_t) = (eta_i, eta_t);
            }
            // A named field: textures and vertex colours multiply it per
            // pixel, as gltf-pbr's.
            Specular::Unlit { base_color } => p.base_color = base_color,
        }
        p
    }
}

impl FresnelTerm {
    fn write_params(self, p: &mut ShaderParams) {
        match self {
            FresnelTerm::Conductor { eta, kappa }
            | FresnelTerm::ConductorLecture { eta, kappa }
            | FresnelTerm::Schlick { eta, kappa, .. }
            | FresnelTerm::Tabulated { eta, kappa, .. } => (p.eta, p.kappa) = (eta, kappa),
            FresnelTerm::Dielectric { eta_i, eta_t } => (p.eta_i, p.eta_t) = (eta_i, eta_t),
            FresnelTerm::None => {}
        }
    }
}
