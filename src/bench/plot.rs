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
            let c = COLORS[k % COLORS.len()];
            let points: Vec<(f64, f64)> = self
                .rows
                .iter()
                .filter(|r| r.config.knob == *knob)
                .map(|r| self.xy(r))
                .collect();
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 6, c.filled())))
                .map_err(err)?
                .label(knob.to_string())
                .legend(move |(x, y)| Circle::new((x + 12, y), 6, c.filled()));
        }
        // Front points: ringed and labelled.
        for r in self.rows.iter().filter(|r| r.on_front) {
            let p = self.xy(r);
            chart
                .draw_series([Circle::new(p, 10, BLACK.stroke_width(2))])
                .map_err(err)?;
            // Label beside the ring, not on the dot.
            chart
                .draw_series([EmptyElement::at(p)
                    + Text::new(r.config.label(), (12, -16), ("sans-serif", 13).into_font())])
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}
