//! The `"sh"` mode's estimate (`environment.specular = "sh"`): the SH
//! diffuse term plus, for the lecture's Phong lobes, the lobe convolved
//! with the map's radiance in spherical harmonics
//! (`crate::environment::sh_phong`, Ramamoorthi & Hanrahan 2002, whose
//! module documentation derives the lobes and their approximations).
//!
//! WGSL twin: `environment_sh` in shaders/environment_sh.wgsl.

use super::diffuse::environment_diffuse_albedo;
use crate::base::{Rgb, SurfaceFrame};
use crate::environment::EnvironmentMap;
use crate::environment::sh_phong::{Lobe, glossy};
use crate::material::Material;
use crate::material::brdf::Specular as BrdfSpecular;
use crate::material::brdf::phong::mirror_direction;
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// The lobe of `material` (`None`: the SH diffuse term alone); the
/// lecture's Blinn-Phong as the mirror lobe of exponent `n/4`, the
/// normalized one as normalized Phong of exponent `n/4` (module docs).
pub fn lobe(material: &Material) -> Option<Lobe> {
    match material.brdf().specular {
        BrdfSpecular::Phong { k_e } => Some(Lobe::Lecture { k_e }),
        BrdfSpecular::BlinnPhong { k_e } => Some(Lobe::Lecture { k_e: 0.25 * k_e }),
        BrdfSpecular::PhongNormalized { k_e } => Some(Lobe::Normalized { k_e }),
        BrdfSpecular::BlinnPhongNormalized { k_e } => Some(Lobe::Normalized { k_e: 0.25 * k_e }),
        _ => None,
    }
}

/// `L_o` of the environment in the `"sh"` mode: the SH diffuse term plus,
/// for the Phong models, `k_s` times the convolved lobe read at the
/// mirror direction of `wo`. The f64 twin of the GPU's `environment_sh`.
pub fn estimate(map: &EnvironmentMap, material: &Material, frame: &SurfaceFrame, wo: DVec3) -> Rgb {
    let n = frame.n;
    let diffuse = environment_diffuse_albedo(material) * FRAC_1_PI * map.irradiance_sh(n);
    let Some(lobe) = lobe(material) else {
        return diffuse;
    };
    if n.dot(wo) <= 0.0 {
        return diffuse;
    }
    let r = mirror_direction(wo, n);
    let c = map.radiance_coefficients();
    diffuse + material.brdf().k_s * glossy(map, &c, lobe, r, n)
}
