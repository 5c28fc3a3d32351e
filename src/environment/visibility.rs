//! The truth's visibility switch (`environment.visibility`): the
//! CPU reference's environment term with the scene's own geometry
//! blocking the map, ray traced.
//!
//! The GPU's raster path is unshadowed (the map lights every surface as if
//! nothing stood in the way), so the like-for-like comparison leaves this
//! off (the default); with it on, the reference is the truth with
//! occlusion, and on minus off is what ignoring occlusion costs.
//!
//! The same deterministic texel quadrature as the unoccluded term
//! ([`super::quadrature`]), written as the unoccluded integral minus the
//! part the geometry blocks:
//!
//! `L_o = ∫ f L V cos dω = ∫ f L cos dω − Σ_{nodes with V = 0} f L cos w`,
//!
//! so a shading point that sees the whole sky keeps exactly the
//! unoccluded value (for the SH-diffuse mode its control-variate
//! integral, [`super::quadrature::Truth`]), and only the nodes a ray from
//! the point towards them hits something subtract. One ray per node above
//! the horizon: up to 12 288 per shading point for a map of
//! [`super::quadrature::MAX_TEXELS`].

use super::EnvironmentMap;
use super::quadrature::Node;
use crate::base::Rgb;
use crate::base::SurfaceFrame;
use glam::DVec3;

/// `scale · Σ f(ω) L(ω) cos θ w` over the nodes above the horizon of
/// `frame` that `visible` says are blocked (`visible(ω)` false), `ω` in
/// world space; `f(ω)` the BRDF (or the diffuse albedo over π) towards
/// `ω`. Subtracted from the unoccluded term by the reference.
pub fn occluded(
    map: &EnvironmentMap,
    nodes: &[Node],
    frame: &SurfaceFrame,
    f: impl Fn(DVec3) -> Rgb,
    visible: impl Fn(DVec3) -> bool,
) -> Rgb {
    let mut sum = Rgb::ZERO;
    for node in nodes {
        let wi = map.from_map(node.direction);
        let cos = frame.n.dot(wi);
        if cos > 0.0 && !visible(wi) {
            sum += f(wi) * node.radiance * (cos * node.weight);
        }
    }
    sum * map.settings.scale
}
