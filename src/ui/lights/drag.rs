//! Dragging a light's handle in the 3D view: a press on
//! a handle ([`super::overlay`]) grabs it instead of orbiting; the
//! handle then follows the mouse in the screen plane at the depth it was
//! grabbed at (the plane through it facing the camera), so it stays under
//! the cursor. A point, spot or area light moves there (its direction is
//! kept). A directional light's handle sits on the sphere about the point
//! the camera looks at (radius [`directional_reach`]), so it moves on that
//! sphere, where the cursor's ray meets it (the side nearer the depth it
//! was grabbed at; the sphere's silhouette where the ray misses), and the
//! light turns to shine from the handle towards the centre.
//!
//! Each move goes through [`Document::set_light`], validated as the scene
//! file is; a position the file would refuse leaves the light where it was
//! and says why.

use super::kinds::directional_reach;
use super::overlay::{Glyph, handles};
use super::projection::ScreenProjection;
use crate::scene::Camera;
use crate::scene::scene_file::LightEntry;
use crate::ui::document::Document;
use glam::{DVec2, DVec3};

/// A handle being dragged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightDrag {
    /// The `[[lights]]` entry.
    pub index: usize,
    /// View depth of the plane the handle moves in.
    depth: f64,
    /// Cursor minus the handle's screen point when grabbed (the handle
    /// keeps its place under the cursor rather than jumping to it).
    grab: DVec2,
}

/// The handle under `cursor` (within the marker, with a margin for the
/// hand), the nearest if several.
pub fn pick(
    doc: &Document,
    camera: &Camera,
    proj: &ScreenProjection,
    cursor: DVec2,
    pick_radius: f64,
) -> Option<LightDrag> {
    handles(doc, camera)
        .into_iter()
        .enumerate()
        .filter_map(|(index, h)| {
            let s = proj.project(h)?;
            let off = cursor - s;
            (off.length() <= pick_radius).then_some((
                off.length(),
                LightDrag {
                    index,
                    depth: proj.depth(h),
                    grab: off,
                },
            ))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, d)| d)
}

impl LightDrag {
    /// Moves the grabbed light so that its handle is under `cursor`.
    pub fn drag_to(
        &self,
        doc: &mut Document,
        camera: &Camera,
        proj: &ScreenProjection,
        cursor: DVec2,
    ) -> Result<(), String> {
        let entry = doc
            .lights
            .entries
            .get(self.index)
            .ok_or_else(|| format!("there is no light {}", self.index))?;
        let at = cursor - self.grab;
        let handle = match entry {
            LightEntry::Directional(_) => self.on_sphere(camera, proj, at),
            _ => proj.unproject(at, self.depth),
        };
        let moved = moved(entry, handle, camera.target);
        doc.set_light(self.index, moved)
    }
}

impl LightDrag {
    /// Where the ray through screen point `at` meets the sphere of radius
    /// [`directional_reach`] about the target: of its two crossings the
    /// one whose depth is nearer the grabbed depth; where it misses, the
    /// sphere's point nearest the ray.
    fn on_sphere(&self, camera: &Camera, proj: &ScreenProjection, at: DVec2) -> DVec3 {
        let (eye, target) = (camera.position, camera.target);
        let radius = directional_reach(eye, target);
        let d = (proj.unproject(at, 1.0) - eye).normalize();
        let oc = eye - target;
        let b = oc.dot(d);
        let disc = b * b - (oc.length_squared() - radius * radius);
        if disc < 0.0 {
            let nearest = eye + d * (-b) - target;
            return target + nearest.normalize_or(d) * radius;
        }
        let roots = [-b - disc.sqrt(), -b + disc.sqrt()];
        let depth_of = |t: f64| proj.depth(eye + d * t);
        let t = roots
            .into_iter()
            .min_by(|p, q| {
                (depth_of(*p) - self.depth)
                    .abs()
                    .total_cmp(&(depth_of(*q) - self.depth).abs())
            })
            .expect("two roots");
        eye + d * t
    }
}

/// `entry` with its handle at `handle`.
fn moved(entry: &LightEntry, handle: DVec3, target: DVec3) -> LightEntry {
    let mut entry = entry.clone();
    let at = handle.to_array();
    match &mut entry {
        LightEntry::Point(e) => e.position = at,
        LightEntry::Spot(e) => e.position = at,
        LightEntry::Area(e) => e.position = at,
        LightEntry::Directional(e) => {
            // A handle dragged onto the target leaves the direction alone.
            if let Some(d) = (target - handle).try_normalize() {
                e.direction = d.to_array();
            }
        }
    }
    entry
}

/// The glyph's handle for entry `index`, on the screen.
pub fn handle_on_screen(
    doc: &Document,
    camera: &Camera,
    proj: &ScreenProjection,
    index: usize,
) -> Option<DVec2> {
    let entry = doc.lights.entries.get(index)?;
    proj.project(Glyph::of_entry(entry).handle(camera.position, camera.target))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::limits::Limits;
    use crate::scene::scene_file::SceneSource;

    fn setup() -> (Document, Camera, ScreenProjection) {
        let mut doc = Document::load(SceneSource::BuiltIn, vec![], Limits::default()).unwrap();
        doc.edit("lights.add=directional").unwrap();
        doc.edit("lights.add=spot").unwrap();
        let camera = doc.scene.camera;
        let proj = ScreenProjection::new(&camera, DVec2::new(0.0, 0.0), DVec2::new(640.0, 480.0));
        (doc, camera, proj)
    }

    #[test]
    fn a_dragged_light_stays_under_the_cursor_at_its_depth() {
        let (mut doc, camera, proj) = setup();
        for index in [0, 2] {
            let start = handle_on_screen(&doc, &camera, &proj, index).unwrap();
            // Grabbed 3 px off the handle's centre.
            let drag = pick(&doc, &camera, &proj, start + DVec2::new(3.0, 0.0), 12.0).unwrap();
            assert_eq!(drag.index, index);
            let depth = proj.depth(handles(&doc, &camera)[index]);
            let direction_before = doc.lights.entries[index]
                .to_table()
                .get("direction")
                .cloned();
            let to = start + DVec2::new(43.0, -27.0);
            drag.drag_to(&mut doc, &camera, &proj, to).unwrap();
            let now = handle_on_screen(&doc, &camera, &proj, index).unwrap();
            assert!(
                (now - (to - DVec2::new(3.0, 0.0))).length() < 1e-6,
                "{now} {to}"
            );
            let h = handles(&doc, &camera)[index];
            assert!((proj.depth(h) - depth).abs() < 1e-9);
            // The scene's light moved with it; a spot keeps its direction.
            assert_eq!(
                doc.lights.entries[index]
                    .to_table()
                    .get("direction")
                    .cloned(),
                direction_before
            );
            assert_eq!(doc.scene.lights[index].position(), Some(h));
        }
    }

    #[test]
    fn a_dragged_directional_light_shines_from_the_handle_at_the_target() {
        let (mut doc, camera, proj) = setup();
        let start = handle_on_screen(&doc, &camera, &proj, 1).unwrap();
        let drag = pick(&doc, &camera, &proj, start, 12.0).unwrap();
        assert_eq!(drag.index, 1);
        let to = start + DVec2::new(-60.0, 35.0);
        drag.drag_to(&mut doc, &camera, &proj, to).unwrap();
        // The handle stays under the cursor, on its sphere about the
        // target, and the light shines from it at the target.
        let now = handle_on_screen(&doc, &camera, &proj, 1).unwrap();
        assert!((now - to).length() < 1e-6, "{now} vs {to}");
        let h = handles(&doc, &camera)[1];
        let reach = directional_reach(camera.position, camera.target);
        assert!(((h - camera.target).length() - reach).abs() < 1e-9);
        let crate::scene::Light::Directional { direction, .. } = doc.scene.lights[1] else {
            panic!("{:?}", doc.scene.lights[1])
        };
        let want = (camera.target - h).normalize();
        assert!(direction.dot(want) > 1.0 - 1e-12, "{direction} vs {want}");
        // Far off the sphere: the handle goes to its rim, still valid.
        drag.drag_to(&mut doc, &camera, &proj, DVec2::new(-5000.0, 0.0))
            .unwrap();
        let h = handles(&doc, &camera)[1];
        assert!(((h - camera.target).length() - reach).abs() < 1e-9);
    }

    #[test]
    fn nothing_is_picked_away_from_the_handles() {
        let (doc, camera, proj) = setup();
        let far = DVec2::new(-100.0, -100.0);
        assert!(pick(&doc, &camera, &proj, far, 12.0).is_none());
    }
}
