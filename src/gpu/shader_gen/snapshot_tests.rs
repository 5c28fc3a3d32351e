//! Snapshot tests: three generated modules stored as `.wgsl` files in
//! `src/gpu/shader_gen/snapshots/`, compared exactly, so that a review
//! diff shows what a change does to a scene's shader. After an intended
//! change, rewrite them with `GONIO_UPDATE_SNAPSHOTS=1 cargo test --lib
//! snapshot` and commit the diff.

use super::*;
use crate::material::{Denominator, Material, ReflectanceModel};

/// Compares `wgsl` with `snapshots/NAME.wgsl` (or rewrites it when
/// `GONIO_UPDATE_SNAPSHOTS` is set).
fn check_snapshot(name: &str, wgsl: &str) {
    validate(wgsl).unwrap_or_else(|e| panic!("snapshot {name} does not validate: {e}"));
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src/gpu/shader_gen/snapshots")
        .join(format!("{name}.wgsl"));
    if std::env::var_os("GONIO_UPDATE_SNAPSHOTS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, wgsl).unwrap();
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_default();
    if stored != wgsl {
        let line = stored
            .lines()
            .zip(wgsl.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(stored.lines().count().min(wgsl.lines().count()))
            + 1;
        panic!(
            "the generated module `{name}` differs from {} (first at line {line}).\n\
             If the change is intended, rewrite the snapshots with\n    \
             GONIO_UPDATE_SNAPSHOTS=1 cargo test --release --lib snapshot\n\
             and commit them: the diff shows what the change does to the shader.",
            path.display()
        );
    }
}

#[test]
fn snapshot_lambert_point_light() {
    let key = ShaderKey {
        shading: ShadingMode::Phong,
        variants: [Material::new("m", ReflectanceModel::Lambert).variant()].into(),
        light_kinds: [LightKind::Point].into(),
        counts: LoopCounts {
            lights: 1,
            ..Default::default()
        },
        arrays: UniformArrays::for_counts(1, 0),
        vertex_shadow_coords: true,
        ..Default::default()
    };
    check_snapshot("lambert_point", &compose(&key));
}

#[test]
fn snapshot_cook_torrance_shadowed_sun_pcf() {
    let ct = Material {
        distribution: Distribution::Ggx,
        fresnel: Fresnel::Schlick,
        denominator: Denominator::Microfacet,
        ..Material::new("m", ReflectanceModel::CookTorrance)
    };
    let key = ShaderKey {
        shading: ShadingMode::Phong,
        variants: [ct.variant()].into(),
        light_kinds: [LightKind::Directional].into(),
        shadows: ShadowFeatures {
            projections: [Projection::Ortho].into(),
            pcf: true,
        },
        counts: LoopCounts {
            lights: 1,
            shadow_maps: 1,
            pcf_radius: Some(1),
        },
        arrays: UniformArrays::for_counts(1, 1),
        light_range: false,
        light_guard: false,
        vertex_shadow_coords: true,
        approximate_shadow_coords: false,
        environment: false,
        environment_sampled: false,
        environment_prefiltered: false,
        environment_sh: false,
        texture_slots: 0,
        normal_maps: false,
        two_sided: false,
        culling: false,
        vertex_colors: false,
        alpha: false,
        alpha_blend: false,
        measured_network: false,
        energy_compensation: false,
        smith_beckmann_rational: false,
        emission: false,
        occlusion: false,
        tone_map: Default::default(),
    };
    check_snapshot("cook_torrance_sun_pcf", &compose(&key));
}

#[test]
fn snapshot_everything() {
    let key = ShaderKey {
        shading: ShadingMode::Phong,
        variants: all_variants().into_iter().collect(),
        light_kinds: LightKind::ALL.into(),
        shadows: ShadowFeatures {
            projections: [Projection::Ortho, Projection::Perspective, Projection::Cube].into(),
            pcf: true,
        },
        counts: LoopCounts {
            lights: 5,
            shadow_maps: 3,
            pcf_radius: None,
        },
        arrays: UniformArrays::for_counts(5, 8),
        light_range: true,
        light_guard: true,
        vertex_shadow_coords: true,
        approximate_shadow_coords: false,
        environment: true,
        environment_sampled: true,
        environment_prefiltered: true,
        environment_sh: true,
        texture_slots: 0,
        normal_maps: false,
        two_sided: false,
        culling: false,
        vertex_colors: false,
        alpha: true,
        alpha_blend: false,
        measured_network: false,
        energy_compensation: true,
        smith_beckmann_rational: false,
        emission: true,
        occlusion: true,
        tone_map: Default::default(),
    };
    check_snapshot("everything", &compose(&key));
}
