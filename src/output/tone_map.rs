//! Tone mapping: how linear radiance (after the exposure scale) becomes a
//! display value in [0, 1] before the sRGB encoding of a PNG or the
//! viewer's window (`image.tone_map`). EXR output stays linear whatever
//! this says (the contract: no tone mapping, no exposure).
//!
//! `clamp` is what gonio always did and stays the default, so the
//! lecture's exact images do not change. The others compress highlights
//! instead of clipping them:
//!
//! - `reinhard`: `x / (1 + x)` per channel, the global operator of
//!   Reinhard, Stark, Shirley, Ferwerda, "Photographic Tone Reproduction
//!   for Digital Images", SIGGRAPH 2002, eq. 3 (applied per channel, as
//!   three.js's `ReinhardToneMapping` does).
//! - `aces`: Krzysztof Narkowicz's fit of the ACES RRT + sRGB ODT curve,
//!   "ACES Filmic Tone Mapping Curve" (2016),
//!   `x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)` per channel, as
//!   published (pre-exposed: 1 maps to about 0.8; the original ACES
//!   scale is this with the input × 0.6).
//! - `pbr-neutral`: the Khronos PBR Neutral tone mapper, specification in
//!   KhronosGroup/ToneMapping `PBR_Neutral/README.md` (2024): with
//!   `F90 = 0.04`, `Ks = 0.8 − F90`, `Kd = 0.15`, `x = min(R, G, B)`,
//!   `f = x − x²/(4 F90)` for `x ≤ 2 F90` else `F90`,
//!   `p = max(c − f)`, `pn = 1 − (1 − Ks)² / (p + 1 − 2 Ks)`,
//!   `g = 1 / (Kd (p − pn) + 1)`; out `c − f` for `p ≤ Ks`, else
//!   `(c − f)·(pn/p)·g + pn·(1 − g)`. Colours up to about 0.76 pass
//!   through (less the small offset near black), so base colours render
//!   as themselves.
//!
//! The WGSL twin is `tone_map` in shaders/common.wgsl, chosen by
//! [`ToneMap::code`] through a uniform with `select`s (UNIFORM_BRANCHES).

use std::fmt;
use std::str::FromStr;

/// The operator from display-scaled linear radiance to [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ToneMap {
    /// `clamp(x, 0, 1)`: today's images, the default.
    #[default]
    Clamp,
    Reinhard,
    Aces,
    PbrNeutral,
}

/// The names `image.tone_map` takes, in [`ToneMap::code`] order.
pub const NAMES: [&str; 4] = ["clamp", "reinhard", "aces", "pbr-neutral"];

impl ToneMap {
    pub const ALL: [ToneMap; 4] = [
        ToneMap::Clamp,
        ToneMap::Reinhard,
        ToneMap::Aces,
        ToneMap::PbrNeutral,
    ];

    /// The value the shader's `globals.tone_map` holds.
    pub fn code(self) -> u32 {
        self as u32
    }

    pub fn name(self) -> &'static str {
        NAMES[self as usize]
    }

    /// Maps one pixel's display-scaled radiance (`L_o · 2^exposure`) to
    /// [0, 1]³. NaN and negative values map to 0, as the clamp does.
    pub fn apply(self, rgb: [f64; 3]) -> [f64; 3] {
        let c = rgb.map(|v| if v > 0.0 { v } else { 0.0 });
        let out = match self {
            ToneMap::Clamp => c,
            ToneMap::Reinhard => c.map(|x| x / (1.0 + x)),
            ToneMap::Aces => c.map(aces),
            ToneMap::PbrNeutral => pbr_neutral(c),
        };
        out.map(|v| v.clamp(0.0, 1.0))
    }
}

/// Narkowicz 2016, the fitted ACES curve (before its `saturate`).
fn aces(x: f64) -> f64 {
    x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)
}

/// Khronos PBR Neutral, as its specification writes it.
fn pbr_neutral(c: [f64; 3]) -> [f64; 3] {
    const F90: f64 = 0.04;
    const KS: f64 = 0.8 - F90;
    const KD: f64 = 0.15;
    let x = c[0].min(c[1]).min(c[2]);
    let f = if x <= 2.0 * F90 {
        x - x * x / (4.0 * F90)
    } else {
        F90
    };
    let c = c.map(|v| v - f);
    let p = c[0].max(c[1]).max(c[2]);
    if p <= KS {
        return c;
    }
    let pn = 1.0 - (1.0 - KS) * (1.0 - KS) / (p + 1.0 - 2.0 * KS);
    let g = 1.0 / (KD * (p - pn) + 1.0);
    c.map(|v| v * (pn / p) * g + pn * (1.0 - g))
}

impl FromStr for ToneMap {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        ToneMap::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown tone map `{s}`; choose one of {}",
                    NAMES.map(|n| format!("`{n}`")).join(", ")
                )
            })
    }
}

impl fmt::Display for ToneMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(t: ToneMap, x: f64) -> f64 {
        t.apply([x; 3])[0]
    }

    #[test]
    fn clamp_is_the_old_clamp() {
        for x in [-1.0, 0.0, 0.25, 1.0, 7.0, f64::NAN, f64::INFINITY] {
            let want = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
            assert_eq!(grey(ToneMap::Clamp, x), want, "{x}");
        }
    }

    #[test]
    fn reinhard_is_x_over_one_plus_x() {
        assert_eq!(grey(ToneMap::Reinhard, 1.0), 0.5);
        assert_eq!(grey(ToneMap::Reinhard, 3.0), 0.75);
        assert_eq!(grey(ToneMap::Reinhard, 0.0), 0.0);
    }

    #[test]
    fn aces_matches_the_published_fit() {
        // 1 → 2.54 / 3.16 (Narkowicz: "1 on input maps to ~0.8").
        assert!((grey(ToneMap::Aces, 1.0) - 2.54 / 3.16).abs() < 1e-15);
        assert_eq!(grey(ToneMap::Aces, 0.0), 0.0);
        // The curve reaches 1 where 0.08 x² − 0.56 x − 0.14 = 0, x ≈ 7.24,
        // and saturates beyond.
        let x1 = (0.56 + (0.56f64 * 0.56 + 4.0 * 0.08 * 0.14).sqrt()) / 0.16;
        assert!((grey(ToneMap::Aces, x1) - 1.0).abs() < 1e-12);
        assert!(grey(ToneMap::Aces, x1 * 0.99) < 1.0);
        assert_eq!(grey(ToneMap::Aces, 100.0), 1.0);
    }

    #[test]
    fn pbr_neutral_follows_its_specification() {
        // Below the compression start a colour only loses the offset:
        // x = 0.5 > 2·F90, so f = 0.04.
        let out = ToneMap::PbrNeutral.apply([0.5, 0.3, 0.2]);
        let want = [0.46, 0.26, 0.16];
        for (o, w) in out.iter().zip(want) {
            assert!((o - w).abs() < 1e-15, "{out:?}");
        }
        // Near black the offset is x − x²/0.16: a grey 0.04 maps to
        // 0.04 − (0.04 − 0.01) = 0.01.
        assert!((grey(ToneMap::PbrNeutral, 0.04) - 0.01).abs() < 1e-15);
        // A grey of 2 (p = 1.96): pn = 1 − 0.0576/(1.96 − 0.52), and a grey
        // stays grey at pn.
        let pn = 1.0 - 0.24 * 0.24 / (1.96 + 1.0 - 1.52);
        let out = ToneMap::PbrNeutral.apply([2.0; 3]);
        for o in out {
            assert!((o - pn).abs() < 1e-15, "{out:?} vs {pn}");
        }
        // A saturated highlight moves towards white (desaturates).
        let out = ToneMap::PbrNeutral.apply([4.0, 1.0, 0.5]);
        assert!(out[0] < 1.0 && out[2] / out[0] > 0.5 / 4.0, "{out:?}");
    }

    #[test]
    fn every_operator_is_monotonic_and_in_range() {
        for t in ToneMap::ALL {
            let mut last = -1.0;
            for k in 0..=4000 {
                let x = (k as f64 / 200.0).powi(2); // 0 … 400
                let y = grey(t, x);
                assert!((0.0..=1.0).contains(&y), "{t}: {x} → {y}");
                assert!(y >= last, "{t} not monotonic at {x}: {y} < {last}");
                last = y;
            }
            // One channel rising with the others fixed does not lower it.
            let mut last = -1.0;
            for k in 0..=400 {
                let r = k as f64 / 20.0;
                let y = t.apply([r, 0.3, 0.1])[0];
                assert!(y >= last - 1e-15, "{t}: r = {r} → {y} < {last}");
                last = y;
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for t in ToneMap::ALL {
            assert_eq!(t.name().parse::<ToneMap>(), Ok(t));
        }
        assert!(
            "filmic"
                .parse::<ToneMap>()
                .unwrap_err()
                .contains("pbr-neutral")
        );
    }
}
