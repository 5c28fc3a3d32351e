//! The rough boundary's sampled weights against the albedo of Walter et
//! al. 2007's BSDF by quadrature ([`rough_dielectric_albedo`]), and their
//! smooth limit.

use super::rough_boundary::{Boundary, samples_of, second_crossing_samples};
use super::thin::STRAIGHT_ALPHA;
use super::visible_normals::LOBE_SAMPLES;
use crate::base::SurfaceFrame;
use crate::material::brdf::fresnel::fresnel_dielectric;
use crate::material::brdf::gltf_layers::volume_albedo::rough_dielectric_albedo;
use crate::material::brdf::gltf_layers::volume_btdf::refract;
use glam::DVec3;

/// The view at `μ` above a flat boundary of normal +Z.
fn view(mu: f64) -> DVec3 {
    DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
}

/// A flat boundary of normal +Z seen from `wi`, reflections kept.
fn boundary(frame: &SurfaceFrame, wi: DVec3, alpha: f64, etas: (f64, f64)) -> Boundary<'_> {
    Boundary {
        frame,
        face: DVec3::Z,
        wi,
        alpha,
        etas,
        reflections: true,
    }
}

/// `[R, T]`: the summed weights of the reflected and refracted samples of
/// `count` points, viewer at `μ` above a flat boundary.
fn sampled(count: u32, alpha: f64, mu: f64, etas: (f64, f64)) -> [f64; 2] {
    let frame = SurfaceFrame::from_normal(DVec3::Z);
    let samples = samples_of(count, &boundary(&frame, view(mu), alpha, etas));
    let sum = |refracted: bool| {
        samples
            .iter()
            .filter(|s| s.refracted == refracted)
            .map(|s| s.weight)
            .sum()
    };
    [sum(false), sum(true)]
}

/// The sampled weights sum to the BSDF's reflected and transmitted
/// albedo, `R = ∫ f_r |o·n|` and `T = ∫ f_t |o·n|` by quadrature of
/// Walter's eq. 20 and 21 (`rough_dielectric_albedo`, 2000 × 512 cells),
/// at four α (from the roughness of `glass.toml`'s glass, 0.05, to 1),
/// three views and three pairs of indices: into glass, out of it (`n < 1`,
/// beyond the critical angle at μ = 0.7 and 0.3) and from glass into
/// water.
///
/// * The quadrature's own error `e_q` is estimated by halving its steps
///   (1000 × 256): the rule converges at least linearly (first order
///   where the integrand jumps: the χ⁺ cuts of `G`), so the coarser
///   rule's difference bounds the finer rule's error. At most 3.6·10⁻⁴
///   (α = 1, grazing), below 3·10⁻⁶ for α ≤ 0.09.
/// * 64 points (what the renderer traces): the Hammersley rule's error,
///   measured on 2026-12-05 at these 36 cases, at most 2.1·10⁻³ into the
///   denser medium and 2.6·10⁻² out of it, where the onset of total
///   internal reflection (`F` rising to 1 within the lobe) crosses the
///   visible normals: tolerances 3·10⁻³ and 3·10⁻².
/// * 65536 points: the same sums converge to the quadrature, which a
///   wrong weight would not: the rule's error bound, `O(log N / N)` for a
///   two-dimensional Hammersley set (Koksma–Hlawka with its discrepancy),
///   scaled from the 64-point tolerance, `tol₆₄ · (64 · 16) / (65536 · 6)`
///   (7.8·10⁻⁶ and 7.8·10⁻⁵), plus `2 e_q`.
#[test]
fn the_sampled_weights_sum_to_the_walter_albedo() {
    let fine = 65536;
    let scale =
        (LOBE_SAMPLES as f64 * (fine as f64).log2()) / (fine as f64 * (LOBE_SAMPLES as f64).log2());
    for etas in [(1.0, 1.5), (1.5, 1.0), (1.5, 1.33)] {
        let tol = if etas.0 < etas.1 { 3e-3 } else { 3e-2 };
        for alpha in [0.0025, 0.09, 0.25, 1.0] {
            for mu in [1.0, 0.7, 0.3] {
                let q = rough_dielectric_albedo(alpha, mu, etas, (2000, 512));
                let coarse = rough_dielectric_albedo(alpha, mu, etas, (1000, 256));
                let s = sampled(LOBE_SAMPLES, alpha, mu, etas);
                let s_fine = sampled(fine, alpha, mu, etas);
                for k in 0..2 {
                    let what = format!(
                        "η {etas:?} α {alpha} μ {mu} {}: quadrature {:.6}",
                        ["R", "T"][k],
                        q[k]
                    );
                    let e_q = (q[k] - coarse[k]).abs();
                    let err = (s[k] - q[k]).abs();
                    assert!(err <= tol, "{what}, 64 points {:.6}", s[k]);
                    let err_fine = (s_fine[k] - q[k]).abs();
                    let tol_fine = tol * scale + 2.0 * e_q;
                    assert!(
                        err_fine <= tol_fine,
                        "{what}, {fine} points {:.6} (err {err_fine:.1e}, tol {tol_fine:.1e})",
                        s_fine[k]
                    );
                }
                assert!(s[0] + s[1] <= 1.0 + 1e-12, "η {etas:?} α {alpha} μ {mu}");
            }
        }
    }
}

/// At the threshold where the reference switches between the smooth and
/// the rough boundary (`thin::STRAIGHT_ALPHA`), the rough one is the
/// smooth one: the weights sum to Fresnel's split `F(μ)`, `1 − F(μ)`, and
/// every direction lies near the smooth one, so nothing jumps where a
/// roughness crosses it. The cases avoid the critical angle (where the
/// smooth split itself jumps).
///
/// * Weights: the 64-point rule's error shrinks with α (every sampled
///   normal tilts by `O(α)`); measured on 2026-12-05 at most 4.0·10⁻⁵
///   (into glass at μ = 0.3, where `F` is steepest), against 7.0·10⁻⁴
///   at α = 10⁻² and 5.3·10⁻² at 10⁻¹ (out of glass at μ = 0.9, near
///   its critical angle): tolerance 10⁻⁴ at the threshold, and the
///   largest difference falls with α.
/// * Directions: the set's most tilted visible normal lies at
///   `tan θ = α √(u/(1 − u))`, `u = 63.5/64`, from the normal (GGX's slope
///   quantile at its largest point, `α √127`); a mirror direction turns
///   by twice its normal's tilt, a refracted one by less here (the factor
///   `|1 − η_i cos θ_i / (η_t cos θ_t)|` is below 2 at these views), so
///   every direction lies within `2 atan(α √127)` of the smooth one.
#[test]
fn the_rough_split_is_the_smooth_one_at_the_threshold() {
    let frame = SurfaceFrame::from_normal(DVec3::Z);
    let mut previous = f64::INFINITY;
    for alpha in [1e-1, 1e-2, STRAIGHT_ALPHA] {
        let mut largest: f64 = 0.0;
        for (etas, mus) in [
            ((1.0, 1.5), &[1.0, 0.9, 0.7, 0.3][..]),
            ((1.5, 1.0), &[1.0, 0.9][..]),
            ((1.5, 1.33), &[1.0, 0.9, 0.7][..]),
        ] {
            for &mu in mus {
                let what = format!("α {alpha} η {etas:?} μ {mu}");
                let f = fresnel_dielectric(mu, etas.0, etas.1);
                let [r, t] = sampled(LOBE_SAMPLES, alpha, mu, etas);
                let diff = (r - f).abs().max((t - (1.0 - f)).abs());
                largest = largest.max(diff);
                if alpha == STRAIGHT_ALPHA {
                    assert!(diff <= 1e-4, "{what}: R {r} T {t} vs F {f}");
                    let wi = view(mu);
                    let mirror = DVec3::new(-wi.x, 0.0, mu);
                    let straight = refract(wi, DVec3::Z, etas.0, etas.1).unwrap();
                    let bound = 2.0 * (alpha * 127f64.sqrt()).atan() + 1e-12;
                    for s in samples_of(LOBE_SAMPLES, &boundary(&frame, wi, alpha, etas)) {
                        let smooth = if s.refracted { straight } else { mirror };
                        let angle = s.direction.angle_between(smooth);
                        assert!(
                            angle <= bound,
                            "{what}: {angle:e} rad off (bound {bound:e})"
                        );
                    }
                }
            }
        }
        assert!(largest < previous, "α {alpha}: {largest} after {previous}");
        previous = largest;
    }
}

/// A slab's two rough faces: the paths of the first crossing (`count`
/// points, into glass at `μ`), each crossing the parallel far face (out of
/// the glass, reflections kept) along the one normal of its stratum
/// (`second_crossing_samples`). Returns `Σ_k w_k g_k` (`g_k` the summed
/// weights of path `k`'s second crossing) and `Σ_k w_k A(μ_k)`, its value
/// with each path's second crossing integrated by `reference_points` of
/// the Hammersley set instead.
fn two_crossings(count: u32, reference_points: u32, alpha: f64, mu: f64) -> (f64, f64) {
    let frame = SurfaceFrame::from_normal(DVec3::Z);
    let entry = Boundary {
        reflections: false,
        ..boundary(&frame, view(mu), alpha, (1.0, 1.5))
    };
    let (mut one_point, mut integrated) = (0.0, 0.0);
    for s in samples_of(count, &entry) {
        // The far face seen from inside: its normal towards the path's
        // origin (+Z), the path arriving along `s.direction`.
        let exit = boundary(&frame, -s.direction, alpha, (1.5, 1.0));
        let g: f64 = second_crossing_samples(&exit, s.stratum)
            .iter()
            .map(|t| t.weight)
            .sum();
        let a: f64 = samples_of(reference_points, &exit)
            .iter()
            .map(|t| t.weight)
            .sum();
        one_point += s.weight * g;
        integrated += s.weight * a;
    }
    (one_point, integrated)
}

/// The second rough crossing, one normal a path, integrates the far face
/// over the first crossing's paths: on a slab (into glass, then out of
/// it), `Σ_k w_k g_k` is `Σ_k w_k A(μ_k)`, each path's exit albedo by the
/// 4096-point rule.
///
/// Tolerance: the 64 paths are a 64-point rule of the exit's albedo
/// weighted by the entry's (weights summing to at most 1), so the
/// 64-point rule's error out of glass bounds it, 3·10⁻² (unit test
/// `the_sampled_weights_sum_to_the_walter_albedo`), plus the 4096-point
/// rule's own, scaled from it by `log N / N`: 8.1·10⁻⁴. With 4096 paths
/// the error falls below the 4096-point bound (twice 8.1·10⁻⁴, the
/// reference's and the rule's), which pairing the strata wrongly (every
/// path the same point, say) would not.
#[test]
fn the_second_crossing_integrates_the_far_face() {
    let own = 3e-2 * (4096f64.ln() / 4096.0) / (64f64.ln() / 64.0);
    for alpha in [0.0025, 0.09, 0.25, 1.0] {
        for mu in [1.0, 0.7, 0.3] {
            let (got, want) = two_crossings(LOBE_SAMPLES, 4096, alpha, mu);
            let what = format!("α {alpha} μ {mu}");
            eprintln!("{what}: {got:.6} vs {want:.6} ({:.1e})", got - want);
            assert!((got - want).abs() <= 3e-2 + own, "{what}: {got} vs {want}");
            assert!(got <= 1.0 + 1e-12, "{what}: {got}");
        }
    }
    for (alpha, mu) in [(0.25, 0.7), (1.0, 0.3)] {
        let (got, want) = two_crossings(4096, 4096, alpha, mu);
        eprintln!(
            "4096 paths, α {alpha} μ {mu}: {got:.6} vs {want:.6} ({:.1e})",
            got - want
        );
        assert!(
            (got - want).abs() <= 2.0 * own,
            "α {alpha} μ {mu}: {got} vs {want}"
        );
    }
}
