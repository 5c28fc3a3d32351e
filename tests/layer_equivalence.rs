//! GPU = CPU for the layers of the glTF material (contract: "Layered glTF
//! materials"), layer by layer, every pair and the whole stack: the WGSL twins in
//! `shaders/brdf/gltf_layers/` run in a compute shader over ≥ 10⁵ samples
//! per case (directions to 89.99° and below the horizon, every layer
//! parameter over its range, the core's base colour, metallic, roughness
//! and energy compensation's ratio), against `gonio::material::brdf::
//! gltf_layers` in f64 on the same f32-rounded inputs.
//!
//! The sheen's albedos `E(μ_o)`, `E(μ_i)` are inputs of the compared
//! function (`gltf_layered_with_albedos`), the same f32 numbers on both
//! sides: the formulas are compared alone. The GPU's table of `E` is
//! measured against the exact quadrature separately
//! (`sheen_albedo_table_error`), and its effect on `f_r` is bounded there.
//!
//! Tolerance per sample, as tests/brdf_equivalence.rs derives it (backward
//! error analysis): `Σ_j max± |f(x ± Δ_j) − f(x)|` over every input `j`
//! moved by K = 64 roundings (directions absolutely, parameters
//! relatively), plus N = 64 roundings of the result, plus what Vulkan
//! allows the transcendental functions beyond rounding:
//! * (the anisotropy direction `(cos ρ, sin ρ)` is computed in f64 and
//!   rounded once, as the renderer uploads it: `t` and `b` move by the
//!   roundings of the direction's use, no transcendental allowance);
//! * the thin film's `cos` of the (reduced) phase: 2⁻¹¹ absolute per XYZ
//!   term, through `M` and the Airy coefficients to `F_ir`
//!   ([`film_cos_bound`]) and from `F_ir` to `f_r` at most
//!   `ι ((1 − m)(b/π + S (1 + ms)) + m S (1 + b ms))`;
//! * the sheen lobe (relative to it): `exp` 3 + 2|x| ≤ 163 ulp, `log` of
//!   `sin²θ_h` 3 ulp times the exponent (≤ 80: 240 ulp), and where the
//!   series of `ln(1 − cos²)` hands over to `log` (0.1 ≤ cos²θ_h < 0.5)
//!   Vulkan's 2⁻²¹ absolute times `1/(2α)`; Λ's `exp(l)` (≤ 53 ulp) and
//!   `pow(x, c)` inside `l` (2⁻²¹ · c · ln 2 · a/4): [`SHEEN_V_ERROR`].

mod common;

use glam::DVec3;
use gonio::gpu::shader_gen::{ShaderKey, compose_brdf_library};
use gonio::material::brdf::SurfaceFrame;
use gonio::material::brdf::gltf_layers::GltfLayers;
use gonio::material::brdf::gltf_layers::base_ior_specular::base_lobe;
use gonio::material::brdf::gltf_layers::iridescence::{
    SENSITIVITY_NORM, SENSITIVITY_SIGMA, SENSITIVITY_V, SENSITIVITY_X2, XYZ_TO_REC709,
};
use gonio::material::brdf::gltf_layers::sheen::{sheen_alpha, sheen_lobe};
use gonio::material::brdf::gltf_layers::sheen_albedo::{
    SHEEN_ALBEDO_COS_MIN, SHEEN_ALBEDO_TABLE_SIZE, sheen_albedo, sheen_albedo_lookup,
    sheen_table_error_bound,
};
use gonio::material::brdf::gltf_layers::stack::gltf_layered_with_albedos;
use gonio::material::brdf::microfacet::{half_vector, sin2_between};
use gonio::material::{Material, ReflectanceModel};
use gonio::scene::Rgb;
use std::collections::BTreeSet;
use std::f64::consts::{PI, TAU};
use wgpu::util::DeviceExt;

const SAMPLES_PER_CASE: usize = 100_000;
const U: f64 = 1.0 / 16_777_216.0;
const K_INPUT: f64 = 64.0;
const N_ASSEMBLY: f64 = 64.0;
/// Vulkan's absolute error of `sin` and `cos` on [−π, π].
const TRIG_ERROR: f64 = 1.0 / 2048.0;
/// Vulkan's absolute error of `log` on [0.5, 2].
const LOG_ERROR: f64 = 1.0 / 2_097_152.0;
/// The sheen visibility's relative error beyond rounding: `exp(l)` with
/// |l| ≤ 25 (53 ulp), and `x^c = exp2(c log2 x)` inside `l`: `log2` off
/// by 2⁻²¹ (or 3 ulp of a larger value), times `c ≤ 0.2` and ln 2, moves
/// `l` by at most `a/4 ≤ 6.4` times that relative error.
const SHEEN_V_ERROR: f64 = 53.0 * U + 6.4 * 0.2 * std::f64::consts::LN_2 * LOG_ERROR + 64.0 * U;

/// One evaluation.
#[derive(Clone, Debug)]
struct Sample {
    wi: DVec3,
    wo: DVec3,
    frame: SurfaceFrame,
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
    ms: f64,
    layers: GltfLayers,
    albedo_o: f64,
    albedo_i: f64,
}

fn halton(mut i: u64, base: u64) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= base as f64;
        r += f * (i % base) as f64;
        i /= base;
    }
    r
}

fn direction(theta_deg: f64, phi: f64) -> DVec3 {
    let t = theta_deg.to_radians();
    DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

fn r32(x: f64) -> f64 {
    x as f32 as f64
}

fn r32v(v: DVec3) -> DVec3 {
    v.as_vec3().as_dvec3()
}

/// Which layers a case sweeps (the others stay at their defaults).
#[derive(Clone, Copy)]
struct Case {
    base: bool,
    anisotropy: bool,
    iridescence: bool,
    sheen: bool,
    clearcoat: bool,
}

/// The layers' names, in the order of [`Case`]'s flags.
const LAYERS: [&str; 5] = [
    "base: ior, specular, specular_color",
    "anisotropy",
    "iridescence",
    "sheen",
    "clearcoat",
];

impl Case {
    /// The case with the layers whose bits are set in `mask` (bit k:
    /// `LAYERS[k]`).
    fn of(mask: u32) -> Case {
        let on = |k: u32| mask & (1 << k) != 0;
        Case {
            base: on(0),
            anisotropy: on(1),
            iridescence: on(2),
            sheen: on(3),
            clearcoat: on(4),
        }
    }

    fn name(self) -> String {
        let flags = [
            self.base,
            self.anisotropy,
            self.iridescence,
            self.sheen,
            self.clearcoat,
        ];
        let on: Vec<&str> = LAYERS
            .iter()
            .zip(flags)
            .filter_map(|(name, on)| on.then_some(*name))
            .collect();
        match on.len() {
            5 => "full stack".into(),
            1 => on[0].into(),
            _ => on
                .iter()
                .map(|n| n.split(':').next().unwrap_or(n))
                .collect::<Vec<_>>()
                .join(" + "),
        }
    }
}

/// Each layer alone, every pair of layers (where two layers meet in the
/// composition: the film on the base's Fresnel, the sheen's scaling of
/// an anisotropic or iridescent base, the coat over each), and the full
/// stack.
fn cases() -> Vec<Case> {
    let singles = (0..5).map(|k| 1 << k);
    let pairs = (0..5).flat_map(|a| (a + 1..5).map(move |b| (1 << a) | (1 << b)));
    singles
        .chain(pairs)
        .chain([0b11111])
        .map(Case::of)
        .collect()
}

// Sample values of each parameter, over its range (0 and the ends included).
const BASE_COLOR: &[f64] = &[0.0, 0.2, 0.5, 1.0];
const METALLIC: &[f64] = &[0.0, 0.25, 0.9, 1.0];
const ROUGHNESS: &[f64] = &[0.01, 0.03, 0.1, 0.3, 0.5, 1.0];
const MS: &[f64] = &[0.0, 0.0, 0.6];
const IOR: &[f64] = &[0.0, 1.0, 1.0001, 1.33, 1.5, 2.5, 5.0];
const SPECULAR: &[f64] = &[0.0, 0.5, 1.0];
const SPECULAR_COLOR: &[f64] = &[0.0, 0.5, 1.0, 2.5];
const STRENGTH: &[f64] = &[0.0, 0.2, 0.8, 1.0];
const ROTATION: &[f64] = &[0.0, 0.7, std::f64::consts::FRAC_PI_2, 3.0, -1.2];
const IRIDESCENCE: &[f64] = &[0.0, 0.5, 1.0];
const FILM_IOR: &[f64] = &[1.0, 1.3, 2.0, 3.0];
const THICKNESS: &[f64] = &[0.0, 0.01, 10.0, 100.0, 400.0, 1200.0];
const SHEEN_COLOR: &[f64] = &[0.0, 0.2, 1.0];
const SHEEN_ROUGHNESS: &[f64] = &[0.0, 0.01, 0.05, 0.2, 0.5, 1.0];
const CLEARCOAT: &[f64] = &[0.0, 0.3, 1.0];
const CLEARCOAT_ROUGHNESS: &[f64] = &[0.0, 0.01, 0.1, 0.3, 0.7, 1.0];
/// The coat's own normal (`clearcoat_normal_texture`) in the frame: the
/// shading normal, tilted ones, and one turned below the view's horizon
/// for some directions (`F_c` at `max(n_c·V, 0)`).
const COAT_NORMAL: &[[f64; 3]] = &[
    [0.0, 0.0, 1.0],
    [0.3, -0.2, 0.93],
    [-0.6, 0.5, 0.62],
    [0.9, 0.0, 0.44],
];

/// The GPU's table (the stored nodes, which the lib test
/// `sheen_table_is_current` checks against the quadrature).
fn table_nodes() -> &'static [f32] {
    &gonio::material::brdf::gltf_layers::sheen_albedo_nodes::SHEEN_ALBEDO_NODES
}

fn samples(case: Case) -> Vec<Sample> {
    let frame = SurfaceFrame {
        n: DVec3::Z,
        t: DVec3::X,
        b: DVec3::Y,
    };
    (0..SAMPLES_PER_CASE as u64)
        .map(|i| {
            let j = i + 1;
            let theta = |u: f64| {
                if u < 0.05 {
                    89.99 + u / 0.05 * 10.0
                } else {
                    (u - 0.05) / 0.95 * 89.99
                }
            };
            let wi = direction(theta(halton(j, 2)), halton(j, 3) * TAU);
            let wo = direction(theta(halton(j, 5)), halton(j, 7) * TAU);
            let wo = match i % 97 {
                0 => DVec3::new(-wi.x, -wi.y, wi.z),
                1 => wi,
                _ => wo,
            };
            // Each parameter steps through its list with its own prime
            // stride, so that combinations mix.
            let mut strides = [
                1u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71, 73,
                79, 83,
            ]
            .into_iter();
            let mut pick = |list: &[f64]| {
                let k = strides.next().unwrap();
                list[((i / k) % list.len() as u64) as usize]
            };
            let base_color = Rgb::new(pick(BASE_COLOR), pick(BASE_COLOR), pick(BASE_COLOR));
            let (metallic, roughness, ms) = (pick(METALLIC), pick(ROUGHNESS), pick(MS));
            let mut l = GltfLayers::default();
            if case.base {
                l.ior = pick(IOR);
                l.specular = pick(SPECULAR);
                l.specular_color = Rgb::new(
                    pick(SPECULAR_COLOR),
                    pick(SPECULAR_COLOR),
                    pick(SPECULAR_COLOR),
                );
            }
            if case.anisotropy {
                l.anisotropy_strength = pick(STRENGTH);
                l.anisotropy_rotation = pick(ROTATION);
            }
            if case.iridescence {
                l.iridescence = pick(IRIDESCENCE);
                l.iridescence_ior = pick(FILM_IOR);
                l.iridescence_thickness = pick(THICKNESS);
            }
            if case.sheen {
                l.sheen_color = Rgb::new(pick(SHEEN_COLOR), pick(SHEEN_COLOR), pick(SHEEN_COLOR));
                l.sheen_roughness = pick(SHEEN_ROUGHNESS);
            }
            if case.clearcoat {
                l.clearcoat = pick(CLEARCOAT);
                l.clearcoat_roughness = pick(CLEARCOAT_ROUGHNESS);
                let k = strides.next().unwrap();
                let c = COAT_NORMAL[((i / k) % COAT_NORMAL.len() as u64) as usize];
                l.clearcoat_normal = DVec3::from_array(c).normalize();
            }
            let layers = round_layers(&l);
            let (wi, wo) = (r32v(wi), r32v(wo));
            // The albedos both sides get: the table's, at these directions.
            let albedo = |c: f64| {
                r32(sheen_albedo_lookup(
                    c,
                    layers.sheen_roughness,
                    table_nodes(),
                ))
            };
            Sample {
                wi,
                wo,
                frame,
                base_color: r32v(base_color),
                metallic: r32(metallic),
                roughness: r32(roughness),
                ms: r32(ms),
                layers,
                albedo_o: albedo(wo.z),
                albedo_i: albedo(wi.z),
            }
        })
        .collect()
}

fn round_layers(l: &GltfLayers) -> GltfLayers {
    GltfLayers {
        ior: r32(l.ior),
        specular: r32(l.specular),
        specular_color: r32v(l.specular_color),
        clearcoat: r32(l.clearcoat),
        clearcoat_roughness: r32(l.clearcoat_roughness),
        sheen_color: r32v(l.sheen_color),
        sheen_roughness: r32(l.sheen_roughness),
        iridescence: r32(l.iridescence),
        iridescence_ior: r32(l.iridescence_ior),
        iridescence_thickness: r32(l.iridescence_thickness),
        anisotropy_strength: r32(l.anisotropy_strength),
        anisotropy_rotation: r32(l.anisotropy_rotation),
        clearcoat_normal: r32v(l.clearcoat_normal),
        // Light through surfaces: not in the GPU's material.
        ..*l
    }
}

/// The f64 value (one-sided like `Material::f_r`).
fn cpu_eval(s: &Sample) -> Rgb {
    if s.wi.z <= 0.0 || s.wo.z <= 0.0 {
        return Rgb::ZERO;
    }
    gltf_layered_with_albedos(
        s.base_color,
        s.metallic,
        s.roughness,
        s.ms,
        &s.layers,
        s.albedo_o,
        s.albedo_i,
        &s.frame,
        s.wi,
        s.wo,
    )
}

type Perturb = Box<dyn Fn(&mut Sample, f64) + Sync>;

/// Every input the GPU rounds, with how far it moves: (how, absolute?).
fn perturbations() -> Vec<(Perturb, bool)> {
    let mut p: Vec<(Perturb, bool)> = Vec::new();
    for a in 0..3 {
        p.push((Box::new(move |s: &mut Sample, d| s.wi[a] += d), true));
        p.push((Box::new(move |s: &mut Sample, d| s.wo[a] += d), true));
        p.push((
            Box::new(move |s: &mut Sample, d| s.base_color[a] *= 1.0 + d),
            false,
        ));
        p.push((
            Box::new(move |s: &mut Sample, d| s.layers.specular_color[a] *= 1.0 + d),
            false,
        ));
        p.push((
            Box::new(move |s: &mut Sample, d| s.layers.sheen_color[a] *= 1.0 + d),
            false,
        ));
        p.push((
            Box::new(move |s: &mut Sample, d| s.layers.clearcoat_normal[a] += d),
            true,
        ));
    }
    let scalars: [fn(&mut Sample) -> &mut f64; 14] = [
        |s| &mut s.metallic,
        |s| &mut s.roughness,
        |s| &mut s.ms,
        |s| &mut s.layers.ior,
        |s| &mut s.layers.specular,
        |s| &mut s.layers.clearcoat,
        |s| &mut s.layers.clearcoat_roughness,
        |s| &mut s.layers.sheen_roughness,
        |s| &mut s.layers.iridescence,
        |s| &mut s.layers.iridescence_ior,
        |s| &mut s.layers.iridescence_thickness,
        |s| &mut s.layers.anisotropy_strength,
        |s| &mut s.layers.anisotropy_rotation,
        |s| &mut s.albedo_o,
    ];
    for f in scalars {
        p.push((Box::new(move |s: &mut Sample, d| *f(s) *= 1.0 + d), false));
    }
    p
}

/// The frame's tangent and bitangent moved as the rounded direction
/// `(cos ρ, sin ρ)` moves them (anisotropic samples only).
fn frame_perturbations() -> Vec<Perturb> {
    let mut p: Vec<Perturb> = Vec::new();
    for a in 0..3 {
        p.push(Box::new(move |s: &mut Sample, d| s.frame.t[a] += d));
        p.push(Box::new(move |s: &mut Sample, d| s.frame.b[a] += d));
    }
    p
}

/// `Σ_j max± |f(x ± Δ_j) − f(x)|`.
fn perturbation_error(s: &Sample, f: Rgb, list: &[(Perturb, bool)], frame: &[Perturb]) -> Rgb {
    let mut total = Rgb::ZERO;
    let step = K_INPUT * U;
    let mut add = |p: &dyn Fn(&mut Sample, f64), d: f64| {
        let mut worst = Rgb::ZERO;
        for d in [d, -d] {
            let mut moved = s.clone();
            p(&mut moved, d);
            worst = worst.max((cpu_eval(&moved) - f).abs());
        }
        total += worst;
    };
    for (p, _) in list {
        add(p.as_ref(), step);
    }
    if s.layers.anisotropy_strength > 0.0 {
        for p in frame {
            add(p.as_ref(), step);
        }
    }
    total
}

/// `|ΔF_ir|` per channel from Vulkan's 2⁻¹¹ on each `cos` of the phase:
/// `Σ_m 2 |C_m| Σ_k |M_ck| A_k 2⁻¹¹`, `A_k` the amplitudes of the XYZ terms
/// over the normalization and `|C_m| ≤ |R_s − T₁₂₁| r^m ≤ 1 + R_s`
/// (bounded here by its largest value, `(R_s + 1)`, with `R_s ≤
/// 0.9999·…/(1 − 0.9999)` taken from the sample).
fn film_cos_bound(l: &GltfLayers, cos_o: f64, f0: Rgb) -> Rgb {
    use gonio::material::brdf::gltf_layers::iridescence::iridescence_fresnel;
    let amplitude: [f64; 3] = std::array::from_fn(|k| {
        let mut a = SENSITIVITY_V[k] * (TAU * SENSITIVITY_SIGMA[k]).sqrt();
        if k == 0 {
            a += SENSITIVITY_X2[0] * (TAU * SENSITIVITY_X2[2]).sqrt();
        }
        a / SENSITIVITY_NORM
    });
    // The Airy coefficients: |C_1| + |C_2| ≤ 2 max(R_s, T₁₂₁) ≤ 2 (1 + R_s);
    // R_s ≤ F_ir + something: bound it by the film's own largest value.
    let f = iridescence_fresnel(cos_o, l.iridescence_ior, l.iridescence_thickness, f0);
    let coefficient = 2.0 * 2.0 * (2.0 + f.max_element());
    Rgb::from_array(std::array::from_fn(|c| {
        let row: f64 = (0..3)
            .map(|k| XYZ_TO_REC709[c][k].abs() * amplitude[k])
            .sum();
        coefficient * row * TRIG_ERROR
    }))
}

/// What Vulkan's transcendental functions add beyond rounding (module doc).
fn transcendental(s: &Sample) -> Rgb {
    let l = &s.layers;
    let n = s.frame.n;
    let mut t = Rgb::ZERO;
    if l.has_iridescence() {
        let lobe = base_lobe(
            s.roughness * s.roughness,
            l,
            n,
            s.frame.t,
            s.frame.b,
            s.wi,
            s.wo,
        );
        let f0 = gonio::material::brdf::gltf_layers::base_ior_specular::dielectric_f0(
            l.ior,
            l.specular_color,
        ) * l.specular;
        let b = s.base_color;
        let reach = (Rgb::splat(b.max_element() / PI + lobe * (1.0 + s.ms)) * (1.0 - s.metallic)
            + Rgb::splat(lobe) * (Rgb::ONE + b * s.ms) * s.metallic)
            * l.iridescence;
        let df = film_cos_bound(l, s.wo.z, f0).max(film_cos_bound(l, s.wo.z, b));
        // The diffuse reads max₃ F*: any channel's error reaches every channel.
        t += reach * df.max_element();
    }
    if l.has_sheen() {
        let alpha = sheen_alpha(l.sheen_roughness);
        let h = half_vector(s.wi, s.wo);
        let cos2 = h.z * h.z;
        let lobe = sheen_lobe(alpha, h.z, sin2_between(n, h), s.wi.z, s.wo.z);
        let handover = if (0.1..0.5).contains(&cos2) {
            LOG_ERROR / (2.0 * alpha)
        } else {
            0.0
        };
        let d_error = 163.0 * U + 240.0 * U + handover;
        t += l.sheen_color * lobe * (d_error + SHEEN_V_ERROR);
    }
    t
}

/// The compute shader: the BRDF library of gltf-pbr, the layer files, and
/// an entry point evaluating `gltf_layered_with_albedos` and the table.
fn compute_source() -> String {
    let material = Material::new("layers", ReflectanceModel::GltfPbr);
    let variants: BTreeSet<_> = [material.variant()].into();
    // Every layer compiled, as a scene with all of them has it (the
    // sheen's table a uniform buffer at group 0, binding 4).
    let key = ShaderKey {
        shading: gonio::scene::ShadingMode::Phong,
        variants: variants.clone(),
        materials: gonio::gpu::shader_gen::MaterialsKey {
            gltf_layers: true,
            layer_ior_specular: true,
            layer_clearcoat: true,
            layer_sheen: true,
            layer_iridescence: true,
            layer_anisotropy: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut src = compose_brdf_library(&variants, &key.features());
    src.push_str(
        r#"
struct LayerSample {
    wi: vec3<f32>,
    metallic: f32,
    wo: vec3<f32>,
    roughness: f32,
    base_color: vec3<f32>,
    ms: f32,
    albedo: vec4<f32>,
    layers: GltfLayers,
}

@group(0) @binding(0) var<storage, read> layer_samples: array<LayerSample>;
@group(0) @binding(1) var<storage, read_write> layer_results: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&layer_samples) {
        return;
    }
    let s = layer_samples[i];
    let frame = SurfaceFrame(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0));
    var f = vec3<f32>(0.0);
    if s.wi.z > 0.0 && s.wo.z > 0.0 {
        f = gltf_layered_with_albedos(s.base_color, s.metallic, s.roughness, s.ms, s.layers, s.albedo.x, s.albedo.y, frame, s.wi, s.wo);
    }
    // The table at (μ, r_sh) = albedo.zw.
    layer_results[i] = vec4<f32>(f, sheen_albedo_lookup(s.albedo.z, s.albedo.w));
}
"#,
    );
    src
}

fn pack(s: &Sample, table_at: (f64, f64)) -> [f32; 48] {
    let l = &s.layers;
    let v = |x: f64| x as f32;
    // (cos ρ, sin ρ) in f64, rounded once (gpu::layout::GpuGltfLayers).
    let direction = l.anisotropy_direction();
    [
        v(s.wi.x),
        v(s.wi.y),
        v(s.wi.z),
        v(s.metallic),
        v(s.wo.x),
        v(s.wo.y),
        v(s.wo.z),
        v(s.roughness),
        v(s.base_color.x),
        v(s.base_color.y),
        v(s.base_color.z),
        v(s.ms),
        v(s.albedo_o),
        v(s.albedo_i),
        v(table_at.0),
        v(table_at.1),
        v(l.specular_color.x),
        v(l.specular_color.y),
        v(l.specular_color.z),
        v(l.ior),
        v(l.sheen_color.x),
        v(l.sheen_color.y),
        v(l.sheen_color.z),
        v(l.specular),
        v(l.clearcoat_normal.x),
        v(l.clearcoat_normal.y),
        v(l.clearcoat_normal.z),
        v(l.clearcoat),
        v(direction.x),
        v(direction.y),
        v(l.clearcoat_roughness),
        v(l.sheen_roughness),
        v(l.iridescence),
        v(l.iridescence_ior),
        v(l.iridescence_thickness),
        v(l.anisotropy_strength),
        // Light through surfaces (read only with layer_transmission,
        // which this shader leaves out), as gpu::layout::GpuGltfLayers.
        v(l.attenuation_color.x),
        v(l.attenuation_color.y),
        v(l.attenuation_color.z),
        v(l.transmission),
        v(l.thickness),
        if l.attenuation_distance.is_finite() {
            v(1.0 / l.attenuation_distance)
        } else {
            0.0
        },
        v(l.dispersion),
        v(l.diffuse_transmission),
        v(l.diffuse_transmission_color.x),
        v(l.diffuse_transmission_color.y),
        v(l.diffuse_transmission_color.z),
        0.0,
    ]
}

/// Runs the shader; returns per sample (f_r, table lookup at `table_at`).
fn gpu_eval(
    ctx: &gonio::gpu::GpuContext,
    samples: &[Sample],
    table_at: &[(f64, f64)],
) -> Vec<([f32; 3], f32)> {
    let src = compute_source();
    gonio::gpu::shader_gen::validate(&src).unwrap_or_else(|e| panic!("{e}"));
    let data: Vec<[f32; 48]> = samples
        .iter()
        .zip(table_at)
        .map(|(s, t)| pack(s, *t))
        .collect();
    let input = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytemuck::cast_slice(&data),
            usage: wgpu::BufferUsages::STORAGE,
        });
    let table = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytemuck::cast_slice(table_nodes()),
            usage: wgpu::BufferUsages::UNIFORM,
        });
    let output = common::compute_output(ctx, (samples.len() * 16) as u64);
    let bytes = common::run_compute(
        ctx,
        "layer equivalence",
        &src,
        &[(0, vec![(0, &input), (1, &output), (4, &table)])],
        samples.len(),
        &output,
    );
    let values: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    values.iter().map(|v| ([v[0], v[1], v[2]], v[3])).collect()
}

#[derive(Default)]
struct Stats {
    max_abs: f64,
    max_rel: f64,
    worst_ratio: f64,
    failures: usize,
    non_finite: usize,
    worst: String,
}

#[test]
fn every_layer_matches_its_f64_reference() {
    use rayon::prelude::*;
    let renderer = common::gpu_renderer();
    let ctx = renderer.context();
    let list = perturbations();
    let frame = frame_perturbations();
    let mut rows = Vec::new();
    let mut failed = Vec::new();
    for case in cases() {
        let samples = samples(case);
        let table_at: Vec<(f64, f64)> = samples
            .iter()
            .map(|s| (s.wo.z.max(0.0), s.layers.sheen_roughness))
            .collect();
        let gpu = gpu_eval(ctx, &samples, &table_at);
        let stats = samples
            .par_iter()
            .zip(&gpu)
            .map(|(s, (g, _))| {
                let mut st = Stats::default();
                let f = cpu_eval(s);
                let sens = perturbation_error(s, f, &list, &frame);
                let t = transcendental(s);
                for c in 0..3 {
                    let (cpu, gpu) = (f[c], g[c] as f64);
                    if !cpu.is_finite() || !gpu.is_finite() {
                        st.non_finite += 1;
                        continue;
                    }
                    let tol = sens[c] + N_ASSEMBLY * U * cpu.abs() + t[c] + 1e-37;
                    let err = (gpu - cpu).abs();
                    st.max_abs = st.max_abs.max(err);
                    if cpu.abs() > 1e-30 {
                        st.max_rel = st.max_rel.max(err / cpu.abs());
                    }
                    let ratio = err / tol;
                    if ratio > st.worst_ratio {
                        st.worst_ratio = ratio;
                        st.worst =
                            format!("{s:?}: channel {c} gpu {gpu:e} cpu {cpu:e} tol {tol:e}");
                    }
                    st.failures += (ratio > 1.0) as usize;
                }
                st
            })
            .reduce(Stats::default, |a, b| Stats {
                max_abs: a.max_abs.max(b.max_abs),
                max_rel: a.max_rel.max(b.max_rel),
                failures: a.failures + b.failures,
                non_finite: a.non_finite + b.non_finite,
                worst: if a.worst_ratio >= b.worst_ratio {
                    a.worst.clone()
                } else {
                    b.worst.clone()
                },
                worst_ratio: a.worst_ratio.max(b.worst_ratio),
            });
        let row = format!(
            "| {:<36} | {:>7} | {:>9.3e} | {:>9.3e} | {:>7.4} | {:>6} | {:>4} |",
            case.name(),
            samples.len(),
            stats.max_abs,
            stats.max_rel,
            stats.worst_ratio,
            stats.failures,
            stats.non_finite
        );
        eprintln!("{row}");
        if stats.failures > 0 || stats.non_finite > 0 {
            failed.push(format!(
                "{}: {} failures, {} non-finite; worst: {}",
                case.name(),
                stats.failures,
                stats.non_finite,
                stats.worst
            ));
        } else {
            eprintln!("  worst: {}", stats.worst);
        }
        rows.push(row);
    }
    eprintln!(
        "\n| case | samples | max abs error | max rel error | max err/tol | failures | NaN/Inf |\n|---|---|---|---|---|---|---|\n{}",
        rows.join("\n")
    );
    assert!(
        failed.is_empty(),
        "GPU and CPU layers disagree:\n{}",
        failed.join("\n")
    );
}

/// The GPU's table of the sheen albedo against the exact quadrature, on a
/// grid through the nodes and the cell centres of both axes
/// (`SHEEN_ALBEDO_TABLE_SIZE`: `u = ((μ − μ_min)/(1 − μ_min))^¼` and
/// `r_sh` in steps of 1/126, from `r_sh = 1/63`, the table's domain): the
/// GPU lookup equals its f64 twin (`sheen_albedo_lookup`, the same f32
/// nodes) to f32 rounding, and the table's own error `|E_table − E|` is
/// within its documented bound (`sheen_table_error_bound`) everywhere on
/// the grid, reported per band of `sheen_roughness`. Through the albedo
/// scaling it moves `f_r` by at most `max₃(c_sh) |ΔE| · f_below` (while
/// σ > 0).
#[test]
fn sheen_albedo_table_error() {
    use rayon::prelude::*;
    let renderer = common::gpu_renderer();
    let ctx = renderer.context();
    let n = SHEEN_ALBEDO_TABLE_SIZE;
    let last = (n - 1) as f64;
    let steps = 2 * (n - 1);
    let grid: Vec<(f64, f64)> = (2..=steps)
        .flat_map(|j| {
            (0..=steps).map(move |i| {
                let u = i as f64 / steps as f64;
                let mu = SHEEN_ALBEDO_COS_MIN + (1.0 - SHEEN_ALBEDO_COS_MIN) * u.powi(4);
                (r32(mu), r32(j as f64 / steps as f64))
            })
        })
        .collect();
    // Dummy samples carrying the grid in albedo.zw.
    let frame = SurfaceFrame {
        n: DVec3::Z,
        t: DVec3::X,
        b: DVec3::Y,
    };
    let dummy = Sample {
        wi: DVec3::Z,
        wo: DVec3::Z,
        frame,
        base_color: Rgb::ZERO,
        metallic: 0.0,
        roughness: 0.5,
        ms: 0.0,
        layers: GltfLayers::default(),
        albedo_o: 0.0,
        albedo_i: 0.0,
    };
    let samples = vec![dummy; grid.len()];
    let gpu = gpu_eval(ctx, &samples, &grid);
    let nodes = table_nodes();
    let results: Vec<(f64, f64, f64, f64, f64)> = grid
        .par_iter()
        .zip(&gpu)
        .map(|(&(mu, r), (_, g))| {
            let twin = sheen_albedo_lookup(mu, r, nodes);
            let exact = sheen_albedo(mu, sheen_alpha(r));
            // f32 rounding of the lookup of g: 64 roundings of the
            // largest node of the cell, and the position x = 63 u off by
            // two sqrt's 3 ulp and 64 roundings, times the cell's largest
            // node step; over r_sh (its rounding and the division's, 2U
            // of the result).
            let t = (mu - SHEEN_ALBEDO_COS_MIN) / (1.0 - SHEEN_ALBEDO_COS_MIN);
            let (x, y) = (t.max(0.0).sqrt().sqrt() * last, r * last);
            let (i, j) = (
                (x.floor().min(last - 1.0)) as usize,
                (y.floor().min(last - 1.0)) as usize,
            );
            let cell = [
                nodes[j * n + i],
                nodes[j * n + i + 1],
                nodes[(j + 1) * n + i],
                nodes[(j + 1) * n + i + 1],
            ]
            .map(|v| v as f64);
            let big = cell.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let step = cell.iter().fold(0.0f64, |a, v| a.max(*v))
                - cell.iter().fold(f64::INFINITY, |a, v| a.min(*v));
            let tol_g = 64.0 * U * big + step * (6.0 + 64.0) * U * x.max(1.0) + 1e-37;
            let tol = tol_g / r + 4.0 * U * twin.abs();
            (
                r,
                (*g as f64 - twin).abs() / tol,
                (twin - exact).abs(),
                exact,
                (twin - exact).abs() / sheen_table_error_bound(r),
            )
        })
        .collect();
    let worst_twin = results.iter().map(|r| r.1).fold(0.0, f64::max);
    eprintln!("sheen table: GPU lookup vs its f64 twin, max err/tol {worst_twin:.4}");
    eprintln!(
        "| sheen_roughness | max |E_table − E| | max E | bound | max error/bound |\n|---|---|---|---|---|"
    );
    for (lo, hi) in [
        (0.0, 0.05),
        (0.05, 0.1),
        (0.1, 0.23),
        (0.23, 0.5),
        (0.5, 1.01),
    ] {
        let band: Vec<_> = results.iter().filter(|r| r.0 >= lo && r.0 < hi).collect();
        let (err, e_max, ratio) = band.iter().fold((0.0f64, 0.0f64, 0.0f64), |a, r| {
            (a.0.max(r.2), a.1.max(r.3), a.2.max(r.4))
        });
        eprintln!(
            "| [{lo}, {hi}) | {err:.3e} | {e_max:.4} | {:.1e} | {ratio:.3} |",
            sheen_table_error_bound(lo.max(1.0 / last))
        );
    }
    assert!(worst_twin <= 1.0, "{worst_twin}");
    let worst_bound = results.iter().map(|r| r.4).fold(0.0, f64::max);
    assert!(
        worst_bound <= 1.0,
        "the sheen table's error exceeds its documented bound by {worst_bound}"
    );
}
