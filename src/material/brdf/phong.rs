//! Phong and Blinn-Phong glossy lobes (lecture: "Phong Glossy Reflection
//! Model", "Blinn-Phong Glossy Reflection"), as written in the lecture.
//! WGSL twin: `shaders/brdf/phong.wgsl` (same names, same order).
//!
//! Both return the lobe without `k_s`; the material multiplies.

use super::COS_FLOOR;
use glam::DVec3;

/// `c^k_e` for the cosine lobes, with `c ≤ 0` giving 0: the lecture warns
/// that the raw cosine lobe is non-zero "into the material"; gonio keeps
/// only the hemisphere around the lobe axis. `k_e = 0` gives 1 for `c > 0`
/// (no `0^0` evaluation, which WGSL's `pow` leaves undefined).
pub fn cos_power(c: f64, k_e: f64) -> f64 {
    if c <= 0.0 {
        0.0
    } else if k_e == 0.0 {
        1.0
    } else {
        c.powf(k_e)
    }
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
/// surface, so `|I + V| > 0`.
pub fn blinn_phong_lecture(k_e: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    let h = (wi + wo).normalize_or_zero();
    cos_power(h.dot(n), k_e) / n.dot(wi).max(COS_FLOOR)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lobes_peak_in_the_mirror_direction() {
        let n = DVec3::Z;
        let wi = DVec3::new(0.6, 0.0, 0.8);
        let wo = mirror_direction(wi, n);
        assert!((phong_lecture(50.0, n, wi, wo) - 1.0 / 0.8).abs() < 1e-12);
        assert!((blinn_phong_lecture(50.0, n, wi, wo) - 1.0 / 0.8).abs() < 1e-12);
    }

    #[test]
    fn cos_power_edge_cases() {
        assert_eq!(cos_power(0.0, 0.0), 0.0);
        assert_eq!(cos_power(0.5, 0.0), 1.0);
        assert_eq!(cos_power(-0.5, 3.0), 0.0);
        assert_eq!(cos_power(0.999, 1e6), 0.999f64.powf(1e6));
    }
}
