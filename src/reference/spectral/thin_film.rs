//! The thin film as physics: the exact reflectance of a film of index
//! `η_f` and thickness `d` between air and a base (a dielectric of real
//! index, or a metal `n(λ) + i k(λ)`), both polarizations averaged, per
//! wavelength, integrated to a colour by [`super::cie`]; and the error of
//! `KHR_materials_iridescence`'s three-channel form
//! ([`iridescence_fresnel`]) against it.
//!
//! Reflectance (M. Born, E. Wolf, *Principles of Optics*, 7th ed., §1.6.4,
//! eq. 57; the Airy summation of all multiple reflections):
//! `r = (r₁₂ + r₂₃ e^{2iβ}) / (1 + r₁₂ r₂₃ e^{2iβ})`, `2β = (4π/λ) d q₂`,
//! `R = |r|²`, with `q_j = n_j cos θ_j = √(n_j² − sin²θ₁)` (Snell's law, the
//! root with `Im ≥ 0`: the wave decays into an absorbing base for
//! `n + ik`, Born & Wolf §14.2) and the Fresnel amplitude coefficients of
//! each interface `i → j`:
//! `r_s = (q_i − q_j)/(q_i + q_j)`, `r_p = (n_j² q_i − n_i² q_j)/(n_j² q_i + n_i² q_j)`.
//! Unpolarized: `R = (R_s + R_p)/2`.
//!
//! The specification's form (Belcour & Barla 2017, "A Practical Extension
//! to Microfacet Theory for the Modeling of Varying Iridescence", ACM TOG
//! 36(4)) is the same summation with Schlick's Fresnel for the interface
//! magnitudes, phase shifts of 0 or π (exact for real indices), the base
//! index recovered from a three-channel F0, and the spectral integral
//! replaced by the first two Fourier orders against Gaussian fits of the
//! matching functions. [`film_error`] measures what that loses.

use super::cie::rgb_of;
use super::complex::Complex;
use super::error_table::ChannelError;
use super::metals::SpectralMetal;
use crate::base::Rgb;
use crate::material::brdf::gltf_layers::iridescence::{ior_to_f0, iridescence_fresnel};
use crate::material::conductors::COLOURED_CONDUCTORS;
use std::f64::consts::PI;

/// What the film lies on.
#[derive(Clone, Copy)]
pub enum FilmBase {
    /// A dielectric of real index (1 = a free-standing film in air).
    Dielectric(f64),
    /// A metal with its measured `n(λ) + i k(λ)`.
    Metal(&'static SpectralMetal),
}

impl FilmBase {
    /// The base's complex index at `nm`.
    pub fn index_at(self, nm: f64) -> Complex {
        match self {
            FilmBase::Dielectric(n) => Complex::real(n),
            FilmBase::Metal(m) => {
                let (n, k) = m.index_at(nm);
                Complex::new(n, k)
            }
        }
    }

    /// The three-channel normal-incidence reflectance the specification's
    /// form is given for this base: `((n − 1)/(n + 1))²` for a dielectric
    /// (what glTF's `ior` makes of F0), the coloured conductor preset's F0
    /// for a metal (a glTF metal's base colour).
    pub fn rgb_f0(self) -> Rgb {
        match self {
            FilmBase::Dielectric(n) => Rgb::splat(ior_to_f0(n, 1.0)),
            FilmBase::Metal(m) => {
                let row = COLOURED_CONDUCTORS
                    .iter()
                    .find(|c| c.name == m.preset)
                    .expect("every spectral metal has its preset");
                Rgb::from_array(row.f0)
            }
        }
    }
}

/// Fresnel amplitude coefficients `(r_s, r_p)` of the interface from
/// index `n_i` to `n_j` with `q = n cos θ` on each side (module docs).
/// Equal indices are no interface: `(0, 0)`, also where `q_i = q_j = 0`.
fn amplitudes(n_i: Complex, q_i: Complex, n_j: Complex, q_j: Complex) -> (Complex, Complex) {
    if n_i == n_j {
        return (Complex::real(0.0), Complex::real(0.0));
    }
    let r_s = (q_i - q_j) / (q_i + q_j);
    let (a, b) = (n_j * n_j * q_i, n_i * n_i * q_j);
    let r_p = (a - b) / (a + b);
    (r_s, r_p)
}

/// The Airy sum of one polarization: `(r₁₂ + r₂₃ e) / (1 + r₁₂ r₂₃ e)`,
/// `e = e^{2iβ}`.
fn airy(r12: Complex, r23: Complex, e: Complex) -> Complex {
    let t = r23 * e;
    (r12 + t) / (Complex::ONE + r12 * t)
}

/// Unpolarized reflectance at wavelength `nm` of a film of index `eta_f`
/// and thickness `thickness` nm, in air over a base of index `base`, lit
/// at `cos θ₁ = cos_i` from the air (module docs).
pub fn airy_reflectance(cos_i: f64, eta_f: f64, thickness: f64, base: Complex, nm: f64) -> f64 {
    let cos1 = cos_i.clamp(0.0, 1.0);
    let sin2 = Complex::real(1.0 - cos1 * cos1);
    let (n1, n2, n3) = (Complex::ONE, Complex::real(eta_f), base);
    let q1 = Complex::real(cos1);
    let q2 = (n2 * n2 - sin2).sqrt();
    let q3 = (n3 * n3 - sin2).sqrt();
    let (r12_s, r12_p) = amplitudes(n1, q1, n2, q2);
    let (r23_s, r23_p) = amplitudes(n2, q2, n3, q3);
    // e^{2iβ}, 2β = 4π d q₂ / λ (q₂ real for η_f ≥ 1; complex past the
    // critical angle of a film below 1, where it decays).
    let two_beta = q2 * (4.0 * PI * thickness / nm);
    let e = Complex::cis(two_beta.re) * (-two_beta.im).exp();
    let r_s = airy(r12_s, r23_s, e);
    let r_p = airy(r12_p, r23_p, e);
    0.5 * (r_s.norm_sqr() + r_p.norm_sqr())
}

/// The film's colour: [`airy_reflectance`] at every wavelength of
/// [`super::cie`], to linear Rec.709 under D65.
pub fn spectral_film_rgb(cos_i: f64, eta_f: f64, thickness: f64, base: FilmBase) -> Rgb {
    rgb_of(|nm| airy_reflectance(cos_i, eta_f, thickness, base.index_at(nm), nm))
}

/// The specification's colour of the same film: [`iridescence_fresnel`]
/// with the base's [`FilmBase::rgb_f0`].
pub fn gltf_film_rgb(cos_i: f64, eta_f: f64, thickness: f64, base: FilmBase) -> Rgb {
    iridescence_fresnel(cos_i, eta_f, thickness, base.rgb_f0())
}

/// One measured film: a name for the tables, its index and its base.
#[derive(Clone, Copy)]
pub struct FilmCase {
    pub label: &'static str,
    pub eta_f: f64,
    pub base: FilmBase,
}

/// The films measured: the glTF defaults (film 1.3 on `ior` 1.5), a
/// film of higher index than its base (the phase of the second
/// reflection flips), a soap film in air (base F0 = 0) and the default
/// film on gold (a metal base, whose reflection phase is neither 0 nor π).
pub const FILM_CASES: [FilmCase; 4] = [
    FilmCase {
        label: "film 1.3 on dielectric 1.5",
        eta_f: 1.3,
        base: FilmBase::Dielectric(1.5),
    },
    FilmCase {
        label: "film 2.0 on dielectric 1.5",
        eta_f: 2.0,
        base: FilmBase::Dielectric(1.5),
    },
    FilmCase {
        label: "film 1.33 in air (soap film)",
        eta_f: 1.33,
        base: FilmBase::Dielectric(1.0),
    },
    FilmCase {
        label: "film 1.3 on gold (J&C 1972)",
        eta_f: 1.3,
        base: FilmBase::Metal(&super::metals::GOLD),
    },
];

/// Thickness step of the measurement grid \[nm\] (0–1000 nm).
pub const THICKNESS_STEP_NM: f64 = 2.0;
/// Largest thickness measured \[nm\].
pub const THICKNESS_MAX_NM: f64 = 1000.0;
/// Angles measured: 0–85° every degree (and 0–60° apart, away from the
/// grazing angles where Schlick's interfaces dominate the error).
pub const ANGLE_MAX_DEG: u32 = 85;

/// The thickness standing for `d → 0⁺` \[nm\]: far below the 0.03 nm of the
/// index blend, so the form's film index is 1 to rounding, and no phase.
pub const THIN_LIMIT_NM: f64 = 1e-9;

/// The error of the form in the limit of a vanishing film (`d → 0⁺`,
/// every degree 0–`max_deg`°), where the truth is the base's own Fresnel
/// reflectance. The form's film index blends to 1 there, but its first
/// interface keeps Schlick's `(1 − cos θ)⁵` (Schlick's F0 of 0 is not "no
/// interface"), so it reflects where nothing is.
pub fn thin_limit_error(case: FilmCase, max_deg: u32) -> ChannelError<u32> {
    ChannelError::of((0..=max_deg).map(|deg| {
        let cos = (deg as f64).to_radians().cos();
        (
            deg,
            gltf_film_rgb(cos, case.eta_f, THIN_LIMIT_NM, case.base),
            spectral_film_rgb(cos, case.eta_f, 0.0, case.base),
        )
    }))
    .expect("the grid is not empty")
}

/// The error of [`gltf_film_rgb`] against [`spectral_film_rgb`] over
/// thickness 2–1000 nm (every [`THICKNESS_STEP_NM`]) and angle
/// 0–`max_deg`° (every degree), conditions `(d [nm], θ [°])`. `d = 0` is
/// left out: the contract switches the layer off there (pinned choice 2);
/// [`thin_limit_error`] measures the form's limit `d → 0⁺`.
pub fn film_error(case: FilmCase, max_deg: u32) -> ChannelError<(f64, u32)> {
    let steps = (THICKNESS_MAX_NM / THICKNESS_STEP_NM).round() as usize;
    let grid = (1..=steps).flat_map(move |i| (0..=max_deg).map(move |a| (i, a)));
    ChannelError::of(grid.map(|(i, deg)| {
        let d = i as f64 * THICKNESS_STEP_NM;
        let cos = (deg as f64).to_radians().cos();
        (
            (d, deg),
            gltf_film_rgb(cos, case.eta_f, d, case.base),
            spectral_film_rgb(cos, case.eta_f, d, case.base),
        )
    }))
    .expect("the grid is not empty")
}

#[cfg(test)]
mod tests {
    use super::super::cie::rgb_of;
    use super::super::error_table::{MarkdownHeader, markdown_row};
    use super::super::metals::METALS;
    use super::*;
    use crate::material::brdf::fresnel::{fresnel_conductor, fresnel_dielectric};

    /// 0–89°: exactly at grazing a film between equal indices at `d = 0`
    /// is `0/0` (`r₁₂ = −1`, `r₂₃ = 1`), a limit the measurement never
    /// takes.
    fn angles() -> impl Iterator<Item = f64> {
        (0..90).map(|deg| (deg as f64).to_radians().cos())
    }

    /// A film of thickness 0 is no film: the Airy sum is the base's own
    /// Fresnel reflectance, at every angle and wavelength, for dielectric
    /// and metal bases (`(r₁₂ + r₂₃)/(1 + r₁₂r₂₃) = r₁₃` for both
    /// polarizations; this fails if a sign of `r_p` or the branch of `q₃`
    /// is wrong). Tolerance: a few rounding errors of quotients near 1.
    #[test]
    fn zero_thickness_is_the_base_fresnel() {
        for cos in angles() {
            for eta_f in [1.0, 1.3, 2.0] {
                for n3 in [1.0, 1.33, 1.5, 2.4] {
                    let got = airy_reflectance(cos, eta_f, 0.0, Complex::real(n3), 550.0);
                    let want = fresnel_dielectric(cos, 1.0, n3);
                    assert!(
                        (got - want).abs() < 1e-14,
                        "{cos} {eta_f} {n3}: {got} {want}"
                    );
                }
                for m in METALS {
                    for nm in [380.0, 550.0, 780.0] {
                        let (n, k) = m.index_at(nm);
                        let got = airy_reflectance(cos, eta_f, 0.0, Complex::new(n, k), nm);
                        let want = fresnel_conductor(cos, Rgb::splat(n), Rgb::splat(k)).x;
                        assert!((got - want).abs() < 1e-14, "{}: {got} {want}", m.preset);
                    }
                }
            }
        }
    }

    /// The same in colour: the spectral film at `d = 0` is the colour of
    /// the base's spectral Fresnel (gold: its spectral colour, not the
    /// preset's).
    #[test]
    fn zero_thickness_colour_is_the_base_colour() {
        for cos in angles() {
            let film = spectral_film_rgb(cos, 1.3, 0.0, FilmBase::Dielectric(1.5));
            let plain = Rgb::splat(fresnel_dielectric(cos, 1.0, 1.5));
            assert!((film - plain).abs().max_element() < 1e-14, "{film} {plain}");
            let gold = &super::super::metals::GOLD;
            let film = spectral_film_rgb(cos, 1.3, 0.0, FilmBase::Metal(gold));
            let plain = rgb_of(|nm| {
                let (n, k) = gold.index_at(nm);
                fresnel_conductor(cos, Rgb::splat(n), Rgb::splat(k)).x
            });
            assert!((film - plain).abs().max_element() < 1e-14, "{film} {plain}");
        }
    }

    /// A quarter-wave film of index `√n₃` cancels the reflection at its
    /// design wavelength (normal incidence: `r₁₂ = r₂₃`, opposite phase),
    /// and a half-wave film is absent (`R = R₁₃`). This fixes the phase
    /// `2β` and its sign against the amplitudes.
    #[test]
    fn quarter_wave_coating_cancels_and_half_wave_is_absent() {
        let (n3, nm) = (1.5f64, 550.0);
        let n2 = n3.sqrt();
        let quarter = airy_reflectance(1.0, n2, nm / (4.0 * n2), Complex::real(n3), nm);
        assert!(quarter < 1e-16, "{quarter}");
        let half = airy_reflectance(1.0, 1.38, nm / (2.0 * 1.38), Complex::real(n3), nm);
        let bare = fresnel_dielectric(1.0, 1.0, n3);
        assert!((half - bare).abs() < 1e-15, "{half} {bare}");
        // Off design the coating reflects again, below the bare base.
        let off = airy_reflectance(1.0, n2, nm / (4.0 * n2), Complex::real(n3), 450.0);
        assert!(off > 1e-4 && off < bare, "{off}");
    }

    /// Energy: `0 ≤ R ≤ 1` for every film, base, thickness, angle and
    /// wavelength sampled (a lossless film cannot add light; a wrong sign
    /// of `Im q₃` makes an absorbing base amplify). Slack 10⁻¹⁵: a few
    /// roundings of `|r|²` near 1.
    #[test]
    fn reflectance_never_exceeds_one() {
        let mut bases: Vec<FilmBase> = [1.0, 1.5, 2.4].map(FilmBase::Dielectric).to_vec();
        bases.extend(METALS.map(FilmBase::Metal));
        let mut worst = 0.0f64;
        for base in bases {
            for eta_f in [1.0, 1.3, 1.8, 2.5] {
                for d in (0..=1000).step_by(7) {
                    for cos in angles() {
                        for i in 0..super::super::cie::SAMPLES {
                            let nm = super::super::cie::wavelength(i);
                            let r = airy_reflectance(cos, eta_f, d as f64, base.index_at(nm), nm);
                            assert!(
                                (0.0..=1.0 + 1e-15).contains(&r),
                                "{eta_f} {d} {cos} {nm}: {r}"
                            );
                            worst = worst.max(r);
                        }
                    }
                }
            }
        }
        assert!(worst > 0.9, "89° reaches past 0.9: {worst}");
    }

    /// The measured error of the specification's form (printed with
    /// `--nocapture`; docs/spectral.md). Asserted: every entry finite and
    /// below 1, and the error larger towards grazing (the 0–85° maximum at
    /// least the 0–60° one, and reached past 60° for the dielectric
    /// bases, where Schlick's interfaces depart most from Fresnel's).
    #[test]
    fn gltf_form_error_against_the_spectral_film() {
        for max_deg in [ANGLE_MAX_DEG, 60] {
            println!(
                "{}",
                MarkdownHeader(&format!("film (d 2–1000 nm, θ 0–{max_deg}°)"))
            );
            for case in FILM_CASES {
                let e = film_error(case, max_deg);
                let row = markdown_row(case.label, &e, |(d, deg)| format!("{d:.0} nm, {deg}°"));
                println!("{row}");
                for ch in 0..3 {
                    assert!(e.max[ch].is_finite() && e.max[ch] < 1.0, "{}", case.label);
                }
                if max_deg == ANGLE_MAX_DEG {
                    let near = film_error(case, 60);
                    assert!(e.max.cmpge(near.max).all(), "{}", case.label);
                    if let FilmBase::Dielectric(_) = case.base {
                        assert!(e.at_max.iter().all(|m| m.0.1 > 60), "{}", case.label);
                    }
                }
            }
            println!();
        }
        println!("{}", MarkdownHeader("film, d → 0⁺ (θ 0–85°)"));
        for case in FILM_CASES {
            let e = thin_limit_error(case, ANGLE_MAX_DEG);
            println!("{}", markdown_row(case.label, &e, |deg| format!("{deg}°")));
        }
    }

    /// The form's sensitivity at zero path difference, `𝒮(0, 0)`, is the
    /// colour of the equal-energy illuminant E in linear Rec.709 without
    /// white balance (`M · ∫(x̄, ȳ, z̄) / ∫ȳ`, pinkish), not white: Belcour
    /// & Barla's fit integrates under E, while the form's non-oscillating
    /// terms are taken as white. So a vanishing film tints the base even at
    /// normal incidence. Tolerance: the Gaussian fit's own error in the
    /// integral, 1.4·10⁻³ at most (measured against the 5 nm tables).
    #[test]
    fn gltf_sensitivity_at_zero_path_is_illuminant_e() {
        use super::super::cie::{SAMPLES, X_BAR, Y_BAR, Z_BAR, xyz_to_rec709};
        use crate::material::brdf::gltf_layers::iridescence::eval_sensitivity;
        let sum = |t: &[f64; SAMPLES]| t.iter().sum::<f64>();
        let e = xyz_to_rec709(Rgb::new(sum(&X_BAR), sum(&Y_BAR), sum(&Z_BAR)) / sum(&Y_BAR));
        let s = eval_sensitivity(0.0, Rgb::ZERO);
        println!("S(0, 0) = {s:.4}, illuminant E = {e:.4}");
        assert!((s - e).abs().max_element() < 2e-3, "{s} {e}");
        assert!(s.x > 1.15 && s.z < 0.95, "not white: {s}");
    }
}
