//! The closed set of reflectance models and their contract names.

use std::fmt;
use std::str::FromStr;

/// Every reflectance model gonio knows, by the contract's names. A material
/// picks one; the GPU compiles only the models a scene uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ReflectanceModel {
    /// `f_r = k_d / π` (lecture: "Diffuse Reflection Model").
    Lambert,
    /// The lecture's Phong: `k_d/π + k_s (R(I)·V)^k_e / (I·N)`, as written
    /// (not normalized, not reciprocal).
    Phong,
    /// The lecture's Blinn-Phong: `k_d/π + k_s (H·N)^k_e / (I·N)`, as
    /// written (not normalized, not reciprocal).
    BlinnPhong,
}

impl ReflectanceModel {
    /// All models implemented, in the contract's order.
    pub const ALL: [ReflectanceModel; 3] = [
        ReflectanceModel::Lambert,
        ReflectanceModel::Phong,
        ReflectanceModel::BlinnPhong,
    ];

    /// Contract names that are reserved for models of the catalog still
    /// to come; naming one gives a clear error rather than "unknown".
    pub const PLANNED: [&'static str; 6] = [
        "phong-normalized",
        "blinn-phong-normalized",
        "ward",
        "ward-anisotropic",
        "cook-torrance",
        "mirror",
    ];

    /// The contract's name.
    pub fn name(self) -> &'static str {
        match self {
            ReflectanceModel::Lambert => "lambert",
            ReflectanceModel::Phong => "phong",
            ReflectanceModel::BlinnPhong => "blinn-phong",
        }
    }

    /// A stable small integer shared with WGSL (`MODEL_*` constants).
    pub fn id(self) -> u32 {
        match self {
            ReflectanceModel::Lambert => 0,
            ReflectanceModel::Phong => 1,
            ReflectanceModel::BlinnPhong => 2,
        }
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
        if let Some(m) = Self::ALL.into_iter().find(|m| m.name() == s) {
            return Ok(m);
        }
        let known: Vec<_> = Self::ALL.iter().map(|m| m.name()).collect();
        if Self::PLANNED.contains(&s) {
            Err(format!(
                "reflectance model `{s}` is not implemented yet (the catalog is issue #4); available: {}",
                known.join(", ")
            ))
        } else {
            Err(format!(
                "unknown reflectance model `{s}`; expected one of {}",
                known.join(", ")
            ))
        }
    }
}
