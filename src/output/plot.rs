//! Plots to PNG or SVG with `plotters`: the destination, the font, the
//! palette and the number formatting every gonio plot shares (the BRDF
//! explorer's slices and albedo, the bench's Pareto front).
//!
//! Text needs a font: plotters' `ab_glyph` backend (pure Rust, no
//! fontconfig) is given DejaVu Sans, read at run time from
//! [`FONT_PATH`] (Debian's `fonts-dejavu-core`, which `setup.sh` installs)
//! or from the file `GONIO_FONT` names. Files are written like renders:
//! to a temporary file first, renamed into place only when complete.

use super::AtomicFile;
use crate::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Where Debian's `fonts-dejavu-core` puts DejaVu Sans.
pub const FONT_PATH: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

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

/// The `k`-th line colour, cycling through [`COLORS`].
pub fn color(k: usize) -> RGBColor {
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
        let bytes = self.encode(plot)?;
        self.file.commit(&bytes)
    }

    /// The claimed file, for a set written together
    /// ([`super::atomic::commit_all`]) with the bytes of [`Self::encode`].
    pub fn into_file(self) -> AtomicFile {
        self.file
    }

    /// Draws `plot` into the bytes of the file.
    pub fn encode(&self, plot: &impl Plot) -> Result<Vec<u8>> {
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
        Ok(bytes)
    }
}

/// Registers the plot font (as `"sans-serif"`) once per process.
pub fn load_font() -> Result<()> {
    static LOADED: OnceLock<std::result::Result<(), (PathBuf, String)>> = OnceLock::new();
    let loaded = LOADED.get_or_init(|| {
        let path = std::env::var_os("GONIO_FONT")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(FONT_PATH));
        // DejaVu Sans is 740 kB; the largest fonts are tens of MB.
        let bytes = crate::base::input::read_regular_file(&path, 256 << 20)
            .map_err(|e| (path.clone(), e.to_string()))?;
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

/// A drawing error as the message [`Plot::draw`] returns.
pub fn err(e: impl std::fmt::Display) -> String {
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
pub fn thin(points: impl Iterator<Item = (f64, f64)>, pixel: f64) -> Vec<(f64, f64)> {
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
pub fn nice_step(max: f64, count: f64) -> f64 {
    let raw = max / count;
    let decade = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * decade)
}
