//! The environment BRDF of the split-sum approximation (Karis 2013, "Real
//! Shading in Unreal Engine 4", SIGGRAPH course notes, eq. 4-5): the
//! directional albedo of GGX with height-correlated Smith `G` split into a
//! scale and a bias of Schlick's `F0`,
//!
//! `∫ f_r cos θ_i dω_i = F0 · A(μ, α) + B(μ, α)`,
//! `A = ∫ (1 − w)·D·Vis·cos θ_i dω_i`, `B = ∫ w·D·Vis·cos θ_i dω_i`,
//! `w = (1 − V·H)⁵`,
//!
//! tabulated over `√μ` (`μ = N·V`) and `√α` (both 0..1, nodes at both
//! ends, [`SIZE`] a side) and looked up bilinearly. `A + B` is `E(μ, α)`, the
//! directional albedo with `F = 1` that energy compensation divides by
//! (Turquin 2019).
//!
//! Computed here by quadrature: [`QUADRATURE_SAMPLES`] GGX-distributed
//! half vectors of the Hammersley set per entry (deterministic; the
//! estimator `G·(V·H)/((N·H)(N·V))` of Karis's listing), in f64, stored in
//! f32 (what the GPU reads; the CPU twin reads the same f32 values).
//! The table's own error in `E = A + B`, measured (test below): bilinear
//! interpolation at most 2.3e-3 for μ ≥ 0.1, 1.0e-2 for μ ≥ 0.01, 7.5e-2
//! in the corner μ, α < 1e-3 (where `E` has no limit); the quadrature
//! 5.9e-3 at its worst (grazing, α = 0.05), 5e-5 at α = 1.
//!
//! WGSL twin of the lookup: `environment_dfg` in shaders/environment.wgsl.
//! `E = A + B` is also kept per node ([`DfgTable::albedo_nodes`]) for
//! energy compensation (`material::brdf::energy`), whose GPU twin reads
//! the same nodes from the globals (`ms_albedo` in shaders/brdf/energy.wgsl).

use super::DistributionTerm;
use super::microfacet::{schlick_weight, vis_smith_ggx_correlated};
use std::f64::consts::TAU;
use std::sync::OnceLock;

/// Entries per side (μ and α).
pub const SIZE: usize = 32;

/// Half vectors per entry.
pub const QUADRATURE_SAMPLES: u32 = 4096;

/// The smallest `μ` the table is computed at (its first node, μ = 0, where
/// `A` and `B` have a finite limit that the quadrature cannot evaluate).
const MU_MIN: f64 = 1e-4;

/// `[A, B]` at node `(√μ_i, √α_j) = (i, j)/(SIZE − 1)`, row-major by α
/// (both axes in square roots: the albedo changes fastest towards
/// grazing and towards α = 0, where the square root puts a quarter of the
/// nodes below 1/16).
pub struct DfgTable {
    pub entries: Vec<[f32; 2]>,
    /// `E = A + B` at the same nodes (the sum in f64, rounded once): the
    /// albedo energy compensation divides by, the same f32 values on the
    /// CPU ([`DfgTable::albedo`]) and the GPU (`Globals::albedo`,
    /// [`DfgTable::albedo_uniform`]).
    pub albedo_nodes: Vec<f32>,
}

/// The table (computed once per process, about 4 M BRDF evaluations).
pub fn table() -> &'static DfgTable {
    static TABLE: OnceLock<DfgTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        use rayon::prelude::*;
        let node = |k: usize| k as f64 / (SIZE - 1) as f64;
        let sums: Vec<[f64; 2]> = (0..SIZE * SIZE)
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % SIZE, k / SIZE);
                let mu = (node(i) * node(i)).max(MU_MIN);
                integrate(mu, node(j) * node(j), QUADRATURE_SAMPLES)
            })
            .collect();
        DfgTable {
            entries: sums.iter().map(|[a, b]| [*a as f32, *b as f32]).collect(),
            albedo_nodes: sums.iter().map(|[a, b]| (a + b) as f32).collect(),
        }
    })
}

/// `[A, B]` at `(μ, α)` by `n` GGX-sampled half vectors (Hammersley).
pub fn integrate(mu: f64, alpha: f64, n: u32) -> [f64; 2] {
    let v = glam::DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    let alpha2 = alpha * alpha;
    let (mut a, mut b) = (0.0, 0.0);
    for k in 0..n {
        let u1 = (k as f64 + 0.5) / n as f64;
        let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
        // GGX's D(h)·cos θ_h as a density of h (Walter et al. 2007, eq. 35).
        let cos_h = ((1.0 - u1) / (1.0 + (alpha2 - 1.0) * u1)).sqrt();
        let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
        let phi = TAU * u2;
        let h = glam::DVec3::new(sin_h * phi.cos(), sin_h * phi.sin(), cos_h);
        let vh = v.dot(h);
        let l = h * (2.0 * vh) - v;
        if l.z <= 0.0 || vh <= 0.0 {
            continue;
        }
        // f_r cos θ_i / pdf(l) with pdf(l) = D·cos θ_h / (4 V·H):
        // Vis·4·cos θ_i·(V·H)/cos θ_h.
        let vis = vis_smith_ggx_correlated(alpha, l.z, mu, vh, vh);
        let weight = vis * 4.0 * l.z * vh / cos_h;
        let w = schlick_weight(vh);
        a += (1.0 - w) * weight;
        b += w * weight;
    }
    [a / n as f64, b / n as f64]
}

/// The bilinear interpolation at `(μ, α)` of the grid `node(i, j)`
/// (column `i` of `√μ`, row `j` of `√α`, both clamped to [0, 1]) that
/// both of the tables share; the WGSL twins (`environment_dfg`,
/// `ms_albedo`) write it out for their own storage.
fn bilinear(mu: f64, alpha: f64, node: impl Fn(usize, usize) -> f64) -> f64 {
    let last = (SIZE - 1) as f64;
    let x = mu.clamp(0.0, 1.0).sqrt() * last;
    let y = alpha.clamp(0.0, 1.0).sqrt() * last;
    let (x0, y0) = (x.floor().min(last - 1.0), y.floor().min(last - 1.0));
    let (fx, fy) = (x - x0, y - y0);
    let (i, j) = (x0 as usize, y0 as usize);
    let lo = node(i, j) * (1.0 - fx) + node(i + 1, j) * fx;
    let hi = node(i, j + 1) * (1.0 - fx) + node(i + 1, j + 1) * fx;
    lo * (1.0 - fy) + hi * fy
}

impl DfgTable {
    /// `[A, B]` at `(μ, α)`, bilinear between the nodes, both clamped to
    /// [0, 1]. Twin: `environment_dfg` in shaders/environment.wgsl.
    pub fn lookup(&self, mu: f64, alpha: f64) -> [f64; 2] {
        [0, 1].map(|c| bilinear(mu, alpha, |i, j| self.entries[j * SIZE + i][c] as f64))
    }

    /// `E(μ, α) = A + B`: the directional albedo of GGX with `F = 1`,
    /// bilinear between the nodes of [`DfgTable::albedo_nodes`] as
    /// [`DfgTable::lookup`]. Twin: `ms_albedo` in shaders/brdf/energy.wgsl.
    pub fn albedo(&self, mu: f64, alpha: f64) -> f64 {
        bilinear(mu, alpha, |i, j| self.albedo_nodes[j * SIZE + i] as f64)
    }

    /// [`DfgTable::albedo_nodes`] four to a row, as `Globals::albedo`
    /// (shaders/common.wgsl) holds them: node `k` at `[k / 4][k % 4]`.
    pub fn albedo_uniform(&self) -> [[f32; 4]; SIZE * SIZE / 4] {
        let mut out = [[0.0; 4]; SIZE * SIZE / 4];
        for (k, e) in self.albedo_nodes.iter().enumerate() {
            out[k / 4][k % 4] = *e;
        }
        out
    }
}

/// The GGX α standing in for distribution `d`: its own slope scale `m`
/// (Beckmann, the Gaussians: the same narrow lobe to first order), GGX's
/// α, and for Blinn's exponent `e` the Beckmann slope of the same lobe,
/// `√(2/(e + 2))` (Walter et al. 2007, eq. 33's Phong–Beckmann match).
/// The table is read at this α for the distributions that are not GGX
/// (the split-sum mode's lobe, energy compensation's albedo). Twin: the
/// `alpha` of `prefiltered_terms` in shaders/environment.wgsl.
pub fn ggx_alpha(d: DistributionTerm) -> f64 {
    match d {
        DistributionTerm::Beckmann { m }
        | DistributionTerm::Gaussian { m }
        | DistributionTerm::GaussianNormalized { m, .. } => m,
        DistributionTerm::Ggx { alpha } => alpha,
        DistributionTerm::Blinn { e } | DistributionTerm::BlinnNormalized { e } => {
            (2.0 / (e + 2.0)).sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const E05: f64 = 0.4507;
    const E_AVG: f64 = 0.4091;

    /// With α → 0 the surface is a mirror: all light reflected, `A + B = 1`,
    /// and `B` is Schlick's weight at the view angle.
    #[test]
    fn a_smooth_surface_reflects_everything() {
        let [a, b] = integrate(0.5, 0.0, 256);
        assert!((a + b - 1.0).abs() < 1e-9, "{a} {b}");
        assert!((b - 0.5f64.powi(5)).abs() < 1e-9, "{b}");
    }

    /// The white furnace before energy compensation: a white conductor
    /// (`F = 1`) of GGX with height-correlated Smith at α = 1 keeps
    /// `E(μ, 1)` of the light arriving from a uniform
    /// white sky, and `E_avg = 2∫ E μ dμ` averaged over the hemisphere
    /// (three.js users measured about 0.45 at the highest roughness).
    /// At μ = 1, α = 1 it has a closed form: `D = 1/π`, `Vis = ½/(1 + μ_i)`,
    /// so `E = ∫₀¹ μ_i/(1 + μ_i) dμ_i = 1 − ln 2 = 0.3069`. Measured (this
    /// session): E(1, 1) = 0.3069, E(0.5, 1) = 0.4507, E_avg = 0.4091;
    /// asserted to 1e-3 (the quadrature's error at α = 1 is 5e-5, the
    /// midpoint rule's in μ below that).
    #[test]
    fn the_rough_white_furnace_loses_half_the_light() {
        let e = |mu: f64| {
            let [a, b] = integrate(mu, 1.0, QUADRATURE_SAMPLES);
            a + b
        };
        let n = 64;
        let e_avg: f64 = (0..n)
            .map(|k| {
                let mu = (k as f64 + 0.5) / n as f64;
                2.0 * e(mu) * mu / n as f64
            })
            .sum();
        let (e1, e05) = (e(1.0), e(0.5));
        eprintln!(
            "white furnace, α = 1, F = 1: E(1) = {e1:.4}, E(0.5) = {e05:.4}, E_avg = {e_avg:.4}"
        );
        let exact = 1.0 - std::f64::consts::LN_2;
        assert!(
            (e1 - exact).abs() < 1e-3 && (e05 - E05).abs() < 1e-3 && (e_avg - E_AVG).abs() < 1e-3,
            "{e1} {e05} {e_avg}"
        );
    }

    /// The table's error: bilinear lookup between the nodes against the
    /// quadrature at the cell centres (all cells; those with μ ≥ 0.01; with
    /// μ ≥ 0.1), and the quadrature against one with 64 times the samples
    /// at a few points. Measured at commit c9acb23: see the asserts, which
    /// hold those numbers with less than 30 % to spare; the worst cell is
    /// the corner μ, α → 0, where `E` has no limit (1 along α = 0, 0
    /// along μ = 0).
    #[test]
    fn the_table_error_is_what_the_docs_say() {
        let t = table();
        let mut worst = [0.0f64; 3];
        for j in 0..SIZE - 1 {
            for i in 0..SIZE - 1 {
                let x = (i as f64 + 0.5) / (SIZE - 1) as f64;
                let y = (j as f64 + 0.5) / (SIZE - 1) as f64;
                let (mu, alpha) = (x * x, y * y);
                let exact = integrate(mu, alpha, QUADRATURE_SAMPLES);
                let got = t.lookup(mu, alpha);
                let e = (exact[0] + exact[1] - got[0] - got[1]).abs();
                for (w, floor) in worst.iter_mut().zip([0.0, 0.01, 0.1]) {
                    if mu >= floor {
                        *w = w.max(e);
                    }
                }
            }
        }
        let mut quad = 0.0f64;
        for (mu, alpha) in [
            (0.05, 0.3),
            (0.5, 0.5),
            (0.9, 1.0),
            (0.2, 1.0),
            (0.01, 0.05),
        ] {
            let a = integrate(mu, alpha, QUADRATURE_SAMPLES);
            let b = integrate(mu, alpha, 64 * QUADRATURE_SAMPLES);
            quad = quad.max((a[0] + a[1] - b[0] - b[1]).abs());
        }
        eprintln!(
            "DFG table: interpolation {:.2e} (μ ≥ 0.01: {:.2e}, μ ≥ 0.1: {:.2e}), quadrature {quad:.2e}",
            worst[0], worst[1], worst[2]
        );
        assert!(worst[0] < 0.1 && worst[1] < 1.4e-2 && worst[2] < 3e-3 && quad < 8e-3);
    }
}
