//! The selectable terms of Cook-Torrance (and the mirror's Fresnel), with
//! the contract's names (`base::named_enum!` keeps name, parse and list in
//! one place).

use crate::base::named_enum;

named_enum!(
    /// Microfacet distribution `D` (lecture: "Microfacet Distribution Functions").
    Distribution, "distribution" {
        /// Beckmann, normalized; `roughness` is the RMS slope m.
        Beckmann = "beckmann",
        /// The lecture's Blinn `cos^(−ln2/ln cos m)`, as written: peak 1, not
        /// normalized; `roughness` is the angle m (radians) where D = ½.
        Blinn = "blinn",
        /// Blinn's lobe normalized so that ∫ D cosθ_h dω_h = 1.
        BlinnNormalized = "blinn-normalized",
        /// The lecture's Gaussian (Torrance-Sparrow) `exp(−ln2 (α/m)²)`, as
        /// written: peak 1, not normalized; `roughness` is the angle m.
        Gaussian = "gaussian",
        /// The Gaussian lobe normalized so that ∫ D cosθ_h dω_h = 1.
        GaussianNormalized = "gaussian-normalized",
        /// GGX / Trowbridge-Reitz, normalized; `roughness` is α.
        Ggx = "ggx",
    }
);

named_enum!(
    /// Geometric attenuation `G` (lecture: "Geometric Attenuation Factor").
    Geometry, "geometry" {
        /// The lecture's V-groove `min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·I)/(V·H))`.
        VGroove = "v-groove",
        /// Separable Smith `G1(I)·G1(V)` matched to the distribution.
        Smith = "smith",
        /// `G = 1`.
        None = "none",
        /// Height-correlated Smith `1 / (1 + Λ(I) + Λ(V))` (Heitz 2014,
        /// "Understanding the Masking-Shadowing Function", eq. 99), Λ matched
        /// to the distribution as `smith`'s G1; glTF 2.0's `Vis` for GGX.
        SmithCorrelated = "smith-correlated",
    }
);

named_enum!(
    /// Fresnel term `F`, evaluated at the microfacet angle `cos θ = I·H`.
    Fresnel, "fresnel" {
        /// Exact unpolarized Fresnel of a conductor with index η + iκ.
        Conductor = "conductor",
        /// The lecture's approximation of r∥², r⊥² for conductors.
        ConductorLecture = "conductor-lecture",
        /// Exact unpolarized Fresnel of a dielectric interface η_i → η_t.
        Dielectric = "dielectric",
        /// Schlick's approximation with F0 from η, κ (conductor).
        Schlick = "schlick",
        /// `F = 1`.
        None = "none",
    }
);

named_enum!(
    /// How the GPU evaluates Smith's `G1` and Λ for Beckmann (also the
    /// Blinn and Gaussian distributions' matched G1): `shading.smith_beckmann`,
    /// a knob of the GPU path only. The reference always evaluates the
    /// exact erf form (`brdf::microfacet::g1_beckmann`).
    #[derive(Default)]
    SmithBeckmann, "smith_beckmann" {
        /// The exact form with an f32 `erfc` (Abramowitz & Stegun 7.1.26):
        /// within `G1_BECKMANN_F32_ERROR` (7.5e-8 plus Vulkan's `exp`
        /// allowance) of the truth. The default.
        #[default]
        Erf = "erf",
        /// Walter et al. 2007's rational approximation: up to 0.313 % per
        /// `G1` (`G1_BECKMANN_RATIONAL_ERROR`), 0.63 % per `G`; no `exp`.
        Rational = "rational",
    }
);

named_enum!(
    /// The Cook-Torrance denominator.
    Denominator, "denominator" {
        /// `4 (N·V)(N·I)`: the microfacet-standard normalization (default).
        Microfacet = "microfacet",
        /// `π (N·V)(N·I)`: as the lecture writes it.
        Lecture = "lecture",
    }
);

impl Denominator {
    /// The constant in front of `(N·V)(N·I)`.
    pub fn factor(self) -> f64 {
        match self {
            Denominator::Microfacet => 4.0,
            Denominator::Lecture => std::f64::consts::PI,
        }
    }
}
