//! Colour of a spectrum: the CIE 1931 2° standard observer under CIE
//! standard illuminant D65, to linear Rec.709 (IEC 61966-2-1), normalized
//! so that a constant spectrum of 1 (a perfect reflector) is exactly
//! (1, 1, 1).
//!
//! Tables: CIE 15.2-1986, Tables 1.1 (D65) and 2.1 (x̄, ȳ, z̄), 380–780 nm
//! every 5 nm, as abridged to 4 digits — the rows of
//! `scripts/conductor_presets.py`, which reduced the coloured conductor
//! presets with them, so the two reductions agree to rounding.
//!
//! Reduction (the script's, line by line): `XYZ = Σ R S x̄ / Σ S ȳ` (and
//! ȳ, z̄), `RGB = M · XYZ` with `M` = [`XYZ_TO_REC709`], then divided
//! channel-wise by the RGB of `R ≡ 1` (which the 4-digit tables leave a
//! few 10⁻⁴ from white).

use crate::base::Rgb;
pub use crate::material::brdf::gltf_layers::iridescence::XYZ_TO_REC709;

/// Number of wavelength samples: 380, 385, …, 780 nm.
pub const SAMPLES: usize = 81;
/// First wavelength \[nm\].
pub const FIRST_NM: f64 = 380.0;
/// Spacing \[nm\].
pub const STEP_NM: f64 = 5.0;

/// The `i`-th wavelength \[nm\].
pub fn wavelength(i: usize) -> f64 {
    FIRST_NM + STEP_NM * i as f64
}

/// Relative spectral power of illuminant D65.
pub const D65: [f64; SAMPLES] = [
    49.9755, 52.3118, 54.6482, 68.7015, 82.7549, 87.1204, 91.486, 92.4589, 93.4318, 90.057,
    86.6823, 95.7736, 104.865, 110.936, 117.008, 117.41, 117.812, 116.336, 114.861, 115.392,
    115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802, 106.296, 104.79, 106.239,
    107.689, 106.047, 104.405, 104.225, 104.046, 102.023, 100.0, 98.1671, 96.3342, 96.0611, 95.788,
    92.2368, 88.6856, 89.3459, 90.0062, 89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886,
    83.4939, 83.6992, 81.863, 80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.281, 78.2842,
    74.0027, 69.7213, 70.6652, 71.6091, 72.979, 74.349, 67.9765, 61.604, 65.7448, 69.8856, 72.4863,
    75.087, 69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941, 63.3828,
];

/// `x̄(λ)`.
pub const X_BAR: [f64; SAMPLES] = [
    0.0014, 0.0022, 0.0042, 0.0076, 0.0143, 0.0232, 0.0435, 0.0776, 0.1344, 0.2148, 0.2839, 0.3285,
    0.3483, 0.3481, 0.3362, 0.3187, 0.2908, 0.2511, 0.1954, 0.1421, 0.0956, 0.058, 0.032, 0.0147,
    0.0049, 0.0024, 0.0093, 0.0291, 0.0633, 0.1096, 0.1655, 0.2257, 0.2904, 0.3597, 0.4334, 0.5121,
    0.5945, 0.6784, 0.7621, 0.8425, 0.9163, 0.9786, 1.0263, 1.0567, 1.0622, 1.0456, 1.0026, 0.9384,
    0.8544, 0.7514, 0.6424, 0.5419, 0.4479, 0.3608, 0.2835, 0.2187, 0.1649, 0.1212, 0.0874, 0.0636,
    0.0468, 0.0329, 0.0227, 0.0158, 0.0114, 0.0081, 0.0058, 0.0041, 0.0029, 0.002, 0.0014, 0.001,
    0.0007, 0.0005, 0.0003, 0.0002, 0.0002, 0.0001, 0.0001, 0.0001, 0.0,
];

/// `ȳ(λ)`.
pub const Y_BAR: [f64; SAMPLES] = [
    0.0, 0.0001, 0.0001, 0.0002, 0.0004, 0.0006, 0.0012, 0.0022, 0.004, 0.0073, 0.0116, 0.0168,
    0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.091, 0.1126, 0.139, 0.1693, 0.208, 0.2586, 0.323,
    0.4073, 0.503, 0.6082, 0.71, 0.7932, 0.862, 0.9149, 0.954, 0.9803, 0.995, 1.0, 0.995, 0.9786,
    0.952, 0.9154, 0.87, 0.8163, 0.757, 0.6949, 0.631, 0.5668, 0.503, 0.4412, 0.381, 0.321, 0.265,
    0.217, 0.175, 0.1382, 0.107, 0.0816, 0.061, 0.0446, 0.032, 0.0232, 0.017, 0.0119, 0.0082,
    0.0057, 0.0041, 0.0029, 0.0021, 0.0015, 0.001, 0.0007, 0.0005, 0.0004, 0.0002, 0.0002, 0.0001,
    0.0001, 0.0001, 0.0, 0.0, 0.0, 0.0,
];

/// `z̄(λ)`: tabulated to 630 nm in the abridged table, 0 beyond.
pub const Z_BAR: [f64; SAMPLES] = [
    0.0065, 0.0105, 0.0201, 0.0362, 0.0679, 0.1102, 0.2074, 0.3713, 0.6456, 1.0391, 1.3856, 1.623,
    1.7471, 1.7826, 1.7721, 1.7441, 1.6692, 1.5281, 1.2876, 1.0419, 0.813, 0.6162, 0.4652, 0.3533,
    0.272, 0.2123, 0.1582, 0.1117, 0.0782, 0.0573, 0.0422, 0.0298, 0.0203, 0.0134, 0.0087, 0.0057,
    0.0039, 0.0027, 0.0021, 0.0018, 0.0017, 0.0014, 0.0011, 0.001, 0.0008, 0.0006, 0.0003, 0.0002,
    0.0002, 0.0001, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
];

/// `XYZ` of the spectrum `r` (sampled at [`wavelength`]) under D65,
/// `Y = 1` for `r ≡ 1`.
pub fn spectrum_to_xyz(r: &[f64; SAMPLES]) -> Rgb {
    let norm: f64 = (0..SAMPLES).map(|i| D65[i] * Y_BAR[i]).sum();
    let sum = |cmf: &[f64; SAMPLES]| -> f64 {
        (0..SAMPLES).map(|i| r[i] * D65[i] * cmf[i]).sum::<f64>() / norm
    };
    Rgb::new(sum(&X_BAR), sum(&Y_BAR), sum(&Z_BAR))
}

/// Linear Rec.709 of `XYZ` (not white-normalized).
pub fn xyz_to_rec709(xyz: Rgb) -> Rgb {
    let m = XYZ_TO_REC709;
    Rgb::new(
        Rgb::from_array(m[0]).dot(xyz),
        Rgb::from_array(m[1]).dot(xyz),
        Rgb::from_array(m[2]).dot(xyz),
    )
}

/// The RGB of a perfect reflector before normalization.
pub fn white_rgb() -> Rgb {
    xyz_to_rec709(spectrum_to_xyz(&[1.0; SAMPLES]))
}

/// The linear Rec.709 colour of the reflectance spectrum `r` under D65,
/// white-normalized (see the module docs).
pub fn spectrum_to_rgb(r: &[f64; SAMPLES]) -> Rgb {
    xyz_to_rec709(spectrum_to_xyz(r)) / white_rgb()
}

/// [`spectrum_to_rgb`] of `f(λ)` sampled at every [`wavelength`].
pub fn rgb_of(f: impl Fn(f64) -> f64) -> Rgb {
    spectrum_to_rgb(&std::array::from_fn(|i| f(wavelength(i))))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant spectrum is grey with its value in every channel (to
    /// rounding: the reduction is linear and white is divided out), and
    /// the unnormalized white is within 10⁻³ of (1, 1, 1), so the tables
    /// are D65's and Rec.709's white point is D65.
    #[test]
    fn constant_spectrum_is_white() {
        for c in [0.0, 0.25, 1.0] {
            let rgb = rgb_of(|_| c);
            assert!(
                (rgb - Rgb::splat(c)).abs().max_element() < 1e-15,
                "{c}: {rgb}"
            );
        }
        let w = white_rgb();
        assert!((w - Rgb::ONE).abs().max_element() < 1e-3, "{w}");
    }

    /// A narrow band lands where the observer puts it: 450 nm blue above
    /// red, 530 nm green above both, 620 nm red above both.
    #[test]
    fn narrow_bands_have_their_hues() {
        let band = |nm: f64| rgb_of(move |l| if (l - nm).abs() < 1.0 { 1.0 } else { 0.0 });
        let (b, g, r) = (band(450.0), band(530.0), band(620.0));
        assert!(b.z > b.x && b.z > b.y, "{b}");
        assert!(g.y > g.x && g.y > g.z, "{g}");
        assert!(r.x > r.y && r.x > r.z, "{r}");
    }
}
