//! The BRDF the reference evaluates for a material: the material's own
//! ([`Material::brdf`]), except that a spectral metal's Fresnel term
//! (scene-file key `spectral_metal`) is the metal's CIE-integrated
//! spectral Fresnel ([`super::spectral::fresnel_tables`]) in place of its
//! three-channel preset's, which the GPU renders. The reference is where
//! the spectral truth lives; the material only names the metal.
//!
//! Every place the reference evaluates `f_r`, the mirror's reflectance or
//! the split sum's `F0` goes through here.

use super::spectral::fresnel_tables;
use crate::base::Rgb;
use crate::material::Material;
use crate::material::brdf::{Brdf, FresnelTerm, Specular};

/// `material`'s BRDF as the reference evaluates it (module doc).
pub fn reference_brdf(material: &Material) -> Brdf {
    let mut brdf = material.brdf();
    let Some(metal) = material.spectral_metal else {
        return brdf;
    };
    let spectral = |f: FresnelTerm| match f {
        FresnelTerm::Conductor { eta, kappa } => FresnelTerm::Tabulated {
            eta,
            kappa,
            table: fresnel_tables::table(metal),
        },
        other => other,
    };
    match &mut brdf.specular {
        Specular::CookTorrance(ct) => ct.f = spectral(ct.f),
        Specular::Mirror(f) => *f = spectral(*f),
        _ => {}
    }
    brdf
}

/// The ideal mirror's reflectance `ρ_s(θ) = k_s · F(cos θ)` as the
/// reference evaluates it: `crate::material::brdf::mirror_reflectance`
/// with [`reference_brdf`]'s Fresnel.
pub fn mirror_reflectance(material: &Material, cos_theta: f64) -> Rgb {
    if cos_theta <= 0.0 {
        return Rgb::ZERO;
    }
    match reference_brdf(material) {
        Brdf {
            k_s,
            specular: Specular::Mirror(f),
            ..
        } => k_s * f.eval(cos_theta),
        _ => Rgb::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;
    use crate::material::conductors::Metal;
    use crate::material::spectral_metal;
    use crate::reference::spectral::conductors::spectral_conductor_rgb;
    use crate::reference::spectral::metals;

    /// A spectral gold's Fresnel is the spectral table's in Cook-Torrance
    /// and the mirror; without the key the material's own is untouched.
    #[test]
    fn a_spectral_metal_takes_the_spectral_fresnel() {
        for model in [ReflectanceModel::CookTorrance, ReflectanceModel::Mirror] {
            let mut m = Material::new("m", model);
            let plain = reference_brdf(&m);
            assert_eq!(plain, m.brdf());
            spectral_metal::set(&mut m, Metal::Gold);
            let f = match reference_brdf(&m).specular {
                Specular::CookTorrance(ct) => ct.f,
                Specular::Mirror(f) => f,
                s => panic!("{s:?}"),
            };
            assert!(matches!(f, FresnelTerm::Tabulated { .. }));
            assert_eq!(
                f.eval(1.0),
                spectral_conductor_rgb(metals::of(Metal::Gold), 1.0)
            );
        }
        let mut mirror = Material::new("m", ReflectanceModel::Mirror);
        spectral_metal::set(&mut mirror, Metal::Copper);
        let want = mirror.k_s * spectral_conductor_rgb(metals::of(Metal::Copper), 1.0);
        assert_eq!(mirror_reflectance(&mirror, 1.0), want);
    }
}
