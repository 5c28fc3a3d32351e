//! The radiance of the split-sum approximation (Karis 2013, "Real
//! Shading in Unreal Engine 4", SIGGRAPH course notes):
//! `∫ f_r L cos θ_i dω ≈ L̃(R, α) · (F0 · A(μ, α) + B(μ, α))`,
//! `L̃` the radiance prefiltered by the GGX lobe around the mirror
//! direction `R` (computed with `N = V = R`, Karis's assumption); the
//! environment BRDF `A`, `B` is the table of `material::brdf::dfg`, and
//! the per-pixel estimate of `environment.specular = "prefiltered"` that
//! multiplies the two is `reference::environment::prefiltered`.
//!
//! The prefiltered radiance is a stack of [`LEVELS`] lat-long images of
//! `environment.prefilter_size × size/2` texels, level `k` filtered at
//! perceptual roughness `√α = k/(LEVELS − 1)` (level 0: the map itself);
//! a lookup is bilinear within a level and linear between the two levels
//! around `√α` (α clamped to [0, 1]). Each texel is the GGX-weighted mean
//! `Σ L(l_k)(R·l_k) / Σ (R·l_k)` over [`PREFILTER_SAMPLES`] half vectors
//! of the Hammersley set, each read from the map's box-filtered mip whose
//! texel matches the sample's solid angle (filtered importance sampling,
//! Colbert & Křivánek 2007, GPU Gems 3 ch. 20), so the result is smooth
//! with few samples.
//!
//! WGSL twin: the stack's lookup in `environment_prefiltered`,
//! shaders/environment.wgsl (the GPU reads the f32 stack made here).

use super::latlong;
use crate::base::{Rgb, any_tangent};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};

/// Roughness levels of the stack.
pub const LEVELS: u32 = 6;

/// Half vectors per prefiltered texel.
pub const PREFILTER_SAMPLES: u32 = 128;

/// Default `environment.prefilter_size` (level width in texels).
pub const DEFAULT_SIZE: u32 = 64;

/// The prefiltered stack: level `k` is rows `k·height .. (k+1)·height`.
#[derive(Debug, PartialEq)]
pub struct Prefiltered {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
}

/// Box-filtered mips of a lat-long map (each half the size, the 2 × 2
/// texels weighted by their solid angle), down to 4 × 2.
struct Pyramid {
    levels: Vec<(u32, u32, Vec<[f64; 3]>)>,
}

impl Pyramid {
    fn new(width: u32, height: u32, texels: &[[f32; 3]]) -> Pyramid {
        let first: Vec<[f64; 3]> = texels.iter().map(|t| t.map(f64::from)).collect();
        let mut levels = vec![(width, height, first)];
        loop {
            let (w, h, src) = levels.last().unwrap();
            let (w, h) = (*w, *h);
            if w < 8 || h < 4 || w % 2 != 0 || h % 2 != 0 {
                break;
            }
            let weight = |row: u32| {
                let (top, bottom) = latlong::row_cos_bounds(row, h);
                top - bottom
            };
            let (w2, h2) = (w / 2, h / 2);
            let mut out = vec![[0.0; 3]; (w2 * h2) as usize];
            for r in 0..h2 {
                let (wa, wb) = (weight(2 * r), weight(2 * r + 1));
                for c in 0..w2 {
                    let t = |cc: u32, rr: u32| src[(rr * w + cc) as usize];
                    let mut v = [0.0; 3];
                    for (ch, v) in v.iter_mut().enumerate() {
                        *v = (wa * (t(2 * c, 2 * r)[ch] + t(2 * c + 1, 2 * r)[ch])
                            + wb * (t(2 * c, 2 * r + 1)[ch] + t(2 * c + 1, 2 * r + 1)[ch]))
                            / (2.0 * (wa + wb));
                    }
                    out[(r * w2 + c) as usize] = v;
                }
            }
            levels.push((w2, h2, out));
        }
        Pyramid { levels }
    }

    /// Bilinear lookup of `d` in mip `k` (as `MapData::lookup`).
    fn bilinear(&self, k: usize, d: DVec3) -> [f64; 3] {
        let (w, h, t) = &self.levels[k];
        bilinear(*w, *h, |c, r| t[(r * w + c) as usize], d)
    }

    /// Trilinear lookup at fractional mip `lod`.
    fn trilinear(&self, lod: f64, d: DVec3) -> [f64; 3] {
        let last = (self.levels.len() - 1) as f64;
        let lod = lod.clamp(0.0, last);
        let k = lod.floor().min((last - 1.0).max(0.0));
        let f = lod - k;
        let a = self.bilinear(k as usize, d);
        if f == 0.0 || self.levels.len() == 1 {
            return a;
        }
        let b = self.bilinear(k as usize + 1, d);
        std::array::from_fn(|c| a[c] * (1.0 - f) + b[c] * f)
    }
}

/// Bilinear lookup of unit `d` in a `w × h` lat-long image `t(col, row)`:
/// texel centres at `((col + ½)/W, (row + ½)/H)`, `u` wraps, `v` clamps.
fn bilinear(w: u32, h: u32, t: impl Fn(u32, u32) -> [f64; 3], d: DVec3) -> [f64; 3] {
    let (u, v) = latlong::uv(d);
    let x = u * w as f64 - 0.5;
    let y = v * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let col = |c: i64| c.rem_euclid(w as i64) as u32;
    let row = |r: i64| r.clamp(0, h as i64 - 1) as u32;
    let (c0, c1) = (col(x0 as i64), col(x0 as i64 + 1));
    let (r0, r1) = (row(y0 as i64), row(y0 as i64 + 1));
    let (a, b, c, e) = (t(c0, r0), t(c1, r0), t(c0, r1), t(c1, r1));
    std::array::from_fn(|k| {
        let top = a[k] * (1.0 - fx) + b[k] * fx;
        let bottom = c[k] * (1.0 - fx) + e[k] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

/// α of level `k`: `(k/(LEVELS − 1))²`.
pub fn level_alpha(k: u32) -> f64 {
    let r = k as f64 / (LEVELS - 1) as f64;
    r * r
}

impl Prefiltered {
    /// Prefilters the `width × height` texels into levels `size` wide.
    pub fn new(width: u32, height: u32, texels: &[[f32; 3]], size: u32) -> Prefiltered {
        let pyramid = Pyramid::new(width, height, texels);
        let (w, h) = (size, size / 2);
        // A source texel's mean solid angle at mip 0.
        let omega_texel = 4.0 * PI / (width as f64 * height as f64);
        let rows: Vec<Vec<[f32; 3]>> = (0..LEVELS * h)
            .into_par_iter()
            .map(|row| {
                let (k, r) = (row / h, row % h);
                let alpha = level_alpha(k);
                (0..w)
                    .map(|c| {
                        let d = latlong::texel_direction(c, r, w, h);
                        let v = prefilter(&pyramid, d, alpha, omega_texel);
                        v.map(|x| x as f32)
                    })
                    .collect()
            })
            .collect();
        Prefiltered {
            width: w,
            height: h,
            texels: rows.concat(),
        }
    }

    /// Bilinear lookup of unit `d` (the file's frame) in level `k`.
    pub fn level_lookup(&self, k: u32, d: DVec3) -> Rgb {
        let base = k * self.height;
        let v = bilinear(
            self.width,
            self.height,
            |c, r| self.texels[((base + r) * self.width + c) as usize].map(f64::from),
            d,
        );
        Rgb::from(v)
    }

    /// `L̃(d, α)` (unscaled, the file's frame): linear between the levels
    /// around `√α`. Twin: `prefiltered_lookup` in shaders/environment.wgsl.
    pub fn lookup(&self, d: DVec3, alpha: f64) -> Rgb {
        let f = alpha.clamp(0.0, 1.0).sqrt() * (LEVELS - 1) as f64;
        let k = f.floor().min((LEVELS - 2) as f64);
        let t = f - k;
        let k = k as u32;
        self.level_lookup(k, d) * (1.0 - t) + self.level_lookup(k + 1, d) * t
    }
}

/// One prefiltered texel: the GGX lobe of `alpha` about `r` (`N = V = R`).
fn prefilter(pyramid: &Pyramid, r: DVec3, alpha: f64, omega_texel: f64) -> [f64; 3] {
    if alpha == 0.0 {
        return pyramid.bilinear(0, r);
    }
    let t = any_tangent(r);
    let b = r.cross(t);
    let n = PREFILTER_SAMPLES;
    let alpha2 = alpha * alpha;
    let (mut sum, mut weight) = ([0.0; 3], 0.0);
    for k in 0..n {
        let u1 = (k as f64 + 0.5) / n as f64;
        let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
        let cos_h = ((1.0 - u1) / (1.0 + (alpha2 - 1.0) * u1)).sqrt();
        let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
        let phi = TAU * u2;
        let h = t * (sin_h * phi.cos()) + b * (sin_h * phi.sin()) + r * cos_h;
        let l = h * (2.0 * r.dot(h)) - r;
        let cos_l = r.dot(l);
        if cos_l <= 0.0 {
            continue;
        }
        // pdf(l) = D(h)·cos θ_h/(4 V·H) = D/4 with V = N; the sample's
        // solid angle 1/(n·pdf) chooses the mip (+1: GPU Gems 3, 20.4).
        let d = {
            let x = 1.0 + (alpha2 - 1.0) * cos_h * cos_h;
            alpha2 / (PI * x * x)
        };
        let omega_sample = 4.0 / (n as f64 * d);
        let lod = 0.5 * (omega_sample / omega_texel).log2() + 1.0;
        let v = pyramid.trilinear(lod, l);
        for c in 0..3 {
            sum[c] += v[c] * cos_l;
        }
        weight += cos_l;
    }
    sum.map(|s| s / weight)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant map stays constant at every level (the weights are
    /// normalized), and level 0 of a ramp is the ramp.
    #[test]
    fn a_constant_map_prefilters_to_itself() {
        let texels = vec![[0.5f32, 1.0, 2.0]; 64 * 32];
        let p = Prefiltered::new(64, 32, &texels, 32);
        for t in &p.texels {
            for (c, want) in [0.5, 1.0, 2.0].into_iter().enumerate() {
                assert!((t[c] as f64 - want).abs() < 1e-5 * want, "{t:?}");
            }
        }
    }
}
