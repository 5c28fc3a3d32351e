//! Named materials from the lecture's tables: the conductors of
//! "Electric Conductors (e.g. Metals)" and the media of "Dielectrics
//! (e.g. Glass)". The lecture gives one value per material; gonio uses it
//! for all three channels. Coloured conductors with per-channel η, κ from
//! spectral measurements follow under their own names (`gold-rgb`, …; see
//! [`super::conductors`]).

use super::Material;
use super::conductors::{COLOURED_CONDUCTORS, ColouredConductor};
use super::terms::Fresnel;
use crate::base::Rgb;

/// What a preset sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Preset {
    /// Complex index of refraction η + iκ per channel (R, G, B); the
    /// lecture's rows repeat one value.
    Conductor { eta: [f64; 3], kappa: [f64; 3] },
    /// Index of refraction of the medium (the outside is vacuum, η_i = 1).
    Dielectric { eta: f64 },
}

/// Every preset: (name, values). Names are lower case, spaces as hyphens.
pub const PRESETS: &[(&str, Preset)] = &[
    (
        "gold",
        Preset::Conductor {
            eta: [0.370; 3],
            kappa: [2.820; 3],
        },
    ),
    (
        "silver",
        Preset::Conductor {
            eta: [0.177; 3],
            kappa: [3.638; 3],
        },
    ),
    (
        "copper",
        Preset::Conductor {
            eta: [0.617; 3],
            kappa: [2.63; 3],
        },
    ),
    (
        "steel",
        Preset::Conductor {
            eta: [2.485; 3],
            kappa: [3.433; 3],
        },
    ),
    ("vacuum", Preset::Dielectric { eta: 1.0 }),
    ("air", Preset::Dielectric { eta: 1.00029 }),
    ("ice", Preset::Dielectric { eta: 1.31 }),
    ("water", Preset::Dielectric { eta: 1.333 }),
    ("fused-quartz", Preset::Dielectric { eta: 1.46 }),
    // The lecture gives glass as 1.5–1.6: both ends are offered.
    ("glass", Preset::Dielectric { eta: 1.5 }),
    ("glass-dense", Preset::Dielectric { eta: 1.6 }),
    ("sapphire", Preset::Dielectric { eta: 1.77 }),
    ("diamond", Preset::Dielectric { eta: 2.42 }),
    (COLOURED_CONDUCTORS[0].name, COLOURED_CONDUCTORS[0].preset()),
    (COLOURED_CONDUCTORS[1].name, COLOURED_CONDUCTORS[1].preset()),
    (COLOURED_CONDUCTORS[2].name, COLOURED_CONDUCTORS[2].preset()),
    (COLOURED_CONDUCTORS[3].name, COLOURED_CONDUCTORS[3].preset()),
    (COLOURED_CONDUCTORS[4].name, COLOURED_CONDUCTORS[4].preset()),
];

/// The preset called `name`.
pub fn preset(name: &str) -> Result<Preset, String> {
    PRESETS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, p)| *p)
        .ok_or_else(|| {
            let names: Vec<_> = PRESETS.iter().map(|(n, _)| *n).collect();
            format!(
                "unknown preset `{name}`; expected one of {}",
                names.join(", ")
            )
        })
}

impl Preset {
    /// Applies the preset to `m`: a conductor sets η, κ and the exact
    /// conductor Fresnel; a dielectric sets η_i = 1, η_t = η, the same η
    /// with κ = 0 (so Schlick's F0 and the conductor formula agree with the
    /// dielectric one) and the dielectric Fresnel. It sets nothing else:
    /// a scene-file entry then takes the model's default `k_d`, `k_s` for
    /// the Fresnel term the preset chose (Cook-Torrance: a conductor is a
    /// bare metal, `k_d = 0`, `k_s = 1`; a dielectric `k_d = 0.5`,
    /// `k_s = 1`; see `material/weights.rs`). Keys given explicitly in the
    /// scene are applied after the preset and win.
    pub fn apply(self, m: &mut Material) {
        match self {
            Preset::Conductor { eta, kappa } => {
                m.eta = Rgb::from_array(eta);
                m.kappa = Rgb::from_array(kappa);
                m.fresnel = Fresnel::Conductor;
            }
            Preset::Dielectric { eta } => {
                m.eta = Rgb::splat(eta);
                m.kappa = Rgb::ZERO;
                m.eta_i = 1.0;
                m.eta_t = eta;
                m.fresnel = Fresnel::Dielectric;
            }
        }
    }
}

impl ColouredConductor {
    /// The preset this row sets (here, beside the type it makes: the
    /// table of conductors knows nothing of presets).
    pub const fn preset(&self) -> Preset {
        Preset::Conductor {
            eta: self.eta,
            kappa: self.kappa,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::conductors::COLOURED_CONDUCTORS;

    /// The lecture's conductors keep their names and single values.
    #[test]
    fn lecture_conductors_are_unchanged() {
        for (name, eta, kappa) in [
            ("gold", 0.370, 2.820),
            ("silver", 0.177, 3.638),
            ("copper", 0.617, 2.63),
            ("steel", 2.485, 3.433),
        ] {
            assert_eq!(
                preset(name),
                Ok(Preset::Conductor {
                    eta: [eta; 3],
                    kappa: [kappa; 3]
                })
            );
        }
    }

    /// Every coloured conductor is a preset under its name, with its row's
    /// values, and no name is listed twice.
    #[test]
    fn coloured_conductors_are_presets() {
        for c in COLOURED_CONDUCTORS {
            assert_eq!(preset(c.name), Ok(c.preset()));
        }
        let mut names: Vec<_> = PRESETS.iter().map(|(n, _)| *n).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), PRESETS.len());
    }
}
