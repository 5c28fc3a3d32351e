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
use std::sync::atomic::{AtomicU64, Ordering};

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
pub(super) struct Pyramid {
    levels: Vec<(u32, u32, Vec<[f64; 3]>)>,
}

impl Pyramid {
    pub(super) fn new(width: u32, height: u32, texels: &[[f32; 3]]) -> Pyramid {
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
        bilinear_latlong(*w, *h, |c, r| t[(r * w + c) as usize], d)
    }

    /// Trilinear lookup at fractional mip `lod`.
    pub(super) fn trilinear(&self, lod: f64, d: DVec3) -> [f64; 3] {
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
pub(super) fn bilinear_latlong(
    w: u32,
    h: u32,
    t: impl Fn(u32, u32) -> [f64; 3],
    d: DVec3,
) -> [f64; 3] {
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

/// The narrowest level width a level is computed at before it is
/// resampled to the stack's width ([`level_width`]): the default size, so
/// stacks of up to [`DEFAULT_SIZE`] are computed texel by texel.
pub const MIN_LEVEL_WIDTH: u32 = DEFAULT_SIZE;

/// Texels a level's lobe spans at least across its half width at half
/// maximum, where a level is computed at fewer texels than the stack's.
pub const TEXELS_PER_LOBE: f64 = 4.0;

/// The width level `k` of a stack `size` wide is computed at: `size`, or
/// fewer where the level's GGX lobe is wide enough that the level is
/// smooth over several texels. The reflected lobe's half width at half
/// maximum is `2 atan(α √(√2 − 1))` (GGX's `D(θ_h) = D(0)/2` at
/// `tan² θ_h = α² (√2 − 1)`, the reflection doubling the angle); the
/// level is computed with a texel of at most 1/[`TEXELS_PER_LOBE`] of it,
/// `W_k ≥ 2π·TEXELS_PER_LOBE / θ_lobe` (even, at least
/// [`MIN_LEVEL_WIDTH`]), and read bilinearly at the stack's texels. For
/// a stack 2048 wide the levels are 2048 (the map), 490, 124, 64, 64, 64
/// wide: a 60th of the work.
pub fn level_width(k: u32, size: u32) -> u32 {
    let alpha = level_alpha(k);
    if alpha == 0.0 {
        return size;
    }
    let lobe = 2.0 * (alpha * (2f64.sqrt() - 1.0).sqrt()).atan();
    let needed = (TAU * TEXELS_PER_LOBE / lobe).ceil() as u32;
    needed.next_multiple_of(2).max(MIN_LEVEL_WIDTH).min(size)
}

/// Texels computed for a stack `size` wide (the sum of its levels' at
/// [`level_width`]): the whole of a progress bar.
pub fn texels_to_compute(size: u32) -> u64 {
    (0..LEVELS)
        .map(|k| {
            let w = u64::from(level_width(k, size));
            w * (w / 2)
        })
        .sum()
}

impl Prefiltered {
    /// Prefilters the `width × height` texels into levels `size` wide.
    pub fn new(width: u32, height: u32, texels: &[[f32; 3]], size: u32) -> Prefiltered {
        Self::with_progress(width, height, texels, size, &AtomicU64::new(0))
    }

    /// As [`Self::new`], adding each texel computed to `done` (of
    /// [`texels_to_compute`]`(size)`), for a progress bar.
    pub fn with_progress(
        width: u32,
        height: u32,
        texels: &[[f32; 3]],
        size: u32,
        done: &AtomicU64,
    ) -> Prefiltered {
        Self::computed(width, height, texels, size, |k| level_width(k, size), done)
    }

    /// As [`Self::new`], level `k` computed at `widths(k)` texels wide
    /// (at most `size`) and resampled to `size`.
    pub fn with_level_widths(
        width: u32,
        height: u32,
        texels: &[[f32; 3]],
        size: u32,
        widths: impl Fn(u32) -> u32,
    ) -> Prefiltered {
        Self::computed(width, height, texels, size, widths, &AtomicU64::new(0))
    }

    fn computed(
        width: u32,
        height: u32,
        texels: &[[f32; 3]],
        size: u32,
        widths: impl Fn(u32) -> u32,
        done: &AtomicU64,
    ) -> Prefiltered {
        let pyramid = Pyramid::new(width, height, texels);
        let (w, h) = (size, size / 2);
        // A source texel's mean solid angle at mip 0.
        let omega_texel = 4.0 * PI / (width as f64 * height as f64);
        let mut texels = Vec::with_capacity((w * h * LEVELS) as usize);
        for k in 0..LEVELS {
            let alpha = level_alpha(k);
            let samples = LobeSample::all(alpha, omega_texel);
            let wk = widths(k).min(size);
            let hk = wk / 2;
            let level: Vec<[f64; 3]> = (0..hk)
                .into_par_iter()
                .flat_map_iter(|r| {
                    let (pyramid, samples) = (&pyramid, &samples);
                    let row: Vec<[f64; 3]> = (0..wk)
                        .map(move |c| {
                            let d = latlong::texel_direction(c, r, wk, hk);
                            prefilter(pyramid, d, alpha, samples)
                        })
                        .collect();
                    done.fetch_add(u64::from(wk), Ordering::Relaxed);
                    row
                })
                .collect();
            if wk == w {
                texels.extend(level.iter().map(|v| v.map(|x| x as f32)));
            } else {
                let at = |c: u32, r: u32| level[(r * wk + c) as usize];
                for r in 0..h {
                    for c in 0..w {
                        let d = latlong::texel_direction(c, r, w, h);
                        texels.push(bilinear_latlong(wk, hk, at, d).map(|x| x as f32));
                    }
                }
            }
        }
        Prefiltered {
            width: w,
            height: h,
            texels,
        }
    }

    /// Bilinear lookup of unit `d` (the file's frame) in level `k`.
    pub fn level_lookup(&self, k: u32, d: DVec3) -> Rgb {
        let base = k * self.height;
        let v = bilinear_latlong(
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
        let (k, t) = level_blend(alpha);
        self.level_lookup(k, d) * (1.0 - t) + self.level_lookup(k + 1, d) * t
    }
}

/// The two levels around `√α` (α clamped to [0, 1]), `k` and `k + 1`,
/// and the weight `t` of the upper one. Twin: `stack_levels` in
/// shaders/environment.wgsl.
pub fn level_blend(alpha: f64) -> (u32, f64) {
    let f = alpha.clamp(0.0, 1.0).sqrt() * (LEVELS - 1) as f64;
    let k = f.floor().min((LEVELS - 2) as f64);
    (k as u32, f - k)
}

/// One half vector of the GGX lobe of a level, in the lobe's own frame
/// (`t`, `b`, `R`), with the mip it reads: the same for every texel of
/// the level (they depend on the sample's index, `α` and the map's texel
/// solid angle alone), so computed once per level rather than once per
/// texel (the sines, cosines and logarithm were most of a stack's cost).
struct LobeSample {
    /// `sin θ_h cos φ`, `sin θ_h sin φ`, `cos θ_h`.
    along_t: f64,
    along_b: f64,
    cos_h: f64,
    /// The box-filtered mip whose texel matches the sample's solid angle.
    lod: f64,
}

impl LobeSample {
    /// The [`PREFILTER_SAMPLES`] half vectors of the Hammersley set for
    /// `alpha`, their mips chosen against `omega_texel` (a source texel's
    /// mean solid angle at mip 0).
    fn all(alpha: f64, omega_texel: f64) -> Vec<LobeSample> {
        let n = PREFILTER_SAMPLES;
        let alpha2 = alpha * alpha;
        (0..n)
            .map(|k| {
                let u1 = (k as f64 + 0.5) / n as f64;
                let u2 = k.reverse_bits() as f64 / 4_294_967_296.0;
                let cos_h = ((1.0 - u1) / (1.0 + (alpha2 - 1.0) * u1)).sqrt();
                let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
                let phi = TAU * u2;
                // pdf(l) = D(h)·cos θ_h/(4 V·H) = D/4 with V = N; the
                // sample's solid angle 1/(n·pdf) chooses the mip (+1: GPU
                // Gems 3, 20.4).
                let d = {
                    let x = 1.0 + (alpha2 - 1.0) * cos_h * cos_h;
                    alpha2 / (PI * x * x)
                };
                let omega_sample = 4.0 / (n as f64 * d);
                LobeSample {
                    along_t: sin_h * phi.cos(),
                    along_b: sin_h * phi.sin(),
                    cos_h,
                    lod: 0.5 * (omega_sample / omega_texel).log2() + 1.0,
                }
            })
            .collect()
    }
}

/// One prefiltered texel: the GGX lobe of `alpha` about `r` (`N = V = R`), over its
/// `samples` ([`LobeSample::all`]).
fn prefilter(pyramid: &Pyramid, r: DVec3, alpha: f64, samples: &[LobeSample]) -> [f64; 3] {
    if alpha == 0.0 {
        return pyramid.bilinear(0, r);
    }
    let t = any_tangent(r);
    let b = r.cross(t);
    let (mut sum, mut weight) = ([0.0; 3], 0.0);
    for s in samples {
        let h = t * s.along_t + b * s.along_b + r * s.cos_h;
        let l = h * (2.0 * r.dot(h)) - r;
        let cos_l = r.dot(l);
        if cos_l <= 0.0 {
            continue;
        }
        let v = pyramid.trilinear(s.lod, l);
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

    /// The widths the docs give, and no reduction up to the default size.
    #[test]
    fn level_widths() {
        let widths: Vec<u32> = (0..LEVELS).map(|k| level_width(k, 2048)).collect();
        assert_eq!(widths, [2048, 490, 124, 64, 64, 64]);
        for size in [8, 32, 64] {
            assert!((0..LEVELS).all(|k| level_width(k, size) == size));
        }
    }

    /// The stack's levels against the convolution they estimate,
    /// `Σ_t L_t D(h) (R·l_t) Ω_t / Σ_t D(h) (R·l_t) Ω_t` over every texel
    /// of the map, at 400 directions (a Fibonacci sphere), for a stack
    /// 256 wide computed at [`level_width`] and resampled and for one
    /// computed texel by texel: mean and largest |error| relative to the
    /// level's peak, under the sky (a 2.5° sun) and the blobs. Both carry
    /// the 128-sample estimate's own error (its pattern differs from
    /// texel to texel), and the resampled levels' error is asserted no
    /// larger than the computed ones' plus the bilinear reading's own,
    /// `Δ² max|f''|/8`: for a lobe-shaped peak `e^{−x²/2σ²}` spanning 4
    /// texels at half maximum (`σ = 4Δ/1.18`) that is `Δ²/(8σ²)` = 1.1 %
    /// of the peak.
    #[test]
    fn resampled_levels_are_as_close_to_the_convolution() {
        for map in [
            crate::environment::sky::map(),
            crate::environment::test_maps::blobs(),
        ] {
            let size = 256;
            let fast = Prefiltered::new(map.width, map.height, &map.texels, size);
            let full =
                Prefiltered::with_level_widths(map.width, map.height, &map.texels, size, |_| size);
            let texel = |i: usize| Rgb::from(map.texels[i].map(f64::from));
            let n = 400;
            let dirs: Vec<DVec3> = (0..n)
                .map(|i| {
                    let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                    let phi = i as f64 * PI * (3.0 - 5f64.sqrt());
                    let s = (1.0 - y * y).sqrt();
                    DVec3::new(s * phi.cos(), y, s * phi.sin())
                })
                .collect();
            for k in 1..LEVELS {
                let alpha2 = level_alpha(k).powi(2);
                let truth: Vec<Rgb> = dirs
                    .iter()
                    .map(|&r| {
                        let (mut sum, mut weight) = (Rgb::ZERO, 0.0);
                        for row in 0..map.height {
                            let (top, bottom) = latlong::row_cos_bounds(row, map.height);
                            let omega = TAU / map.width as f64 * (top - bottom);
                            for col in 0..map.width {
                                let l = latlong::texel_direction(col, row, map.width, map.height);
                                let cos_l = r.dot(l);
                                if cos_l <= 0.0 {
                                    continue;
                                }
                                let cos_h = (r + l).normalize().dot(r);
                                let x = 1.0 + (alpha2 - 1.0) * cos_h * cos_h;
                                let w = alpha2 / (PI * x * x) * cos_l * omega;
                                sum += texel((row * map.width + col) as usize) * w;
                                weight += w;
                            }
                        }
                        sum / weight
                    })
                    .collect();
                let peak = truth.iter().fold(0.0f64, |m, t| m.max(t.max_element()));
                let error = |p: &Prefiltered| {
                    let (mut sum, mut worst) = (0.0, 0.0f64);
                    for (d, t) in dirs.iter().zip(&truth) {
                        let e = (p.level_lookup(k, *d) - *t).abs().max_element() / peak;
                        sum += e;
                        worst = worst.max(e);
                    }
                    (sum / n as f64, worst)
                };
                let (f, c) = (error(&fast), error(&full));
                eprintln!(
                    "{}: level {k} ({} wide): resampled {:.4} / {:.4}, computed {:.4} / {:.4} (mean / largest of the peak)",
                    map.name,
                    level_width(k, size),
                    f.0,
                    f.1,
                    c.0,
                    c.1
                );
                assert!(
                    f.0 <= c.0 + 0.011 && f.1 <= c.1 + 0.011,
                    "{}: level {k}: resampled {f:?}, computed {c:?}",
                    map.name
                );
            }
        }
    }

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
