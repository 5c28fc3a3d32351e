//! A stack of the map's radiance averaged by a zonal kernel: a weight
//! `w_α(cos θ)` of the angle θ between the lookup direction `d` and the
//! light's direction `l` alone, one level per roughness of
//! [`super::prefiltered`]'s levels,
//! `L̃(d, α) = ∫ L(l) w_α(d·l) dl / ∫ w_α(d·l) dl` over the hemisphere
//! about `d`.
//!
//! Why: a lobe whose shape does not follow the mirror direction is not
//! the GGX stack's. The sheen's Charlie lobe (`KHR_materials_sheen`) seen
//! along the normal (`V = N = d`) is zonal about `d`, and its split-sum
//! radiance is this stack read at the normal (the reference's
//! `prefiltered_layers`, measured there against the integrated truth).
//! The kernel comes from the caller, since this module knows no material
//! ([`ZonalKernel`]).
//!
//! The integral is a product rule in (θ, φ) about `d`: in θ, [`THETA_NODES`]
//! nodes at the mass midpoints of equal-mass strata of `w_α(cos θ) sin θ`
//! (so a kernel concentrated in a narrow ring, as Charlie's at low
//! roughness near the horizon, puts every node there), in φ
//! [`PHI_NODES`] equally spaced, each rotated by the golden ratio per θ
//! node; every node reads the map's box-filtered mip whose texel matches
//! its solid angle (filtered importance sampling, as the GGX stack does:
//! Colbert & Křivánek 2007). The stack is smooth (the narrowest kernel
//! spans a ring), so it is [`ZONAL_WIDTH`] × `ZONAL_WIDTH/2` texels at
//! any map size, read bilinearly.
//!
//! WGSL twin: `prefiltered_zonal_lookup` in shaders/environment.wgsl.

use super::latlong;
use super::prefiltered::{LEVELS, Pyramid, bilinear_latlong, level_alpha, level_blend};
use crate::base::{Rgb, any_tangent};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Width of every level in texels (height half of it).
pub const ZONAL_WIDTH: u32 = 64;

/// θ nodes per texel.
pub const THETA_NODES: usize = 16;

/// φ nodes per θ node.
pub const PHI_NODES: usize = 24;

/// Cells of the 1-D table the θ nodes are placed by.
const CDF_CELLS: usize = 4096;

/// A zonal kernel: `ln w_α(cos θ)` (−∞ where the weight is 0), `α` the
/// level's [`level_alpha`]; `name` tells stacks apart in a map's cache.
#[derive(Clone, Copy, Debug)]
pub struct ZonalKernel {
    pub name: &'static str,
    pub ln_weight: fn(alpha: f64, cos_theta: f64) -> f64,
}

/// The stack: level `k` is rows `k·height .. (k+1)·height`.
#[derive(Debug, PartialEq)]
pub struct ZonalStack {
    pub name: &'static str,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
}

/// One level's θ nodes: (θ, the stratum's width in θ).
fn theta_nodes(kernel: &ZonalKernel, alpha: f64) -> Vec<(f64, f64)> {
    let cell = FRAC_PI_2 / CDF_CELLS as f64;
    let ln: Vec<f64> = (0..CDF_CELLS)
        .map(|i| {
            let theta = (i as f64 + 0.5) * cell;
            (kernel.ln_weight)(alpha, theta.cos()) + theta.sin().ln()
        })
        .collect();
    let top = ln.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mass: Vec<f64> = ln.iter().map(|&l| (l - top).exp()).collect();
    let total: f64 = mass.iter().sum();
    // Cumulative mass at the cells' upper ends.
    let mut cumulative = Vec::with_capacity(CDF_CELLS);
    let mut sum = 0.0;
    for m in &mass {
        sum += m / total;
        cumulative.push(sum);
    }
    // θ where the cumulative mass reaches q (linear within a cell).
    let theta_at = |q: f64| {
        let i = cumulative.partition_point(|&c| c < q).min(CDF_CELLS - 1);
        let below = if i == 0 { 0.0 } else { cumulative[i - 1] };
        let inside = mass[i] / total;
        let t = if inside > 0.0 {
            ((q - below) / inside).clamp(0.0, 1.0)
        } else {
            0.5
        };
        (i as f64 + t) * cell
    };
    (0..THETA_NODES)
        .map(|j| {
            let n = THETA_NODES as f64;
            let (lo, hi) = (theta_at(j as f64 / n), theta_at((j as f64 + 1.0) / n));
            (theta_at((j as f64 + 0.5) / n), (hi - lo).max(cell))
        })
        .collect()
}

/// The mip a node at θ of stratum width `width` reads: the one whose
/// texel's solid angle matches the node's, `sin θ · width · 2π/`
/// [`PHI_NODES`], plus one (the GGX stack's bias, GPU Gems 3 §20.4).
fn node_lod(theta: f64, width: f64, omega_texel: f64) -> f64 {
    let omega = theta.sin().max(1e-6) * width * TAU / PHI_NODES as f64;
    0.5 * (omega / omega_texel).log2() + 1.0
}

impl ZonalStack {
    /// The stack of `kernel` over the `width × height` texels.
    pub fn new(kernel: &ZonalKernel, width: u32, height: u32, texels: &[[f32; 3]]) -> ZonalStack {
        let pyramid = Pyramid::new(width, height, texels);
        let omega_texel = 4.0 * PI / (width as f64 * height as f64);
        let (w, h) = (ZONAL_WIDTH, ZONAL_WIDTH / 2);
        let golden = (5f64.sqrt() - 1.0) / 2.0;
        let mut out = Vec::with_capacity((w * h * LEVELS) as usize);
        for k in 0..LEVELS {
            let nodes = theta_nodes(kernel, level_alpha(k));
            let level: Vec<[f32; 3]> = (0..w * h)
                .into_par_iter()
                .map(|i| {
                    let d = latlong::texel_direction(i % w, i / w, w, h);
                    let t = any_tangent(d);
                    let b = d.cross(t);
                    let mut sum = [0.0; 3];
                    for (j, &(theta, width)) in nodes.iter().enumerate() {
                        let (sin_t, cos_t) = theta.sin_cos();
                        let lod = node_lod(theta, width, omega_texel);
                        for p in 0..PHI_NODES {
                            let phi = TAU * ((p as f64 + golden * j as f64) / PHI_NODES as f64);
                            let l = d * cos_t + (t * phi.cos() + b * phi.sin()) * sin_t;
                            let v = pyramid.trilinear(lod, l);
                            for c in 0..3 {
                                sum[c] += v[c];
                            }
                        }
                    }
                    let n = (THETA_NODES * PHI_NODES) as f64;
                    sum.map(|s| (s / n) as f32)
                })
                .collect();
            out.extend(level);
        }
        ZonalStack {
            name: kernel.name,
            width: w,
            height: h,
            texels: out,
        }
    }

    /// Bilinear lookup of unit `d` (the file's frame) in level `k`.
    pub fn level_lookup(&self, k: u32, d: DVec3) -> Rgb {
        let base = k * self.height;
        Rgb::from(bilinear_latlong(
            self.width,
            self.height,
            |c, r| self.texels[((base + r) * self.width + c) as usize].map(f64::from),
            d,
        ))
    }

    /// `L̃(d, α)` (unscaled, the file's frame): linear between the levels
    /// around `√α`, as [`super::prefiltered::Prefiltered::lookup`]. Twin:
    /// `prefiltered_zonal_lookup` in shaders/environment.wgsl.
    pub fn lookup(&self, d: DVec3, alpha: f64) -> Rgb {
        let (k, t) = level_blend(alpha);
        self.level_lookup(k, d) * (1.0 - t) + self.level_lookup(k + 1, d) * t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A kernel of `cos^n θ`, whose mean of a linear map is known.
    fn cosine_power(alpha: f64, cos: f64) -> f64 {
        if cos <= 0.0 {
            return f64::NEG_INFINITY;
        }
        // α = (k/5)²: exponents 1 (k = 0) up to 26.
        (1.0 + 25.0 * alpha) * cos.ln()
    }

    /// A constant map stays constant at every level, and a map linear in
    /// `y` (`L = 1 + y`) averages to `1 + y_d · c̄`, `c̄` the kernel's mean
    /// cosine `(n + 1)/(n + 2)` for `cos^n`, within the two errors the
    /// stack makes on it: the bilinear reading of its levels
    /// (`Δ² max|f''|/8` with `Δ = π/32` in the polar angle and
    /// `|∂²y/∂θ²| ≤ 1`: 1.2·10⁻³) and the box mips the nodes read (a mip
    /// texel of polar height `s` averages `cos θ` to `cos θ₀ · sin(s/2)/(s/2)`,
    /// off by at most `s²/24`; `s = 2^⌈lod⌉ π/H` at the level's coarsest
    /// node).
    #[test]
    fn constant_and_linear_maps_average_as_the_kernel_says() {
        let kernel = ZonalKernel {
            name: "cosine power",
            ln_weight: cosine_power,
        };
        let (w, h) = (128u32, 64u32);
        let constant = vec![[0.5f32, 1.0, 2.0]; (w * h) as usize];
        let s = ZonalStack::new(&kernel, w, h, &constant);
        for t in &s.texels {
            assert!((t[1] as f64 - 1.0).abs() < 1e-6, "{t:?}");
        }
        let linear: Vec<[f32; 3]> = (0..w * h)
            .map(|i| {
                let y = latlong::texel_direction(i % w, i / w, w, h).y;
                [(1.0 + y) as f32; 3]
            })
            .collect();
        let s = ZonalStack::new(&kernel, w, h, &linear);
        let omega_texel = 4.0 * PI / (w as f64 * h as f64);
        let bilinear = (PI / 32.0).powi(2) / 8.0;
        for k in 0..LEVELS {
            let n = 1.0 + 25.0 * level_alpha(k);
            let mean_cos = (n + 1.0) / (n + 2.0);
            let coarsest = theta_nodes(&kernel, level_alpha(k))
                .iter()
                .map(|&(theta, width)| node_lod(theta, width, omega_texel))
                .fold(0.0, f64::max);
            let box_height = 2f64.powf(coarsest.ceil()) * PI / h as f64;
            let bound = bilinear + box_height * box_height / 24.0;
            let mut worst = 0.0f64;
            for d in [DVec3::Y, DVec3::X, DVec3::new(0.3, -0.8, 0.52).normalize()] {
                let got = s.level_lookup(k, d).y;
                worst = worst.max((got - (1.0 + d.y * mean_cos)).abs());
            }
            eprintln!("level {k}: largest error {worst:.2e}, bound {bound:.2e}");
            assert!(worst <= bound, "level {k}: {worst:e} > {bound:e}");
        }
    }
}
