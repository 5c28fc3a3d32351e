//! Khronos glTF conformance models (assets/gltf, CC0, unmodified), each
//! with an assertion that fails when the feature it tests is wrong, and
//! GPU against reference where a small image affords it.

mod common;

use gonio::frame::Frame;
use gonio::scene::Scene;
use gonio::scene::scene_file::{self, SceneSource};

fn load(relative: &str, sets: &[String]) -> Scene {
    scene_file::load(&SceneSource::File(common::gltf_asset(relative)), sets)
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
