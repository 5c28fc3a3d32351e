//! `image.msaa = 4`: the GPU renderer's multisampling.
//!
//! Without sample-rate shading a multisampled pixel runs the fragment
//! shader once per covering triangle, at the pixel centre (extrapolated on
//! the triangle's plane when the centre lies outside it, at most one pixel
//! from its covered samples), and the resolve averages the four samples.
//! So (derived bound): each averaged value is what one of the pixel's
//! surfaces shows within one pixel of its covered samples, i.e. what the
//! one-sample image shows within two pixels of this one. The difference
//! from the one-sample image is therefore at most the largest difference
//! between the pixel and the 5×5 block around it in that image (plus f32
//! rounding, 2⁻²⁰ of the value), and zero where all four samples fall in
//! one triangle. Coverage (alpha > ½ after the resolve) changes only where
//! a neighbour's coverage differs.

mod common;

use gonio::frame::Frame;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

fn scene(msaa: u32) -> Scene {
    scene_file::load(
        &SceneSource::BuiltIn,
        &[
            "image.width=200".into(),
            "image.height=150".into(),
            format!("image.msaa={msaa}"),
            "lights.0.shadows=true".into(),
        ],
    )
    .expect("built-in scene loads")
}

fn neighbours(f: &Frame, i: u32, j: u32, r: i64) -> impl Iterator<Item = usize> + '_ {
    (-r..=r).flat_map(move |di| {
        (-r..=r).filter_map(move |dj| {
            let (y, x) = (i as i64 + di, j as i64 + dj);
            (y >= 0 && x >= 0 && y < f.height as i64 && x < f.width as i64)
                .then(|| f.index(y as u32, x as u32))
        })
    })
}

#[test]
fn multisampling_only_changes_edge_pixels_within_their_neighbourhood() {
    let mut renderer = common::gpu_renderer();
    let (one, _) = renderer.render(&scene(1)).expect("1 sample renders");
    let (four, _) = renderer.render(&scene(4)).expect("4 samples render");
    let (mut changed, mut beyond) = (0, Vec::new());
    for i in 0..one.height {
        for j in 0..one.width {
            let k = one.index(i, j);
            for c in 0..3 {
                let (a, b) = (one.radiance[k][c], four.radiance[k][c]);
                let spread = neighbours(&one, i, j, 2)
                    .map(|n| (one.radiance[n][c] - a).abs())
                    .fold(0.0f32, f32::max);
                let d = (b - a).abs();
                if d > 0.0 {
                    changed += 1;
                }
                if d > spread + a.abs() * 2f32.powi(-20) + 1e-7 {
                    beyond.push((i, j, c, a, b, spread));
                }
            }
            if one.coverage[k] != four.coverage[k] {
                let edge = neighbours(&one, i, j, 1).any(|n| one.coverage[n] != one.coverage[k]);
                assert!(edge, "coverage changed inside a surface at ({i}, {j})");
            }
        }
    }
    assert!(
        beyond.is_empty(),
        "{} channel values moved beyond their neighbourhood, e.g. {:?}",
        beyond.len(),
        &beyond[..beyond.len().min(5)]
    );
    // Antialiasing happened (the sphere's silhouette, the plane's edges),
    // and most pixels are untouched.
    let total = (3 * one.width * one.height) as usize;
    assert!(changed > 200, "only {changed} values changed");
    assert!(changed < total / 2, "{changed} of {total} values changed");
}

#[test]
fn an_unsupported_sample_count_is_refused() {
    let Err(err) = scene_file::load(&SceneSource::BuiltIn, &["image.msaa=8".into()]) else {
        panic!("8 samples per pixel were accepted");
    };
    let err = err.to_string();
    assert!(err.contains("image.msaa = 8"), "{err}");
}

/// Gouraud shading with `image.msaa = 4`: the colour varying
/// was once interpolated at the pixel centre, extrapolated outside the
/// triangle at silhouettes (11 pixels of the built-in scene down to
/// −1.305). Interpolated at the centroid of the covered samples
/// (shaders/raster_vertex_shaded.wgsl) it is a convex combination of the
/// vertices' radiance, which is ≥ 0, so every resolved pixel is too.
#[test]
fn gouraud_with_msaa_has_no_negative_radiance_at_silhouettes() {
    let mut renderer = common::gpu_renderer();
    for size in [(200, 150), (320, 240)] {
        let scene = scene_file::load(
            &SceneSource::BuiltIn,
            &[
                format!("image.width={}", size.0),
                format!("image.height={}", size.1),
                "image.msaa=4".into(),
                "shading.mode=\"gouraud\"".into(),
            ],
        )
        .expect("built-in scene loads");
        let (frame, _) = renderer.render(&scene).expect("renders");
        let negative: Vec<(usize, [f32; 3])> = frame
            .radiance
            .iter()
            .copied()
            .enumerate()
            .filter(|(_, r)| r.iter().any(|&c| c < 0.0))
            .collect();
        assert!(
            negative.is_empty(),
            "{size:?}: {} pixels with negative radiance, e.g. {:?}",
            negative.len(),
            &negative[..negative.len().min(5)]
        );
    }
}
