//! What each specular mode does not compute, said at load time: the
//! `"sh"` and `"prefiltered"` modes approximate the glossy lobes of some
//! models only (docs/environment.md); every other model a mesh uses gets
//! the SH diffuse term alone, which is not the model's `f_r`. Without a
//! word that would be silently wrong (a Cook-Torrance metal in the `"sh"`
//! mode is black; a measured table is black in both), so the loader adds
//! one warning per such material (`scene_file::WARNING`, printed without
//! `--verbose`). The `"none"` mode is the SH diffuse term of every model
//! by definition (its name says so) and `"sampled"` integrates every
//! `f_r`: no warning.

use crate::environment::map::Specular;
use crate::material::ReflectanceModel;
use crate::scene::Scene;

/// Whether `model`'s environment light is what the mode computes for it
/// (exactly or by a documented approximation).
pub fn handles(mode: Specular, model: ReflectanceModel) -> bool {
    use ReflectanceModel::*;
    match model {
        // No glossy lobe: the SH diffuse term is all of it; the mirror's
        // Dirac lobe reflects the map in every mode.
        Lambert | Mirror => true,
        _ => match mode {
            Specular::Sh => matches!(
                model,
                Phong | PhongNormalized | BlinnPhong | BlinnPhongNormalized
            ),
            Specular::Prefiltered => matches!(model, CookTorrance | GltfPbr),
            Specular::None | Specular::Sampled => true,
        },
    }
}

/// One warning per material that a mesh uses and the scene's specular
/// mode does not handle (module docs), without the `warning: ` prefix.
pub fn warnings(scene: &Scene) -> Vec<String> {
    let Some(map) = &scene.environment.map else {
        return Vec::new();
    };
    let mode = map.settings.specular;
    let mut used: Vec<usize> = scene.meshes.iter().map(|m| m.material).collect();
    used.sort_unstable();
    used.dedup();
    used.into_iter()
        .filter_map(|i| scene.materials.get(i))
        .filter(|m| !handles(mode, m.model))
        .map(|m| {
            let what = match m.model {
                ReflectanceModel::Measured => "a measured table has no separate diffuse term, so it is black",
                ReflectanceModel::OrenNayar | ReflectanceModel::OrenNayarFull => {
                    "its diffuse term is taken as Lambert's (k_d/π times the SH irradiance)"
                }
                _ => "its glossy lobe is left out (the SH diffuse term alone)",
            };
            let instead = match mode {
                Specular::Sh => "\"sh\" convolves the Phong and Blinn-Phong lobes only; \"prefiltered\" does Cook-Torrance and gltf-pbr, \"sampled\" every model",
                _ => "\"prefiltered\" does Cook-Torrance and gltf-pbr only; \"sh\" does the Phong and Blinn-Phong lobes, \"sampled\" every model",
            };
            format!(
                "material `{}` (model `{}`) under environment.specular = \"{}\": {what}; {instead}",
                m.name,
                m.model.name(),
                mode.name(),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every model is either handled or warned about in each glossy mode,
    /// and the lobes each mode claims are handled.
    #[test]
    fn each_mode_names_what_it_handles() {
        for model in ReflectanceModel::ALL {
            assert!(handles(Specular::Sampled, model), "{model:?}");
            assert!(handles(Specular::None, model), "{model:?}");
        }
        assert!(handles(
            Specular::Sh,
            ReflectanceModel::BlinnPhongNormalized
        ));
        assert!(!handles(Specular::Sh, ReflectanceModel::CookTorrance));
        assert!(!handles(Specular::Sh, ReflectanceModel::Measured));
        assert!(!handles(Specular::Prefiltered, ReflectanceModel::Phong));
        assert!(handles(Specular::Prefiltered, ReflectanceModel::GltfPbr));
    }
}
