//! The exact directional albedo of the sheen lobe,
//! `E(μ, α) = ∫ D_sh V_sh μ' dω'` over the hemisphere for one direction at
//! `N·ω = μ` (contract: "Sheen"; pinned choice 6: "the exact directional
//! albedo of the specified `D_sh V_sh`, not a table"), which
//! `KHR_materials_sheen`'s albedo scaling (Kulla & Conty 2017, "Revisiting
//! Physically Based Shading at Imageworks", §"Energy compensation") reads.
//!
//! By symmetry `E(μ) = 2 ∫₀¹ dμ' ∫₀^π dφ D_sh(H) V_sh(μ, μ') μ'`, with the
//! two directions `(√(1−μ²), 0, μ)` and `(√(1−μ'²) cos φ, √(1−μ'²) sin φ, μ')`.
//! The integral over `μ'` is adaptive Gauss-Kronrod (7-15 points, panels
//! split until the Kronrod-Gauss difference is below 10⁻¹² absolute or
//! 10⁻¹⁰ relative of the whole), starting from panels graded towards
//! `μ' = 0` where the lobe of a small `α` lives near grazing `μ`, and
//! broken at `μ' = ½` where Λ's fit changes branch. The integral over `φ`
//! is composite Gauss-Legendre (16 points on each of 6 panels graded
//! towards `φ = π`, where `H → N` and the lobe of `α > ½` has a cusp). The
//! test below bounds the result's error against a quadrature of four
//! times the resolution.
//!
//! Results are kept per thread for the `(μ, α)` they were asked for: the
//! two albedos of an evaluation are often asked again (the light's
//! direction over a quadrature of the view, or a scene's few `α`).
//!
//! The GPU reads a table of it (`shaders/brdf/gltf_layers/sheen_albedo.wgsl`,
//! [`SHEEN_ALBEDO_TABLE_SIZE`]): its error is bounded by
//! [`SHEEN_ALBEDO_TABLE_ERROR`], measured in `tests/layer_equivalence.rs`.

use super::sheen::{d_charlie, v_sheen};
use glam::DVec3;
use std::cell::RefCell;
use std::collections::HashMap;
use std::f64::consts::PI;

/// Gauss-Kronrod 7-15 nodes on [−1, 1] (positive half; the centre last),
/// Kronrod weights, and the weights of the embedded 7-point Gauss rule
/// (on the odd nodes).
const GK_NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const GK_KRONROD: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_728,
];
const GK_GAUSS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// 16-point Gauss-Legendre nodes and weights on [−1, 1] (positive half).
const GL16_NODES: [f64; 8] = [
    0.095_012_509_837_637_44,
    0.281_603_550_779_258_9,
    0.458_016_777_657_227_4,
    0.617_876_244_402_643_7,
    0.755_404_408_355_003,
    0.865_631_202_387_831_7,
    0.944_575_023_073_232_6,
    0.989_400_934_991_649_9,
];
const GL16_WEIGHTS: [f64; 8] = [
    0.189_450_610_455_068_5,
    0.182_603_415_044_923_6,
    0.169_156_519_395_002_5,
    0.149_595_988_816_576_7,
    0.124_628_971_255_533_9,
    0.095_158_511_682_492_78,
    0.062_253_523_938_647_89,
    0.027_152_459_411_754_09,
];

/// One Gauss-Kronrod panel: (Kronrod estimate, |Kronrod − Gauss|).
fn gk15(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let centre = f(c);
    let (mut k, mut g) = (GK_KRONROD[7] * centre, GK_GAUSS[3] * centre);
    for (j, (&x, &w)) in GK_NODES.iter().zip(&GK_KRONROD).take(7).enumerate() {
        let pair = f(c - h * x) + f(c + h * x);
        k += w * pair;
        if j % 2 == 1 {
            g += GK_GAUSS[j / 2] * pair;
        }
    }
    (k * h, ((k - g) * h).abs())
}

/// The relative error at which a panel is left alone whatever its share of
/// the absolute tolerance: a few hundred roundings of `f64`. A narrow
/// sheen's `E` near its cusp is large (`E(2·10⁻⁶) ≈ 1.2·10⁴` at the
/// roughness floor), and there the Kronrod-Gauss difference of a panel is
/// rounding noise above any absolute share, so without this stop the
/// recursion ran to its full depth (201 s for that one value, measured
/// 2026-12-06; 0.005 s with it).
const PANEL_RELATIVE: f64 = 1e-13;

/// Adaptive Gauss-Kronrod over `[a, b]` to `tol` absolute, a panel also
/// accepted at [`PANEL_RELATIVE`] of its own value. The integrands here
/// are non-negative, so the total error is at most
/// `tol + PANEL_RELATIVE · ∫f`.
fn adaptive(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
    let (value, error) = gk15(f, a, b);
    if error <= tol || error <= PANEL_RELATIVE * value.abs() || depth == 0 {
        return value;
    }
    let m = 0.5 * (a + b);
    adaptive(f, a, m, 0.5 * tol, depth - 1) + adaptive(f, m, b, 0.5 * tol, depth - 1)
}

/// Composite Gauss-Legendre over the panels between consecutive `breaks`,
/// each split into `split` equal parts of 16 points.
fn gauss_legendre(f: &dyn Fn(f64) -> f64, breaks: &[f64], split: usize) -> f64 {
    let mut sum = 0.0;
    for w in breaks.windows(2) {
        let step = (w[1] - w[0]) / split as f64;
        for s in 0..split {
            let a = w[0] + step * s as f64;
            let (c, h) = (a + 0.5 * step, 0.5 * step);
            for (&node, &weight) in GL16_NODES.iter().zip(&GL16_WEIGHTS) {
                let x = h * node;
                sum += weight * (f(c - x) + f(c + x)) * h;
            }
        }
    }
    sum
}

/// Break points of `φ` on [0, π], graded towards π.
const PHI_BREAKS: [f64; 7] = [
    0.0,
    0.5 * PI,
    0.75 * PI,
    0.875 * PI,
    0.9375 * PI,
    0.984375 * PI,
    PI,
];

/// `E(μ, α)` with the `φ` panels split `phi_split` times (1: the
/// reference's resolution) and the `μ'` tolerance `tol`.
fn albedo_with(cos: f64, alpha: f64, phi_split: usize, tol: f64) -> f64 {
    if cos <= 0.0 {
        return 0.0;
    }
    let c = cos.min(1.0);
    let wo = DVec3::new((1.0 - c * c).max(0.0).sqrt(), 0.0, c);
    let inner = |mu: f64| {
        if mu <= 0.0 {
            return 0.0;
        }
        let s = (1.0 - mu * mu).max(0.0).sqrt();
        let v = v_sheen(alpha, mu, c) * mu;
        if v == 0.0 {
            return 0.0;
        }
        let lobe = |phi: f64| {
            let wi = DVec3::new(s * phi.cos(), s * phi.sin(), mu);
            let sum = wi + wo;
            let len2 = sum.length_squared();
            if len2 <= 0.0 {
                return 0.0;
            }
            let sin2_h = (sum.x * sum.x + sum.y * sum.y) / len2;
            let cos_h = sum.z / len2.sqrt();
            d_charlie(alpha, cos_h, sin2_h)
        };
        2.0 * v * gauss_legendre(&lobe, &PHI_BREAKS, phi_split)
    };
    // Panels graded towards 0 at the lobe's width in μ' (about 2√(2α)
    // near grazing), then ½ and 1.
    let width = (8.0 * alpha).sqrt().clamp(1e-6, 0.25);
    let mut breaks = vec![0.0];
    let mut x = width / 64.0;
    while x < 0.5 {
        breaks.push(x);
        x *= 4.0;
    }
    breaks.extend([0.5, 1.0]);
    let panels = breaks.len() - 1;
    breaks
        .windows(2)
        .map(|w| adaptive(&inner, w[0], w[1], tol / panels as f64, 30))
        .sum()
}

/// The absolute tolerance of the `μ'` integral.
const TOLERANCE: f64 = 1e-11;

thread_local! {
    static CACHE: RefCell<HashMap<(u64, u64), f64>> = RefCell::new(HashMap::new());
}

/// Entries kept per thread before the cache starts over.
const CACHE_LIMIT: usize = 1 << 16;

/// `E(μ, α)`: the exact directional albedo of the sheen lobe `D_sh V_sh`
/// at `N·ω = μ`, sheen `α = α_sh` (see the module doc).
pub fn sheen_albedo(cos: f64, alpha: f64) -> f64 {
    sheen_albedo_computed(cos, alpha).0
}

/// [`sheen_albedo`], and whether the integral was computed (not found in
/// this thread's cache of recent values): what a
/// [`SheenAlbedo`](super::sheen_curve::SheenAlbedo) counts against the
/// cost of its curve, since a value found again costs nothing.
pub fn sheen_albedo_computed(cos: f64, alpha: f64) -> (f64, bool) {
    let key = (cos.to_bits(), alpha.to_bits());
    if let Some(e) = CACHE.with(|c| c.borrow().get(&key).copied()) {
        return (e, false);
    }
    let e = albedo_with(cos, alpha, 1, TOLERANCE);
    CACHE.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() >= CACHE_LIMIT {
            c.clear();
        }
        c.insert(key, e);
    });
    (e, true)
}

/// `E` at four times the `φ` resolution and a hundredth of the `μ'`
/// tolerance: the check of [`sheen_albedo`]'s own error.
pub fn sheen_albedo_fine(cos: f64, alpha: f64) -> f64 {
    albedo_with(cos, alpha, 4, TOLERANCE / 100.0)
}

/// Nodes per axis of the GPU's table of `E` (stored in
/// [`super::sheen_albedo_nodes`], bound as `sheen_albedo_table` in
/// `shaders/brdf/gltf_layers/sheen_albedo.wgsl`).
///
/// The table holds `g = r_sh · E(μ, α_sh(r_sh))` at node `(i, j)`, `i`
/// the fast index, with `μ_i = μ_min + (1 − μ_min) (i/(N − 1))⁴` and
/// `r_j = j/(N − 1)`, rounded to `f32`; the lookup
/// ([`sheen_albedo_lookup`]) is bilinear in `(u, r_sh)`,
/// `u = ((μ − μ_min)/(1 − μ_min))^¼`, and returns `g / r_sh`. Why this
/// form: near grazing `E` varies with `log μ` (it rises from 0.03 at
/// `μ = 1` to its peak within `μ < 10⁻³`), which the fourth root spreads
/// over a quarter of the nodes; and for a narrow sheen `E ∝ 1/r_sh` near
/// grazing (`r_sh E ≈ 0.18` for every `r_sh ≤ 0.1` at `μ = 10⁻⁴`), which
/// `g` makes nearly linear. The table of `E` itself in `(√μ, r_sh)`,
/// 32², that this replaces was off by up to 0.6 in its first column
/// (`μ < 10⁻³`, interpolated towards `E = 0` at `μ = 0`).
///
/// Its domain: `μ ≥ μ_min` ([`SHEEN_ALBEDO_COS_MIN`], θ ≤ 89.994°;
/// below, `E(μ_min)`: the exact `E` of the specified `V_sh` is not even
/// monotone there, and rises again towards `μ ≈ 10⁻⁶`) and `r_sh = 0` or
/// `r_sh ≥ 1/(N − 1)` (between, `g` runs linearly from 0 and the lookup
/// returns `E(1/(N − 1))`, which underestimates a sheen narrower than the
/// table resolves); at `r_sh = 0` it returns 0, the exact `E` of the
/// roughness floor for θ ≤ 89° (contract, pinned choice 5). Its error
/// over that domain is [`SHEEN_ALBEDO_TABLE_ERROR`].
pub const SHEEN_ALBEDO_TABLE_SIZE: usize = 64;

/// The smallest `μ = cos θ` of the table (θ = 89.994°).
pub const SHEEN_ALBEDO_COS_MIN: f64 = 1e-4;

/// The table's largest error over its domain ([`SHEEN_ALBEDO_TABLE_SIZE`])
/// by band of `r_sh`: `(from, bound)`, `|E_table − E| ≤ bound` for
/// `r_sh ≥ from` (up to the next band), measured against the exact
/// quadrature on the nodes and the cell centres of both axes by
/// `sheen_albedo_table_error` (tests/layer_equivalence.rs; 2026-12-05):
/// 0.209 (at E = 5.4: 4 %) for `r_sh < 0.1`, where a narrow sheen's `E`
/// peaks within `μ < 10⁻²`; 2.39·10⁻³ for `0.1 ≤ r_sh < 0.23`;
/// 7.39·10⁻⁴ for `r_sh ≥ 0.23`, where `E ≤ 1` (the 32² table in
/// `(√μ, r_sh)` it replaces was off by 0.6 there). Rounded up.
pub const SHEEN_ALBEDO_TABLE_ERROR: &[(f64, f64)] = &[
    (1.0 / (SHEEN_ALBEDO_TABLE_SIZE - 1) as f64, 0.22),
    (0.1, 2.5e-3),
    (0.23, 8e-4),
];

/// The bound of [`SHEEN_ALBEDO_TABLE_ERROR`] at `r_sh`: 0 at `r_sh = 0`
/// (both are 0), infinite between 0 and the first row (outside the
/// domain).
pub fn sheen_table_error_bound(sheen_roughness: f64) -> f64 {
    if sheen_roughness <= 0.0 {
        return 0.0;
    }
    SHEEN_ALBEDO_TABLE_ERROR
        .iter()
        .rev()
        .find(|(from, _)| sheen_roughness >= *from)
        .map_or(f64::INFINITY, |&(_, bound)| bound)
}

/// `μ` of the table's column `i`.
pub fn sheen_table_cos(i: usize) -> f64 {
    let u = i as f64 / (SHEEN_ALBEDO_TABLE_SIZE - 1) as f64;
    SHEEN_ALBEDO_COS_MIN + (1.0 - SHEEN_ALBEDO_COS_MIN) * u.powi(4)
}

/// `r_sh` of the table's row `j`.
pub fn sheen_table_roughness(j: usize) -> f64 {
    j as f64 / (SHEEN_ALBEDO_TABLE_SIZE - 1) as f64
}

/// The table's nodes, computed by the exact quadrature (what
/// [`super::sheen_albedo_nodes`] stores; the test `sheen_table_is_current`
/// compares them).
pub fn sheen_albedo_table() -> Vec<f32> {
    use rayon::prelude::*;
    let n = SHEEN_ALBEDO_TABLE_SIZE;
    (0..n * n)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % n, k / n);
            let r = sheen_table_roughness(j);
            (r * sheen_albedo(sheen_table_cos(i), super::sheen::sheen_alpha(r))) as f32
        })
        .collect()
}

/// `E(μ, α_sh(r_sh))` from the table `nodes` (see
/// [`SHEEN_ALBEDO_TABLE_SIZE`]): `g` bilinear in `(u, r_sh)`, over
/// `r_sh`. The f64 twin of the GPU's `sheen_albedo_lookup`.
pub fn sheen_albedo_lookup(cos: f64, sheen_roughness: f64, nodes: &[f32]) -> f64 {
    let n = SHEEN_ALBEDO_TABLE_SIZE;
    let last = (n - 1) as f64;
    let t = (cos.clamp(SHEEN_ALBEDO_COS_MIN, 1.0) - SHEEN_ALBEDO_COS_MIN)
        / (1.0 - SHEEN_ALBEDO_COS_MIN);
    let x = t.sqrt().sqrt() * last;
    let r = sheen_roughness.clamp(0.0, 1.0);
    let y = r * last;
    let (x0, y0) = (x.floor().min(last - 1.0), y.floor().min(last - 1.0));
    let (fx, fy) = (x - x0, y - y0);
    let (i, j) = (x0 as usize, y0 as usize);
    let node = |i: usize, j: usize| nodes[j * n + i] as f64;
    let lo = node(i, j) * (1.0 - fx) + node(i + 1, j) * fx;
    let hi = node(i, j + 1) * (1.0 - fx) + node(i + 1, j + 1) * fx;
    let g = lo * (1.0 - fy) + hi * fy;
    if r > 0.0 { g / r } else { 0.0 }
}
