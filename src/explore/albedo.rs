//! Directional albedo `ρ(ω_i) = ∫_Ω+ f_r(ω_i, ω_o) cos θ_o dω_o`: the
//! quantity of the lecture's energy-conservation law ("Integral of f_r over
//! *outgoing* directions integrates to less than one, for any incoming
//! direction"), computed with a stated error estimate.
//!
//! # The quadrature
//!
//! Every glossy lobe of gonio peaks at (or, for microfacet lobes at grazing
//! incidence, is centred on) the mirror direction `r = R(ω_i)`, and may be
//! as narrow as ~10⁻⁴ rad. A fixed grid in (θ_o, φ_o) misses such a peak;
//! so the hemisphere is parametrized around `r` instead:
//!
//! `ω_o(α, β) = cos α · r + sin α · (cos β · u + sin β · v)`,
//! `dω_o = sin α dα dβ`,
//!
//! with `u` the unit vector in the plane of incidence orthogonal to `r` on
//! the normal's side and `v = r × u` (horizontal). For a fixed β the height
//! `cos θ_o = r_z cos α + u_z cos β sin α` is `C cos(α − δ(β))`, so the
//! upper hemisphere is exactly `0 ≤ α < α_max(β) = π/2 + δ(β)`,
//! `δ = atan2(u_z cos β, r_z)`: the horizon is a panel end, never inside a
//! panel, and the one-sided cut-off of every model costs no accuracy.
//!
//! * In α: adaptive Gauss-Kronrod ([`super::quadrature`]) on panels graded
//!   geometrically (by 2) from 2⁻²⁰ rad ≈ 10⁻⁶ rad at the peak (finer than
//!   any lobe a valid material has) and from `α_max · 2⁻⁸` at the horizon
//!   (where Ward's `√cos θ_o` has a square-root end point). Where a model
//!   has a kink on a known curve, that curve is a breakpoint: `α = π/2`
//!   (the lecture's Phong lobe is cut where `R·V = 0`) and the circles of
//!   constant θ_o listed by `kink_heights`. Other kinks (the V-groove's
//!   `min` in H) are found by the adaptive halving.
//! * In β: adaptive Gauss-Kronrod on the four quadrants, each graded
//!   towards both ends down to `min(π/8, ½ cot θ_i)`. Near grazing
//!   incidence `α_max(β)` swings from ~0 to ~π within `Δβ ≈ cot θ_i`
//!   around β = ±π/2, and microfacet lobes are compressed sideways by
//!   `cos θ_i`; both features live at the quadrant ends. Isotropic models
//!   are symmetric about the plane of incidence: only `β ∈ [0, π]` is
//!   integrated, and doubled.
//!
//! # The error bound
//!
//! Every panel is integrated with the 15-point Kronrod rule and, from the
//! same evaluations, the 7-point Gauss rule. The value reported is the
//! Kronrod one; the error bound is the sum over the final panels of
//! `|K15 − G7|` (of the outer integral, plus the Kronrod-weighted bounds of
//! the inner integrals), plus `10⁻¹² |ρ|` for rounding in sums of ~10⁵
//! terms. For integrands analytic in a panel the Kronrod error is orders
//! of magnitude below the Gauss error (Piessens et al. 1983, §2.2), so the
//! difference bounds it; panels holding a kink are halved until their
//! difference is below 10⁻¹¹ (inner) or 10⁻⁸ (outer) of the integral, so
//! what remains there is small and still counted. It is an a-posteriori
//! estimate, not a proof: the unit tests check it against closed forms
//! (Lambert: `ρ = k_d`; normalized Phong at normal incidence: `ρ = k_s`
//! exactly) and against an independent (θ_o, φ_o) product rule.
//!
//! The ideal mirror's Dirac lobe is not a function: its albedo
//! `k_s · F(cos θ_i)` is added in closed form (no error).

use super::part::MaterialPart;
use super::quadrature::{Tolerance, graded, insert_break, integrate as integrate_panels};
use crate::material::Material;
use crate::material::brdf::{self, CookTorrance, GeometryTerm, Specular, SurfaceFrame};
use crate::scene::Rgb;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_8, PI};

/// A directional albedo and the bound on its error (per channel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlbedoEstimate {
    /// `ρ = ∫ f_r cos θ_o dω_o`, dimensionless.
    pub value: Rgb,
    /// `|ρ_true − value|` is below this (see the module notes for how it is
    /// obtained and when it is an estimate rather than a proof).
    pub error_bound: Rgb,
}

/// Smallest α panel at the peak: 2⁻²⁰ rad ≈ 9.5·10⁻⁷ rad, finer than the
/// narrowest lobe a valid material has (roughness ≥ 10⁻⁴ in `f_r`, Phong
/// `k_e ≤ 10⁶`, width ≥ 1.4·10⁻³ rad).
const PEAK_PANEL: f64 = 1.0 / (1u32 << 20) as f64;

/// Smallest α panel at the horizon, relative to `α_max`.
const HORIZON_PANEL: f64 = 1.0 / 256.0;

/// The directional albedo of `material` for light from polar angle
/// `theta_i` (radians from the normal) in the plane `φ_i = 0` (along the
/// tangent), in the frame of [`super::frame`]. Zero for `θ_i ≥ π/2`
/// (one-sided).
pub fn directional_albedo<'a>(
    material: impl Into<MaterialPart<'a>>,
    theta_i: f64,
) -> AlbedoEstimate {
    albedo_towards(material, super::direction(theta_i, 0.0), &super::frame())
}

/// The directional albedo at several polar angles `thetas` in the plane
/// `φ_i = phi_i` (radians), in parallel. (`gonio brdf --plot-albedo` once
/// ignored `--phi-i`, giving 0.626 where `--albedo` gave 0.6371 for an
/// anisotropic Ward material.)
pub fn albedo_curve<'a>(
    material: impl Into<MaterialPart<'a>>,
    thetas: &[f64],
    phi_i: f64,
) -> Vec<AlbedoEstimate> {
    albedo_curve_with(material, thetas, phi_i, &|| {})
}

/// [`albedo_curve`], calling `done` after each angle (a progress bar: a
/// measured network's curve takes a minute on 2 cores).
pub fn albedo_curve_with<'a>(
    material: impl Into<MaterialPart<'a>>,
    thetas: &[f64],
    phi_i: f64,
    done: &(dyn Fn() + Sync),
) -> Vec<AlbedoEstimate> {
    let material = material.into();
    let frame = super::frame();
    thetas
        .par_iter()
        .map(|&t| {
            let a = albedo_towards(material, super::direction(t, phi_i), &frame);
            done();
            a
        })
        .collect()
}

/// The directional albedo for the unit direction `wi` (towards the light)
/// in an arbitrary shading frame.
/// A `&Material` is its whole `f_r`; a [`MaterialPart`] one layer's term.
pub fn albedo_towards<'a>(
    material: impl Into<MaterialPart<'a>>,
    wi: DVec3,
    frame: &SurfaceFrame,
) -> AlbedoEstimate {
    let material = material.into();
    let local = DVec3::new(wi.dot(frame.t), wi.dot(frame.b), wi.dot(frame.n));
    if local.z <= 0.0 {
        return AlbedoEstimate {
            value: Rgb::ZERO,
            error_bound: Rgb::ZERO,
        };
    }
    let geometry = MirrorFrame::new(local);
    let (q, error) = integrate(&material, wi, frame, &geometry);
    // Zero but for a Dirac lobe (the mirror).
    let dirac = material.dirac(local.z);
    AlbedoEstimate {
        value: q + dirac,
        error_bound: error + 1e-12 * q.abs() + material.sheen_curve_error(),
    }
}

/// The mirror direction and its orthonormal companions, in local
/// coordinates (`n = +Z`).
struct MirrorFrame {
    r: DVec3,
    u: DVec3,
    v: DVec3,
    /// `cot θ_i`, the scale of the sideways features near grazing.
    cot_theta: f64,
}

impl MirrorFrame {
    fn new(wi: DVec3) -> Self {
        let r = DVec3::new(-wi.x, -wi.y, wi.z);
        let sin_theta = r.truncate().length();
        let u = if sin_theta > 1e-12 {
            // (n − r cos θ) / sin θ: in the plane of incidence, ⟂ r, u_z = sin θ.
            (DVec3::Z - r * r.z) / sin_theta
        } else {
            DVec3::X
        };
        MirrorFrame {
            r,
            u,
            v: r.cross(u),
            cot_theta: r.z / sin_theta.max(1e-300),
        }
    }

    /// Where the great circle from `r` in direction β meets the horizon.
    fn alpha_max(&self, beta: f64) -> (f64, f64) {
        let delta = (self.u.z * beta.cos()).atan2(self.r.z);
        (FRAC_PI_2 + delta, delta)
    }

    fn direction(&self, alpha: f64, (sin_b, cos_b): (f64, f64)) -> DVec3 {
        let (sin_a, cos_a) = alpha.sin_cos();
        self.r * cos_a + (self.u * cos_b + self.v * sin_b) * sin_a
    }
}

/// Inner (α) tolerance: tight, so that the inner integrals are smooth in β
/// far below the outer tolerance.
const INNER: Tolerance = Tolerance {
    rel: 1e-11,
    abs: 1e-300,
    max_depth: 24,
};

/// Outer (β) tolerance.
const OUTER: Tolerance = Tolerance {
    rel: 1e-8,
    abs: 1e-300,
    max_depth: 10,
};

/// `(∫ f_r cos θ_o dω_o, error bound)` over the upper hemisphere.
fn integrate(part: &MaterialPart, wi: DVec3, frame: &SurfaceFrame, g: &MirrorFrame) -> (Rgb, Rgb) {
    let material = part.material;
    // gltf-pbr's anisotropy layer turns its lobe out of the plane of
    // incidence: no mirror symmetry then.
    let isotropic = !material.model.needs_tangents() && material.layers.anisotropy_strength == 0.0;
    let (beta_end, symmetry) = if isotropic {
        (PI, 2.0)
    } else {
        (2.0 * PI, 1.0)
    };
    let h_beta = FRAC_PI_8.min(0.5 * g.cot_theta);
    let mut beta_breaks = vec![0.0];
    let mut start = 0.0;
    while start < beta_end - 1e-12 {
        let end = start + FRAC_PI_2;
        beta_breaks.extend_from_slice(&graded(start, end, h_beta, h_beta)[1..]);
        start = end;
    }
    let kinks = kink_heights(material, g.r.z);
    let mut inner = |beta: f64| {
        let (alpha_max, delta) = g.alpha_max(beta);
        let mut breaks = graded(0.0, alpha_max, PEAK_PANEL, alpha_max * HORIZON_PANEL);
        insert_break(&mut breaks, FRAC_PI_2);
        // cos θ_o = C cos(α − δ): the circle cos θ_o = h at α = δ ± acos(h/C).
        let (sin_b, cos_b) = beta.sin_cos();
        let c = g.r.z.hypot(g.u.z * cos_b);
        for &h in &kinks {
            if h < c {
                let spread = (h / c).acos();
                insert_break(&mut breaks, delta + spread);
                insert_break(&mut breaks, delta - spread);
            }
        }
        integrate_panels(&breaks, INNER, &mut |alpha: f64| {
            let local = g.direction(alpha, (sin_b, cos_b));
            if local.z <= 0.0 {
                return (Rgb::ZERO, Rgb::ZERO);
            }
            let wo = (frame.t * local.x + frame.b * local.y + frame.n * local.z).normalize();
            let value = part.f_r(wi, wo, frame) * (local.z * alpha.sin());
            (value, Rgb::ZERO)
        })
    };
    let (value, error) = integrate_panels(&beta_breaks, OUTER, &mut inner);
    (value * symmetry, error * symmetry)
}

/// Heights `cos θ_o` of the circles on which a model's `f_r` has a kink,
/// made breakpoints so no panel holds them: `θ_o = θ_i` (the `max(N·I,
/// N·V)` of normalized Blinn-Phong, the `min(N·V, N·I)` of the V-groove
/// term), `cos θ_o = COS_FLOOR` (where the cosine floors of the lecture
/// and microfacet forms take over), and for Smith's G with a Beckmann
/// slope `m_b` the branch `cot θ_o = 1.6 m_b` of its rational fit.
fn kink_heights(material: &Material, cos_theta_i: f64) -> Vec<f64> {
    let mut heights = vec![cos_theta_i, brdf::COS_FLOOR];
    if let Specular::CookTorrance(CookTorrance {
        g: GeometryTerm::SmithBeckmann { slope },
        ..
    }) = material.brdf().specular
    {
        let cot = 1.6 * slope;
        heights.push(cot / (1.0 + cot * cot).sqrt());
    }
    heights
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The curve `--plot-albedo` draws takes φ_i as `--albedo` does:
    /// an anisotropic Ward material's albedo depends on it.
    #[test]
    fn the_albedo_curve_is_taken_at_phi_i() {
        let mut m = Material::new("w", crate::material::ReflectanceModel::WardAnisotropic);
        (m.sigma_x, m.sigma_y) = (0.05, 0.4);
        (m.k_d, m.k_s) = (Rgb::ZERO, Rgb::ONE);
        let (theta, phi) = (1.2, 90f64.to_radians());
        let curve = albedo_curve(&m, &[theta], phi)[0];
        let cli = albedo_towards(
            &m,
            crate::explore::direction(theta, phi),
            &crate::explore::frame(),
        );
        assert_eq!(curve, cli);
        let along_tangent = albedo_curve(&m, &[theta], 0.0)[0];
        assert!((curve.value - along_tangent.value).abs().max_element() > 1e-3);
    }
    use crate::material::ReflectanceModel;

    fn lambert(k_d: Rgb) -> Material {
        let mut m = Material::new("lambert", ReflectanceModel::Lambert);
        m.k_d = k_d;
        m
    }

    fn lobe(model: ReflectanceModel) -> Material {
        let mut m = Material::new("lobe", model);
        m.k_d = Rgb::ZERO;
        m.k_s = Rgb::ONE;
        m
    }

    /// `|value − exact| ≤ bound` in every channel.
    fn within(e: &AlbedoEstimate, exact: Rgb) -> bool {
        ((e.value - exact).abs() - e.error_bound).max_element() <= 0.0
    }

    #[test]
    fn lambert_albedo_is_k_d_within_the_bound() {
        let k_d = Rgb::new(0.2, 0.5, 0.9);
        let m = lambert(k_d);
        for deg in [
            0.0, 1e-3, 10.0, 30.0, 45.0, 60.0, 80.0, 85.0, 89.0, 89.9, 89.999,
        ] {
            let e = directional_albedo(&m, f64::to_radians(deg));
            assert!(within(&e, k_d), "θ_i = {deg}°: {e:?}");
            assert!(e.error_bound.max_element() < 1e-9, "θ_i = {deg}°: {e:?}");
        }
    }

    #[test]
    fn normalized_phong_conserves_energy_exactly_at_normal_incidence() {
        // ∫ (k_e+2)/(2π) cos^k_e θ cos θ dω = 1 over the hemisphere. Beyond
        // the quadrature, f_r itself is uncertain by k_e · 2⁻⁵² relative:
        // the rounding of the cosine R·V, raised to the power k_e.
        for k_e in [0.0, 1.0, 100.0, 1e4, 1e6] {
            let mut m = lobe(ReflectanceModel::PhongNormalized);
            m.k_e = k_e;
            let e = directional_albedo(&m, 0.0);
            let evaluation = 4.0 * k_e * f64::EPSILON;
            let error = (e.value - Rgb::ONE).abs().max_element();
            assert!(
                error <= e.error_bound.max_element() + evaluation,
                "k_e = {k_e}: {e:?}"
            );
            assert!(e.error_bound.max_element() < 1e-9, "k_e = {k_e}: {e:?}");
        }
    }

    #[test]
    fn sharp_lobes_are_found_away_from_the_normal() {
        // A cos^k lobe around r loses only what lies below the horizon:
        // nothing for k_e = 1e4 at 30°, so ρ = ∫ lobe · cos θ_o ≈ cos θ_i.
        let mut m = lobe(ReflectanceModel::PhongNormalized);
        m.k_e = 1e4;
        let theta: f64 = 30f64.to_radians();
        let e = directional_albedo(&m, theta);
        // The lobe averages cos θ_o over a cap of angular radius ~1e-2:
        // cos θ_i up to O(1/k_e).
        assert!((e.value.x - theta.cos()).abs() < 2.0 / m.k_e, "{e:?}");
        // The narrowest roughness: Beckmann with F = 1 and no G keeps
        // ρ ≈ 1 for an almost-flat mirror-like surface.
        let mut ct = lobe(ReflectanceModel::CookTorrance);
        ct.roughness = 1e-3;
        ct.distribution = crate::material::Distribution::Beckmann;
        ct.geometry = crate::material::Geometry::None;
        ct.fresnel = crate::material::Fresnel::None;
        let e = directional_albedo(&ct, theta);
        assert!((e.value.x - 1.0).abs() < 1e-4, "{e:?}");
    }

    #[test]
    fn mirror_albedo_is_its_reflectance() {
        let mut m = Material::new("m", ReflectanceModel::Mirror);
        m.k_s = Rgb::splat(0.7);
        let e = directional_albedo(&m, 0.4);
        assert!(within(&e, Rgb::splat(0.7)), "{e:?}");
    }

    #[test]
    fn below_the_horizon_is_zero() {
        let e = directional_albedo(&lambert(Rgb::ONE), 2.0);
        assert_eq!(e.value, Rgb::ZERO);
    }

    /// The albedo by a plain product rule in (cos θ_o, φ_o), which shares
    /// nothing with the mirror-centred parametrization but the quadrature
    /// panels; fine for the broad lobes used here.
    fn product_rule(m: &Material, theta: f64) -> Rgb {
        let (wi, f) = (
            crate::explore::direction(theta, 0.0),
            crate::explore::frame(),
        );
        let tol = Tolerance {
            rel: 1e-12,
            abs: 1e-300,
            max_depth: 30,
        };
        let (mu_breaks, phi_breaks) = (graded(0.0, 1.0, 1e-4, 1e-4), graded(0.0, PI, 1e-3, 1e-3));
        let (v, _) = integrate_panels(&phi_breaks, tol, &mut |phi: f64| {
            integrate_panels(&mu_breaks, tol, &mut |mu: f64| {
                let s = (1.0 - mu * mu).sqrt();
                let wo = DVec3::new(s * phi.cos(), s * phi.sin(), mu);
                (m.f_r(wi, wo, &f) * mu, Rgb::ZERO)
            })
        });
        2.0 * v
    }

    #[test]
    fn agrees_with_an_independent_product_rule() {
        for spec in [
            "phong,k_d=0.3,k_s=0.5,k_e=10",
            "blinn-phong-normalized,k_d=0,k_s=1,k_e=10",
            "ward,k_d=0,k_s=1,sigma=0.5",
            "cook-torrance,k_d=0,k_s=1,distribution=ggx,roughness=0.5,fresnel=schlick",
            "cook-torrance,k_d=0,k_s=1,preset=gold,roughness=0.5,geometry=none",
        ] {
            let m = crate::explore::spec::compare_spec(spec, &[])
                .unwrap()
                .material;
            for deg in [0.0, 45.0, 85.0] {
                let e = directional_albedo(&m, f64::to_radians(deg));
                let reference = product_rule(&m, f64::to_radians(deg));
                // 1e-10: the product rule's own error.
                let gap = (e.value - reference).abs() - e.error_bound;
                assert!(
                    gap.max_element() < 1e-10,
                    "{spec} at {deg}°: {e:?} vs {reference}"
                );
            }
        }
    }
}
