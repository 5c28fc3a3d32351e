//! Conductors as physics: the exact Fresnel reflectance of a metal's
//! measured `n(λ) + i k(λ)` ([`super::metals`]) at every wavelength,
//! integrated to a colour by [`super::cie`]; and the error of the
//! three-channel presets ([`crate::material::conductors::COLOURED_CONDUCTORS`], evaluated as the
//! renderer does, [`fresnel_conductor`] per channel) against it.
//!
//! The presets were reduced from the same tables (`scripts/conductor_presets.py`,
//! the module docs of [`crate::material::conductors`]): their
//! normal-incidence colour is the spectral one by construction (gold's red
//! clipped to its largest spectral F0: the spectral colour is outside
//! Rec.709), and `η` per channel is the measured `n` at 630 / 532 / 465 nm.
//! What three channels cannot carry is how the spectrum's shape changes
//! with angle: [`conductor_error`] measures it. The lecture's one-value
//! presets (`gold`, `silver`, `copper`) are measured the same way.

use super::cie::{SAMPLES, rgb_of, wavelength};
use super::error_table::ChannelError;
use super::metals::SpectralMetal;
use crate::base::Rgb;
use crate::material::brdf::fresnel::fresnel_conductor;

/// The colour of the metal's exact Fresnel reflectance at `cos θ = cos_i`.
pub fn spectral_conductor_rgb(metal: &SpectralMetal, cos_i: f64) -> Rgb {
    rgb_of(|nm| {
        let (n, k) = metal.index_at(nm);
        fresnel_conductor(cos_i, Rgb::splat(n), Rgb::splat(k)).x
    })
}

/// The largest spectral reflectance at normal incidence over 380–780 nm:
/// the reduction clips a channel above it (no Fresnel reflectance of the
/// metal reaches more).
pub fn largest_spectral_f0(metal: &SpectralMetal) -> f64 {
    (0..SAMPLES)
        .map(|i| {
            let (n, k) = metal.index_at(wavelength(i));
            fresnel_conductor(1.0, Rgb::splat(n), Rgb::splat(k)).x
        })
        .fold(0.0, f64::max)
}

/// Angles measured: 0–89° every degree.
pub const ANGLE_MAX_DEG: u32 = 89;

/// The error of the three-channel `η`, `κ` against the metal's spectral
/// Fresnel over 0–89°, conditions `θ [°]`.
pub fn conductor_error(metal: &SpectralMetal, eta: Rgb, kappa: Rgb) -> ChannelError<u32> {
    ChannelError::of((0..=ANGLE_MAX_DEG).map(|deg| {
        let cos = (deg as f64).to_radians().cos();
        (
            deg,
            fresnel_conductor(cos, eta, kappa),
            spectral_conductor_rgb(metal, cos),
        )
    }))
    .expect("the grid is not empty")
}

#[cfg(test)]
mod tests {
    use super::super::error_table::{MarkdownHeader, markdown_row};
    use super::super::metals::{COPPER, GOLD, METALS, SILVER};
    use super::*;
    use crate::material::conductors::{COLOURED_CONDUCTORS, ColouredConductor};
    use crate::material::presets::{Preset, preset};

    fn row(metal: &SpectralMetal) -> &'static ColouredConductor {
        COLOURED_CONDUCTORS
            .iter()
            .find(|c| c.name == metal.preset)
            .unwrap()
    }

    /// The presets' normal-incidence colour is the spectral colour (a
    /// channel above the largest spectral F0 clipped to it), recomputed
    /// here from the ported tables: the stored F0 within its 4-decimal
    /// rounding (5·10⁻⁵), the renderer's Fresnel of the stored η, κ within
    /// 10⁻⁴ (η and κ rounded to ±5·10⁻⁵ each, |∂F0/∂η|, |∂F0/∂κ| < 1 for
    /// every row), and η the measured n at 630 / 532 / 465 nm (±5·10⁻⁵).
    /// Fails if the tables, the observer or the reduction drifted apart
    /// from the script's.
    #[test]
    fn presets_are_the_spectral_colour_at_normal_incidence() {
        for metal in METALS {
            let c = row(metal);
            let spectral = spectral_conductor_rgb(metal, 1.0);
            let clipped = spectral.min(Rgb::splat(largest_spectral_f0(metal)));
            let stored = Rgb::from_array(c.f0);
            let rendered = fresnel_conductor(1.0, Rgb::from_array(c.eta), Rgb::from_array(c.kappa));
            println!("{}: spectral {spectral:.5}, preset {rendered:.5}", c.name);
            assert!(
                (stored - clipped).abs().max_element() <= 5e-5 + 1e-12,
                "{}",
                c.name
            );
            assert!(
                (rendered - clipped).abs().max_element() <= 1e-4,
                "{}",
                c.name
            );
            for (ch, nm) in [630.0, 532.0, 465.0].into_iter().enumerate() {
                assert!((metal.index_at(nm).0 - c.eta[ch]).abs() <= 5e-5 + 1e-12);
            }
        }
        // Only gold's red is clipped: its spectral red is above 1.
        let gold = spectral_conductor_rgb(&GOLD, 1.0);
        assert!(gold.x > 1.0 && gold.x - row(&GOLD).f0[0] > 0.05, "{gold}");
    }

    /// Energy of the spectral colour of a metal: every channel of a
    /// non-gold metal below 1 at every angle below grazing (gold's red is
    /// outside the gamut and passes 1), and all channels reach 1 at 90°.
    #[test]
    fn spectral_colours_are_bounded_and_white_at_grazing() {
        for metal in METALS {
            for deg in 0..90 {
                let c = spectral_conductor_rgb(metal, (deg as f64).to_radians().cos());
                if metal.preset != "gold-rgb" {
                    assert!(c.max_element() < 1.0, "{} {deg}°: {c}", metal.preset);
                }
                assert!(c.min_element() > 0.0);
            }
            let grazing = spectral_conductor_rgb(metal, 0.0);
            assert!(
                (grazing - Rgb::ONE).abs().max_element() < 1e-14,
                "{grazing}"
            );
        }
    }

    /// The measured error of the presets (printed with `--nocapture`;
    /// docs/spectral.md). Asserted: the coloured presets are exact at
    /// normal incidence except gold's clipped red (10⁻⁴ as above), so
    /// their largest error is away from 0°, and they beat the lecture's
    /// one-value presets of the same metal on the mean.
    #[test]
    fn preset_error_against_the_spectral_fresnel() {
        println!("{}", MarkdownHeader("preset (θ 0–89°)"));
        let mut coloured = Vec::new();
        for metal in METALS {
            let c = row(metal);
            let e = conductor_error(metal, Rgb::from_array(c.eta), Rgb::from_array(c.kappa));
            println!("{}", markdown_row(c.name, &e, |deg| format!("{deg}°")));
            for ch in 0..3 {
                if !(metal.preset == "gold-rgb" && ch == 0) {
                    assert!(e.at_max[ch].0 > 0, "{} channel {ch}", c.name);
                }
            }
            coloured.push((metal.preset, e));
        }
        for (name, metal) in [("gold", &GOLD), ("silver", &SILVER), ("copper", &COPPER)] {
            let Ok(Preset::Conductor { eta, kappa }) = preset(name) else {
                panic!("{name} is a conductor preset");
            };
            let e = conductor_error(metal, Rgb::from_array(eta), Rgb::from_array(kappa));
            let label = format!("{name} (lecture, one η, κ)");
            println!("{}", markdown_row(&label, &e, |deg| format!("{deg}°")));
            let rgb = &coloured.iter().find(|(p, _)| *p == metal.preset).unwrap().1;
            assert!(rgb.mean.max_element() < e.mean.max_element(), "{name}");
        }
    }
}
