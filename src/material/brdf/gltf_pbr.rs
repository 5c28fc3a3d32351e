//! glTF 2.0's metallic-roughness BRDF (The Khronos Group, "glTF 2.0
//! Specification", Appendix B "BRDF Implementation"), in the `mix` form the
//! specification builds it from and the Khronos sample renderer evaluates:
//!
//! `f = (1 − m)·[(1 − F_d)·b/π + F_d·D·Vis] + m·(b + (1 − b)·w)·D·Vis`,
//! `w = (1 − |V·H|)⁵`, `F_d = 0.04 + 0.96·w`,
//!
//! with base colour `b`, metallic `m`, GGX `D` of `α = r²` and the
//! height-correlated Smith-GGX visibility `Vis = G / (4 |N·L| |N·V|)`.
//! The often-quoted single lerp (`c_diff = lerp(b, 0, m)`,
//! `F0 = lerp(0.04, b, m)`) equals it only at m = 0 and m = 1: its diffuse
//! term carries `(1 − F(F0))` with the metal's F0 mixed in, the mix form
//! the dielectric's `(1 − F_d)` alone (the test below measures 40 % at
//! m = ½).
//!
//! `r` is glTF's *perceptual* roughness: GGX's α is `r²`. Cook-Torrance's
//! `roughness` in gonio is α itself (the contract's `m`); the same scene key
//! means r here and α there, and the panel's label says which.
//!
//! WGSL twin: `shaders/brdf/gltf_pbr.wgsl` (same names, same order; its
//! `vis_smith_ggx_correlated` and `schlick_weight` are in `microfacet.rs`
//! here, below the environment BRDF table of `dfg.rs` that integrates them
//! and that this file's energy compensation reads).

use super::microfacet::{
    d_ggx, half_vector, schlick_weight, sin2_between, vis_smith_ggx_correlated,
};
use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// The Fresnel reflectance of glTF's dielectric at normal incidence (an
/// index of refraction of 1.5).
pub const DIELECTRIC_F0: f64 = 0.04;

/// `f_r` of glTF's metallic-roughness material (see the module doc), for
/// `N·I > 0`, `N·V > 0` (the caller's one-sided test). `roughness` is the
/// perceptual r; α = r². `ms` is energy compensation's `(1 − E)/E`
/// (`super::energy`; 0 without it, and the lobes are then exactly the
/// specification's): the dielectric's lobe is scaled by `1 + 0.04·ms`, the
/// metal's by `1 + b·ms`, each by its own `F0`.
pub fn gltf_pbr(
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let alpha = roughness * roughness;
    let h = half_vector(wi, wo);
    let cos_i = n.dot(wi);
    let cos_o = n.dot(wo);
    let cos_h = n.dot(h);
    let sin2_h = sin2_between(n, h);
    let cos_ih = wi.dot(h);
    let cos_oh = wo.dot(h);
    let specular =
        d_ggx(alpha, cos_h, sin2_h) * vis_smith_ggx_correlated(alpha, cos_i, cos_o, cos_ih, cos_oh);
    let w = schlick_weight(cos_oh);
    let f_dielectric = DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * w;
    let dielectric = base_color * ((1.0 - f_dielectric) * FRAC_1_PI)
        + Rgb::splat(f_dielectric * specular)
            * super::energy::ms_factor(Rgb::splat(DIELECTRIC_F0), ms);
    let metal = (base_color + (Rgb::ONE - base_color) * w)
        * specular
        * super::energy::ms_factor(base_color, ms);
    dielectric * (1.0 - metallic) + metal * metallic
}

#[cfg(test)]
mod tests {
    use super::super::microfacet::{d_ggx, g1_ggx, lambda_ggx};
    use super::*;
    use std::f64::consts::PI;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// The visibility equals the height-correlated G2 = 1/(1 + Λ_i + Λ_o)
    /// over 4 (N·L)(N·V), and is at least the separable Smith's.
    #[test]
    fn vis_is_the_height_correlated_smith_g() {
        let n = DVec3::Z;
        for alpha in [0.01, 0.2, 0.6, 1.0] {
            for (ti, to, p) in [(10.0, 20.0, 180.0), (60.0, 45.0, 90.0), (85.0, 80.0, 170.0)] {
                let (wi, wo) = (dir(ti, 0.0), dir(to, p));
                let h = half_vector(wi, wo);
                let (ci, co) = (n.dot(wi), n.dot(wo));
                let vis = vis_smith_ggx_correlated(alpha, ci, co, wi.dot(h), wo.dot(h));
                let g2 = 1.0 / (1.0 + lambda_ggx(alpha, ci) + lambda_ggx(alpha, co));
                let expected = g2 / (4.0 * ci * co);
                assert!(
                    (vis - expected).abs() < 1e-13 * expected,
                    "{vis} vs {expected}"
                );
                let separable =
                    g1_ggx(alpha, ci, wi.dot(h)) * g1_ggx(alpha, co, wo.dot(h)) / (4.0 * ci * co);
                assert!(
                    vis >= separable * (1.0 - 1e-14),
                    "α {alpha}: {vis} < {separable}"
                );
            }
        }
    }

    /// Golden values from the specification's formulas typed independently
    /// (Python, `math` only, outside this crate): b = (0.8, 0.5, 0.2),
    /// r = 0.5, θ_i = 30° at φ 0, θ_o = 50° at φ 160°, m ∈ {0, ½, 1}.
    #[test]
    fn golden_values() {
        let b = Rgb::new(0.8, 0.5, 0.2);
        let (wi, wo) = (dir(30.0, 0.0), dir(50.0, 160.0));
        for (m, expected) in [(0.0, GOLDEN_M0), (0.5, GOLDEN_M05), (1.0, GOLDEN_M1)] {
            let f = gltf_pbr(b, m, 0.5, 0.0, DVec3::Z, wi, wo);
            for c in 0..3 {
                assert!(
                    (f[c] - expected[c]).abs() < 1e-12 * expected[c],
                    "m {m} channel {c}: {} vs {}",
                    f[c],
                    expected[c]
                );
            }
        }
    }

    const GOLDEN_M0: [f64; 3] = [0.2744021037238076, 0.18278345004940055, 0.09116479637499353];
    const GOLDEN_M05: [f64; 3] = [0.4338627289911265, 0.2768880744566091, 0.11991341992209187];
    const GOLDEN_M1: [f64; 3] = [0.5933233542584454, 0.37099269886381775, 0.1486620434691902];

    /// The mix form is not the common lerp of `c_diff` and `F0`: equal at
    /// m = 0 and m = 1, 40 % off at m = ½ near normal incidence
    /// (the contract's warning), measured here.
    #[test]
    fn mix_form_differs_from_the_lerp_between_the_ends() {
        let b = Rgb::new(0.9, 0.9, 0.9);
        let (wi, wo) = (dir(10.0, 0.0), dir(20.0, 120.0));
        let lerp = |m: f64| {
            let alpha: f64 = 0.25;
            let h = half_vector(wi, wo);
            let w = schlick_weight(wo.dot(h));
            let f0 = Rgb::splat(DIELECTRIC_F0 * (1.0 - m)) + b * m;
            let f = f0 + (Rgb::ONE - f0) * w;
            let c_diff = b * (1.0 - m);
            let spec = d_ggx(alpha, h.z, sin2_between(DVec3::Z, h))
                * vis_smith_ggx_correlated(alpha, wi.z, wo.z, wi.dot(h), wo.dot(h));
            (Rgb::ONE - f) * c_diff * FRAC_1_PI + f * spec
        };
        for m in [0.0, 1.0] {
            let a = gltf_pbr(b, m, 0.5, 0.0, DVec3::Z, wi, wo);
            assert!((a - lerp(m)).abs().max_element() < 1e-14, "m {m}");
        }
        let (mix, lerped) = (gltf_pbr(b, 0.5, 0.5, 0.0, DVec3::Z, wi, wo), lerp(0.5));
        let off = (mix.x - lerped.x).abs() / lerped.x;
        assert!(off > 0.05, "mix {mix} lerp {lerped}: {off}");
    }

    /// Metallic 1, base colour 1: F = 1, so f_r = D·Vis, and at
    /// normal incidence into the mirror direction D = 1/(π α²) and
    /// Vis = 1/4.
    #[test]
    fn white_metal_is_the_bare_microfacet_lobe() {
        for r in [0.1, 0.5, 1.0] {
            let f = gltf_pbr(Rgb::ONE, 1.0, r, 0.0, DVec3::Z, DVec3::Z, DVec3::Z);
            let alpha: f64 = r * r;
            let expected = 1.0 / (PI * alpha * alpha) / 4.0;
            assert!((f.x - expected).abs() < 1e-12 * expected, "r {r}: {f}");
        }
    }
}
