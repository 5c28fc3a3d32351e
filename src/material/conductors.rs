//! Coloured conductors: per-channel (linear Rec.709 R, G, B) η, κ reduced
//! from published spectral measurements. The lecture's
//! presets ([`super::presets`]) give one η, κ for one wavelength, so a
//! lecture `gold` is grey (F0 0.849 in every channel); these make gold
//! yellow and copper red.
//!
//! Data (refractiveindex.info database, CC0):
//! * Au, Ag, Cu: P. B. Johnson, R. W. Christy, "Optical constants of the
//!   noble metals", Phys. Rev. B 6, 4370 (1972).
//! * Fe: P. B. Johnson, R. W. Christy, "Optical constants of transition
//!   metals", Phys. Rev. B 9, 5056 (1974).
//! * Al: A. D. Rakić, "Algorithm for the determination of intrinsic optical
//!   constants of metal films: application to aluminum", Appl. Opt. 34,
//!   4755 (1995).
//!
//! Reduction (`scripts/conductor_presets.py` prints these rows):
//! 1. `F0(λ) = ((n−1)² + k²)/((n+1)² + k²)`, the exact normal-incidence
//!    Fresnel reflectance, every 5 nm over 380–780 nm (n, k interpolated
//!    linearly between the published samples);
//! 2. integrated against the CIE 1931 2° observer under illuminant D65
//!    (CIE 15.2-1986, 5 nm) to XYZ, then to linear Rec.709 (IEC 61966-2-1),
//!    normalized so a perfect reflector is exactly (1, 1, 1);
//! 3. a channel above the metal's largest spectral F0 is clipped to it
//!    (only gold's red: 1.038 → 0.975, its yellow is outside Rec.709);
//! 4. per channel, η = the measured n at 630 / 532 / 465 nm (R / G / B) and κ
//!    solved in closed form so that F0(η, κ) is the channel's value:
//!    `κ² = (F0 (η+1)² − (η−1)²) / (1 − F0)`.
//!
//! So the normal-incidence colour is the measured one exactly (to the
//! table's 4 decimals), and η, which shapes the fall-off towards grazing,
//! is the measurement at the channel's wavelength.

use crate::base::named_enum;

/// One coloured conductor: preset name, η and κ per channel, and the
/// normal-incidence reflectance (linear Rec.709) the reduction produced,
/// which the η, κ reproduce.
pub struct ColouredConductor {
    pub name: &'static str,
    pub eta: [f64; 3],
    pub kappa: [f64; 3],
    pub f0: [f64; 3],
}

/// The coloured conductors, from `scripts/conductor_presets.py`.
pub const COLOURED_CONDUCTORS: &[ColouredConductor] = &[
    // Johnson & Christy 1972, Au.
    ColouredConductor {
        name: "gold-rgb",
        eta: [0.1884, 0.5439, 1.3319],
        kappa: [5.3856, 2.3716, 1.7166],
        f0: [0.9752, 0.7283, 0.3646],
    },
    // Johnson & Christy 1972, Ag.
    ColouredConductor {
        name: "silver-rgb",
        eta: [0.0569, 0.0540, 0.0469],
        kappa: [4.5028, 3.5141, 2.7131],
        f0: [0.9894, 0.9840, 0.9778],
    },
    // Johnson & Christy 1972, Cu.
    ColouredConductor {
        name: "copper-rgb",
        eta: [0.2753, 1.1159, 1.2469],
        kappa: [3.8082, 2.7115, 2.3223],
        f0: [0.9317, 0.6227, 0.5223],
    },
    // Rakić 1995, Al.
    ColouredConductor {
        name: "aluminium-rgb",
        eta: [1.4303, 0.9388, 0.6860],
        kappa: [7.4724, 6.3929, 5.7000],
        f0: [0.9073, 0.9159, 0.9223],
    },
    // Johnson & Christy 1974, Fe.
    ColouredConductor {
        name: "iron-rgb",
        eta: [2.8924, 2.8954, 2.6460],
        kappa: [3.0739, 2.9357, 2.7629],
        f0: [0.5297, 0.5132, 0.4942],
    },
];

named_enum!(
    /// A metal of the table above by its name without `-rgb`: the value of
    /// the material key `spectral_metal` (`super::spectral_metal`), which
    /// the reference evaluates from the metal's spectral table.
    Metal, "spectral metal" {
        /// Au, Johnson & Christy 1972.
        Gold = "gold",
        /// Ag, Johnson & Christy 1972.
        Silver = "silver",
        /// Cu, Johnson & Christy 1972.
        Copper = "copper",
        /// Al, Rakić 1995.
        Aluminium = "aluminium",
        /// Fe, Johnson & Christy 1974.
        Iron = "iron",
    }
);

impl Metal {
    /// Its three-channel preset (the reduction of the same table).
    pub fn coloured(self) -> &'static ColouredConductor {
        let name = self.preset_name();
        COLOURED_CONDUCTORS
            .iter()
            .find(|c| c.name == name)
            .expect("every metal has its preset")
    }

    /// The name of its three-channel preset: `gold` → `gold-rgb`.
    pub fn preset_name(self) -> String {
        format!("{}-rgb", self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::Rgb;
    use crate::material::brdf::fresnel::fresnel_conductor;

    fn f0_of(c: &ColouredConductor) -> Rgb {
        fresnel_conductor(1.0, Rgb::from_array(c.eta), Rgb::from_array(c.kappa))
    }

    fn row(name: &str) -> &'static ColouredConductor {
        COLOURED_CONDUCTORS.iter().find(|c| c.name == name).unwrap()
    }

    /// The renderer's exact Fresnel at normal incidence reproduces the
    /// reduced colour. Tolerance: η, κ and F0 are rounded to 4 decimals
    /// (±5e-5 each) and |∂F0/∂η|, |∂F0/∂κ| < 1 for every row (largest:
    /// iron's ∂F0/∂η ≈ 0.63), so the error is below 5e-5 (F0) + 2 · 5e-5.
    #[test]
    fn normal_incidence_reflectance_is_the_published_colour() {
        for c in COLOURED_CONDUCTORS {
            let got = f0_of(c);
            for ch in 0..3 {
                assert!(
                    (got[ch] - c.f0[ch]).abs() < 1.5e-4,
                    "{} channel {ch}: F0 {} vs {}",
                    c.name,
                    got[ch],
                    c.f0[ch]
                );
            }
        }
    }

    /// The colours are the metals': gold yellow (R > G > B, blue less than
    /// half the red), copper red (R − B > 0.35), silver and aluminium near
    /// neutral and bright, iron a darker grey; every channel below 1.
    #[test]
    fn the_metals_have_their_colours() {
        let gold = f0_of(row("gold-rgb"));
        assert!(gold.x > gold.y && gold.y > gold.z && gold.z < 0.5 * gold.x);
        let copper = f0_of(row("copper-rgb"));
        assert!(copper.x > copper.y && copper.y > copper.z);
        assert!(copper.x - copper.z > 0.35);
        for name in ["silver-rgb", "aluminium-rgb"] {
            let c = f0_of(row(name));
            assert!(c.min_element() > 0.9 && c.max_element() - c.min_element() < 0.02);
        }
        let iron = f0_of(row("iron-rgb"));
        assert!(iron.max_element() < 0.6 && iron.max_element() - iron.min_element() < 0.05);
        for c in COLOURED_CONDUCTORS {
            assert!(f0_of(c).max_element() < 1.0, "{}", c.name);
        }
    }

    /// Every metal names its preset, in the table's order.
    #[test]
    fn every_metal_has_its_preset() {
        let names: Vec<_> = Metal::ALL.iter().map(|m| m.coloured().name).collect();
        let presets: Vec<_> = COLOURED_CONDUCTORS.iter().map(|c| c.name).collect();
        assert_eq!(names, presets);
    }

    /// A bad name is refused with the allowed ones listed.
    #[test]
    fn a_bad_metal_name_lists_the_metals() {
        let e = "platinum".parse::<Metal>().unwrap_err();
        assert!(
            e.contains("platinum") && e.contains("gold, silver, copper, aluminium, iron"),
            "{e}"
        );
    }
}
