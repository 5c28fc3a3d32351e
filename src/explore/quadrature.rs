//! Adaptive Gauss-Kronrod quadrature on graded panels: the numerical tool
//! behind [`super::albedo`] and [`super::gloss`].
//!
//! * **Rule.** The 7-point Gauss rule and its 15-point Kronrod extension
//!   (QUADPACK's `qk15`; Piessens et al., *QUADPACK*, 1983, §2.2). The
//!   Kronrod nodes contain the Gauss nodes, so one set of 15 evaluations
//!   gives two results of different order: G7 is exact for polynomials of
//!   degree ≤ 13, K15 for degree ≤ 22. The value kept is K15; `|K15 − G7|`
//!   is the panel's error bound (QUADPACK's raw estimate, without its
//!   empirical down-scaling: for smooth integrands K15's error is orders
//!   of magnitude below G7's, so the difference bounds it).
//! * **Graded panels.** A BRDF lobe is smooth but can be very narrow (a
//!   Phong exponent of 10⁶ has an angular width of ~1.4·10⁻³ rad, a
//!   roughness of 10⁻⁴ one of ~2·10⁻⁴ rad), and its peak sits at a known
//!   point. Panels that shrink geometrically towards that point with a
//!   fixed rule in each converge exponentially whatever the lobe width
//!   between the finest panel and the whole interval ("hp-graded" meshes:
//!   Schwab, *p- and hp-Finite Element Methods*, 1998, §4.2); see [`graded`].
//! * **Adaptivity.** A panel whose `|K15 − G7|` exceeds the tolerance is
//!   halved, recursively (QUADPACK's `qag` strategy, here depth-first with
//!   a depth cap). This resolves kinks that are not at breakpoints (the
//!   `min` of the V-groove term, the branch of the Smith–Beckmann fit):
//!   there the rules converge only algebraically, and only the panels
//!   holding the kink are refined.

use crate::scene::Rgb;

/// Kronrod nodes on `[0, 1)` (the rule is symmetric), descending, with
/// the Gauss nodes at odd indices and 0 last (QUADPACK `qk15`, `xgk`).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights for [`XGK`] (`wgk`).
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights for the nodes `XGK[1], XGK[3], XGK[5], XGK[7]` (`wg`).
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// One Gauss-Kronrod 7-15 panel on `[a, b]` of an integrand that returns a
/// value and a bound on that value's own error (an inner integral; `0` for
/// plain functions). Returns `(K15, G7, K15-weighted inner error)`.
pub fn gk15(a: f64, b: f64, f: &mut impl FnMut(f64) -> (Rgb, Rgb)) -> (Rgb, Rgb, Rgb) {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let (v, e) = f(mid);
    let (mut k, mut g, mut inner) = (v * WGK[7], v * WG[3], e * WGK[7]);
    for j in 0..7 {
        let dx = half * XGK[j];
        let (v1, e1) = f(mid - dx);
        let (v2, e2) = f(mid + dx);
        let v = v1 + v2;
        k += v * WGK[j];
        inner += (e1 + e2) * WGK[j];
        if j % 2 == 1 {
            g += v * WG[j / 2];
        }
    }
    (k * half, g * half, inner * half.abs())
}

/// When a panel is good enough: `|K15 − G7| ≤ rel · |Q| + abs` in every
/// channel, with `Q` the integral over all panels (first estimate). The
/// allowance does not shrink with the panel, so a kink is refined only
/// until its panel's error is negligible against the whole integral.
#[derive(Clone, Copy, Debug)]
pub struct Tolerance {
    pub rel: f64,
    pub abs: f64,
    /// Most halvings of an initial panel.
    pub max_depth: u32,
}

/// `∫ f` over the panels of `breaks` (ascending), each refined by halving
/// until it meets `tol`. Returns the value and its error bound: the sum of
/// `|K15 − G7|` over the final panels plus the integrated inner errors.
pub fn integrate(
    breaks: &[f64],
    tol: Tolerance,
    f: &mut impl FnMut(f64) -> (Rgb, Rgb),
) -> (Rgb, Rgb) {
    let first: Vec<_> = breaks
        .windows(2)
        .map(|p| (p[0], p[1], gk15(p[0], p[1], f)))
        .collect();
    let total = first.iter().fold(Rgb::ZERO, |s, (_, _, (k, _, _))| s + *k);
    let allowed = tol.rel * total.abs().max_element() + tol.abs;
    let (mut value, mut error) = (Rgb::ZERO, Rgb::ZERO);
    for (a, b, estimate) in first {
        let (v, e) = refine(a, b, estimate, allowed, tol.max_depth, f);
        value += v;
        error += e;
    }
    (value, error)
}

/// Keeps the panel's estimate if good enough, else halves it.
fn refine(
    a: f64,
    b: f64,
    (k, g, inner): (Rgb, Rgb, Rgb),
    allowed: f64,
    depth: u32,
    f: &mut impl FnMut(f64) -> (Rgb, Rgb),
) -> (Rgb, Rgb) {
    let diff = (k - g).abs();
    if diff.max_element() <= allowed || depth == 0 {
        return (k, diff + inner);
    }
    let mid = 0.5 * (a + b);
    let left = gk15(a, mid, f);
    let right = gk15(mid, b, f);
    let (v1, e1) = refine(a, mid, left, allowed, depth - 1, f);
    let (v2, e2) = refine(mid, b, right, allowed, depth - 1, f);
    (v1 + v2, e1 + e2)
}

/// Growth factor of graded panels. 4 rather than the classical 2: a
/// Kronrod panel `[h, 4h]` still resolves a lobe of width ~h to ~10⁻¹⁰
/// (and the adaptive halving catches what it does not), at half the
/// panels of a factor of 2.
pub const GRADING: f64 = 4.0;

/// Breakpoints of `[a, b]` whose panels grow geometrically (by
/// [`GRADING`]) away from both ends: `h_a` is the first panel at `a`, `h_b`
/// the last one at `b` (each capped at half the interval). Ascending;
/// `[a, b]` when `b ≤ a`.
pub fn graded(a: f64, b: f64, h_a: f64, h_b: f64) -> Vec<f64> {
    if b <= a {
        return vec![a, b];
    }
    let mid = 0.5 * (a + b);
    let mut breaks = vec![a];
    let mut h = h_a;
    while h > 0.0 && a + h < mid {
        breaks.push(a + h);
        h *= GRADING;
    }
    breaks.push(mid);
    let mut right = Vec::new();
    let mut h = h_b;
    while h > 0.0 && b - h > mid {
        right.push(b - h);
        h *= GRADING;
    }
    breaks.extend(right.into_iter().rev());
    breaks.push(b);
    breaks.dedup();
    breaks
}

/// Inserts `x` into ascending `breaks` if it lies strictly inside.
pub fn insert_break(breaks: &mut Vec<f64>, x: f64) {
    let (first, last) = (breaks[0], breaks[breaks.len() - 1]);
    if x > first && x < last {
        let at = breaks.partition_point(|&b| b < x);
        if breaks[at] != x {
            breaks.insert(at, x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn scalar(f: impl Fn(f64) -> f64) -> impl FnMut(f64) -> (Rgb, Rgb) {
        move |x| (Rgb::splat(f(x)), Rgb::ZERO)
    }

    #[test]
    fn kronrod_and_gauss_have_their_degrees() {
        for degree in 0..=22 {
            let exact = if degree % 2 == 1 {
                0.0
            } else {
                2.0 / (degree as f64 + 1.0)
            };
            let (k, g, _) = gk15(-1.0, 1.0, &mut scalar(|x| x.powi(degree)));
            assert!((k.x - exact).abs() < 1e-14, "K15, degree {degree}: {}", k.x);
            if degree <= 13 {
                assert!((g.x - exact).abs() < 1e-14, "G7, degree {degree}: {}", g.x);
            }
        }
        // Degree 14 is beyond G7: the difference shows.
        let (k, g, _) = gk15(-1.0, 1.0, &mut scalar(|x| x.powi(14)));
        assert!((k.x - g.x).abs() > 1e-6);
    }

    #[test]
    fn graded_panels_resolve_a_narrow_peak() {
        let breaks = graded(0.0, 1.0, 1e-6, 1e-2);
        assert!(breaks.windows(2).all(|p| p[0] < p[1]));
        assert_eq!(
            (breaks[0], breaks[1], *breaks.last().unwrap()),
            (0.0, 1e-6, 1.0)
        );
        let w = 1e-4; // ∫₀¹ exp(−x²/w²) dx = w √π / 2
        let tol = Tolerance {
            rel: 1e-12,
            abs: 0.0,
            max_depth: 20,
        };
        let (v, e) = integrate(&breaks, tol, &mut scalar(|x| (-(x / w).powi(2)).exp()));
        let exact = w * PI.sqrt() / 2.0;
        assert!(
            (v.x - exact).abs() <= e.x && e.x < 1e-12 * exact,
            "{v} ± {e} vs {exact}"
        );
    }

    #[test]
    fn adaptivity_finds_a_kink_and_bounds_the_error() {
        // ∫₀¹ |x − 0.3| dx = (0.3² + 0.7²) / 2 = 0.29.
        let tol = Tolerance {
            rel: 1e-13,
            abs: 0.0,
            max_depth: 40,
        };
        let (v, e) = integrate(&[0.0, 1.0], tol, &mut scalar(|x| (x - 0.3).abs()));
        assert!((v.x - 0.29).abs() <= e.x && e.x < 1e-11, "{v} ± {e}");
    }

    #[test]
    fn breaks_insert_inside_only() {
        let mut b = vec![0.0, 1.0];
        insert_break(&mut b, 0.5);
        insert_break(&mut b, 0.5);
        insert_break(&mut b, 2.0);
        assert_eq!(b, vec![0.0, 0.5, 1.0]);
    }
}
