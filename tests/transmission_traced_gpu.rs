//! The GPU's traced volume exit (`shading.transmission_exit_ray =
//! "traced"`, shaders/transmission_traced.wgsl) against the f64
//! reference, on the case the thickness read cannot draw: a ball lens.
//!
//! A clear glass sphere (index 1.5, radius 0.6, `thickness` its diameter)
//! at the origin, seen from `(0, 0, 5)`, before a wall of two emitters at
//! z = −2: one colour left of x = 0, another right of it. The ball's
//! focus lies `nR / (2(n − 1)) = 0.9` from its centre (the paraxial ball
//! lens formula), so the wall, 2 from the centre, is past it and the
//! sphere shows it inverted: left of the sphere's centre the right
//! emitter, and the other way round. The reference traces that exactly.
//! The thickness read (the Khronos sample renderer's) projects the point
//! `thickness` along the ray refracted in, which stays on the pixel's own
//! side, and shows the wall upright.
//!
//! **Tolerances, derived.** A test pixel sees one emitter of radiance `L`
//! through two interfaces; the reference's pixel also holds the light
//! the exit reflects inside and lets out at a later crossing, at most
//! `F_exit (1 − F) ≤ 0.05 L` at the angles of the test pixels (exact
//! Fresnel at index 1.5 stays below 0.05 up to 55° of incidence, and the
//! test pixels lie within 0.45 of the sphere's radius of its centre:
//! incidence below 27°), which the GPU leaves out. The image is stored in
//! half floats (`2⁻¹⁰` relative, once). The march finds each crossing
//! within `W / (32 · 2⁶)` pixels (W the march's length on screen, under
//! 64 here), under a pixel, and the pixels tested lie at least 3 pixels
//! from the image of the emitters' edge, so the read lands on the right
//! emitter. Hence a relative tolerance of `0.05 + 2⁻¹⁰` per channel
//! against the reference. The two colours differ per channel by far
//! more (0.7 against 0.1), so a read of the wrong emitter fails it by a
//! factor of 7 or more.

mod common;
mod transmission_scenes;

use glam::DVec3;
use gonio::frame::Frame;
use gonio::scene::{Rgb, Scene, TransmissionExitRay};

const SIZE: u32 = 64;
/// Half precision's relative rounding: `2⁻¹⁰`.
const HALF_ROUNDING: f64 = 1.0 / 1024.0;
/// The most the reference's internal reflections add, relative.
const INTERNAL_REFLECTIONS: f64 = 0.05;

/// Left and right emitters.
const LEFT: Rgb = Rgb::new(0.7, 0.3, 0.1);
const RIGHT: Rgb = Rgb::new(0.1, 0.45, 0.9);

/// Pixels (row, column) inside the sphere (about 22 pixels in radius
/// about (32, 32)), left of its centre; [`RIGHT_PIXELS`] mirrors them.
const LEFT_PIXELS: [(u32, u32); 4] = [(30, 24), (33, 25), (36, 24), (32, 27)];
const RIGHT_PIXELS: [(u32, u32); 4] = [(30, 40), (33, 39), (36, 40), (32, 37)];

/// The ball lens before the two emitters, the exit ray as `exit_ray`.
fn ball_lens(exit_ray: TransmissionExitRay) -> Scene {
    let meshes = vec![
        gonio::scene::primitives::uv_sphere(DVec3::ZERO, 0.6, 96, 0),
        transmission_scenes::cuboid(DVec3::new(-6.0, -6.0, -2.5), DVec3::new(0.0, 6.0, -2.0), 1),
        transmission_scenes::cuboid(DVec3::new(0.0, -6.0, -2.5), DVec3::new(6.0, 6.0, -2.0), 2),
    ];
    let mut glass = transmission_scenes::glass(1.5, 1.2);
    glass.roughness = 0.01;
    let materials = vec![
        glass,
        transmission_scenes::emitter(LEFT),
        transmission_scenes::emitter(RIGHT),
    ];
    let mut s = transmission_scenes::gpu_scene(SIZE, meshes, materials);
    s.transmission.exit_ray = exit_ray;
    s
}

fn pixel(frame: &Frame, (i, j): (u32, u32)) -> Rgb {
    transmission_scenes::pixel(frame, i, j)
}

/// The largest per-channel relative difference of `got` from `want`.
fn relative_error(got: Rgb, want: Rgb) -> f64 {
    got.to_array()
        .into_iter()
        .zip(want.to_array())
        .map(|(g, w)| (g - w).abs() / w.abs().max(1e-9))
        .fold(0.0, f64::max)
}

/// Whether `c` has the hue of `emitter` rather than the other one: blue
/// over red for the right emitter, red over blue for the left.
fn shows(c: Rgb, emitter: Rgb) -> bool {
    let [r, _, b] = c.to_array();
    (b > r) == (emitter == RIGHT)
}

/// The traced exit shows the ball lens's inverted image as the reference
/// does, within the tolerance derived above, at four pixels each side of
/// the sphere's centre; the thickness read shows each side's own emitter
/// there (checked, so the test tells the two apart).
#[test]
fn the_traced_exit_inverts_what_a_ball_lens_shows() {
    let traced = ball_lens(TransmissionExitRay::Traced);
    let reference = gonio::reference::render(&traced);
    let gpu = common::gpu_renderer().render(&traced).expect("GPU").0;
    let thickness = common::gpu_renderer()
        .render(&ball_lens(TransmissionExitRay::Thickness))
        .expect("GPU")
        .0;
    let tolerance = INTERNAL_REFLECTIONS + HALF_ROUNDING;
    for (pixels, seen) in [(LEFT_PIXELS, RIGHT), (RIGHT_PIXELS, LEFT)] {
        for p in pixels {
            let want = pixel(&reference, p);
            assert!(shows(want, seen), "reference at {p:?}: {want:?}");
            let got = pixel(&gpu, p);
            let error = relative_error(got, want);
            eprintln!(
                "{p:?}: reference {want:?}, traced {got:?} ({error:.4}), thickness {:?}",
                pixel(&thickness, p)
            );
            assert!(
                error <= tolerance,
                "traced at {p:?}: {got:?} against the reference's {want:?}: {error:.4} > {tolerance:.4}"
            );
            let upright = pixel(&thickness, p);
            assert!(
                !shows(upright, seen),
                "thickness read at {p:?}: {upright:?}"
            );
        }
    }
}
