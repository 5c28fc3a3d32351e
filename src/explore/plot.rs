//! Drawing the slice and albedo plots to PNG or SVG with `plotters`.
//!
//! Text needs a font: plotters' `ab_glyph` backend (pure Rust, no
//! fontconfig) is given DejaVu Sans, read at run time from
//! [`FONT_PATH`] (Debian's `fonts-dejavu-core`, which `setup.sh` installs)
//! or from the file `GONIO_FONT` names. Files are written like renders:
//! to a temporary file first, renamed into place only when complete.

use super::Channel;
use super::albedo::AlbedoEstimate;
use super::slice::{Quantity, Slice};
use crate::output::AtomicFile;
use crate::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Where Debian's `fonts-dejavu-core` puts DejaVu Sans.
pub const FONT_PATH: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// Upper end of the albedo axis.
const ALBEDO_CLIP: f64 = 3.0;

/// Size of every plot, in pixels (SVG user units).
const SIZE: (u32, u32) = (960, 600);

/// Line colours (Tableau 10): distinct, and distinguishable in print.
pub const COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

fn color(k: usize) -> RGBColor {
    COLORS[k % COLORS.len()]
}

/// The output formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlotFormat {
    Png,
    Svg,
}

/// A plot destination claimed before any work is done, so a bad path fails
/// first and a failure leaves no partial file.
pub struct PlotFile {
    format: PlotFormat,
    file: AtomicFile,
}

impl PlotFile {
    /// Checks the extension (`.png` or `.svg`) and that the folder accepts a
    /// file; also loads the font, whose absence is an error too.
    pub fn prepare(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let format = match ext.as_deref() {
            Some("png") => PlotFormat::Png,
            Some("svg") => PlotFormat::Svg,
            _ => {
                return Err(Error::output(
                    path,
                    "unknown plot format; the file name must end in .png or .svg",
                ));
            }
        };
        load_font()?;
        let file = AtomicFile::create(path)?;
        Ok(PlotFile { format, file })
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Draws `plot` and moves the file into place.
    pub fn write(self, plot: &impl Plot) -> Result<()> {
        let fail = |e: String| Error::output(self.file.path(), e);
        let bytes = match self.format {
            PlotFormat::Svg => {
                let mut svg = String::new();
                {
                    let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
                    plot.draw(&root).map_err(fail)?;
                    root.present().map_err(|e| fail(e.to_string()))?;
                }
                svg.into_bytes()
            }
            PlotFormat::Png => {
                let (w, h) = SIZE;
                let mut pixels = vec![0u8; (w * h * 3) as usize];
                {
                    let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
                    plot.draw(&root).map_err(fail)?;
                    root.present().map_err(|e| fail(e.to_string()))?;
                }
                let image = image::RgbImage::from_raw(w, h, pixels)
                    .ok_or_else(|| fail("plot buffer has the wrong size".into()))?;
                let mut out = Cursor::new(Vec::new());
                image
                    .write_to(&mut out, image::ImageFormat::Png)
                    .map_err(|e| fail(format!("PNG encoding failed: {e}")))?;
                out.into_inner()
            }
        };
        self.file.commit(&bytes)
    }
}

/// Registers the plot font once per process.
fn load_font() -> Result<()> {
    static LOADED: OnceLock<std::result::Result<(), (PathBuf, String)>> = OnceLock::new();
    let loaded = LOADED.get_or_init(|| {
        let path = std::env::var_os("GONIO_FONT")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(FONT_PATH));
        let bytes = std::fs::read(&path).map_err(|e| (path.clone(), e.to_string()))?;
        // plotters keeps fonts for the whole process: leaking once is that.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
            .map_err(|_| (path.clone(), "not a TrueType/OpenType font".to_string()))
    });
    loaded.clone().map_err(|(path, problem)| {
        Error::input(
            path,
            format!(
                "cannot load the font for plot labels ({problem}); install Debian's fonts-dejavu-core (./setup.sh does) or set GONIO_FONT to a .ttf file"
            ),
        )
    })
}

/// Something [`PlotFile::write`] can draw on any backend.
pub trait Plot {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), String>;
}

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// A short decimal for labels: 4 significant digits, trailing zeros cut.
pub fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e5).contains(&v.abs()) {
        return format!("{v:.2e}");
    }
    let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The points of a polyline less those closer than half a pixel to the
/// last one kept (the first and last are kept): thousands of sub-pixel
/// segments of a thick line rasterize as a ragged edge.
fn thin(points: impl Iterator<Item = (f64, f64)>, pixel: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut last_skipped = None;
    for p in points {
        match out.last() {
            Some(&(x, y)) if (p.0 - x).hypot(p.1 - y) < 0.5 * pixel => last_skipped = Some(p),
            _ => {
                out.push(p);
                last_skipped = None;
            }
        }
    }
    out.extend(last_skipped);
    out
}

/// A 1-2-5 step giving about `count` intervals over `[0, max]`.
fn nice_step(max: f64, count: f64) -> f64 {
    let raw = max / count;
    let decade = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * decade)
}

/// The polar slice of several materials at one incidence angle.
pub struct SlicePlot {
    /// Incidence angle θ_i, radians.
    pub theta_i: f64,
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
        let title = format!(
            "BRDF slice in the plane of incidence, θ_i = {}°",
            number(self.theta_i.to_degrees())
        );
        let root = root.titled(&title, ("sans-serif", 24)).map_err(err)?;
        let (_, h) = root.dim_in_pixel();
        let (area, footer) = root.split_vertically(h - 50);
        let footer_style =
            TextStyle::from(("sans-serif", 15).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
        let (fw, _) = footer.dim_in_pixel();
        let mut line1 = format!("{}; {}", self.quantity.describe(), self.channel.describe());
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
            .flat_map(|(_, s)| s.points.iter().map(|p| p.1))
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let r = self.max.unwrap_or(largest);
        let r = if r > 0.0 && r.is_finite() { r } else { 1.0 };
        // Equal scales on both axes: the data box has the area's aspect.
        let (w, h) = area.dim_in_pixel();
        let (y0, mut y1) = (-0.09 * r, 1.14 * r);
        let mut xh = 0.5 * (y1 - y0) * w as f64 / h as f64;
        if xh < 1.2 * r {
            xh = 1.2 * r;
            y1 = y0 + 2.0 * xh * h as f64 / w as f64;
        }
        let mut chart = ChartBuilder::on(&area)
            .build_cartesian_2d(-xh..xh, y0..y1)
            .map_err(err)?;
        let polar = |radius: f64, t: f64| (radius * t.sin(), radius * t.cos());
        let pixel = 2.0 * xh / w as f64;
        let grey = RGBColor(200, 200, 200);
        let label = TextStyle::from(("sans-serif", 14).into_font()).color(&BLACK);

        // Grid: circles at 1-2-5 radii, labelled along the surface; spokes.
        let step = nice_step(r, 4.0);
        let mut k = 1.0;
        while k * step <= r * 1.0001 {
            let radius = k * step;
            let arc = (0..=180).map(|d| polar(radius, (d as f64 - 90.0).to_radians()));
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
        for d in (-90i32..=90).step_by(15) {
            let t = (d as f64).to_radians();
            chart
                .draw_series(LineSeries::new([(0.0, 0.0), polar(r, t)], grey.mix(0.6)))
                .map_err(err)?;
            let marked = [0.0, self.theta_i, -self.theta_i]
                .iter()
                .any(|m| (t - m).abs() < 0.09);
            if d % 30 == 0 && d.abs() != 90 && !marked {
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
        let marks = [
            (0.0, "n", BLACK),
            (self.theta_i, "ω_i (light)", RGBColor(90, 90, 90)),
            (-self.theta_i, "mirror", RGBColor(90, 90, 90)),
        ];
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
            let text = label.color(&c).pos(Pos::new(anchor, VPos::Bottom));
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
            "{}; φ_i = 0 (along the tangent); quadrature error ≤ {} (Gauss-Kronrod 7-15)",
            self.channel.describe(),
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
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
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
