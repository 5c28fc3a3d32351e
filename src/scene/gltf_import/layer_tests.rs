//! Tests of the material extensions: the layer extensions' values and
//! texture slots (`layers`), the unlit and specular-glossiness
//! conversions, variants, and the note naming the extensions gonio
//! ignores. Hand-written files (a material each, textures as data URIs)
//! and the Khronos samples where the machine has them.

use super::*;
use crate::material::texture::{MaterialTexture, TextureTarget, UvTransform};
use crate::scene::Rgb;
use crate::scene::texture::Encoding;
use base64::Engine as _;
use glam::DVec2;
use std::path::PathBuf;

/// A 4×1 RGBA PNG whose texels' G run through 0, 85, 170, 255 and A
/// through 255, 170, 85, 0, as a data URI.
fn png_uri() -> String {
    let mut img = image::RgbaImage::new(4, 1);
    for x in 0..4u8 {
        img.put_pixel(
            u32::from(x),
            0,
            image::Rgba([10 + x, 85 * x, 200, 255 - 85 * x]),
        );
    }
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).unwrap();
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes.into_inner())
    )
}

/// A file with no geometry and `materials` (JSON objects, joined), one
/// image and two textures of it (texture 1 with a sampler).
fn file_with(materials: &[&str], top_level: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {top_level}
  "images": [{{"uri": "{}"}}],
  "samplers": [{{"magFilter": 9728, "wrapS": 33071}}],
  "textures": [{{"source": 0}}, {{"source": 0, "sampler": 0}}],
  "materials": [{}]}}"#,
        png_uri(),
        materials.join(",\n")
    )
}

fn load_json(json: &str) -> Result<GltfScene> {
    load_from_bytes(json.as_bytes(), Path::new("."), &Limits::default())
}

/// The texture on `key` of `m`.
fn slot<'a>(m: &'a crate::material::Material, key: &'static str) -> &'a MaterialTexture {
    m.textures
        .iter()
        .find(|t| t.target == TextureTarget::Param(key))
        .unwrap_or_else(|| panic!("{}: no texture on {key}: {:?}", m.name, m.textures))
}

#[test]
fn layer_extensions_set_the_keys_and_their_textures() {
    let materials = [
        r#"{"name": "coat", "extensions": {"KHR_materials_clearcoat": {
            "clearcoatFactor": 0.5, "clearcoatRoughnessFactor": 0.25,
            "clearcoatTexture": {"index": 1, "texCoord": 1},
            "clearcoatNormalTexture": {"index": 0, "scale": 0.5, "extensions":
                {"KHR_texture_transform": {"rotation": 0.5}}},
            "clearcoatRoughnessTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                {"offset": [0.5, 0.25], "rotation": 0.3, "scale": [2, 3], "texCoord": 1}}}}}}"#,
        r#"{"name": "sheen", "extensions": {"KHR_materials_sheen": {
            "sheenColorFactor": [0.2, 0.4, 0.6], "sheenRoughnessFactor": 0.7,
            "sheenColorTexture": {"index": 0}, "sheenRoughnessTexture": {"index": 0}}}}"#,
        r#"{"name": "specular", "extensions": {"KHR_materials_specular": {
            "specularFactor": 0.5, "specularColorFactor": [2, 1, 0.5],
            "specularTexture": {"index": 0}, "specularColorTexture": {"index": 0}},
            "KHR_materials_ior": {"ior": 1.8}}}"#,
        r#"{"name": "film", "extensions": {"KHR_materials_iridescence": {
            "iridescenceFactor": 0.8, "iridescenceIor": 1.4,
            "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 600,
            "iridescenceTexture": {"index": 0}, "iridescenceThicknessTexture": {"index": 0}}}}"#,
        r#"{"name": "brushed", "extensions": {"KHR_materials_anisotropy": {
            "anisotropyStrength": 0.6, "anisotropyRotation": -1.0,
            "anisotropyTexture": {"index": 1, "texCoord": 1}}}}"#,
        r#"{"name": "defaults", "extensions": {"KHR_materials_clearcoat": {},
            "KHR_materials_sheen": {}, "KHR_materials_iridescence": {},
            "KHR_materials_specular": {}, "KHR_materials_anisotropy": {}, "KHR_materials_ior": {}}}"#,
        r#"{"name": "sg-mode", "extensions": {"KHR_materials_ior": {"ior": 0}}}"#,
    ];
    let scene = load_json(&file_with(&materials, "")).unwrap();
    let m = &scene.materials;

    let coat = &m[0];
    assert_eq!(
        (coat.layers.clearcoat, coat.layers.clearcoat_roughness),
        (0.5, 0.25)
    );
    let t = slot(coat, "clearcoat");
    assert_eq!((t.channel, t.tex_coord, t.image), (0, 1, 0));
    assert_eq!(t.transform, UvTransform::default());
    // Texture 1's sampler: NEAREST magnification, clamped in u.
    assert_eq!(t.sampler.mag, crate::material::texture::Filter::Nearest);
    let t = slot(coat, "clearcoat_roughness");
    assert_eq!((t.channel, t.tex_coord), (1, 1), "G, the transform's set");
    assert_eq!(
        t.transform,
        UvTransform {
            offset: DVec2::new(0.5, 0.25),
            rotation: 0.3,
            scale: DVec2::new(2.0, 3.0)
        }
    );

    let normal = coat
        .textures
        .iter()
        .find(|t| t.target == TextureTarget::ClearcoatNormal { scale: 0.5 })
        .expect("the coat's normal map with its scale");
    assert_eq!(normal.transform.rotation, 0.5);
    assert_eq!(scene.images[normal.image].encoding, Encoding::Linear);

    let sheen = &m[1];
    assert_eq!(sheen.layers.sheen_color, Rgb::new(0.2, 0.4, 0.6));
    assert_eq!(sheen.layers.sheen_roughness, 0.7);
    assert_eq!(slot(sheen, "sheen_roughness").channel, 3, "A");
    let colour = slot(sheen, "sheen_color");
    assert_eq!(scene.images[colour.image].encoding, Encoding::Srgb);
    assert_eq!(
        scene.images[slot(sheen, "sheen_roughness").image].encoding,
        Encoding::Linear
    );

    let spec = &m[2];
    assert_eq!(spec.layers.ior, 1.8);
    assert_eq!(spec.layers.specular, 0.5);
    assert_eq!(spec.layers.specular_color, Rgb::new(2.0, 1.0, 0.5));
    assert_eq!(slot(spec, "specular").channel, 3, "A");
    assert_eq!(
        scene.images[slot(spec, "specular_color").image].encoding,
        Encoding::Srgb
    );

    let film = &m[3];
    assert_eq!(film.layers.iridescence, 0.8);
    assert_eq!(film.layers.iridescence_ior, 1.4);
    assert_eq!(film.layers.iridescence_thickness, 600.0, "the maximum");
    assert_eq!(slot(film, "iridescence").channel, 0, "R");
    // The thickness texture reads the derived image: 600·t = mix(200, 600, G).
    let thickness = slot(film, "iridescence_thickness");
    let level = &scene.images[thickness.image].levels[0];
    for x in 0..4 {
        let g = f64::from(85 * x as u8) / 255.0;
        let want = 200.0 + 400.0 * g;
        let got = 600.0 * level.texel(x, 0)[thickness.channel];
        // One rounding to a half float of t ≤ 1: within 600·2⁻¹¹.
        assert!(
            (got - want).abs() <= 600.0 * 2f64.powi(-11),
            "G = {g}: {got} nm, want {want} nm"
        );
    }

    let brushed = &m[4];
    assert_eq!(brushed.layers.anisotropy_strength, 0.6);
    assert_eq!(brushed.layers.anisotropy_rotation, -1.0);
    let map = brushed
        .textures
        .iter()
        .find(|t| t.target == TextureTarget::Anisotropy)
        .expect("the anisotropy map");
    assert_eq!(map.tex_coord, 1);
    assert_eq!(scene.images[map.image].encoding, Encoding::Linear);

    // Every extension at its defaults leaves the core unchanged.
    assert_eq!(m[5].layers, crate::material::layers::GltfLayers::default());
    assert!(m[5].textures.is_empty());
    assert_eq!(m[6].layers.ior, 0.0);
    // Every material reads its values as the contract's ranges allow.
    for material in m {
        material.validate().unwrap();
    }
}

#[test]
fn thickness_map_is_the_specifications_mix() {
    for (minimum, maximum) in [(100.0, 400.0), (0.0, 1200.0), (500.0, 200.0), (0.0, 0.0)] {
        let (s, map) = layers::thickness_map(minimum, maximum);
        assert_eq!(s, f64::max(minimum, maximum));
        for k in 0..=255 {
            let g = f64::from(k) / 255.0;
            let mut texel = [0.0, g as f32, 0.0, 1.0];
            map(&mut texel);
            let want = minimum + (maximum - minimum) * g;
            // f32 arithmetic of the map: well inside the half float's 2⁻¹¹.
            assert!((s * f64::from(texel[0]) - want).abs() <= 1e-6 * s.max(1.0));
            assert!(texel[0] >= 0.0 && texel[0] <= 1.0);
        }
    }
}

#[test]
fn out_of_range_values_and_textures_are_named() {
    let cases = [
        (
            r#"{"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.5}}}"#,
            &[
                "material 0",
                "KHR_materials_clearcoat.clearcoatFactor",
                "1.5",
            ][..],
        ),
        (
            r#"{"extensions": {"KHR_materials_ior": {"ior": 0.5}}}"#,
            &["KHR_materials_ior.ior", "0.5", "neither 0 nor ≥ 1"],
        ),
        (
            r#"{"extensions": {"KHR_materials_sheen": {"sheenColorTexture": {"index": 9}}}}"#,
            &[
                "KHR_materials_sheen.sheenColorTexture",
                "texture 9 does not exist",
            ],
        ),
        (
            r#"{"extensions": {"KHR_materials_iridescence": {"iridescenceThicknessMaximum": -1}}}"#,
            &["iridescenceThicknessMaximum", "-1"],
        ),
        (
            r#"{"extensions": {"KHR_materials_specular": {"specularFactor": "high"}}}"#,
            &["KHR_materials_specular", "invalid type"],
        ),
        (
            r#"{"extensions": {"KHR_materials_pbrSpecularGlossiness": {"glossinessFactor": 2}}}"#,
            &["KHR_materials_pbrSpecularGlossiness.glossinessFactor", "2"],
        ),
    ];
    for (material, needles) in cases {
        let err = load_json(&file_with(&[material], ""))
            .err()
            .unwrap_or_else(|| panic!("accepted: {material}"))
            .to_string();
        for needle in needles {
            assert!(err.contains(needle), "`{needle}` not in: {err}");
        }
    }
}

#[test]
fn unlit_becomes_the_unlit_model_and_reflects_nothing() {
    let materials = [
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 0.5],
            "baseColorTexture": {"index": 0}, "metallicFactor": 1},
            "emissiveFactor": [1, 1, 1], "alphaMode": "BLEND",
            "extensions": {"KHR_materials_unlit": {}}}"#,
        r#"{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 1],
            "baseColorTexture": {"index": 0}},
            "extensions": {"KHR_materials_unlit": {}}}"#,
    ];
    let scene = load_json(&file_with(&materials, "")).unwrap();
    let m = &scene.materials[0];
    assert_eq!(m.model, crate::material::ReflectanceModel::Unlit);
    // The crate's f32 base colour, widened.
    assert_eq!(m.base_color, Rgb::new(0.2f32.into(), 0.5, 0.8f32.into()));
    assert_eq!(m.alpha, 0.5);
    // The emissive factor is ignored, as the extension says.
    assert_eq!((m.emission, m.k_a), (Rgb::ZERO, Rgb::ZERO));
    assert_eq!(
        scene.images[slot(m, "base_color").image].encoding,
        Encoding::Srgb
    );
    // Blended: the texture's A reaches the alpha.
    assert!(slot(m, "base_color").carries_alpha());
    assert_eq!(m.textures.len(), 1);
    // The BRDF is zero everywhere: f_r at a few pairs of directions.
    let frame = crate::material::brdf::SurfaceFrame::new(glam::DVec3::Z, glam::DVec3::X);
    for (wi, wo) in [
        (glam::DVec3::Z, glam::DVec3::Z),
        (
            glam::DVec3::new(0.6, 0.0, 0.8),
            glam::DVec3::new(-0.6, 0.0, 0.8),
        ),
        (
            glam::DVec3::new(0.0, 0.99, 0.141),
            glam::DVec3::new(0.3, 0.0, 0.954),
        ),
    ] {
        let f = m.f_r(wi.normalize(), wo.normalize(), &frame);
        assert_eq!(f, Rgb::ZERO, "{wi} {wo}");
    }
    // Opaque: the same one texture on the colour (its A unread, as the
    // alpha mode says).
    let opaque = &scene.materials[1];
    assert_eq!(opaque.model, crate::material::ReflectanceModel::Unlit);
    assert_eq!(opaque.textures.len(), 1);
}

#[test]
fn specular_glossiness_converts_as_the_specular_extension_says() {
    let materials = [r#"{"extensions": {"KHR_materials_pbrSpecularGlossiness": {
        "diffuseFactor": [0.5, 0.4, 0.3, 0.9], "specularFactor": [0.1, 0.2, 0.3],
        "glossinessFactor": 0.6,
        "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1}}}}"#];
    let top = r#""extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "extensionsRequired": ["KHR_materials_pbrSpecularGlossiness"],"#;
    let scene = load_json(&file_with(&materials, top)).unwrap();
    let m = &scene.materials[0];
    assert_eq!(m.base_color, Rgb::new(0.5, 0.4, 0.3));
    assert_eq!(m.alpha, 0.9);
    assert_eq!(
        (m.metallic, m.layers.ior, m.layers.specular),
        (0.0, 0.0, 1.0)
    );
    assert_eq!(m.layers.specular_color, Rgb::new(0.1, 0.2, 0.3));
    assert!(slot(m, "base_color").carries_alpha());
    assert_eq!(
        scene.images[slot(m, "specular_color").image].encoding,
        Encoding::Srgb
    );
    // Roughness 1 times the derived image: 1 − 0.6·A.
    assert_eq!(m.roughness, 1.0);
    let r = slot(m, "roughness");
    assert_eq!(r.sampler.mag, crate::material::texture::Filter::Nearest);
    let level = &scene.images[r.image].levels[0];
    for x in 0..4 {
        let a = f64::from(255 - 85 * x as u8) / 255.0;
        let got = level.texel(x, 0)[r.channel];
        assert!((got - (1.0 - 0.6 * a)).abs() <= 2f64.powi(-11), "{got}");
    }
    // Without the texture, roughness = 1 − glossiness.
    let plain =
        [r#"{"extensions": {"KHR_materials_pbrSpecularGlossiness": {"glossinessFactor": 0.25}}}"#];
    let scene = load_json(&file_with(&plain, "")).unwrap();
    assert_eq!(scene.materials[0].roughness, 0.75);
    assert_eq!(scene.materials[0].layers.specular_color, Rgb::ONE);
    assert_eq!(scene.materials[0].base_color, Rgb::ONE);
}

/// A triangle drawn twice (two nodes, one mesh) with material 0 by
/// default and the given variant mappings.
fn variant_file(mappings: &str) -> String {
    let positions: Vec<u8> = [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&positions)
    );
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0,
  "extensionsUsed": ["KHR_materials_variants"],
  "extensions": {{"KHR_materials_variants": {{"variants": [{{"name": "red"}}, {{"name": "blue"}}, {{"name": "green"}}]}}}},
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [{{"mesh": 0}}, {{"mesh": 0, "translation": [2, 0, 0]}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0,
     "extensions": {{"KHR_materials_variants": {{"mappings": {mappings}}}}}}}]}}],
  "materials": [{{"name": "default"}}, {{"name": "red"}}, {{"name": "blue"}}],
  "buffers": [{{"uri": "{uri}", "byteLength": 36}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]}}]}}"#
    )
}

#[test]
fn variants_load_and_one_is_chosen_by_name() {
    let file =
        variant_file(r#"[{"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]"#);
    let scene = load_json(&file).unwrap();
    assert_eq!(scene.variants, ["red", "blue", "green"]);
    assert_eq!(scene.materials.len(), 3, "every variant's material loads");
    let drawn = |s: &GltfScene| s.meshes.iter().map(|m| m.material).collect::<Vec<_>>();
    assert_eq!(drawn(&scene), [0, 0], "the default materials");
    let mut blue = scene.clone();
    blue.choose_variant("blue").unwrap();
    assert_eq!(drawn(&blue), [2, 2]);
    // A variant no mapping names keeps the default material.
    let mut green = scene.clone();
    green.choose_variant("green").unwrap();
    assert_eq!(drawn(&green), [0, 0]);
    let err = scene.clone().choose_variant("Blue").unwrap_err();
    assert!(
        err.contains("\"Blue\"") && err.contains("\"red\", \"blue\", \"green\""),
        "{err}"
    );
    // Indices past the file's are named.
    for (mappings, needle) in [
        (r#"[{"material": 3, "variants": [0]}]"#, "material 3"),
        (r#"[{"material": 1, "variants": [3]}]"#, "variant 3"),
    ] {
        let err = load_json(&variant_file(mappings)).unwrap_err().to_string();
        assert!(
            err.contains(needle) && err.contains("KHR_materials_variants"),
            "{err}"
        );
    }
}

#[test]
fn ignored_extensions_are_named_in_one_warning() {
    let top = r#""extensionsUsed": ["EXT_mesh_gpu_instancing", "KHR_materials_clearcoat",
        "KHR_animation_pointer", "KHR_materials_sheen"],
        "extensionsRequired": ["KHR_materials_clearcoat", "KHR_materials_sheen"],"#;
    let scene = load_json(&file_with(&["{}"], top)).unwrap();
    let warnings: Vec<&String> = scene
        .notes
        .iter()
        .filter(|n| n.contains("ignores"))
        .collect();
    assert_eq!(warnings.len(), 1, "{:?}", scene.notes);
    let w = warnings[0];
    assert!(w.starts_with(hostile::WARNING), "{w}");
    assert!(
        w.contains("EXT_mesh_gpu_instancing") && w.contains("KHR_animation_pointer"),
        "{w}"
    );
    assert!(!w.contains("clearcoat") && !w.contains("sheen"), "{w}");
    // Nothing ignored: no warning.
    let top = r#""extensionsUsed": ["KHR_materials_iridescence"],"#;
    let scene = load_json(&file_with(&["{}"], top)).unwrap();
    assert!(scene.notes.is_empty(), "{:?}", scene.notes);
    // Every extension gonio reads is accepted as required.
    for name in [
        "KHR_materials_ior",
        "KHR_materials_specular",
        "KHR_materials_clearcoat",
        "KHR_materials_sheen",
        "KHR_materials_iridescence",
        "KHR_materials_anisotropy",
        "KHR_materials_unlit",
        "KHR_materials_pbrSpecularGlossiness",
        "KHR_materials_variants",
        "KHR_materials_transmission",
        "KHR_materials_volume",
        "KHR_materials_dispersion",
        "KHR_materials_diffuse_transmission",
    ] {
        let top = format!(r#""extensionsUsed": ["{name}"], "extensionsRequired": ["{name}"],"#);
        load_json(&file_with(&["{}"], &top)).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    // A required one it does not read is refused by name.
    let top = r#""extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],"#;
    let err = load_json(&file_with(&["{}"], top)).unwrap_err().to_string();
    assert!(err.contains("EXT_mesh_gpu_instancing"), "{err}");
}

/// A Khronos sample the repository ships (assets/gltf-pbr-next, with its
/// licence): a missing file fails the test.
fn sample(file: &str) -> GltfScene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/gltf-pbr-next")
        .join(file);
    load_with_limits(&path, &Limits::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn named<'a>(scene: &'a GltfScene, name: &str) -> &'a crate::material::Material {
    scene
        .materials
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no material {name}"))
}

#[test]
fn khronos_samples_read_their_extensions() {
    let s = sample("ClearCoatTest/ClearCoatTest.glb");
    let partial = named(&s, "Partial_Coated");
    assert_eq!(
        (partial.layers.clearcoat, partial.layers.clearcoat_roughness),
        (1.0, 0.03)
    );
    assert_eq!(slot(partial, "clearcoat").channel, 0);
    assert_eq!(
        slot(named(&s, "RoughVariations_Coated"), "clearcoat_roughness").channel,
        1
    );
    let s = sample("SheenCloth/SheenCloth.gltf");
    let cloth = named(&s, "SheenClothMat");
    assert_eq!(cloth.layers.sheen_color, Rgb::ONE);
    assert_eq!(cloth.layers.sheen_roughness, 1.0);
    // The colour from RGB, the roughness from A, both through the
    // texture's transform (scale 30, −30).
    assert_eq!(slot(cloth, "sheen_roughness").channel, 3);
    let s = sample("SpecularTest/SpecularTest.glb");
    assert_eq!(
        named(&s, "M7.5_HDR").layers.specular_color,
        Rgb::splat(25.0)
    );
    assert_eq!(slot(named(&s, "M2_SpecTex"), "specular").channel, 3);
    let s = sample("IridescenceSuzanne/IridescenceSuzanne.glb");
    assert!(s.materials.iter().any(|m| m.layers.iridescence == 1.0));
    // Its transmission is read, not ignored.
    assert!(s.materials.iter().any(|m| m.layers.transmission > 0.0));
    assert!(
        !s.notes
            .iter()
            .any(|n| n.contains("KHR_materials_transmission")),
        "{:?}",
        s.notes
    );
    let s = sample("UnlitTest/UnlitTest.glb");
    assert!(
        s.materials
            .iter()
            .all(|m| m.model == crate::material::ReflectanceModel::Unlit && m.emission == Rgb::ZERO)
    );
    let s = sample("AnisotropyStrengthTest/AnisotropyStrengthTest.glb");
    assert!(
        s.materials
            .iter()
            .any(|m| m.layers.anisotropy_strength > 0.0)
    );
}

#[test]
fn transmission_extensions_set_the_keys_and_their_textures() {
    let materials = [
        r#"{"name": "glass", "extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 0.75,
                "transmissionTexture": {"index": 0}},
            "KHR_materials_volume": {"thicknessFactor": 2.0,
                "thicknessTexture": {"index": 1},
                "attenuationDistance": 0.5, "attenuationColor": [0.9, 0.5, 0.25]},
            "KHR_materials_dispersion": {"dispersion": 0.4}}}"#,
        r#"{"name": "leaf", "extensions": {"KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": 0.5, "diffuseTransmissionTexture": {"index": 0},
            "diffuseTransmissionColorFactor": [0.2, 0.8, 0.1],
            "diffuseTransmissionColorTexture": {"index": 0}}}}"#,
        r#"{"name": "clear", "extensions": {"KHR_materials_volume": {"thicknessFactor": 1.0}}}"#,
    ];
    let scene = load_json(&file_with(&materials, "")).unwrap();
    let glass = named(&scene, "glass");
    assert_eq!(glass.layers.transmission, 0.75);
    assert_eq!(glass.layers.thickness, 2.0);
    assert_eq!(glass.layers.attenuation_distance, 0.5);
    assert_eq!(glass.layers.attenuation_color, Rgb::new(0.9, 0.5, 0.25));
    assert_eq!(glass.layers.dispersion, 0.4);
    assert_eq!(slot(glass, "transmission").channel, 0, "R");
    assert_eq!(slot(glass, "thickness").channel, 1, "G");
    let leaf = named(&scene, "leaf");
    assert_eq!(leaf.layers.diffuse_transmission, 0.5);
    assert_eq!(
        leaf.layers.diffuse_transmission_color,
        Rgb::new(0.2, 0.8, 0.1)
    );
    assert_eq!(slot(leaf, "diffuse_transmission").channel, 3, "A");
    assert_eq!(
        scene.images[slot(leaf, "diffuse_transmission_color").image].encoding,
        crate::scene::texture::Encoding::Srgb
    );
    // Absent attenuationDistance is the extension's +Infinity.
    let clear = named(&scene, "clear");
    assert_eq!(clear.layers.attenuation_distance, f64::INFINITY);
    assert_eq!(clear.layers.transmission, 0.0);
    // Out of range: an error naming the extension and the property.
    for (bad, needle) in [
        (
            r#"{"KHR_materials_transmission": {"transmissionFactor": 1.5}}"#,
            "KHR_materials_transmission.transmissionFactor",
        ),
        (
            r#"{"KHR_materials_volume": {"attenuationDistance": 0}}"#,
            "KHR_materials_volume.attenuationDistance",
        ),
        (
            r#"{"KHR_materials_volume": {"thicknessFactor": -1}}"#,
            "KHR_materials_volume.thicknessFactor",
        ),
        (
            r#"{"KHR_materials_dispersion": {"dispersion": -0.1}}"#,
            "KHR_materials_dispersion.dispersion",
        ),
        (
            r#"{"KHR_materials_diffuse_transmission": {"diffuseTransmissionColorFactor": [2, 0, 0]}}"#,
            "KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor",
        ),
    ] {
        let m = format!(r#"{{"name": "bad", "extensions": {bad}}}"#);
        let err = load_json(&file_with(&[&m], "")).unwrap_err().to_string();
        assert!(err.contains(needle), "{err}");
    }
}

#[test]
fn khronos_transmission_samples_read_their_extensions() {
    let s = sample("TransmissionTest/TransmissionTest.glb");
    assert!(s.materials.iter().any(|m| m.layers.transmission == 1.0));
    assert!(
        s.notes.iter().all(|n| !n.contains("KHR_materials_")),
        "{:?}",
        s.notes
    );
    let s = sample("AttenuationTest/AttenuationTest.glb");
    assert!(s.materials.iter().any(|m| m.layers.thickness > 0.0
        && m.layers.attenuation_distance.is_finite()
        && m.layers.attenuation_color != Rgb::ONE));
}
