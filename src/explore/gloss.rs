//! The lecture's "Standardized Gloss Model": industry measures only "a
//! subset of BRDF values ... at discrete set of angles, in plane". This is
//! the specular gloss of ISO 2813 / ASTM D523, computed from a BRDF.
//!
//! # What is computed
//!
//! A gloss meter lights the sample with a (nearly) collimated beam at the
//! angle θ = 20°, 60° or 85° from the normal and measures, with a receptor
//! at the mirror angle, the flux that enters the receptor's rectangular
//! field stop. It reports that flux relative to the flux a polished black
//! glass standard of refractive index 1.567 sends into the same stop, times
//! 100 gloss units (GU). Here:
//!
//! `GU(θ) = 100 · Y[ ∫_A f_r(ω_i, ω_o) cos θ_o dω_o ] / F_1.567(θ)`
//!
//! * `ω_i` at polar angle θ in the plane `φ = 0`; `A` the receptor
//!   aperture around the mirror direction: `|a| ≤ ½ Δ_∥`, `|b| ≤ ½ Δ_⊥`,
//!   where `a` is the polar angle offset in the plane of incidence and `b`
//!   the angle out of it, `ω_o = cos b · (−sin(θ+a), 0, cos(θ+a)) + sin b · ŷ`,
//!   `dω_o = cos b da db`. The apertures `Δ_∥ × Δ_⊥` are the receptor
//!   field stops of ISO 2813 / ASTM D523: 1.80° × 3.6° (20°),
//!   4.4° × 11.7° (60°), 4.0° × 6.0° (85°).
//! * The integral is the fraction of the incident flux reflected into `A`
//!   (reflected radiance per unit irradiance, integrated over projected
//!   solid angle). For the black glass standard all reflected flux is
//!   specular and enters `A`: the fraction is its Fresnel reflectance
//!   `F_1.567(θ)` (unpolarized, air → glass).
//! * `Y` is relative luminance (Rec. 709 weights): a gloss meter's detector
//!   is weighted by the CIE `V(λ)` (photopic) curve.
//! * Simplifications, stated: the source is taken as perfectly collimated
//!   (the standards allow a source image of 0.75° × 2.5°, which would
//!   convolve the BRDF with that small angular spread); the receptor
//!   response is uniform over the stop.
//!
//! So a black glass gives 100 GU at every angle, an ideal mirror of
//! reflectance 1 gives `100 / F_1.567(θ)` (≈ 2000 GU at 20°), and a Lambert
//! surface of albedo `k_d` about `100 k_d cos θ · Ω_A / (π F)` — small.
//!
//! Quadrature: adaptive Gauss-Kronrod in `b` of adaptive Gauss-Kronrod in
//! `a` ([`super::quadrature`]), on panels graded towards the mirror
//! direction `a = b = 0` from 10⁻⁶ rad; the error bound is the sum of the
//! panels' `|K15 − G7|`, as in [`super::albedo`].

use super::Channel;
use super::part::MaterialPart;
use super::quadrature::{Tolerance, graded, integrate};
use crate::material::brdf::{SurfaceFrame, fresnel::fresnel_dielectric};
use crate::scene::Rgb;
use glam::DVec3;

/// Refractive index of the primary black glass standard (ISO 2813, ASTM
/// D523), at the sodium D line.
pub const STANDARD_ETA: f64 = 1.567;

/// A gloss meter geometry: illumination angle and receptor aperture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossGeometry {
    /// Angle of incidence (= angle of the receptor's axis) from the normal.
    pub angle_deg: f64,
    /// Receptor aperture in the plane of incidence.
    pub in_plane_deg: f64,
    /// Receptor aperture perpendicular to it.
    pub perpendicular_deg: f64,
}

/// The three geometries of ISO 2813 / ASTM D523: 20° for high gloss, 60°
/// for all, 85° for low gloss (sheen).
pub const GEOMETRIES: [GlossGeometry; 3] = [
    GlossGeometry {
        angle_deg: 20.0,
        in_plane_deg: 1.80,
        perpendicular_deg: 3.6,
    },
    GlossGeometry {
        angle_deg: 60.0,
        in_plane_deg: 4.4,
        perpendicular_deg: 11.7,
    },
    GlossGeometry {
        angle_deg: 85.0,
        in_plane_deg: 4.0,
        perpendicular_deg: 6.0,
    },
];

/// One gloss reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossReading {
    pub geometry: GlossGeometry,
    /// `∫_A f_r cos θ_o dω_o` per channel: the fraction of the incident flux
    /// reflected into the receptor.
    pub aperture_reflectance: Rgb,
    /// Bound on the error of `aperture_reflectance` (per channel).
    pub error_bound: Rgb,
    /// The black glass standard's reflectance `F_1.567(θ)`.
    pub standard_reflectance: f64,
    /// Gloss units: `100 · Y(aperture_reflectance) / standard_reflectance`.
    pub gloss_units: f64,
}

/// The gloss of `material` in `geometry`, light at azimuth `φ_i = 0`.
pub fn gloss<'a>(material: impl Into<MaterialPart<'a>>, geometry: GlossGeometry) -> GlossReading {
    gloss_at(material, geometry, 0.0)
}

/// The gloss of `material` in `geometry` with the plane of incidence at
/// azimuth `phi_i` (radians) from the tangent: the sample turned under the
/// meter. The meter's geometry stays in the plane `y = 0`; the sample's
/// tangent is turned to `(cos φ_i, −sin φ_i, 0)`, so the light's azimuth
/// seen from the tangent is `+φ_i` (only anisotropic models change).
pub fn gloss_at<'a>(
    material: impl Into<MaterialPart<'a>>,
    geometry: GlossGeometry,
    phi_i: f64,
) -> GlossReading {
    let material = material.into();
    let theta = geometry.angle_deg.to_radians();
    let wi = super::direction(theta, 0.0);
    let half_a = 0.5 * geometry.in_plane_deg.to_radians();
    let half_b = 0.5 * geometry.perpendicular_deg.to_radians();
    let (sin_p, cos_p) = phi_i.sin_cos();
    let frame = SurfaceFrame::new(DVec3::Z, DVec3::new(cos_p, -sin_p, 0.0));
    let (q, error) = aperture_integral(&material, wi, theta, half_a, half_b, &frame);
    // Zero but for a Dirac lobe (the mirror).
    let dirac = material.dirac(theta.cos());
    let aperture_reflectance = q + dirac;
    let standard_reflectance = fresnel_dielectric(theta.cos(), 1.0, STANDARD_ETA);
    GlossReading {
        geometry,
        aperture_reflectance,
        error_bound: error + 1e-12 * q.abs() + material.sheen_curve_error(),
        standard_reflectance,
        gloss_units: 100.0 * Channel::Luminance.of(aperture_reflectance) / standard_reflectance,
    }
}

/// Tolerance of both directions of the aperture integral.
const TOLERANCE: Tolerance = Tolerance {
    rel: 1e-10,
    abs: 1e-300,
    max_depth: 16,
};

/// `(∫_A f_r cos θ_o dω_o, error bound)` over the aperture `|a| ≤ half_a`,
/// `|b| ≤ half_b`.
fn aperture_integral(
    material: &MaterialPart,
    wi: DVec3,
    theta: f64,
    half_a: f64,
    half_b: f64,
    frame: &SurfaceFrame,
) -> (Rgb, Rgb) {
    // Panels graded towards the mirror direction from 1e-6 rad.
    let symmetric = |half: f64| {
        let right = graded(0.0, half, 1e-6, 0.25 * half);
        let mut breaks: Vec<f64> = right.iter().rev().map(|x| -x).collect();
        breaks.extend_from_slice(&right[1..]);
        breaks
    };
    let (a_breaks, b_breaks) = (symmetric(half_a), symmetric(half_b));
    integrate(&b_breaks, TOLERANCE, &mut |b: f64| {
        let (sin_b, cos_b) = b.sin_cos();
        integrate(&a_breaks, TOLERANCE, &mut |a: f64| {
            let (sin_o, cos_o) = (theta + a).sin_cos();
            let wo = DVec3::new(-sin_o * cos_b, sin_b, cos_o * cos_b);
            if wo.z <= 0.0 {
                return (Rgb::ZERO, Rgb::ZERO);
            }
            (material.f_r(wi, wo, frame) * (wo.z * cos_b), Rgb::ZERO)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, ReflectanceModel};

    #[test]
    fn black_glass_reads_100() {
        let mut glass = Material::new("standard", ReflectanceModel::Mirror);
        glass.fresnel = crate::material::Fresnel::Dielectric;
        glass.eta_i = 1.0;
        glass.eta_t = STANDARD_ETA;
        for g in GEOMETRIES {
            let r = gloss(&glass, g);
            assert!((r.gloss_units - 100.0).abs() < 1e-9, "{r:?}");
        }
    }

    /// Turning the sample by φ_i = 90° under the meter is anisotropic
    /// Ward with σ_x and σ_y swapped at φ_i = 0; an isotropic material
    /// reads the same at every φ_i.
    #[test]
    fn gloss_follows_the_azimuth() {
        let mut w = Material::new("w", ReflectanceModel::WardAnisotropic);
        (w.k_d, w.k_s, w.sigma_x, w.sigma_y) = (Rgb::ZERO, Rgb::ONE, 0.05, 0.3);
        let mut swapped = w.clone();
        (swapped.sigma_x, swapped.sigma_y) = (0.3, 0.05);
        let g = GEOMETRIES[1];
        let turned = gloss_at(&w, g, std::f64::consts::FRAC_PI_2).gloss_units;
        let same = gloss(&swapped, g).gloss_units;
        assert!((turned / same - 1.0).abs() < 1e-8, "{turned} vs {same}");
        assert!((turned / gloss(&w, g).gloss_units - 1.0).abs() > 0.1);
        let l = Material::new("l", ReflectanceModel::BlinnPhong);
        let (a, b) = (gloss(&l, g).gloss_units, gloss_at(&l, g, 1.0).gloss_units);
        assert!((a / b - 1.0).abs() < 1e-10, "{a} vs {b}");
    }

    #[test]
    fn lambert_gloss_matches_the_small_aperture_estimate() {
        let m = Material::new("l", ReflectanceModel::Lambert); // k_d = 0.8
        for g in GEOMETRIES {
            let r = gloss(&m, g);
            let theta = g.angle_deg.to_radians();
            // Aperture solid angle ≈ Δ_∥ Δ_⊥, cos θ_o ≈ cos θ over it.
            let omega = g.in_plane_deg.to_radians() * g.perpendicular_deg.to_radians();
            let approx = 0.8 / std::f64::consts::PI * theta.cos() * omega;
            let rel = r.aperture_reflectance.x / approx - 1.0;
            assert!(rel.abs() < 0.02, "{g:?}: {r:?} vs {approx}");
            assert!(r.error_bound.x < 1e-12, "{r:?}");
        }
    }
}
