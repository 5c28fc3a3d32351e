//! A picture of the thin film's colour against thickness: the spectral
//! truth and the specification's form side by side, as colour strips
//! (sRGB-encoded, exposed so the truth's brightest channel is 1) and as
//! R, G, B curves (truth solid, form dashed). Plain SVG text: the curves
//! need no font and no plotting back end, and the file is reproducible
//! to the digit (`docs/spectral-film.svg`).

use super::thin_film::{FilmCase, gltf_film_rgb, spectral_film_rgb};
use crate::base::Rgb;
use std::fmt::Write;

const WIDTH: f64 = 960.0;
const HEIGHT: f64 = 600.0;
const LEFT: f64 = 80.0;
const RIGHT: f64 = 940.0;
const CHART_TOP: f64 = 170.0;
const CHART_BOTTOM: f64 = 550.0;
/// Largest thickness drawn [nm], one sample every nm.
const MAX_NM: usize = 1000;

/// The sRGB transfer function of one linear value in [0, 1] (IEC
/// 61966-2-1), as an 8-bit level.
fn srgb8(linear: f64) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let v = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (v * 255.0).round() as u8
}

/// The SVG of `case` at `cos θ = cos_i` over 0–1000 nm.
pub fn film_svg(case: FilmCase, cos_i: f64, title: &str) -> String {
    let truth: Vec<Rgb> = (0..=MAX_NM)
        .map(|d| spectral_film_rgb(cos_i, case.eta_f, d as f64, case.base))
        .collect();
    // d = 0 switches the layer off (pinned choice 2): the form starts at 1 nm.
    let form: Vec<Rgb> = (0..=MAX_NM)
        .map(|d| gltf_film_rgb(cos_i, case.eta_f, (d as f64).max(1.0), case.base))
        .collect();
    let peak = truth
        .iter()
        .chain(&form)
        .map(|c| c.max_element())
        .fold(0.0, f64::max);
    // Out-of-gamut colours have negative channels: the axis shows them.
    let trough = truth
        .iter()
        .chain(&form)
        .map(|c| c.min_element())
        .fold(0.0, f64::min);
    let exposure = 1.0 / truth.iter().map(|c| c.max_element()).fold(0.0, f64::max);
    let y_max = (peak * 100.0).ceil() / 100.0;
    let y_min = (trough * 100.0).floor() / 100.0;
    let x = |d: usize| LEFT + (RIGHT - LEFT) * d as f64 / MAX_NM as f64;
    let y = |v: f64| CHART_BOTTOM - (CHART_BOTTOM - CHART_TOP) * (v - y_min) / (y_max - y_min);

    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" font-family="DejaVu Sans, sans-serif" font-size="13">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{LEFT}" y="22" font-size="15">{title}</text>"#
    );
    for (row, (label, colours)) in [("spectral", &truth), ("glTF form", &form)]
        .into_iter()
        .enumerate()
    {
        let top = 40.0 + 50.0 * row as f64;
        let _ = writeln!(
            s,
            r#"<text x="{:.0}" y="{:.0}" text-anchor="end">{label}</text>"#,
            LEFT - 6.0,
            top + 25.0
        );
        // One gradient stop every 2 nm: smooth in every SVG renderer.
        let _ = writeln!(s, r#"<linearGradient id="strip{row}">"#);
        for (d, c) in colours.iter().enumerate().step_by(2) {
            let c = *c * exposure;
            let _ = writeln!(
                s,
                r#"<stop offset="{:.3}" stop-color="rgb({},{},{})"/>"#,
                d as f64 / MAX_NM as f64,
                srgb8(c.x),
                srgb8(c.y),
                srgb8(c.z)
            );
        }
        let _ = writeln!(s, "</linearGradient>");
        let _ = writeln!(
            s,
            r#"<rect x="{LEFT}" y="{top}" width="{:.0}" height="40" fill="url(#strip{row})"/>"#,
            RIGHT - LEFT
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{RIGHT}" y="150" text-anchor="end" font-size="11">strips exposed ×{exposure:.2}, sRGB-encoded</text>"#
    );
    // Axes, ticks and labels.
    let _ = writeln!(
        s,
        r#"<path d="M{LEFT} {CHART_TOP} V{CHART_BOTTOM} H{RIGHT}" fill="none" stroke="black"/>"#
    );
    let _ = writeln!(
        s,
        r##"<line x1="{LEFT}" y1="{0:.1}" x2="{RIGHT}" y2="{0:.1}" stroke="#999" stroke-width="0.5"/>"##,
        y(0.0)
    );
    for d in (0..=MAX_NM).step_by(100) {
        let _ = writeln!(
            s,
            r#"<line x1="{0:.1}" y1="{CHART_BOTTOM}" x2="{0:.1}" y2="{1}" stroke="black"/><text x="{0:.1}" y="{2}" text-anchor="middle">{d}</text>"#,
            x(d),
            CHART_BOTTOM + 5.0,
            CHART_BOTTOM + 20.0
        );
    }
    let (first, last) = (
        (y_min * 100.0).round() as i64,
        (y_max * 100.0).round() as i64,
    );
    let every = ((last - first) as usize).div_ceil(8).max(1);
    for k in (first..=last).step_by(every) {
        let v = 0.01 * k as f64;
        let _ = writeln!(
            s,
            r#"<line x1="{0}" y1="{1:.1}" x2="{LEFT}" y2="{1:.1}" stroke="black"/><text x="{2}" y="{3:.1}" text-anchor="end">{v:.2}</text>"#,
            LEFT - 5.0,
            y(v),
            LEFT - 8.0,
            y(v) + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.0}" y="592" text-anchor="middle">film thickness d [nm]</text>"#,
        0.5 * (LEFT + RIGHT)
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(22 {:.0}) rotate(-90)" text-anchor="middle">reflectance (linear Rec.709)</text>"#,
        0.5 * (CHART_TOP + CHART_BOTTOM)
    );
    // Curves: truth solid, form dashed, one colour per channel.
    let strokes = ["#d62728", "#2ca02c", "#1f77b4"];
    for (colours, dash) in [(&truth, ""), (&form, r#" stroke-dasharray="6 4""#)] {
        for (ch, stroke) in strokes.iter().enumerate() {
            let points: Vec<String> = colours
                .iter()
                .enumerate()
                .map(|(d, c)| format!("{:.1},{:.1}", x(d), y(c[ch])))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{stroke}" stroke-width="1.3"{dash}/>"#,
                points.join(" ")
            );
        }
    }
    let _ = writeln!(
        s,
        r#"<text x="{RIGHT}" y="{:.0}" text-anchor="end" font-size="12">solid: spectral (Airy, CIE 1931, D65) · dashed: glTF form (Belcour &amp; Barla 2017)</text>"#,
        CHART_TOP - 6.0
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::super::thin_film::FILM_CASES;
    use super::*;

    /// `docs/spectral-film.svg` is the current picture of the glTF default
    /// film (1.3 on 1.5) at normal incidence; `GONIO_UPDATE_SPECTRAL_PLOT=1`
    /// writes it. Also: the SVG holds both strips and six curves.
    #[test]
    fn film_plot_is_current() {
        let svg = film_svg(
            FILM_CASES[0],
            1.0,
            "Thin film 1.3 on 1.5 at normal incidence: colour against thickness",
        );
        assert_eq!(svg.matches("<polyline").count(), 6);
        assert_eq!(svg.matches("<stop ").count(), 2 * (MAX_NM / 2 + 1));
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/spectral-film.svg");
        if std::env::var_os("GONIO_UPDATE_SPECTRAL_PLOT").is_some() {
            std::fs::write(path, &svg).unwrap();
        }
        let stored = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            stored == svg,
            "{path} is not the current plot: run with GONIO_UPDATE_SPECTRAL_PLOT=1"
        );
    }
}
