//! f64 reference BRDF evaluation, one benchmark per model (Cook-Torrance
//! once per Fresnel term): the CPU reference renderer's inner loop.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use gonio::material::brdf::SurfaceFrame;
use gonio::material::{Fresnel, Material, ReflectanceModel};
use std::hint::black_box;

fn brdf(c: &mut Criterion) {
    let frame = SurfaceFrame::from_normal(DVec3::Z);
    // 64 direction pairs over the upper hemisphere, so branches and
    // exponents see a spread of angles rather than one cached value.
    let pairs: Vec<(DVec3, DVec3)> = (0..64)
        .map(|k| {
            let a = k as f64 * 0.37;
            let wi = DVec3::new(a.cos() * 0.6, a.sin() * 0.6, 0.8).normalize();
            let wo = DVec3::new(-(a * 1.7).cos() * 0.5, (a * 1.3).sin() * 0.5, 0.7).normalize();
            (wi, wo)
        })
        .collect();
    let mut group = c.benchmark_group("f_r (64 direction pairs)");
    let mut materials: Vec<(String, Material)> = ReflectanceModel::ALL
        .iter()
        .map(|&m| {
            let mut mat = Material::new("bench", m);
            mat.k_s = DVec3::splat(0.5);
            (m.name().to_string(), mat)
        })
        .collect();
    for f in [Fresnel::ConductorLecture, Fresnel::Schlick] {
        let mut mat = Material::new("bench", ReflectanceModel::CookTorrance);
        mat.k_s = DVec3::splat(0.5);
        mat.fresnel = f;
        materials.push((format!("cook-torrance, fresnel {}", f.name()), mat));
    }
    for (name, m) in &materials {
        group.bench_function(name.as_str(), |b| {
            b.iter(|| {
                let mut sum = DVec3::ZERO;
                for (wi, wo) in &pairs {
                    sum += m.f_r(black_box(*wi), black_box(*wo), &frame);
                }
                sum
            })
        });
    }
    group.finish();
}

criterion_group!(benches, brdf);
criterion_main!(benches);
