//! 8-bit sRGB of a linear value in [0, 1], exactly as
//! `(srgb_encode(v) · 255 + 0.5) as u8` (IEC 61966-2-1, rounded to the
//! nearest code), without a `powf` per channel.
//!
//! Why: converting a frame to PNG called `powf` three times a pixel, about
//! 7 % of a cold `gonio render`'s CPU samples at 640×480 (`perf`,
//! 2026-12-03) and 6 million calls for a 1080p image. The code is a step
//! function of `v`: it is `k` from the smallest `v` whose code is `k` up
//! to the next such threshold. The 255 thresholds are found once, by
//! bisection over the `f64` values with the formula itself, so looking a
//! value up (its cell's first code, then at most two comparisons) gives
//! the formula's code bit for bit
//! wherever the formula does not decrease as `v` grows; the tests check
//! that it does not around every threshold, where a `powf` rounding could
//! make it, and compare both on random values.

use std::sync::OnceLock;

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// The formula this module reproduces: `v`'s 8-bit sRGB code (`NaN` and
/// anything ≤ 0 give 0, anything ≥ 1 gives 255: the cast saturates).
pub fn srgb8_by_formula(v: f64) -> u8 {
    (srgb_encode(v) * 255.0 + 0.5) as u8
}

/// `v`'s 8-bit sRGB code, equal to [`srgb8_by_formula`]: the number of
/// thresholds at or below `v` (none for `NaN`), counted from the code at
/// the start of `v`'s cell of width 1/4096 (at most one more
/// threshold lies in a cell: the narrowest code step, about 1/3240 near
/// `v` = 0.0031, is wider than a cell).
pub fn srgb8(v: f64) -> u8 {
    if v.is_nan() || v <= 0.0 {
        return 0;
    }
    if v >= 1.0 {
        return 255;
    }
    let table = table();
    // `v · CELLS` is exact (a power of two), so the cell starts at or
    // below `v`.
    let mut code = table.cell_start[(v * CELLS as f64) as usize];
    while code < 255 && table.thresholds[code as usize] <= v {
        code += 1;
    }
    code
}

/// Cells of [0, 1) with their first code.
const CELLS: usize = 4096;

struct Table {
    /// `thresholds[k − 1]`: the smallest `v` whose code is at least `k`,
    /// for `k` in 1..=255.
    thresholds: [f64; 255],
    /// The code at `i / CELLS`.
    cell_start: [u8; CELLS],
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Box<Table>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let thresholds: [f64; 255] = std::array::from_fn(|i| first_reaching(i as u8 + 1));
        let cell_start = std::array::from_fn(|i| {
            let start = i as f64 / CELLS as f64;
            thresholds.partition_point(|&t| t <= start) as u8
        });
        Box::new(Table {
            thresholds,
            cell_start,
        })
    })
}

/// The smallest `v` in (0, 1] with `srgb8_by_formula(v) ≥ code`, by
/// bisection over the ordered bit patterns of the non-negative `f64`s.
fn first_reaching(code: u8) -> f64 {
    let (mut lo, mut hi) = (0.0f64.to_bits(), 1.0f64.to_bits());
    // Invariant: the code at `lo` is below `code`, at `hi` it reaches it.
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if srgb8_by_formula(f64::from_bits(mid)) >= code {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    f64::from_bits(hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thresholds() -> &'static [f64; 255] {
        &table().thresholds
    }

    #[test]
    fn a_cell_holds_at_most_one_threshold() {
        let most = (0..CELLS)
            .map(|i| {
                let (a, b) = (i as f64 / CELLS as f64, (i + 1) as f64 / CELLS as f64);
                thresholds().iter().filter(|&&t| a < t && t <= b).count()
            })
            .max();
        assert_eq!(most, Some(1), "the lookup steps up at most once");
    }

    fn ulps_around(v: f64, n: u64) -> impl Iterator<Item = f64> {
        let bits = v.to_bits();
        (bits.saturating_sub(n)..=bits + n).map(f64::from_bits)
    }

    #[test]
    fn every_threshold_is_where_the_formula_steps_up_by_one() {
        let t = thresholds();
        for (i, &v) in t.iter().enumerate() {
            let code = i as u8 + 1;
            assert_eq!(srgb8_by_formula(v), code, "at threshold {code}");
            let below = f64::from_bits(v.to_bits() - 1);
            assert_eq!(srgb8_by_formula(below), code - 1, "below threshold {code}");
        }
        assert!(t.windows(2).all(|w| w[0] < w[1]), "increasing");
    }

    #[test]
    fn the_table_gives_the_formula_around_every_threshold_and_at_the_ends() {
        // The formula can only fail to grow where a rounding of `powf`
        // crosses the half-code boundary, that is within a few ulps of a
        // threshold: 4096 on each side of each are checked.
        for &t in thresholds() {
            for v in ulps_around(t, 4096) {
                assert_eq!(srgb8(v), srgb8_by_formula(v), "v = {v:e}");
            }
        }
        for v in [
            f64::NAN,
            f64::NEG_INFINITY,
            -1.0,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            1e-300,
            0.0031308,
            0.5,
            1.0,
            1.0 + f64::EPSILON,
            2.0,
            f64::INFINITY,
        ] {
            assert_eq!(srgb8(v), srgb8_by_formula(v), "v = {v:e}");
        }
    }

    #[test]
    fn the_table_gives_the_formula_on_a_million_values() {
        // Every f32 radiance a frame can hold, scaled as the writers do:
        // a deterministic spread over [0, 1.1] and over f32 bit patterns.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let uniform = (state >> 11) as f64 / (1u64 << 53) as f64 * 1.1;
            let bits = f32::from_bits((state >> 32) as u32 & 0x3fff_ffff) as f64;
            for v in [uniform, bits] {
                assert_eq!(srgb8(v), srgb8_by_formula(v), "v = {v:e}");
            }
        }
    }
}
