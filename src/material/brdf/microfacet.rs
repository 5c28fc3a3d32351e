//! Microfacet terms of the Cook-Torrance model (lecture: "Microfacet
//! Distribution Functions", "Geometric Attenuation Factor", "Cook-Torrance
//! Specular Term"; R. L. Cook & K. E. Torrance, "A Reflectance Model for
//! Computer Graphics", 1982; B. Walter et al., "Microfacet Models for
//! Refraction through Rough Surfaces", EGSR 2007).
//! WGSL twin: `shaders/brdf/microfacet.wgsl` (same names, same order; the
//! GGX visibility and Schlick weight of glTF's BRDF, here for the
//! environment BRDF table of `dfg.rs`, are in `shaders/brdf/gltf_pbr.wgsl`).
//!
//! Distributions take `(roughness, cos_h)`, `cos_h = N·H`, and are 0 for
//! `cos_h ≤ 0`; `cos_h` is clamped to ≤ 1 (rounding of unit vectors). The
//! lecture's Blinn and Gaussian peak at 1 (not normalized) and take an
//! angle `m` in radians; their `_normalized` twins satisfy
//! `∫ D cosθ_h dω_h = 1`, as do Beckmann and GGX. Smith's `G1` terms are
//! separable, `G = G1(ω_i) G1(ω_o)`, as Mitsuba's.
//!
//! In `f32` a distribution that takes `cos_h` cannot resolve lobes
//! narrower than about 3e-4 rad (`cos` of smaller angles rounds to 1);
//! the renderer's roughness floor (1e-4) plus the pixel footprint keeps
//! lobes wider than that in practice.

use super::COS_FLOOR;
pub use super::phong::sin2_between;
use super::phong::{EXP_CUTOFF, exp_cutoff, ln_cos};
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, FRAC_PI_2, LN_2, PI};

/// The half vector (lecture: "Reflection Geometry"): `H = (I + V) / |I + V|`.
/// For `I = −V` it is undefined;
/// gonio returns the zero vector there (not `n`): every term then sees
/// `N·H = I·H = V·H = 0`, so `D = 0`, `G1 = 0`, and the lobe is 0 — the
/// configuration has no microfacet that reflects `I` into `V`. (A one-sided
/// model never meets it: both directions are above the surface.)
pub fn half_vector(wi: DVec3, wo: DVec3) -> DVec3 {
    (wi + wo).normalize_or_zero()
}

/// Beckmann distribution (lecture: "Microfacet Distribution Functions",
/// used by Cook-Torrance): `exp(−tan²α / m²) / (π m² cos⁴α)`, `m` the RMS
/// slope. Normalized: `∫ D cosθ_h dω_h = 1`.
///
/// Takes `sin2_h = |N × H|²` besides `cos_h = N·H`: near the peak `cos_h`
/// rounds to 1 in `f32` (its ulp, 6e-8, is an angle of 3.5e-4 rad), which
/// would flatten lobes narrower than that; `|N × H|²` keeps full relative
/// precision for small angles. The exponent is tested before dividing
/// (`sin² ≥ 80 cos² m²` ⇔ exponent ≤ −80 → 0, [`exp_cutoff`]): no `tan²`
/// overflow and no `∞ · 0` from `1/cos⁴` as `cos_h → 0` (in `f32` too);
/// past the test `cos² > 1/81`, so the value is ≤ `1/(π m²)` = 3.2e7 at
/// m = 1e-4.
pub fn d_beckmann(m: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = cos_h.min(1.0); // rounding can pass 1
    let cos2 = cos_hc * cos_hc;
    let m2 = m * m;
    if sin2_h >= EXP_CUTOFF * cos2 * m2 {
        return 0.0; // exponent ≤ −80
    }
    let exponent = -sin2_h / (cos2 * m2); // in (−80, 0]; cos2 * m2 > 0 here
    exp_cutoff(exponent) / (PI * m2 * cos2 * cos2)
}

/// GGX / Trowbridge-Reitz distribution (Walter et al. 2007, eq. 33):
/// `α² / (π ((α² − 1) cos² + 1)²)`. Normalized.
///
/// The bracket is evaluated as `α² cos² + sin²` with `sin2_h = |N × H|²`
/// (see [`d_beckmann`] for why not `1 − cos²`): in `f32`, `α² − 1` rounds
/// to −1 for α < 2.4e-4 and the bracket would be 0 at `cos = 1`. It is ≥
/// about `min(α², 1)`, so the value is ≤ `1/(π α²)` = 3.2e7 at α = 1e-4.
/// Needs α > 0 (the renderer floors roughness at 1e-4).
pub fn d_ggx(alpha: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = cos_h.min(1.0); // rounding can pass 1
    let cos2 = cos_hc * cos_hc;
    let alpha2 = alpha * alpha;
    let d = alpha2 * cos2 + sin2_h; // = (α² − 1) cos² + 1
    alpha2 / (PI * d * d)
}

/// The exponent of the lecture's Blinn distribution ("Microfacet
/// Distribution Functions"): `e = −ln 2 / ln(cos m)` in `cos^e α`, which falls to ½ at `α = m` (`m` an angle in
/// radians, in (0, π/2); the renderer's (0, 1]). Large for small m:
/// e ≈ 2 ln 2 / m² = 1.39e8 at m = 1e-4.
///
/// `−ln cos m = −½ ln(1 − sin² m)` by `ln_1p`, accurate for small m where
/// `cos m` rounds towards 1. (WGSL has no `log1p`: its twin sums the
/// series `x + x²/2 + … + x⁸/8` for `x = sin² m < 0.1`, truncation
/// < 1.2e-9 relative, and uses `log(1 − x)` above.)
pub fn blinn_exponent(m: f64) -> f64 {
    let sin_m = m.sin();
    let x = sin_m * sin_m;
    let neg_ln_2x = -(-x).ln_1p(); // −2 ln cos m = −ln(1 − x)
    let neg_ln_cos = 0.5 * neg_ln_2x; // −ln cos m
    LN_2 / neg_ln_cos
}

/// Blinn's distribution as the lecture writes it ("Microfacet
/// Distribution Functions"): `cos^(−ln 2 / ln cos m) α`. Peak 1 at
/// `α = 0`, ½ at `α = m`; not normalized. Evaluated as
/// `exp(e · ½ ln(1 − sin²α))` from `sin2_h = |N × H|²` (see
/// [`d_beckmann`]): the exponent e reaches 1.4e8 at m = 1e-4, where `cos`
/// itself has no precision left in `f32`. 0 for `cos_h ≤ 0`, cut off below
/// `e^−80` ([`exp_cutoff`]).
///
/// Takes the exponent `e` = [`blinn_exponent`]`(m)`, not `m`: it depends
/// on the material alone, so the renderers compute it once in f64 (the GPU
/// gets it in the material buffer, `blinn_e`; WGSL's `sin` is only
/// accurate to 2⁻¹¹ absolute on Vulkan, which would move e by 10⁻³).
pub fn d_blinn_lecture(e: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    exp_cutoff(e * ln_cos(cos_h, sin2_h.min(1.0)))
}

/// Blinn's distribution normalized (Blinn 1977's form with the
/// normalization of Walter et al. 2007 "Phong" distribution):
/// `((e + 2) / (2π)) cos^e α`, `e` = [`blinn_exponent`]`(m)`, so that
/// `∫ D cosθ_h dω_h = 1`. At most `(e + 2)/(2π)` = 2.2e7 at m = 1e-4.
/// Takes `e` like [`d_blinn_lecture`].
pub fn d_blinn_normalized(e: f64, cos_h: f64, sin2_h: f64) -> f64 {
    (e + 2.0) * 0.5 * FRAC_1_PI * d_blinn_lecture(e, cos_h, sin2_h)
}

/// The Gaussian distribution as the lecture writes it ("Torrance-Sparrow,
/// Gaussian"): `exp(−ln 2 (α/m)²)`, `α` the angle between N and H, `m` an
/// angle in radians. Peak 1, ½ at `α = m`; not normalized. α =
/// `atan2(sqrt(sin2_h), cos_h)`, accurate at small angles where `acos(cos_h)`
/// is not (see [`d_beckmann`]); the exponential is cut off below `e^−80`
/// ([`exp_cutoff`]) like the others.
pub fn d_gaussian_lecture(m: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let alpha = sin2_h.max(0.0).sqrt().atan2(cos_h);
    let ratio = alpha / m;
    exp_cutoff(-LN_2 * ratio * ratio)
}

/// The lecture's Gaussian ("Microfacet Distribution Functions")
/// normalized: `norm · exp(−ln 2 (α/m)²)` with
/// `norm` = [`gaussian_normalization`]`(m)`, computed once per material on
/// the CPU and passed to the GPU in the material buffer (`d_norm`).
pub fn d_gaussian_normalized(m: f64, cos_h: f64, sin2_h: f64, norm: f64) -> f64 {
    norm * d_gaussian_lecture(m, cos_h, sin2_h)
}

/// Normalization of the lecture's Gaussian ("Microfacet Distribution
/// Functions"): `1 / (2π ∫_0^{π/2} exp(−ln 2 (θ/m)²) cosθ sinθ dθ)`, the factor that
/// makes the lecture's Gaussian satisfy `∫ D cosθ_h dω_h = 1`. CPU only
/// (f64); for m → 0 it tends to `ln 2 / (π m²)`.
///
/// Not a quadrature: the integral `J = ½ ∫_0^L e^{−aθ²} sin 2θ dθ`
/// (`a = ln 2 / m²`, `L = π/2`) is summed from the Taylor series of
/// `sin 2θ`, whose moments are incomplete gamma functions of integer order:
/// `J = ½ Σ_k (−1)^k c_k P(k+1, aL²)` with `c_k = 4^k k! / (a^{k+1} (2k+1)!)`
/// and `P` the regularized lower incomplete gamma (a Poisson tail,
/// `poisson_tail`).
///
/// Error bound: the terms alternate and, for `a ≥ 2/3` (m ≤ 1.019), decrease
/// in magnitude from the first (`c_{k+1}/c_k = 2 / (a (2k+3))`, `P`
/// decreasing in k), so the truncation error is at most the first omitted
/// term; summing stops when a term is below 1e-17 of the sum. Rounding:
/// at most 15 terms (m = 1; fewer for smaller m), each within ~10 ulp,
/// and the sum of their magnitudes at most 3.3× the result (m = 1): relative
/// error below 1e-13 for m ∈ (0, 1] (the test checks it against adaptive
/// quadrature to 1e-11).
pub fn gaussian_normalization(m: f64) -> f64 {
    let a = LN_2 / (m * m);
    let x = a * FRAC_PI_2 * FRAC_PI_2; // a L²
    let mut c = 1.0 / a; // c_0
    let mut sum = 0.0;
    for k in 0..1000u32 {
        let term = c * poisson_tail(k + 1, x);
        sum += if k % 2 == 0 { term } else { -term };
        if term <= 1e-17 * sum.abs() {
            break; // |remainder| ≤ next term ≤ this term
        }
        c *= 2.0 / (a * f64::from(2 * k + 3));
    }
    let j = 0.5 * sum;
    1.0 / (2.0 * PI * j)
}

/// `P(s, x) = γ(s, x) / Γ(s)` for integer `s ≥ 1`: the probability that a
/// Poisson variable of mean `x` is ≥ `s`. For `x > s` as
/// `1 − e^{−x} Σ_{j<s} x^j/j!` (the subtracted sum is below ~½, so no
/// cancellation to speak of), else as `e^{−x} x^s/s! Σ_j x^j/((s+1)…(s+j))`
/// (positive terms, ratio < 1).
fn poisson_tail(s: u32, x: f64) -> f64 {
    if x > f64::from(s) {
        let mut t = (-x).exp();
        let mut head = 0.0;
        for j in 0..s {
            head += t;
            t *= x / f64::from(j + 1);
        }
        1.0 - head
    } else {
        let mut t = (-x).exp();
        for j in 1..=s {
            t *= x / f64::from(j);
        }
        let (mut r, mut series) = (1.0, 1.0);
        for j in 1..10_000u32 {
            r *= x / f64::from(s + j);
            series += r;
            if r < 1e-17 * series {
                break;
            }
        }
        t * series
    }
}

/// `erfc(x)`, the complementary error function, to f64 precision (musl's
/// `erfc` by way of the `libm` crate; under 1 ulp). Its WGSL twin is
/// Abramowitz & Stegun 7.1.26, `|ε| ≤ 1.5e-7` absolute ([`ERFC_F32_ERROR`]).
pub fn erfc(x: f64) -> f64 {
    libm::erfc(x)
}

/// The absolute error bound of the WGSL `erfc` (Abramowitz & Stegun,
/// "Handbook of Mathematical Functions", 1964, 7.1.26, after Hastings):
/// `erfc(x) ≈ t (a₁ + t (a₂ + t (a₃ + t (a₄ + t a₅)))) e^{−x²}`,
/// `t = 1/(1 + p x)`, for `x ≥ 0`.
pub const ERFC_F32_ERROR: f64 = 1.5e-7;

/// `√π`.
const SQRT_PI: f64 = 1.772_453_850_905_516;

/// Past `a = 1/(m tanθ_v) ≥ 6` Smith-Beckmann's Λ is below
/// `Λ(6) = 1.1e-17`, under half an ulp of 1 in f64 (and f32): `G1 = 1`,
/// `Λ = 0` there, in both twins. The test also keeps `a` finite
/// (normal incidence, `sin = 0`, passes it).
pub const BECKMANN_A_CUTOFF: f64 = 6.0;

/// Smith's `G1` for Beckmann, exact (Walter et al. 2007, eq. 25 and 27):
/// `G1 = 1/(1 + Λ(a))`, `a = 1/(m tanθ_v)`,
/// `Λ(a) = (erf(a) − 1)/2 + e^{−a²}/(2a√π)`, times `χ⁺(cos_vh / cos_v)`.
/// `cos_v = N·V`, `cos_vh = V·H` for the direction v (ω_i or ω_o). Also the
/// G1 of the lecture's Blinn and Gaussian distributions, with the slopes
/// [`beckmann_slope_of_blinn`], [`beckmann_slope_of_gaussian`]. The
/// reference's truth; the GPU's default twin evaluates the same formula
/// with an f32 `erfc` ([`ERFC_F32_ERROR`]); [`g1_beckmann_rational`] is
/// the cheaper approximation the GPU offers as a knob
/// (`shading.smith_beckmann = "rational"`).
///
/// Evaluated without dividing by `a`: with `s = 2a√π`,
/// `2a√π Λ = e^{−a²} − (s/2) erfc(a)` (≥ 0; clamped so that an
/// approximate `erfc` cannot give `G1 > 1`) and `G1 = s / (s + 2a√π Λ)`;
/// the denominator is ≥ `e^{−a²} − a√π erfc(a) → 1` as `a → 0` (grazing),
/// where `G1 → 0`. 0 when `cos_v ≤ 0` (one-sided: below the horizon) or
/// `cos_vh ≤ 0` (the microfacet faces away from v; χ⁺). `a ≥ 6`
/// ([`BECKMANN_A_CUTOFF`]) is tested as `cos ≥ 6 m sin` (no division);
/// past it `m sin > cos / 6 > 0`. In [0, 1].
pub fn g1_beckmann(m: f64, cos_v: f64, cos_vh: f64) -> f64 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let sin_v = (1.0 - cos_vc * cos_vc).sqrt();
    if cos_vc >= BECKMANN_A_CUTOFF * m * sin_v {
        return 1.0; // a ≥ 6: Λ < 1.1e-17
    }
    let a = cos_vc / (m * sin_v);
    let s = 2.0 * SQRT_PI * a;
    let s_lambda = ((-a * a).exp() - 0.5 * s * erfc(a)).max(0.0); // 2a√π Λ
    s / (s + s_lambda)
}

/// Smith's `G1` for Beckmann, Walter et al. 2007's rational approximation
/// (eq. 27; Mitsuba uses the same): `a = 1/(m tanθ_v)`; `a ≥ 1.6 → 1`;
/// else `(3.535a + 2.181a²) / (1 + 2.276a + 2.577a²)`, times
/// `χ⁺(cos_vh / cos_v)`. The GPU's cheaper knob
/// (`shading.smith_beckmann = "rational"`); the reference uses
/// [`g1_beckmann`]. Up to [`G1_BECKMANN_RATIONAL_ERROR`] = 0.313 % above
/// the exact G1 (at `a ≈ 1.34`; Walter et al. say "within 0.35 %").
///
/// 0 when `cos_v ≤ 0` or `cos_vh ≤ 0`, as [`g1_beckmann`]. `a ≥ 1.6` is
/// tested as `cos ≥ 1.6 m sin` (no division; normal incidence, `sin = 0`,
/// gives 1); past it `m sin > cos / 1.6 > 0`. In [0, 1].
pub fn g1_beckmann_rational(m: f64, cos_v: f64, cos_vh: f64) -> f64 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let sin_v = (1.0 - cos_vc * cos_vc).sqrt();
    if cos_vc >= 1.6 * m * sin_v {
        return 1.0; // a ≥ 1.6
    }
    let a = cos_vc / (m * sin_v);
    let a2 = a * a;
    (3.535 * a + 2.181 * a2) / (1.0 + 2.276 * a + 2.577 * a2)
}

/// The largest relative difference of [`g1_beckmann_rational`] from the
/// exact [`g1_beckmann`], over all `a`: 0.3127 %, the rational above the
/// exact, at `a ≈ 1.336` (the test `rational_g1_error_bound` measures
/// it). A separable `G = G1(ω_i) G1(ω_o)` doubles it (0.627 % when both
/// directions sit at `a ≈ 1.34`), as does the height-correlated G of the
/// Λ twins (0.624 %).
pub const G1_BECKMANN_RATIONAL_ERROR: f64 = 0.003128;

/// The relative error the GPU's default (erf) Smith-Beckmann G1 may have
/// per direction, beyond the f32 rounding of its inputs: with
/// `G1 = 1/(1 + Λ)`, `δG1/G1 = G1 δΛ`, and
/// * the approximate `erfc` moves `2a√π Λ` by `a√π δerfc`, i.e. Λ by
///   `δerfc/2` ≤ [`ERFC_F32_ERROR`]/2 = 7.5e-8 (measured against f64:
///   6.9e-8);
/// * Vulkan allows `exp(x)` 3 + 2|x| ulp, `|x| = a² < 36`: 75 ulp on each
///   of the two `e^{−a²}` (one inside `erfc`), which moves Λ by at most
///   `(Λ + erfc(a)) · 75u` and G1 by `G1 (Λ + erfc(a)) · 75u ≤ 75u`
///   (`(Λ + erfc)/(1 + Λ) ≤ 1`, largest as `a → 0`), twice: 150u.
///
/// `u = 2⁻²⁴`. The rounding of the ~20 other operations (the cancellation
/// in `e^{−a²} − a√π erfc(a)` is amplified by the same factor ≤ 1) is
/// each test's own assembly term. A G of two directions (separable, or
/// height-correlated through the Λ twins) has twice this.
pub const G1_BECKMANN_F32_ERROR: f64 = 0.5 * ERFC_F32_ERROR + 150.0 / 16_777_216.0;

/// Smith's `G1` for GGX (Walter et al. 2007, eq. 34):
/// `2 / (1 + sqrt(1 + α² tan²θ_v))`, times `χ⁺(cos_vh / cos_v)`;
/// 0 for `cos_v ≤ 0` as [`g1_beckmann`]. Evaluated as
/// `2 cos / (cos + sqrt(cos² + α² sin²))` (the same number), which has no
/// `tan²` to overflow as `cos → 0`; the denominator is ≥ `cos > 0`. In [0, 1].
pub fn g1_ggx(alpha: f64, cos_v: f64, cos_vh: f64) -> f64 {
    if cos_v <= 0.0 || cos_vh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺(cos_vh / cos_v) = 0
    }
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let cos2 = cos_vc * cos_vc;
    let sin2 = 1.0 - cos2;
    2.0 * cos_vc / (cos_vc + (cos2 + alpha * alpha * sin2).sqrt())
}

/// Smith's Λ for Beckmann, exact (Walter et al. 2007, eq. 27; Heitz 2014,
/// eq. 72): `Λ(a) = (erf(a) − 1)/2 + e^{−a²}/(2a√π)`, `a = 1/(m tanθ_v)`,
/// the Λ of [`g1_beckmann`]'s G1 = 1/(1 + Λ), evaluated as
/// `(e^{−a²} − a√π erfc(a)) / (2a√π)` (numerator clamped at 0 as there);
/// `a ≥ 6 → 0` ([`BECKMANN_A_CUTOFF`]). Needs `cos_v > 0` (the caller's
/// χ⁺ test); grows as `1/(2a√π)` towards grazing (∞ where `a`
/// underflows, which [`g_smith_correlated`] turns into G = 0, the limit).
pub fn lambda_beckmann(m: f64, cos_v: f64) -> f64 {
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let sin_v = (1.0 - cos_vc * cos_vc).sqrt();
    if cos_vc >= BECKMANN_A_CUTOFF * m * sin_v {
        return 0.0; // a ≥ 6: Λ < 1.1e-17
    }
    let a = cos_vc / (m * sin_v);
    let s = 2.0 * SQRT_PI * a;
    ((-a * a).exp() - 0.5 * s * erfc(a)).max(0.0) / s
}

/// Smith's Λ for Beckmann, Walter et al. 2007's rational approximation
/// (the Λ of [`g1_beckmann_rational`]'s G1 = 1/(1 + Λ)):
/// `a = 1/(m tanθ_v)`; `a ≥ 1.6 → 0`; else
/// `(1 − 1.259a + 0.396a²) / (3.535a + 2.181a²)`. The GPU's knob, as
/// [`g1_beckmann_rational`]. Needs `cos_v > 0`; grows as `1/(3.535a)`
/// towards grazing.
pub fn lambda_beckmann_rational(m: f64, cos_v: f64) -> f64 {
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let sin_v = (1.0 - cos_vc * cos_vc).sqrt();
    if cos_vc >= 1.6 * m * sin_v {
        return 0.0; // a ≥ 1.6
    }
    let a = cos_vc / (m * sin_v);
    let a2 = a * a;
    (1.0 - 1.259 * a + 0.396 * a2) / (3.535 * a + 2.181 * a2)
}

/// Smith's Λ for GGX (Heitz 2014, eq. 72): `(sqrt(1 + α² tan²θ_v) − 1) / 2`,
/// evaluated as `α² sin² / (2 cos (cos + sqrt(cos² + α² sin²)))` (the same
/// number without the cancellation of `sqrt(1 + x) − 1` for small α).
/// Needs `cos_v > 0`, like [`lambda_beckmann`].
pub fn lambda_ggx(alpha: f64, cos_v: f64) -> f64 {
    let cos_vc = cos_v.min(1.0); // rounding can pass 1
    let cos2 = cos_vc * cos_vc;
    let a2s2 = alpha * alpha * (1.0 - cos2);
    a2s2 / (2.0 * cos_vc * (cos_vc + (cos2 + a2s2).sqrt()))
}

/// Height-correlated Smith (Heitz 2014, "Understanding the
/// Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99):
/// `G2 = χ⁺(I·H) χ⁺(V·H) / (1 + Λ(I) + Λ(V))`, from the two Λ
/// ([`lambda_ggx`], [`lambda_beckmann`]); 0 below either horizon. Never
/// below the separable `G1(I)·G1(V)` (masking and shadowing by the same
/// heights are correlated); in [0, 1].
pub fn g_smith_correlated(
    lambda_i: f64,
    lambda_o: f64,
    cos_i: f64,
    cos_o: f64,
    cos_ih: f64,
    cos_oh: f64,
) -> f64 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺ = 0
    }
    1.0 / (1.0 + lambda_i + lambda_o)
}

/// glTF's visibility term, height-correlated Smith for GGX (Appendix B,
/// "Specular BRDF"; Heitz 2014, eq. 99):
/// `Vis = G2 / (4 |N·L| |N·V|)
///      = ½ / (N·L √(N·V² (1 − α²) + α²) + N·V √(N·L² (1 − α²) + α²))`,
/// times `χ⁺(H·L) χ⁺(H·V)`; 0 below either horizon. The roots are taken
/// as `√(cos² + α² sin²)` (the same number; `1 − α²` rounds to 1 in `f32`
/// for α < 2.4e-4). The cosines in front of the roots are floored at
/// [`COS_FLOOR`], as Cook-Torrance's denominator is: at both grazing the
/// denominator tends to 0 and `D·Vis` would leave `f32`'s range; nothing
/// changes where both cosines exceed 1e-6.
pub fn vis_smith_ggx_correlated(
    alpha: f64,
    cos_i: f64,
    cos_o: f64,
    cos_ih: f64,
    cos_oh: f64,
) -> f64 {
    if cos_i <= 0.0 || cos_o <= 0.0 || cos_ih <= 0.0 || cos_oh <= 0.0 {
        return 0.0; // below the horizon, or χ⁺ = 0
    }
    let (ci, co) = (cos_i.min(1.0), cos_o.min(1.0)); // rounding can pass 1
    let alpha2 = alpha * alpha;
    let root_o = (co * co + alpha2 * (1.0 - co * co)).sqrt();
    let root_i = (ci * ci + alpha2 * (1.0 - ci * ci)).sqrt();
    0.5 / (ci.max(COS_FLOOR) * root_o + co.max(COS_FLOOR) * root_i)
}

/// Schlick's weight `w = (1 − |V·H|)⁵` (Appendix B, "Fresnel"), by
/// multiplications (no `pow`: WGSL's would take it from `log`, 2⁻²¹
/// absolute error in Vulkan).
pub fn schlick_weight(cos_oh: f64) -> f64 {
    let x = 1.0 - cos_oh.abs().min(1.0);
    let x2 = x * x;
    x2 * x2 * x
}

/// The Beckmann slope whose lobe matches the lecture's Blinn distribution
/// of angle `m`: `sqrt(2 / (e + 2))`, `e` = [`blinn_exponent`]`(m)`.
///
/// Derivation: the normalized Blinn `((e+2)/(2π)) cos^e α` and Beckmann
/// `exp(−tan²α/m_b²)/(π m_b² cos⁴α)` have equal peaks at `α = 0` iff
/// `m_b² = 2/(e+2)` (Walter et al. 2007's conversion `e = 2/m_b² − 2`);
/// for small angles `cos^e α ≈ exp(−e α²/2)` and Beckmann ≈ `exp(−α²/m_b²)`,
/// so the widths agree too, to O(1/e). For small m, `e ≈ 2 ln 2/m²` and
/// this tends to [`beckmann_slope_of_gaussian`]`(m)`.
/// Takes `e` like [`d_blinn_lecture`].
pub fn beckmann_slope_of_blinn(e: f64) -> f64 {
    (2.0 / (e + 2.0)).sqrt()
}

/// The Beckmann slope whose lobe matches the lecture's Gaussian of angle
/// `m`: `m / sqrt(ln 2)`. Derivation: for small angles `tan α ≈ α`, so
/// Beckmann's `exp(−tan²α/m_b²)` ≈ `exp(−α²/m_b²)`, which equals the
/// Gaussian's `exp(−ln 2 α²/m²)` iff `m_b² = m²/ln 2`.
pub fn beckmann_slope_of_gaussian(m: f64) -> f64 {
    m / LN_2.sqrt()
}

/// The lecture's "Final" geometric attenuation (V-grooves; Torrance &
/// Sparrow 1967, Cook & Torrance 1982):
/// `min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·I)/(V·H))`.
///
/// Both fractions share `V·H`, so the smaller is `2(N·H) min(N·V, N·I)/(V·H)`;
/// it is compared with `V·H` before dividing, so `V·H → 0` gives 1 (the
/// limit) instead of a division by 0. A cosine ≤ 0 (below the horizon, or
/// `H = 0`) gives 0, so G ∈ [0, 1] always.
pub fn g_vgroove(cos_h: f64, cos_o: f64, cos_i: f64, cos_oh: f64) -> f64 {
    let num = 2.0 * cos_h * cos_o.min(cos_i);
    if num <= 0.0 {
        return 0.0; // below the horizon, or H = 0
    }
    if num >= cos_oh {
        return 1.0; // min(1, …) = 1; includes V·H → 0
    }
    num / cos_oh // cos_oh > num > 0 here
}

/// The Cook-Torrance specular lobe (lecture: "Cook-Torrance Specular
/// Term"): `D G F / (denominator (N·V)(N·I))`, with `denominator` = 4 (the
/// microfacet standard, Walter et al. 2007, Mitsuba) or π (the lecture's,
/// which is not energy conserving: it is 4/π times the former).
///
/// The cosines are floored at `COS_FLOOR`: the form diverges at grazing
/// angles (D·G does not vanish there for `G = 1`); the floor keeps it
/// finite (≤ 3.2e7 · 1 / (4 · 1e-12) = 8e18, finite in `f32`) and changes
/// nothing where both cosines exceed 1e-6.
pub fn cook_torrance_specular(
    d: f64,
    g: f64,
    f: Rgb,
    cos_i: f64,
    cos_o: f64,
    denominator: f64,
) -> Rgb {
    f * (d * g / (denominator * cos_o.max(COS_FLOOR) * cos_i.max(COS_FLOOR)))
}

#[cfg(test)]
mod tests {
    /// `1 − c²`, the sin² the distributions take, for tests given a cosine.
    fn sin2_of(c: f64) -> f64 {
        (1.0 - c * c).max(0.0)
    }

    use super::super::fresnel::fresnel_conductor;
    use super::*;

    /// Adaptive Simpson on [a, b] to absolute tolerance `tol`.
    fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
        #[allow(clippy::too_many_arguments)]
        fn rec(
            f: &dyn Fn(f64) -> f64,
            a: f64,
            b: f64,
            fa: f64,
            fm: f64,
            fb: f64,
            whole: f64,
            tol: f64,
            depth: u32,
        ) -> f64 {
            let m = 0.5 * (a + b);
            let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
            let (flm, frm) = (f(lm), f(rm));
            let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
            let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
            let delta = left + right - whole;
            if depth == 0 || delta.abs() <= 15.0 * tol {
                return left + right + delta / 15.0;
            }
            rec(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1)
                + rec(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1)
        }
        let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
        let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
        rec(f, a, b, fa, fm, fb, whole, tol, 30)
    }

    /// `∫_0^{π/2} g(θ) dθ` for a lobe of width ~`w` at θ = 0: panels of
    /// width w/4 up to 12 w (so no adaptive step can miss the peak), then
    /// panels doubling in width to π/2 (heavy tails, GGX). Each panel to
    /// 1e-13 of the whole (estimated first by plain Simpson; tighter
    /// would chase rounding noise).
    fn integrate_lobe(g: &dyn Fn(f64) -> f64, w: f64) -> f64 {
        let mut edges = vec![0.0];
        let mut x = 0.0;
        while x < 12.0 * w && x < FRAC_PI_2 {
            x = (x + 0.25 * w).min(FRAC_PI_2);
            edges.push(x);
        }
        while x < FRAC_PI_2 {
            x = (2.0 * x).min(FRAC_PI_2);
            edges.push(x);
        }
        let plain: f64 = edges
            .windows(2)
            .map(|e| (e[1] - e[0]) / 6.0 * (g(e[0]) + 4.0 * g(0.5 * (e[0] + e[1])) + g(e[1])))
            .sum();
        let tol = 1e-13 * plain.abs() / edges.len() as f64;
        edges.windows(2).map(|e| simpson(g, e[0], e[1], tol)).sum()
    }

    /// `∫ D(h) cosθ_h dω_h = 2π ∫ D(cos θ) cosθ sinθ dθ`.
    fn projected_integral(d: &dyn Fn(f64) -> f64, width: f64) -> f64 {
        2.0 * PI * integrate_lobe(&|t: f64| d(t.cos()) * t.cos() * t.sin(), width)
    }

    type Lobe = Box<dyn Fn(f64) -> f64>;

    #[test]
    fn distributions_are_normalized() {
        for m in [0.05, 0.3, 1.0] {
            let norm = gaussian_normalization(m);
            let cases: [(&str, Lobe); 4] = [
                ("beckmann", Box::new(move |c| d_beckmann(m, c, sin2_of(c)))),
                ("ggx", Box::new(move |c| d_ggx(m, c, sin2_of(c)))),
                (
                    "blinn",
                    Box::new(move |c| d_blinn_normalized(blinn_exponent(m), c, sin2_of(c))),
                ),
                (
                    "gaussian",
                    Box::new(move |c| d_gaussian_normalized(m, c, sin2_of(c), norm)),
                ),
            ];
            for (name, d) in cases {
                let total = projected_integral(&*d, m);
                // Quadrature tolerance 1e-13 of the whole; the
                // e^−80 cut-off removes < 1e-30.
                assert!((total - 1.0).abs() < 1e-9, "{name} m {m}: {total}");
            }
        }
    }

    #[test]
    fn gaussian_normalization_matches_quadrature() {
        for m in [1e-4, 1e-3, 0.01, 0.05, 0.3, 0.7, 1.0] {
            let j = integrate_lobe(
                &|t: f64| (-LN_2 * (t / m).powi(2)).exp() * t.cos() * t.sin(),
                m,
            );
            let quad = 1.0 / (2.0 * PI * j);
            let series = gaussian_normalization(m);
            assert!(
                (series - quad).abs() < 1e-11 * quad,
                "m {m}: {series} vs {quad}"
            );
        }
        // The small-m limit: ln 2 / (π m²) (1 + O(m²)).
        let m = 1e-4;
        let limit = LN_2 / (PI * m * m);
        assert!((gaussian_normalization(m) / limit - 1.0).abs() < 1e-8);
    }

    #[test]
    fn lecture_distributions_peak_at_one_and_halve_at_m() {
        for m in [0.01, 0.05, 0.3, 1.0] {
            assert_eq!(
                d_blinn_lecture(blinn_exponent(m), 1.0, sin2_of(1.0)),
                1.0 - (-EXP_CUTOFF).exp()
            );
            assert_eq!(
                d_gaussian_lecture(m, 1.0, sin2_of(1.0)),
                1.0 - (-EXP_CUTOFF).exp()
            );
            let b = d_blinn_lecture(blinn_exponent(m), m.cos(), sin2_of(m.cos()));
            let g = d_gaussian_lecture(m, m.cos(), sin2_of(m.cos()));
            assert!((b - 0.5).abs() < 1e-10, "blinn m {m}: {b}");
            assert!((g - 0.5).abs() < 1e-10, "gaussian m {m}: {g}");
        }
        // The exponent by ln_1p agrees with the naive formula where that is accurate.
        for m in [0.3, 0.7, 1.0f64] {
            let naive = -LN_2 / m.cos().ln();
            assert!((blinn_exponent(m) - naive).abs() < 1e-13 * naive);
        }
        let m = 1e-4;
        assert!((blinn_exponent(m) * m * m / (2.0 * LN_2) - 1.0).abs() < 1e-8);
    }

    #[test]
    fn beckmann_slopes_match_the_lobes() {
        // Equal peaks of the normalized forms.
        for m in [0.05, 0.3, 1.0] {
            let mb = beckmann_slope_of_blinn(blinn_exponent(m));
            assert!(
                (d_blinn_normalized(blinn_exponent(m), 1.0, sin2_of(1.0))
                    - d_beckmann(mb, 1.0, sin2_of(1.0)))
                .abs()
                    < 1e-9 * d_beckmann(mb, 1.0, sin2_of(1.0))
            );
        }
        // Small m: Blinn's slope tends to the Gaussian's.
        let m = 1e-3;
        assert!(
            (beckmann_slope_of_blinn(blinn_exponent(m)) / beckmann_slope_of_gaussian(m) - 1.0)
                .abs()
                < 1e-6
        );
        assert!((beckmann_slope_of_gaussian(0.5) - 0.5 / LN_2.sqrt()).abs() < 1e-15);
    }

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// Directions on a coarse sphere grid, including grazing, below the
    /// horizon, and the poles.
    fn sphere() -> Vec<DVec3> {
        let mut out = vec![DVec3::Z, -DVec3::Z];
        for t in [
            1.0, 10.0, 30.0, 45.0, 60.0, 80.0, 89.0, 89.999, 90.0, 95.0, 135.0,
        ] {
            for p in [0.0, 37.0, 90.0, 150.0, 180.0, 250.0, 320.0] {
                out.push(dir(t, p));
            }
        }
        out
    }

    #[test]
    fn g1_and_vgroove_are_in_unit_interval() {
        let n = DVec3::Z;
        for wi in sphere() {
            for wo in sphere() {
                let h = half_vector(wi, wo);
                let (cos_i, cos_o, cos_h) = (n.dot(wi), n.dot(wo), n.dot(h));
                let (cos_ih, cos_oh) = (wi.dot(h), wo.dot(h));
                for m in [1e-4, 0.05, 0.3, 1.0] {
                    for g in [
                        g1_beckmann(m, cos_i, cos_ih),
                        g1_beckmann(m, cos_o, cos_oh),
                        g1_beckmann_rational(m, cos_i, cos_ih),
                        g1_beckmann_rational(m, cos_o, cos_oh),
                        g1_ggx(m, cos_i, cos_ih),
                        g1_ggx(m, cos_o, cos_oh),
                    ] {
                        assert!((0.0..=1.0).contains(&g), "{wi} {wo} m {m}: {g}");
                    }
                }
                let g = g_vgroove(cos_h, cos_o, cos_i, cos_oh);
                assert!((0.0..=1.0).contains(&g), "{wi} {wo}: {g}");
            }
        }
        // The rational approximation meets 1 continuously at a = 1.6.
        let a: f64 = 1.6;
        let r = (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
        assert!((r - 1.0).abs() < 1e-3, "{r}");
        // Normal incidence: no masking.
        assert_eq!(g1_beckmann(0.5, 1.0, 1.0), 1.0);
        assert_eq!(g1_beckmann_rational(0.5, 1.0, 1.0), 1.0);
        assert_eq!(g1_ggx(0.5, 1.0, 1.0), 1.0);
        // GGX G1 against the tan² form.
        let (alpha, theta) = (0.4, 70f64.to_radians());
        let tan2 = theta.tan().powi(2);
        let expected = 2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt());
        assert!((g1_ggx(alpha, theta.cos(), 0.5) - expected).abs() < 1e-15);
    }

    /// Distribution and G of every combination, with the exact conductor
    /// Fresnel: the assembled lobe for wi → wo.
    fn cook_torrance(
        dist: usize,
        geom: usize,
        m: f64,
        wi: DVec3,
        wo: DVec3,
        denominator: f64,
    ) -> Rgb {
        let n = DVec3::Z;
        let h = half_vector(wi, wo);
        let (cos_i, cos_o, cos_h) = (n.dot(wi), n.dot(wo), n.dot(h));
        let (cos_ih, cos_oh) = (wi.dot(h), wo.dot(h));
        let (d, slope) = match dist {
            0 => (d_beckmann(m, cos_h, sin2_of(cos_h)), m),
            1 => (d_ggx(m, cos_h, sin2_of(cos_h)), m),
            2 => (
                d_blinn_lecture(blinn_exponent(m), cos_h, sin2_of(cos_h)),
                beckmann_slope_of_blinn(blinn_exponent(m)),
            ),
            3 => (
                d_blinn_normalized(blinn_exponent(m), cos_h, sin2_of(cos_h)),
                beckmann_slope_of_blinn(blinn_exponent(m)),
            ),
            4 => (
                d_gaussian_lecture(m, cos_h, sin2_of(cos_h)),
                beckmann_slope_of_gaussian(m),
            ),
            _ => (
                d_gaussian_normalized(m, cos_h, sin2_of(cos_h), gaussian_normalization(m)),
                beckmann_slope_of_gaussian(m),
            ),
        };
        let g = match geom {
            0 => 1.0,
            1 => g_vgroove(cos_h, cos_o, cos_i, cos_oh),
            _ if dist == 1 => g1_ggx(m, cos_i, cos_ih) * g1_ggx(m, cos_o, cos_oh),
            _ => g1_beckmann(slope, cos_i, cos_ih) * g1_beckmann(slope, cos_o, cos_oh),
        };
        let f = fresnel_conductor(
            cos_ih,
            Rgb::new(0.370, 0.177, 2.485),
            Rgb::new(2.820, 3.638, 3.433),
        );
        cook_torrance_specular(d, g, f, cos_i, cos_o, denominator)
    }

    #[test]
    fn cook_torrance_is_reciprocal() {
        let dirs: Vec<DVec3> = [
            (5.0, 0.0),
            (30.0, 20.0),
            (45.0, 200.0),
            (60.0, 90.0),
            (80.0, 170.0),
            (89.0, 10.0),
        ]
        .iter()
        .map(|&(t, p)| dir(t, p))
        .collect();
        for dist in 0..6 {
            for geom in 0..3 {
                for m in [0.05, 0.3, 1.0] {
                    for &wi in &dirs {
                        for &wo in &dirs {
                            for den in [4.0, PI] {
                                let a = cook_torrance(dist, geom, m, wi, wo, den);
                                let b = cook_torrance(dist, geom, m, wo, wi, den);
                                let err = (a - b).abs().max_element();
                                assert!(
                                    err <= 1e-12 * a.max_element().max(1e-300),
                                    "dist {dist} geom {geom} m {m}: {a} vs {b}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// White furnace (F = 1, 4 (N·V)(N·I)): the albedo of Smith-GGX is ≤ 1
    /// (separable Smith loses energy to masking, never gains). Midpoint rule,
    /// 2000 × 4000 cells over the hemisphere of ω_o (φ by symmetry).
    #[test]
    fn smith_ggx_white_furnace_albedo_is_at_most_one() {
        let n = DVec3::Z;
        let (nt, np) = (2000, 2000);
        let (dt, dp) = (FRAC_PI_2 / nt as f64, PI / np as f64);
        for alpha in [0.1, 0.5, 1.0] {
            for deg in [0.0, 45.0, 80.0f64] {
                let wi = dir(deg, 0.0);
                let mut sum = 0.0;
                for a in 0..nt {
                    let (st, ct) = ((a as f64 + 0.5) * dt).sin_cos();
                    let mut ring = 0.0;
                    for b in 0..np {
                        let (sp, cp) = ((b as f64 + 0.5) * dp).sin_cos();
                        let wo = DVec3::new(st * cp, st * sp, ct);
                        let h = half_vector(wi, wo);
                        let (cos_i, cos_o, cos_h) = (n.dot(wi), n.dot(wo), n.dot(h));
                        let g = g1_ggx(alpha, cos_i, wi.dot(h)) * g1_ggx(alpha, cos_o, wo.dot(h));
                        ring += cook_torrance_specular(
                            d_ggx(alpha, cos_h, sin2_of(cos_h)),
                            g,
                            Rgb::ONE,
                            cos_i,
                            cos_o,
                            4.0,
                        )
                        .x;
                    }
                    sum += ring * ct * st;
                }
                let albedo = 2.0 * sum * dt * dp;
                eprintln!("smith-ggx α {alpha} θ_i {deg}°: albedo {albedo:.5}");
                // α = 1 loses most: D = 1/π, and at θ_i = 0 the albedo is
                // exactly 1 − ln 2 = 0.3069.
                assert!(
                    albedo <= 1.0 && albedo > 0.3,
                    "α {alpha} θ_i {deg}°: {albedo}"
                );
            }
        }
    }

    #[test]
    fn finite_at_the_extremes() {
        let coss = [
            -1.0,
            -1e-8,
            0.0,
            1e-300,
            1e-8,
            1e-4,
            0.5,
            1.0 - 1e-12,
            1.0,
            1.0 + 1e-7,
        ];
        let roughs = [1e-4, 1e-3, 0.05, 0.3, 1.0];
        for &m in &roughs {
            let norm = gaussian_normalization(m);
            assert!(norm.is_finite() && norm > 0.0);
            for &c in &coss {
                let ds = [
                    d_beckmann(m, c, sin2_of(c)),
                    d_ggx(m, c, sin2_of(c)),
                    d_blinn_lecture(blinn_exponent(m), c, sin2_of(c)),
                    d_blinn_normalized(blinn_exponent(m), c, sin2_of(c)),
                    d_gaussian_lecture(m, c, sin2_of(c)),
                    d_gaussian_normalized(m, c, sin2_of(c), norm),
                ];
                for d in ds {
                    assert!(d.is_finite() && d >= 0.0, "m {m} cos {c}: {d}");
                    if c <= 0.0 {
                        assert_eq!(d, 0.0);
                    }
                    // and the assembled lobe at the cosine floor
                    let f = cook_torrance_specular(d, 1.0, Rgb::ONE, c, c, 4.0);
                    assert!(f.is_finite(), "{f}");
                }
                for &c2 in &coss {
                    for g in [
                        g1_beckmann(m, c, c2),
                        g1_beckmann_rational(m, c, c2),
                        g1_ggx(m, c, c2),
                        g_vgroove(c, c2, c, c2),
                        g_vgroove(c, c, c2, c2),
                        g_vgroove(c2, c, c, 0.0),
                    ] {
                        assert!(
                            g.is_finite() && (0.0..=1.0).contains(&g),
                            "m {m} {c} {c2}: {g}"
                        );
                    }
                }
            }
        }
        for m in [1e-4, 1.0] {
            assert!(beckmann_slope_of_blinn(blinn_exponent(m)).is_finite());
            assert!(beckmann_slope_of_gaussian(m).is_finite());
        }
        assert_eq!(half_vector(DVec3::Z, -DVec3::Z), DVec3::ZERO);
        assert_eq!(half_vector(dir(30.0, 10.0), -dir(30.0, 10.0)), DVec3::ZERO);
    }

    /// Golden values computed independently (Python's `cmath` and
    /// `math.erf`, outside this crate): gold (η 0.370, κ 2.820), Beckmann
    /// m = 0.5, ω_i at 80°, ω_o its mirror image (so H = N, D = 1/(π m²)),
    /// Smith G with the exact G1 and with Walter's rational one
    /// (a = 1/(m tan 80°) = 0.35265), exact Fresnel at cos 80°,
    /// denominator 4.
    #[test]
    fn golden_beckmann_smith_gold() {
        let n = DVec3::Z;
        let wi = dir(80.0, 0.0);
        let wo = dir(80.0, 180.0);
        let h = half_vector(wi, wo);
        let m = 0.5;
        let d = d_beckmann(m, n.dot(h), sin2_between(n, h));
        let g = g1_beckmann(m, n.dot(wi), wi.dot(h)) * g1_beckmann(m, n.dot(wo), wo.dot(h));
        let g_rational = g1_beckmann_rational(m, n.dot(wi), wi.dot(h))
            * g1_beckmann_rational(m, n.dot(wo), wo.dot(h));
        let f = fresnel_conductor(wi.dot(h), Rgb::splat(0.370), Rgb::splat(2.820));
        let fr = cook_torrance_specular(d, g, f, n.dot(wi), n.dot(wo), 4.0);
        let fr_rational = cook_torrance_specular(d, g_rational, f, n.dot(wi), n.dot(wo), 4.0);
        assert!((d - GOLDEN_D).abs() < 1e-12 * GOLDEN_D, "D {d}");
        assert!((g - GOLDEN_G).abs() < 1e-12, "G {g}");
        assert!((g_rational - GOLDEN_G_RATIONAL).abs() < 1e-12, "G {g}");
        assert!((f.x - GOLDEN_F).abs() < 1e-12, "F {}", f.x);
        assert!((fr.x - GOLDEN_FR).abs() < 1e-10 * GOLDEN_FR, "f_r {}", fr.x);
        assert!(
            (fr_rational.x - GOLDEN_FR_RATIONAL).abs() < 1e-10 * GOLDEN_FR_RATIONAL,
            "f_r {}",
            fr_rational.x
        );
    }

    const GOLDEN_D: f64 = 1.2732395447351628;
    const GOLDEN_G: f64 = 0.5121120828428586;
    const GOLDEN_G_RATIONAL: f64 = 0.511113540423823;
    const GOLDEN_F: f64 = 0.887398175401015;
    const GOLDEN_FR: f64 = 4.79725960936903;
    const GOLDEN_FR_RATIONAL: f64 = 4.787905666403089;

    /// Smith's Λ for Beckmann by its definition (Smith 1967; Heitz 2014,
    /// eq. 72 and 86): `Λ(μ) = (1/μ) ∫_μ^∞ (q − μ) p(q) dq` with the slope
    /// marginal `p(q) = e^{−q²/m²}/(m√π)` and `μ = cot θ_v`; with
    /// `s = q/m`, `a = μ/m`: `(1/a) ∫_a^∞ (s − a) e^{−s²}/√π ds`. Composite
    /// Simpson on [a, a + 9] (the tail beyond holds `e^{−81}` of it),
    /// 200000 intervals: the integrand decays at the rate 2a ≤ 12, so the
    /// rule's relative error is of order `(2a h)⁴/180` ≤ 4e-15 (with 20000
    /// intervals it was 1e-10 at a = 5.5, measured against mpmath). No
    /// `erf` involved.
    fn lambda_by_integration(m: f64, cos_v: f64) -> f64 {
        let sin_v = (1.0 - cos_v * cos_v).sqrt();
        let a = cos_v / (m * sin_v);
        let n = 200_000;
        let h = 9.0 / n as f64;
        let f = |s: f64| (s - a) * (-s * s).exp() / PI.sqrt();
        let mut sum = f(a) + f(a + 9.0);
        for k in 1..n {
            sum += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * h / 3.0 / a
    }

    /// The exact Λ and G1 against Smith's integral, from grazing to the
    /// cut-off: Λ to 1e-11 relative (the integration's error, with the
    /// cancellation in `e^{−a²} − a√π erfc(a)` amplifying f64 rounding by
    /// at most 2a² ≤ 72), G1 to that through `dG1/dΛ = −G1²`; and
    /// G1 = 1/(1 + Λ) of the twin to 1e-15.
    #[test]
    fn lambda_beckmann_matches_the_smith_integral() {
        let mut checked = 0;
        for m in [0.01, 0.1, 0.3, 0.7, 1.0] {
            for k in 1..200 {
                let cos_v = k as f64 / 200.0;
                let lambda = lambda_beckmann(m, cos_v);
                let truth = lambda_by_integration(m, cos_v);
                let g1 = g1_beckmann(m, cos_v, 1.0);
                // Λ's 1e-11 through dG1/dΛ = −G1², plus rounding.
                let g1_tol = 1e-11 * truth / (1.0 + truth).powi(2) + 1e-15;
                assert!(
                    (g1 - 1.0 / (1.0 + truth)).abs() < g1_tol,
                    "m {m} cos {cos_v}: G1 {g1} vs {}",
                    1.0 / (1.0 + truth)
                );
                assert!((g1 - 1.0 / (1.0 + lambda)).abs() < 1e-15);
                let a = cos_v / (m * (1.0 - cos_v * cos_v).sqrt());
                if a < BECKMANN_A_CUTOFF {
                    assert!(
                        (lambda - truth).abs() <= 1e-11 * truth,
                        "m {m} cos {cos_v} (a {a}): Λ {lambda} vs {truth}"
                    );
                    checked += 1;
                } else {
                    assert_eq!(lambda, 0.0);
                    assert!(truth < 1.1e-17, "a {a}: Λ {truth}");
                }
            }
        }
        assert!(checked > 300, "{checked}");
        // Known value: Λ(1) = (e⁻¹ − √π erfc 1)/(2√π), erfc(1) =
        // 0.15729920705028513066 (A&S table 7.1).
        let lambda_1 = ((-1f64).exp() - PI.sqrt() * 0.157_299_207_050_285_13) / (2.0 * PI.sqrt());
        let cos_v = 1.0 / 2f64.sqrt(); // m = 1, θ = 45°: a = 1
        assert!((lambda_beckmann(1.0, cos_v) - lambda_1).abs() < 1e-15);
    }

    /// Walter's rational G1 against the exact one over a: the largest
    /// relative difference is the documented bound
    /// [`G1_BECKMANN_RATIONAL_ERROR`] (within 0.1 % of it, so the bound is
    /// tight), and the two-direction G's twice that.
    #[test]
    fn rational_g1_error_bound() {
        let (mut worst, mut at) = (0.0f64, 0.0);
        let (mut worst_g, mut worst_corr) = (0.0f64, 0.0f64);
        for k in 1..=80_000 {
            let a = k as f64 * 1e-4; // up to 8, past both cut-offs
            // m = 1: cos/sin = a.
            let cos_v = a / (1.0 + a * a).sqrt();
            let exact = g1_beckmann(1.0, cos_v, 1.0);
            let rational = g1_beckmann_rational(1.0, cos_v, 1.0);
            let rel = (rational / exact - 1.0).abs();
            if rel > worst {
                (worst, at) = (rel, a);
            }
            worst_g = worst_g.max((rational * rational / (exact * exact) - 1.0).abs());
            let corr = |l: f64| 1.0 / (1.0 + 2.0 * l);
            worst_corr = worst_corr.max(
                (corr(lambda_beckmann_rational(1.0, cos_v)) / corr(lambda_beckmann(1.0, cos_v))
                    - 1.0)
                    .abs(),
            );
        }
        eprintln!(
            "rational G1: worst {worst:.5e} at a = {at}; separable G {worst_g:.5e}; correlated G {worst_corr:.5e}"
        );
        assert!(
            (0.999 * G1_BECKMANN_RATIONAL_ERROR..=G1_BECKMANN_RATIONAL_ERROR).contains(&worst),
            "{worst} at a = {at}"
        );
        assert!((1.30..1.37).contains(&at), "{at}");
        assert!(worst_g <= 2.01 * G1_BECKMANN_RATIONAL_ERROR, "{worst_g}");
        assert!(
            worst_corr <= 2.0 * G1_BECKMANN_RATIONAL_ERROR,
            "{worst_corr}"
        );
    }

    /// Every BRDF WGSL file parses and validates with naga, in the order the
    /// renderer concatenates them.
    #[test]
    fn wgsl_files_validate() {
        let common = crate::gpu::shader_gen::common(&[]);
        let source = [
            common.as_str(),
            include_str!("../../../shaders/brdf/lambert.wgsl"),
            include_str!("../../../shaders/brdf/phong.wgsl"),
            include_str!("../../../shaders/brdf/fresnel.wgsl"),
            include_str!("../../../shaders/brdf/microfacet.wgsl"),
            include_str!("../../../shaders/brdf/ward.wgsl"),
            "@compute @workgroup_size(1) fn main() {}\n",
        ]
        .join("\n");
        let module = naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::empty(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
    }
}
