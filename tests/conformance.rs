//! Khronos glTF conformance models (assets/gltf, CC0, unmodified), each
//! with an assertion that fails when the feature it tests is wrong, and
//! GPU against reference where a small image affords it.

mod common;

use gonio::frame::Frame;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

/// The model under the scene files' directional default light (not the
/// studio a glTF without lights gets by default): a light both renderers
/// evaluate exactly, so GPU and reference compare like for like.
fn load(relative: &str, sets: &[String]) -> Scene {
    let mut sets = sets.to_vec();
    sets.insert(0, "gltf.default_light=\"directional\"".into());
    scene_file::load(&SceneSource::File(common::gltf_asset(relative)), &sets)
        .unwrap_or_else(|e| panic!("{relative} loads: {e}"))
}

/// A camera `distance` in front of world point (x, y, 0), looking at it
/// along −Z with a vertical field of view of `fov` degrees, and the
/// pixel (column, row) world point (x + dx, y + dy, 0) lands on in a
/// `size`² image.
struct Frontal {
    x: f64,
    y: f64,
    distance: f64,
    fov: f64,
    size: u32,
}

impl Frontal {
    fn sets(&self) -> Vec<String> {
        let (x, y, d) = (self.x, self.y, self.distance);
        vec![
            format!("image.width={}", self.size),
            format!("image.height={}", self.size),
            format!(
                "camera={{position = [{x}, {y}, {d}], target = [{x}, {y}, 0.0], up = [0.0, 1.0, 0.0], fov_y_deg = {}}}",
                self.fov
            ),
        ]
    }

    fn pixel(&self, dx: f64, dy: f64) -> (u32, u32) {
        let half = self.distance * (self.fov.to_radians() / 2.0).tan();
        let scale = f64::from(self.size) / 2.0 / half;
        let c = f64::from(self.size) / 2.0;
        ((c + dx * scale) as u32, (c - dy * scale) as u32)
    }
}

fn luminance(f: &Frame, (column, row): (u32, u32)) -> f64 {
    let [r, g, b] = f.radiance[f.index(row, column)].map(f64::from);
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// TextureTransformTest, "Rotation" (r = 0.3927 rad): the arrow must
/// point at the "Correct" marker (node offset (−0.079, −0.516) from the
/// plane's centre), not at "Error" (its mirror image across the arrow's
/// start, the plane's top-left corner: the sign of KhronosGroup/glTF#1563)
/// nor along the diagonal (the transform ignored: "Not supported"). A
/// point 80 % of the way from that corner to "Correct" is on the arrow
/// (black), the same point towards "Error" on the light background.
/// Both renderers.
#[test]
fn texture_transform_rotation_points_at_correct() {
    let view = Frontal {
        x: -1.1,
        y: -0.55,
        distance: 3.0,
        fov: 30.0,
        size: 120,
    };
    let scene = load(
        "TextureTransformTest/TextureTransformTest.gltf",
        &view.sets(),
    );
    let corner = (-0.45, 0.45);
    let towards = |(x, y): (f64, f64)| {
        view.pixel(
            corner.0 + 0.8 * (x - corner.0),
            corner.1 + 0.8 * (y - corner.1),
        )
    };
    let (correct, error) = (towards((-0.079, -0.516)), towards((0.516, 0.079)));
    for (name, f) in [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ] {
        let (on, off) = (luminance(&f, correct), luminance(&f, error));
        eprintln!("{name}: towards Correct {on:.4}, towards Error {off:.4}");
        assert!(
            on < 0.2 * off,
            "{name}: the arrow does not point at Correct ({on} at {correct:?} vs {off} at {error:?})"
        );
    }
}

/// TextureTransformTest whole, GPU against reference (derived tolerance,
/// with the level-of-detail spread of textured scenes).
#[test]
fn texture_transform_gpu_matches_reference() {
    let scene = load(
        "TextureTransformTest/TextureTransformTest.gltf",
        &["image.width=96".into(), "image.height=80".into()],
    );
    let frame = common::gpu_renderer().render(&scene).unwrap().0;
    let (center, jittered) = common::reference_with_jitter(&scene);
    let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
    eprintln!("TextureTransformTest: {}", c.summary());
    assert!(c.compared > 1500);
    common::assert_agrees(
        "TextureTransformTest",
        "GPU and reference disagree",
        &c,
        &frame,
        &center,
    );
}

/// TextureEncodingTest: each row's spheres (base colour, emission,
/// metallic-roughness) take the same value from a factor and from 8-bit
/// PNG textures, plain, with a gAMA chunk and with an ICC profile (which
/// glTF requires to be ignored), so a row's spheres look the same: each
/// seen from straight in front (the same geometry), its centre pixel.
/// Tolerance: the texel is stored as f16 (half an ulp, 2⁻¹², relative),
/// and the roughness reaches the radiance at most through GGX's peak
/// ∝ r⁻⁴ (×4); 4 · 2⁻¹¹ bounds both, f32 shading adds ~10⁻⁶. A gamma
/// chunk honoured would move 136/255 by tens of per cent. Both renderers.
#[test]
fn texture_encoding_factors_equal_textures() {
    let tolerance = 4.0 * 2f64.powi(-11);
    let centre = |x: f64, y: f64, reference: bool| {
        let view = Frontal {
            x,
            y,
            distance: 20.0,
            fov: 4.0,
            size: 9,
        };
        let scene = load("TextureEncodingTest/TextureEncodingTest.glb", &view.sets());
        let f = if reference {
            gonio::reference::render(&scene)
        } else {
            common::gpu_renderer().render(&scene).unwrap().0
        };
        f.radiance[f.index(4, 4)].map(f64::from)
    };
    for (name, reference) in [("GPU", false), ("reference", true)] {
        for (row, y) in [
            ("base colour", 2.0),
            ("emissive", -1.0),
            ("metallic-roughness", -4.0),
        ] {
            let factor = centre(-2.75, y, reference);
            assert!(
                factor.iter().any(|&v| v > 1e-3),
                "{name} {row}: dark {factor:?}"
            );
            for (column, x) in [("texture", 0.25), ("gamma", 3.25), ("ICC", 6.25)] {
                let got = centre(x, y, reference);
                for c in 0..3 {
                    let err = (got[c] - factor[c]).abs();
                    assert!(
                        err <= tolerance * factor[c].abs() + 1e-6,
                        "{name} {row}, {column}: channel {c} {} vs factor {}",
                        got[c],
                        factor[c]
                    );
                }
            }
        }
    }
}

/// The first row from the top, in `column` between `rows`, whose pixel
/// is saturated (AlphaBlendModeTest's blue and yellow stripes; its
/// marble is grey-beige): (max − min) / max of RGB above ½.
fn first_striped_row(f: &Frame, column: u32, rows: std::ops::Range<u32>) -> Option<u32> {
    rows.into_iter().find(|&r| {
        let [a, b, c] = f.radiance[f.index(r, column)].map(f64::from);
        let (hi, lo) = (a.max(b).max(c), a.min(b).min(c));
        hi > 0.0 && (hi - lo) / hi > 0.5
    })
}

/// AlphaBlendModeTest's MASK panels (cutoff 0.25 at x = 0, the default
/// 0.5 at 1.5, 0.75 at 3; a linear alpha ramp from the top, opaque at the
/// bottom): each is cut where its ramp crosses its cutoff, so the first
/// striped row moves down the panel in equal steps (the default is 0.5
/// exactly when the middle step equals the outer one: ±2 px), by at
/// least a tenth of the panel's height each; above it the marble behind
/// shows. Both renderers.
#[test]
fn alpha_blend_mode_test_cutoffs() {
    let view = Frontal {
        x: 1.5,
        y: 1.035,
        distance: 8.0,
        fov: 30.0,
        size: 200,
    };
    let scene = load("AlphaBlendModeTest/AlphaBlendModeTest.glb", &view.sets());
    // The panels span y 0.1 to 1.97 (their quads), a little inside.
    let (_, top) = view.pixel(0.0, 1.9 - view.y);
    let (_, bottom) = view.pixel(0.0, 0.2 - view.y);
    let height = f64::from(bottom - top);
    for (name, f) in [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ] {
        let cut = [0.0, 1.5, 3.0].map(|x| {
            let (column, _) = view.pixel(x + 0.2 - view.x, 0.0);
            first_striped_row(&f, column, top..bottom)
                .unwrap_or_else(|| panic!("{name}: no stripes in the panel at x = {x}"))
        });
        eprintln!("{name}: first striped rows {cut:?} in rows {top}..{bottom}");
        let steps = [cut[1] as f64 - cut[0] as f64, cut[2] as f64 - cut[1] as f64];
        assert!(
            steps.iter().all(|&s| s > 0.1 * height),
            "{name}: cuts {cut:?} do not step down the panel"
        );
        assert!(
            (steps[0] - steps[1]).abs() <= 2.0,
            "{name}: the default cutoff is not halfway: steps {steps:?}"
        );
    }
}

/// AlphaBlendModeTest whole (OPAQUE, BLEND over the marble, MASK with
/// mipmapped textures), GPU against reference: the derived render
/// tolerance with the jitter and the level-of-detail envelope
/// ([`common::lod_envelope`]).
#[test]
fn alpha_blend_mode_test_gpu_matches_reference() {
    let view = Frontal {
        x: 0.0,
        y: 1.1,
        distance: 9.0,
        fov: 18.0,
        size: 90,
    };
    let mut sets = view.sets();
    sets[0] = "image.width=240".into();
    let scene = load("AlphaBlendModeTest/AlphaBlendModeTest.glb", &sets);
    let frame = common::gpu_renderer().render(&scene).unwrap().0;
    let (center, jittered) = common::reference_with_jitter(&scene);
    let (up, down) = common::lod_envelope(&scene, &center);
    let c = gonio::output::compare::compare_with_spreads(
        &frame,
        &center,
        &[
            (&jittered[0], &jittered[1]),
            (&jittered[2], &jittered[3]),
            (&up, &down),
        ],
        common::tolerance(&scene, &center),
    );
    eprintln!("AlphaBlendModeTest: {}", c.summary());
    assert!(c.compared > 10_000);
    common::assert_agrees(
        "AlphaBlendModeTest",
        "GPU and reference disagree",
        &c,
        &frame,
        &center,
    );
}

/// The darkest luminance along the segment from world (x0, y) to (x1, y)
/// (in the plane z = 0), one sample per pixel.
fn darkest(f: &Frame, view: &Frontal, y: f64, (x0, x1): (f64, f64)) -> f64 {
    (0..=24)
        .map(|i| {
            let x = x0 + (x1 - x0) * f64::from(i) / 24.0;
            luminance(f, view.pixel(x - view.x, y - view.y))
        })
        .fold(f64::INFINITY, f64::min)
}

/// TextureCoordinateTest: UV (0, 0) is the image's top-left corner
/// (glTF), so each quad's black-and-white checker runs along its outer
/// edges from its outer corner: along the outer edge near that corner
/// there is black; at the places a flipped v (the other horizontal edge)
/// or a flipped u (the other end of the same edge) would put it, only
/// the quad's colour. Both renderers.
#[test]
fn texture_coordinates_start_at_the_top_left() {
    let view = Frontal {
        x: 0.0,
        y: 0.0,
        distance: 4.0,
        fov: 40.0,
        size: 200,
    };
    let scene = load(
        "TextureCoordinateTest/TextureCoordinateTest.glb",
        &view.sets(),
    );
    for (name, f) in [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ] {
        for (quad, sx, sy) in [
            ("top left", -1.0, 1.0),
            ("top right", 1.0, 1.0),
            ("bottom left", -1.0, -1.0),
            ("bottom right", 1.0, -1.0),
        ] {
            let outer = darkest(&f, &view, sy * 1.15, (sx * 1.15, sx * 0.85));
            let v_flipped = darkest(&f, &view, sy * 0.25, (sx * 1.15, sx * 0.85));
            let u_flipped = darkest(&f, &view, sy * 1.15, (sx * 0.55, sx * 0.25));
            assert!(
                outer < 0.3 * v_flipped.min(u_flipped),
                "{name} {quad}: checker not at the outer corner: {outer} vs {v_flipped} (v flipped), {u_flipped} (u flipped)"
            );
        }
    }
}

/// Pixels of a square cell (centre (x, y), half-size `half`, world) that
/// are green (a check mark or a green square) and that are red (an X).
fn green_and_red(f: &Frame, view: &Frontal, (x, y): (f64, f64), half: f64) -> (usize, usize) {
    let (c0, r0) = view.pixel(x - half - view.x, y + half - view.y);
    let (c1, r1) = view.pixel(x + half - view.x, y - half - view.y);
    let (mut green, mut red) = (0, 0);
    for r in r0..=r1 {
        for c in c0..=c1 {
            let [red_, g, b] = f.radiance[f.index(r, c)].map(f64::from);
            green += usize::from(g > 1.5 * red_ && g > 1.5 * b);
            red += usize::from(red_ > 1.5 * g && red_ > 1.5 * b);
        }
    }
    (green, red)
}

/// TextureSettingsTest: in each row (single- and double-sided, clamp,
/// repeat and mirror in s and in t) the "Test" cell shows what the
/// "Sample pass" cell shows, a green check mark or a green square, when
/// the sampler's wrap mode and `doubleSided` are honoured; a wrong one
/// shows a red X or nothing. The test cell's green area is within 25 %
/// of the sample's (the two cells sit at different sub-pixel offsets),
/// and neither has red. Both renderers.
#[test]
fn texture_settings_match_the_sample_column() {
    let view = Frontal {
        x: 1.5,
        y: -1.1,
        distance: 12.0,
        fov: 40.0,
        size: 400,
    };
    let scene = load("TextureSettingsTest/TextureSettingsTest.glb", &view.sets());
    // Row centres: the meshes' z extents, turned to y by the root node's
    // −90° rotation about x.
    let rows = [
        ("single-sided", 2.545),
        ("double-sided", 1.52),
        ("clamp s", 0.467),
        ("clamp t", -0.57),
        ("repeat s", -1.604),
        ("repeat t", -2.641),
        ("mirror s", -3.678),
        ("mirror t", -4.715),
    ];
    for (name, f) in [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ] {
        for (row, y) in rows {
            let (test_green, test_red) = green_and_red(&f, &view, (0.455, y), 0.4);
            let (sample_green, sample_red) = green_and_red(&f, &view, (2.6, y), 0.4);
            eprintln!(
                "{name} {row}: green {test_green} vs {sample_green}, red {test_red} / {sample_red}"
            );
            assert!(
                sample_green > 100,
                "{name} {row}: the sample cell is not green"
            );
            assert!(
                (test_green as f64 - sample_green as f64).abs() <= 0.25 * sample_green as f64,
                "{name} {row}: test cell green {test_green} vs sample {sample_green}"
            );
            assert!(test_red + sample_red == 0, "{name} {row}: red (an X) shows");
        }
    }
}

/// VertexColorTest: the "Test" row's check marks are coloured by
/// `COLOR_0` only, the "Sample pass" row's by a texture; each red, green
/// and blue check covers about as many pixels of its colour in both rows
/// (within 25 %: the rows sit at different sub-pixel offsets). Ignoring
/// `COLOR_0` leaves the test row's checks uncoloured. Both renderers.
#[test]
fn vertex_colors_match_the_sample_row() {
    let view = Frontal {
        x: 0.0,
        y: 0.0,
        distance: 4.0,
        fov: 30.0,
        size: 200,
    };
    let scene = load("VertexColorTest/VertexColorTest.glb", &view.sets());
    let count = |f: &Frame, (x, y): (f64, f64), channel: usize| {
        let half = 0.22;
        let (c0, r0) = view.pixel(x - half, y + half);
        let (c1, r1) = view.pixel(x + half, y - half);
        let mut n = 0;
        for r in r0..=r1 {
            for c in c0..=c1 {
                let v = f.radiance[f.index(r, c)].map(f64::from);
                n += usize::from((0..3).all(|o| o == channel || v[channel] > 2.0 * v[o]));
            }
        }
        n
    };
    for (name, f) in [
        ("GPU", common::gpu_renderer().render(&scene).unwrap().0),
        ("reference", gonio::reference::render(&scene)),
    ] {
        for (colour, x, channel) in [("red", -0.59, 0), ("green", 0.0, 1), ("blue", 0.59, 2)] {
            let test = count(&f, (x, 0.27), channel);
            let sample = count(&f, (x, -0.51), channel);
            eprintln!("{name} {colour}: test {test}, sample {sample} pixels");
            assert!(
                sample > 100,
                "{name} {colour}: the sample check is not {colour}"
            );
            assert!(
                (test as f64 - sample as f64).abs() <= 0.25 * sample as f64,
                "{name} {colour}: test check {test} vs sample {sample} pixels"
            );
        }
    }
}

/// The other conformance models whole, at their default camera and
/// light, GPU against reference (derived tolerance with the jitter and
/// level-of-detail spreads of `common`).
#[test]
fn conformance_models_gpu_match_reference() {
    for model in [
        "TextureSettingsTest/TextureSettingsTest.glb",
        "TextureCoordinateTest/TextureCoordinateTest.glb",
        "VertexColorTest/VertexColorTest.glb",
        "TextureEncodingTest/TextureEncodingTest.glb",
        "TextureLinearInterpolationTest/TextureLinearInterpolationTest.glb",
        "MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb",
    ] {
        let scene = load(model, &["image.width=80".into(), "image.height=60".into()]);
        let frame = common::gpu_renderer().render(&scene).unwrap().0;
        let (center, jittered) = common::reference_with_jitter(&scene);
        let c = common::compare_to_reference(&scene, &frame, &center, &jittered);
        eprintln!("{model}: {}", c.summary());
        assert!(c.compared > 300, "{model}: {} compared", c.compared);
        common::assert_agrees(model, "GPU and reference disagree", &c, &frame, &center);
    }
}

/// MetalRoughSpheres against MetalRoughSpheresNoTextures, in the form
/// available here (`assets/gltf/MetalRoughSpheresTextured`, made by
/// `scripts/make_metal_rough_spheres_textured.py`): Khronos's textures of
/// MetalRoughSpheres on the 98 spheres of NoTextures, each material
/// reading its cell's texel, against the same spheres with those texels
/// as factors. Whole images, both renderers, every pixel. Tolerance, as
/// in `texture_encoding_factors_equal_textures`: the texels are stored
/// as f16 (relative 2⁻¹²), and metallic-roughness reaches the radiance at
/// most through GGX's D and height-correlated V, each |∂ln/∂ln α| ≤ 2
/// with α = r² (so ×4 per term in r): 4 · 2⁻¹¹ relative, plus 10⁻⁶ for
/// f32 shading. Geometry and coverage are the same in both files.
#[test]
fn metal_rough_spheres_textures_equal_their_texel_factors() {
    let tolerance = 4.0 * 2f64.powi(-11);
    let sets = [
        "image.width=160".to_string(),
        "image.height=120".to_string(),
    ];
    let textured = load(
        "MetalRoughSpheresTextured/MetalRoughSpheresTextured.gltf",
        &sets,
    );
    let factors = load(
        "MetalRoughSpheresTextured/MetalRoughSpheresTexelFactors.gltf",
        &sets,
    );
    assert!(textured.has_textures() && !factors.has_textures());
    for name in ["GPU", "reference"] {
        let render = |scene: &Scene| {
            if name == "GPU" {
                common::gpu_renderer().render(scene).unwrap().0
            } else {
                gonio::reference::render(scene)
            }
        };
        let (t, f) = (render(&textured), render(&factors));
        let (mut lit, mut worst) = (0, 0.0f64);
        for (i, (a, b)) in t.radiance.iter().zip(&f.radiance).enumerate() {
            for c in 0..3 {
                let (a, b) = (f64::from(a[c]), f64::from(b[c]));
                if b > 1e-3 {
                    lit += 1;
                }
                let err = (a - b).abs() / (b.abs() * tolerance + 1e-6);
                if err > 1.0 && err > worst {
                    eprintln!(
                        "{name}: pixel {} of row {}, channel {c}: {a} vs {b}",
                        i % 160,
                        i / 160
                    );
                }
                worst = worst.max(err);
            }
        }
        eprintln!("{name}: {lit} lit channels, worst error / tolerance {worst:.3}");
        assert!(lit > 5_000, "{name}: only {lit} lit channels");
        assert!(
            worst <= 1.0,
            "{name}: textures and texel factors differ: {worst:.3} × the tolerance"
        );
    }
}
