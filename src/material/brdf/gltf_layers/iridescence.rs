//! The thin-film Fresnel of `KHR_materials_iridescence` (contract:
//! "Layered glTF materials", "Iridescence"; pinned choices 1-3): Belcour &
//! Barla (2017, "A Practical Extension to Microfacet Theory for the
//! Modeling of Varying Iridescence", ACM TOG 36(4), §4 and the
//! supplemental's analytic XYZ sensitivity), in the form of the Khronos
//! glTF Sample Renderer (`evalIridescence`, `evalSensitivity`): an Airy
//! summation of a film of index `n₂` and thickness `d` over a base whose
//! index is recovered from its normal-incidence reflectance `f`, with
//! Schlick's Fresnel at each interface, the first two orders of the
//! Fourier series integrated against Gaussian fits of the CIE 1931
//! matching functions, then taken from XYZ to linear Rec.709.
//!
//! All lengths in nm. Evaluated at `cos θ₁ = N·V` (pinned choice 1), so
//! the layer depends on the view alone (not reciprocal).
//!
//! WGSL twin: `shaders/brdf/gltf_layers/iridescence.wgsl`.

use crate::base::Rgb;
use crate::material::brdf::microfacet::schlick_weight;
use std::f64::consts::{PI, TAU};

/// XYZ → linear Rec.709 (sRGB primaries, D65), rows.
pub const XYZ_TO_REC709: [[f64; 3]; 3] = [
    [3.2404542, -1.5371385, -0.4985314],
    [-0.9692660, 1.8760108, 0.0415560],
    [0.0556434, -0.2040259, 1.0572252],
];

/// Belcour & Barla's Gaussian fits of the CIE 1931 2° matching functions
/// in the Fourier domain (supplemental, as the Sample Renderer types
/// them): amplitude `v`, position `p`, variance `σ` per XYZ component,
/// and the second lobe of X.
pub const SENSITIVITY_V: [f64; 3] = [5.4856e-13, 4.4201e-13, 5.2481e-13];
pub const SENSITIVITY_P: [f64; 3] = [1.6810e6, 1.7953e6, 2.2084e6];
pub const SENSITIVITY_SIGMA: [f64; 3] = [4.3278e9, 9.3046e9, 6.6121e9];
pub const SENSITIVITY_X2: [f64; 3] = [9.7470e-14, 2.2399e6, 4.5282e9];
/// The normalization of the sensitivity (`∫ ȳ` in the fit's units).
pub const SENSITIVITY_NORM: f64 = 1.0685e-7;

/// The thickness below which the film's index blends towards the
/// outside's (1): `smoothstep(0, 0.03, d)` (pinned choice 2).
pub const THIN_FILM_BLEND_NM: f64 = 0.03;

/// `cos x` with `x` first reduced to `[−π, π]`: the WGSL twin reduces
/// because Vulkan bounds `cos`'s error (2⁻¹¹ absolute) only there; the
/// arguments reach a few hundred radians for thick films.
pub fn cos_wrapped(x: f64) -> f64 {
    (x - TAU * (x / TAU).round()).cos()
}

/// `𝒮(x, φ)`: the sensitivity of the Fourier term of optical path
/// difference `x` \[nm\] and phase shifts `shift` (one per RGB channel,
/// applied to the XYZ component of the same index, as the Sample Renderer
/// does), in linear Rec.709.
pub fn eval_sensitivity(opd: f64, shift: Rgb) -> Rgb {
    let phase = TAU * opd * 1e-9;
    let mut xyz: [f64; 3] = std::array::from_fn(|k| {
        let (v, p, s) = (SENSITIVITY_V[k], SENSITIVITY_P[k], SENSITIVITY_SIGMA[k]);
        v * (TAU * s).sqrt() * cos_wrapped(p * phase + shift[k]) * (-phase * phase * s).exp()
    });
    let [v2, p2, s2] = SENSITIVITY_X2;
    xyz[0] +=
        v2 * (TAU * s2).sqrt() * cos_wrapped(p2 * phase + shift[0]) * (-s2 * phase * phase).exp();
    let xyz = Rgb::from_array(xyz) / SENSITIVITY_NORM;
    let m = XYZ_TO_REC709;
    Rgb::new(
        Rgb::from_array(m[0]).dot(xyz),
        Rgb::from_array(m[1]).dot(xyz),
        Rgb::from_array(m[2]).dot(xyz),
    )
}

/// `((n_a − n_b)/(n_a + n_b))²`: normal-incidence reflectance between two
/// indices.
pub fn ior_to_f0(n_a: f64, n_b: f64) -> f64 {
    let r = (n_a - n_b) / (n_a + n_b);
    r * r
}

/// The index whose normal-incidence reflectance from air is `f`:
/// `(1 + √f)/(1 − √f)`, `f` clamped to `[0, 0.9999]` (pinned choice 3).
pub fn f0_to_ior(f: f64) -> f64 {
    let s = f.clamp(0.0, 0.9999).sqrt();
    (1.0 + s) / (1.0 - s)
}

/// `F_ir(f)`: the reflectance of a film of index `eta_f` and thickness
/// `thickness` nm on a base of normal-incidence reflectance `base_f0`
/// (RGB), seen at `cos θ₁ = cos_o` (contract formula, line by line).
pub fn iridescence_fresnel(cos_o: f64, eta_f: f64, thickness: f64, base_f0: Rgb) -> Rgb {
    let x = (thickness / THIN_FILM_BLEND_NM).clamp(0.0, 1.0);
    let n2 = 1.0 + (eta_f - 1.0) * (x * x * (3.0 - 2.0 * x));
    let cos1 = cos_o.clamp(0.0, 1.0);
    let cos2 = (1.0 - (1.0 - cos1 * cos1) / (n2 * n2)).sqrt();
    // First interface (air → film): φ₂₁ = π since n₂ ≥ 1.
    let r12 = {
        let r0 = ior_to_f0(n2, 1.0);
        r0 + (1.0 - r0) * schlick_weight(cos1)
    };
    let t121 = 1.0 - r12;
    let opd = 2.0 * n2 * thickness * cos2;
    let mut r23 = Rgb::ZERO;
    let mut phi = Rgb::ZERO;
    for c in 0..3 {
        let n3 = f0_to_ior(base_f0[c]);
        let r1 = ior_to_f0(n3, n2);
        r23[c] = r1 + (1.0 - r1) * schlick_weight(cos2);
        phi[c] = PI + if n3 < n2 { PI } else { 0.0 };
    }
    let r123 = (r23 * r12).clamp(Rgb::splat(1e-5), Rgb::splat(0.9999));
    let r = Rgb::new(r123.x.sqrt(), r123.y.sqrt(), r123.z.sqrt());
    let rs = r23 * (t121 * t121) / (Rgb::ONE - r123);
    let mut out = rs + r12;
    let mut cm = rs - t121;
    for m in 1..=2 {
        cm *= r;
        out += cm * eval_sensitivity(m as f64 * opd, phi * m as f64) * 2.0;
    }
    out.max(Rgb::ZERO)
}
