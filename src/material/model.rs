//! The closed set of reflectance models and their contract names.

use std::fmt;
use std::str::FromStr;

/// Every reflectance model gonio knows, by the contract's names. A material
/// picks one; the GPU compiles only the models (and terms) a scene uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ReflectanceModel {
    /// `f_r = k_d / π` (lecture: "Diffuse Reflection Model").
    Lambert,
    /// The lecture's Phong: `k_d/π + k_s (R(I)·V)^k_e / (I·N)`, as written
    /// (not normalized, not reciprocal).
    Phong,
    /// Normalized Phong: `k_d/π + k_s (k_e+2)/(2π) (R(I)·V)^k_e`
    /// (reciprocal, energy conserving).
    PhongNormalized,
    /// The lecture's Blinn-Phong: `k_d/π + k_s (H·N)^k_e / (I·N)`, as
    /// written (not normalized, not reciprocal).
    BlinnPhong,
    /// Normalized Blinn-Phong (reciprocal, energy conserving).
    BlinnPhongNormalized,
    /// Ward's isotropic model as the lecture writes it (σ = `sigma`).
    Ward,
    /// Ward's anisotropic model (σ_x along the tangent, σ_y along the bitangent).
    WardAnisotropic,
    /// Cook-Torrance: `k_d/π + k_s · D·G·F / (denominator (N·V)(N·I))`
    /// with selectable D, G, F and denominator.
    CookTorrance,
    /// An ideal mirror: a Dirac lobe of reflectance `k_s · F(cos θ)`; it
    /// reflects the environment and the discs of lights of finite size.
    Mirror,
}

impl ReflectanceModel {
    /// All models, in the contract's order.
    pub const ALL: [ReflectanceModel; 9] = [
        ReflectanceModel::Lambert,
        ReflectanceModel::Phong,
        ReflectanceModel::PhongNormalized,
        ReflectanceModel::BlinnPhong,
        ReflectanceModel::BlinnPhongNormalized,
        ReflectanceModel::Ward,
        ReflectanceModel::WardAnisotropic,
        ReflectanceModel::CookTorrance,
        ReflectanceModel::Mirror,
    ];

    /// The contract's name.
    pub fn name(self) -> &'static str {
        match self {
            ReflectanceModel::Lambert => "lambert",
            ReflectanceModel::Phong => "phong",
            ReflectanceModel::PhongNormalized => "phong-normalized",
            ReflectanceModel::BlinnPhong => "blinn-phong",
            ReflectanceModel::BlinnPhongNormalized => "blinn-phong-normalized",
            ReflectanceModel::Ward => "ward",
            ReflectanceModel::WardAnisotropic => "ward-anisotropic",
            ReflectanceModel::CookTorrance => "cook-torrance",
            ReflectanceModel::Mirror => "mirror",
        }
    }

    /// Whether the model needs a tangent frame (anisotropy).
    pub fn needs_tangents(self) -> bool {
        self == ReflectanceModel::WardAnisotropic
    }
}

impl fmt::Display for ReflectanceModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ReflectanceModel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let known: Vec<_> = Self::ALL.iter().map(|m| m.name()).collect();
                format!(
                    "unknown reflectance model `{s}`; expected one of {}",
                    known.join(", ")
                )
            })
    }
}
