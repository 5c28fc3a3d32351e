//! Time against error, every configuration a dot coloured by its knob,
//! the Pareto front drawn as a line through its points and labelled.
//! Drawn with the plot machinery of `gonio brdf` (same fonts, same
//! atomic PNG/SVG files).

use super::Row;
use crate::output::plot::{COLORS, Plot, number};
use plotters::coord::Shift;
use plotters::prelude::*;

/// A tick label with two significant digits (16, 25, 40, 1.6).
fn two_digits(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return number(v);
    }
    let scale = 10f64.powf(v.log10().floor() - 1.0);
    number((v / scale).round() * scale)
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The plot of [`super::BenchReport::rows`].
pub struct ParetoPlot<'a> {
    pub rows: &'a [Row],
    /// Shown under the title: scene, adapter, floors.
    pub note: String,
    /// x is time divided by this (the unlit floor), so the axis reads as
    /// "× unlit pass".
    pub floor_ms: f64,
}

impl ParetoPlot<'_> {
    /// Errors of 0 (an exact match) cannot sit on a log axis: they are
    /// drawn at the axis' bottom.
    fn y_floor(&self) -> f64 {
        let min = self
            .rows
            .iter()
            .map(|r| r.error)
            .filter(|e| *e > 0.0)
            .fold(f64::INFINITY, f64::min);
        if min.is_finite() { min / 2.0 } else { 1e-6 }
    }

    /// x is log10 of the time ratio on a linear axis (plotters' log axis
    /// leaves the decades' insides unlabelled), y the error on a log axis.
    fn xy(&self, r: &Row) -> (f64, f64) {
        (
            (r.time.median / self.floor_ms).log10(),
            r.error.max(self.y_floor()),
        )
    }
}

impl Plot for ParetoPlot<'_> {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root
            .titled("Frame time vs error, Pareto front", ("sans-serif", 24))
            .map_err(err)?;
        let (_, h) = root.dim_in_pixel();
        let (area, footer) = root.split_vertically(h - 30);
        let (fw, _) = footer.dim_in_pixel();
        let style = TextStyle::from(("sans-serif", 14).into_font()).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Top,
            ),
        );
        footer
            .draw_text(&self.note, &style, (fw as i32 / 2, 4))
            .map_err(err)?;
        let pts: Vec<(f64, f64)> = self.rows.iter().map(|r| self.xy(r)).collect();
        let (x_lo, x_hi) = pts.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
        let (y_lo, y_hi) = pts.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
        let (x_lo, x_hi) = (x_lo - 0.1, x_hi + 0.1);
        let (y_lo, y_hi) = (y_lo / 2.0, y_hi * 2.0);
        let mut chart = ChartBuilder::on(&area)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d(x_lo..x_hi, (y_lo..y_hi).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_labels(14)
            .y_labels(12)
            .x_desc("GPU frame time / unlit pass (log)")
            .y_desc("relative RMS error vs truth (log)")
            .x_label_formatter(&|x| two_digits(10f64.powf(*x)))
            .y_label_formatter(&|y| number(*y))
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;

        // The front: a staircase through its points in time order.
        let mut front: Vec<(f64, f64)> = self
            .rows
            .iter()
            .filter(|r| r.on_front)
            .map(|r| self.xy(r))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs = Vec::new();
        for (k, p) in front.iter().enumerate() {
            if k > 0 {
                stairs.push((p.0, front[k - 1].1));
            }
            stairs.push(*p);
        }
        chart
            .draw_series(LineSeries::new(stairs, BLACK.stroke_width(2)))
            .map_err(err)?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));

        let mut knobs: Vec<&str> = Vec::new();
        for r in self.rows {
            if !knobs.contains(&r.config.knob.as_str()) {
                knobs.push(&r.config.knob);
            }
        }
        for (k, knob) in knobs.iter().enumerate() {
            let (c, marker) = knob_style(k);
            let points: Vec<(f64, f64)> = self
                .rows
                .iter()
                .filter(|r| r.config.knob == *knob)
                .map(|r| self.xy(r))
                .collect();
            match marker {
                Marker::Triangle => {
                    chart
                        .draw_series(
                            points
                                .iter()
                                .map(|&p| TriangleMarker::new(p, 8, c.filled())),
                        )
                        .map_err(err)?
                        .label(knob.to_string())
                        .legend(move |(x, y)| TriangleMarker::new((x + 12, y), 8, c.filled()));
                }
                Marker::Square => {
                    let square = move |(x, y): (i32, i32)| {
                        Rectangle::new([(x - 5, y - 5), (x + 5, y + 5)], c.filled())
                    };
                    chart
                        .draw_series(points.iter().map(|&p| {
                            EmptyElement::at(p) + Rectangle::new([(-5, -5), (5, 5)], c.filled())
                        }))
                        .map_err(err)?
                        .label(knob.to_string())
                        .legend(move |(x, y)| square((x + 12, y)));
                }
                Marker::Dot => {
                    chart
                        .draw_series(points.iter().map(|&p| Circle::new(p, 6, c.filled())))
                        .map_err(err)?
                        .label(knob.to_string())
                        .legend(move |(x, y)| Circle::new((x + 12, y), 6, c.filled()));
                }
            }
        }
        // Front points: ringed and labelled, each label beside its ring
        // where it overlaps no other label and no front point
        // (`place_labels`; labels once overlapped).
        let front_rows: Vec<&Row> = self.rows.iter().filter(|r| r.on_front).collect();
        let anchors: Vec<(i32, i32)> = front_rows
            .iter()
            .map(|r| chart.backend_coord(&self.xy(r)))
            .collect();
        let widths: Vec<i32> = front_rows
            .iter()
            .map(|r| label_width(&r.config.label()))
            .collect();
        let offsets = place_labels(&anchors, &widths);
        let offsets_kept = offsets.clone();
        for (r, offset) in front_rows.iter().zip(offsets) {
            let p = self.xy(r);
            chart
                .draw_series([Circle::new(p, 10, BLACK.stroke_width(2))])
                .map_err(err)?;
            chart
                .draw_series([EmptyElement::at(p)
                    + Text::new(r.config.label(), offset, ("sans-serif", 13).into_font())])
                .map_err(err)?;
        }
        // The legend in the corner the dots and labels crowd least.
        let plot = chart.plotting_area();
        let (pw, ph) = plot.dim_in_pixel();
        let (ox, oy) = plot.get_base_pixel();
        let mut labels = vec!["Pareto front".to_string()];
        labels.extend(knobs.iter().map(|k| k.to_string()));
        let (bw, bh) = crate::output::legend::box_fraction(&labels, 14.0, pw as f64, ph as f64);
        let fraction = |(x, y): (i32, i32)| {
            (
                (x - ox) as f64 / pw as f64,
                1.0 - (y - oy) as f64 / ph as f64,
            )
        };
        let mut drawn: Vec<(f64, f64)> = self
            .rows
            .iter()
            .map(|r| fraction(chart.backend_coord(&self.xy(r))))
            .collect();
        // A front label's box, by its corners.
        for ((&(x, y), &(dx, dy)), &w) in anchors.iter().zip(&offsets_kept).zip(&widths) {
            for (cx, cy) in [(0, 0), (w, 0), (0, LABEL_H), (w, LABEL_H)] {
                drawn.push(fraction((x + dx + cx, y + dy + cy)));
            }
        }
        chart
            .configure_series_labels()
            .position(crate::output::legend::quietest_corner(&drawn, bw, bh))
            .label_font(("sans-serif", 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// The marker of a knob's points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    Dot,
    Triangle,
    Square,
}

/// The colour and marker of the `k`-th knob: the ten colours of
/// [`COLORS`] as dots, then again as triangles, then as squares, so every
/// knob of the bench (22 with the layer knobs, up to 30) is told apart
/// (with one marker, `base` and `area_samples` were both blue dots).
pub fn knob_style(k: usize) -> (RGBColor, Marker) {
    let marker = match (k / COLORS.len()) % 3 {
        0 => Marker::Dot,
        1 => Marker::Triangle,
        _ => Marker::Square,
    };
    (COLORS[k % COLORS.len()], marker)
}

/// Height of a 13 px label's box, and the width per character assumed for
/// it (sans-serif at 13 px averages about 7 px; generous, so estimated
/// boxes do not undercut drawn ones).
const LABEL_H: i32 = 15;
const LABEL_CHAR_W: i32 = 7;
/// Radius kept free around each front point (its ring is 10 px).
const RING: i32 = 11;

fn label_width(text: &str) -> i32 {
    text.chars().count() as i32 * LABEL_CHAR_W
}

/// Offsets (from each anchor, in pixels, to the label's top-left corner)
/// for labels of `widths` beside `anchors`: the first of a list of
/// candidate spots right of the ring, then left of it, stepping further up
/// and down, whose box overlaps no label placed before and no ring. Where
/// every spot collides the first is kept (a crowded cluster still gets
/// its label).
pub fn place_labels(anchors: &[(i32, i32)], widths: &[i32]) -> Vec<(i32, i32)> {
    type Box4 = (i32, i32, i32, i32);
    let overlaps = |a: Box4, b: Box4| a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3;
    let rings: Vec<Box4> = anchors
        .iter()
        .map(|&(x, y)| (x - RING, y - RING, x + RING, y + RING))
        .collect();
    let mut placed: Vec<Box4> = Vec::new();
    let mut order: Vec<usize> = (0..anchors.len()).collect();
    order.sort_by_key(|&i| (anchors[i].0, anchors[i].1));
    let mut out = vec![(12, -16); anchors.len()];
    for i in order {
        let (x, y) = anchors[i];
        let w = widths[i];
        let mut candidates = Vec::new();
        for dy in [-16, 2, -32, 18, -48, 34, -64, 50] {
            candidates.push((12, dy));
            candidates.push((-12 - w, dy));
        }
        let fits = |&(dx, dy): &(i32, i32)| {
            let b = (x + dx, y + dy, x + dx + w, y + dy + LABEL_H);
            !placed.iter().any(|p| overlaps(*p, b)) && !rings.iter().any(|r| overlaps(*r, b))
        };
        let (dx, dy) = candidates
            .iter()
            .copied()
            .find(fits)
            .unwrap_or(candidates[0]);
        placed.push((x + dx, y + dy, x + dx + w, y + dy + LABEL_H));
        out[i] = (dx, dy);
    }
    out
}

#[cfg(test)]
mod label_tests {
    use super::*;

    #[test]
    fn every_knob_has_its_own_style() {
        let styles: Vec<_> = (0..30)
            .map(|k| {
                let (c, marker) = knob_style(k);
                (c.0, c.1, c.2, marker)
            })
            .collect();
        for (i, a) in styles.iter().enumerate() {
            assert!(!styles[i + 1..].contains(a), "knob {i}");
        }
    }

    /// The cluster of the committed docs/bench/pareto.png (fresnel,
    /// distribution and shading_model front points a few pixels apart):
    /// every label box is clear of the others and of every ring.
    #[test]
    fn clustered_front_labels_do_not_overlap() {
        let anchors = [
            (372, 425),
            (405, 432),
            (418, 431),
            (423, 448),
            (690, 457),
            (147, 354),
        ];
        let widths = [120, 140, 150, 130, 160, 150];
        let offsets = place_labels(&anchors, &widths);
        let boxes: Vec<(i32, i32, i32, i32)> = anchors
            .iter()
            .zip(&offsets)
            .zip(&widths)
            .map(|((&(x, y), &(dx, dy)), &w)| (x + dx, y + dy, x + dx + w, y + dy + LABEL_H))
            .collect();
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                let clear = a.2 <= b.0 || b.2 <= a.0 || a.3 <= b.1 || b.3 <= a.1;
                assert!(clear, "{a:?} overlaps {b:?}");
            }
            for &(x, y) in &anchors {
                let clear =
                    a.2 <= x - RING || x + RING <= a.0 || a.3 <= y - RING || y + RING <= a.1;
                assert!(clear, "{a:?} covers the ring at {x},{y}");
            }
        }
        // A lone point keeps the old spot, right of and above its ring.
        assert_eq!(place_labels(&[(100, 100)], &[80]), vec![(12, -16)]);
    }
}
