//! The sample models of `assets/gltf` as `gonio render` draws them (each
//! file's own camera and lights, or gonio's default headlight where it has
//! none). The test checks that each shows something lit; the ignored test
//! writes the README's contact sheet, `docs/gallery.png`:
//! `cargo test --release --test gallery -- --ignored`.

mod common;

use gonio::frame::Frame;
use gonio::output::write::to_srgb8;
use gonio::scene::scene_file::{self, SceneSource};
use plotters::prelude::*;
use std::path::PathBuf;

/// The models, by path under `assets/gltf`.
const MODELS: [&str; 12] = [
    "Avocado/Avocado.gltf",
    "Box/Box.glb",
    "BoxInterleaved/BoxInterleaved.gltf",
    "BoxTextured/BoxTextured.gltf",
    "Cameras/Cameras.gltf",
    "MultipleScenes/MultipleScenes.gltf",
    "NormalTangentTest/NormalTangentTest.glb",
    "ShadowsDirectional/shadows-directional.gltf",
    "SimpleMeshes/SimpleMeshes.gltf",
    "Suzanne/Suzanne.gltf",
    "Triangle/Triangle.gltf",
    "TriangleWithoutIndices/TriangleWithoutIndices.gltf",
];

/// One cell of the sheet.
const CELL: (u32, u32) = (320, 240);
/// The label strip under each cell.
const LABEL: u32 = 22;
const COLUMNS: u32 = 4;

fn render(model: &str) -> Frame {
    let path = common::gltf_asset(model);
    let sets = [
        format!("image.width={}", CELL.0),
        format!("image.height={}", CELL.1),
    ];
    let (scene, _) = scene_file::load_with_limits(
        &SceneSource::File(path),
        &sets,
        gonio::scene::limits::Limits::default(),
    )
    .unwrap_or_else(|e| panic!("{model}: {e}"));
    let mut renderer = common::gpu_renderer();
    renderer
        .render(&scene)
        .unwrap_or_else(|e| panic!("{model}: {e}"))
        .0
}

/// Every model covers part of its frame, and the covered part is lit: not
/// NaN, not all black (which is how textures, normal maps and lights
/// that were ignored used to show).
#[test]
fn every_sample_model_renders_something_lit() {
    for model in MODELS {
        let frame = render(model);
        assert!(
            frame.radiance.iter().flatten().all(|v| v.is_finite()),
            "{model}: NaN or Inf"
        );
        let covered: Vec<&[f32; 3]> = frame
            .radiance
            .iter()
            .zip(&frame.coverage)
            .filter(|(_, c)| **c)
            .map(|(r, _)| r)
            .collect();
        assert!(
            covered.len() * 100 > frame.len(),
            "{model}: covers {} of {} pixels",
            covered.len(),
            frame.len()
        );
        let lit = covered
            .iter()
            .filter(|r| r.iter().any(|v| *v > 1e-3))
            .count();
        assert!(
            lit * 2 > covered.len(),
            "{model}: only {lit} of {} covered pixels are lit",
            covered.len()
        );
    }
}

#[test]
#[ignore = "writes docs/gallery.png; run by hand after a change that alters the sample renders"]
fn write_the_contact_sheet() {
    gonio::output::plot::load_font().unwrap();
    let rows = (MODELS.len() as u32).div_ceil(COLUMNS);
    let (w, h) = (COLUMNS * CELL.0, rows * (CELL.1 + LABEL));
    let mut pixels = vec![255u8; (w * h * 3) as usize];
    for (k, model) in MODELS.iter().enumerate() {
        let frame = render(model);
        let (x0, y0) = (
            (k as u32 % COLUMNS) * CELL.0,
            (k as u32 / COLUMNS) * (CELL.1 + LABEL),
        );
        for y in 0..CELL.1 {
            for x in 0..CELL.0 {
                let rgb = frame.radiance[frame.index(y, x)];
                let at = (((y0 + y) * w + x0 + x) * 3) as usize;
                for c in 0..3 {
                    pixels[at + c] = to_srgb8(rgb[c], 0.0);
                }
            }
        }
    }
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
        let style = ("sans-serif", 15).into_font().color(&BLACK);
        for (k, model) in MODELS.iter().enumerate() {
            let name = model.rsplit('/').next().unwrap();
            let x = (k as u32 % COLUMNS) * CELL.0 + 6;
            let y = (k as u32 / COLUMNS) * (CELL.1 + LABEL) + CELL.1 + 3;
            root.draw_text(name, &style, (x as i32, y as i32)).unwrap();
        }
        root.present().unwrap();
    }
    let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/gallery.png");
    image::RgbImage::from_raw(w, h, pixels)
        .unwrap()
        .save(&out)
        .unwrap();
    eprintln!("wrote {}", out.display());
}
