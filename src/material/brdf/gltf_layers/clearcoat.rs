//! The coat of `KHR_materials_clearcoat` (contract: "Layered glTF
//! materials", "Clearcoat"; pinned choice 7): a dielectric layer of IOR
//! 1.5 (whatever `ior` is) with its own isotropic GGX lobe of
//! `α_c = r_c²` (glTF 2.0 Appendix B's `specular_brdf`), over the layers
//! below, weighted by the coat's Fresnel at the view,
//! `F_c = 0.04 + 0.96 (1 − μ_o)⁵` (the specification's
//! `fresnel_coat(clearcoat_normal, …)`, evaluated with `N·V`):
//!
//! `f_r = (1 − k F_c) · below + k F_c · G_{α_c}`.
//!
//! `r_c = 0` is an ideal mirror coat: its Dirac lobe of weight `k F_c(μ_o)`
//! is not a function value, so `G_0 = 0` here (the finite part). Above 0,
//! `α_c` is floored at the renderer's [`ROUGHNESS_FLOOR`] (1e-4), as every
//! other lobe is: below it `1/α²` leaves `f32`'s range.
//!
//! `F_c` depends on `V` alone: with a coat `f_r` is not reciprocal.
//!
//! The coat has its own normal `n_c` (`clearcoat_normal_texture`,
//! glTF's `clearcoatNormalTexture`; [`coat_normal`]): the coat's lobe and
//! `F_c` are evaluated about it, `F_c` at `max(n_c·V, 0)` (the Sample
//! Renderer's `clampedDot`: a coat normal turned away from the viewer
//! reflects everything, `F_c = 1`). Without the texture `n_c = N`, where
//! `N·V > 0`, and nothing changes.
//!
//! WGSL twin: `shaders/brdf/gltf_layers/clearcoat.wgsl`.

use crate::base::Rgb;
use crate::material::ROUGHNESS_FLOOR;
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::gltf_pbr::DIELECTRIC_F0;
use crate::material::brdf::microfacet::{d_ggx, half_vector, sin2_between};
use crate::material::brdf::microfacet::{schlick_weight, vis_smith_ggx_correlated};
use glam::DVec3;

/// `F_c = 0.04 + 0.96 (1 − μ_o)⁵`: the coat's Schlick Fresnel (IOR 1.5)
/// at the view.
pub fn clearcoat_fresnel(cos_o: f64) -> f64 {
    DIELECTRIC_F0 + (1.0 - DIELECTRIC_F0) * schlick_weight(cos_o)
}

/// The coat's GGX lobe `G_{α_c} = D·Vis`, `α_c = r_c²` floored at
/// [`ROUGHNESS_FLOOR`]; 0 for `r_c = 0` (the mirror coat's finite part).
pub fn clearcoat_lobe(clearcoat_roughness: f64, n: DVec3, wi: DVec3, wo: DVec3) -> f64 {
    if clearcoat_roughness <= 0.0 {
        return 0.0;
    }
    let alpha = (clearcoat_roughness * clearcoat_roughness).max(ROUGHNESS_FLOOR);
    let h = half_vector(wi, wo);
    d_ggx(alpha, n.dot(h), sin2_between(n, h))
        * vis_smith_ggx_correlated(alpha, n.dot(wi), n.dot(wo), wi.dot(h), wo.dot(h))
}

/// The coat's normal `n_c = x·t + y·b + z·n` from its coordinates
/// `(x, y, z)` in the shading frame ([`super::GltfLayers::clearcoat_normal`]);
/// exactly `n` for `(0, 0, 1)`.
pub fn coat_normal(frame: &SurfaceFrame, coords: DVec3) -> DVec3 {
    if coords == DVec3::Z {
        return frame.n;
    }
    frame.t * coords.x + frame.b * coords.y + frame.n * coords.z
}

/// The coat's weight `k F_c` about the coat normal `n`: what the coat
/// reflects of its own lobe; `1 − k F_c` is what it lets through.
pub fn clearcoat_weight(clearcoat: f64, n: DVec3, wo: DVec3) -> f64 {
    clearcoat * clearcoat_fresnel(n.dot(wo).max(0.0))
}

/// The coat's own term `k F_c · G_{α_c}` (the explorer's
/// [`LayerTerm::Clearcoat`](crate::material::layers::LayerTerm)).
pub fn clearcoat_term(
    clearcoat: f64,
    clearcoat_roughness: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let weight = clearcoat_weight(clearcoat, n, wo);
    Rgb::splat(weight * clearcoat_lobe(clearcoat_roughness, n, wi, wo))
}

/// The coat over `below` about the coat normal `n`:
/// `(1 − k F_c) · below + k F_c · G_{α_c}`.
pub fn clearcoat_over(
    below: Rgb,
    clearcoat: f64,
    clearcoat_roughness: f64,
    n: DVec3,
    wi: DVec3,
    wo: DVec3,
) -> Rgb {
    let weight = clearcoat_weight(clearcoat, n, wo);
    below * (1.0 - weight) + clearcoat_term(clearcoat, clearcoat_roughness, n, wi, wo)
}
