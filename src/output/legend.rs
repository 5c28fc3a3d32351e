//! Where a plot's legend goes: the corner of the plotting area that its
//! curves cross least (the albedo plot's legend, once fixed upper
//! left, covered a curve). Points are given as fractions of the area
//! (x from the left, y from the bottom), the legend's box as fractions of
//! its width and height.

use plotters::prelude::SeriesLabelPosition;

/// The corners tried, in order of preference on a tie.
const CORNERS: [SeriesLabelPosition; 4] = [
    SeriesLabelPosition::UpperLeft,
    SeriesLabelPosition::UpperRight,
    SeriesLabelPosition::LowerRight,
    SeriesLabelPosition::LowerLeft,
];

/// The corner whose `box_w × box_h` box (area fractions, with the
/// legend's margin included) holds the fewest of `points`.
pub fn quietest_corner(points: &[(f64, f64)], box_w: f64, box_h: f64) -> SeriesLabelPosition {
    let inside = |corner: &SeriesLabelPosition, &(x, y): &(f64, f64)| {
        let left = matches!(
            corner,
            SeriesLabelPosition::UpperLeft | SeriesLabelPosition::LowerLeft
        );
        let upper = matches!(
            corner,
            SeriesLabelPosition::UpperLeft | SeriesLabelPosition::UpperRight
        );
        let in_x = if left { x <= box_w } else { x >= 1.0 - box_w };
        let in_y = if upper { y >= 1.0 - box_h } else { y <= box_h };
        in_x && in_y
    };
    CORNERS
        .iter()
        .min_by_key(|c| points.iter().filter(|p| inside(c, p)).count())
        .cloned()
        .unwrap_or(SeriesLabelPosition::UpperLeft)
}

/// The legend box of `labels` (the longest label's characters, one row
/// each) as fractions of an area of `w × h` pixels, for a `font_px` font:
/// about 0.6 em per character, a 40 px sample and margins, rows of 1.4 em.
pub fn box_fraction(labels: &[String], font_px: f64, w: f64, h: f64) -> (f64, f64) {
    let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
    let width = chars * 0.6 * font_px + 60.0;
    let height = labels.len() as f64 * 1.4 * font_px + 20.0;
    ((width / w).min(1.0), (height / h).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_legend_goes_where_no_curve_is() {
        // A curve rising from the lower left to the upper right, a second
        // along the top: the lower right is free.
        let mut points: Vec<(f64, f64)> = (0..=100)
            .map(|k| (k as f64 / 100.0, k as f64 / 100.0))
            .collect();
        points.extend((0..=100).map(|k| (k as f64 / 100.0, 0.95)));
        assert!(matches!(
            quietest_corner(&points, 0.3, 0.2),
            SeriesLabelPosition::LowerRight
        ));
        // Nothing drawn: the first preference.
        assert!(matches!(
            quietest_corner(&[], 0.3, 0.2),
            SeriesLabelPosition::UpperLeft
        ));
    }
}
