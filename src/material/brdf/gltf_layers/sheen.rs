//! The sheen of `KHR_materials_sheen` (contract: "Layered glTF
//! materials", "Sheen"; pinned choices 5, 6, 10): Conty & Kulla's
//! "Charlie" distribution (2017, "Production Friendly Microfacet Sheen
//! BRDF", SIGGRAPH course "Physically Based Shading", eq. 2)
//! `D = (2 + 1/α) sin^(1/α)θ_h / (2π)` with their fitted Λ (§3, the
//! five-parameter fit interpolated in `(1 − α)²`) in the
//! non-height-correlated form `V = 1 / ((1 + Λ(μ_o) + Λ(μ_i)) 4 μ_o μ_i)`,
//! and the albedo scaling of the layer below,
//! `σ = max(0, min(1 − max₃(c_sh) E(μ_o), 1 − max₃(c_sh) E(μ_i)))`, with
//! `E` the exact directional albedo of `D·V` ([`super::sheen_albedo`]).
//!
//! WGSL twin: `shaders/brdf/gltf_layers/sheen.wgsl`.

use crate::base::Rgb;
use crate::material::brdf::COS_FLOOR;
use crate::material::brdf::phong::{exp_cutoff, neg_ln_1m};
use std::f64::consts::PI;

/// The sheen roughness floor (pinned choice 5, the Sample Renderer's).
pub const SHEEN_ROUGHNESS_FLOOR: f64 = 1e-6;

/// `α_sh = max(r_sh, 10⁻⁶)²`.
pub fn sheen_alpha(sheen_roughness: f64) -> f64 {
    let r = sheen_roughness.max(SHEEN_ROUGHNESS_FLOOR);
    r * r
}

/// `ln sin²θ_h` from `cos²θ_h` and `sin²θ_h`: `−(−ln(1 − cos²))` by the
/// series of `neg_ln_1m` where `cos²` is small (there the lobe lives, and
/// WGSL's `log` is only absolutely accurate near 1), `ln sin²` above.
pub fn ln_sin2(cos2_h: f64, sin2_h: f64) -> f64 {
    if cos2_h < 0.5 {
        -neg_ln_1m(cos2_h)
    } else {
        sin2_h.ln()
    }
}

/// Charlie's `D = (2 + 1/α) (sin²θ_h)^(1/(2α)) / (2π)` from `cos θ_h` and
/// `sin²θ_h = |N × H|²`; 0 for `N·H ≤ 0`. The power is
/// `e^(ln sin² / (2α))` through `exp_cutoff` (0 below `e^−80`, as every
/// lobe of gonio, so the f32 twin underflows at the same place; the
/// change is below 1.8e-35 times the prefactor).
pub fn d_charlie(alpha: f64, cos_h: f64, sin2_h: f64) -> f64 {
    if cos_h <= 0.0 || sin2_h <= 0.0 {
        return 0.0;
    }
    let cos_hc = cos_h.min(1.0);
    let exponent = ln_sin2(cos_hc * cos_hc, sin2_h.min(1.0)) / (2.0 * alpha);
    (2.0 + 1.0 / alpha) * exp_cutoff(exponent) / (2.0 * PI)
}

/// Conty & Kulla's fit `l(x) = a/(1 + b x^c) + d x + e`, each coefficient
/// `p₁ (1 − q) + p₀ q` with `q = (1 − α)²` (the contract's table).
pub fn sheen_lambda_fit(x: f64, alpha: f64) -> f64 {
    let q = (1.0 - alpha) * (1.0 - alpha);
    let mix = |p0: f64, p1: f64| p1 * (1.0 - q) + p0 * q;
    let a = mix(25.3245, 21.5473);
    let b = mix(3.32435, 3.82987);
    let c = mix(0.16801, 0.19823);
    let d = mix(-1.27393, -1.97760);
    let e = mix(-4.85967, -4.32054);
    let xc = if x > 0.0 { x.powf(c) } else { 0.0 };
    a / (1.0 + b * xc) + d * x + e
}

/// `Λ(μ) = exp(l(μ))` for `μ < 0.5`, `exp(2 l(0.5) − l(1 − μ))` otherwise.
pub fn sheen_lambda(cos: f64, alpha: f64) -> f64 {
    if cos < 0.5 {
        sheen_lambda_fit(cos, alpha).exp()
    } else {
        (2.0 * sheen_lambda_fit(0.5, alpha) - sheen_lambda_fit(1.0 - cos, alpha)).exp()
    }
}

/// `V = 1 / ((1 + Λ(μ_o) + Λ(μ_i)) · 4 μ_o μ_i)`, the cosines floored at
/// [`COS_FLOOR`] as the other visibilities are; 0 below either horizon.
pub fn v_sheen(alpha: f64, cos_i: f64, cos_o: f64) -> f64 {
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return 0.0;
    }
    let (ci, co) = (cos_i.min(1.0), cos_o.min(1.0));
    let lambda = 1.0 + sheen_lambda(co, alpha) + sheen_lambda(ci, alpha);
    1.0 / (lambda * 4.0 * ci.max(COS_FLOOR) * co.max(COS_FLOOR))
}

/// The sheen lobe `D_sh · V_sh` (without its colour).
pub fn sheen_lobe(alpha: f64, cos_h: f64, sin2_h: f64, cos_i: f64, cos_o: f64) -> f64 {
    d_charlie(alpha, cos_h, sin2_h) * v_sheen(alpha, cos_i, cos_o)
}

/// `ln` of the sheen lobe's weight seen along the normal (`V = N`):
/// `D_sh(θ_h) V_sh(cos θ, 1) cos θ` for light at θ from the normal, with
/// `θ_h = θ/2` (`sin²θ_h = (1 − cos θ)/2`) and `D`'s constant factor
/// dropped; −∞ below the horizon. A function of θ alone: the zonal kernel
/// of the environment's sheen stack (`scene::sheen_stack`), whose level
/// `α_level = r²` is floored as [`sheen_alpha`] floors `r_sh`. In the log
/// domain because at `r → 0` the weight underflows everywhere but at the
/// horizon, where the stack's quadrature still finds it.
pub fn sheen_normal_view_ln_weight(alpha_level: f64, cos: f64) -> f64 {
    if cos <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let cos = cos.min(1.0);
    let alpha = sheen_alpha(alpha_level.max(0.0).sqrt());
    let (cos2_h, sin2_h) = ((1.0 + cos) / 2.0, (1.0 - cos) / 2.0);
    if sin2_h <= 0.0 {
        return f64::NEG_INFINITY;
    }
    ln_sin2(cos2_h, sin2_h) / (2.0 * alpha) + (v_sheen(alpha, cos, 1.0) * cos).ln()
}

/// The albedo scaling of the layer below (pinned choices 6 and 10):
/// `σ = max(0, min(1 − max₃(c_sh) E(μ_o), 1 − max₃(c_sh) E(μ_i)))`.
pub fn sheen_scaling(sheen_color: Rgb, albedo_o: f64, albedo_i: f64) -> f64 {
    let c = sheen_color.max_element();
    (1.0 - c * albedo_o).min(1.0 - c * albedo_i).max(0.0)
}
