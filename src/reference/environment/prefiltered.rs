//! Glossy reflection by the split-sum approximation (Karis 2013, "Real
//! Shading in Unreal Engine 4", SIGGRAPH course notes),
//! `environment.specular = "prefiltered"`:
//! `∫ f_r L cos θ_i dω ≈ L̃(R, α) · (F0 · A(μ, α) + B(μ, α))`, the
//! prefiltered radiance `L̃` of `crate::environment::prefiltered` times
//! the environment BRDF of `crate::material::brdf::dfg`.
//!
//! Which models it applies to: gltf-pbr, with its layers, by
//! [`super::prefiltered_layers`] (α = r², the split of its mix form, the
//! diffuse term weighted by one minus the dielectric lobe's albedo); and
//! (`specular_terms`) Cook-Torrance
//! with every distribution taken as GGX of a matched α (`dfg::ggx_alpha`:
//! Beckmann's and the Gaussians' m, Blinn's exponent through Walter et
//! al.'s Phong–Beckmann match) and its Fresnel as Schlick's of `F0 = F(1)`, the lobe times
//! `k_s · 4/c` (`c` its denominator). Its `G` (Smith, V-groove, none) is
//! replaced by GGX's height-correlated Smith: that mismatch is part of the
//! measured error. The other models get the diffuse term alone (as in
//! `"none"`). Diffuse: SH irradiance times the diffuse albedo.
//!
//! WGSL twin: `environment_prefiltered` in shaders/environment.wgsl; this
//! file's [`estimate`] is its f64 twin (the same f32 tables).

use super::diffuse::environment_diffuse_albedo;
use super::dominant::dominant_direction;
use crate::base::{Rgb, SurfaceFrame};
use crate::environment::EnvironmentMap;
use crate::environment::prefiltered::Prefiltered;
use crate::material::brdf::Specular as BrdfSpecular;
use crate::material::brdf::dfg::{self, ggx_alpha};
use crate::material::brdf::phong::mirror_direction;
use crate::material::{Material, ReflectanceModel};
use crate::reference::brdf::reference_brdf;
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// `(α, F0, weight)` of the split for `material` (see the module doc):
/// the specular part is `weight · L̃(R, α) · (F0·A + B)`; weight 0 for
/// models it does not apply to (gltf-pbr has its own,
/// [`super::prefiltered_layers::estimate`]). Twin: `prefiltered_terms` in
/// shaders/environment.wgsl.
pub fn specular_terms(material: &Material) -> (f64, Rgb, Rgb) {
    // The F0 of a spectral metal is its spectral colour (`reference_brdf`).
    match reference_brdf(material).specular {
        BrdfSpecular::CookTorrance(ct) => (
            ggx_alpha(ct.d),
            ct.f.eval(1.0),
            material.brdf().k_s * (4.0 / ct.denominator),
        ),
        _ => (0.0, Rgb::ZERO, Rgb::ZERO),
    }
}

/// The split-sum estimate of `L_o` (diffuse by SH plus the prefiltered
/// specular), the f64 twin of the GPU's `environment_prefiltered`.
pub fn estimate(
    map: &EnvironmentMap,
    prefiltered: &Prefiltered,
    material: &Material,
    frame: &SurfaceFrame,
    wo: DVec3,
) -> Rgb {
    let n = frame.n;
    let diffuse = environment_diffuse_albedo(material) * FRAC_1_PI * map.irradiance_sh(n);
    let cos_o = n.dot(wo);
    if cos_o <= 0.0 {
        return diffuse;
    }
    if material.model == ReflectanceModel::GltfPbr {
        return super::prefiltered_layers::estimate(map, prefiltered, material, frame, wo);
    }
    let (alpha, f0, weight) = specular_terms(material);
    let [a, b] = dfg::table().lookup(cos_o, alpha);
    let r = dominant_direction(mirror_direction(wo, n), n, alpha);
    let l = prefiltered.lookup(map.to_map(r), alpha) * map.settings.scale;
    // Energy compensation (`brdf::energy`): the split's lobe times the
    // same factor, with the split's F0.
    let ms = if material.energy_compensation {
        crate::material::brdf::energy::ms_ratio(alpha, cos_o)
    } else {
        0.0
    };
    let compensation = crate::material::brdf::energy::ms_factor(f0, ms);
    diffuse + weight * (f0 * a + Rgb::splat(b)) * l * compensation
}
