//! The explorer's plots: the polar slice and the albedo curve of several
//! materials, drawn with the shared plotting of [`crate::output::plot`].

use super::Channel;
use super::albedo::AlbedoEstimate;
use super::slice::{Quantity, Slice};
use crate::output::plot::{Plot, color, err, nice_step, number, thin};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Upper end of the albedo axis.
const ALBEDO_CLIP: f64 = 3.0;

/// The polar slice of several materials at one incidence angle.
pub struct SlicePlot {
    /// Incidence angle θ_i, radians.
    pub theta_i: f64,
    /// Azimuth φ_i of the plane of incidence, radians.
    pub phi_i: f64,
    pub quantity: Quantity,
    pub channel: Channel,
    /// `(legend label, slice)` per material.
    pub series: Vec<(String, Slice)>,
    /// Outer radius; `None`: the largest value drawn. Larger values are
    /// clipped to it.
    pub max: Option<f64>,
    /// Shared parameters, shown under the title.
    pub note: String,
}

impl Plot for SlicePlot {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let below = self.series.iter().any(|(_, s)| !s.transmitted.is_empty());
        let title = format!(
            "{} slice in the plane of incidence, θ_i = {}°, φ_i = {}°",
            if below { "BSDF" } else { "BRDF" },
            number(self.theta_i.to_degrees()),
            number(self.phi_i.to_degrees())
        );
        let root = root.titled(&title, ("sans-serif", 24)).map_err(err)?;
        let (_, h) = root.dim_in_pixel();
        let (area, footer) = root.split_vertically(h - 50);
        let footer_style =
            TextStyle::from(("sans-serif", 15).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
        let (fw, _) = footer.dim_in_pixel();
        let mut line1 = format!("{}; {}", self.quantity.describe(), self.channel.describe());
        if below {
            line1 += "; below the surface: transmitted (f_t)";
        }
        if let Some(max) = self.max {
            line1 += &format!("; clipped at {}", number(max));
        }
        let line2 = if self.note.is_empty() {
            "θ_o > 0 on the light's side, < 0 on the mirror side; n = +Z".to_string()
        } else {
            format!("{}; θ_o > 0 on the light's side", self.note)
        };
        footer
            .draw_text(&line1, &footer_style, (fw as i32 / 2, 4))
            .map_err(err)?;
        footer
            .draw_text(&line2, &footer_style, (fw as i32 / 2, 25))
            .map_err(err)?;

        let area = area.margin(4, 4, 10, 10);
        let largest = self
            .series
            .iter()
            .flat_map(|(_, s)| s.points.iter().chain(&s.transmitted).map(|p| p.1))
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let r = self.max.unwrap_or(largest);
        let r = if r > 0.0 && r.is_finite() { r } else { 1.0 };
        // A material that lets light through: the whole circle, the
        // transmitted lobe below the surface.
        let (half_turn, quarter): (i32, i32) = if below { (180, 360) } else { (90, 180) };
        // Equal scales on both axes: the data box has the area's aspect.
        let (w, h) = area.dim_in_pixel();
        let (y0, mut y1) = (if below { -1.14 * r } else { -0.09 * r }, 1.14 * r);
        let mut xh = 0.5 * (y1 - y0) * w as f64 / h as f64;
        if xh < 1.2 * r {
            xh = 1.2 * r;
            y1 = y0 + 2.0 * xh * h as f64 / w as f64;
        }
        let mut chart = ChartBuilder::on(&area)
            .build_cartesian_2d(-xh..xh, y0..y1)
            .map_err(err)?;
        let polar = |radius: f64, t: f64| {
            let [x, y] = super::slice::polar(radius, t);
            (x, y)
        };
        let pixel = 2.0 * xh / w as f64;
        let grey = RGBColor(200, 200, 200);
        let label = TextStyle::from(("sans-serif", 14).into_font()).color(&BLACK);

        // Grid: circles at 1-2-5 radii, labelled along the surface; spokes.
        let step = nice_step(r, 4.0);
        let mut k = 1.0;
        while k * step <= r * 1.0001 {
            let radius = k * step;
            let arc =
                (0..=quarter).map(|d| polar(radius, (d as f64 - half_turn as f64).to_radians()));
            chart.draw_series(LineSeries::new(arc, grey)).map_err(err)?;
            let text = label.pos(Pos::new(HPos::Center, VPos::Top));
            chart
                .draw_series(std::iter::once(Text::new(
                    number(radius),
                    (radius, -0.015 * r),
                    text,
                )))
                .map_err(err)?;
            k += 1.0;
        }
        for d in (-half_turn..=half_turn).step_by(15) {
            let t = (d as f64).to_radians();
            chart
                .draw_series(LineSeries::new([(0.0, 0.0), polar(r, t)], grey.mix(0.6)))
                .map_err(err)?;
            let marked = [0.0, self.theta_i, -self.theta_i]
                .iter()
                .any(|m| (t - m).abs() < 0.09);
            if d % 30 == 0 && d.abs() != 90 && d != -180 && !marked {
                let text = label.pos(Pos::new(HPos::Center, VPos::Center));
                chart
                    .draw_series(std::iter::once(Text::new(
                        format!("{d}°"),
                        polar(1.07 * r, t),
                        text,
                    )))
                    .map_err(err)?;
            }
        }
        // The surface, the normal, the light and the mirror direction.
        chart
            .draw_series(LineSeries::new(
                [(-1.1 * r, 0.0), (1.1 * r, 0.0)],
                BLACK.stroke_width(2),
            ))
            .map_err(err)?;
        let mut marks = vec![
            (0.0, "n", BLACK),
            (self.theta_i, "ω_i (light)", RGBColor(90, 90, 90)),
            (-self.theta_i, "mirror", RGBColor(90, 90, 90)),
        ];
        if below {
            // The light's straight line through the surface, −ω_i.
            marks.push((
                self.theta_i - std::f64::consts::PI,
                "−ω_i (straight through)",
                RGBColor(90, 90, 90),
            ));
        }
        for (t, name, c) in marks {
            let end = polar(1.1 * r, t);
            if name == "ω_i (light)" {
                chart
                    .draw_series(LineSeries::new([(0.0, 0.0), end], c.stroke_width(2)))
                    .map_err(err)?;
            } else {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(0.0, 0.0), end],
                        6,
                        5,
                        c.stroke_width(1),
                    ))
                    .map_err(err)?;
            }
            let anchor = if t > 1e-9 {
                HPos::Left
            } else if t < -1e-9 {
                HPos::Right
            } else {
                HPos::Center
            };
            let vertical = if polar(1.0, t).1 < 0.0 {
                VPos::Top
            } else {
                VPos::Bottom
            };
            let text = label.color(&c).pos(Pos::new(anchor, vertical));
            chart
                .draw_series(std::iter::once(Text::new(name, polar(1.12 * r, t), text)))
                .map_err(err)?;
        }

        // The lobes.
        for (k, (name, slice)) in self.series.iter().enumerate() {
            let c = color(k);
            let curve = thin(
                slice.points.iter().map(|&(t, v)| polar(v.clamp(0.0, r), t)),
                pixel,
            );
            chart
                .draw_series(LineSeries::new(curve, c.stroke_width(2)))
                .map_err(err)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3))
                });
            if !slice.transmitted.is_empty() {
                let curve = thin(
                    slice
                        .transmitted
                        .iter()
                        .map(|&(t, v)| polar(v.clamp(0.0, r), t)),
                    pixel,
                );
                chart
                    .draw_series(LineSeries::new(curve, c.stroke_width(2)))
                    .map_err(err)?;
            }
            if let Some(rho) = slice.dirac {
                let end = polar(r, -self.theta_i);
                chart
                    .draw_series(LineSeries::new([(0.0, 0.0), end], c.stroke_width(4)))
                    .map_err(err)?;
                chart
                    .draw_series(std::iter::once(Circle::new(end, 5, c.filled())))
                    .map_err(err)?;
                // Beside the middle of the spike, on the side away from the normal.
                let text = label.color(&c).pos(Pos::new(HPos::Right, VPos::Top));
                let at = polar(0.55 * r, -self.theta_i);
                chart
                    .draw_series(std::iter::once(Text::new(
                        format!("δ lobe, ρ = {}", number(rho)),
                        (at.0 - 0.03 * r, at.1 - 0.03 * r),
                        text,
                    )))
                    .map_err(err)?;
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// Directional albedo against incidence angle for several materials.
pub struct AlbedoPlot {
    /// Incidence angles θ_i, degrees.
    pub thetas_deg: Vec<f64>,
    /// Azimuth φ_i of the incident light, radians.
    pub phi_i: f64,
    /// `(legend label, estimate per angle)` per material.
    pub series: Vec<(String, Vec<AlbedoEstimate>)>,
    pub channel: Channel,
    /// Shared parameters, shown under the title.
    pub note: String,
}

impl Plot for AlbedoPlot {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root
            .titled(
                "Directional albedo ρ(θ_i) = ∫ f_r cos θ_o dω_o",
                ("sans-serif", 24),
            )
            .map_err(err)?;
        let (_, h) = root.dim_in_pixel();
        let (area, footer) = root.split_vertically(h - 30);
        let worst = self
            .series
            .iter()
            .flat_map(|(_, e)| e.iter().map(|e| self.channel.of(e.error_bound)))
            .fold(0.0, f64::max);
        let mut line = format!(
            "{}; φ_i = {}° (0: along the tangent); quadrature error ≤ {} (Gauss-Kronrod 7-15)",
            self.channel.describe(),
            number(self.phi_i.to_degrees()),
            number(worst)
        );
        if !self.note.is_empty() {
            line = format!("{}; {line}", self.note);
        }
        let top = self
            .series
            .iter()
            .flat_map(|(_, e)| e.iter().map(|e| self.channel.of(e.value)))
            .filter(|v| v.is_finite())
            .fold(1.0, f64::max);
        // The lecture's forms diverge at grazing incidence (ρ ≈ 39 for Phong
        // k_e = 1 at 89°): above 3 the curves are clipped, so that the
        // region around ρ = 1 stays readable.
        let y_max = (1.1 * top).min(ALBEDO_CLIP);
        if top > ALBEDO_CLIP {
            line += &format!("; clipped at ρ = {ALBEDO_CLIP}");
        }
        let (fw, _) = footer.dim_in_pixel();
        let style =
            TextStyle::from(("sans-serif", 15).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
        footer
            .draw_text(&line, &style, (fw as i32 / 2, 4))
            .map_err(err)?;
        let mut chart = ChartBuilder::on(&area)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0..90.0, 0.0..y_max)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("incidence angle θ_i [°]")
            .y_desc("ρ(θ_i)")
            .x_labels(10)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| number(*y))
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, 1.0), (90.0, 1.0)],
                10,
                6,
                BLACK.stroke_width(2),
            ))
            .map_err(err)?
            .label("ρ = 1: energy conservation")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2)));
        for (k, (name, estimates)) in self.series.iter().enumerate() {
            let c = color(k);
            let points = self
                .thetas_deg
                .iter()
                .zip(estimates)
                .map(|(&t, e)| (t, self.channel.of(e.value).min(y_max)));
            chart
                .draw_series(LineSeries::new(points, c.stroke_width(2)))
                .map_err(err)?
                .label(name.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3))
                });
        }
        // The legend in the corner the curves cross least.
        let (pw, ph) = chart.plotting_area().dim_in_pixel();
        let mut labels = vec!["ρ = 1: energy conservation".to_string()];
        labels.extend(self.series.iter().map(|(name, _)| name.clone()));
        let (bw, bh) = crate::output::legend::box_fraction(&labels, 15.0, pw as f64, ph as f64);
        let mut drawn: Vec<(f64, f64)> = (0..=90).map(|t| (t as f64 / 90.0, 1.0 / y_max)).collect();
        for (_, estimates) in &self.series {
            drawn.extend(
                self.thetas_deg
                    .iter()
                    .zip(estimates)
                    .map(|(&t, e)| (t / 90.0, self.channel.of(e.value).min(y_max) / y_max)),
            );
        }
        chart
            .configure_series_labels()
            .position(crate::output::legend::quietest_corner(&drawn, bw, bh))
            .label_font(("sans-serif", 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_short() {
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(1.0), "1");
        assert_eq!(number(12.5), "12.5");
        assert_eq!(number(1234.5678), "1235");
        assert_eq!(number(2.5e-5), "2.50e-5");
        assert_eq!(nice_step(1.0, 4.0), 0.5);
        assert_eq!(nice_step(0.3, 4.0), 0.1);
    }
}
