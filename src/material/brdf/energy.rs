//! Energy compensation for the microfacet models (the material key
//! `energy_compensation = true`, off by default: with it off, `f_r` is
//! exactly the contract's model).
//!
//! A single-scattering microfacet BRDF loses the light that bounces more
//! than once between the facets: a white conductor (`F = 1`) of GGX at
//! α = 1 keeps only `E(μ_o, α) = 0.31..0.45` of a uniform white sky
//! (`E` the directional albedo, `crate::material::brdf::dfg`). Turquin
//! (2019, "Practical multiple scattering compensation for microfacet
//! models", Tech. report, eq. 7-8) scales the specular lobe by
//!
//! `1 + F0 · (1 − E(μ_o, α)) / E(μ_o, α)`,
//!
//! which makes a white conductor's albedo `E/E = 1` exactly and, for a
//! coloured one, adds the energy the missing bounces would carry to first
//! order in `F0` (Turquin's Fig. 4 compares it with Kulla & Conty 2017's
//! separate lobe: within a few percent, at no second table). `E` is the
//! GGX / height-correlated-Smith albedo of [`crate::material::brdf::dfg`]
//! (the same f32 nodes on the GPU, `Globals::albedo`), read at `μ_o = N·V`
//! (Turquin's choice; the compensated BRDF is then not reciprocal) and at
//! the GGX α of the lobe:
//!
//! * gltf-pbr: α = r²; each of its two specular lobes (the dielectric's
//!   with `F0 = 0.04`, the metal's with `F0 = b`) gets its own factor;
//! * Cook-Torrance: the GGX α standing in for its distribution
//!   (`dfg::ggx_alpha`, as the split-sum mode takes it) and
//!   `F0 = F(1)`. Exact (to the table's error) for `distribution = "ggx"`,
//!   `geometry = "smith-correlated"`, `denominator = "microfacet"`: the
//!   model the table integrates; for its other terms the GGX albedo is a
//!   stand-in (their furnace is not 1).
//!
//! Every light sees the compensated `f_r` (point lights, area samples and
//! the environment: the reference integrates [`crate::material::Material::f_r`]).
//!
//! WGSL twin: `shaders/brdf/energy.wgsl` (same names, same order).

use super::dfg;
use crate::base::Rgb;

/// The smallest albedo divided by: `E ≥ 0.3069` everywhere in the table
/// (α = 1 seen head-on, `1 − ln 2`), so the floor only guards a zeroed
/// table.
pub const E_FLOOR: f64 = 1e-4;

/// The relative f32 error the GPU's compensation factor adds (the
/// GPU-vs-reference tolerance, `tests/common`): the factor
/// `1 + F0(1 − E)/E` moves by at most `δE/E` relative (`F0 ≤ 1`), `E ≥
/// 0.3`. `δE`: the bilinear sum of f32 nodes (≤ 1, 8 operations: 8ε)
/// and its weights, `31·√μ` off by Vulkan's `sqrt` (inherited from
/// `1/inversesqrt`: 2 + 2.5 ulp) and `μ`'s own rounding (8ε; at μ ≥ 1e-2
/// `√μ` amplifies it at most 5×), times a node step of `E` (≤ 0.3): about
/// 31·(5 + 40)ε·0.3 + 8ε ≈ 430ε; over E: 1440ε, taken as 2048ε.
pub const F32_ERROR: f64 = 2048.0 / 16_777_216.0;

/// `E(μ_o, α)`, bilinear in the table (`DfgTable::albedo`). Twin:
/// `ms_albedo`.
pub fn ms_albedo(alpha: f64, cos_o: f64) -> f64 {
    dfg::table().albedo(cos_o, alpha)
}

/// `(1 − E)/E` at `(μ_o, α)`: what the lobe gains per unit of `F0`.
/// Twin: `ms_ratio`.
pub fn ms_ratio(alpha: f64, cos_o: f64) -> f64 {
    let e = ms_albedo(alpha, cos_o);
    (1.0 - e) / e.max(E_FLOOR)
}

/// The factor `1 + F0 · ratio` a lobe of normal-incidence Fresnel `f0` is
/// scaled by (`ratio` 0 without compensation: the factor is then exactly
/// 1). Twin: `ms_factor`.
pub fn ms_factor(f0: Rgb, ratio: f64) -> Rgb {
    Rgb::ONE + f0 * ratio
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::brdf::microfacet::d_ggx;
    use crate::material::brdf::{SurfaceFrame, any_tangent};
    use crate::material::{Material, ReflectanceModel};
    use glam::DVec3;
    use std::f64::consts::TAU;

    /// `∫ f_r(l, v) cos θ_l dω_l` of `m` at `μ = N·V` by `n` GGX-distributed
    /// half vectors of α (Hammersley; weight `f_r cos θ_l / pdf(l)`,
    /// `pdf(l) = D(h) cos θ_h / (4 V·H)`): the albedo under a uniform white
    /// sky, through `Material::f_r` itself.
    fn albedo(m: &Material, alpha: f64, mu: f64, n: u32) -> Rgb {
        let frame = SurfaceFrame {
            n: DVec3::Z,
            t: any_tangent(DVec3::Z),
            b: DVec3::Z.cross(any_tangent(DVec3::Z)),
        };
        let v = DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        let mut sum = Rgb::ZERO;
        for k in 0..n {
            let u1 = (k as f64 + 0.5) / n as f64;
            let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
            let cos_h = ((1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1)).sqrt();
            let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
            let h = DVec3::new(sin_h * (TAU * u2).cos(), sin_h * (TAU * u2).sin(), cos_h);
            let l = h * (2.0 * v.dot(h)) - v;
            if l.z <= 0.0 || v.dot(h) <= 0.0 {
                continue;
            }
            let pdf = d_ggx(alpha, cos_h, sin_h * sin_h) * cos_h / (4.0 * v.dot(h));
            sum += m.f_r(l, v, &frame) * (l.z / pdf);
        }
        sum * (1.0 / n as f64)
    }

    fn white_metal(r: f64, on: bool) -> Material {
        let mut m = Material::new("white metal", ReflectanceModel::GltfPbr);
        (m.base_color, m.metallic, m.roughness) = (Rgb::ONE, 1.0, r);
        m.energy_compensation = on;
        m
    }

    /// The white furnace before and after: a white
    /// conductor (gltf-pbr, b = 1, m = 1; and the same lobe as
    /// Cook-Torrance ggx / smith-correlated / Fresnel none / 4 (N·V)(N·I))
    /// under a uniform white sky keeps `E(μ, α)` without compensation and
    /// `E/E_table = 1` with it, to the table's error: its interpolation
    /// (at most 2.3e-3 in `E` for μ ≥ 0.1) plus its quadrature's (4096
    /// half vectors: at most 5.9e-3, at grazing with small α; both
    /// measured by `dfg`'s test) plus this test's own (65 536 half
    /// vectors of the same sequence: 1e-3 allowed), over `E`: asserted
    /// with `(2.3e-3 + 5.9e-3 + 1e-3)/E`. Printed: before/after at r = 0.25 .. 1 and
    /// μ = 0.1 .. 1, and the hemispherical averages `2∫ E μ dμ`.
    #[test]
    fn the_white_furnace_before_and_after() {
        let n = 1 << 16;
        let mut ct = Material::new("white ct", ReflectanceModel::CookTorrance);
        ct.distribution = crate::material::Distribution::Ggx;
        ct.geometry = crate::material::Geometry::SmithCorrelated;
        ct.fresnel = crate::material::Fresnel::None;
        (ct.k_d, ct.k_s) = (Rgb::ZERO, Rgb::ONE);
        let mut worst = 0.0f64;
        for r in [0.25, 0.5, 0.75, 1.0] {
            let alpha = r * r;
            let (mut avg_off, mut avg_on) = (0.0, 0.0);
            let steps = 16;
            let mut row = String::new();
            for k in 0..steps {
                let mu = (k as f64 + 0.5) / steps as f64;
                let off = albedo(&white_metal(r, false), alpha, mu, n / 4).x;
                let on = albedo(&white_metal(r, true), alpha, mu, n / 4).x;
                avg_off += 2.0 * off * mu / steps as f64;
                avg_on += 2.0 * on * mu / steps as f64;
            }
            for mu in [0.1, 0.25, 0.5, 1.0] {
                let off = albedo(&white_metal(r, false), alpha, mu, n).x;
                let on = albedo(&white_metal(r, true), alpha, mu, n).x;
                let ct_on = {
                    let mut c = ct.clone();
                    (c.roughness, c.energy_compensation) = (alpha, true);
                    albedo(&c, alpha, mu, n).x
                };
                let tol = (2.3e-3 + 5.9e-3 + 1e-3) / off;
                worst = worst.max((on - 1.0).abs() / tol);
                assert!(
                    (on - 1.0).abs() < tol && (ct_on - 1.0).abs() < tol,
                    "r {r} μ {mu}: {off} → {on} (Cook-Torrance {ct_on}), tolerance {tol}"
                );
                row += &format!(" μ {mu}: {off:.4} → {on:.4} |");
            }
            eprintln!("furnace r = {r} (α = {alpha:.4}):{row} E_avg {avg_off:.4} → {avg_on:.4}");
        }
        eprintln!("worst |after − 1| / tolerance: {worst:.2}");
    }

    /// The floor never acts on the real table: its smallest node (α = 1
    /// head-on, `1 − ln 2`) is far above [`E_FLOOR`], which is what bounds
    /// the factor and the f32 error ([`F32_ERROR`] assumes `E ≥ 0.3`).
    /// Measured: min 0.3069, max 1.0076 (the quadrature's overshoot at the
    /// first node, μ = 1e-4 with small α: a factor just below 1 there).
    #[test]
    fn the_albedo_table_is_bounded_away_from_zero() {
        let t = dfg::table();
        let min = t.albedo_nodes.iter().fold(f32::INFINITY, |a, &e| a.min(e));
        let max = t.albedo_nodes.iter().fold(0.0f32, |a, &e| a.max(e));
        eprintln!("albedo nodes: min {min:.4}, max {max:.4}");
        assert!(min > 0.3 && max < 1.01, "{min} {max}");
    }

    /// Off is exactly the contract's model: every model's `f_r` with the
    /// flag off equals the one with no flag at all (the factor is exactly
    /// 1), and on changes only gltf-pbr and Cook-Torrance (whose lobes grow:
    /// the factor is ≥ 1).
    #[test]
    fn off_is_the_contract_and_on_only_grows_the_lobes() {
        let frame = SurfaceFrame {
            n: DVec3::Z,
            t: DVec3::X,
            b: DVec3::Y,
        };
        let (wi, wo) = (
            DVec3::new(0.5, 0.1, 0.86).normalize(),
            DVec3::new(-0.6, 0.2, 0.77).normalize(),
        );
        for row in crate::material::table::ROWS {
            let mut m = Material::new("m", row.model);
            m.k_s = Rgb::splat(0.5);
            let off = m.f_r(wi, wo, &frame);
            if !row.energy_compensation {
                let mut on = m.clone();
                on.energy_compensation = true;
                assert!(on.validate().is_err(), "{}", row.model.name());
                continue;
            }
            let mut k = m.clone();
            k.energy_compensation = false;
            assert_eq!(k.f_r(wi, wo, &frame), off);
            k.energy_compensation = true;
            let on = k.f_r(wi, wo, &frame);
            for c in 0..3 {
                assert!(on[c] > off[c], "{}: {on} vs {off}", row.model.name());
            }
        }
    }
}
