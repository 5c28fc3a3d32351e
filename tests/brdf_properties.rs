//! Physics of every reflectance model, measured (pbrt-v4's
//! `TestEnergyConservation`, Mitsuba's BSDF tests): positivity and
//! finiteness everywhere, reciprocity where the model is reciprocal (and the
//! measured violation where it is not: the lecture's Phong forms), and
//! directional albedo ≤ 1 for the energy-conserving models, with the
//! quadrature's stated error bound (`gonio::explore::albedo`).

use glam::DVec3;
use gonio::explore::albedo::directional_albedo;
use gonio::material::brdf::SurfaceFrame;
use gonio::material::param::{Kind, Param, Scale, Value, Widget};
use gonio::material::{Distribution, Fresnel, Geometry, Material, ReflectanceModel};
use gonio::scene::Rgb;
use proptest::prelude::*;

fn frame() -> SurfaceFrame {
    SurfaceFrame {
        n: DVec3::Z,
        t: DVec3::X,
        b: DVec3::Y,
    }
}

/// A direction in the upper hemisphere, θ up to 89.99°.
fn hemisphere() -> impl Strategy<Value = DVec3> {
    (0.0..89.99f64, 0.0..std::f64::consts::TAU).prop_map(|(t, p)| {
        let t = t.to_radians();
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    })
}

/// A direction anywhere on the sphere.
fn sphere() -> impl Strategy<Value = DVec3> {
    (0.0..180.0f64, 0.0..std::f64::consts::TAU).prop_map(|(t, p)| {
        let t = t.to_radians();
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    })
}

/// A value of `p` for `u` in [0, 1): between its smallest and largest
/// sample (its range in the table of models), log-uniform for a parameter
/// on a logarithmic slider (shifted by one when the range starts at 0).
fn draw(p: &Param, u: f64) -> f64 {
    let lo = p.samples.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = p.samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    match p.widget {
        Widget::Slider {
            scale: Scale::Log, ..
        } if lo > 0.0 => 10f64.powf(lo.log10() + u * (hi / lo).log10()),
        Widget::Slider {
            scale: Scale::Log, ..
        } => lo - 1.0 + 10f64.powf(u * (hi - lo + 1.0).log10()),
        _ => lo + u * (hi - lo),
    }
}

/// Every model of the table, with every term it selects, each of its
/// parameters over its whole range ([`draw`]; a triple grey).
fn material() -> impl Strategy<Value = Material> {
    let model = prop::sample::select(ReflectanceModel::ALL.to_vec());
    let distribution = prop::sample::select(Distribution::ALL.to_vec());
    let geometry = prop::sample::select(Geometry::ALL.to_vec());
    let fresnel = prop::sample::select(Fresnel::ALL.to_vec());
    (
        model,
        (distribution, geometry, fresnel, any::<bool>()),
        prop::collection::vec(0.0..1.0f64, 16),
    )
        .prop_map(|(model, (d, g, f, lecture), u)| {
            let mut m = Material::new("p", model);
            m.distribution = d;
            m.geometry = g;
            m.fresnel = f;
            if lecture {
                m.denominator = gonio::material::Denominator::Lecture;
            }
            for (p, &u) in model.row().params.iter().zip(u.iter().cycle()) {
                let v = draw(p, u);
                let value = match p.kind {
                    Kind::Color => Value::Color(Rgb::splat(v)),
                    Kind::Scalar => Value::Scalar(v),
                };
                p.write(&mut m, value);
            }
            m
        })
}

/// Models whose f_r(i, o) = f_r(o, i) by construction (the table says).
fn reciprocal(m: &Material) -> bool {
    m.model.row().reciprocal
}

proptest! {
    // Fixed seed-free runs are still deterministic enough to rerun: a
    // failure prints the minimal case; nothing is persisted to disk.
    #![proptest_config(ProptestConfig { cases: 20_000, failure_persistence: None, ..ProptestConfig::default() })]

    /// f_r ≥ 0 and finite for every direction pair, including below the
    /// horizon, and zero there (one-sided).
    #[test]
    fn brdfs_are_positive_finite_and_one_sided(m in material(), wi in sphere(), wo in sphere()) {
        let f = m.f_r(wi, wo, &frame());
        prop_assert!(f.is_finite(), "{} f = {f}", m.variant().describe());
        prop_assert!(f.min_element() >= 0.0, "{} f = {f}", m.variant().describe());
        if wi.z <= 0.0 || wo.z <= 0.0 {
            prop_assert_eq!(f, Rgb::ZERO);
        }
    }

    /// f_r(i, o) = f_r(o, i) for the reciprocal models, to rounding.
    #[test]
    fn reciprocal_models_are_reciprocal(m in material(), wi in hemisphere(), wo in hemisphere()) {
        if !reciprocal(&m) {
            return Ok(());
        }
        let a = m.f_r(wi, wo, &frame());
        let b = m.f_r(wo, wi, &frame());
        let scale = a.max(b).max_element().max(1e-300);
        prop_assert!((a - b).abs().max_element() <= 1e-9 * scale,
            "{}: f(i,o) = {a}, f(o,i) = {b}", m.variant().describe());
    }
}

/// The lecture's Phong forms divide by I·N, so they are not reciprocal:
/// f(i,o)/f(o,i) = (V·N)/(I·N). Measured on a grid and printed; the ratio
/// must be exactly that (which also shows the violation is real).
#[test]
fn lecture_phong_forms_violate_reciprocity_by_the_cosine_ratio() {
    let mut worst: f64 = 1.0;
    for model in [ReflectanceModel::Phong, ReflectanceModel::BlinnPhong] {
        let mut m = Material::new("p", model);
        m.k_d = Rgb::ZERO;
        m.k_s = Rgb::ONE;
        m.k_e = 10.0;
        for ti in (5..=85).step_by(10) {
            for to in (5..=85).step_by(10) {
                let (ti, to) = ((ti as f64).to_radians(), (to as f64).to_radians());
                let wi = DVec3::new(ti.sin(), 0.0, ti.cos());
                let wo = DVec3::new(-to.sin(), 0.0, to.cos());
                let a = m.f_r(wi, wo, &frame()).x;
                let b = m.f_r(wo, wi, &frame()).x;
                if a > 1e-12 && b > 1e-12 {
                    let expected = wo.z / wi.z;
                    assert!(
                        (a / b - expected).abs() <= 1e-9 * expected,
                        "{model}: {a}/{b} vs {expected}"
                    );
                    worst = worst.max((a / b).max(b / a));
                }
            }
        }
    }
    eprintln!("lecture Phong / Blinn-Phong: worst f(i,o)/f(o,i) on a 10° grid = {worst:.2}");
    assert!(worst > 10.0);
}

/// The energy-conserving models reflect at most what they receive:
/// ρ(θ_i) = ∫ f_r cos θ_o dω_o ≤ 1 + (the quadrature's error bound), for
/// parameters across their ranges and θ_i up to 89°. The lecture forms and
/// the combinations measured to exceed 1 are in docs/brdf-models.md.
#[test]
fn normalized_models_conserve_energy() {
    let mut cases: Vec<Material> = Vec::new();
    for k_e in [0.0, 1.0, 10.0, 100.0, 1e3, 1e4] {
        for model in [
            ReflectanceModel::PhongNormalized,
            ReflectanceModel::BlinnPhongNormalized,
        ] {
            let mut m = Material::new("n", model);
            (m.k_d, m.k_s, m.k_e) = (Rgb::ZERO, Rgb::ONE, k_e);
            cases.push(m);
        }
    }
    for roughness in [1e-3, 0.05, 0.3, 0.7, 1.0] {
        for distribution in [Distribution::Beckmann, Distribution::Ggx] {
            for fresnel in [Fresnel::None, Fresnel::Conductor, Fresnel::Dielectric] {
                let mut m = Material::new("ct", ReflectanceModel::CookTorrance);
                (m.k_d, m.k_s, m.roughness, m.distribution, m.fresnel) =
                    (Rgb::ZERO, Rgb::ONE, roughness, distribution, fresnel);
                cases.push(m);
            }
        }
    }
    let mut lambert = Material::new("l", ReflectanceModel::Lambert);
    lambert.k_d = Rgb::ONE;
    cases.push(lambert);
    let mut worst = (0.0, String::new());
    for m in &cases {
        for theta_deg in [0.0, 30.0, 60.0, 80.0, 89.0] {
            let a = directional_albedo(m, f64::to_radians(theta_deg));
            let excess = (a.value - Rgb::ONE - a.error_bound).max_element();
            let label = format!(
                "{} k_e {} roughness {} at {theta_deg}°: ρ = {} ± {}",
                m.variant().describe(),
                m.k_e,
                m.roughness,
                a.value,
                a.error_bound
            );
            assert!(excess <= 0.0, "albedo above 1: {label}");
            if a.value.max_element() > worst.0 {
                worst = (a.value.max_element(), label);
            }
        }
    }
    eprintln!("largest albedo among energy-conserving models: {}", worst.1);
}

/// gltf-pbr conserves energy where its form allows: a metal (F ≤ 1 times
/// the height-correlated Smith-GGX lobe, whose single-scattering albedo
/// is ≤ 1) at every angle, and the dielectric near normal incidence. The
/// dielectric does NOT conserve energy towards grazing: its diffuse term
/// is weighted by 1 − F_d(V·H) over all the ω_o while the specular lobe
/// takes F_d at the mirror's larger V·H, so white (b = 1) reaches
/// ρ = 1.025 at 60° and 1.35 at 80° (r = 0.1; docs/brdf-models.md). That is
/// the specification's BRDF, kept as written, and this test pins both
/// sides: ≤ 1 below 30°, > 1 at 80°.
#[test]
fn gltf_pbr_conserves_energy_where_its_form_allows() {
    let material = |b: f64, metallic: f64, roughness: f64| {
        let mut m = Material::new("g", ReflectanceModel::GltfPbr);
        (m.base_color, m.metallic, m.roughness) = (Rgb::splat(b), metallic, roughness);
        m
    };
    for roughness in [0.1, 0.3, 0.7, 1.0] {
        for b in [0.5, 1.0] {
            let metal = material(b, 1.0, roughness);
            for theta_deg in [0.0, 30.0, 60.0, 80.0, 89.0] {
                let a = directional_albedo(&metal, f64::to_radians(theta_deg));
                let excess = (a.value - Rgb::ONE - a.error_bound).max_element();
                assert!(
                    excess <= 0.0,
                    "metal b {b} r {roughness} θ {theta_deg}°: ρ = {}",
                    a.value
                );
            }
            let dielectric = material(b, 0.0, roughness);
            for theta_deg in [0.0, 15.0, 30.0] {
                let a = directional_albedo(&dielectric, f64::to_radians(theta_deg));
                let excess = (a.value - Rgb::ONE - a.error_bound).max_element();
                assert!(
                    excess <= 0.0,
                    "dielectric b {b} r {roughness} θ {theta_deg}°: ρ = {}",
                    a.value
                );
            }
        }
    }
    let white = directional_albedo(&material(1.0, 0.0, 0.1), f64::to_radians(80.0));
    assert!(white.value.x > 1.3, "{}", white.value);
}
