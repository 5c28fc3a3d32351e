//! A model's `f_r` at every sample of a fit, with what depends on the
//! samples alone computed once: the fit's inner loop.
//!
//! A fit evaluates its model at the same few thousand direction pairs
//! thousands of times (`problem.rs`). [`brdf::eval`] recomputes at every
//! call the half vector and its cosines and, for Cook-Torrance with the
//! conductor Fresnel, the exact complex-index Fresnel per channel (two
//! square roots and three divisions each) per sample — most of a
//! conductor fit's time. On the fit's grid (`samples.rs`, cell centres in
//! `(θ_h, θ_d, φ_d)`) the Fresnel's argument `I·H = cos θ_d` takes one
//! value per θ_d cell and the distribution's `(N·H, |N × H|²)` one per
//! θ_h cell: so [`Terms`] groups the samples by those values once, and
//! per evaluation computes `F` once per θ_d group (15 on the grid), `D`
//! once per θ_h group (30), and per sample only the geometry term and the
//! products. The cosines per sample are cached.
//!
//! The same functions in the same order as `brdf::eval`'s Cook-Torrance
//! and abc arms (`brdf::cook_torrance`, `abc::abc_specular`), so the
//! values agree with it to rounding: a group's members have the same
//! `I·H` (or `N·H`, `|N × H|²`) up to the rounding of their unit vectors
//! (about 1e-16 relative; 1e-12 for `|N × H|²` in the narrowest θ_h
//! cell), and the group uses its first member's; tested against
//! [`brdf::eval`] below for every fitted model. Other models (and
//! Cook-Torrance with energy compensation, which the fits leave off) are
//! evaluated by [`brdf::eval`] itself.
//!
//! But for one term: a `gltf-pbr` material with a sheen
//! (`layers=sheen`) scales its base by the sheen's albedo `E(μ)` at both
//! directions, which [`brdf::eval`] takes exactly (the integral, or its
//! curve once an `α` is asked for often:
//! `brdf::gltf_layers::sheen_curve`, a few seconds per `α`). A search
//! visits a new sheen roughness at nearly every point, so here `E` is
//! the GPU's table ([`sheen_albedo_lookup`]; its error is 2.5·10⁻³ or
//! less over the fit's sheen roughness, `SHEEN_ALBEDO_TABLE_ERROR`), and
//! the error a fit reports is [`brdf::eval`]'s at the point found
//! (`problem.rs`), the exact model's.

use super::samples::Sample;
use crate::base::Rgb;
use crate::base::frame::SurfaceFrame;
use crate::material::Material;
use crate::material::brdf::gltf_layers::sheen_albedo::sheen_albedo_lookup;
use crate::material::brdf::gltf_layers::sheen_albedo_nodes::SHEEN_ALBEDO_NODES;
use crate::material::brdf::gltf_layers::stack::gltf_layered_with_albedos;
use crate::material::brdf::microfacet::{half_vector, sin2_between};
use crate::material::brdf::{self, Brdf, Specular, abc, fresnel, lambert, microfacet};
use glam::DVec3;
use std::f64::consts::PI;

/// Two values join a group when within this relative distance of the
/// group's first: far above the rounding of one cell's members (above),
/// far below the distance between cells (`1e-3` relative and more).
const SAME: f64 = 1e-9;

/// One sample's cosines, as [`brdf::cook_torrance`] computes them (`N = z`).
#[derive(Clone, Copy, Debug)]
struct Cosines {
    cos_i: f64,
    cos_o: f64,
    cos_h: f64,
    cos_oh: f64,
    cos_ih: f64,
    /// The sample's θ_h group (index into [`Terms::half`]).
    h: u32,
    /// The sample's θ_d group (index into [`Terms::diff`]).
    d: u32,
}

/// The samples' cosines and groups (module doc).
#[derive(Clone, Debug)]
pub struct Terms {
    cosines: Vec<Cosines>,
    /// `(N·H, |N × H|²)` of each θ_h group's first member.
    half: Vec<(f64, f64)>,
    /// `I·H` of each θ_d group's first member.
    diff: Vec<f64>,
}

/// Group indices for `keys` (values within [`SAME`] of a group's first
/// member share it) and the first members' keys.
fn groups<const N: usize>(keys: &[[f64; N]]) -> (Vec<u32>, Vec<[f64; N]>) {
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by(|&a, &b| keys[a].partial_cmp(&keys[b]).expect("finite cosines"));
    let mut index = vec![0u32; keys.len()];
    let mut firsts: Vec<[f64; N]> = Vec::new();
    for k in order {
        let near = |first: &[f64; N]| {
            first
                .iter()
                .zip(&keys[k])
                .all(|(a, b)| (a - b).abs() <= SAME * a.abs().max(b.abs()))
        };
        if !firsts.last().is_some_and(near) {
            firsts.push(keys[k]);
        }
        index[k] = (firsts.len() - 1) as u32;
    }
    (index, firsts)
}

impl Terms {
    /// The cosines and groups of `samples`.
    pub fn new(samples: &[Sample]) -> Terms {
        let n = DVec3::Z;
        let per: Vec<(DVec3, DVec3, DVec3)> = samples
            .iter()
            .map(|s| (s.wi, s.wo, half_vector(s.wi, s.wo)))
            .collect();
        let half_keys: Vec<[f64; 2]> = per
            .iter()
            .map(|&(_, _, h)| [sin2_between(n, h), n.dot(h)])
            .collect();
        let diff_keys: Vec<[f64; 1]> = per.iter().map(|&(wi, _, h)| [wi.dot(h)]).collect();
        let (h_index, half) = groups(&half_keys);
        let (d_index, diff) = groups(&diff_keys);
        let cosines = per
            .iter()
            .enumerate()
            .map(|(k, &(wi, wo, h))| Cosines {
                cos_i: n.dot(wi),
                cos_o: n.dot(wo),
                cos_h: n.dot(h),
                cos_oh: wo.dot(h),
                cos_ih: wi.dot(h),
                h: h_index[k],
                d: d_index[k],
            })
            .collect();
        Terms {
            cosines,
            half: half.into_iter().map(|[s, c]| (c, s)).collect(),
            diff: diff.into_iter().map(|[c]| c).collect(),
        }
    }

    /// How many θ_h and θ_d groups the samples fall into.
    pub fn group_counts(&self) -> (usize, usize) {
        (self.half.len(), self.diff.len())
    }

    /// `f_r` of `m` at every sample (the samples [`Terms::new`] was given),
    /// written into `out`.
    pub fn f_r(&self, m: &Material, samples: &[Sample], out: &mut Vec<Rgb>) {
        out.clear();
        let b = m.brdf();
        match b.specular {
            Specular::CookTorrance(ct) if !b.energy_compensation => {
                let d: Vec<f64> = self.half.iter().map(|&(c, s)| ct.d.eval(c, s)).collect();
                let f: Vec<Rgb> = self.diff.iter().map(|&c| ct.f.eval(c)).collect();
                let diffuse = lambert::lambert(b.k_d);
                out.extend(self.cosines.iter().map(|c| {
                    let g = ct.g.eval(c.cos_h, c.cos_i, c.cos_o, c.cos_ih, c.cos_oh);
                    let spec = microfacet::cook_torrance_specular(
                        d[c.h as usize],
                        g,
                        f[c.d as usize],
                        c.cos_i,
                        c.cos_o,
                        ct.denominator,
                    );
                    diffuse + b.k_s * spec
                }));
            }
            Specular::Abc {
                a,
                b: abc_b,
                c: abc_c,
                eta_i,
                eta_t,
            } => {
                let d: Vec<f64> = self
                    .half
                    .iter()
                    .map(|&(c, s)| abc::d_abc_shape(abc_b, abc_c, c, s))
                    .collect();
                let f: Vec<f64> = self
                    .diff
                    .iter()
                    .map(|&c| fresnel::fresnel_dielectric(c, eta_i, eta_t))
                    .collect();
                let diffuse = lambert::lambert(b.k_d);
                out.extend(self.cosines.iter().map(|c| {
                    let g = microfacet::g_vgroove(c.cos_h, c.cos_o, c.cos_i, c.cos_oh);
                    let spec = microfacet::cook_torrance_specular(
                        d[c.h as usize],
                        g,
                        Rgb::splat(f[c.d as usize]),
                        c.cos_i,
                        c.cos_o,
                        PI,
                    )
                    .x;
                    diffuse + b.k_s * (a * spec)
                }));
            }
            Specular::GltfPbr { layers, .. } if layers.has_sheen() && !b.energy_compensation => {
                out.extend(samples.iter().map(|s| sheen_by_table(&b, s.wi, s.wo)));
            }
            _ => out.extend(generic(&b, samples)),
        }
    }
}

/// `f_r` of a `gltf-pbr` `b` with a sheen and no energy compensation, the
/// sheen's albedos from the GPU's table (module doc); `N = z`.
fn sheen_by_table(b: &Brdf, wi: DVec3, wo: DVec3) -> Rgb {
    let Specular::GltfPbr {
        base_color,
        metallic,
        roughness,
        layers,
    } = b.specular
    else {
        unreachable!("a gltf-pbr material")
    };
    let table = |cos: f64| sheen_albedo_lookup(cos, layers.sheen_roughness, &SHEEN_ALBEDO_NODES);
    let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
    gltf_layered_with_albedos(
        base_color,
        metallic,
        roughness,
        0.0,
        &layers,
        table(wo.z),
        table(wi.z),
        &frame,
        wi,
        wo,
    )
}

/// [`brdf::eval`] at every sample.
fn generic<'a>(b: &'a Brdf, samples: &'a [Sample]) -> impl Iterator<Item = Rgb> + 'a {
    let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
    samples
        .iter()
        .map(move |s| brdf::eval(b, s.wi, s.wo, &frame))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::models::{ALL, FitModel};
    use crate::fit::samples::{GRID, samples_of};
    use crate::material::brdf::gltf_layers::GltfLayers;
    use crate::material::brdf::gltf_layers::sheen_albedo::sheen_table_error_bound;

    /// The grid's samples fall into one group per θ_h and θ_d cell that
    /// has a pair above the 80° cut-off (the last θ_h and θ_d cells have
    /// none): no cell split, no two cells merged.
    #[test]
    fn the_grid_has_one_group_per_cell() {
        // Each sample's "measurement" is its cell's (θ_h, θ_d).
        let samples = samples_of(|theta_h, theta_d, _, _, _| Rgb::new(theta_h, theta_d, 0.0));
        let distinct = |axis: fn(&Sample) -> f64| {
            let mut v: Vec<f64> = samples.iter().map(axis).collect();
            v.sort_by(f64::total_cmp);
            v.dedup();
            v.len()
        };
        let cells = (distinct(|s| s.measured.x), distinct(|s| s.measured.y));
        assert!(cells.0 > GRID[0] - 5 && cells.1 > GRID[1] - 5, "{cells:?}");
        assert_eq!(Terms::new(&samples).group_counts(), cells);
    }

    /// Every fitted model, at several points of its bounds (narrow and
    /// wide lobes, low and high indices), agrees with `brdf::eval` sample
    /// by sample to within the grouping's rounding (module doc: 1e-12
    /// relative in `|N × H|²`, amplified by a Beckmann-like exponent of
    /// up to 80). With a sheen, `Terms` reads the sheen's albedo from the
    /// table (module doc) and `brdf::eval` takes it exactly, so they
    /// differ by the scaling `σ`'s change, at most `max₃(C)` times the
    /// table's error bound (`sheen_table_error_bound`, the fit's sheen
    /// roughness ≥ 0.1 and its directions within 80°, inside the table's
    /// domain) times what `σ` scales: the material without its sheen.
    #[test]
    fn terms_match_brdf_eval_at_every_sample() {
        let samples = samples_of(|_, _, _, _, _| Rgb::ONE);
        let terms = Terms::new(&samples);
        let frame = SurfaceFrame::new(DVec3::Z, DVec3::X);
        let mut out = Vec::new();
        for spec in ALL {
            let model = FitModel::parse(spec).unwrap();
            // A sheen's exact albedo costs a curve per sheen roughness
            // (seconds, `sheen_curve`): two points of its model.
            let points: &[f64] = if spec.contains("sheen") {
                &[0.37, 1.0]
            } else {
                &[0.0, 0.05, 0.37, 0.8, 1.0]
            };
            for &t in points {
                let values: Vec<f64> = model
                    .free
                    .iter()
                    .enumerate()
                    .map(|(k, f)| f.at((t + 0.13 * k as f64) % 1.0))
                    .collect();
                let m = model.material(&values);
                terms.f_r(&m, &samples, &mut out);
                assert_eq!(out.len(), samples.len());
                let b = m.brdf();
                let unsheened = Material {
                    layers: GltfLayers {
                        sheen_color: Rgb::ZERO,
                        ..m.layers
                    },
                    ..m.clone()
                }
                .brdf();
                let table_error = m.layers.sheen_color.max_element()
                    * sheen_table_error_bound(m.layers.sheen_roughness);
                for (s, fast) in samples.iter().zip(&out) {
                    let want = brdf::eval(&b, s.wi, s.wo, &frame);
                    let sheen = match b.specular {
                        Specular::GltfPbr { layers, .. } if layers.has_sheen() => {
                            table_error * brdf::eval(&unsheened, s.wi, s.wo, &frame).max_element()
                        }
                        _ => 0.0,
                    };
                    let diff = (*fast - want).abs().max_element();
                    assert!(
                        diff <= 1e-9 * want.abs().max_element() + sheen,
                        "{spec} at t = {t}: {fast:?} vs brdf::eval {want:?}"
                    );
                }
            }
        }
    }
}
