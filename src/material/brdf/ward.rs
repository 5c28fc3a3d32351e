//! Ward's glossy lobe (lecture: "Ward Reflection Model"; G. J. Ward,
//! "Measuring and Modeling Anisotropic Reflection", SIGGRAPH 1992),
//! isotropic and anisotropic, as the lecture writes it: the specular part
//! without `ρ_s` (the material's `k_s` multiplies) and without the diffuse
//! `ρ_d/π` (the material's Lambert term).
//! WGSL twin: `shaders/brdf/ward.wgsl` (same names, same order).
//!
//! Not normalized exactly (its albedo exceeds 1 near grazing for large σ,
//! as Ward's paper notes), but reciprocal.

use super::COS_FLOOR;
use super::phong::{EXP_CUTOFF, exp_cutoff};
use glam::DVec3;
use std::f64::consts::PI;

/// Isotropic Ward (lecture: "Ward Reflection Model"):
/// `exp(−tan²θ_h / σ²) / (4π σ² sqrt((I·N)(V·N)))`, θ_h = ∠(H, N),
/// `σ` the RMS surface slope in (0, 1].
///
/// - `tan²θ_h = |N×H|² / (N·H)²`: the cross product keeps `sin²θ_h`
///   accurate in `f32` for narrow lobes (`1 − cos²` would cancel).
/// - The exponent is tested before dividing (`sin² ≥ 80 cos² σ²`, i.e.
///   exponent ≤ −80) and the lobe is then 0 ([`exp_cutoff`]): no `tan²`
///   overflow as `N·H → 0`, no `0/0`, no `∞ · 0`. σ → 0 gives 0, not a
///   Dirac.
/// - The cosines under the root are floored at `COS_FLOOR`: the lecture's
///   form diverges at grazing angles; the floor keeps it finite
///   (≤ `1/(4π σ² · 1e-6)` = 8e12 for σ = 1e-4) and does not change it
///   where either cosine is above 1e-6.
pub fn ward_isotropic(sigma: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let h = (wi + wo).normalize_or_zero(); // 0 for I = −V: then N·H = 0
    let cos_h = n.dot(h);
    if cos_h <= 0.0 {
        return 0.0;
    }
    let n_x_h = n.cross(h);
    let sin2 = n_x_h.dot(n_x_h);
    let cos2 = cos_h * cos_h;
    let sigma2 = sigma * sigma;
    if sin2 >= EXP_CUTOFF * cos2 * sigma2 {
        return 0.0; // exponent ≤ −80 (also catches σ = 0 and cos² underflow)
    }
    let exponent = -sin2 / (cos2 * sigma2); // in (−80, 0]; cos2 * sigma2 > 0 here
    let root = (n.dot(wi).max(COS_FLOOR) * n.dot(wo).max(COS_FLOOR)).sqrt();
    exp_cutoff(exponent) / (4.0 * PI * sigma2 * root)
}

/// Anisotropic Ward (Ward 1992, eq. 5; the lecture's "expansion to
/// anisotropic model"):
/// `exp(−((H·t/σx)² + (H·b/σy)²) / (H·n)²) / (4π σx σy sqrt((I·N)(V·N)))`,
/// `t`, `b` the unit tangent and bitangent of the shading frame, `σx`,
/// `σy` the RMS slopes along them. `σx = σy = σ` is [`ward_isotropic`]
/// (`(H·t)² + (H·b)² = |N×H|²`).
///
/// Multiplied through by `σx² σy²` so that no slope is divided by a small
/// σ: `slope2 = (H·t)² σy² + (H·b)² σx²`, exponent `−slope2 / ((H·n)² σx² σy²)`,
/// tested against −80 before dividing, as in [`ward_isotropic`]; the same
/// `COS_FLOOR` under the root.
pub fn ward_anisotropic(
    sigma_x: f64,
    sigma_y: f64,
    n: DVec3,
    t: DVec3,
    b: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> f64 {
    let h = (wi + wo).normalize_or_zero(); // 0 for I = −V: then N·H = 0
    let cos_h = n.dot(h);
    if cos_h <= 0.0 {
        return 0.0;
    }
    let h_t = h.dot(t);
    let h_b = h.dot(b);
    let cos2 = cos_h * cos_h;
    let sigma_x2 = sigma_x * sigma_x;
    let sigma_y2 = sigma_y * sigma_y;
    let slope2 = h_t * h_t * sigma_y2 + h_b * h_b * sigma_x2;
    let scale = cos2 * sigma_x2 * sigma_y2;
    if slope2 >= EXP_CUTOFF * scale {
        return 0.0; // exponent ≤ −80 (also catches σ = 0 and underflow of scale)
    }
    let exponent = -slope2 / scale; // in (−80, 0]; scale > 0 here
    let root = (n.dot(wi).max(COS_FLOOR) * n.dot(wo).max(COS_FLOOR)).sqrt();
    exp_cutoff(exponent) / (4.0 * PI * sigma_x * sigma_y * root)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    #[test]
    fn peak_value_in_the_mirror_direction() {
        let n = DVec3::Z;
        let wi = dir(40.0, 10.0);
        let wo = super::super::phong::mirror_direction(wi, n);
        let sigma = 0.2;
        let expected = 1.0 / (4.0 * PI * sigma * sigma * wi.z);
        let got = ward_isotropic(sigma, n, wi, wo);
        assert!(
            (got - expected).abs() < 1e-12 * expected,
            "{got} {expected}"
        );
    }

    #[test]
    fn off_peak_value_matches_the_formula() {
        let n = DVec3::Z;
        let (wi, wo) = (dir(30.0, 0.0), dir(50.0, 160.0));
        let sigma = 0.3;
        let h = (wi + wo).normalize();
        let tan2 = (1.0 - h.z * h.z) / (h.z * h.z);
        let expected =
            (-tan2 / (sigma * sigma)).exp() / (4.0 * PI * sigma * sigma * (wi.z * wo.z).sqrt());
        let got = ward_isotropic(sigma, n, wi, wo);
        assert!(
            (got - expected).abs() < 1e-12 * expected,
            "{got} {expected}"
        );
    }

    /// σx = σy: the anisotropic lobe is the isotropic one, in any
    /// orthonormal tangent frame around n.
    #[test]
    fn anisotropic_with_equal_slopes_is_isotropic() {
        let n = DVec3::new(0.2, -0.3, 0.9).normalize();
        let t0 = DVec3::X - n * n.x;
        let t0 = t0.normalize();
        for rot in [0.0, 0.7, 2.0, 4.0f64] {
            let t = t0 * rot.cos() + n.cross(t0) * rot.sin();
            let b = n.cross(t);
            for sigma in [1e-4, 0.01, 0.1, 0.5, 1.0] {
                for (wi, wo) in [
                    (dir(30.0, 0.0), dir(40.0, 170.0)),
                    (dir(10.0, 50.0), dir(80.0, 260.0)),
                    (dir(60.0, 120.0), dir(60.0, 300.0)),
                    (n, n),
                ] {
                    let iso = ward_isotropic(sigma, n, wi, wo);
                    let aniso = ward_anisotropic(sigma, sigma, n, t, b, wi, wo);
                    assert!(
                        (iso - aniso).abs() <= 1e-12 * iso.max(1e-300),
                        "σ {sigma}: {iso} vs {aniso}"
                    );
                }
            }
        }
    }

    #[test]
    fn anisotropic_stretches_along_the_rougher_axis() {
        let (n, t, b) = (DVec3::Z, DVec3::X, DVec3::Y);
        let wi = dir(30.0, 0.0);
        // H tilted towards t vs towards b by the same angle.
        let along_t = ward_anisotropic(0.4, 0.1, n, t, b, wi, dir(40.0, 180.0));
        let along_b = ward_anisotropic(0.1, 0.4, n, t, b, wi, dir(40.0, 180.0));
        assert!(along_t > along_b);
        // Swapping (t, σx) with (b, σy) changes nothing.
        let wo = dir(50.0, 200.0);
        let a = ward_anisotropic(0.4, 0.1, n, t, b, wi, wo);
        let c = ward_anisotropic(0.1, 0.4, n, b, t, wi, wo);
        assert!((a - c).abs() <= 1e-12 * a);
    }

    #[test]
    fn reciprocal() {
        let (n, t, b) = (DVec3::Z, DVec3::X, DVec3::Y);
        for (wi, wo) in [
            (dir(20.0, 10.0), dir(70.0, 200.0)),
            (dir(85.0, 0.0), dir(5.0, 90.0)),
        ] {
            let (p, q) = (
                ward_isotropic(0.3, n, wi, wo),
                ward_isotropic(0.3, n, wo, wi),
            );
            assert!((p - q).abs() <= 1e-12 * p);
            let (p, q) = (
                ward_anisotropic(0.3, 0.1, n, t, b, wi, wo),
                ward_anisotropic(0.3, 0.1, n, t, b, wo, wi),
            );
            assert!((p - q).abs() <= 1e-12 * p.max(1e-300));
        }
    }

    #[test]
    fn finite_at_the_extremes() {
        let (n, t, b) = (DVec3::Z, DVec3::X, DVec3::Y);
        let dirs = [
            DVec3::Z,
            DVec3::X,
            -DVec3::X,
            DVec3::new(1.0, 0.0, 1e-8).normalize(),
            DVec3::new(-1.0, 0.0, 1e-8).normalize(),
            DVec3::new(0.0, 1e-8, 1.0).normalize(),
            -DVec3::Z,
        ];
        for wi in dirs {
            for wo in dirs {
                for s in [0.0, 1e-4, 1e-3, 0.3, 1.0] {
                    for v in [
                        ward_isotropic(s, n, wi, wo),
                        ward_anisotropic(s, 1.0, n, t, b, wi, wo),
                        ward_anisotropic(1e-4, s, n, t, b, wi, wo),
                    ] {
                        assert!(v.is_finite() && v >= 0.0, "σ {s} {wi} {wo}: {v}");
                    }
                }
            }
        }
    }
}
