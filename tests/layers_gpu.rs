//! The layers of the glTF material (contract: "Layered glTF materials")
//! rendered by the GPU against the f64 reference, pixel by pixel, as
//! tests/gpu_vs_cpu.rs compares the lecture's models: the built-in
//! scene's ball as a scene-file `gltf-pbr` material with each layer
//! alone, all of them together, the two maps that are not multipliers
//! (`clearcoat_normal_texture`, `anisotropy_texture` with a rotation) and
//! textures on layer keys, under the built-in point light.
//!
//! Tolerance: the derivation of tests/gpu_vs_cpu.rs (`common::tolerance`:
//! the light loop's roundings, the narrowest lobe's slope error, the
//! pixel-position jitter, the textures' level-of-detail spread), plus per
//! layer what the GPU's evaluation adds beyond it ([`layer_rel`]):
//! * the coat's own GGX lobe: its slope error `128ε/α_c`, as the base's;
//! * the sheen: Vulkan's `exp` (163 ulp) and `log` (3 ulp × the exponent ≤
//!   80) of Charlie's power, the series/`log` hand-over's 2⁻²¹ absolute
//!   times `1/(2α_sh)`, Λ's `exp` and `pow` (tests/layer_equivalence.rs,
//!   `SHEEN_V_ERROR`), and the GPU's table of `E` where the reference
//!   integrates it exactly: the scaling moves by `max₃(c_sh) ΔE`, a
//!   relative `max₃(c_sh) ΔE / σ_min` of `f_r ≥ σ · below`, with `ΔE` the
//!   table's largest error at this `sheen_roughness` (measured here
//!   against the quadrature) and `σ_min` the smallest scaling;
//! * the thin film: its phases `m·OPD·p_k` (up to ~30 rad) rounded in f32
//!   (16 roundings of the phase, plus 4 ulp of `cos`), through the Airy
//!   sum to `F_ir` (`film_phase_bound`), relative to the smallest Fresnel
//!   term `F*` the film gives over the view angles (the dielectric's
//!   `(1 − max₃ F*) b/π + F* S` moves by `ι ΔF (b/π + S)`);
//! * the anisotropy direction: rounded once from f64, within the light
//!   loop's 64ε.

mod common;

use gonio::frame::Frame;
use gonio::material::brdf::gltf_layers::iridescence::{
    SENSITIVITY_NORM, SENSITIVITY_P, SENSITIVITY_SIGMA, SENSITIVITY_V, SENSITIVITY_X2,
    XYZ_TO_REC709, iridescence_fresnel,
};
use gonio::material::brdf::gltf_layers::sheen::sheen_alpha;
use gonio::material::brdf::gltf_layers::sheen_albedo::{
    sheen_albedo_lookup, sheen_table_error_bound,
};
use gonio::material::brdf::gltf_layers::sheen_albedo_nodes::SHEEN_ALBEDO_NODES;
use gonio::material::{Material, ReflectanceModel};
use gonio::output::compare::{Comparison, Tolerance, compare_with_jitter, compare_with_spreads};
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Rgb, Scene};
use std::f64::consts::{PI, TAU};

const EPS: f64 = 1.0 / 16_777_216.0;

fn asset(name: &str) -> String {
    format!("{}/assets/scenes/layers/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn load(extra: &[String]) -> Scene {
    let mut sets = vec![
        "image.width=120".to_string(),
        "image.height=90".to_string(),
        "shading.mode=phong".to_string(),
        "materials.ball.model=gltf-pbr".to_string(),
        "materials.ball.base_color=[0.6, 0.25, 0.1]".to_string(),
        "materials.ball.metallic=0".to_string(),
        "materials.ball.roughness=0.4".to_string(),
    ];
    sets.extend(extra.iter().cloned());
    scene_file::load(&SceneSource::BuiltIn, &sets).expect("scene loads")
}

/// The sheen table's error bound at `r` (its documented bound,
/// `sheen_table_error_bound`, measured by tests/layer_equivalence.rs)
/// and the largest `E` at `r`: the table's largest value over `μ` plus
/// that bound.
fn sheen_table_error(r: f64) -> (f64, f64) {
    let bound = sheen_table_error_bound(r);
    let table_max = (0..=1000).fold(0.0f64, |e, i| {
        let mu = f64::from(i) / 1000.0;
        e.max(sheen_albedo_lookup(mu, r, &SHEEN_ALBEDO_NODES))
    });
    (bound, table_max + bound)
}

/// `|ΔF_ir|` from the f32 phases: each `cos(m·p_k ψ + m φ_k)` of the
/// XYZ-Fourier sensitivity off by `Δ = 16ε |phase| + 4ε`, through `M` and
/// the Airy coefficients (`|C_m| ≤ 2 (2 + F_ir)` summed over m = 1, 2, as
/// tests/layer_equivalence.rs bounds them).
fn film_phase_bound(m: &Material, f_max: f64) -> f64 {
    let l = &m.layers;
    let n2 = l.iridescence_ior.max(1.0);
    let opd = 2.0 * n2 * l.iridescence_thickness;
    let amplitude: [f64; 3] = std::array::from_fn(|k| {
        let mut a = SENSITIVITY_V[k] * (TAU * SENSITIVITY_SIGMA[k]).sqrt();
        if k == 0 {
            a += SENSITIVITY_X2[0] * (TAU * SENSITIVITY_X2[2]).sqrt();
        }
        a / SENSITIVITY_NORM
    });
    let p_max = SENSITIVITY_P
        .iter()
        .fold(SENSITIVITY_X2[1], |a, &p| a.max(p));
    let phase = 2.0 * (p_max * TAU * opd * 1e-9) + 2.0 * PI;
    let delta = 16.0 * EPS * phase + 4.0 * EPS;
    let row = (0..3)
        .map(|c| {
            (0..3)
                .map(|k| XYZ_TO_REC709[c][k].abs() * amplitude[k])
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    2.0 * 2.0 * (2.0 + f_max) * row * delta
}

/// The relative error the layers add beyond `common::tolerance` (module
/// doc).
fn layer_rel(m: &Material) -> f64 {
    let l = &m.layers;
    let mut rel = 0.0;
    if l.has_clearcoat() && l.clearcoat_roughness > 0.0 {
        let alpha_c = (l.clearcoat_roughness * l.clearcoat_roughness).max(1e-4);
        rel += 128.0 * EPS / alpha_c;
    }
    if l.has_sheen() {
        let alpha = sheen_alpha(l.sheen_roughness);
        let log_error = 1.0 / 2_097_152.0;
        let lobe = (163.0 + 240.0 + 53.0 + 64.0) * EPS
            + log_error / (2.0 * alpha)
            + 6.4 * 0.2 * std::f64::consts::LN_2 * log_error;
        let c = l.sheen_color.max_element();
        let (delta_e, e_max) = sheen_table_error(l.sheen_roughness);
        let sigma_min = 1.0 - c * e_max;
        assert!(
            sigma_min > 0.05,
            "the test's sheen leaves σ ≥ 0.05 (σ_min {sigma_min})"
        );
        rel += lobe + c * delta_e / sigma_min;
    }
    if l.has_iridescence() {
        let f0 = gonio::material::brdf::gltf_layers::base_ior_specular::dielectric_f0(
            l.ior,
            l.specular_color,
        ) * l.specular;
        let f_max = (0..=200).fold(0.0f64, |f_max, i| {
            let cos = (i as f64 / 200.0).max(1e-3);
            let film = iridescence_fresnel(cos, l.iridescence_ior, l.iridescence_thickness, f0);
            let metal = iridescence_fresnel(
                cos,
                l.iridescence_ior,
                l.iridescence_thickness,
                m.base_color,
            );
            f_max.max(film.max_element()).max(metal.max_element())
        });
        rel += l.iridescence * film_phase_bound(m, f_max) * film_gain(m);
    }
    rel
}

/// How much an error `ΔF` of the film's Fresnel term moves `f_r`,
/// relative to `f_r`, at its largest over a grid of directions (θ_i, θ_o
/// to 88°, Δφ over [0, π]): the dielectric's `(1 − max₃ F*) b/π + F* S`
/// and the metal's `F_metal S` move by at most `ΔF ((1 − m) b/π + S)` per
/// channel (through the sheen's and the coat's scalings, which are ≤ 1),
/// against the material's own `f_r` in the same directions. `S` is the
/// base lobe `D·Vis` (with the anisotropy), the `f_r` of a white metal
/// of the same roughness. This replaces `ΔF · max(1/F*_min, 1/(1 − F_max))`,
/// which a film's near-zero `F*` (destructive interference) made 10³.
fn film_gain(m: &Material) -> f64 {
    let frame = gonio::material::brdf::SurfaceFrame {
        n: glam::DVec3::Z,
        t: glam::DVec3::X,
        b: glam::DVec3::Y,
    };
    let mut lobe = Material::new("lobe", ReflectanceModel::GltfPbr);
    lobe.base_color = Rgb::ONE;
    lobe.metallic = 1.0;
    lobe.roughness = m.roughness;
    lobe.energy_compensation = false;
    lobe.layers.anisotropy_strength = m.layers.anisotropy_strength;
    lobe.layers.anisotropy_rotation = m.layers.anisotropy_rotation;
    let dir = |theta: f64, phi: f64| {
        glam::DVec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    };
    let mut gain = 0.0f64;
    for i in 0..=22 {
        for o in 0..=22 {
            for k in 0..=8 {
                let deg = std::f64::consts::PI / 180.0;
                let wi = dir(f64::from(i) * 4.0 * deg, 0.0);
                let wo = dir(f64::from(o) * 4.0 * deg, f64::from(k) * PI / 8.0);
                let f = m.f_r(wi, wo, &frame);
                let s = lobe.f_r(wi, wo, &frame);
                for c in 0..3 {
                    let moved = (1.0 - m.metallic) * m.base_color[c] / PI + s[c];
                    gain = gain.max(moved / f[c].max(1e-300));
                }
            }
        }
    }
    gain
}

/// Renders both sides and compares under the tolerance with the layers'
/// terms; prints one row.
fn layered_vs_reference(label: &str, scene: &Scene) -> Comparison {
    let ball = scene
        .materials
        .iter()
        .find(|m| m.name == "ball")
        .expect("the ball");
    assert_eq!(ball.model, ReflectanceModel::GltfPbr);
    assert!(!ball.gltf_layers_used().is_empty() || label.starts_with("core"));
    let mut renderer = common::gpu_renderer();
    let (gpu, _) = renderer.render(scene).expect("GPU render");
    let (center, jittered) = common::reference_with_jitter(scene);
    let finite = |f: &Frame| f.radiance.iter().flatten().all(|v| v.is_finite());
    assert!(finite(&gpu), "{label}: the GPU frame has NaN or Inf");
    assert!(finite(&center), "{label}: the reference has NaN or Inf");
    let base = common::tolerance(scene, &center);
    let extra = scene
        .effective_materials()
        .iter()
        .map(layer_rel)
        .fold(0.0, f64::max);
    let tol = Tolerance {
        rel: base.rel + extra,
        abs: base.abs,
    };
    let c = if scene.has_textures() {
        let (low, high) = common::lod_envelope(scene, &center);
        compare_with_spreads(
            &gpu,
            &center,
            &[
                (&jittered[0], &jittered[1]),
                (&jittered[2], &jittered[3]),
                (&low, &high),
            ],
            tol,
        )
    } else {
        compare_with_jitter(&gpu, &center, &jittered, tol)
    };
    eprintln!(
        "{label:<34} rel tol {:.2e} (layers {:.2e}) | {}",
        tol.rel,
        extra,
        c.summary()
    );
    assert!(
        c.compared > scene.width as usize * scene.height as usize / 10,
        "{label}: too few covered pixels"
    );
    common::assert_agrees(label, "GPU and reference disagree", &c, &gpu, &center);
    c
}

fn sets(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| format!("materials.ball.{s}")).collect()
}

/// Each layer alone, then all of them: the GPU's stack is the reference's.
#[test]
fn each_layer_renders_like_the_reference() {
    let cases: &[(&str, &[&str])] = &[
        ("core", &[]),
        (
            "ior, specular, specular_color",
            &["ior=1.8", "specular=0.7", "specular_color=[0.4, 0.9, 1.7]"],
        ),
        (
            "ior = 0 (specular-glossiness)",
            &["ior=0", "specular_color=[0.05, 0.04, 0.03]"],
        ),
        ("clearcoat", &["clearcoat=1.0", "clearcoat_roughness=0.1"]),
        (
            "sheen",
            &["sheen_color=[0.7, 0.5, 0.9]", "sheen_roughness=0.4"],
        ),
        (
            "iridescence",
            &[
                "iridescence=1.0",
                "iridescence_ior=1.3",
                "iridescence_thickness=450",
            ],
        ),
        (
            "anisotropy with a rotation",
            &[
                "metallic=1",
                "anisotropy_strength=0.8",
                "anisotropy_rotation=0.7",
            ],
        ),
        (
            "every layer",
            &[
                "metallic=0.3",
                "ior=1.6",
                "specular_color=[1.2, 1.0, 0.8]",
                "clearcoat=0.8",
                "clearcoat_roughness=0.15",
                "sheen_color=[0.3, 0.3, 0.5]",
                "sheen_roughness=0.5",
                "iridescence=0.5",
                "iridescence_thickness=350",
                "anisotropy_strength=0.6",
                "anisotropy_rotation=1.0",
            ],
        ),
    ];
    for (label, keys) in cases {
        let scene = load(&sets(keys));
        layered_vs_reference(label, &scene);
    }
}

/// The two maps that are not multipliers: the coat's own normal map (the
/// base keeps its normal) and the anisotropy direction map turned by the
/// rotation; then textures on layer keys, which multiply them.
#[test]
fn layer_maps_and_textures_render_like_the_reference() {
    let ripples = asset("ripples.png");
    let swirl = asset("swirl.png");
    let stripes = asset("stripes.png");
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "clearcoat_normal_texture",
            vec![
                "clearcoat=1.0".into(),
                "clearcoat_roughness=0.1".into(),
                format!("clearcoat_normal_texture=\"{ripples}\""),
            ],
        ),
        (
            "anisotropy_texture, rotation",
            vec![
                "metallic=1".into(),
                "anisotropy_strength=0.9".into(),
                "anisotropy_rotation=0.5".into(),
                format!("anisotropy_texture=\"{swirl}\""),
            ],
        ),
        (
            "textures on layer keys",
            vec![
                "clearcoat=1.0".into(),
                "clearcoat_roughness=0.2".into(),
                format!("clearcoat_texture=\"{stripes}\""),
                "sheen_color=[0.8, 0.7, 0.3]".into(),
                "sheen_roughness=0.5".into(),
                format!("sheen_color_texture=\"{stripes}\""),
                "iridescence=0.7".into(),
                "iridescence_thickness=600".into(),
                format!("iridescence_thickness_texture=\"{stripes}\""),
                "specular_color=[1.0, 0.8, 0.6]".into(),
                format!("specular_color_texture=\"{stripes}\""),
            ],
        ),
    ];
    for (label, keys) in cases {
        let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
        let scene = load(&sets(&keys));
        assert!(scene.has_textures(), "{label}: textured");
        layered_vs_reference(label, &scene);
    }
}

/// A material with a distinct image on each of 13 keys (the core's and the
/// layers', two normal maps among them): more textures than WebGPU's
/// guaranteed per-stage limits leave a material (11, `TextureBudget`), all
/// bound and read as the reference reads them. Each image a different
/// pattern and colour, so a texel read from the wrong binding shows.
#[test]
fn a_material_with_thirteen_distinct_textures_renders_like_the_reference() {
    let dir = std::env::temp_dir().join(format!("gonio-thirteen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let keys = [
        "base_color",
        "metallic",
        "roughness",
        "normal",
        "clearcoat",
        "clearcoat_roughness",
        "clearcoat_normal",
        "sheen_color",
        "sheen_roughness",
        "specular",
        "specular_color",
        "iridescence",
        "iridescence_thickness",
    ];
    let mut list: Vec<String> = [
        "metallic=0.5",
        "clearcoat=0.8",
        "clearcoat_roughness=0.3",
        "sheen_color=[0.8, 0.7, 0.3]",
        "sheen_roughness=0.5",
        "specular=0.9",
        "specular_color=[1.0, 0.8, 0.6]",
        "iridescence=0.7",
        "iridescence_thickness=600",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for (i, key) in keys.iter().enumerate() {
        // Stripes of period 4 + i texels, at an angle and in a colour of
        // their own; the normal maps gently tilted, so they stay maps.
        let path = dir.join(format!("{key}.png"));
        let normal = key.ends_with("normal");
        let image = image::RgbImage::from_fn(32, 32, |x, y| {
            let on = ((x + (i as u32 % 3) * y) / (4 + i as u32)).is_multiple_of(2);
            if normal {
                image::Rgb(if on { [150, 128, 240] } else { [110, 140, 240] })
            } else {
                let c = 60 + 14 * i as u8;
                image::Rgb(if on {
                    [255, c, 255 - c]
                } else {
                    [c, 255 - c, 90]
                })
            }
        });
        image.save(&path).unwrap();
        list.push(format!("{key}_texture=\"{}\"", path.display()));
    }
    let list: Vec<&str> = list.iter().map(String::as_str).collect();
    let scene = load(&sets(&list));
    let ball = scene.materials.iter().find(|m| m.name == "ball").unwrap();
    assert_eq!(ball.textures.len(), 13, "every key has its texture");
    assert_eq!(gonio::gpu::textures::binding_count(&scene), 13);
    layered_vs_reference("thirteen distinct textures", &scene);
    std::fs::remove_dir_all(&dir).ok();
}

/// The coat's normal map changes the picture (the test above would pass
/// on a renderer that ignores it only if it did not): with and without it
/// the reference differs, and the GPU follows (checked above).
#[test]
fn the_coat_normal_map_is_not_ignored() {
    let ripples = asset("ripples.png");
    let coat = sets(&["clearcoat=1.0", "clearcoat_roughness=0.1"]);
    let mut mapped = coat.clone();
    mapped.push(format!(
        "materials.ball.clearcoat_normal_texture=\"{ripples}\""
    ));
    let plain = gonio::reference::render(&load(&coat));
    let rippled = gonio::reference::render(&load(&mapped));
    let differing = plain
        .radiance
        .iter()
        .zip(&rippled.radiance)
        .filter(|(a, b)| {
            a.iter()
                .zip(b.iter())
                .any(|(x, y)| (x - y).abs() > 1e-3 * x.abs().max(1e-3))
        })
        .count();
    assert!(differing > 500, "{differing} pixels differ");
}
