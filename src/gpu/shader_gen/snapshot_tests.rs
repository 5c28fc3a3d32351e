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
        lights: LightsKey {
            kinds: [LightKind::Point].into(),
            ..Default::default()
        },
        shadows: ShadowKey {
            vertex_coords: true,
            ..Default::default()
        },
        counts: LoopCounts {
            lights: 1,
            ..Default::default()
        },
        arrays: UniformArrays::for_counts(1, 0),
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
        lights: LightsKey {
            kinds: [LightKind::Directional].into(),
            ..Default::default()
        },
        shadows: ShadowKey {
            maps: ShadowFeatures {
                projections: [Projection::Ortho].into(),
                pcf: true,
            },
            vertex_coords: true,
            approximate_coords: false,
        },
        counts: LoopCounts {
            lights: 1,
            shadow_maps: 1,
            pcf_radius: Some(1),
        },
        arrays: UniformArrays::for_counts(1, 1),
        ..Default::default()
    };
    check_snapshot("cook_torrance_sun_pcf", &compose(&key));
}

#[test]
fn snapshot_everything() {
    let key = ShaderKey {
        shading: ShadingMode::Phong,
        variants: all_variants().into_iter().collect(),
        lights: LightsKey {
            kinds: LightKind::ALL.into(),
            ..Default::default()
        }
        .with_flags(true),
        shadows: ShadowKey {
            maps: ShadowFeatures {
                projections: [Projection::Ortho, Projection::Perspective, Projection::Cube].into(),
                pcf: true,
            },
            vertex_coords: true,
            approximate_coords: false,
        },
        counts: LoopCounts {
            lights: 5,
            shadow_maps: 3,
            pcf_radius: None,
        },
        arrays: UniformArrays::for_counts(5, 8),
        environment: EnvironmentKey {
            map: true,
            ..Default::default()
        }
        .with_flags(true),
        materials: MaterialsKey {
            alpha: true,
            energy_compensation: true,
            emission: true,
            occlusion: true,
            ..Default::default()
        },
        ..Default::default()
    };
    check_snapshot("everything", &compose(&key));
}
