//! The reflection equation for punctual lights, summed (contract):
//! `L_o = L_e + k_a·L_a + Σ_l f_r(ω_l, ω_o) · E_l · cosθ_l · V_l`
//! (`L_e` the material's emission, the contract's extension),
//! (an unlit material: `L_e + k_a·L_a·o + b` alone, `brdf::unlit`),
//! plus, for the ideal mirror, `ρ_s(θ_o) · L_env(R(V))` (lecture: "Mirror
//! BRDF": `L_o = ρ_s(θ_o) L_i(θ_o, φ_o ± π)`),
//! plus, with an environment map, the diffuse term of every model lit by
//! it, `k_d/π · E(n)` (Ramamoorthi & Hanrahan 2001): `E` by SH on the GPU,
//! integrated (or by the same SH, `environment.reference = "sh"`) here.
//!
//! The material's ambient occlusion `o` (`Material::occlusion`, glTF's
//! `occlusionTexture`) multiplies the ambient term and every term of the
//! environment (its diffuse and specular parts, the mirror's reflection),
//! never a direct light: glTF 2.0 leaves where it applies to the
//! implementation, and the Khronos sample viewer applies it "to all
//! lighting that is not punctual" (its image-based diffuse and specular
//! terms, `1 + strength·(ao − 1)`), as here.
//!
//! This is the CPU twin of `reflected_radiance` in `shaders/shading.wgsl`.

use super::environment::diffuse::environment_diffuse_albedo;
use crate::material::brdf::{self, SurfaceFrame, phong::mirror_direction};
use crate::material::{Material, ReflectanceModel};
use crate::scene::{Rgb, Scene};
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// Reflected radiance at `x` with shading frame `frame`, seen from `eye`.
/// `material` is an effective material (`Scene::effective_materials`).
/// `visibility(l, x)` is `V_l` in [0, 1] for light index `l`;
/// `environment_visible(ω)` whether the map is seen from `x` towards `ω`
/// (used only with `environment.visibility` and the integrated reference:
/// [`crate::environment::visibility`]).
pub fn reflected_radiance(
    scene: &Scene,
    material: &Material,
    x: DVec3,
    frame: &SurfaceFrame,
    eye: DVec3,
    visibility: impl Fn(usize, DVec3) -> f64,
    environment_visible: impl Fn(DVec3) -> bool,
) -> Rgb {
    let wo = (eye - x).normalize_or_zero();
    // A glTF material's normal turned toward the viewer where it faces
    // away (`SurfaceFrame::facing`); every term below reads this frame.
    let facing;
    let frame = if material.facing_normals {
        facing = frame.facing(wo);
        &facing
    } else {
        frame
    };
    let n = frame.n;
    let occlusion = material.occlusion;
    let mut radiance = material.emission + material.k_a * scene.ambient * occlusion;
    if material.model == ReflectanceModel::Unlit {
        // Its own terms and its base colour; no light, no environment.
        return radiance + brdf::unlit::unlit_radiance(material.base_color);
    }
    // Built once for every light and direction below (a spectral metal's
    // Fresnel from its table: `super::brdf`).
    let f = super::brdf::reference_brdf(material);
    for (l, light) in scene.lights.iter().enumerate() {
        let incidence = light.incidence(x);
        let cos_theta_i = n.dot(incidence.wi);
        if cos_theta_i <= 0.0 {
            continue;
        }
        let v = visibility(l, x);
        if v <= 0.0 {
            continue;
        }
        radiance += f.f_r(incidence.wi, wo, frame) * incidence.irradiance * (cos_theta_i * v);
    }
    if let Some(map) = &scene.environment.map {
        use super::environment::sampled;
        use crate::environment::map::{ReferenceDiffuse, Specular};
        let mut environment = match (map.settings.specular, map.settings.reference) {
            (Specular::None, _) => {
                environment_diffuse_albedo(material) * FRAC_1_PI * map.irradiance_reference(n)
            }
            (Specular::Sampled, ReferenceDiffuse::Sh) => {
                sampled::estimate(map, material, frame, wo)
            }
            (Specular::Prefiltered, ReferenceDiffuse::Sh) => {
                super::environment::prefiltered::estimate(
                    map,
                    &map.prefiltered(),
                    material,
                    frame,
                    wo,
                )
            }
            (Specular::Sh, ReferenceDiffuse::Sh) => {
                super::environment::sh_phong::estimate(map, material, frame, wo)
            }
            (
                Specular::Sampled | Specular::Prefiltered | Specular::Sh,
                ReferenceDiffuse::Integrated,
            ) => sampled::integrated(map, &map.data.nodes, material, frame, wo),
        };
        // The truth's visibility switch: what the geometry blocks, off the
        // same quadrature (the SH-diffuse mode's diffuse term, the other
        // modes' whole BRDF).
        if map.settings.visibility && map.settings.reference == ReferenceDiffuse::Integrated {
            let diffuse = environment_diffuse_albedo(material) * FRAC_1_PI;
            let whole = map.settings.specular != Specular::None;
            environment -= crate::environment::visibility::occluded(
                map,
                &map.data.nodes,
                frame,
                |wi| {
                    if whole { f.f_r(wi, wo, frame) } else { diffuse }
                },
                &environment_visible,
            );
        }
        radiance += environment * occlusion;
    }
    if material.model == ReflectanceModel::Mirror {
        let reflected = mirror_direction(wo, n);
        radiance += super::brdf::mirror_reflectance(material, n.dot(wo))
            * scene.environment.radiance(reflected)
            * occlusion;
    }
    radiance
}
