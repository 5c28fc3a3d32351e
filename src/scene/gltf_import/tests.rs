//! Unit tests of the glTF import: the sample models, the mapping, and one
//! malformed file per check. The wider hostile corpus is in
//! `tests/hostile_input.rs`.

use super::accessors::triangulate;
use super::buffers::{has_scheme, percent_decode, relative_path};
use super::hostile::PARSER_PANICKED;
use super::*;
use crate::material::ReflectanceModel;
use crate::scene::mesh::area_weighted_normals;
use crate::scene::{Light, Rgb};
use base64::Engine as _;
use glam::DVec3;
use gltf::mesh::Mode;
use std::fs;
use std::path::PathBuf;

const ASSETS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/gltf");

fn asset(relative: &str) -> PathBuf {
    Path::new(ASSETS).join(relative)
}

fn load_asset(relative: &str) -> GltfScene {
    let path = asset(relative);
    load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn triangles(scene: &GltfScene) -> usize {
    scene.meshes.iter().map(|m| m.indices.len()).sum()
}

fn scene_bounds(scene: &GltfScene) -> (DVec3, DVec3) {
    crate::scene::mesh::bounds(
        scene
            .meshes
            .iter()
            .flat_map(|m| m.positions.iter().copied()),
    )
    .expect("geometry")
}

fn assert_unit_normals(scene: &GltfScene) {
    for mesh in &scene.meshes {
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-9, "{}: normal {n}", mesh.name);
        }
    }
}

#[test]
fn box_gltf_and_glb_agree() {
    let text = load_asset("Box/Box.gltf");
    let binary = load_asset("Box/Box.glb");
    assert_eq!(triangles(&text), 12);
    assert_eq!(triangles(&binary), 12);
    let (a, b) = (scene_bounds(&text), scene_bounds(&binary));
    assert!((a.0 - b.0).length() < 1e-12 && (a.1 - b.1).length() < 1e-12);
    // The unit box is rotated by the root node: still ±0.5 on all axes.
    assert!((a.0 + DVec3::splat(0.5)).length() < 1e-6, "{a:?}");
    assert!((a.1 - DVec3::splat(0.5)).length() < 1e-6, "{a:?}");
    assert_unit_normals(&text);
    assert_eq!(text.materials.len(), 1);
    assert_eq!(text.materials[0].name, "Red");
    assert_eq!(text.materials[0].model, ReflectanceModel::GltfPbr);
    assert!((text.materials[0].base_color - DVec3::new(0.8, 0.0, 0.0)).length() < 1e-6);
    assert_eq!(text.skipped_primitives, 0);
}

#[test]
fn box_normals_point_out_of_the_box() {
    let scene = load_asset("Box/Box.gltf");
    for mesh in &scene.meshes {
        for t in 0..mesh.indices.len() {
            let corners = mesh.triangle(t);
            let centroid = crate::scene::mesh::centroid(corners);
            let n = crate::scene::mesh::face_normal(corners);
            assert!(n.dot(centroid) > 0.0, "inward face {t}");
        }
    }
}

#[test]
fn interleaved_box_matches_the_plain_box() {
    let plain = load_asset("Box/Box.gltf");
    let interleaved = load_asset("BoxInterleaved/BoxInterleaved.gltf");
    assert_eq!(triangles(&interleaved), 12);
    let (a, b) = (scene_bounds(&plain), scene_bounds(&interleaved));
    assert!((a.0 - b.0).length() < 1e-12 && (a.1 - b.1).length() < 1e-12);
    assert_unit_normals(&interleaved);
}

#[test]
fn triangle_without_indices_gets_generated_normals() {
    let scene = load_asset("TriangleWithoutIndices/TriangleWithoutIndices.gltf");
    assert_eq!(scene.meshes.len(), 1);
    assert_eq!(triangles(&scene), 1);
    for n in &scene.meshes[0].normals {
        assert!((*n - DVec3::Z).length() < 1e-12, "{n}");
    }
    // No material in the file: glTF's default, mapped like the others.
    let material = &scene.materials[scene.meshes[0].material];
    assert_eq!(material.name, "gltf-default");
    // b = m = r = 1: a white rough metal.
    assert_eq!(material.model, ReflectanceModel::GltfPbr);
    assert_eq!(material.base_color, Rgb::ONE);
    assert_eq!(material.metallic, 1.0);
    assert_eq!(material.roughness, 1.0);
}

#[test]
fn suzanne_has_its_own_normals() {
    let scene = load_asset("Suzanne/Suzanne.gltf");
    assert!(triangles(&scene) > 0);
    assert_unit_normals(&scene);
    // The file's normals are smooth, which generated ones would not
    // reproduce exactly; check they were taken from the file.
    let mesh = &scene.meshes[0];
    let generated = area_weighted_normals(&mesh.positions, &mesh.indices);
    assert!(
        mesh.normals
            .iter()
            .zip(&generated)
            .any(|(a, b)| (*a - *b).length() > 1e-3)
    );
}

#[test]
fn other_samples_load() {
    for (file, min_triangles) in [
        ("Avocado/Avocado.gltf", 100),
        ("Triangle/Triangle.gltf", 1),
        ("NormalTangentTest/NormalTangentTest.glb", 100),
        ("MultipleScenes/MultipleScenes.gltf", 1),
    ] {
        let scene = load_asset(file);
        assert!(triangles(&scene) >= min_triangles, "{file}");
        assert_unit_normals(&scene);
        for m in &scene.materials {
            m.validate().unwrap();
        }
    }
}

#[test]
fn multiple_scenes_uses_the_default_scene_only() {
    // `scene = 1` lists node 1 alone.
    let scene = load_asset("MultipleScenes/MultipleScenes.gltf");
    assert_eq!(scene.meshes.len(), 1);
    assert_eq!(scene.meshes[0].name, "mesh 1");
}

#[test]
fn shadows_directional_has_a_directional_light_and_a_camera() {
    let scene = load_asset("ShadowsDirectional/shadows-directional.gltf");
    let directional: Vec<_> = scene
        .lights
        .iter()
        .filter_map(|l| match l {
            Light::Directional {
                direction,
                irradiance,
                shadows,
            } => Some((*direction, *irradiance, *shadows)),
            _ => None,
        })
        .collect();
    assert_eq!(directional.len(), 1);
    let (direction, irradiance, shadows) = directional[0];
    assert!((direction.length() - 1.0).abs() < 1e-12);
    assert!(direction.y < 0.0, "the sun shines downwards: {direction}");
    assert!((irradiance - Rgb::splat(10.0)).length() < 1e-9);
    assert!(!shadows);
    let camera = scene.camera.expect("camera");
    assert!((camera.fov_y_deg - 0.39959652046304894f64.to_degrees()).abs() < 1e-5);
    assert_eq!((camera.near, camera.far), (0.0, 0.0));
    // The camera at (20, 17.5, 20) looks back towards the origin.
    assert!(camera.forward().dot(-camera.position.normalize()) > 0.9);
    assert_eq!(scene.materials.len(), 4);
}

#[test]
fn simple_meshes_instances_the_shared_mesh() {
    let scene = load_asset("SimpleMeshes/SimpleMeshes.gltf");
    assert_eq!(scene.meshes.len(), 2);
    let shift = scene.meshes[1].positions[0] - scene.meshes[0].positions[0];
    assert!((shift - DVec3::X).length() < 1e-12, "{shift}");
}

#[test]
fn cameras_takes_the_perspective_camera() {
    let scene = load_asset("Cameras/Cameras.gltf");
    let camera = scene.camera.expect("camera");
    assert!((camera.position - DVec3::new(0.5, 0.5, 3.0)).length() < 1e-6);
    assert!((camera.forward() - DVec3::NEG_Z).length() < 1e-12);
    assert!((camera.up - DVec3::Y).length() < 1e-12);
    assert!((camera.fov_y_deg - 0.7f64.to_degrees()).abs() < 1e-5);
}

#[test]
fn metallic_roughness_factors_make_a_gltf_pbr_material() {
    let b = Rgb::new(0.9, 0.5, 0.1);
    let dielectric = material_from_metallic_roughness("d", b, 0.0, 0.5);
    assert_eq!(dielectric.model, ReflectanceModel::GltfPbr);
    assert_eq!(dielectric.base_color, b);
    assert_eq!(dielectric.metallic, 0.0);
    assert_eq!(dielectric.k_a, b);
    // The perceptual roughness as the file gives it (α = r² is the model's).
    assert_eq!(dielectric.roughness, 0.5);
    let metal = material_from_metallic_roughness("m", b, 1.0, 0.0);
    assert_eq!(metal.metallic, 1.0);
    assert_eq!(metal.roughness, crate::material::ROUGHNESS_FLOOR);
    let wild = material_from_metallic_roughness("w", Rgb::splat(7.0), -3.0, 9.0);
    wild.validate().unwrap();
    assert_eq!(wild.roughness, 1.0);
    assert_eq!(wild.base_color, Rgb::ONE);
    assert_eq!(wild.metallic, 0.0);
}

#[test]
fn emissive_factor_times_strength_is_the_emission() {
    let json = r#"{"asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_emissive_strength"],
  "materials": [
    {"name": "glow", "emissiveFactor": [1.0, 0.5, 0.25],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}},
    {"name": "plain", "emissiveFactor": [0.2, 0.0, 0.0]},
    {"name": "bad", "emissiveFactor": [1.0, 1.0, 1.0],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": -1.0}}}
  ]}"#;
    let err = crate::scene::gltf_import::load_from_bytes(
        json.as_bytes(),
        std::path::Path::new("."),
        &Limits::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("bad") && err.contains("emission"), "{err}");
    let ok = json.replace("-1.0", "2.0");
    let scene = crate::scene::gltf_import::load_from_bytes(
        ok.as_bytes(),
        std::path::Path::new("."),
        &Limits::default(),
    )
    .unwrap();
    assert_eq!(scene.materials[0].emission, Rgb::new(4.0, 2.0, 1.0));
    // The file's f32, widened.
    assert_eq!(
        scene.materials[1].emission,
        Rgb::new(0.2f32.into(), 0.0, 0.0)
    );
    assert_eq!(scene.materials[2].emission, Rgb::splat(2.0));
    assert!(
        !scene.notes.iter().any(|n| n.contains("emissive_strength")),
        "{:?}",
        scene.notes
    );
}

#[test]
fn strips_and_fans_become_ccw_triangles() {
    let v = [0, 1, 2, 3, 4];
    assert_eq!(
        triangulate(Mode::TriangleStrip, &v).unwrap(),
        vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
    );
    assert_eq!(
        triangulate(Mode::TriangleFan, &v).unwrap(),
        vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
    );
    assert!(triangulate(Mode::Triangles, &v).is_err());
    assert!(
        triangulate(Mode::TriangleStrip, &v[..2])
            .unwrap()
            .is_empty()
    );
}

#[test]
fn uri_helpers() {
    assert!(has_scheme("http://example.com/a.bin"));
    assert!(has_scheme("file:///etc/passwd"));
    assert!(has_scheme("C:/x.bin"));
    assert!(!has_scheme("a.bin"));
    assert!(!has_scheme("./a:b.bin"));
    assert_eq!(percent_decode("a%20b%2Fc.bin").unwrap(), "a b/c.bin");
    assert!(percent_decode("a%2").is_err());
    assert!(percent_decode("a%+1").is_err());
    assert!(percent_decode("%FF").is_err());
    assert!(relative_path("sub/../a.bin").is_ok());
    assert!(relative_path("sub/../../a.bin").is_err());
    assert!(relative_path("/etc/passwd").is_err());
    assert!(relative_path("..\\a.bin").is_err());
}

#[test]
fn a_panic_in_the_parser_becomes_an_error() {
    // Prints the panic message; the point is that it is caught.
    let result: Result<(), String> = guarded(|| panic!("simulated gltf crate bug"));
    assert_eq!(result.unwrap_err(), PARSER_PANICKED);
}

// -- malformed files ---------------------------------------------------

/// A one-triangle glTF whose only buffer has the given URI and 44
/// bytes: three `VEC3` positions and three `u16` indices (+2 padding).
/// Tests edit the text with `replace` to break one thing at a time.
fn triangle_gltf(uri: &str) -> String {
    r#"{
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": "URI", "byteLength": 44}],
  "bufferViews": [
{"buffer": 0, "byteOffset": 0, "byteLength": 36},
{"buffer": 0, "byteOffset": 36, "byteLength": 6}
  ],
  "accessors": [
{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
 "min": [0, 0, 0], "max": [1, 1, 0]},
{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ]
}"#
    .replace("URI", uri)
}

fn triangle_bytes(indices: [u16; 3]) -> Vec<u8> {
    let mut bytes = Vec::new();
    for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in p {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in indices {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes.extend_from_slice(&[0, 0]);
    bytes
}

fn data_uri(bytes: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// Writes `contents` as `name` in a fresh folder and loads it.
fn load_written(dir: &Path, name: &str, contents: &[u8]) -> Result<GltfScene> {
    let path = dir.join(name);
    fs::write(&path, contents).unwrap();
    load(&path)
}

/// Asserts an input error naming the file whose message contains all
/// of `needles`.
fn assert_input_error(result: Result<GltfScene>, needles: &[&str]) {
    match result {
        Err(Error::Input { path, problem }) => {
            assert!(
                path.to_string_lossy().contains("model"),
                "{}",
                path.display()
            );
            for needle in needles {
                assert!(problem.contains(needle), "`{needle}` not in: {problem}");
            }
        }
        Err(e) => panic!("expected an input error, got {e}"),
        Ok(_) => panic!("expected an error for {needles:?}"),
    }
}

#[test]
fn the_test_triangle_loads() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])));
    let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
    assert_eq!(triangles(&scene), 1);
    // External buffer, percent-encoded name, in a subfolder.
    fs::create_dir(dir.path().join("sub dir")).unwrap();
    fs::write(
        dir.path().join("sub dir/tri.bin"),
        triangle_bytes([0, 1, 2]),
    )
    .unwrap();
    let gltf = triangle_gltf("sub%20dir/./tri.bin");
    let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
    assert_eq!(triangles(&scene), 1);
}

#[test]
fn invalid_json_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let result = load_written(dir.path(), "model.gltf", b"{ \"asset\": ");
    assert_input_error(result, &["invalid glTF"]);
}

#[test]
fn truncated_glb_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let glb = fs::read(asset("Box/Box.glb")).unwrap();
    let result = load_written(dir.path(), "model.glb", &glb[..20]);
    assert_input_error(result, &["invalid GLB"]);
}

#[test]
fn buffer_outside_the_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("outside.bin"), triangle_bytes([0, 1, 2])).unwrap();
    let inner = dir.path().join("inner");
    fs::create_dir(&inner).unwrap();
    for (uri, needle) in [
        ("../outside.bin", "leaves the glTF's folder"),
        ("sub/../../outside.bin", "leaves the glTF's folder"),
        ("%2E%2E/outside.bin", "leaves the glTF's folder"),
        ("/etc/passwd", "absolute path"),
        ("http://example.com/tri.bin", "URI scheme"),
        ("file:///etc/passwd", "URI scheme"),
        ("missing.bin", "cannot be opened"),
        (".", "is not a regular file"),
    ] {
        let gltf = triangle_gltf(uri);
        let result = load_written(&inner, "model.gltf", gltf.as_bytes());
        assert_input_error(result, &["buffer 0", needle]);
    }
}

#[cfg(unix)]
#[test]
fn symlink_out_of_the_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("outside.bin"), triangle_bytes([0, 1, 2])).unwrap();
    let inner = dir.path().join("inner");
    fs::create_dir(&inner).unwrap();
    std::os::unix::fs::symlink(dir.path().join("outside.bin"), inner.join("link.bin")).unwrap();
    let gltf = triangle_gltf("link.bin");
    let result = load_written(&inner, "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["outside the glTF's folder"]);
}

#[test]
fn short_buffer_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("tri.bin"), &triangle_bytes([0, 1, 2])[..40]).unwrap();
    let gltf = triangle_gltf("tri.bin");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["buffer 0", "40 bytes", "byteLength 44"]);
}

#[test]
fn huge_buffer_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf("tri.bin").replace("\"byteLength\": 44", "\"byteLength\": 2000000000");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["buffer 0", "--limit bytes=N"]);
}

#[test]
fn bad_base64_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf("data:application/octet-stream;base64,AAAA*AAA");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["buffer 0", "invalid base64"]);
    let gltf = triangle_gltf("data:application/octet-stream,plain");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["buffer 0", "without base64"]);
}

#[test]
fn unsupported_required_extension_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2]))).replace(
        "\"scene\": 0,",
        r#""scene": 0,
  "extensionsUsed": ["EXT_texture_avif"],
  "extensionsRequired": ["EXT_texture_avif"],"#,
    );
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["EXT_texture_avif", "AVIF textures"]);
}

#[test]
fn index_out_of_range_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 7])));
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 1", "index 7", "out of range"]);
}

#[test]
fn accessor_outside_its_view_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let uri = data_uri(&triangle_bytes([0, 1, 2]));
    // Four positions in a 36-byte view.
    let gltf = triangle_gltf(&uri).replace(
        "\"count\": 3, \"type\": \"VEC3\"",
        "\"count\": 4, \"type\": \"VEC3\"",
    );
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 0 (POSITION)", "do not fit"]);
    // A view reaching past the end of its buffer.
    let gltf = triangle_gltf(&uri).replace(
        "\"byteOffset\": 36, \"byteLength\": 6",
        "\"byteOffset\": 40, \"byteLength\": 6",
    );
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 1 (indices)", "buffer view 1"]);
    // An offset so large that offset + stride·(count−1) overflows.
    let gltf = triangle_gltf(&uri).replace(
        "{\"bufferView\": 1, ",
        "{\"bufferView\": 1, \"byteOffset\": 18446744073709551610, ",
    );
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 1 (indices)", "do not fit"]);
    // Wrong component type for positions.
    let gltf = triangle_gltf(&uri).replace("\"componentType\": 5126", "\"componentType\": 5123");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 0 (POSITION)", "expected VEC3 of FLOAT"]);
}

#[test]
fn non_finite_position_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = triangle_bytes([0, 1, 2]);
    bytes[12..16].copy_from_slice(&f32::NAN.to_le_bytes());
    let gltf = triangle_gltf(&data_uri(&bytes));
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["accessor 0 (POSITION)", "vertex 1", "not finite"]);
}

#[test]
fn missing_position_accessor_does_not_panic() {
    // gltf-json's validation would index `accessors[99]` unchecked.
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
        .replace("\"POSITION\": 0", "\"POSITION\": 99");
    let result = load_written(dir.path(), "model.gltf", gltf.as_bytes());
    assert_input_error(result, &["POSITION", "accessor 99 does not exist"]);
}

#[test]
fn cyclic_and_shared_nodes_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let base = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])));
    let cyclic = base.replace(
        "\"nodes\": [{\"mesh\": 0}]",
        "\"nodes\": [{\"mesh\": 0, \"children\": [1]}, {\"children\": [0]}]",
    );
    let result = load_written(dir.path(), "model.gltf", cyclic.as_bytes());
    assert_input_error(result, &["cycle", "node 0 → node 1 → node 0"]);
    let shared = base
        .replace(
            "\"nodes\": [{\"mesh\": 0}]",
            "\"nodes\": [{\"children\": [2]}, {\"children\": [2]}, {\"mesh\": 0}]",
        )
        .replace(
            "\"scenes\": [{\"nodes\": [0]}]",
            "\"scenes\": [{\"nodes\": [0, 1]}]",
        );
    let result = load_written(dir.path(), "model.gltf", shared.as_bytes());
    assert_input_error(result, &["node 2 has two parents, nodes 0 and 1"]);
}

#[test]
fn points_are_skipped_and_counted() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
        .replace("\"indices\": 1}", "\"indices\": 1, \"mode\": 0}");
    let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
    assert!(scene.meshes.is_empty());
    assert_eq!(scene.skipped_primitives, 1);
    assert!(scene.materials.is_empty());
}

#[test]
fn lights_and_scaled_nodes() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])))
        .replace(
            "\"scene\": 0,",
            r#""scene": 0,
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
{"type": "point", "color": [1, 0.5, 0], "intensity": 4, "range": 10},
{"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}
  ]}},"#,
        )
        .replace(
            "\"scenes\": [{\"nodes\": [0]}]",
            "\"scenes\": [{\"nodes\": [0, 1, 2]}]",
        )
        .replace(
            "\"nodes\": [{\"mesh\": 0}]",
            r#""nodes": [
{"mesh": 0, "scale": [2, 0, 1]},
{"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
{"rotation": [-0.7071068, 0, 0, 0.7071068], "extensions": {"KHR_lights_punctual": {"light": 1}}}
  ]"#,
        );
    let scene = load_written(dir.path(), "model.gltf", gltf.as_bytes()).unwrap();
    // The zero scale flattens the triangle; normals stay unit length.
    assert_eq!(triangles(&scene), 1);
    assert_unit_normals(&scene);
    assert_eq!(scene.lights.len(), 2);
    match &scene.lights[0] {
        Light::Point {
            position,
            intensity,
            range,
            shadows,
        } => {
            assert!((*position - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
            assert!((*intensity - Rgb::new(4.0, 2.0, 0.0)).length() < 1e-12);
            assert_eq!(*range, Some(10.0));
            assert!(!shadows);
        }
        other => panic!("{other:?}"),
    }
    match &scene.lights[1] {
        Light::Spot {
            direction,
            intensity,
            inner_cone_deg,
            outer_cone_deg,
            range,
            ..
        } => {
            // −90° about X turns −Z into −Y.
            assert!((*direction - DVec3::NEG_Y).length() < 1e-6, "{direction}");
            assert_eq!(*intensity, Rgb::splat(2.0));
            assert!((inner_cone_deg - 0.1f64.to_degrees()).abs() < 1e-5);
            assert!((outer_cone_deg - 0.5f64.to_degrees()).abs() < 1e-5);
            assert_eq!(*range, None);
        }
        other => panic!("{other:?}"),
    }
    // Under the zero-scaled node the spot would have no direction.
    let nested = gltf
        .replace(
            "\"scale\": [2, 0, 1]}",
            "\"scale\": [2, 0, 1], \"children\": [2]}",
        )
        .replace("[0, 1, 2]", "[0, 1]");
    let result = load_written(dir.path(), "model.gltf", nested.as_bytes());
    assert_input_error(result, &["node 2", "light 1", "no direction"]);
}

#[test]
fn other_major_versions_and_later_min_versions_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = triangle_gltf(&data_uri(&triangle_bytes([0, 1, 2])));
    let v3 = gltf.replace(r#""version": "2.0""#, r#""version": "3.0""#);
    assert_input_error(
        load_written(dir.path(), "model.gltf", v3.as_bytes()),
        &["asset.version is \"3.0\"", "glTF 2.x"],
    );
    let min = gltf.replace(
        r#""version": "2.0""#,
        r#""version": "2.1", "minVersion": "2.1""#,
    );
    assert_input_error(
        load_written(dir.path(), "model.gltf", min.as_bytes()),
        &["asset.minVersion is \"2.1\""],
    );
    let garbled = gltf.replace(r#""version": "2.0""#, r#""version": "two""#);
    assert_input_error(
        load_written(dir.path(), "model.gltf", garbled.as_bytes()),
        &["not MAJOR.MINOR"],
    );
    // A later minor version without minVersion is read (forward compatible).
    let minor = gltf.replace(r#""version": "2.0""#, r#""version": "2.1""#);
    assert_eq!(
        triangles(&load_written(dir.path(), "model.gltf", minor.as_bytes()).unwrap()),
        1
    );
}

#[test]
fn sparse_indices_past_the_count_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    // The positions accessor gets one sparse element whose index is the
    // u16 in the buffer's last two bytes (a view of its own), whose value
    // is the first position.
    let with_sparse = |index: u16| {
        let mut bytes = triangle_bytes([0, 1, 2]);
        let n = bytes.len();
        bytes[n - 2..].copy_from_slice(&index.to_le_bytes());
        triangle_gltf(&data_uri(&bytes))
            .replace(
                r#"{"buffer": 0, "byteOffset": 36, "byteLength": 6}"#,
                r#"{"buffer": 0, "byteOffset": 36, "byteLength": 6},
{"buffer": 0, "byteOffset": 42, "byteLength": 2}"#,
            )
            .replace(
                r#""min": [0, 0, 0], "max": [1, 1, 0]}"#,
                r#""min": [0, 0, 0], "max": [1, 1, 0],
 "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
            "values": {"bufferView": 0}}}"#,
            )
    };
    let ok = with_sparse(2);
    assert_eq!(
        triangles(&load_written(dir.path(), "model.gltf", ok.as_bytes()).unwrap()),
        1
    );
    let past = with_sparse(7);
    assert_input_error(
        load_written(dir.path(), "model.gltf", past.as_bytes()),
        &["sparse index 0 is 7", "3 elements"],
    );
}

/// A triangle as `KHR_mesh_quantization` writes it: POSITION as unsigned
/// shorts (non-normalized, stride 8), NORMAL as normalized signed bytes
/// (stride 4), and the same accessors without the extension.
fn quantized_triangle(extension: bool, position_normalized: bool) -> String {
    let mut bytes = Vec::new();
    for p in [[0u16, 0, 0], [2, 0, 0], [0, 3, 65535]] {
        for c in p {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    for _ in 0..3 {
        bytes.extend_from_slice(&[0u8, 0, 127, 0]); // +Z, normalized i8
    }
    let used = if extension {
        r#""extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],"#
    } else {
        ""
    };
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {used}
  "buffers": [{{"uri": "{}", "byteLength": 36}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 24, "byteStride": 8}},
                  {{"buffer": 0, "byteOffset": 24, "byteLength": 12, "byteStride": 4}}],
  "accessors": [{{"bufferView": 0, "componentType": 5123, "normalized": {position_normalized}, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 3, 65535]}},
                {{"bufferView": 1, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3"}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}}}]}}],
  "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]}}"#,
        data_uri(&bytes)
    )
}

#[test]
fn quantized_attributes_decode_as_the_extension_says() {
    let dir = tempfile::tempdir().unwrap();
    let scene = load_written(
        dir.path(),
        "q.gltf",
        quantized_triangle(true, false).as_bytes(),
    )
    .unwrap();
    let mesh = &scene.meshes[0];
    assert_eq!(
        mesh.positions,
        vec![
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 3.0, 65535.0)
        ]
    );
    assert!(
        mesh.normals.iter().all(|&n| n == DVec3::Z),
        "{:?}",
        mesh.normals
    );
    // Normalized unsigned shorts: c / 65535.
    let scene = load_written(
        dir.path(),
        "qn.gltf",
        quantized_triangle(true, true).as_bytes(),
    )
    .unwrap();
    assert_eq!(
        scene.meshes[0].positions[2],
        DVec3::new(0.0, 3.0 / 65535.0, 1.0)
    );
    // Without the extension, integer positions are refused by name.
    let result = load_written(
        dir.path(),
        "model.gltf",
        quantized_triangle(false, false).as_bytes(),
    );
    assert_input_error(
        result,
        &["accessor 0 (POSITION)", "U16", "KHR_mesh_quantization"],
    );
}
