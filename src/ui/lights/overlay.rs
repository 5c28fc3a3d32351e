//! The lights drawn over the 3D view: a point light as a
//! marker, a spot as its cones, a directional light as an arrow along the
//! way its light travels, an area light as its outline and normal. Drawn
//! with egui's painter, projected with the camera the scene is drawn with
//! ([`ScreenProjection`]), on top of the scene (no depth test: a light
//! behind an object stays visible and grabbable).
//!
//! Each `[[lights]]` entry has one handle, the filled marker, which the
//! mouse drags (`super::drag`); lights from a glTF file and the
//! default light are drawn grey and have none (the scene file cannot
//! address them). `L` or the Lights section's check box shows and hides
//! the overlay; it is part of the overlay, so `--no-overlay` hides it too.

use super::kinds::directional_reach;
use super::projection::ScreenProjection;
use crate::scene::scene_file::LightEntry;
use crate::scene::{Camera, Light};
use crate::ui::document::Document;
use egui::{Color32, Pos2, Stroke};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// Radius of a handle's marker, in points.
pub const HANDLE_RADIUS: f32 = 6.0;
/// Edges of the circles drawn for cones and disks.
const CIRCLE_EDGES: usize = 48;

/// What is drawn for one light, in world space.
#[derive(Clone, Debug, PartialEq)]
pub enum Glyph {
    Point {
        position: DVec3,
    },
    Spot {
        position: DVec3,
        axis: DVec3,
        inner_deg: f64,
        outer_deg: f64,
    },
    Directional {
        axis: DVec3,
    },
    Area {
        position: DVec3,
        normal: DVec3,
        outline: Vec<DVec3>,
    },
}

impl Glyph {
    /// The glyph of a `[[lights]]` entry as written (it may not be valid
    /// yet: degenerate vectors fall back to something drawable).
    pub fn of_entry(entry: &LightEntry) -> Glyph {
        let unit = |v: [f64; 3]| DVec3::from_array(v).normalize_or(DVec3::NEG_Y);
        let at = DVec3::from_array;
        match entry {
            LightEntry::Point(e) => Glyph::Point {
                position: at(e.position),
            },
            LightEntry::Spot(e) => Glyph::Spot {
                position: at(e.position),
                axis: unit(e.direction),
                inner_deg: e.inner_cone_deg.unwrap_or(0.0),
                outer_deg: e.outer_cone_deg.unwrap_or(45.0),
            },
            LightEntry::Directional(e) => Glyph::Directional {
                axis: unit(e.direction),
            },
            LightEntry::Area(e) => {
                let position = at(e.position);
                let normal = unit(e.normal);
                let tangent = e
                    .tangent
                    .map(|t| DVec3::from_array(t).reject_from_normalized(normal))
                    .and_then(DVec3::try_normalize)
                    .unwrap_or_else(|| crate::base::any_tangent(normal));
                let bitangent = normal.cross(tangent);
                let outline = match (e.shape.as_str(), e.size, e.radius) {
                    ("disk", _, Some(r)) => (0..CIRCLE_EDGES)
                        .map(|k| {
                            let a = TAU * k as f64 / CIRCLE_EDGES as f64;
                            position + (tangent * a.cos() + bitangent * a.sin()) * r
                        })
                        .collect(),
                    (_, Some([w, h]), _) => [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                        .iter()
                        .map(|&(x, y)| {
                            position + tangent * (0.5 * w * x) + bitangent * (0.5 * h * y)
                        })
                        .collect(),
                    _ => Vec::new(),
                };
                Glyph::Area {
                    position,
                    normal,
                    outline,
                }
            }
        }
    }

    /// The glyph of a light the scene file does not hold (imported, or the
    /// default light); an area light's sample has none (its entry has).
    pub fn of_light(light: &Light) -> Option<Glyph> {
        Some(match *light {
            Light::Point { position, .. } => Glyph::Point { position },
            Light::Spot {
                position,
                direction,
                inner_cone_deg,
                outer_cone_deg,
                ..
            } => Glyph::Spot {
                position,
                axis: direction,
                inner_deg: inner_cone_deg,
                outer_deg: outer_cone_deg,
            },
            Light::Directional { direction, .. } => Glyph::Directional { axis: direction },
            Light::AreaSample { .. } => return None,
        })
    }

    /// Where the handle is: the light's position; a directional light's
    /// up-light of the target ([`directional_reach`]).
    pub fn handle(&self, eye: DVec3, target: DVec3) -> DVec3 {
        match self {
            Glyph::Point { position }
            | Glyph::Spot { position, .. }
            | Glyph::Area { position, .. } => *position,
            Glyph::Directional { axis } => target - *axis * directional_reach(eye, target),
        }
    }
}

/// The handle of every `[[lights]]` entry, by index.
pub fn handles(doc: &Document, camera: &Camera) -> Vec<DVec3> {
    doc.lights
        .entries
        .iter()
        .map(|e| Glyph::of_entry(e).handle(camera.position, camera.target))
        .collect()
}

/// Draws every light over `area` (egui points) as `camera` sees it;
/// `active` is the handle being dragged, `pointer` the mouse.
pub fn draw(
    painter: &egui::Painter,
    doc: &Document,
    camera: &Camera,
    area: egui::Rect,
    active: Option<usize>,
    pointer: Option<Pos2>,
) {
    let painter = painter.with_clip_rect(area);
    let proj = ScreenProjection::new(
        camera,
        DVec2::new(area.min.x as f64, area.min.y as f64),
        DVec2::new(area.width() as f64, area.height() as f64),
    );
    let pen = Pen {
        painter: &painter,
        proj: &proj,
        camera,
    };
    let others = doc.lights.imported.iter().cloned().chain(
        doc.lights
            .gets_default_light()
            .then(crate::scene::scene_file::default_light),
    );
    for light in others {
        if let Some(glyph) = Glyph::of_light(&light) {
            pen.glyph(&glyph, Color32::from_gray(150), None, false);
        }
    }
    for (i, entry) in doc.lights.entries.iter().enumerate() {
        let glyph = Glyph::of_entry(entry);
        let handle = proj.project(glyph.handle(camera.position, camera.target));
        let near = |p: Pos2| {
            handle.is_some_and(|h| {
                (DVec2::new(p.x as f64, p.y as f64) - h).length() <= 2.0 * HANDLE_RADIUS as f64
            })
        };
        let hot = active == Some(i) || (active.is_none() && pointer.is_some_and(near));
        let label = format!("{i} {}", entry.kind());
        pen.glyph(&glyph, colour_of(entry), Some(&label), hot);
    }
}

/// The light's colour at full brightness, for its glyph.
fn colour_of(entry: &LightEntry) -> Color32 {
    let power = match entry {
        LightEntry::Point(e) => e.intensity,
        LightEntry::Spot(e) => e.intensity,
        LightEntry::Directional(e) => e.irradiance,
        LightEntry::Area(e) => e.radiance,
    }
    .rgb();
    let peak = power.max_element();
    if !(peak.is_finite() && peak > 0.0) {
        return Color32::from_gray(110);
    }
    let c = (power / peak).to_array().map(|v| {
        // Lifted towards white so that a deep colour stays visible on a
        // dark scene.
        let v = 0.35 + 0.65 * v.clamp(0.0, 1.0);
        (crate::output::srgb8::srgb_encode(v) * 255.0).round() as u8
    });
    Color32::from_rgb(c[0], c[1], c[2])
}

/// Draws glyphs with one projection.
struct Pen<'a> {
    painter: &'a egui::Painter,
    proj: &'a ScreenProjection,
    camera: &'a Camera,
}

impl Pen<'_> {
    fn line(&self, a: DVec3, b: DVec3, stroke: Stroke) {
        if let Some((a, b)) = self.proj.project_segment(a, b) {
            self.painter.line_segment([pos(a), pos(b)], stroke);
        }
    }

    fn polygon(&self, points: &[DVec3], stroke: Stroke) {
        for (k, &a) in points.iter().enumerate() {
            self.line(a, points[(k + 1) % points.len()], stroke);
        }
    }

    /// A line with an arrowhead at `b` drawn in screen space.
    fn arrow(&self, a: DVec3, b: DVec3, stroke: Stroke) {
        let Some((sa, sb)) = self.proj.project_segment(a, b) else {
            return;
        };
        self.painter.line_segment([pos(sa), pos(sb)], stroke);
        let Some(back) = (sa - sb).try_normalize() else {
            return;
        };
        for turn in [0.45f64, -0.45] {
            let (s, c) = turn.sin_cos();
            let side = DVec2::new(back.x * c - back.y * s, back.x * s + back.y * c);
            self.painter
                .line_segment([pos(sb), pos(sb + side * 9.0)], stroke);
        }
    }

    /// A circle of `radius` about `centre` across `axis`.
    fn circle(&self, centre: DVec3, axis: DVec3, radius: f64, stroke: Stroke) {
        let t = crate::base::any_tangent(axis);
        let b = axis.cross(t);
        let points: Vec<DVec3> = (0..CIRCLE_EDGES)
            .map(|k| {
                let a = TAU * k as f64 / CIRCLE_EDGES as f64;
                centre + (t * a.cos() + b * a.sin()) * radius
            })
            .collect();
        self.polygon(&points, stroke);
    }

    fn glyph(&self, glyph: &Glyph, colour: Color32, label: Option<&str>, hot: bool) {
        let (eye, target) = (self.camera.position, self.camera.target);
        let reach = directional_reach(eye, target);
        let width = if hot { 2.5 } else { 1.5 };
        let stroke = Stroke::new(width, colour);
        let thin = Stroke::new(1.0, colour.gamma_multiply(0.7));
        match glyph {
            Glyph::Point { .. } => {}
            Glyph::Spot {
                position,
                axis,
                inner_deg,
                outer_deg,
            } => {
                // The cones reach the target's distance along the axis.
                let length = (target - *position).dot(*axis).max(0.25 * reach);
                let end = *position + *axis * length;
                self.line(*position, end, thin);
                let outer = length * outer_deg.to_radians().tan().min(10.0);
                let inner = length * inner_deg.to_radians().tan().min(10.0);
                self.circle(end, *axis, outer, stroke);
                if *inner_deg > 0.0 {
                    self.circle(end, *axis, inner, thin);
                }
                let t = crate::base::any_tangent(*axis);
                let b = axis.cross(t);
                for side in [t, -t, b, -b] {
                    self.line(*position, end + side * outer, stroke);
                }
            }
            Glyph::Directional { axis } => {
                let from = glyph.handle(eye, target);
                self.arrow(from, from + *axis * (0.6 * reach), stroke);
                // Two more shafts beside it: parallel light.
                let side = crate::base::any_tangent(*axis) * (0.12 * reach);
                for offset in [side, -side] {
                    self.arrow(from + offset, from + offset + *axis * (0.45 * reach), thin);
                }
            }
            Glyph::Area {
                position,
                normal,
                outline,
            } => {
                self.polygon(outline, stroke);
                if outline.len() == 4 {
                    self.line(outline[0], outline[2], thin);
                    self.line(outline[1], outline[3], thin);
                }
                self.arrow(*position, *position + *normal * (0.3 * reach), stroke);
            }
        }
        let Some(h) = self.proj.project(glyph.handle(eye, target)) else {
            return;
        };
        let radius = if hot {
            HANDLE_RADIUS + 2.0
        } else {
            HANDLE_RADIUS
        };
        let outline = Stroke::new(1.5, Color32::from_black_alpha(200));
        if label.is_some() {
            self.painter.circle(pos(h), radius, colour, outline);
        } else {
            // No handle: a ring only.
            self.painter.circle_stroke(pos(h), radius - 1.0, stroke);
        }
        if let Some(label) = label {
            let at = pos(h) + egui::vec2(radius + 3.0, -radius - 2.0);
            let font = egui::FontId::proportional(12.0);
            self.painter.text(
                at + egui::vec2(1.0, 1.0),
                egui::Align2::LEFT_BOTTOM,
                label,
                font.clone(),
                Color32::from_black_alpha(220),
            );
            self.painter
                .text(at, egui::Align2::LEFT_BOTTOM, label, font, colour);
        }
    }
}

fn pos(p: DVec2) -> Pos2 {
    Pos2::new(p.x as f32, p.y as f32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::limits::Limits;
    use crate::scene::scene_file::SceneSource;

    #[test]
    fn glyphs_follow_the_entries() {
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("lights.add=area").unwrap();
        doc.edit("lights.1.size=[2.0, 1.0]").unwrap();
        let Glyph::Area {
            position,
            normal,
            outline,
        } = Glyph::of_entry(&doc.lights.entries[1])
        else {
            panic!()
        };
        // The outline is the assembled light's: same corners.
        let assembled = doc.scene.area_lights[0].outline();
        assert_eq!(outline.len(), 4);
        for (a, b) in outline.iter().zip(&assembled) {
            assert!((*a - *b).length() < 1e-12, "{a} vs {b}");
        }
        assert_eq!(position, doc.scene.area_lights[0].position);
        assert!((normal - doc.scene.area_lights[0].normal).length() < 1e-12);
        doc.edit("lights.1.shape=\"disk\"")
            .expect_err("a disk needs a radius");
        // A directional light's handle is up-light of the target.
        doc.edit("lights.1.kind=directional").unwrap();
        let camera = doc.scene.camera;
        let h = handles(&doc, &camera)[1];
        let LightEntry::Directional(e) = &doc.lights.entries[1] else {
            panic!()
        };
        let to_target = (camera.target - h).normalize();
        assert!(to_target.dot(DVec3::from_array(e.direction).normalize()) > 1.0 - 1e-12);
    }
}
