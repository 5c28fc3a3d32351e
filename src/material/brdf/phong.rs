//! Phong and Blinn-Phong glossy lobes (lecture: "Phong Glossy Reflection
//! Model", "Blinn-Phong Glossy Reflection"): first as written in the
//! lecture, then in reciprocal, energy-conserving normalized forms.
//! WGSL twin: `shaders/brdf/phong.wgsl` (same names, same order).
//!
//! All lobes are returned without `k_s`; the material multiplies. The
//! helpers here ([`COS_FLOOR`], [`cos_power`], [`mirror_direction`], [`exp_cutoff`]) are
//! shared by the later BRDF files (Ward, microfacet).

use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// Lower bound for the cosines the lecture's forms divide by (`I·N`):
/// cos θ = 1e-6 is θ = 89.99994°. It keeps `f_r` finite (≤ k_s · 10⁶) where
/// the formula as written diverges; `f_r · cos θ_i` is unaffected above it.
pub const COS_FLOOR: f64 = 1e-6;

/// The exponentials of the lobes are cut off at `e^−80 ≈ 1.8e-35`: below
/// that `exp` leaves `f32`'s normal range (`e^−87.3`) on the GPU, where it
/// is flushed to zero or loses its precision, while the prefactors that
/// multiply it (up to ~1e13 for roughness 1e-4 and cosines at
/// `COS_FLOOR`) would make the CPU's f64 value visible. Cutting both off
/// at the same place keeps them equal; see [`exp_cutoff`].
pub const EXP_CUTOFF: f64 = 80.0;

/// gonio's cut-off exponential (a numerical device, no source): `e^x − e^−80`
/// for `x > −80`, else 0 (an `exp` whose tail is cut off at [`EXP_CUTOFF`]). Subtracting `e^−80` makes the cut continuous, so CPU and
/// GPU never disagree by a jump when rounding puts them on different sides
/// of it; the change is below 1.8e-35 absolute, and below 1e-17 relative
/// wherever `x > −40`. Never negative (the `max` absorbs `exp`'s rounding
/// just above the cut).
pub fn exp_cutoff(x: f64) -> f64 {
    if x <= -EXP_CUTOFF {
        return 0.0;
    }
    (x.exp() - (-EXP_CUTOFF).exp()).max(0.0)
}

/// `c^k_e` for the cosine lobes, with `c ≤ 0` giving 0: the lecture warns
/// that the raw cosine lobe is non-zero "into the material"; gonio keeps
/// only the hemisphere around the lobe axis. `k_e = 0` gives 1 for `c > 0`
/// (no `0^0` evaluation, which WGSL's `pow` leaves undefined).
///
/// Evaluated as `e^(k_e ln c)` through [`exp_cutoff`], so that values below
/// `e^−80` are 0 on CPU and GPU alike (`pow` underflows in `f32` there).
/// Near `c = 1`, where the lobes live for large `k_e`, `ln c = ln_1p(c − 1)`
/// (`c − 1` is exact): the WGSL twin sums the series of `ln(1 + u)` there,
/// because WGSL's `log` (and `pow`) is only absolutely accurate near 1
/// (2⁻²¹, Vulkan), which `k_e` up to 1e6 would amplify to 0.5 in the
/// exponent. `c` is clamped to ≤ 1: a cosine of unit vectors exceeds 1 only
/// by rounding, and `c^1e6` would amplify that.
pub fn cos_power(c: f64, k_e: f64) -> f64 {
    if c <= 0.0 {
        return 0.0;
    }
    if k_e == 0.0 {
        return 1.0;
    }
    let u = c.min(1.0) - 1.0; // exact for c ≥ 0.5 (Sterbenz)
    let ln_c = if u > -0.0625 { u.ln_1p() } else { c.ln() };
    exp_cutoff(k_e * ln_c)
}

/// `R(I) = −I + 2 (I·N) N`: the mirror direction of `wi` about `n`.
pub fn mirror_direction(wi: DVec3, n: DVec3) -> DVec3 {
    -wi + 2.0 * wi.dot(n) * n
}

/// Lecture Phong lobe: `(R(I)·V)^k_e / (I·N)`. Not reciprocal, not
/// normalized (its albedo exceeds 1 near grazing incidence).
pub fn phong_lecture(k_e: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    cos_power(mirror_direction(wi, n).dot(wo), k_e) / n.dot(wi).max(COS_FLOOR)
}

/// Lecture Blinn-Phong lobe: `(H·N)^k_e / (I·N)` with
/// `H = (I + V) / |I + V|`. Not reciprocal, not normalized. `I = −V`
/// (H undefined) cannot occur for a one-sided model: both are above the
/// surface, so `|I + V| > 0`; should it happen, `H = 0` and the lobe is 0.
pub fn blinn_phong_lecture(k_e: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let h = (wi + wo).normalize_or_zero();
    cos_power_precise(n.dot(h), sin2_between(n, h), k_e) / n.dot(wi).max(COS_FLOOR)
}

/// Normalized Phong (Lewis 1994, "Making Shaders More Physically
/// Plausible"): `((k_e + 2) / (2π)) (R(I)·V)^k_e`, without the lecture's
/// `1/(I·N)`. Reciprocal (`R(I)·V = R(V)·I`); its directional albedo is 1
/// at normal incidence and smaller elsewhere (part of the lobe falls below
/// the horizon). Finite for `k_e ∈ [0, 1e6]`: at most `1.6e5`.
pub fn phong_normalized(k_e: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    (k_e + 2.0) * 0.5 * FRAC_1_PI * cos_power(mirror_direction(wi, n).dot(wo), k_e)
}

/// Normalized Blinn-Phong as a microfacet lobe (the form of Ashikhmin &
/// Shirley 2000, with the normalized Blinn distribution of Walter et al.
/// 2007): `D(H) / (4 (I·H) max(N·I, N·V))` with
/// `D(H) = ((k_e + 2) / (2π)) (N·H)^k_e`, `∫ D cosθ_h dω_h = 1`.
///
/// Reciprocal (`I·H = V·H`, `max` is symmetric) and energy conserving:
/// the directional albedo is ≤ 1 for every `k_e ≥ 0` (measured maximum
/// 0.99976; the argument is in `docs/brdf-math-notes.md`). The often-quoted
/// `((k_e + 8)/(8π)) (N·H)^k_e` (Real-Time Rendering) is not used: its
/// albedo reaches 1.075 (k_e = 10, normal incidence).
///
/// `I·H` and the `max` are floored at `COS_FLOOR` so that `I = −V`
/// (`H = 0`, then `D = 0`) and grazing pairs stay finite: at most
/// `1.6e5 / (4 · 1e-12) = 4e16`, finite in `f32`.
pub fn blinn_phong_normalized(k_e: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let h = (wi + wo).normalize_or_zero();
    let d = (k_e + 2.0) * 0.5 * FRAC_1_PI * cos_power_precise(n.dot(h), sin2_between(n, h), k_e);
    let cos_ih = wi.dot(h).max(COS_FLOOR); // I·H = V·H ≥ 0; 0 only for I = −V
    let cos_max = n.dot(wi).max(n.dot(wo)).max(COS_FLOOR); // both grazing
    d / (4.0 * cos_ih * cos_max)
}

/// `sin²θ = |N × H|²` for unit vectors: accurate for small angles, where
/// `1 − (N·H)²` cancels (in `f32` `N·H` rounds to 1 within 3.5e-4 rad).
pub fn sin2_between(n: DVec3, h: DVec3) -> f64 {
    n.cross(h).length_squared()
}

/// `−ln(1 − x)` for x in [0, 1], accurate for small x (`ln_1p`; the WGSL
/// twin sums its series below 0.1). 1 − x = 0 gives +∞, which the callers
/// turn into `exp(−∞) = 0`.
pub fn neg_ln_1m(x: f64) -> f64 {
    -(-x).ln_1p()
}

/// `ln cos θ` from both `cos θ` and `sin²θ`, each where it is accurate:
/// `½ ln(1 − sin²θ)` for small angles (`cos θ` has no digits left near 1
/// in `f32`), `ln cos θ` itself for large ones (`1 − sin²θ` would cancel).
pub fn ln_cos(cos: f64, sin2: f64) -> f64 {
    if sin2 < 0.5 {
        -0.5 * neg_ln_1m(sin2)
    } else {
        cos.ln()
    }
}

/// `cos^k_e θ` like [`cos_power`], from `cos θ` and `sin²θ` ([`ln_cos`]):
/// exponents up to 10⁶ and more amplify the error of `ln cos θ`, which
/// this keeps at a few ulp of `sin²θ` near the peak.
pub fn cos_power_precise(cos: f64, sin2: f64, k_e: f64) -> f64 {
    if cos <= 0.0 {
        0.0
    } else if k_e == 0.0 {
        1.0
    } else {
        exp_cutoff(k_e * ln_cos(cos, sin2.min(1.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn lobes_peak_in_the_mirror_direction() {
        let n = DVec3::Z;
        let wi = DVec3::new(0.6, 0.0, 0.8);
        let wo = mirror_direction(wi, n);
        assert!((phong_lecture(50.0, n, wi, wo) - 1.0 / 0.8).abs() < 1e-12);
        assert!((blinn_phong_lecture(50.0, n, wi, wo) - 1.0 / 0.8).abs() < 1e-12);
        assert!((phong_normalized(50.0, n, wi, wo) - 52.0 / (2.0 * PI)).abs() < 1e-12);
        let peak = 52.0 / (2.0 * PI) / (4.0 * 0.8 * 0.8);
        assert!((blinn_phong_normalized(50.0, n, wi, wo) - peak).abs() < 1e-12);
    }

    #[test]
    fn cos_power_edge_cases() {
        assert_eq!(cos_power(0.0, 0.0), 0.0);
        assert_eq!(cos_power(0.5, 0.0), 1.0);
        assert_eq!(cos_power(-0.5, 3.0), 0.0);
        assert_eq!(cos_power(0.999, 1e6), 0.0);
        assert_eq!(cos_power(1.0, 1e6), 1.0 - (-EXP_CUTOFF).exp());
        assert_eq!(cos_power(1.0 + 1e-15, 1e6), cos_power(1.0, 1e6));
        // Away from the cut, the ordinary power to rounding.
        for (c, k) in [(0.5, 3.0), (0.9, 100.0), (0.999, 1e4), (0.3, 0.5)] {
            let exact: f64 = f64::powf(c, k);
            assert!((cos_power(c, k) - exact).abs() <= 1e-13 * exact, "{c}^{k}");
        }
    }

    #[test]
    fn exp_cutoff_is_continuous_and_nonnegative() {
        assert_eq!(exp_cutoff(-EXP_CUTOFF), 0.0);
        assert_eq!(exp_cutoff(-1e300), 0.0);
        assert!(exp_cutoff(-EXP_CUTOFF + 1e-12) >= 0.0);
        assert!(exp_cutoff(-EXP_CUTOFF + 1e-9) < 1e-43);
        assert_eq!(exp_cutoff(0.0), 1.0);
    }

    /// Both normalized lobes are symmetric in (wi, wo).
    #[test]
    fn normalized_lobes_are_reciprocal() {
        let n = DVec3::Z;
        let dirs = [
            DVec3::new(0.3, 0.1, 0.9),
            DVec3::new(-0.5, 0.2, 0.4),
            DVec3::new(0.9, -0.3, 0.05),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        for a in dirs {
            for b in dirs {
                let (wi, wo) = (a.normalize(), b.normalize());
                for k in [0.0, 1.0, 10.0, 1000.0] {
                    let p = (
                        phong_normalized(k, n, wi, wo),
                        phong_normalized(k, n, wo, wi),
                    );
                    assert!((p.0 - p.1).abs() <= 1e-12 * p.0.max(1.0), "phong {p:?}");
                    let q = (
                        blinn_phong_normalized(k, n, wi, wo),
                        blinn_phong_normalized(k, n, wo, wi),
                    );
                    assert!((q.0 - q.1).abs() <= 1e-12 * q.0.max(1.0), "blinn {q:?}");
                }
            }
        }
    }

    #[test]
    fn normalized_lobes_are_finite_at_the_extremes() {
        let n = DVec3::Z;
        let grazing = DVec3::new(1.0, 0.0, 0.0);
        let dirs = [
            DVec3::Z,
            grazing,
            -grazing,
            DVec3::new(1.0, 0.0, 1e-8).normalize(),
            DVec3::new(-1.0, 0.0, 1e-8).normalize(),
            DVec3::new(0.0, 0.0, -1.0),
        ];
        for wi in dirs {
            for wo in dirs {
                for k in [0.0, 1e-3, 1.0, 1e6] {
                    for v in [
                        phong_lecture(k, n, wi, wo),
                        blinn_phong_lecture(k, n, wi, wo),
                        phong_normalized(k, n, wi, wo),
                        blinn_phong_normalized(k, n, wi, wo),
                    ] {
                        assert!(v.is_finite() && v >= 0.0, "{wi} {wo} {k}: {v}");
                    }
                }
            }
        }
    }

    /// Directional albedo `∫ f cosθ_o dω_o` of a lobe of exponent `k`,
    /// integrated over the half vector: `dω_o = 4 (I·H) dω_h`,
    /// `ω_o = 2 (I·H) H − I` (the same integral; ω_o below the horizon and
    /// `I·H ≤ 0` contribute nothing). A midpoint grid over ω_o undersamples
    /// narrow lobes at grazing incidence — the Jacobian squeezes the lobe
    /// by `4 (I·H) ≈ 4 cosθ_i` across the plane of incidence (k_e = 1e4,
    /// θ_i = 89°: 0.36 on a 2000 × 4000 ω_o grid, 0.6638 exactly) — while
    /// over H it is a round lobe of width `1/√k`. Midpoint rule, `nt × np`
    /// cells over θ_h ∈ [0, min(π/2, 12/√(k+1))] (beyond it
    /// `cos^k θ_h < e^−70`) and φ_h ∈ [0, π] (`wi` in the xz-plane: the
    /// integrand is even in φ).
    fn albedo(f: impl Fn(DVec3, DVec3) -> f64, k: f64, theta_i: f64, nt: usize, np: usize) -> f64 {
        let wi = DVec3::new(theta_i.sin(), 0.0, theta_i.cos());
        let theta_max = (12.0 / (k + 1.0).sqrt()).min(0.5 * PI);
        let (dt, dp) = (theta_max / nt as f64, PI / np as f64);
        let mut sum = 0.0;
        for a in 0..nt {
            let (st, ct) = ((a as f64 + 0.5) * dt).sin_cos();
            let mut ring = 0.0;
            for b in 0..np {
                let (sp, cp) = ((b as f64 + 0.5) * dp).sin_cos();
                let h = DVec3::new(st * cp, st * sp, ct);
                let cos_ih = wi.dot(h);
                let wo = 2.0 * cos_ih * h - wi;
                if cos_ih > 0.0 && wo.z > 0.0 {
                    ring += f(wi, wo) * wo.z * 4.0 * cos_ih;
                }
            }
            sum += ring * st;
        }
        2.0 * sum * dt * dp
    }

    /// Exact albedo of [`blinn_phong_normalized`] at normal incidence
    /// (`f cosθ_o dω_o = D cos 2θ_h dω_h`, θ_h < π/4):
    /// `(k+2) [2 (1 − 2^−(k+3)/2)/(k+3) − (1 − 2^−(k+1)/2)/(k+1)]`,
    /// < 1 for every k and 1 − 3/k + O(1/k²) for large k.
    fn normal_incidence_albedo(k: f64) -> f64 {
        (k + 2.0)
            * (2.0 * (1.0 - 2f64.powf(-(k + 3.0) / 2.0)) / (k + 3.0)
                - (1.0 - 2f64.powf(-(k + 1.0) / 2.0)) / (k + 1.0))
    }

    /// The brief's check: albedo ≤ 1 for k_e ∈ {0, 1, 2, 5, 10, 100, 1e3,
    /// 1e4} and θ_i ∈ {0, 30, 60, 80, 89}°, 2000 × 2000 cells over the
    /// half-vector hemisphere (φ by symmetry; = 2000 × 4000 over the full
    /// circle). The quadrature error is ≈ 1.5e-6 (second order: 4.5e-6 at
    /// 1000², 1.1e-6 more at 4000², measured during development), and at
    /// θ_i = 0 the closed form checks it. Largest value: 0.99970 (k_e = 1e4,
    /// θ_i = 0); the supremum over all k_e is 1, approached as k_e → ∞ at
    /// normal incidence.
    #[test]
    fn blinn_phong_normalized_albedo_is_at_most_one() {
        let n = DVec3::Z;
        let mut worst = (0.0, 0.0, 0.0);
        for k in [0.0, 1.0, 2.0, 5.0, 10.0, 100.0, 1000.0, 1e4] {
            for deg in [0.0, 30.0, 60.0, 80.0, 89.0f64] {
                let a = albedo(
                    |wi, wo| blinn_phong_normalized(k, n, wi, wo),
                    k,
                    deg.to_radians(),
                    2000,
                    2000,
                );
                assert!(a <= 1.0, "k_e {k}, θ_i {deg}°: albedo {a}");
                assert!(a > 0.2, "k_e {k}, θ_i {deg}°: albedo {a}");
                if deg == 0.0 {
                    let exact = normal_incidence_albedo(k);
                    assert!((a - exact).abs() < 1e-5, "k_e {k}: {a} vs {exact}");
                }
                if a > worst.0 {
                    worst = (a, k, deg);
                }
            }
        }
        eprintln!("blinn_phong_normalized: max albedo {worst:?}");
    }

    /// Normalized Phong's albedo: exactly 1 at normal incidence, less
    /// elsewhere. Midpoint rule over ω_o, 1000 × 2000 cells; its error is
    /// ≈ 1e-5 at k_e = 100, hence the 1e-4 margin.
    #[test]
    fn phong_normalized_albedo_is_at_most_one() {
        let n = DVec3::Z;
        for k in [0.0, 1.0, 10.0, 100.0] {
            for deg in [0.0, 45.0, 80.0f64] {
                // Over ω_o directly (the Phong lobe is round about R(I)).
                let wi = DVec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
                let (nt, np) = (1000, 1000);
                let (dt, dp) = (0.5 * PI / nt as f64, PI / np as f64);
                let mut sum = 0.0;
                for a in 0..nt {
                    let (st, ct) = ((a as f64 + 0.5) * dt).sin_cos();
                    for b in 0..np {
                        let (sp, cp) = ((b as f64 + 0.5) * dp).sin_cos();
                        let wo = DVec3::new(st * cp, st * sp, ct);
                        sum += phong_normalized(k, n, wi, wo) * ct * st;
                    }
                }
                let a = 2.0 * sum * dt * dp;
                assert!(a <= 1.0 + 1e-4, "k_e {k}, θ_i {deg}°: {a}");
                if deg == 0.0 {
                    assert!((a - 1.0).abs() < 1e-4, "k_e {k}: {a}");
                }
            }
        }
    }

    /// Why not the RTR form `((k_e + 8)/(8π)) (N·H)^k_e`: at normal
    /// incidence its albedo is a 1-D integral, and it exceeds 1.
    #[test]
    fn rtr_blinn_phong_candidate_exceeds_one() {
        // θ_i = 0: θ_h = θ_o / 2; ∫ f cosθ_o dω_o = 2π ∫ f cosθ sinθ dθ.
        let rtr = |k: f64| {
            let nt = 200_000;
            let dt = 0.5 * PI / nt as f64;
            let s: f64 = (0..nt)
                .map(|a| {
                    let t = (a as f64 + 0.5) * dt;
                    (k + 8.0) / (8.0 * PI) * (0.5 * t).cos().powf(k) * t.cos() * t.sin()
                })
                .sum();
            2.0 * PI * s * dt
        };
        assert!((rtr(10.0) - 1.0748).abs() < 1e-3, "{}", rtr(10.0));
        assert!(rtr(0.0) <= 1.0 + 1e-9);
    }

    /// The argument for all k_e ≥ 0 at once (docs/brdf-math-notes.md): D is
    /// a decreasing function of θ_h, so the albedo is a positive mixture,
    /// over cap radii t, of `A(t) / B(t)` with
    /// `A(t) = ∫_{θ_h<t} min(1, cosθ_o / cosθ_i) [cosθ_o > 0] dω_h` and
    /// `B(t) = ∫_{θ_h<t} cosθ_h dω_h`; it is ≤ 1 wherever `A ≤ B`.
    #[test]
    fn blinn_phong_normalized_cap_inequality() {
        let (nt, np) = (1500, 1500);
        let (dt, dp) = (0.5 * PI / nt as f64, PI / np as f64);
        for deg in (0..=89).step_by(2).map(f64::from).chain([89.9]) {
            let ti = deg.to_radians();
            let wi = DVec3::new(ti.sin(), 0.0, ti.cos());
            let (mut a, mut b) = (0.0, 0.0);
            for j in 0..nt {
                let (st, ct) = ((j as f64 + 0.5) * dt).sin_cos();
                let mut ring = 0.0;
                for p in 0..np {
                    let (sp, cp) = ((p as f64 + 0.5) * dp).sin_cos();
                    let h = DVec3::new(st * cp, st * sp, ct);
                    let cos_o = 2.0 * wi.dot(h) * h.z - wi.z;
                    if wi.dot(h) > 0.0 && cos_o > 0.0 {
                        ring += (cos_o / wi.z.max(cos_o)).min(1.0);
                    }
                }
                a += ring / np as f64 * st;
                b += ct * st;
                assert!(
                    a <= b * (1.0 + 1e-9),
                    "θ_i {deg}°, cap {}: A/B = {}",
                    (j + 1) as f64 * dt,
                    a / b
                );
            }
        }
    }
}
