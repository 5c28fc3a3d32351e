//! Per-channel error statistics of a three-channel form against the
//! spectral truth over a grid of conditions (thickness, angle, …).

use crate::base::Rgb;
use std::fmt;

/// `|approx − truth|` per channel over a grid: mean, maximum and where the
/// maximum is (the condition, as the caller describes it).
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelError<C> {
    pub count: usize,
    pub mean: Rgb,
    pub max: Rgb,
    /// The condition of each channel's maximum, and both values there
    /// (approx, truth).
    pub at_max: [(C, f64, f64); 3],
}

impl<C: Copy> ChannelError<C> {
    /// The statistics of `(condition, approx, truth)` samples; `None` for
    /// none.
    pub fn of(samples: impl IntoIterator<Item = (C, Rgb, Rgb)>) -> Option<Self> {
        let mut sum = Rgb::ZERO;
        let mut max = Rgb::splat(-1.0);
        let mut at_max: [Option<(C, f64, f64)>; 3] = [None; 3];
        let mut count = 0;
        for (c, approx, truth) in samples {
            let e = (approx - truth).abs();
            sum += e;
            count += 1;
            for ch in 0..3 {
                if e[ch] > max[ch] {
                    max[ch] = e[ch];
                    at_max[ch] = Some((c, approx[ch], truth[ch]));
                }
            }
        }
        let at_max = [at_max[0]?, at_max[1]?, at_max[2]?];
        Some(ChannelError {
            count,
            mean: sum / count as f64,
            max,
            at_max,
        })
    }
}

/// One Markdown table row: `| label | mean R G B | max R G B | where |`
/// (the maxima's conditions by `show`).
pub fn markdown_row<C: Copy>(
    label: &str,
    e: &ChannelError<C>,
    show: impl Fn(C) -> String,
) -> String {
    let [r, g, b] = &e.at_max;
    format!(
        "| {label} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | R {}; G {}; B {} |",
        e.mean.x,
        e.mean.y,
        e.mean.z,
        e.max.x,
        e.max.y,
        e.max.z,
        show(r.0),
        show(g.0),
        show(b.0),
    )
}

/// The header that goes with [`markdown_row`].
pub struct MarkdownHeader<'a>(pub &'a str);

impl fmt::Display for MarkdownHeader<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        writeln!(
            f,
            "| {} | mean R | mean G | mean B | max R | max G | max B | where the max is |",
            self.0
        )?;
        write!(f, "|---|---|---|---|---|---|---|---|")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean and max of known samples, and the condition of each max.
    #[test]
    fn statistics_of_known_samples() {
        let e = ChannelError::of([
            (1, Rgb::new(0.1, 0.0, 0.5), Rgb::ZERO),
            (2, Rgb::new(0.0, 0.2, 0.0), Rgb::new(0.3, 0.0, 0.0)),
        ])
        .unwrap();
        assert_eq!(e.count, 2);
        assert!((e.mean - Rgb::new(0.2, 0.1, 0.25)).abs().max_element() < 1e-15);
        assert_eq!(e.max, Rgb::new(0.3, 0.2, 0.5));
        assert_eq!(e.at_max.map(|m| m.0), [2, 2, 1]);
        assert!(ChannelError::<i32>::of([]).is_none());
    }
}
