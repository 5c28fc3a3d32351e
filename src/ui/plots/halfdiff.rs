//! The θ_h × θ_d image slice in the panel: f_r over Rusinkiewicz's
//! half/difference angles (EGWR 1998), as BRDF Explorer's "Image Slice"
//! shows it and `gonio brdf --plot-halfdiff` draws it, from the same f64
//! evaluation (`crate::explore::halfdiff`): θ_h to the right and θ_d up,
//! 0 to 90° each in 1° cells (MERL's θ_d resolution), φ_h = 0 and the
//! panel's φ_d (BRDF Explorer's default 90°).
//!
//! The colour is viridis over the panel's scale, linear (0 to a round
//! value at or above the largest value) or logarithmic (its decades below
//! the power of ten at or above it), one scale for every compared
//! material, whose images stand side by side. The values (RGB, 8100
//! evaluations per material; a measured network takes longer) come from
//! a worker thread ([`super::worker`]); channel and scale only recolour
//! them, and the texture is uploaded only when its colours change.
//!
//! Hovering an image reads f_r of every material at the pointer's exact
//! angles (not the cell's centre); `--edit plots.probe=TH,TD` pins that
//! point, and a scripted run prints the readout on stdout once every image
//! is current (`tests/viewer.rs` compares it with the f64 function).

use super::radius::Radius;
use super::{Series, Settings, colour};
use crate::explore::halfdiff::{CELLS, f_r_at, half_diff_rgb};
use crate::explore::halfdiff_plot::{NO_DATA, viridis};
use crate::explore::{Channel, MaterialPart};
use crate::scene::Rgb;
use std::sync::atomic::{AtomicU64, Ordering};

/// One material's image: f_r (RGB) at the centre of every cell for one φ_d.
pub struct Image {
    /// Distinct per computed image, so a texture knows what it shows.
    pub id: u64,
    /// `rgb[j][i]`: cell i along θ_h, row j along θ_d.
    pub rgb: Vec<Vec<Rgb>>,
}

/// The image of `m` at difference azimuth `phi_d_deg`.
pub fn image<'a>(m: impl Into<MaterialPart<'a>>, phi_d_deg: f64) -> Image {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    Image {
        id: NEXT.fetch_add(1, Ordering::Relaxed),
        rgb: half_diff_rgb(m, phi_d_deg.to_radians()),
    }
}

impl Image {
    /// The channel's value of cell `i` (θ_h), row `j` (θ_d).
    pub fn value(&self, channel: Channel, i: usize, j: usize) -> f64 {
        channel.of(self.rgb[j][i])
    }
}

/// The colour scale of all shown images: the panel's radius scale
/// ([`Radius`]: linear or log over its decades) for their largest finite
/// value; its rings label the colour bar.
pub fn scale(s: &Settings, images: &[&Image]) -> Radius {
    let peak = images
        .iter()
        .flat_map(|img| img.rgb.iter().flatten().map(|c| s.channel.of(*c)))
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    Radius::new(peak, s.log, s.decades)
}

/// Where `v` sits on the scale, 0 to 1 (clipped), or `None` (drawn as
/// [`NO_DATA`], as `gonio brdf` does): not finite, or ≤ 0 on a log scale.
pub fn level(radius: &Radius, v: f64) -> Option<f64> {
    if !v.is_finite() || (matches!(radius, Radius::Log { .. }) && v <= 0.0) {
        return None;
    }
    Some((radius.map(v) / radius.outer()).clamp(0.0, 1.0))
}

/// The colour of `v` on the scale.
pub fn colour_of(radius: &Radius, v: f64) -> egui::Color32 {
    let c = level(radius, v).map(viridis).unwrap_or(NO_DATA);
    egui::Color32::from_rgb(c.0, c.1, c.2)
}

/// The texture: [`CELLS`] × [`CELLS`] pixels, one per cell, θ_h to the
/// right and θ_d up (pixel row 0 is θ_d's last row).
pub fn pixels(img: &Image, channel: Channel, radius: &Radius) -> egui::ColorImage {
    let mut px = Vec::with_capacity(CELLS * CELLS);
    for y in 0..CELLS {
        let j = CELLS - 1 - y;
        px.extend((0..CELLS).map(|i| colour_of(radius, img.value(channel, i, j))));
    }
    egui::ColorImage::new([CELLS, CELLS], px)
}

/// The angles (θ_h, θ_d) in degrees at `pos` in an image drawn in `rect`.
pub fn angles_at(rect: egui::Rect, pos: egui::Pos2) -> (f64, f64) {
    let u = ((pos.x - rect.min.x) / rect.width()).clamp(0.0, 1.0) as f64;
    let v = ((rect.max.y - pos.y) / rect.height()).clamp(0.0, 1.0) as f64;
    (90.0 * u, 90.0 * v)
}

/// The point of `rect` at θ_h, θ_d (degrees): [`angles_at`]'s inverse.
pub fn position_of(rect: egui::Rect, theta_h_deg: f64, theta_d_deg: f64) -> egui::Pos2 {
    egui::pos2(
        rect.min.x + (theta_h_deg / 90.0) as f32 * rect.width(),
        rect.max.y - (theta_d_deg / 90.0) as f32 * rect.height(),
    )
}

/// The cell holding angle `deg` (degrees, 90° in the last cell).
pub fn cell_of(deg: f64) -> usize {
    ((deg / 90.0 * CELLS as f64) as usize).min(CELLS - 1)
}

type TextureKey = (u64, Channel, Radius);

/// The view's state: each series' texture and the pinned readout point.
#[derive(Default)]
pub struct View {
    textures: Vec<Option<(TextureKey, egui::TextureHandle)>>,
    /// (θ_h, θ_d) in degrees read out when the pointer is not on an image.
    pub probe: Option<(f64, f64)>,
    /// The last probe report printed (printed again only when it changes).
    printed: String,
}

/// Space left of the images (θ_d ticks), right of them (colour bar and
/// its labels), between them, above each (its name) and below (θ_h ticks
/// and label), in points.
const LEFT: f32 = 30.0;
const BAR: f32 = 70.0;
const GAP: f32 = 10.0;
const ABOVE: f32 = 16.0;
const BELOW: f32 = 30.0;

const FRAME: egui::Color32 = egui::Color32::from_gray(120);
const LABEL: egui::Color32 = egui::Color32::from_gray(170);

/// Draws the images of `series` (up to three side by side, then another
/// row), the colour bar and the readout.
pub fn show(
    ui: &mut egui::Ui,
    s: &Settings,
    view: &mut View,
    series: &[Series],
    images: &[Option<(&Image, bool)>],
) {
    let stale = images.iter().any(|m| !matches!(m, Some((_, true))));
    let shown: Vec<&Image> = images.iter().flatten().map(|(img, _)| *img).collect();
    let radius = scale(s, &shown);
    let scale_name = match radius {
        Radius::Linear { .. } => "linear".to_string(),
        Radius::Log { decades, .. } => format!("log, {decades} decades"),
    };
    ui.label(format!(
        "θ_h × θ_d image (Rusinkiewicz 1998) at φ_d = {:.0}°, φ_h = 0: f_r [1/sr], {}, {scale_name}{}",
        s.phi_d_deg,
        s.channel.describe(),
        if stale { " (updating…)" } else { "" }
    ));
    let n = series.len().max(1);
    let width = ui.available_width() - 8.0;
    let (cols, rows, side) = grid(width, n);
    let (rect, response) = ui.allocate_exact_size(
        egui::vec2(width, rows as f32 * (ABOVE + side + BELOW)),
        egui::Sense::hover(),
    );
    let painter = ui.painter_at(rect);
    let rects = image_rects(rect.min, width, n);
    view.textures.resize_with(n, || None);
    for (k, r) in rects.iter().enumerate() {
        let name = series.get(k).map(|one| one.label.as_str()).unwrap_or("");
        let room = (side / 6.5) as usize;
        let name: String = if name.chars().count() > room {
            name.chars()
                .take(room.saturating_sub(1))
                .chain(['…'])
                .collect()
        } else {
            name.to_string()
        };
        painter.text(
            r.center_top() - egui::vec2(0.0, 2.0),
            egui::Align2::CENTER_BOTTOM,
            name,
            egui::FontId::proportional(11.0),
            colour(k),
        );
        match images.get(k).copied().flatten() {
            Some((img, _)) => {
                let key = (img.id, s.channel, radius);
                let texture = &mut view.textures[k];
                if texture.as_ref().map(|(have, _)| have) != Some(&key) {
                    let px = pixels(img, s.channel, &radius);
                    let handle = ui.ctx().load_texture(
                        format!("halfdiff {k}"),
                        px,
                        egui::TextureOptions::NEAREST,
                    );
                    *texture = Some((key, handle));
                }
                let (_, handle) = texture.as_ref().expect("set above");
                let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
                painter.image(handle.id(), *r, uv, egui::Color32::WHITE);
            }
            None => {
                painter.rect_filled(*r, 0.0, egui::Color32::from_gray(30));
            }
        }
        painter.rect_stroke(*r, 0.0, (1.0, FRAME), egui::StrokeKind::Outside);
        axes(&painter, *r, k % cols == 0);
    }
    colour_bar(&painter, &radius, &rects, cols);

    let hovered = response.hover_pos().and_then(|p| {
        rects
            .iter()
            .find(|r| r.contains(p))
            .map(|r| angles_at(*r, p))
    });
    let Some((th, td)) = hovered.or(view.probe) else {
        ui.weak("Hover an image: f_r of every material at that θ_h, θ_d.");
        return;
    };
    for r in &rects {
        let p = position_of(*r, th, td);
        let stroke = (1.0, egui::Color32::from_rgb(255, 80, 80));
        painter.circle_stroke(p, 4.0, stroke);
    }
    let pd = s.phi_d_deg;
    ui.label(format!(
        "at θ_h = {th:.1}°, θ_d = {td:.1}°, φ_d = {pd:.0}°:"
    ));
    let mut report = String::new();
    for (k, one) in series.iter().enumerate() {
        let f = f_r_at(
            one.part(),
            th.to_radians(),
            td.to_radians(),
            pd.to_radians(),
        );
        ui.label(
            egui::RichText::new(format!("f_r = {:.4e}  {}", s.channel.of(f), one.label))
                .color(colour(k)),
        );
        if let Some(Some((img, true))) = images.get(k) {
            let (i, j) = (cell_of(th), cell_of(td));
            let c = img.rgb[j][i];
            report += &format!(
                "halfdiff probe {k}: theta_h={th:?} theta_d={td:?} phi_d={pd:?} f_r=[{:?}, {:?}, {:?}] cell=({i}, {j}) cell_f_r=[{:?}, {:?}, {:?}]\n",
                f.x, f.y, f.z, c.x, c.y, c.z
            );
        }
    }
    // Printed for a pinned probe once every image is current: a scripted
    // run's check that the image and its readout are f_r where they say.
    if hovered.is_none() && !stale && report != view.printed {
        print!("{report}");
        view.printed = report;
    }
}

/// Columns, rows and the side of each image for `n` images in a `width`
/// points wide area: up to three side by side, then another row.
pub fn grid(width: f32, n: usize) -> (usize, usize, f32) {
    let n = n.max(1);
    let cols = n.min(3);
    let rows = n.div_ceil(cols);
    let side = ((width - LEFT - BAR - GAP * (cols - 1) as f32) / cols as f32).clamp(40.0, 420.0);
    (cols, rows, side)
}

/// The squares of `n` images laid out by [`grid`] in an area of `width`
/// points whose top left is `origin`.
pub fn image_rects(origin: egui::Pos2, width: f32, n: usize) -> Vec<egui::Rect> {
    let (cols, _, side) = grid(width, n);
    (0..n.max(1))
        .map(|k| {
            let (r, c) = ((k / cols) as f32, (k % cols) as f32);
            egui::Rect::from_min_size(
                origin + egui::vec2(LEFT + c * (side + GAP), r * (ABOVE + side + BELOW) + ABOVE),
                egui::vec2(side, side),
            )
        })
        .collect()
}

/// Font size of the axes' labels, in points.
pub const AXIS_FONT: f32 = 10.0;

/// The side below which an image's inner ticks (30°, 60°) go unlabelled:
/// two-digit labels (about 2 × 0.6 em = 12 points wide and 1.2 em high)
/// a third of the side apart need a third of the side to hold one and a
/// half labels and a space (18 + 3 points). At the narrowest panel three
/// images are 51 points wide, and the labels "60" and "90" touched.
pub const INNER_LABELS_FROM: f32 = 63.0;

/// One label of an image's axes: where it is anchored, how, and its text.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisLabel {
    pub at: egui::Pos2,
    pub align: egui::Align2,
    pub text: String,
}

/// The labels of the image at `r`: θ_h's ticks and title under it, θ_d's
/// left of it when `left_labels` (the first column). The end labels stay
/// within their image's extent, so that one image's 90 and the next one's
/// 0 do not read as "900", and the top 90 stays under the θ_d
/// title; the corner's 0 is the θ_h axis' only.
pub fn axis_labels(r: egui::Rect, left_labels: bool) -> Vec<AxisLabel> {
    let inner = r.width() >= INNER_LABELS_FROM;
    let mut labels = Vec::new();
    for deg in [0.0, 30.0, 60.0, 90.0] {
        let end = deg == 0.0 || deg == 90.0;
        if !end && !inner {
            continue;
        }
        let x = position_of(r, deg, 0.0).x;
        let align = if deg == 0.0 {
            egui::Align2::LEFT_TOP
        } else if deg == 90.0 {
            egui::Align2::RIGHT_TOP
        } else {
            egui::Align2::CENTER_TOP
        };
        labels.push(AxisLabel {
            at: egui::pos2(x, r.max.y + 4.0),
            align,
            text: format!("{deg:.0}"),
        });
        if left_labels && deg > 0.0 {
            let y = position_of(r, 0.0, deg).y;
            labels.push(AxisLabel {
                at: egui::pos2(r.min.x - 6.0, y),
                align: if deg == 90.0 {
                    egui::Align2::RIGHT_TOP
                } else {
                    egui::Align2::RIGHT_CENTER
                },
                text: format!("{deg:.0}"),
            });
        }
    }
    labels.push(AxisLabel {
        at: egui::pos2(r.center().x, r.max.y + 16.0),
        align: egui::Align2::CENTER_TOP,
        text: "θ_h (°)".into(),
    });
    if left_labels {
        labels.push(AxisLabel {
            at: egui::pos2(r.min.x - LEFT, r.min.y - 2.0),
            align: egui::Align2::LEFT_BOTTOM,
            text: "θ_d (°)".into(),
        });
    }
    labels
}

/// Ticks every 30° and the [`axis_labels`] of the image at `r`.
fn axes(painter: &egui::Painter, r: egui::Rect, left_labels: bool) {
    let font = egui::FontId::proportional(AXIS_FONT);
    let stroke = (1.0, FRAME);
    for deg in [0.0, 30.0, 60.0, 90.0] {
        let x = position_of(r, deg, 0.0).x;
        painter.line_segment(
            [egui::pos2(x, r.max.y), egui::pos2(x, r.max.y + 4.0)],
            stroke,
        );
        if left_labels && deg > 0.0 {
            let y = position_of(r, 0.0, deg).y;
            painter.line_segment(
                [egui::pos2(r.min.x - 4.0, y), egui::pos2(r.min.x, y)],
                stroke,
            );
        }
    }
    for label in axis_labels(r, left_labels) {
        painter.text(label.at, label.align, label.text, font.clone(), LABEL);
    }
}

/// The colour bar right of the first row's last image, labelled at the
/// scale's rings (round values, or every power of ten).
fn colour_bar(painter: &egui::Painter, radius: &Radius, rects: &[egui::Rect], cols: usize) {
    let Some(last) = rects.get(cols - 1) else {
        return;
    };
    let bar = egui::Rect::from_min_size(
        egui::pos2(last.max.x + 12.0, last.min.y),
        egui::vec2(12.0, last.height()),
    );
    const STEPS: usize = 64;
    let h = bar.height() / STEPS as f32;
    for k in 0..STEPS {
        let t = (k as f64 + 0.5) / STEPS as f64;
        let c = viridis(t);
        let y = bar.max.y - (k + 1) as f32 * h;
        painter.rect_filled(
            egui::Rect::from_min_size(egui::pos2(bar.min.x, y), egui::vec2(bar.width(), h + 0.5)),
            0.0,
            egui::Color32::from_rgb(c.0, c.1, c.2),
        );
    }
    painter.rect_stroke(bar, 0.0, (1.0, FRAME), egui::StrokeKind::Outside);
    let bottom = match radius {
        Radius::Linear { .. } => "0".to_string(),
        Radius::Log { top, decades } => {
            format!("1e{}", top.log10().round() as i32 - *decades as i32)
        }
    };
    let rings = std::iter::once((0.0, bottom)).chain(radius.rings());
    for (at, text) in rings {
        let y = bar.max.y - (at / radius.outer()) as f32 * bar.height();
        painter.line_segment(
            [egui::pos2(bar.max.x, y), egui::pos2(bar.max.x + 3.0, y)],
            (1.0, FRAME),
        );
        painter.text(
            egui::pos2(bar.max.x + 5.0, y),
            egui::Align2::LEFT_CENTER,
            text,
            egui::FontId::proportional(10.0),
            LABEL,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::explore::halfdiff::{cell_centre, directions};
    use crate::explore::spec::compare_spec;
    use crate::explore::{frame, halfdiff};
    use crate::material::Material;

    fn material(spec: &str) -> Material {
        compare_spec(spec, &[]).unwrap().material
    }

    /// The texture's pixel at cell (i, j) is the colour of f_r at the
    /// directions Rusinkiewicz's parameterization gives for that cell's
    /// centre (explore::halfdiff::directions), at a φ_d other than 90°;
    /// at φ_d = 90° the values are `gonio brdf --plot-halfdiff`'s.
    #[test]
    fn a_pixel_is_f_r_at_its_half_and_difference_angles() {
        let m = material("ward,k_d=0.2,k_s=0.3,sigma_x=0.1,sigma_y=0.3");
        let img = image(&m, 60.0);
        let s = Settings {
            log: true,
            channel: Channel::G,
            ..Settings::default()
        };
        let radius = scale(&s, &[&img]);
        let px = pixels(&img, s.channel, &radius);
        for (i, j) in [(0, 0), (3, 70), (45, 45), (89, 10), (60, 89)] {
            let (wi, wo) = directions(cell_centre(i), cell_centre(j), 60f64.to_radians());
            let want = Channel::G.of(m.f_r(wi, wo, &frame()));
            assert_eq!(img.value(Channel::G, i, j), want, "cell {i},{j}");
            let pixel = px.pixels[(CELLS - 1 - j) * CELLS + i];
            assert_eq!(pixel, colour_of(&radius, want), "cell {i},{j}");
        }
        let cli = halfdiff::half_diff_image(&m, Channel::Mean);
        let at_90 = image(&m, 90.0);
        for (i, j) in [(0, 0), (20, 50), (89, 89)] {
            assert_eq!(at_90.value(Channel::Mean, i, j), cli.values[j][i]);
        }
    }

    /// Pointer position and angles are inverse; 90° lands in the last cell.
    #[test]
    fn positions_and_angles_agree() {
        let r = egui::Rect::from_min_size(egui::pos2(10.0, 20.0), egui::vec2(180.0, 180.0));
        for (th, td) in [(0.0, 0.0), (20.0, 40.0), (90.0, 90.0), (33.5, 81.25)] {
            let (a, b) = angles_at(r, position_of(r, th, td));
            assert!((a - th).abs() < 1e-4 && (b - td).abs() < 1e-4, "{a},{b}");
        }
        assert_eq!(angles_at(r, r.left_bottom()), (0.0, 0.0));
        assert_eq!(
            (cell_of(0.0), cell_of(20.5), cell_of(90.0)),
            (0, 20, CELLS - 1)
        );
    }

    /// Linear: 0 at the bottom, the round outer value at the top; log:
    /// decades below the top, non-positive values as no data.
    #[test]
    fn levels_follow_the_scale() {
        let lin = Radius::new(0.37, false, 6);
        assert_eq!(level(&lin, 0.0), Some(0.0));
        assert!((level(&lin, 0.2).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(level(&lin, 9.0), Some(1.0));
        assert_eq!(level(&lin, f64::NAN), None);
        let log = Radius::new(3.0e5, true, 6);
        assert!((level(&log, 1e3).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(level(&log, 0.0), None);
        assert_eq!(level(&log, 1e-9), Some(0.0));
    }
}
