//! Compressed glTF assets (assets/gltf-compressed, see its LICENSES.md):
//! each codec is read into what its uncompressed twin says.
//!
//! - Lossless codecs render bit-identically through `gonio render`:
//!   meshopt (EXT and KHR) against the same quantized data uncompressed;
//!   a KTX2 ETC1S texture against its decode by the reference C++
//!   transcoder; lossless WebP against the PNG it was made from; lossy
//!   WebP against libwebp's decode.
//! - Draco quantizes: every decoded vertex lies within the quantization
//!   step its stream declares of an original vertex (positions), and its
//!   normal within the octahedral step (normals); the render differs from
//!   the original's only where that displacement moves an edge across a
//!   pixel centre.
//! - Lossy textures (ETC1S, UASTC) are compared with the source PNG
//!   under a stated bound.
//! - Hostile data (truncated or garbage streams) is an input error naming
//!   the file, never a panic.

mod common;

use gonio::scene::gltf_import;
use std::path::{Path, PathBuf};

fn sample(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/gltf-compressed")
        .join(relative)
}

/// `gonio render FILE` to an EXR of `size`² pixels; the f32 RGBA.
fn render(file: &Path, size: u32) -> Vec<f32> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.exr");
    let output = common::gonio()
        .arg("render")
        .arg(file)
        .arg("-o")
        .arg(&out)
        .args(["--width", &size.to_string(), "--height", &size.to_string()])
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "gonio render {} failed: {}{}",
        file.display(),
        String::from_utf8_lossy(&output.stderr),
        common::LAVAPIPE_TEST_HINT
    );
    image::open(out).unwrap().into_rgba32f().into_raw()
}

/// Each triangle with its smallest index first (the same triangle and
/// winding).
fn rotated(triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    triangles
        .iter()
        .map(|&[a, b, c]| {
            if a <= b && a <= c {
                [a, b, c]
            } else if b <= c {
                [b, c, a]
            } else {
                [c, a, b]
            }
        })
        .collect()
}

/// Renders agree in coverage, and in radiance within `relative`.
fn assert_renders_alike(compressed: &Path, uncompressed: &Path, relative: f64) {
    let a = render(compressed, 96);
    let b = render(uncompressed, 96);
    let differing = a
        .chunks_exact(4)
        .zip(b.chunks_exact(4))
        .filter(|(x, y)| {
            (x[3] > 0.0) != (y[3] > 0.0)
                || (0..3).any(|c| {
                    f64::from((x[c] - y[c]).abs())
                        > relative * f64::from(x[c].abs().max(y[c].abs())) + 1e-7
                })
        })
        .count();
    assert!(
        differing * 100 <= a.len() / 4,
        "{} and {} differ in {differing} pixels",
        compressed.display(),
        uncompressed.display()
    );
}

fn assert_renders_identically(compressed: &Path, uncompressed: &Path) {
    let a = render(compressed, 96);
    let b = render(uncompressed, 96);
    let lit = b
        .chunks_exact(4)
        .filter(|p| p[..3].iter().any(|&v| v > 0.0))
        .count();
    assert!(
        lit > 500,
        "{}: only {lit} lit pixels",
        uncompressed.display()
    );
    let differing = a
        .chunks_exact(4)
        .zip(b.chunks_exact(4))
        .filter(|(x, y)| {
            x.iter()
                .map(|v| v.to_bits())
                .ne(y.iter().map(|v| v.to_bits()))
        })
        .count();
    assert_eq!(
        differing,
        0,
        "{} and {} render differently",
        compressed.display(),
        uncompressed.display()
    );
}

fn load(path: &Path) -> gltf_import::GltfScene {
    gltf_import::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

// ---------------------------------------------------------------------
// meshopt

/// Meshopt decoding is lossless: the EXT and KHR files hold gltfpack's
/// quantized data compressed, `MetalRoughSpheres-Quantized.glb` the same
/// data uncompressed; meshes and renders are identical.
#[test]
fn meshopt_renders_exactly_as_the_same_data_uncompressed() {
    let plain = sample("MetalRoughSpheres-Meshopt/MetalRoughSpheres-Quantized.glb");
    let expected = load(&plain);
    for name in [
        "MetalRoughSpheres-EXT-Meshopt.glb",
        "MetalRoughSpheres-KHR-Meshopt.glb",
    ] {
        let file = sample(&format!("MetalRoughSpheres-Meshopt/{name}"));
        let scene = load(&file);
        assert_eq!(scene.meshes.len(), expected.meshes.len(), "{name}");
        for (a, b) in scene.meshes.iter().zip(&expected.meshes) {
            assert_eq!(a.positions, b.positions, "{name}: {}", a.name);
            assert_eq!(a.normals, b.normals, "{name}: {}", a.name);
            // The index codec keeps each triangle but may rotate its
            // corners (meshoptimizer, "Index buffer compression").
            assert_eq!(
                rotated(&a.indices),
                rotated(&b.indices),
                "{name}: {}",
                a.name
            );
        }
        // Rotated corners change the GPU's f32 interpolation (barycentrics
        // taken from other edges), so renders agree closely, not bit for
        // bit: at most 1 % of the pixels differ by more than 10⁻³.
        assert_renders_alike(&file, &plain, 1e-3);
    }
}

/// The filtered file (`gltfpack -cc -vpf`: EXPONENTIAL float positions,
/// OCTAHEDRAL 8-bit normals, codec v1) against the quantized one: both
/// approximate the original to 14-bit positions, so they differ by at
/// most two half-steps of 2⁻¹⁴ of each mesh's extent (plus f32 rounding);
/// their normals are 8-bit snorm (each component within ½/127) and 8-bit
/// octahedral ([`octahedral_bound`] of 8 bits), so they differ by at most
/// √3·½/127 + 6√2/255 ≈ 0.040 in length. (The index codec at
/// this level reorders the vertices, so each is matched to its nearest.)
#[test]
fn meshopt_filters_decode_within_their_quantization() {
    let plain = load(&sample(
        "MetalRoughSpheres-Meshopt/MetalRoughSpheres-Quantized.glb",
    ));
    let filtered = load(&sample(
        "MetalRoughSpheres-Meshopt/MetalRoughSpheres-KHR-Meshopt-Filters.glb",
    ));
    let (lo, hi) = plain.meshes.iter().flat_map(|m| &m.positions).fold(
        (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let step = (hi - lo).max_element() / f64::from((1 << 14) - 1);
    // 8-bit snorm (each component within ½/127) against 8-bit octahedral.
    let normal_bound = 3f64.sqrt() * 0.5 / 127.0 + octahedral_bound(8);
    assert_vertices_match(
        "filtered vs quantized",
        &filtered,
        &plain,
        step * (1.0 + 1e-6) + 1e-6,
        normal_bound,
    );
}

// ---------------------------------------------------------------------
// Draco

/// The quantization each attribute of a Draco stream declares: POSITION
/// bits and extent (its `delta_max`), NORMAL octahedral bits.
struct DracoQuantization {
    position_step: f64,
    normal_bits: Option<u8>,
}

fn draco_quantization(stream: &[u8]) -> DracoQuantization {
    use draco_oxide_core::attribute::AttributeType;
    use draco_oxide_decoder::AttributeTransform;
    let portable =
        draco_oxide_decoder::decode_mesh_portable(stream).unwrap_or_else(|e| panic!("{e}"));
    let mut q = DracoQuantization {
        position_step: 0.0,
        normal_bits: None,
    };
    for (attribute, transform) in portable.mesh.attributes.iter().zip(&portable.transforms) {
        match (attribute.get_attribute_type(), transform) {
            (
                AttributeType::Position,
                AttributeTransform::Quantized {
                    delta_max, bits, ..
                },
            ) => {
                q.position_step = f64::from(*delta_max) / f64::from((1u32 << bits) - 1);
            }
            (AttributeType::Normal, AttributeTransform::Octahedral { bits }) => {
                q.normal_bits = Some(*bits);
            }
            _ => {}
        }
    }
    q
}

/// The Draco stream of a file's first compressed primitive (its buffer
/// view, in a GLB's BIN chunk or a `.gltf`'s first buffer file).
fn draco_stream(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    let (json, bin): (serde_json::Value, Vec<u8>) = if bytes.starts_with(b"glTF") {
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let json = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        (json, bytes[20 + json_len + 8..].to_vec())
    } else {
        let json: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        let uri = json["buffers"][0]["uri"].as_str().unwrap().to_string();
        (
            json,
            std::fs::read(path.parent().unwrap().join(uri)).unwrap(),
        )
    };
    let view_index = json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
        ["bufferView"]
        .as_u64()
        .unwrap() as usize;
    let view = &json["bufferViews"][view_index];
    let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    let length = view["byteLength"].as_u64().unwrap() as usize;
    bin[offset..offset + length].to_vec()
}

/// Every vertex of `decoded` lies within `position_bound` (per axis, in
/// the world) of a vertex of `original`, and among those one has a normal
/// within `normal_bound`; the triangle counts agree.
fn assert_vertices_match(
    label: &str,
    decoded: &gltf_import::GltfScene,
    original: &gltf_import::GltfScene,
    position_bound: f64,
    normal_bound: f64,
) {
    use std::collections::HashMap;
    let triangles =
        |s: &gltf_import::GltfScene| s.meshes.iter().map(|m| m.indices.len()).sum::<usize>();
    assert_eq!(
        triangles(decoded),
        triangles(original),
        "{label}: triangles"
    );
    let cell = (position_bound * 4.0).max(1e-9);
    let key = |p: glam::DVec3| (p / cell).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<(glam::DVec3, glam::DVec3)>> = HashMap::new();
    for m in &original.meshes {
        for (p, n) in m.positions.iter().zip(&m.normals) {
            grid.entry(key(*p)).or_default().push((*p, *n));
        }
    }
    let (mut worst_p, mut worst_n) = (0f64, 0f64);
    for m in &decoded.meshes {
        for (p, n) in m.positions.iter().zip(&m.normals) {
            let k = key(*p);
            let mut best: Option<(f64, f64)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        for (q, nq) in grid
                            .get(&(k + glam::IVec3::new(dx, dy, dz)))
                            .into_iter()
                            .flatten()
                        {
                            let dp = (*p - *q).abs().max_element();
                            if dp <= position_bound {
                                let dn = (*n - *nq).length();
                                if best.is_none_or(|(_, b)| dn < b) {
                                    best = Some((dp, dn));
                                }
                            }
                        }
                    }
                }
            }
            let (dp, dn) = best.unwrap_or_else(|| {
                panic!("{label}: vertex {p} has no original vertex within {position_bound:e}")
            });
            assert!(
                dn <= normal_bound,
                "{label}: vertex {p}: normal {n} is {dn} from the nearest original's"
            );
            worst_p = worst_p.max(dp);
            worst_n = worst_n.max(dn);
        }
    }
    eprintln!(
        "{label}: positions within {worst_p:e} (bound {position_bound:e}), normals within {worst_n:.5} (bound {normal_bound:.5})"
    );
}

/// The normal bound of `bits`-bit octahedral coding: each of the two
/// octahedral coordinates is rounded to a grid of step 2/(2^bits − 1), so
/// (u, v) moves by at most h·√2 with h = 1/(2^bits − 1); the point
/// (u, v, 1 − |u| − |v|) then moves by at most √3·h·√2, and normalizing
/// (|p| ≥ 1/√3) at most doubles that over |p|: 2·√3·√3·√2·h = 6√2·h; plus
/// the original's own f32 rounding.
fn octahedral_bound(bits: u8) -> f64 {
    6.0 * 2f64.sqrt() / f64::from((1u32 << bits) - 1) + 1e-6
}

/// Khronos's Box/glTF-Draco against Box/glTF (the same model; the
/// node transforms are the same in both files).
#[test]
fn draco_box_matches_the_uncompressed_box() {
    let draco_file = sample("Box-Draco/Box.gltf");
    let q = draco_quantization(&draco_stream(&draco_file));
    assert!(q.position_step > 0.0, "the Box stream quantizes positions");
    let decoded = load(&draco_file);
    let original = load(&common::gltf_asset("Box/Box.gltf"));
    let normal_bound = q.normal_bits.map_or(1e-6, octahedral_bound);
    // Half a step, plus f32 rounding of the dequantized value.
    assert_vertices_match(
        "Box",
        &decoded,
        &original,
        0.5 * q.position_step + 1e-6,
        normal_bound,
    );
    assert_draco_render_close(
        &draco_file,
        &common::gltf_asset("Box/Box.gltf"),
        q.position_step,
        normal_bound,
    );
}

/// Writes `assets/gltf/Suzanne` with the material of the Suzanne-Draco
/// files (textures removed) into `dir`: the uncompressed original.
fn suzanne_original(dir: &Path) -> PathBuf {
    let source = common::gltf_asset("Suzanne");
    std::fs::copy(source.join("Suzanne.bin"), dir.join("Suzanne.bin")).unwrap();
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(source.join("Suzanne.gltf")).unwrap()).unwrap();
    let root = json.as_object_mut().unwrap();
    for key in ["images", "textures", "samplers"] {
        root.remove(key);
    }
    for material in root["materials"].as_array_mut().unwrap() {
        material["pbrMetallicRoughness"] = serde_json::json!({
            "baseColorFactor": [0.8, 0.55, 0.3, 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 0.5
        });
    }
    let path = dir.join("Suzanne.gltf");
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    path
}

/// gltf-transform's Draco Suzanne (edgebreaker and sequential
/// connectivity) against the uncompressed Suzanne.
#[test]
fn draco_suzanne_matches_the_uncompressed_suzanne() {
    let dir = tempfile::tempdir().unwrap();
    let original_file = suzanne_original(dir.path());
    let original = load(&original_file);
    for name in ["Suzanne-Draco.glb", "Suzanne-Draco-Sequential.glb"] {
        let file = sample(&format!("Suzanne-Draco/{name}"));
        let q = draco_quantization(&draco_stream(&file));
        assert!(q.position_step > 0.0, "{name} quantizes positions");
        let decoded = load(&file);
        let normal_bound = q.normal_bits.map_or(1e-6, octahedral_bound);
        assert_vertices_match(
            name,
            &decoded,
            &original,
            0.5 * q.position_step + 1e-6,
            normal_bound,
        );
        assert_draco_render_close(&file, &original_file, q.position_step, normal_bound);
    }
}

/// The Draco file renders like the original except near edges and where
/// quantized normals move a highlight. A vertex moved by at most half a
/// quantization step moves an edge by at most `shift` pixels, so a pixel
/// centre changes coverage only within `shift` of the original's
/// silhouette: at most its silhouette pixels (those with an uncovered
/// 4-neighbour) times 2·shift, plus one. Where both cover, a normal moved
/// by δ (the octahedral bound) moves glTF's GGX lobe (`r` ≥ 0.5 in these
/// files, α ≥ 0.25) by at most |∂ ln D/∂θ| · δ ≤ (2/α) · δ = 8δ relative,
/// and the diffuse term by δ / (n·l), which exceeds that only at grazing
/// light: at least 98 % of the pixels covered by both must agree within
/// 8δ relative (plus 10⁻⁴ for f32 shading).
fn assert_draco_render_close(draco: &Path, original: &Path, position_step: f64, normal_bound: f64) {
    let size = 96u32;
    let a = render(draco, size);
    let b = render(original, size);
    let covered = |img: &[f32], i: usize| img[4 * i + 3] > 0.0;
    let n = (size * size) as usize;
    let silhouette = (0..n)
        .filter(|&i| {
            let (x, y) = ((i as u32) % size, (i as u32) / size);
            covered(&b, i)
                && [(-1i32, 0i32), (1, 0), (0, -1), (0, 1)]
                    .iter()
                    .any(|(dx, dy)| {
                        let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                        nx < 0
                            || ny < 0
                            || nx >= size as i32
                            || ny >= size as i32
                            || !covered(&b, (ny as u32 * size + nx as u32) as usize)
                    })
        })
        .count();
    // The scene is framed to its bounds, so a world length L spans at
    // most `size` pixels per bound extent; the step is a fraction of the
    // extent (delta_max): shift ≤ ½ step / extent · size, with the
    // extent ≥ the step · (2^bits − 1) ≥ step · 2^10 for ≥ 11 bits.
    let shift = 0.5 * f64::from(size) / 1024.0;
    let coverage_bound = (silhouette as f64 * 2.0 * shift).ceil() as usize + 1;
    let coverage_differs = (0..n).filter(|&i| covered(&a, i) != covered(&b, i)).count();
    assert!(
        coverage_differs <= coverage_bound,
        "{}: {coverage_differs} pixels change coverage, bound {coverage_bound} ({silhouette} silhouette pixels, step {position_step:e})",
        draco.display()
    );
    let both: Vec<usize> = (0..n)
        .filter(|&i| covered(&a, i) && covered(&b, i))
        .collect();
    let shading_differs = both
        .iter()
        .filter(|&&i| {
            (0..3).any(|c| {
                let (x, y) = (a[4 * i + c], b[4 * i + c]);
                let relative = 8.0 * normal_bound + 1e-4;
                f64::from((x - y).abs()) > relative * f64::from(x.abs().max(y.abs())) + 1e-6
            })
        })
        .count();
    eprintln!(
        "{}: {coverage_differs} coverage changes (bound {coverage_bound}), {shading_differs} of {} pixels shaded differently",
        draco.display(),
        both.len()
    );
    assert!(
        both.len() > 200,
        "{}: {} covered pixels",
        draco.display(),
        both.len()
    );
    assert!(
        shading_differs * 50 < both.len(),
        "{}: {shading_differs} of {} pixels differ by more than 8δ",
        draco.display(),
        both.len()
    );
}

// ---------------------------------------------------------------------
// KTX2 / Basis Universal

fn rgba8(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path).unwrap().into_rgba8();
    (img.width(), img.height(), img.into_raw())
}

/// gonio's transcode of `ktx2` (RGBA8, base level).
fn transcoded(ktx2: &Path) -> (u32, u32, Vec<u8>) {
    gonio::scene::texture::ktx2::transcode_rgba8(&std::fs::read(ktx2).unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", ktx2.display()))
}

/// ETC1S decodes bit-exactly as the reference C++ transcoder decodes it
/// (`basisu -unpack`, ETC1 output: ETC1S is a subset of ETC1, so its
/// ETC1 transcode decodes to the same texels), for a file made here and
/// one of the Khronos samples.
#[test]
fn etc1s_transcodes_exactly_as_the_reference_transcoder() {
    for (ktx2, reference) in [
        (
            "BoxTextured-KTX2/CesiumLogoFlat-ETC1S.ktx2",
            "BoxTextured-KTX2/CesiumLogoFlat-ETC1S-reference.png",
        ),
        (
            "StainedGlassLamp-KTX2/StainedGlassLamp_hardware_basecolor.ktx2",
            "StainedGlassLamp-KTX2/StainedGlassLamp_hardware_basecolor-reference.png",
        ),
    ] {
        let (w, h, ours) = transcoded(&sample(ktx2));
        let (rw, rh, theirs) = rgba8(&sample(reference));
        assert_eq!((w, h), (rw, rh), "{ktx2}");
        let differing = ours
            .chunks_exact(4)
            .zip(theirs.chunks_exact(4))
            .filter(|(a, b)| a[..3] != b[..3])
            .count();
        assert_eq!(
            differing, 0,
            "{ktx2}: texels differ from the reference decode"
        );
    }
}

/// Lossy Basis textures against the PNG they were encoded from, with the
/// bounds measured on 2026-12-04 (basisu 1.16.3 defaults): ETC1S (quality
/// 128) mean |Δ| 1.65 levels of 255 (largest 118, at the logo's sharp
/// edges, where ETC1S blocks have two colours), bound 4; UASTC (level 2,
/// Zstandard) bound 2. A wrong block decode (a swapped endpoint, a wrong
/// table, a wrong block order) shows as a mean error of tens of levels.
#[test]
fn basis_textures_stay_close_to_their_source() {
    let (sw, sh, source) = rgba8(&sample("BoxTextured-KTX2/CesiumLogoFlat.png"));
    for (ktx2, mean_bound) in [
        ("BoxTextured-KTX2/CesiumLogoFlat-ETC1S.ktx2", 4.0),
        ("BoxTextured-KTX2/CesiumLogoFlat-UASTC-zstd.ktx2", 2.0),
    ] {
        let (w, h, ours) = transcoded(&sample(ktx2));
        assert_eq!((w, h), (sw, sh));
        let diffs: Vec<u8> = ours
            .chunks_exact(4)
            .zip(source.chunks_exact(4))
            .flat_map(|(a, b)| (0..3).map(move |c| a[c].abs_diff(b[c])))
            .collect();
        let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64;
        let max = diffs.iter().copied().max().unwrap();
        eprintln!("{ktx2}: mean |Δ| {mean:.3}, max {max} (of 255)");
        assert!(mean <= mean_bound, "{ktx2}: mean {mean}, max {max}");
    }
}

/// The UASTC sample of StainedGlassLamp (linear, Zstandard) transcodes
/// to its declared size.
#[test]
fn uastc_zstd_sample_transcodes() {
    let (w, h, ours) = transcoded(&sample(
        "StainedGlassLamp-KTX2/StainedGlassLamp_bulbs_occlusion-rough-metal.ktx2",
    ));
    assert_eq!((w, h), (256, 256));
    // The reference transcoder (`basisu -unpack`, BC7, 2026-12-04) gives
    // R (occlusion) from 32 to 204 and G, B exactly 0 over level 0.
    let range = |c: usize| {
        ours.chunks_exact(4)
            .fold((255u8, 0u8), |(lo, hi), p| (lo.min(p[c]), hi.max(p[c])))
    };
    let (lo, hi) = range(0);
    assert!(
        lo.abs_diff(32) <= 4 && hi.abs_diff(204) <= 4,
        "R from {lo} to {hi}"
    );
    assert_eq!((range(1), range(2)), ((0, 0), (0, 0)));
}

/// The KTX2 (ETC1S) BoxTextured renders exactly as the same box with the
/// reference decode as a PNG: the transcoded texels go the same way as a
/// PNG's (sRGB decode in the base-colour slot, gonio's own mips).
#[test]
fn ktx2_box_renders_exactly_as_its_reference_png() {
    assert_renders_identically(
        &sample("BoxTextured-KTX2/BoxTextured-ETC1S.gltf"),
        &sample("BoxTextured-KTX2/BoxTextured-ETC1S-reference.gltf"),
    );
    // UASTC renders (its bound against the source is checked on texels).
    let uastc = render(&sample("BoxTextured-KTX2/BoxTextured-UASTC.gltf"), 48);
    assert!(uastc.chunks_exact(4).any(|p| p[0] > 0.0));
}

// ---------------------------------------------------------------------
// WebP

/// Lossless WebP renders exactly as the PNG it was made from; lossy WebP
/// (given with the PNG as fallback, `EXT_texture_webp` optional) exactly
/// as libwebp's decode of it, which shows the extension's image is the
/// one read.
#[test]
fn webp_renders_exactly_as_its_decoded_source() {
    assert_renders_identically(
        &sample("BoxTextured-WebP/BoxTextured-WebP-lossless.gltf"),
        &sample("BoxTextured-WebP/BoxTextured.gltf"),
    );
    assert_renders_identically(
        &sample("BoxTextured-WebP/BoxTextured-WebP-lossy-fallback.gltf"),
        &sample("BoxTextured-WebP/BoxTextured-WebP-lossy-reference.gltf"),
    );
}

// ---------------------------------------------------------------------
// Hostile input

/// Runs `gonio render` on `file` and expects exit 2 with a message naming
/// the file and each of `expect`, and no panic text.
fn assert_refused(file: &Path, expect: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    let output = common::gonio()
        .arg("render")
        .arg(file)
        .arg("-o")
        .arg(&out)
        .args(["--width", "16", "--height", "16"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.code(),
        Some(2),
        "{}: {stderr}",
        file.display()
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let name = file.file_name().unwrap().to_string_lossy();
    assert!(
        stderr.contains(name.as_ref()),
        "the message names the file: {stderr}"
    );
    for e in expect {
        assert!(stderr.contains(e), "expected {e:?} in: {stderr}");
    }
    assert!(!out.exists(), "no output file");
}

/// Copies the files of `folder` into a temporary folder, replaces `name`
/// with `bytes`, and returns the folder and the path of `main`.
fn tampered(folder: &str, main: &str, name: &str, bytes: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(sample(folder)).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, dir.path().join(path.file_name().unwrap())).unwrap();
    }
    std::fs::write(dir.path().join(name), bytes).unwrap();
    let main = dir.path().join(main);
    (dir, main)
}

/// A GLB with bytes `range` of its BIN chunk overwritten by `fill`.
fn glb_with_bin_damage(path: &Path, damage: impl Fn(&mut [u8])) -> Vec<u8> {
    let mut bytes = std::fs::read(path).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    damage(&mut bytes[20 + json_len + 8..]);
    bytes
}

#[test]
fn corrupt_draco_streams_are_refused_by_name() {
    // The Box's Draco buffer truncated, then garbage.
    let bin = std::fs::read(sample("Box-Draco/Box.bin")).unwrap();
    let mut truncated = bin[..40].to_vec();
    truncated.resize(bin.len(), 0);
    let (_dir, file) = tampered("Box-Draco", "Box.gltf", "Box.bin", &truncated);
    assert_refused(&file, &["KHR_draco_mesh_compression"]);
    let garbage: Vec<u8> = (0..bin.len()).map(|i| (i * 37 % 251) as u8).collect();
    let (_dir, file) = tampered("Box-Draco", "Box.gltf", "Box.bin", &garbage);
    assert_refused(&file, &["KHR_draco_mesh_compression", "corrupt"]);
    // A real stream with its middle scrambled.
    let suzanne = glb_with_bin_damage(&sample("Suzanne-Draco/Suzanne-Draco.glb"), |bin| {
        let n = bin.len();
        for b in &mut bin[n / 3..n / 2] {
            *b = b.wrapping_mul(31).wrapping_add(7);
        }
    });
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scrambled-draco.glb");
    std::fs::write(&file, suzanne).unwrap();
    assert_refused(&file, &["KHR_draco_mesh_compression"]);
}

#[test]
fn corrupt_meshopt_streams_are_refused_by_name() {
    // Zeroed data has no valid header; scrambled data keeps the first
    // view's header and may decode to garbage that a later check refuses.
    for (label, damage, expect) in [
        (
            "zeroed",
            Box::new(|bin: &mut [u8]| bin.fill(0)) as Box<dyn Fn(&mut [u8])>,
            &["meshopt_compression", "corrupt"][..],
        ),
        (
            "scrambled",
            Box::new(|bin: &mut [u8]| {
                for (i, b) in bin.iter_mut().enumerate() {
                    *b ^= (i * 131 % 256) as u8;
                }
            }),
            &[][..],
        ),
    ] {
        let bytes = glb_with_bin_damage(
            &sample("MetalRoughSpheres-Meshopt/MetalRoughSpheres-KHR-Meshopt.glb"),
            damage,
        );
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join(format!("{label}-meshopt.glb"));
        std::fs::write(&file, bytes).unwrap();
        assert_refused(&file, expect);
    }
}

#[test]
fn corrupt_ktx2_and_webp_textures_are_refused_by_name() {
    let ktx2 = std::fs::read(sample("BoxTextured-KTX2/CesiumLogoFlat-ETC1S.ktx2")).unwrap();
    let (_dir, file) = tampered(
        "BoxTextured-KTX2",
        "BoxTextured-ETC1S.gltf",
        "CesiumLogoFlat-ETC1S.ktx2",
        &ktx2[..ktx2.len() / 2],
    );
    assert_refused(&file, &["KTX2", "CesiumLogoFlat-ETC1S.ktx2"]);
    let mut garbage = ktx2.clone();
    for b in &mut garbage[80..] {
        *b = b.wrapping_mul(17);
    }
    let (_dir, file) = tampered(
        "BoxTextured-KTX2",
        "BoxTextured-ETC1S.gltf",
        "CesiumLogoFlat-ETC1S.ktx2",
        &garbage,
    );
    assert_refused(&file, &["CesiumLogoFlat-ETC1S.ktx2"]);
    let webp = std::fs::read(sample("BoxTextured-WebP/CesiumLogoFlat-lossless.webp")).unwrap();
    let (_dir, file) = tampered(
        "BoxTextured-WebP",
        "BoxTextured-WebP-lossless.gltf",
        "CesiumLogoFlat-lossless.webp",
        &webp[..webp.len() / 2],
    );
    assert_refused(&file, &["CesiumLogoFlat-lossless.webp"]);
}

/// A required extension that is still not implemented is refused by name.
#[test]
fn unsupported_required_extensions_are_still_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(sample("Box-Draco/Box.gltf")).unwrap()).unwrap();
    json["extensionsUsed"] =
        serde_json::json!(["KHR_draco_mesh_compression", "EXT_mesh_gpu_instancing"]);
    json["extensionsRequired"] =
        serde_json::json!(["KHR_draco_mesh_compression", "EXT_mesh_gpu_instancing"]);
    std::fs::copy(sample("Box-Draco/Box.bin"), dir.path().join("Box.bin")).unwrap();
    let file = dir.path().join("instanced.gltf");
    std::fs::write(&file, serde_json::to_vec(&json).unwrap()).unwrap();
    assert_refused(&file, &["EXT_mesh_gpu_instancing"]);
}
