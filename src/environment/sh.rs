//! Real spherical harmonics up to band 4 (25 functions): the lecture's
//! "ortho-normal function basis on the sphere, mathematically elegant
//! filtering, illumination-BRDF integration".
//!
//! Irradiance from an environment (Ramamoorthi & Hanrahan 2001, "An
//! Efficient Representation for Irradiance Environment Maps"): with the
//! radiance projected, `L(ω) = Σ L_lm Y_lm(ω)`, the irradiance of a surface
//! with normal `n`, `E(n) = ∫ L(ω) max(0, n·ω) dω`, is by the Funk–Hecke
//! theorem `E(n) = Σ Â_l L_lm Y_lm(n)` with the clamped cosine's
//! coefficients `Â_0 = π`, `Â_1 = 2π/3`, `Â_2 = π/4`, `Â_3 = 0`,
//! `Â_4 = −π/24` (odd bands above 1 vanish). Truncating after band 2 (9
//! coefficients) leaves, for a single directional light, an error of at
//! most 9.375 % of the peak (at the horizon, `n·ω = 0`; see the test).
//!
//! The basis is written in world coordinates with the polynomial forms of
//! Sloan ("Stupid Spherical Harmonics Tricks", 2008, appendix A2): any
//! orthonormal real basis gives the same `E(n)`. WGSL twin: `sh_basis` in
//! `shaders/environment.wgsl` (same functions, same order).

use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::PI;

/// The highest band gonio projects to.
pub const MAX_ORDER: u32 = 4;
/// Coefficients up to [`MAX_ORDER`]: `(MAX_ORDER + 1)²`.
pub const COUNT: usize = 25;

/// Coefficients of bands `0..=order`.
pub fn count(order: u32) -> usize {
    ((order + 1) * (order + 1)) as usize
}

/// The band `l` of coefficient `i` (`l² ≤ i < (l + 1)²`).
pub fn band(i: usize) -> u32 {
    (i as f64).sqrt().floor() as u32
}

/// `Â_l`: the clamped cosine `max(0, cos θ)`'s zonal coefficient times
/// `√(4π/(2l+1))` (Ramamoorthi & Hanrahan 2001, eq. 8–9).
pub fn cosine_lobe(l: u32) -> f64 {
    match l {
        0 => PI,
        1 => 2.0 * PI / 3.0,
        2 => PI / 4.0,
        4 => -PI / 24.0,
        _ => 0.0,
    }
}

/// The 25 real spherical harmonics at unit direction `d`, bands 0 to 4,
/// `m = −l..=l` in order.
pub fn basis(d: DVec3) -> [f64; COUNT] {
    let (x, y, z) = (d.x, d.y, d.z);
    let (x2, y2, z2) = (x * x, y * y, z * z);
    [
        // l = 0
        0.282_094_791_773_878_1,
        // l = 1
        0.488_602_511_902_919_9 * y,
        0.488_602_511_902_919_9 * z,
        0.488_602_511_902_919_9 * x,
        // l = 2
        1.092_548_430_592_079 * x * y,
        1.092_548_430_592_079 * y * z,
        0.315_391_565_252_520_05 * (3.0 * z2 - 1.0),
        1.092_548_430_592_079 * x * z,
        0.546_274_215_296_039_5 * (x2 - y2),
        // l = 3
        0.590_043_589_926_643_5 * y * (3.0 * x2 - y2),
        2.890_611_442_640_554 * x * y * z,
        0.457_045_799_464_465_8 * y * (5.0 * z2 - 1.0),
        0.373_176_332_590_115_4 * z * (5.0 * z2 - 3.0),
        0.457_045_799_464_465_8 * x * (5.0 * z2 - 1.0),
        1.445_305_721_320_277 * z * (x2 - y2),
        0.590_043_589_926_643_5 * x * (x2 - 3.0 * y2),
        // l = 4
        2.503_342_941_796_705 * x * y * (x2 - y2),
        1.770_130_769_779_931 * y * z * (3.0 * x2 - y2),
        0.946_174_695_757_560 * x * y * (7.0 * z2 - 1.0),
        0.669_046_543_557_289 * y * z * (7.0 * z2 - 3.0),
        0.105_785_546_915_204 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0),
        0.669_046_543_557_289 * x * z * (7.0 * z2 - 3.0),
        0.473_087_347_878_780 * (x2 - y2) * (7.0 * z2 - 1.0),
        1.770_130_769_779_931 * x * z * (x2 - 3.0 * y2),
        0.625_835_735_449_176 * (x2 * x2 - 6.0 * x2 * y2 + y2 * y2),
    ]
}

/// The irradiance coefficients `Â_l · L_lm` of radiance coefficients
/// `radiance` (at least `count(order)` of them), bands above `order`
/// zero: `E(n) = Σ_i c_i Y_i(n)` ([`evaluate`]).
pub fn irradiance_coefficients(radiance: &[Rgb], order: u32) -> [Rgb; COUNT] {
    let mut out = [Rgb::ZERO; COUNT];
    for (i, c) in out.iter_mut().enumerate().take(count(order)) {
        *c = radiance[i] * cosine_lobe(band(i));
    }
    out
}

/// `Σ_i c_i Y_i(d)`: the function with coefficients `c` at unit `d`.
pub fn evaluate(c: &[Rgb; COUNT], d: DVec3) -> Rgb {
    basis(d)
        .iter()
        .zip(c)
        .fold(Rgb::ZERO, |sum, (y, c)| sum + *c * *y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::latlong;
    use std::f64::consts::TAU;

    /// `∫ f(ω) dω` by 3-point Gauss–Legendre in cos θ and the midpoint rule
    /// in φ on a 64 × 32 grid. Products of two band-≤4 functions have
    /// degree ≤ 8: exact in φ (64 points), and 3 points per row integrate
    /// degree 5 exactly, leaving a remainder of order (1/32)⁶ · 8! / 6!
    /// ≈ 1e-8 for the degree-6 to 8 parts.
    fn integrate(f: impl Fn(DVec3) -> f64) -> f64 {
        let (w, h) = (64, 32);
        let nodes = [
            (-(0.6f64).sqrt(), 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            ((0.6f64).sqrt(), 5.0 / 9.0),
        ];
        let mut sum = 0.0;
        for row in 0..h {
            let (top, bottom) = latlong::row_cos_bounds(row, h);
            for (x, weight) in nodes {
                let mu = 0.5 * (top + bottom) + 0.5 * (top - bottom) * x;
                for col in 0..w {
                    let phi = TAU * (col as f64 + 0.5) / w as f64;
                    let d = latlong::direction_phi_cos(phi, mu);
                    sum += f(d) * weight * 0.5 * (top - bottom) * TAU / w as f64;
                }
            }
        }
        sum
    }

    #[test]
    fn the_basis_is_orthonormal() {
        for i in 0..COUNT {
            for j in 0..=i {
                let dot = integrate(|d| {
                    let y = basis(d);
                    y[i] * y[j]
                });
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((dot - want).abs() < 1e-7, "<Y{i}, Y{j}> = {dot}");
            }
        }
    }

    #[test]
    fn the_cosine_lobe_reproduces_the_clamped_cosine_in_the_limit() {
        // E of a delta light from d at n: Σ_l Â_l (2l+1)/(4π) P_l(n·d).
        let d = DVec3::new(0.3, 0.8, -0.52).normalize();
        let delta: Vec<Rgb> = basis(d).iter().map(|&y| Rgb::splat(y)).collect();
        let e = |order: u32, n: DVec3| evaluate(&irradiance_coefficients(&delta, order), n).x;
        // Band 0 alone: the mean of max(0, cos) over the sphere, 1/4.
        assert!((e(0, DVec3::X) - 0.25).abs() < 1e-12);
        // Order 2 (Ramamoorthi & Hanrahan's worst case): 1.0625 facing the
        // light, 0.09375 (9.375 % of the peak 1) at the horizon.
        assert!((e(2, d) - 1.0625).abs() < 1e-12);
        let horizon = d.cross(DVec3::Z).normalize();
        assert!((e(2, horizon) - 0.09375).abs() < 1e-12);
        // Order 4: 1 − 1/4 · … : closer at the peak.
        assert!((e(4, d) - 1.0).abs() < (e(2, d) - 1.0).abs());
    }
}
