//! Which `environment.specular` mode a scene lights its materials with
//! when the user has not chosen one (`"auto"`, the default): the contract
//! says that with a map the environment lights the whole BRDF of every
//! material by default, each renderer by its own method. The CPU
//! reference integrates the truth in every mode but `"none"`; the GPU
//! has one method per mode, each exact or a documented approximation for
//! some models only (`environment::mode_warnings`). So the scene takes
//! the cheapest mode that covers every model it draws:
//!
//! | models drawn                              | mode            |
//! |-------------------------------------------|-----------------|
//! | Lambert and mirror only                   | `"none"` (SH diffuse is their whole BRDF) |
//! | those, Cook-Torrance and gltf-pbr         | `"prefiltered"` (split sum) |
//! | those of the first row, the Phong lobes   | `"sh"` (zonal product) |
//! | anything else, or a mix of the above two  | `"sampled"` (every `f_r`) |
//!
//! A mode the user wrote (`environment.specular = "…"`) is kept as written.

use crate::environment::map::Specular;
use crate::material::ReflectanceModel;
use crate::scene::Scene;

/// The mode that lights the whole BRDF of every model in `models`.
pub fn whole_brdf_mode(models: impl IntoIterator<Item = ReflectanceModel>) -> Specular {
    use ReflectanceModel::*;
    let (mut split_sum, mut sh) = (false, false);
    for model in models {
        match model {
            Lambert | Mirror => {}
            CookTorrance | GltfPbr => split_sum = true,
            Phong | PhongNormalized | BlinnPhong | BlinnPhongNormalized => sh = true,
            _ => return Specular::Sampled,
        }
    }
    match (split_sum, sh) {
        (false, false) => Specular::None,
        (true, false) => Specular::Prefiltered,
        (false, true) => Specular::Sh,
        (true, true) => Specular::Sampled,
    }
}

/// Sets the map's mode of `scene` from the models its meshes draw, when
/// the mode is the scene's to choose (`MapSettings::specular_auto`).
/// Called when a scene is loaded and when the viewer changes a material.
pub fn choose(scene: &mut Scene) {
    let models: Vec<ReflectanceModel> = scene
        .meshes
        .iter()
        .filter_map(|m| scene.materials.get(m.material))
        .map(|m| m.model)
        .collect();
    if let Some(map) = scene.environment.map.as_mut()
        && map.settings.specular_auto
    {
        map.settings.specular = whole_brdf_mode(models);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ReflectanceModel::*;

    #[test]
    fn the_cheapest_mode_that_covers_every_model() {
        assert_eq!(whole_brdf_mode([]), Specular::None);
        assert_eq!(whole_brdf_mode([Lambert, Mirror]), Specular::None);
        assert_eq!(whole_brdf_mode([GltfPbr, Lambert]), Specular::Prefiltered);
        assert_eq!(whole_brdf_mode([CookTorrance]), Specular::Prefiltered);
        assert_eq!(whole_brdf_mode([PhongNormalized]), Specular::Sh);
        assert_eq!(whole_brdf_mode([Phong, GltfPbr]), Specular::Sampled);
        assert_eq!(whole_brdf_mode([Measured, Lambert]), Specular::Sampled);
        assert_eq!(whole_brdf_mode([OrenNayar]), Specular::Sampled);
    }

    /// Every mode the table picks handles every model it was picked for
    /// (no load-time warning of `mode_warnings` can follow from "auto").
    #[test]
    fn the_chosen_mode_never_warns() {
        for model in ReflectanceModel::ALL {
            let mode = whole_brdf_mode([model]);
            assert!(
                crate::scene::scene_file::mode_warnings::handles(mode, model),
                "{model:?} -> {mode:?}"
            );
        }
    }
}
