//! Dispersion seen in RGB: the wavelengths a dispersive volume is traced
//! at, and the linear Rec.709 weight of each (CIE 1931 2° colour matching
//! functions and D65 of [`crate::reference::spectral::cie`]).
//!
//! The scene's light is RGB. Where a dispersive medium splits a ray, the
//! path is traced once per wavelength `λ_k`, each seeing an RGB radiance
//! `L_k`, and the pixel gets `Σ_k c_k ⊙ L_k` with
//! `c_k = M·(x̄, ȳ, z̄)(λ_k)·S_D65(λ_k)`, normalized per channel so that
//! `Σ_k c_k = (1, 1, 1)` (`M` = XYZ → linear Rec.709): with `n(λ)`
//! constant every `L_k` is the same and the sum gives it back exactly,
//! and a white (D65) light split by a prism shows the spectrum's colours
//! in the order and proportions of the colour matching functions. `c_k`
//! has negative entries (the red channel near 440–540 nm: the spectral
//! colours lie outside the Rec.709 gamut), so a pixel may go below 0
//! where one wavelength dominates; it is clamped at 0 there.

use crate::base::Rgb;
use crate::reference::spectral::cie::{
    D65, SAMPLES, X_BAR, Y_BAR, Z_BAR, wavelength, xyz_to_rec709,
};
use std::sync::OnceLock;

/// Every `STRIDE`-th sample of the 5 nm CIE table: 10 nm, 41 wavelengths
/// from 380 to 780 nm. A dispersive path costs 41 traced paths; the
/// sampling error of a 10 nm step on the colour matching functions (which
/// vary on a scale of 30 nm) is below 10⁻³ of the white point's channels.
pub const STRIDE: usize = 2;

/// `(λ_k [nm], c_k)` for every traced wavelength (module doc).
pub fn weights() -> &'static [(f64, Rgb)] {
    static WEIGHTS: OnceLock<Vec<(f64, Rgb)>> = OnceLock::new();
    WEIGHTS.get_or_init(|| {
        let raw: Vec<(f64, Rgb)> = (0..SAMPLES)
            .step_by(STRIDE)
            .map(|i| {
                let xyz = Rgb::new(X_BAR[i], Y_BAR[i], Z_BAR[i]) * D65[i];
                (wavelength(i), xyz_to_rec709(xyz))
            })
            .collect();
        let total = raw.iter().fold(Rgb::ZERO, |s, (_, c)| s + *c);
        raw.into_iter().map(|(l, c)| (l, c / total)).collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_white_and_cover_the_visible_range() {
        let w = weights();
        assert_eq!(w.len(), 41);
        assert_eq!((w[0].0, w[40].0), (380.0, 780.0));
        let sum = w.iter().fold(Rgb::ZERO, |s, (_, c)| s + *c);
        assert!((sum - Rgb::ONE).abs().max_element() < 1e-12, "{sum}");
        // Red peaks in the long wavelengths, blue in the short.
        let peak = |ch: usize| {
            w.iter()
                .max_by(|a, b| a.1[ch].total_cmp(&b.1[ch]))
                .unwrap()
                .0
        };
        assert!(
            peak(0) > 580.0 && peak(2) < 480.0,
            "{} {}",
            peak(0),
            peak(2)
        );
    }
}
