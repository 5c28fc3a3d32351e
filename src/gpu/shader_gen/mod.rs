//! Scene-specialized WGSL: only what a scene uses is compiled.
//!
//! A [`ShaderKey`] lists the features a scene needs: shading mode, BRDF
//! variants (a model with its chosen terms), and groups for the lights,
//! the shadow maps, the environment and the materials
//! (`key_groups`), each flag declared once with the [`Feature`] it
//! switches. [`compose`] concatenates the WGSL files
//! ([`sources`]) for exactly those features, keeps only the conditional
//! blocks (`#if FEATURE` ... `#endif`, [`preprocess`]) whose [`Feature`] is
//! on, and writes the few constants that specialize it: loop counts, the
//! codes of models and terms, and which variant the module draws
//! ([`specialization`]). The BRDF dispatch itself (`eval_brdf`, the
//! Cook-Torrance terms, the mirror) is WGSL, `switch`es on pipeline
//! constants in shaders/brdf/eval.wgsl, with one arm per model the scene
//! uses; the light dispatch (`light_incidence`) likewise switches on the
//! light kinds' codes in shaders/lights/incidence.wgsl, one arm per kind
//! present. A Lambert-only scene with a point light therefore contains no
//! glossy lobe, no Fresnel, no spot-light code. Parameter values live in
//! buffers, so changing them never rebuilds a pipeline; changing the key
//! does.

mod compose;
mod features;
mod key;
mod key_groups;
mod preprocess;
pub mod sources;
pub mod specialization;

pub use compose::{
    Output, common, compose, compose_background, compose_brdf_library, compose_for, validate,
};
pub use features::Feature;
pub use key::{LoopCounts, ShaderKey};
pub use key_groups::{EnvironmentKey, LightsKey, MaterialsKey, ShadowKey};
pub use preprocess::preprocess;
pub use specialization::pipeline_constants;

use crate::gpu::bindings::UniformArrays;
use crate::gpu::shadows::{Projection, ShadowFeatures};
use crate::material::{BrdfVariant, Distribution, Fresnel, Geometry};
use crate::scene::{LightKind, ShadingMode};

/// Every BRDF variant gonio can compile: each model with every
/// combination of the terms its row in the table of models selects.
pub fn all_variants() -> Vec<BrdfVariant> {
    use crate::material::Denominator;
    fn each<T: Copy>(applies: bool, all: &[T]) -> Vec<Option<T>> {
        if applies {
            all.iter().copied().map(Some).collect()
        } else {
            vec![None]
        }
    }
    let mut out = Vec::new();
    for row in crate::material::table::ROWS {
        let terms = row.terms;
        for &distribution in &each(terms.distribution, &Distribution::ALL) {
            for &geometry in &each(terms.geometry, &Geometry::ALL) {
                for &fresnel in &each(terms.fresnel, &Fresnel::ALL) {
                    for &denominator in &each(terms.denominator, &Denominator::ALL) {
                        out.push(BrdfVariant {
                            model: row.model,
                            distribution,
                            geometry,
                            fresnel,
                            denominator,
                        });
                    }
                }
            }
        }
    }
    out
}

/// Keys that together compile every line of every WGSL file: each shading
/// mode with each variant alone (one light kind each, cycling), each
/// shadow projection alone with and without PCF, plus all variants, all
/// light kinds and all shadow code at once, with every flag of every
/// key group off and on. Used by the shader validation test.
pub fn representative_keys() -> Vec<ShaderKey> {
    let all_kinds = LightKind::ALL;
    let all_projections = [Projection::Ortho, Projection::Perspective, Projection::Cube];
    let variants = all_variants();
    // Uniform or storage buffers for every array, alternating.
    let arrays = |uniform: bool| UniformArrays {
        lights: uniform,
        shadow_views: uniform,
        measured: false,
        sheen: false,
    };
    let mut keys = Vec::new();
    for shading in ShadingMode::ALL {
        for (i, v) in variants.iter().enumerate() {
            keys.push(ShaderKey {
                shading,
                variants: [*v].into(),
                lights: LightsKey {
                    kinds: [all_kinds[i % all_kinds.len()]].into(),
                    // The inverse-square law with and without its guard and
                    // range window, on alternate keys.
                    range: i % 2 == 0,
                    guard: i % 4 < 2,
                },
                counts: LoopCounts {
                    lights: 1,
                    ..Default::default()
                },
                arrays: arrays(i % 2 == 0),
                environment: EnvironmentKey {
                    map: i % 3 == 0 || i % 6 == 5,
                    sampled: i % 6 == 0,
                    prefiltered: i % 6 == 3,
                    sh: i % 6 == 5,
                },
                materials: MaterialsKey {
                    // The network arm of measured.wgsl in Phong keys, the
                    // table's in the others.
                    measured_network: shading == ShadingMode::Phong
                        && v.model == crate::material::ReflectanceModel::Measured,
                    energy_compensation: i % 2 == 1,
                    // Both G1 forms, on alternate keys.
                    smith_beckmann_rational: i % 2 == 0,
                    // Emission and occlusion on alternate keys.
                    emission: i % 2 == 1,
                    occlusion: i % 3 == 0,
                    ..Default::default()
                },
                tone_map: crate::output::tone_map::ToneMap::ALL
                    [i % crate::output::tone_map::ToneMap::ALL.len()],
                ..Default::default()
            });
        }
        for (i, projection) in all_projections.into_iter().enumerate() {
            for pcf in [false, true] {
                keys.push(ShaderKey {
                    shading,
                    variants: [variants[i]].into(),
                    lights: LightsKey {
                        kinds: [all_kinds[i]].into(),
                        range: pcf,
                        guard: !pcf,
                    },
                    shadows: ShadowKey {
                        maps: ShadowFeatures {
                            projections: [projection].into(),
                            pcf,
                        },
                        // Orthographic or perspective with PCF: the
                        // coordinates per vertex (perspective approximately).
                        vertex_coords: pcf,
                        approximate_coords: pcf,
                    },
                    counts: LoopCounts {
                        lights: 2,
                        shadow_maps: 1,
                        pcf_radius: (i % 2 == 0).then_some(1),
                    },
                    arrays: arrays(pcf),
                    environment: EnvironmentKey {
                        map: pcf,
                        ..Default::default()
                    },
                    materials: MaterialsKey {
                        smith_beckmann_rational: pcf,
                        emission: pcf,
                        occlusion: !pcf,
                        ..Default::default()
                    },
                    ..Default::default()
                });
            }
        }
        // Every light kind, every shadow projection and, on one key, every
        // flag of every group: each `#if` block compiled at least once.
        for uniform in [false, true] {
            keys.push(ShaderKey {
                shading,
                variants: variants.iter().copied().collect(),
                lights: LightsKey {
                    kinds: all_kinds.into(),
                    ..Default::default()
                }
                .with_flags(uniform),
                shadows: ShadowKey {
                    maps: ShadowFeatures {
                        projections: all_projections.into(),
                        pcf: true,
                    },
                    ..Default::default()
                },
                counts: LoopCounts {
                    lights: 5,
                    shadow_maps: 3,
                    pcf_radius: None,
                },
                arrays: arrays(uniform),
                environment: EnvironmentKey {
                    map: uniform,
                    sampled: uniform,
                    ..Default::default()
                },
                materials: MaterialsKey {
                    // Textures with the uber shader: all slots, all models.
                    texture_slots: if uniform {
                        crate::gpu::textures::MAX_TEXTURE_SLOTS as u32
                    } else {
                        0
                    },
                    texture_bindings: if uniform {
                        crate::gpu::textures::MAX_TEXTURE_SLOTS as u32
                    } else {
                        0
                    },
                    normal_maps: uniform,
                    alpha_blend: uniform,
                    ..Default::default()
                }
                .with_flags(uniform),
                ..Default::default()
            });
        }
    }
    for k in &mut keys {
        k.arrays.measured = k.has_measured();
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, ReflectanceModel};

    #[test]
    fn lambert_only_scene_has_no_glossy_or_spot_code() {
        let key = ShaderKey {
            shading: ShadingMode::Phong,
            variants: [Material::new("m", ReflectanceModel::Lambert).variant()].into(),
            lights: LightsKey {
                kinds: [LightKind::Point].into(),
                ..Default::default()
            },
            ..Default::default()
        };
        let wgsl = compose(&key);
        for absent in [
            "blinn_phong_lecture",
            "fresnel_",
            "d_beckmann",
            "spot_attenuation",
            "switch m.variant",
            "switch light.kind",
            "environment_radiance",
            "tangent: vec3",
            "shadow_visibility",
            "shadow_maps",
            "textureSampleCompare",
            "area_sample",
            "dpdx",
            "unlit_radiance",
        ] {
            assert!(
                !wgsl.contains(absent),
                "`{absent}` compiled into a Lambert-only shader"
            );
        }
        validate(&wgsl).unwrap();
    }

    /// gltf-pbr's layers are compiled one by one, only where a drawn
    /// material uses them: a plain gltf-pbr scene has none of their code
    /// (its module is the one it had before the layers existed), a coat
    /// brings the coat alone, and the sheen its table's binding.
    #[test]
    fn gltf_layers_only_where_a_material_uses_them() {
        use crate::scene::scene_file::{self, SceneSource};
        let key_for = |sets: &[&str]| {
            let mut all = vec!["materials.ball.model=gltf-pbr".to_string()];
            all.extend(sets.iter().map(|s| format!("materials.ball.{s}")));
            let scene = scene_file::load(&SceneSource::BuiltIn, &all).unwrap();
            ShaderKey::new(&scene, &crate::gpu::shadows::ShadowPlan::new(&scene))
        };
        let layer_code = [
            ("layers", "fn gltf_layered"),
            ("layers", "layers: GltfLayers"),
            ("ior_specular", "fn gltf_base"),
            ("clearcoat", "fn clearcoat_over"),
            ("sheen", "fn sheen_over"),
            ("sheen", "sheen_albedo_table"),
            ("iridescence", "fn iridescence_fresnel"),
            ("anisotropy", "fn d_ggx_anisotropic"),
            ("anisotropy", "tangent: vec3"),
        ];
        let plain = compose(&key_for(&[]));
        for (_, code) in layer_code {
            assert!(!plain.contains(code), "`{code}` in a plain gltf-pbr shader");
        }
        validate(&plain).unwrap();
        let cases: [(&[&str], &[&str]); 5] = [
            (&["clearcoat=1"], &["layers", "clearcoat"]),
            (&["sheen_color=[0.5, 0.5, 0.5]"], &["layers", "sheen"]),
            (&["ior=1.7"], &["layers", "ior_specular"]),
            (
                &["iridescence=1"],
                &["layers", "ior_specular", "iridescence"],
            ),
            (
                &["anisotropy_strength=0.5"],
                &["layers", "ior_specular", "anisotropy"],
            ),
        ];
        for (sets, present) in cases {
            let key = key_for(sets);
            let wgsl = compose(&key);
            for (layer, code) in layer_code {
                // The base's file serves ior/specular, iridescence and
                // anisotropy alike.
                assert_eq!(
                    wgsl.contains(code),
                    present.contains(&layer),
                    "{sets:?}: `{code}`"
                );
            }
            assert_eq!(key.arrays.sheen, present.contains(&"sheen"), "{sets:?}");
            validate(&wgsl).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
        }
    }

    /// The built-in scene's key with the ball a `gltf-pbr` material and
    /// `sets` applied.
    fn gltf_ball_key(sets: &[&str]) -> ShaderKey {
        use crate::scene::scene_file::{self, SceneSource};
        let mut all = vec!["materials.ball.model=gltf-pbr".to_string()];
        all.extend(sets.iter().map(|s| s.to_string()));
        let scene = scene_file::load(&SceneSource::BuiltIn, &all).unwrap();
        ShaderKey::new(&scene, &crate::gpu::shadows::ShadowPlan::new(&scene))
    }

    /// The transmission pass's code (its file, group 4, the diffuse
    /// part's share) only where a drawn gltf-pbr material transmits and
    /// `shading.transmission` is "screen".
    #[test]
    fn transmission_only_where_a_material_transmits_and_the_mode_draws_it() {
        let key_for = gltf_ball_key;
        let code = [
            "fn transmitted_radiance",
            "@group(4)",
            "fn reflected_diffuse_weight",
            "transmitted_radiance(m, x, frame, wo)",
        ];
        let cases: [(&[&str], bool); 5] = [
            (&[], false),
            (&["materials.ball.thickness=1"], false),
            (&["materials.ball.transmission=1"], true),
            (
                &["materials.ball.transmission=1", "shading.transmission=off"],
                false,
            ),
            (
                &["materials.ball.transmission=0.5", "shading.mode=gouraud"],
                true,
            ),
        ];
        for (sets, present) in cases {
            let key = key_for(sets);
            assert_eq!(key.materials.layer_transmission, present, "{sets:?}");
            let wgsl = compose(&key);
            for c in code {
                assert_eq!(wgsl.contains(c), present, "{sets:?}: `{c}`");
            }
            validate(&wgsl).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
        }
    }

    /// Diffuse transmission's code (its file, the far-side light and
    /// environment terms) and dispersion's
    /// three reads only where a drawn gltf-pbr material uses them and
    /// `shading.transmission` draws light through surfaces; every case
    /// validates, the Gouraud one (shaded in the vertex stage) too.
    #[test]
    fn diffuse_transmission_and_dispersion_only_where_used() {
        let key_for = gltf_ball_key;
        // (`reflected_diffuse_weight` serves the specular transmission
        // too: the test above.)
        let diffuse_code = [
            "fn diffuse_transmitted",
            "diffuse_transmitted(m, n, incidence.wi, wo)",
        ];
        let dispersion_code = "fn seen_through_dispersed";
        let cases: [(&[&str], bool, bool); 6] = [
            (&[], false, false),
            (&["materials.ball.diffuse_transmission=0.5"], true, false),
            (
                &[
                    "materials.ball.diffuse_transmission=0.5",
                    "shading.transmission=off",
                ],
                false,
                false,
            ),
            (
                &[
                    "materials.ball.diffuse_transmission=0.5",
                    "shading.mode=gouraud",
                    "environment.map=sky",
                ],
                true,
                false,
            ),
            (&["materials.ball.dispersion=1"], false, false),
            (
                &[
                    "materials.ball.dispersion=1",
                    "materials.ball.transmission=1",
                    "materials.ball.thickness=1",
                ],
                false,
                true,
            ),
        ];
        for (sets, diffuse, dispersion) in cases {
            let key = key_for(sets);
            assert_eq!(
                key.materials.layer_diffuse_transmission, diffuse,
                "{sets:?}"
            );
            assert_eq!(
                key.materials.transmission_dispersion, dispersion,
                "{sets:?}"
            );
            let wgsl = compose(&key);
            for c in diffuse_code {
                assert_eq!(wgsl.contains(c), diffuse, "{sets:?}: `{c}`");
            }
            assert_eq!(wgsl.contains(dispersion_code), dispersion, "{sets:?}");
            validate(&wgsl).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
        }
    }

    /// The traced exit's code (its file, group 4's bindings 2 and 3, the
    /// call in `seen_through`) only with `shading.transmission_exit_ray =
    /// "traced"` and a drawn transmissive volume; every case validates,
    /// the Gouraud one (shaded in the vertex stage) and a dispersive one
    /// (three traced reads) too.
    #[test]
    fn the_traced_exit_only_where_asked_for_a_volume() {
        let key_for = gltf_ball_key;
        let code = [
            "fn seen_through_traced",
            "@group(4) @binding(3)",
            "seen_through_traced(m, x, n, wo, ior)",
        ];
        let traced = "shading.transmission_exit_ray=\"traced\"";
        let volume = [
            "materials.ball.transmission=1",
            "materials.ball.thickness=1",
        ];
        let cases: [(Vec<&str>, bool); 6] = [
            (volume.to_vec(), false),
            (vec!["materials.ball.transmission=1", traced], false),
            ([&volume[..], &[traced]].concat(), true),
            (
                [&volume[..], &[traced, "shading.transmission=off"]].concat(),
                false,
            ),
            (
                [&volume[..], &[traced, "shading.mode=gouraud"]].concat(),
                true,
            ),
            (
                [&volume[..], &[traced, "materials.ball.dispersion=1"]].concat(),
                true,
            ),
        ];
        for (sets, present) in cases {
            let key = key_for(&sets);
            assert_eq!(key.materials.transmission_exit_traced, present, "{sets:?}");
            let wgsl = compose(&key);
            for c in code {
                assert_eq!(wgsl.contains(c), present, "{sets:?}: `{c}`");
            }
            validate(&wgsl).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
        }
    }

    /// The unlit model's code (its file, its arm, its radiance in the
    /// reflection equation) only where a drawn material is unlit.
    #[test]
    fn unlit_only_where_a_material_uses_it() {
        use crate::scene::scene_file::{self, SceneSource};
        let key_for = |sets: &[&str]| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let scene = scene_file::load(&SceneSource::BuiltIn, &sets).unwrap();
            ShaderKey::new(&scene, &crate::gpu::shadows::ShadowPlan::new(&scene))
        };
        let code = [
            "fn unlit_radiance",
            "case MODEL_UNLIT",
            "unlit_radiance(m.base_color)",
        ];
        let plain = compose(&key_for(&[]));
        for c in code {
            assert!(!plain.contains(c), "`{c}` in a shader without unlit");
        }
        let unlit = compose(&key_for(&["materials.ball.model=unlit"]));
        for c in code {
            assert!(unlit.contains(c), "`{c}` missing from an unlit shader");
        }
        validate(&unlit).unwrap();
    }

    #[test]
    fn shadow_code_only_for_the_projections_in_use() {
        let key = |projections: &[Projection], pcf| ShaderKey {
            shading: ShadingMode::Phong,
            variants: [Material::new("m", ReflectanceModel::Lambert).variant()].into(),
            lights: LightsKey {
                kinds: [LightKind::Point].into(),
                ..Default::default()
            },
            shadows: ShadowKey {
                maps: ShadowFeatures {
                    projections: projections.iter().copied().collect(),
                    pcf,
                },
                ..Default::default()
            },
            ..Default::default()
        };
        let cube = compose(&key(&[Projection::Cube], false));
        for present in [
            "fn shadow_visibility",
            "fn shadow_cube",
            "textureSampleCompareLevel",
            "dpdx",
        ] {
            assert!(cube.contains(present), "`{present}` missing");
        }
        for absent in [
            "fn shadow_ortho",
            "fn shadow_perspective",
            "for (var i = -r",
        ] {
            assert!(
                !cube.contains(absent),
                "`{absent}` compiled without its feature"
            );
        }
        validate(&cube).unwrap();
        let ortho = compose(&key(&[Projection::Ortho], true));
        assert!(ortho.contains("fn shadow_ortho") && ortho.contains("for (var i = -r"));
        assert!(!ortho.contains("fn shadow_cube") && !ortho.contains("fn shadow_perspective"));
        validate(&ortho).unwrap();
    }

    #[test]
    fn the_background_validates() {
        for output in [Output::Radiance, Output::RadianceBits, Output::Display] {
            for t in crate::output::tone_map::ToneMap::ALL {
                validate(&compose_background(output, t)).unwrap();
            }
        }
    }

    #[test]
    fn every_representative_key_validates() {
        let keys = representative_keys();
        assert!(keys.len() > 3 * 180);
        for key in keys {
            if let Err(e) = validate(&compose_for(&key, Output::Display)) {
                panic!("display output of {}: {e}", key.describe());
            }
            if let Err(e) = validate(&compose_for(&key, Output::RadianceBits)) {
                panic!("radiance-bits output of {}: {e}", key.describe());
            }
            if let Err(e) = validate(&compose(&key)) {
                panic!("{}:\n{e}", key.describe());
            }
        }
    }
}

#[cfg(test)]
mod snapshot_tests;
