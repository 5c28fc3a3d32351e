//! The θ_h × θ_d image ([`super::halfdiff`]) drawn as BRDF Explorer's
//! "Image Slice": θ_h along x, θ_d up, log₁₀ f_r in colour; one panel per
//! material, one colour scale for all. Cells are drawn in pixel space from
//! [`layout`], so a test can find cell (θ_h, θ_d) in the written image.

use super::halfdiff::{CELLS, HalfDiffImage, half_diff_image_at};
use super::{Channel, MaterialPart};
use crate::Result;
use crate::output::plot::{Plot, PlotFile, err, number};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Decades the colour scale spans at most below the largest value: BRDF
/// Explorer's log view, where highlights span 10⁶.
pub const DECADES: f64 = 6.0;

/// Cells with no value (f_r ≤ 0 or not finite: below the scale's reach).
pub const NO_DATA: RGBColor = RGBColor(235, 235, 235);

/// The image slices of several materials.
pub struct HalfDiffPlot {
    pub channel: Channel,
    /// The difference azimuth φ_d [°] of every image.
    pub phi_d_deg: f64,
    /// `(label, image)` per material.
    pub series: Vec<(String, HalfDiffImage)>,
    /// Shared parameters, shown under the title.
    pub note: String,
}

/// A panel's data square in pixels: left, top, side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Panel {
    pub x0: f64,
    pub y0: f64,
    pub side: f64,
}

impl Panel {
    /// The pixel at the centre of cell `i` (θ_h) of row `j` (θ_d; row 0 at
    /// the bottom).
    pub fn cell_centre(&self, i: usize, j: usize) -> (i32, i32) {
        let c = self.side / CELLS as f64;
        let x = self.x0 + (i as f64 + 0.5) * c;
        let y = self.y0 + self.side - (j as f64 + 0.5) * c;
        (x as i32, y as i32)
    }
}

/// The data squares of `n` panels on a `w × h` canvas: a title band on
/// top, axis labels left of and below each square, the colour bar right.
pub fn layout(w: u32, h: u32, n: usize) -> Vec<Panel> {
    let (top, bottom, left, gap, bar) = (56.0, 84.0, 64.0, 80.0, 110.0);
    let n_f = n.max(1) as f64;
    let by_width = (w as f64 - bar - left - (n_f - 1.0) * gap) / n_f;
    let by_height = h as f64 - top - bottom;
    let side = by_width.min(by_height).floor();
    // Centred vertically when the width limits the squares.
    let y0 = (top + 0.5 * (by_height - side)).floor();
    (0..n)
        .map(|k| Panel {
            x0: left + k as f64 * (side + gap),
            y0,
            side,
        })
        .collect()
}

/// The colour of `v` on the log scale `[lo, hi]` (log₁₀ values): viridis
/// (matplotlib's, 9 control points, linear between them); clipped at both
/// ends; [`NO_DATA`] for `v ≤ 0` or not finite.
pub fn colour(v: f64, lo: f64, hi: f64) -> RGBColor {
    if !(v > 0.0 && v.is_finite()) {
        return NO_DATA;
    }
    let t = ((v.log10() - lo) / (hi - lo).max(1e-12)).clamp(0.0, 1.0);
    viridis(t)
}

/// Viridis at `t` in [0, 1] (0 dark blue, 1 yellow): the viewer's
/// image uses the same scale.
pub fn viridis(t: f64) -> RGBColor {
    const P: [(f64, f64, f64); 9] = [
        (68.0, 1.0, 84.0),
        (71.0, 44.0, 122.0),
        (59.0, 81.0, 139.0),
        (44.0, 113.0, 142.0),
        (33.0, 144.0, 141.0),
        (39.0, 173.0, 129.0),
        (92.0, 200.0, 99.0),
        (170.0, 220.0, 50.0),
        (253.0, 231.0, 37.0),
    ];
    let x = t * 8.0;
    let k = (x.floor() as usize).min(7);
    let f = x - k as f64;
    let (a, b) = (P[k], P[k + 1]);
    let mix = |p: f64, q: f64| (p + f * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// `gonio brdf --plot-halfdiff`: the image of every material (or layer
/// term of one, `--layer`) into `file`.
pub fn encode(
    file: &PlotFile,
    materials: &[(String, MaterialPart)],
    channel: Channel,
    phi_d_deg: f64,
    note: String,
) -> Result<Vec<u8>> {
    let plot = HalfDiffPlot {
        channel,
        phi_d_deg,
        series: materials
            .iter()
            .map(|(label, part)| {
                let image = half_diff_image_at(*part, channel, phi_d_deg.to_radians());
                (label.clone(), image)
            })
            .collect(),
        note,
    };
    file.encode(&plot)
}

impl HalfDiffPlot {
    /// The log₁₀ range of the colour scale: the largest positive value
    /// down to the smallest, at most [`DECADES`] below.
    pub fn range(&self) -> (f64, f64) {
        let logs = self
            .series
            .iter()
            .flat_map(|(_, img)| img.values.iter().flatten())
            .filter(|v| **v > 0.0 && v.is_finite())
            .map(|v| v.log10());
        let (lo, hi) = logs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
        if !hi.is_finite() {
            return (-1.0, 0.0);
        }
        let lo = lo.max(hi - DECADES);
        // A constant image (Lambert) still gets a scale around its value.
        if hi - lo < 1e-9 {
            (hi - 0.5, hi + 0.5)
        } else {
            (lo, hi)
        }
    }
}

impl Plot for HalfDiffPlot {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let (w, h) = root.dim_in_pixel();
        let centre = |size| TextStyle::from(("sans-serif", size).into_font());
        let at = |s: TextStyle<'static>, hp, vp| s.pos(Pos::new(hp, vp));
        let title = format!(
            "BRDF image slice: θ_h × θ_d at φ_d = {}° (Rusinkiewicz 1998), colour log₁₀ f_r",
            self.phi_d_deg
        );
        root.draw_text(
            &title,
            &at(centre(22), HPos::Center, VPos::Top),
            (w as i32 / 2, 6),
        )
        .map_err(err)?;
        let mut footer = format!("f_r [1/sr], {}", self.channel.describe());
        if !self.note.is_empty() {
            footer += &format!("; {}", self.note);
        }
        root.draw_text(
            &footer,
            &at(centre(15), HPos::Center, VPos::Bottom),
            (w as i32 / 2, h as i32 - 6),
        )
        .map_err(err)?;

        let (lo, hi) = self.range();
        let panels = layout(w, h, self.series.len());
        let small = at(centre(14), HPos::Center, VPos::Top);
        for (panel, (label, img)) in panels.iter().zip(&self.series) {
            let c = panel.side / CELLS as f64;
            for (j, row) in img.values.iter().enumerate() {
                for (i, v) in row.iter().enumerate() {
                    let x0 = panel.x0 + i as f64 * c;
                    let y1 = panel.y0 + panel.side - j as f64 * c;
                    let rect = [
                        (x0.floor() as i32, (y1 - c).floor() as i32),
                        ((x0 + c).ceil() as i32, y1.ceil() as i32),
                    ];
                    root.draw(&Rectangle::new(rect, colour(*v, lo, hi).filled()))
                        .map_err(err)?;
                }
            }
            let (x0, y0, s) = (panel.x0 as i32, panel.y0 as i32, panel.side as i32);
            root.draw(&Rectangle::new([(x0, y0), (x0 + s, y0 + s)], BLACK))
                .map_err(err)?;
            // About 7 px per character at 13 px: cut what would run into
            // the next panel's label.
            let room = ((panel.side + 70.0) / 7.0) as usize;
            let label = if label.chars().count() > room {
                let cut: String = label.chars().take(room.saturating_sub(1)).collect();
                cut + "…"
            } else {
                label.clone()
            };
            root.draw_text(
                &label,
                &at(centre(13), HPos::Center, VPos::Bottom),
                (x0 + s / 2, y0 - 4),
            )
            .map_err(err)?;
            for deg in [0, 30, 60, 90] {
                let p = deg * s / 90;
                root.draw(&PathElement::new(
                    [(x0 + p, y0 + s), (x0 + p, y0 + s + 5)],
                    BLACK,
                ))
                .map_err(err)?;
                root.draw_text(&format!("{deg}°"), &small, (x0 + p, y0 + s + 7))
                    .map_err(err)?;
                root.draw(&PathElement::new(
                    [(x0 - 5, y0 + s - p), (x0, y0 + s - p)],
                    BLACK,
                ))
                .map_err(err)?;
                // The corner's 0° is the θ_h axis' label: a second one
                // beside it, and the previous panel's 90° beside that,
                // read as "900".
                if deg == 0 {
                    continue;
                }
                root.draw_text(
                    &format!("{deg}°"),
                    &at(centre(14), HPos::Right, VPos::Center),
                    (x0 - 7, y0 + s - p),
                )
                .map_err(err)?;
            }
            root.draw_text("θ_h", &small, (x0 + s / 2, y0 + s + 26))
                .map_err(err)?;
            root.draw_text(
                "θ_d",
                &at(centre(14), HPos::Right, VPos::Center),
                (x0 - 34, y0 + s / 2 - 14),
            )
            .map_err(err)?;
        }

        // Colour bar, labelled at whole decades.
        if let Some(last) = panels.last() {
            let bx = (last.x0 + last.side) as i32 + 30;
            let (by, bs) = (last.y0 as i32, last.side as i32);
            for k in 0..bs {
                let t = 1.0 - (k as f64 + 0.5) / bs as f64;
                root.draw(&Rectangle::new(
                    [(bx, by + k), (bx + 18, by + k + 1)],
                    viridis(t).filled(),
                ))
                .map_err(err)?;
            }
            let mut d = lo.ceil();
            while d <= hi + 1e-9 {
                let y = by + ((hi - d) / (hi - lo) * bs as f64) as i32;
                root.draw(&PathElement::new([(bx + 18, y), (bx + 23, y)], BLACK))
                    .map_err(err)?;
                root.draw_text(
                    &number(10f64.powf(d)),
                    &at(centre(13), HPos::Left, VPos::Center),
                    (bx + 26, y),
                )
                .map_err(err)?;
                d += 1.0;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::explore::halfdiff::half_diff_image;
    use crate::explore::spec::compare_spec;

    /// The drawn image holds each cell's colour where [`layout`] says: the
    /// specular peak at θ_h = 0 (first column) is the scale's top colour, a
    /// cell far from it is darker, and the two panels of a comparison each
    /// show their own material.
    #[test]
    fn cells_are_drawn_where_the_layout_says() {
        let glossy = compare_spec("cook-torrance,k_d=0.1,k_s=1,roughness=0.1", &[]).unwrap();
        let matte = compare_spec("lambert,k_d=0.5", &[]).unwrap();
        let plot = HalfDiffPlot {
            channel: Channel::Mean,
            phi_d_deg: 90.0,
            series: vec![
                (
                    "glossy".into(),
                    half_diff_image(&glossy.material, Channel::Mean),
                ),
                (
                    "matte".into(),
                    half_diff_image(&matte.material, Channel::Mean),
                ),
            ],
            note: String::new(),
        };
        let (w, h) = (960u32, 600u32);
        let mut pixels = vec![0u8; (w * h * 3) as usize];
        crate::output::plot::load_font().unwrap();
        {
            let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
            plot.draw(&root).unwrap();
            root.present().unwrap();
        }
        let at = |(x, y): (i32, i32)| {
            let k = 3 * (y as usize * w as usize + x as usize);
            RGBColor(pixels[k], pixels[k + 1], pixels[k + 2])
        };
        let (lo, hi) = plot.range();
        let panels = layout(w, h, 2);
        assert!(
            panels[0].side >= 2.0 * CELLS as f64,
            "cells of ≥ 2 px: {:?}",
            panels[0]
        );
        for (p, (_, img)) in panels.iter().zip(&plot.series) {
            for (i, j) in [(0, 10), (0, 45), (45, 45), (89, 5), (20, 80)] {
                assert_eq!(
                    at(p.cell_centre(i, j)),
                    colour(img.values[j][i], lo, hi),
                    "cell {i},{j}"
                );
            }
        }
        // The brightest cell of the glossy panel is on the first column.
        let peak = plot.series[0]
            .1
            .values
            .iter()
            .flatten()
            .fold(0.0f64, |a, v| a.max(*v));
        assert!((peak.log10() - hi).abs() < 1e-12);
        let first_column_max = plot.series[0]
            .1
            .values
            .iter()
            .map(|r| r[0])
            .fold(0.0f64, f64::max);
        assert_eq!(first_column_max, peak);
        let j_peak = (0..CELLS)
            .find(|j| plot.series[0].1.values[*j][0] == peak)
            .unwrap();
        assert_eq!(at(panels[0].cell_centre(0, j_peak)), viridis(1.0));
        assert_ne!(
            at(panels[0].cell_centre(45, 45)),
            at(panels[0].cell_centre(0, 45))
        );
    }
}
