//! Glossy reflection of the lecture's Phong lobes by spherical-harmonic
//! convolution (`environment.specular = "sh"`): Ramamoorthi & Hanrahan
//! (2002), "Frequency Space Environment Map Rendering", section 3: a lobe
//! that is rotationally symmetric about the mirror direction `R` filters
//! the environment by a zonal product, band `l` of the radiance scaled by
//! the lobe's zonal coefficient, and the result is read at `R`.
//!
//! **The zonal coefficients.** By the Funk–Hecke theorem, for the clamped
//! cosine power `(R·ω)₊^s`,
//! `∫ (R·ω)₊^s Y_lm(ω) dω = 2π I_l(s) · Y_lm(R)`, `I_l(s) = ∫₀¹ x^s P_l(x) dx`,
//! with `I₀ = 1/(s+1)`, `I₁ = 1/(s+2)` and the recurrence
//! `I_l = (s − l + 2)/(s + l + 1) · I_{l−2}` (from `(2l+1) x P_l =
//! (l+1) P_{l+1} + l P_{l−1}` and integration by parts; for integer `s`
//! it is the closed form of Ramamoorthi & Hanrahan 2001's Phong
//! coefficients, and at `s = 1` it gives the clamped cosine's
//! `Â_l` of [`super::sh::cosine_lobe`]: π, 2π/3, π/4, 0, −π/24, which a
//! test checks). So `F_s(R) = ∫ (R·ω)₊^s L(ω) dω = Σ_lm 2π I_l(s) L_lm Y_lm(R)`
//! ([`convolved`]), exact up to the band `environment.sh_order`.
//!
//! **The lecture's Phong** (`phong`): `f_r = k_s (R(I)·V)^n / (I·N)`, so
//! `f_r cos θ_i = k_s (R·ω)^n` with `R = R(V)` (`R(I)·V = R(V)·I`): the
//! cosine cancels and the lobe is exactly symmetric about `R`, as
//! Ramamoorthi & Hanrahan's reparameterized Phong. Its glossy term is
//! `k_s · F_n(R)`.
//!
//! **Normalized Phong** (`phong-normalized`, Lewis 1994):
//! `f_r cos θ_i = k_s (n+2)/(2π) (R·ω)^n (N·ω)` is not symmetric about `R`
//! (the cosine is about `N`). It is still exact in SH: with `μ = N·R`
//! and `t = N − μR ⊥ R`, `N·ω = μ (R·ω) + t·ω`, and since
//! `∇_R (R·ω)₊^{n+1} = (n+1) (R·ω)₊^n ω`,
//! `∫ (R·ω)₊^n (N·ω) L dω = μ F_{n+1}(R) + t·∇F_{n+1}(R)/(n+1)`,
//! the derivative of the convolved function along the tangent `t`
//! ([`tangent_derivative`]). Its glossy term is
//! `k_s (n+2)/(2π) [μ F_{n+1}(R) + t·∇F_{n+1}(R)/(n+1)]`.
//!
//! **What is not exact.** Both integrals run over the whole sphere; the
//! BRDFs are zero below the horizon. The lecture's lobe below the horizon
//! adds light that the truth does not have (its part of the lobe is
//! small for large `n` away from grazing, and zero where `R = N`); the
//! normalized form's `N·ω < 0` there subtracts it. Beyond that, only the
//! truncation after band `sh_order`: a lobe of exponent `n` is about
//! `1/√n` wide, and bands up to 4 resolve it only for small `n` (the
//! error-vs-order table is in docs/environment.md). Under a white furnace
//! both are exact where `R = N` at every order (band 0 carries it all):
//! the lecture's form gives `k_s 2π/(n+1)`, the normalized one `k_s μ`.
//!
//! **The lecture's Blinn-Phong** (`blinn-phong`), `f_r cos θ_i = k_s
//! (N·H)^n`, is approximated, not exact: its lobe about the half vector is
//! not symmetric about `R`. It is taken as the mirror lobe `(R·ω)^{n/4}`,
//! the usual match (at normal incidence the angle between `ω` and `R` is
//! twice that between `H` and `N`, and `cos^n(θ/2) ≈ e^{−nθ²/8} ≈
//! cos^{n/4} θ` near the peak); it is wrong in shape away from normal
//! incidence, where the true lobe stretches.
//!
//! **Normalized Blinn-Phong** (`blinn-phong-normalized`), `f_r = D(H) /
//! (4 (I·H) max(N·I, N·V))`, `D = (n+2)/(2π) (N·H)^n`, is approximated
//! the same way, as normalized Phong of exponent `n/4`: at normal
//! incidence (`V = N = R`, `H` halfway between `N` and `ω`, `I·H =
//! cos(θ/2)`) `f_r cos θ_i = (n+2)/(8π) cos^n(θ/2) cos θ / cos(θ/2) ≈
//! (n+2)/(8π) (R·ω)^{n/4} (N·ω)`, and normalized Phong of exponent
//! `s = n/4` is `(s+2)/(2π) (R·ω)^s (N·ω) = (n+8)/(8π) (R·ω)^{n/4} (N·ω)`:
//! the same lobe, its factor the familiar `(n+8)/(8π)` instead of
//! `(n+2)/(8π)` (within 6/(n+2) of each other, and the normalized form
//! keeps the albedo near 1 as the model does). Away from normal
//! incidence the true lobe stretches and is cut by `max(N·I, N·V)`; the
//! error is measured (docs/environment.md). Every other model with a
//! glossy lobe (Cook-Torrance, gltf-pbr, Ward, ABC) and the measured
//! tables get the SH diffuse term alone in this mode, and the loader
//! says so (`scene::scene_file::mode_warnings`).
//!
//! Which lobe a material has and the per-pixel estimate are the
//! reference's (`reference::environment::sh_phong`).
//!
//! WGSL twin: shaders/environment_sh.wgsl (same functions, same order).

use super::EnvironmentMap;
use super::sh;
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, TAU};

/// `2π I_l(s)` for bands 0..=4: the zonal coefficients of `(R·ω)₊^s`
/// times `√(4π/(2l+1))` (module docs). Twin: `sh_phong_weights`.
pub fn phong_weights(s: f64) -> [f64; 5] {
    let i0 = 1.0 / (s + 1.0);
    let i1 = 1.0 / (s + 2.0);
    let i2 = i0 * s / (s + 3.0);
    let i3 = i1 * (s - 1.0) / (s + 4.0);
    let i4 = i2 * (s - 2.0) / (s + 5.0);
    [i0, i1, i2, i3, i4].map(|i| TAU * i)
}

/// `F(d) = Σ_i w_band(i) c_i Y_i(d)`: the radiance coefficients `c`
/// filtered by the zonal weights `w`, at `d` (the map's frame; `d` need
/// not be unit: [`tangent_derivative`] evaluates the polynomials off the
/// sphere). Twin: `sh_convolved`.
pub fn convolved(c: &[Rgb; sh::COUNT], w: &[f64; 5], d: DVec3) -> Rgb {
    sh::basis(d)
        .iter()
        .zip(c)
        .enumerate()
        .fold(Rgb::ZERO, |sum, (i, (y, c))| {
            sum + *c * (w[sh::band(i) as usize] * y)
        })
}

/// `t·∇F(d)` for `t ⊥ d` (`d` unit): the derivative along the sphere. The
/// basis functions are polynomials of degree ≤ 4 in (x, y, z), so
/// `F(d + ε t)` is a polynomial of degree ≤ 4 in `ε`, and the five-point
/// central difference `[8(F(h) − F(−h)) − (F(2h) − F(−2h))]/(12h)` is its
/// exact derivative at 0 for any `h` (its remainder is `h⁴ F⁽⁵⁾/30`).
/// With `t` tangent, the polynomials' values off the sphere do not matter.
/// `h = ½` keeps the points within `√2` of the origin. Twin:
/// `sh_convolved_derivative`.
pub fn tangent_derivative(c: &[Rgb; sh::COUNT], w: &[f64; 5], d: DVec3, t: DVec3) -> Rgb {
    let h = 0.5;
    let f = |e: f64| convolved(c, w, d + t * e);
    ((f(h) - f(-h)) * 8.0 - (f(2.0 * h) - f(-2.0 * h))) * (1.0 / (12.0 * h))
}

/// The Phong lobe the mode convolves, if `material` has one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lobe {
    /// The lecture's `(R(I)·V)^n / (I·N)`.
    Lecture { k_e: f64 },
    /// Normalized Phong, `(n+2)/(2π) (R(I)·V)^n`.
    Normalized { k_e: f64 },
}

/// The glossy term without `k_s`, `∫ f_r/k_s · L cos θ_i dω` over the
/// sphere, for the mirror direction `r` and the normal `n` (world
/// frame), with `c` the map's radiance coefficients. Twin:
/// `environment_sh_glossy`.
pub fn glossy(map: &EnvironmentMap, c: &[Rgb; sh::COUNT], lobe: Lobe, r: DVec3, n: DVec3) -> Rgb {
    let rm = map.to_map(r);
    match lobe {
        Lobe::Lecture { k_e } => convolved(c, &phong_weights(k_e), rm),
        Lobe::Normalized { k_e } => {
            let s = k_e + 1.0;
            let w = phong_weights(s);
            let mu = n.dot(r);
            let t = map.to_map(n - r * mu);
            let along_r = convolved(c, &w, rm) * mu;
            let across = tangent_derivative(c, &w, rm, t) * (1.0 / s);
            (along_r + across) * ((k_e + 2.0) * 0.5 * FRAC_1_PI)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::map::MapSettings;
    use crate::environment::test_maps;
    use std::f64::consts::PI;
    use std::sync::Arc;

    /// At `s = 1` the weights are the clamped cosine's `Â_l`; at `s = 0`
    /// the half-sphere's `2π ∫₀¹ P_l`: 2π, π, 0, −π/4, 0.
    #[test]
    fn the_weights_generalize_the_clamped_cosine() {
        let w = phong_weights(1.0);
        for (l, w) in w.iter().enumerate() {
            assert!((w - sh::cosine_lobe(l as u32)).abs() < 1e-15, "{l}");
        }
        let w0 = phong_weights(0.0);
        for (got, want) in w0.iter().zip([2.0 * PI, PI, 0.0, -PI / 4.0, 0.0]) {
            assert!((got - want).abs() < 1e-15, "{w0:?}");
        }
    }

    /// `2π I_l(s)` against a quadrature of `2π ∫₀¹ x^s P_l(x) dx` for
    /// non-integer and large exponents (Gauss–Legendre would need many
    /// nodes for large s; the midpoint rule with 2·10⁶ cells is within
    /// 1e-9 here).
    #[test]
    fn the_recurrence_matches_the_integral() {
        let p = |l: usize, x: f64| match l {
            0 => 1.0,
            1 => x,
            2 => 0.5 * (3.0 * x * x - 1.0),
            3 => 0.5 * (5.0 * x * x * x - 3.0 * x),
            _ => (35.0 * x.powi(4) - 30.0 * x * x + 3.0) / 8.0,
        };
        for s in [0.5, 2.0, 7.3, 50.0, 1000.0] {
            let w = phong_weights(s);
            let n = 2_000_000;
            for (l, w) in w.iter().enumerate() {
                let sum: f64 = (0..n)
                    .map(|k| {
                        let x = (k as f64 + 0.5) / n as f64;
                        x.powf(s) * p(l, x)
                    })
                    .sum();
                let want = TAU * sum / n as f64;
                assert!((w - want).abs() < 1e-9, "s {s}, l {l}: {w} vs {want}");
            }
        }
    }

    /// The five-point derivative is the exact tangential derivative: against
    /// a central difference of the convolved function along the great
    /// circle through `d` towards `t` (step 1e-4, error ≈ 1e-8).
    #[test]
    fn the_tangent_derivative_is_exact() {
        let data = Arc::new(test_maps::blobs());
        let map = EnvironmentMap {
            data,
            settings: MapSettings {
                sh_order: 4,
                ..Default::default()
            },
        };
        let c = map.radiance_coefficients();
        let w = phong_weights(11.0);
        let d = DVec3::new(0.3, 0.8, -0.5).normalize();
        let t = d.cross(DVec3::X).normalize() * 0.7;
        let got = tangent_derivative(&c, &w, d, t);
        let e = 1e-4;
        let along = |a: f64| convolved(&c, &w, d * a.cos() + t.normalize() * a.sin());
        let want = (along(e) - along(-e)) * (0.7 / (2.0 * e));
        assert!((got - want).abs().max_element() < 1e-7, "{got} vs {want}");
    }

    /// The derivation, checked whole: for a map that is a band-≤4 SH sum
    /// (so order 4 holds all of it), [`glossy`] against a direct
    /// quadrature of `∫_{S²} (R·ω)₊^n L(ω) dω` (lecture) and of
    /// `(n+2)/(2π) ∫_{S²} (R·ω)₊^n (N·ω) L(ω) dω` (normalized), the map
    /// turned by 30°, exponents 0 to 40, normals from `R` to 80° away.
    /// Midpoint rule over the cap `R·ω > 0` in its own polar frame, 1500 ×
    /// 600 cells: error ≈ 1e-6 of the value, far below what a wrong band
    /// weight or a missing gradient term would change (≥ 1e-2 here).
    #[test]
    fn the_convolution_is_exact_for_a_band_limited_map() {
        let c: [Rgb; sh::COUNT] = std::array::from_fn(|i| {
            let k = i as f64;
            Rgb::new(
                0.8 / (1.0 + k),
                0.3 * (0.7 * k).sin(),
                0.2 * (1.3 * k).cos(),
            )
        });
        let map = EnvironmentMap {
            data: Arc::new(test_maps::uniform(8, Rgb::ONE)),
            settings: MapSettings {
                rotation_deg: 30.0,
                ..Default::default()
            },
        };
        let radiance = |w: DVec3| sh::evaluate(&c, map.to_map(w));
        let r = DVec3::new(0.2, 0.9, -0.3).normalize();
        let (t, b) = (
            crate::base::any_tangent(r),
            r.cross(crate::base::any_tangent(r)),
        );
        let (nt, np) = (1500, 600);
        let (dt, dp) = (0.5 * PI / nt as f64, TAU / np as f64);
        for deg in [0.0f64, 35.0, 80.0] {
            let n = r * deg.to_radians().cos() + t * deg.to_radians().sin();
            for k_e in [0.0, 1.0, 3.5, 12.0, 40.0] {
                let (mut lecture, mut normalized) = (Rgb::ZERO, Rgb::ZERO);
                for a in 0..nt {
                    let (st, ct) = ((a as f64 + 0.5) * dt).sin_cos();
                    let lobe = ct.powf(k_e) * st * dt * dp;
                    for q in 0..np {
                        let (sp, cp) = ((q as f64 + 0.5) * dp).sin_cos();
                        let w = r * ct + t * (st * cp) + b * (st * sp);
                        let l = radiance(w) * lobe;
                        lecture += l;
                        normalized += l * n.dot(w);
                    }
                }
                normalized *= (k_e + 2.0) * 0.5 * FRAC_1_PI;
                for (lobe, want) in [
                    (Lobe::Lecture { k_e }, lecture),
                    (Lobe::Normalized { k_e }, normalized),
                ] {
                    let got = glossy(&map, &c, lobe, r, n);
                    let scale = want.abs().max_element().max(1e-3);
                    assert!(
                        (got - want).abs().max_element() < 1e-5 * scale,
                        "{lobe:?}, N at {deg}°: {got} vs {want}"
                    );
                }
            }
        }
    }

    /// A white environment: only band 0, carried exactly at every order.
    /// The lecture's lobe gives `2π/(n+1)` whatever the view; the
    /// normalized one `μ = N·R`, 1 at `R = N` (its albedo at normal
    /// incidence: exact there), less elsewhere (the truth, over the
    /// hemisphere only, keeps more: the whole sphere's `N·ω < 0` part
    /// subtracts).
    #[test]
    fn a_white_environment_is_a_furnace() {
        for order in 0..=sh::MAX_ORDER {
            let map = EnvironmentMap {
                data: Arc::new(test_maps::uniform(32, Rgb::ONE)),
                settings: MapSettings {
                    sh_order: order,
                    ..Default::default()
                },
            };
            let c = map.radiance_coefficients();
            let n = DVec3::new(0.1, 0.7, 0.3).normalize();
            for deg in [0.0f64, 40.0, 85.0] {
                let r = (n * deg.to_radians().cos()
                    + crate::base::any_tangent(n) * deg.to_radians().sin())
                .normalize();
                for k_e in [0.0, 1.0, 10.0, 1e3, 1e6] {
                    let lecture = glossy(&map, &c, Lobe::Lecture { k_e }, r, n);
                    let normalized = glossy(&map, &c, Lobe::Normalized { k_e }, r, n);
                    let want = TAU / (k_e + 1.0);
                    assert!((lecture - Rgb::splat(want)).abs().max_element() < 1e-12 * want);
                    let mu = n.dot(r);
                    assert!(
                        (normalized - Rgb::splat(mu)).abs().max_element() < 1e-12,
                        "order {order}, {deg}°, k_e {k_e}: {normalized}"
                    );
                }
            }
        }
    }
}
