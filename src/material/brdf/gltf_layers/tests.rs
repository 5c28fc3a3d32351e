//! The layers against the core and against the contract's own numbers.

use super::GltfLayers;
use super::base_ior_specular::{d_ggx_anisotropic, f0_from_ior, vis_ggx_anisotropic};
use super::iridescence::{XYZ_TO_REC709, eval_sensitivity, iridescence_fresnel};
use super::sheen::{sheen_alpha, sheen_scaling};
use super::sheen_albedo::{sheen_albedo, sheen_albedo_fine};
use super::stack::gltf_layered;
use crate::base::Rgb;
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::gltf_pbr::gltf_pbr;
use crate::material::brdf::microfacet::vis_smith_ggx_correlated;
use crate::material::brdf::microfacet::{d_ggx, half_vector, sin2_between};
use glam::DVec3;

fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn frame() -> SurfaceFrame {
    SurfaceFrame {
        n: DVec3::Z,
        t: DVec3::X,
        b: DVec3::Y,
    }
}

/// Every layer at its glTF default: the core's `f_r`, bit for bit, over
/// directions to 89.9°, base colours, metallic, roughness and energy
/// compensation's ratio.
#[test]
fn defaults_are_the_core_bit_for_bit() {
    let layers = GltfLayers::default();
    let mut checked = 0;
    for b in [Rgb::new(0.8, 0.5, 0.2), Rgb::ONE, Rgb::ZERO] {
        for metallic in [0.0, 0.3, 1.0] {
            for roughness in [0.01, 0.3, 1.0] {
                for ms in [0.0, 0.37] {
                    for i in 0..200 {
                        let k = i as f64;
                        let wi = dir((k * 37.1) % 89.9, (k * 71.3) % 360.0);
                        let wo = dir((k * 53.7) % 89.9, (k * 13.9) % 360.0);
                        let core = gltf_pbr(b, metallic, roughness, ms, DVec3::Z, wi, wo);
                        let layered =
                            gltf_layered(b, metallic, roughness, ms, &layers, &frame(), wi, wo);
                        for c in 0..3 {
                            assert_eq!(
                                core[c].to_bits(),
                                layered[c].to_bits(),
                                "b {b} m {metallic} r {roughness} ms {ms} wi {wi} wo {wo}: {core} vs {layered}"
                            );
                        }
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 3 * 3 * 2 * 200);
}

/// `KHR_materials_ior`: 1.5 gives 0.04 exactly, 1 gives 0, and the
/// specular-glossiness `ior = 0` gives 1 (pinned choice 4).
#[test]
fn f0_from_ior_ends() {
    assert_eq!(f0_from_ior(1.5), 0.04);
    assert_eq!(f0_from_ior(1.0), 0.0);
    assert_eq!(f0_from_ior(0.0), 1.0);
    assert!((f0_from_ior(2.0) - 1.0 / 9.0).abs() < 1e-16);
}

/// The anisotropic lobe with `α_t = α_b = α` is glTF's isotropic `G_α`
/// (contract: "At `s_a = 0` it equals `G_α`"), to rounding.
#[test]
fn anisotropic_lobe_at_equal_alphas_is_isotropic() {
    let n = DVec3::Z;
    for alpha in [1e-4, 0.01, 0.2, 0.7, 1.0] {
        for (ti, pi, to, po) in [
            (10.0, 0.0, 20.0, 180.0),
            (60.0, 30.0, 45.0, 250.0),
            (85.0, 10.0, 80.0, 170.0),
        ] {
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            let h = half_vector(wi, wo);
            let iso = d_ggx(alpha, h.z, sin2_between(n, h))
                * vis_smith_ggx_correlated(alpha, wi.z, wo.z, wi.dot(h), wo.dot(h));
            let (t, b) = (DVec3::X, DVec3::Y);
            let aniso = d_ggx_anisotropic(alpha, alpha, t.dot(h), b.dot(h), h.z)
                * vis_ggx_anisotropic(
                    alpha,
                    alpha,
                    wi.z,
                    wo.z,
                    t.dot(wi),
                    b.dot(wi),
                    t.dot(wo),
                    b.dot(wo),
                    wi.dot(h),
                    wo.dot(h),
                );
            assert!(
                (aniso - iso).abs() <= 1e-12 * iso,
                "α {alpha}: {aniso} vs {iso}"
            );
        }
    }
}

/// The rotation turns the lobe: strength 1 along `t` at ρ = 0 is the
/// same lobe as along `b` at ρ = π/2 with the directions turned by 90°
/// (three.js #26967 rotated it the wrong way).
#[test]
fn anisotropy_rotation_turns_the_lobe_counter_clockwise() {
    let base = Rgb::splat(0.5);
    let along_t = GltfLayers {
        anisotropy_strength: 0.8,
        ..GltfLayers::default()
    };
    let along_b = GltfLayers {
        anisotropy_rotation: std::f64::consts::FRAC_PI_2,
        ..along_t
    };
    for (ti, pi, to, po) in [(30.0, 0.0, 40.0, 170.0), (60.0, 20.0, 50.0, 230.0)] {
        let a = gltf_layered(
            base,
            1.0,
            0.3,
            0.0,
            &along_t,
            &frame(),
            dir(ti, pi),
            dir(to, po),
        );
        let b = gltf_layered(
            base,
            1.0,
            0.3,
            0.0,
            &along_b,
            &frame(),
            dir(ti, pi + 90.0),
            dir(to, po + 90.0),
        );
        assert!(
            (a - b).abs().max_element() <= 1e-12 * a.max_element(),
            "{a} vs {b}"
        );
    }
    // And it is anisotropic: the lobe is wider along T (stretched α_t).
    let (wi, wo_t, wo_b) = (dir(0.0, 0.0), dir(40.0, 0.0), dir(40.0, 90.0));
    let ft = gltf_layered(base, 1.0, 0.3, 0.0, &along_t, &frame(), wi, wo_t);
    let fb = gltf_layered(base, 1.0, 0.3, 0.0, &along_t, &frame(), wi, wo_b);
    assert!(ft.x > 2.0 * fb.x, "{ft} {fb}");
}

/// The sensitivity at zero path difference is the integral of the
/// matching functions: X, Y, Z each 1 (to the fit's 0.1 %), so
/// `𝒮(0, 0) = M · (1, 1, 1)`: the constants are typed as the contract has
/// them.
#[test]
fn sensitivity_at_zero_is_the_matching_functions_integral() {
    let s = eval_sensitivity(0.0, Rgb::ZERO);
    let m = XYZ_TO_REC709;
    for c in 0..3 {
        let white = m[c][0] + m[c][1] + m[c][2];
        assert!((s[c] - white).abs() < 2e-3 * white.abs(), "{s}");
    }
}

/// The film's reflectance is finite and ≥ 0 over thickness and angle,
/// and the first interface alone where the film matches the outside
/// (`η_f = 1`): no film, `F_ir = f'` seen through Schlick at `cos θ₂ = cos θ₁`
/// to the first order: checked at normal incidence, where the two-beam
/// sum is `R₂₃` = the base's F0 (to the Fourier series' smallness).
#[test]
fn film_is_finite_and_invisible_when_index_matched() {
    for d in [0.0, 0.01, 0.03, 1.0, 100.0, 400.0, 1200.0] {
        for cos in [1e-6, 0.01, 0.3, 0.7, 1.0] {
            for eta in [1.0, 1.3, 2.0, 3.0] {
                let f = iridescence_fresnel(cos, eta, d, Rgb::new(0.04, 0.5, 0.9999));
                assert!(
                    f.is_finite() && f.min_element() >= 0.0,
                    "d {d} cos {cos} η {eta}: {f}"
                );
            }
        }
    }
    let f0 = Rgb::new(0.04, 0.2, 0.6);
    let matched = iridescence_fresnel(1.0, 1.0, 400.0, f0);
    assert!(
        (matched - f0).abs().max_element() < 0.02,
        "{matched} vs {f0}"
    );
}

/// The contract's numbers for `E`: 3.0 at θ = 89° for
/// `sheen_roughness = 0.02`; ≤ 1 for all θ ≤ 89° once `sheen_roughness ≥
/// 0.23`; 0 (for θ ≤ 89°) at `sheen_roughness = 0`.
#[test]
fn sheen_albedo_matches_the_contract() {
    let grazing = sheen_albedo(89f64.to_radians().cos(), sheen_alpha(0.02));
    assert!((grazing - 3.0).abs() < 0.05, "E(89°, 0.02) = {grazing}");
    for r in [0.23, 0.3, 0.5, 0.8, 1.0] {
        for theta in (0..=89).step_by(4).chain([89]) {
            let e = sheen_albedo((theta as f64).to_radians().cos(), sheen_alpha(r));
            assert!(e <= 1.0, "r {r} θ {theta}: E = {e}");
        }
    }
    assert_eq!(
        sheen_albedo(89f64.to_radians().cos(), sheen_alpha(0.0)),
        0.0
    );
}

/// The quadrature against one of four times its `φ` resolution and a
/// hundredth of its tolerance: the difference bounds `E`'s own error.
#[test]
fn sheen_albedo_quadrature_converged() {
    let mut worst = 0.0f64;
    for r in [0.02, 0.05, 0.1, 0.3, 0.6, 1.0] {
        for theta in [0.0, 30.0, 60.0, 80.0, 88.0, 89.9] {
            let mu = f64::to_radians(theta).cos();
            let (e, fine) = (
                sheen_albedo(mu, sheen_alpha(r)),
                sheen_albedo_fine(mu, sheen_alpha(r)),
            );
            worst = worst.max((e - fine).abs());
        }
    }
    eprintln!("sheen albedo quadrature: max |E − E_fine| = {worst:e}");
    assert!(worst < 1e-8, "{worst}");
}

/// At the roughness floor (glTF's default `sheen_roughness = 0`) `E`
/// lives within 2·10⁻⁵ of the horizon and peaks at about 5·10⁴ near the
/// visibility's cusp (μ = 10⁻⁶); there the quadrature agrees with the
/// fine one to a relative 10⁻¹⁰ (its panels stop at 10⁻¹³ of their own
/// value, which an absolute tolerance cannot reach at that size), and a
/// value above the lobe's reach is exactly 0.
#[test]
fn sheen_albedo_converged_at_the_floor() {
    let alpha = sheen_alpha(0.0);
    let mut worst = 0.0f64;
    for mu in [1e-9, 1e-7, 5e-7, 1e-6, 1.5e-6, 2e-6, 3e-6, 1e-5] {
        let (e, fine) = (sheen_albedo(mu, alpha), sheen_albedo_fine(mu, alpha));
        assert!(e > 0.0 && e.is_finite(), "μ {mu}: {e}");
        worst = worst.max((e - fine).abs() / fine);
    }
    eprintln!("sheen albedo at the floor: max |E − E_fine| / E_fine = {worst:e}");
    assert!(worst < 1e-10, "{worst}");
    assert_eq!(sheen_albedo(1e-3, alpha), 0.0);
}

/// The albedo scaling is clamped at 0 where `E > 1` (pinned choice 10) and
/// is 1 without colour.
#[test]
fn sheen_scaling_is_clamped() {
    assert_eq!(sheen_scaling(Rgb::ONE, 3.0, 0.2), 0.0);
    assert_eq!(sheen_scaling(Rgb::ZERO, 3.0, 0.2), 1.0);
    assert!((sheen_scaling(Rgb::new(0.5, 0.2, 0.1), 0.4, 0.2) - 0.8).abs() < 1e-15);
}

/// The stored table of the GPU's sheen albedo (`sheen_albedo_nodes.rs`)
/// holds exactly [`super::sheen_albedo::sheen_albedo_table`] (the exact
/// quadrature at the nodes, rounded to f32).
/// `GONIO_UPDATE_SHEEN_TABLE=1` writes it.
#[test]
fn sheen_table_is_current() {
    use super::sheen_albedo::{SHEEN_ALBEDO_TABLE_SIZE, sheen_albedo_table};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src/material/brdf/gltf_layers/sheen_albedo_nodes.rs");
    let nodes = sheen_albedo_table();
    let n = SHEEN_ALBEDO_TABLE_SIZE;
    let mut text = String::from(SHEEN_TABLE_HEADER);
    for row in nodes.chunks(n) {
        let line: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
        text.push_str(&format!("    {},\n", line.join(", ")));
    }
    text.push_str("];\n");
    if std::env::var_os("GONIO_UPDATE_SHEEN_TABLE").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        on_disk == text,
        "{} is not the current table: run with GONIO_UPDATE_SHEEN_TABLE=1",
        path.display()
    );
    assert_eq!(
        nodes.as_slice(),
        super::sheen_albedo_nodes::SHEEN_ALBEDO_NODES.as_slice()
    );
}

const SHEEN_TABLE_HEADER: &str = "//! The GPU's table of the sheen's directional albedo (see
//! [`super::sheen_albedo::sheen_albedo_table`]): the exact quadrature at
//! the nodes, rounded to `f32`, stored so no renderer computes it. The
//! test `sheen_table_is_current` checks it;
//! `GONIO_UPDATE_SHEEN_TABLE=1 cargo test --release --lib sheen_table_is_current`
//! rewrites it.

/// `g = r_sh · E` at `(u, r_sh) = (i, j)/(N − 1)`, `i` the fast index
/// (`super::sheen_albedo::SHEEN_ALBEDO_TABLE_SIZE` says why this form).
#[rustfmt::skip]
pub const SHEEN_ALBEDO_NODES: [f32; 4096] = [
";

/// The coat's own normal: `(0, 0, 1)` is the shading normal to the bit;
/// a tilted one moves the coat's highlight to its mirror direction (the
/// base keeps the shading normal), and a coat normal turned away from the
/// viewer reflects with `F_c = 1` (nothing of the base shows through a
/// full coat).
#[test]
fn the_coat_turns_with_its_own_normal() {
    use super::clearcoat::coat_normal;
    let f = frame();
    assert_eq!(coat_normal(&f, DVec3::Z), f.n);
    let coat = GltfLayers {
        clearcoat: 1.0,
        clearcoat_roughness: 0.05,
        ..GltfLayers::default()
    };
    let tilt = 0.2f64;
    let tilted = GltfLayers {
        clearcoat_normal: DVec3::new(tilt.sin(), 0.0, tilt.cos()),
        ..coat
    };
    let base = Rgb::splat(0.3);
    // The mirror direction about the tilted normal, for a view at 30°.
    let wo = dir(30.0, 180.0);
    let n_c = tilted.clearcoat_normal;
    let wi = (2.0 * n_c.dot(wo) * n_c - wo).normalize();
    let eval = |l: &GltfLayers| gltf_layered(base, 0.0, 0.5, 0.0, l, &f, wi, wo);
    let (flat, turned) = (eval(&coat), eval(&tilted));
    assert!(
        turned.x > 10.0 * flat.x,
        "the coat's peak follows its normal: {turned:?} vs {flat:?}"
    );
    let away = GltfLayers {
        clearcoat_normal: DVec3::new(-0.9, 0.0, 0.1).normalize(),
        ..coat
    };
    let v = dir(60.0, 0.0);
    let l = dir(40.0, 90.0);
    let f_away = gltf_layered(base, 0.0, 0.5, 0.0, &away, &f, l, v);
    assert!(
        f_away.max_element() >= 0.0 && f_away.max_element() < 1e-9,
        "{f_away:?}"
    );
}
