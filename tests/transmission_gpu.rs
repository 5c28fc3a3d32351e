//! The GPU's screen-space transmission (src/gpu/transmission.rs,
//! shaders/transmission.wgsl) against the f64 reference, where the
//! method is exact up to the image's rounding, and where it is not, by
//! the factor its model leaves out (docs/transmission.md, "The GPU
//! renderer").
//!
//! The scenes look along −Z at emitters of known radiance behind glass,
//! with no light (one of no irradiance), no ambient light and no
//! environment, so a pixel on the
//! glass is the transmitted light alone (its reflection is a δ lobe at
//! roughness 0.01, which no light feeds).
//!
//! **Tolerance.** The GPU reads what lies behind from an `Rgba16Float`
//! image. Vulkan lets the conversion of a render target's output to
//! 16-bit float round to nearest or toward zero (lavapipe rounds toward
//! zero: 0.3 is stored as 0.2998, one unit below): a relative error below
//! one unit in the last of the 10 stored bits, `2⁻¹⁰`, for the normal
//! halves used here; the light is stored once per image it passes
//! through. At roughness 0.01 (0.0104 after the pixel
//! footprint's floor) the level of detail is `log2(64) · 0.0104 ≈ 0.06`:
//! the trilinear read mixes 6 % of level 1, whose texels are means of
//! level 0's, so inside a region of one radiance it reads that radiance.
//! The test pixels lie at least 8 pixels from any edge of a region (the
//! 2 × 2 footprint of levels 0 and 1 is 3 pixels). The weight
//! `1 − F(μ_o)` is evaluated by both renderers at the pixel's centre
//! (one sample per pixel, no MSAA), the GPU in f32 from an interpolated
//! position (a relative error of order 10⁻⁶). Hence the relative
//! tolerance `k · 2⁻¹⁰ + 10⁻⁵` for light read through `k` images.

mod common;
mod transmission_scenes;

use glam::DVec3;
use gonio::frame::Frame;
use gonio::material::{Material, ReflectanceModel};
use gonio::scene::{Mesh, Rgb, Scene, TransmissionSettings};

/// Half precision's relative rounding, to nearest or toward zero: `2⁻¹⁰`.
const HALF_ROUNDING: f64 = 1.0 / 1024.0;
/// The f32 arithmetic and the interpolated position, relative.
const F32_SLACK: f64 = 1e-5;
const SIZE: u32 = 64;

fn scene(meshes: Vec<Mesh>, materials: Vec<Material>) -> Scene {
    transmission_scenes::gpu_scene(SIZE, meshes, materials)
}

/// An emitter of radiance `radiance` and nothing else.
fn emitter(name: &str, radiance: Rgb) -> Material {
    let mut m = Material::new(name, ReflectanceModel::Lambert);
    m.k_d = Rgb::ZERO;
    m.k_a = Rgb::ZERO;
    m.emission = radiance;
    m
}

/// A white, smooth glass of index 1.5 (transmission 1), thin-walled at
/// `thickness = 0`.
fn glass(name: &str, thickness: f64) -> Material {
    let mut m = Material::new(name, ReflectanceModel::GltfPbr);
    m.base_color = Rgb::ONE;
    m.k_a = Rgb::ZERO;
    m.roughness = 0.01;
    m.layers.ior = 1.5;
    m.layers.transmission = 1.0;
    m.layers.thickness = thickness;
    m
}

/// The rectangle `[x0, x1] × [y0, y1]` at `z`, facing +Z.
fn rect(z: f64, (x0, x1): (f64, f64), (y0, y1): (f64, f64), material: usize) -> Mesh {
    let p = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| DVec3::new(x, y, z));
    Mesh::with_generated_normals("rect", p.to_vec(), vec![[0, 1, 2], [0, 2, 3]], material)
}

/// The box `[lo, hi]` with outward faces, each face its own vertices.
fn cuboid(lo: DVec3, hi: DVec3, material: usize) -> Mesh {
    let c = |x: bool, y: bool, z: bool| {
        DVec3::new(
            if x { hi.x } else { lo.x },
            if y { hi.y } else { lo.y },
            if z { hi.z } else { lo.z },
        )
    };
    let (f, t) = (false, true);
    let faces = [
        [c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)],
        [c(f, f, f), c(f, t, f), c(t, t, f), c(t, f, f)],
        [c(t, f, f), c(t, t, f), c(t, t, t), c(t, f, t)],
        [c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)],
        [c(f, t, f), c(f, t, t), c(t, t, t), c(t, t, f)],
        [c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)],
    ];
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for face in faces {
        let base = positions.len() as u32;
        positions.extend(face);
        indices.push([base, base + 1, base + 2]);
        indices.push([base, base + 2, base + 3]);
    }
    Mesh::with_generated_normals("box", positions, indices, material)
}

fn pixel(frame: &Frame, i: u32, j: u32) -> Rgb {
    frame.radiance[frame.index(i, j)].map(f64::from).into()
}

/// Asserts `got` is `want` per channel within `relative`.
fn assert_close(what: &str, got: Rgb, want: Rgb, relative: f64) {
    for (g, w) in got.to_array().into_iter().zip(want.to_array()) {
        assert!(
            (g - w).abs() <= relative * w.abs() + 1e-9,
            "{what}: GPU {got:?}, expected {want:?} (relative tolerance {relative:.2e})"
        );
    }
}

fn gpu(scene: &Scene) -> Frame {
    common::gpu_renderer().render(scene).expect("GPU render").0
}

/// Pixels (row, column) at least 8 pixels inside each half of the image
/// (left: the first emitter, right: the second) and inside the glass.
const LEFT: [(u32, u32); 3] = [(20, 12), (32, 16), (44, 20)];
const RIGHT: [(u32, u32); 3] = [(20, 44), (32, 48), (44, 52)];

/// Two emitters side by side at z = −1 (left and right of x = 0) behind
/// `glass_meshes`.
fn behind_glass(glass_meshes: Vec<Mesh>, glass: Vec<Material>) -> (Scene, Rgb, Rgb) {
    let (left, right) = (Rgb::new(0.7, 0.3, 0.1), Rgb::new(0.1, 0.45, 0.9));
    let n = glass.len();
    let mut meshes = glass_meshes;
    meshes.push(rect(-1.0, (-2.0, 0.0), (-2.0, 2.0), n));
    meshes.push(rect(-1.0, (0.0, 2.0), (-2.0, 2.0), n + 1));
    let mut materials = glass;
    materials.push(emitter("left", left));
    materials.push(emitter("right", right));
    (scene(meshes, materials), left, right)
}

/// A thin-walled pane over two emitters: straight through, weight
/// `1 − F(μ_o)` (the reference's smooth thin wall), the image read at the
/// pixel itself, so each half shows its own emitter. Drawn as opaque
/// (`shading.transmission = "off"`, the GPU before the pass) the pane is
/// black: the test fails without the pass.
#[test]
fn a_thin_pane_passes_what_lies_straight_behind() {
    let (scene, left, right) = behind_glass(
        vec![rect(0.0, (-1.0, 1.0), (-1.0, 1.0), 0)],
        vec![glass("pane", 0.0)],
    );
    let reference = gonio::reference::render(&scene);
    let frame = gpu(&scene);
    let tolerance = HALF_ROUNDING + F32_SLACK;
    for (points, behind) in [(LEFT, left), (RIGHT, right)] {
        for (i, j) in points {
            let want = pixel(&reference, i, j);
            // The reference's pixel is (1 − F) times the emitter, F ≥ 4 %.
            let share = want.to_array()[0] / behind.to_array()[0];
            assert!((0.9..0.961).contains(&share), "reference share {share}");
            assert_close(
                &format!("pane at ({i}, {j})"),
                pixel(&frame, i, j),
                want,
                tolerance,
            );
        }
    }
    let mut off = scene.clone();
    off.transmission.mode = gonio::scene::TransmissionMode::Off;
    let opaque = gpu(&off);
    assert_eq!(pixel(&opaque, 16, 32), Rgb::ZERO, "drawn as opaque");
}

/// A thin pane whose transmission is textured (`transmission_texture`,
/// glTF's `transmissionTexture` R): a 2 × 1 image read NEAREST, 1 over
/// the left half of the pane and 0.25 over the right. Both renderers
/// multiply the factor by the texel, so each half passes its share of
/// its emitter, `T (1 − F)`; where it does not pass (`1 − T`) the white
/// base reflects no light. Tolerance as for the untextured pane; the
/// shares are checked on the reference, so a renderer that ignored the
/// texture would fail.
#[test]
fn a_transmission_texture_scales_what_the_pane_passes() {
    use gonio::material::texture::{Filter, MaterialTexture, Sampler, TextureTarget};
    use gonio::scene::texture::{Encoding, Image, decode::Decoded};
    let mut pane = rect(0.0, (-1.0, 1.0), (-1.0, 1.0), 0);
    let uvs = pane
        .positions
        .iter()
        .map(|p| glam::DVec2::new(0.5 * (p.x + 1.0), 0.5 * (1.0 - p.y)))
        .collect();
    pane.tex_coords = vec![uvs];
    let mut material = glass("textured pane", 0.0);
    material.textures.push(MaterialTexture {
        target: TextureTarget::Param("transmission"),
        image: 0,
        channel: 0,
        tex_coord: 0,
        transform: Default::default(),
        sampler: Sampler {
            mag: Filter::Nearest,
            min: Filter::Nearest,
            mipmap: None,
            ..Default::default()
        },
    });
    let (mut scene, left, right) = behind_glass(vec![pane], vec![material]);
    scene.images.push(std::sync::Arc::new(Image::new(
        "transmission",
        Encoding::Linear,
        Decoded {
            width: 2,
            height: 1,
            rgba: vec![[1.0, 1.0, 1.0, 1.0], [0.25, 1.0, 1.0, 1.0]],
        },
    )));
    let reference = gonio::reference::render(&scene);
    let frame = gpu(&scene);
    let tolerance = HALF_ROUNDING + F32_SLACK;
    for (points, behind, texel) in [(LEFT, left, 1.0), (RIGHT, right, 0.25)] {
        for (i, j) in points {
            let want = pixel(&reference, i, j);
            // T (1 − F), F ≥ 4 % at these angles.
            let share = want.to_array()[0] / behind.to_array()[0] / texel;
            assert!(
                (0.9..0.961).contains(&share),
                "reference share {share} of T = {texel}"
            );
            assert_close(
                &format!("textured pane at ({i}, {j})"),
                pixel(&frame, i, j),
                want,
                tolerance,
            );
        }
    }
}

/// A green slab (a closed box, attenuation distance 0.5) of two
/// thicknesses in front of an emitter, seen at normal incidence (the
/// image's centre). The GPU attenuates by Beer–Lambert over the
/// thickness, `a = c^(d/D)`, and weights both interfaces,
/// `(1 − F)² a L` (one with `shading.transmission_exit = false`, the
/// sample renderer's `(1 − F) a L`); the reference also follows every
/// internal reflection, `(1 − F)² a L / (1 − F² a²)`, F = 0.04
/// (tests/transmission.rs checks it). So the GPU's pixel is the
/// reference's times `1 − F² a²` (times `1/(1 − F)` more with one
/// interface), the factor its model leaves out, and the ratio of the two
/// thicknesses' pixels is exactly `c^(Δd/D)`.
#[test]
fn an_attenuating_slab_follows_beer_lambert() {
    let colour = Rgb::new(0.3, 0.9, 0.4);
    let distance = 0.5;
    let behind = Rgb::new(0.8, 0.8, 0.8);
    let f = 0.04;
    let mut gpu_pixels = Vec::new();
    for (d, exit) in [(0.2, true), (0.6, true), (0.2, false)] {
        let mut slab = glass("slab", d);
        slab.layers.attenuation_color = colour;
        slab.layers.attenuation_distance = distance;
        let meshes = vec![
            cuboid(
                DVec3::new(-1.0, -1.0, -d / 2.0),
                DVec3::new(1.0, 1.0, d / 2.0),
                0,
            ),
            rect(-1.0, (-2.0, 2.0), (-2.0, 2.0), 1),
        ];
        let mut scene = scene(meshes, vec![slab, emitter("behind", behind)]);
        scene.transmission.exit = exit;
        let reference = gonio::reference::render(&scene);
        let frame = gpu(&scene);
        // The centre pixel's ray is the axis (even size: the four
        // around it are within 0.3 % of normal incidence in F).
        let (i, j) = (SIZE / 2, SIZE / 2);
        let a = colour.map(|c| c.powf(d / distance));
        let one_interface = if exit { 1.0 } else { 1.0 / (1.0 - f) };
        let model = a.map(|a| (1.0 - f * f * a * a) * one_interface);
        let want = pixel(&reference, i, j) * model;
        // F at the pixel's centre, 0.09° off the axis, is F(0) within
        // 10⁻⁸; the reference's closed form within 10⁻⁷.
        assert_close(
            &format!("slab d = {d}, exit {exit}"),
            pixel(&frame, i, j),
            want,
            HALF_ROUNDING + F32_SLACK,
        );
        gpu_pixels.push(pixel(&frame, i, j));
    }
    let ratio = gpu_pixels[1] / gpu_pixels[0];
    let beer = colour.map(|c| c.powf(0.4 / distance));
    // Each pixel rounded once: twice the rounding on the ratio.
    assert_close(
        "Beer–Lambert ratio",
        ratio,
        beer,
        2.0 * HALF_ROUNDING + F32_SLACK,
    );
}

/// `KHR_materials_volume`'s thickness is in mesh space: a slab made
/// 0.3 thick and scaled by 2 (`Mesh::transform`, as a glTF node's scale
/// is applied on import) is 0.6 thick in the world, where the reference
/// traces it. The GPU scales the material's 0.3 by the mesh's
/// `volume_scale` (the draw's first instance), so its pixel is the
/// reference's times `1 − F² a²`, `a = c^(0.6/D)`, as in
/// [`an_attenuating_slab_follows_beer_lambert`]; the thickness unscaled
/// would pass `c^(−0.3/D)` more light (2.1× in red).
#[test]
fn a_node_scale_scales_the_volumes_thickness() {
    let colour = Rgb::new(0.3, 0.9, 0.4);
    let distance = 0.5;
    let behind = Rgb::new(0.8, 0.8, 0.8);
    let f = 0.04;
    let (d, scale) = (0.3, 2.0);
    let mut slab = glass("slab", d);
    slab.layers.attenuation_color = colour;
    slab.layers.attenuation_distance = distance;
    let mut box_mesh = cuboid(
        DVec3::new(-0.5, -0.5, -d / 2.0),
        DVec3::new(0.5, 0.5, d / 2.0),
        0,
    );
    box_mesh.transform(glam::DMat4::from_scale(DVec3::splat(scale)));
    assert_eq!(box_mesh.volume_scale, scale);
    let meshes = vec![box_mesh, rect(-1.0, (-2.0, 2.0), (-2.0, 2.0), 1)];
    let scene = scene(meshes, vec![slab, emitter("behind", behind)]);
    let reference = gonio::reference::render(&scene);
    let frame = gpu(&scene);
    let (i, j) = (SIZE / 2, SIZE / 2);
    let a = colour.map(|c| c.powf(scale * d / distance));
    let want = pixel(&reference, i, j) * a.map(|a| 1.0 - f * f * a * a);
    assert_close(
        "slab 0.3 scaled by 2",
        pixel(&frame, i, j),
        want,
        HALF_ROUNDING + F32_SLACK,
    );
}

/// Glass behind glass: two thin panes, one behind the other, over the
/// emitters. The reference passes `(1 − F)²` of the light. With one
/// transmission layer the front pane reads the opaque scene's image, in
/// which the back pane is missing: `(1 − F)` (the screen-space method's
/// known failure, measured here); with two layers it reads the image
/// with the back pane drawn: `(1 − F)²`, through two images.
#[test]
fn glass_behind_glass_needs_a_second_layer() {
    let (base, _, _) = behind_glass(
        vec![
            rect(0.0, (-1.0, 1.0), (-1.0, 1.0), 0),
            rect(-0.5, (-1.5, 1.5), (-1.5, 1.5), 1),
        ],
        vec![glass("front", 0.0), glass("back", 0.0)],
    );
    let reference = gonio::reference::render(&base);
    let mut renderer = common::gpu_renderer();
    for layers in [1, 2] {
        let mut scene = base.clone();
        scene.transmission = TransmissionSettings {
            layers,
            ..Default::default()
        };
        let frame = renderer.render(&scene).expect("GPU render").0;
        for (i, j) in LEFT.into_iter().chain(RIGHT) {
            let want = pixel(&reference, i, j);
            let got = pixel(&frame, i, j);
            if layers == 2 {
                assert_close(
                    &format!("two layers at ({i}, {j})"),
                    got,
                    want,
                    2.0 * HALF_ROUNDING + F32_SLACK,
                );
            } else {
                // Missing the back pane's 1 − F(μ_o): these pixels are
                // within 7° of the axis, where F = 0.04 to 10⁻⁹.
                let ratio = got.to_array()[2] / want.to_array()[2];
                assert!(
                    (1.0 / 0.961..1.0 / 0.959).contains(&ratio),
                    "one layer at ({i}, {j}): GPU {got:?} / reference {want:?} = {ratio}"
                );
            }
        }
    }
}

/// The slab of index 1.7 and `dispersion` turned 40° in front of the
/// white/black edge ([`dispersion_refracts_each_channel_by_its_own_index`]).
fn turned_slab(dispersion: f64) -> Scene {
    turned_slab_before(dispersion, &[(-5.0, -0.6, 1), (-0.6, 5.0, 2)])
}

/// The turned slab before emitters at z = −4 spanning `[x0, x1]` each
/// (material 1 white, 2 black).
fn turned_slab_before(dispersion: f64, emitters: &[(f64, f64, usize)]) -> Scene {
    let mut slab = glass("slab", 2.0);
    slab.layers.ior = 1.7;
    slab.layers.dispersion = dispersion;
    let mut mesh = cuboid(DVec3::new(-3.0, -3.0, -1.0), DVec3::new(3.0, 3.0, 1.0), 0);
    mesh.transform(glam::DMat4::from_rotation_y(40f64.to_radians()));
    let mut meshes = vec![mesh];
    meshes.extend(
        emitters
            .iter()
            .map(|&(x0, x1, material)| rect(-4.0, (x0, x1), (-5.0, 5.0), material)),
    );
    let materials = vec![
        slab,
        emitter("white", Rgb::ONE),
        emitter("black", Rgb::ZERO),
    ];
    scene(meshes, materials)
}

/// Along the centre row of [`turned_slab`]'s image, the column where each
/// channel first falls below half its value at column 20 (the white).
fn edges(frame: &Frame) -> [u32; 3] {
    let row = SIZE / 2;
    let peak = pixel(frame, row, 20).to_array();
    [0, 1, 2].map(|c| {
        (20..SIZE - 8)
            .find(|&j| pixel(frame, row, j).to_array()[c] < 0.5 * peak[c])
            .expect("the edge is in view")
    })
}

/// The turned slab against the reference, which traces it spectrally
/// (41 wavelengths, each refracted by the Cauchy index of the Abbe
/// number, `n(λ) = a + b/λ²`, the spectrum converted to Rec.709: the
/// contract's dispersion): the GPU's three reads (red at `ior − s`, blue
/// at `ior + s`, the sample renderer's approximation) put each channel's
/// edge where one index puts it, the reference's channels are means over
/// the spectrum. Printed (`--nocapture`): the edges and the relative RMS
/// error (`bench::measure::error`) of the GPU against the spectral truth,
/// drawing the dispersion and ignoring it (`dispersion = 0` on the GPU).
/// Asserted: without dispersion the reference puts the three edges on one
/// column; with it, the GPU's spread from red's edge to blue's is closer
/// to the reference's than ignoring the dispersion (no spread) is. The
/// edges' place itself is the screen-space method's (docs/transmission.md,
/// "Dispersion against the spectral truth"), not compared.
#[test]
fn dispersion_on_the_gpu_against_the_spectral_reference() {
    use gonio::bench::measure::error;
    let truth = gonio::reference::render(&turned_slab(5.0));
    let drawn = gpu(&turned_slab(5.0));
    let ignored = gpu(&turned_slab(0.0));
    let (with, _) = error(&drawn, &truth);
    let (without, _) = error(&ignored, &truth);
    let plain = edges(&gonio::reference::render(&turned_slab(0.0)));
    let (t, d) = (edges(&truth), edges(&drawn));
    println!(
        "edges (R, G, B): reference {t:?}, GPU {d:?}, GPU ignoring dispersion {:?}; reference without dispersion {plain:?}",
        edges(&ignored)
    );
    println!("relative RMS against the spectral reference: drawn {with:.4}, ignored {without:.4}");
    assert!(plain[0] == plain[1] && plain[1] == plain[2], "{plain:?}");
    let spread = |e: [u32; 3]| e[2] as i64 - e[0] as i64;
    assert!(spread(t) > 0, "the reference disperses: {t:?}");
    assert!(
        (spread(d) - spread(t)).abs() < spread(t),
        "GPU spread {} vs the reference's {} (ignoring it: 0)",
        spread(d),
        spread(t)
    );
}

/// The traced exit (`shading.transmission_exit_ray = "traced"`,
/// shaders/transmission_traced.wgsl) on the turned slab: the ray
/// refracted in is marched to the slab's far face, leaves it parallel to
/// the view ray (parallel faces) and is marched on to the emitters, so
/// each channel's edge falls where the reference's traced ray puts it,
/// where the thickness read puts every edge 6–8 columns right
/// ("Dispersion against the spectral truth"). Tolerance, derived: the
/// reference's edge column is where one ray through the pixel's centre
/// crosses the emitters' edge; the GPU's march places its crossings
/// within `W / (32 · 2⁶)` pixels (W, its length on screen, under 128
/// here: under 0.07 pixels) and reads the image bilinearly, which blurs
/// the step by half a texel each side; so the half-value column is the
/// reference's or its neighbour: within 1 column, without dispersion
/// (one column for the three channels). With `dispersion = 5` the three
/// traced reads refract red, green and blue by one index each (the sample
/// renderer's `ior ∓ s`) where the reference's channels are means over 41
/// wavelengths: not the same model, so the same 1 column is asserted as
/// measured, not derived (2026-12-06: reference [33, 34, 35], traced
/// [33, 34, 34]). The relative RMS error against the reference is
/// printed (`--nocapture`) and asserted below the thickness read's.
#[test]
fn the_traced_exit_puts_the_slabs_edges_where_the_reference_does() {
    use gonio::bench::measure::error;
    use gonio::scene::TransmissionExitRay;
    let traced = |dispersion: f64| {
        let mut s = turned_slab(dispersion);
        s.transmission.exit_ray = TransmissionExitRay::Traced;
        s
    };
    for dispersion in [0.0, 5.0] {
        let truth = gonio::reference::render(&turned_slab(dispersion));
        let (drawn, read) = (gpu(&traced(dispersion)), gpu(&turned_slab(dispersion)));
        let (t, d, r) = (edges(&truth), edges(&drawn), edges(&read));
        let ((traced_rms, _), (read_rms, _)) = (error(&drawn, &truth), error(&read, &truth));
        println!(
            "dispersion {dispersion}: edges (R, G, B) reference {t:?}, traced {d:?}, thickness read {r:?}; relative RMS traced {traced_rms:.4}, thickness read {read_rms:.4}"
        );
        for c in 0..3 {
            assert!(
                t[c].abs_diff(d[c]) <= 1,
                "dispersion {dispersion}, channel {c}: traced edge {d:?}, reference {t:?}"
            );
            assert!(t[c].abs_diff(r[c]) > 1, "the thickness read: {r:?}");
        }
        assert!(traced_rms < read_rms, "{traced_rms} vs {read_rms}");
    }
}

/// What the screen-space method cannot read: light from outside the
/// frame. The slab of [`turned_slab`] (index 1.7, no dispersion) bends
/// the view rays towards −X, before a black emitter left of x = −1.8, a
/// white one from there to x = −0.6 and a black one right of it; the
/// frame's left border meets the emitters near x = −1.6, so the pixels
/// next to it see, through the slab, the black beyond the border. The
/// GPU reads its image of what lies behind where the refracted ray
/// leaves the slab; a read left of the frame is clamped to its first
/// column (white). The same camera with the image twice as wide (the
/// vertical field of view, so the projection, unchanged: its middle half
/// is the narrow frame where no read leaves it, checked) holds the black
/// on screen. Printed (`--nocapture`): the centre row's white run in the
/// reference and in both GPU frames, and the mean |difference| over the
/// 16 border columns between the two frames and from each to the
/// reference (docs/transmission.md, "Where the screen-space method
/// fails"). Asserted: the narrow frame's border band reads white where
/// the wide frame's reads the black beyond the border (the clamped read
/// is what the method loses), by more than the two images' rounding.
#[test]
fn a_read_outside_the_frame_is_what_the_screen_space_method_misses() {
    let scene_of = |width: u32| {
        let mut s = turned_slab_before(0.0, &[(-8.0, -1.8, 2), (-1.8, -0.6, 1), (-0.6, 8.0, 2)]);
        s.width = width;
        s
    };
    let narrow = scene_of(SIZE);
    let truth = gonio::reference::render(&narrow);
    let (cut, wide) = (gpu(&narrow), gpu(&scene_of(2 * SIZE)));
    let offset = SIZE / 2;
    let at = |f: &Frame, i: u32, j: u32| pixel(f, i, j);
    // The wide frame's middle half is the narrow frame where no read
    // leaves it (the right half of the narrow frame): equal but at the
    // white/black edge, which the two images' mip chains (64 and 128
    // wide) blur a little differently, so equal on average.
    let mut differs = 0.0;
    for i in 8..SIZE - 8 {
        for j in SIZE / 2..SIZE - 8 {
            differs += (at(&cut, i, j) - at(&wide, i, j + offset))
                .abs()
                .max_element();
        }
    }
    let differs = differs / ((SIZE - 16) * (SIZE / 2 - 8)) as f64;
    assert!(
        differs <= HALF_ROUNDING,
        "the middle half differs by {differs} on average"
    );
    let white_run = |f: &Frame, o: u32| {
        let white: Vec<u32> = (0..SIZE)
            .filter(|&j| at(f, SIZE / 2, j + o).x > 0.5)
            .collect();
        (white[0], white[white.len() - 1])
    };
    println!(
        "white along the centre row (columns): reference {:?}, GPU narrow {:?}, GPU wide {:?}",
        white_run(&truth, 0),
        white_run(&cut, 0),
        white_run(&wide, offset)
    );
    let band = |a: &dyn Fn(u32, u32) -> Rgb, b: &dyn Fn(u32, u32) -> Rgb| {
        let mut sum = 0.0;
        for i in 8..SIZE - 8 {
            for j in 0..16 {
                sum += (a(i, j) - b(i, j)).abs().element_sum() / 3.0;
            }
        }
        sum / ((SIZE - 16) * 16) as f64
    };
    let narrow_px = |i, j| at(&cut, i, j);
    let wide_px = |i, j| at(&wide, i, j + offset);
    let truth_px = |i, j| at(&truth, i, j);
    let lost = band(&narrow_px, &wide_px);
    println!(
        "mean |difference| over the 16 border columns: narrow − wide {lost:.4}; against the reference: narrow {:.4}, wide {:.4}",
        band(&narrow_px, &truth_px),
        band(&wide_px, &truth_px)
    );
    assert!(lost > 4.0 * HALF_ROUNDING, "the border band: {lost}");
}

/// Dispersion (`KHR_materials_dispersion`) as the sample renderer draws
/// it: one read of the image per channel, red refracted with `ior − s`
/// and blue with `ior + s`. A slab 2 thick turned 40° about +Y (its
/// normal towards +X; 6 wide, so its front face fills the view) in front
/// of a white emitter left of x = −0.6 and a black one right of it: the view ray refracted into the slab runs
/// 1.90 back and 0.61 towards −X at `ior` = 1.7, so the pixels near the
/// centre read the emitters' edge; a larger index bends it further
/// towards −N. Along the centre row, the column where each channel first
/// falls below half the white's is the same for all three without
/// dispersion; with `dispersion = 5` (V_d = 4, indices 1.6125, 1.7,
/// 1.7875) the reads part by 0.040 towards −X per step of index (red's
/// edge measured 3 columns left of blue's): red falls first, blue last.
/// Ignoring the dispersion (one read) fails the second case.
#[test]
fn dispersion_refracts_each_channel_by_its_own_index() {
    let edges = |dispersion: f64| edges(&gpu(&turned_slab(dispersion)));
    let plain = edges(0.0);
    assert!(
        plain[0] == plain[1] && plain[1] == plain[2],
        "no dispersion: one edge, {plain:?}"
    );
    let dispersed = edges(5.0);
    assert!(
        dispersed[0] < dispersed[2] && dispersed[0] <= dispersed[1] && dispersed[1] <= dispersed[2],
        "dispersion: red's edge left of blue's, {dispersed:?} (without: {plain:?})"
    );
}
