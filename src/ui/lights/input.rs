//! The window's mouse for the light handles (`super::drag`): a press on a
//! handle grabs it, a move drags it, a release lets go, before the orbit
//! sees the event.

use super::drag::pick;
use super::overlay::HANDLE_RADIUS;
use super::projection::ScreenProjection;
use super::section::LightsSection;
use crate::scene::Camera;
use crate::scene::change::Change;
use crate::ui::shared::Shared;
use glam::DVec2;
use winit::event::{ElementState, MouseButton, WindowEvent};

/// Where the 3D view is and where the mouse is.
#[derive(Clone, Copy, Debug)]
pub struct Pointer {
    /// The 3D area in window pixels: x, y, width, height.
    pub view_rect: [u32; 4],
    /// The last cursor position, window pixels.
    pub cursor: (f64, f64),
    /// egui's scale (the handles are sized in points).
    pub pixels_per_point: f64,
    /// The overlay is on (`--no-overlay` hides the handles too).
    pub overlay_shown: bool,
}

impl LightsSection {
    /// The window's mouse, for the light handles, before the orbit sees
    /// it: `Some(redraw)` when the event was theirs (a press on a handle,
    /// a move or release while dragging one), `None` otherwise. `camera`
    /// is the one the scene is drawn with.
    pub fn on_input(
        &mut self,
        shared: &mut Shared,
        camera: &Camera,
        at: Pointer,
        event: &WindowEvent,
    ) -> Option<bool> {
        let [x, y, w, h] = at.view_rect.map(f64::from);
        let proj = ScreenProjection::new(camera, DVec2::new(x, y), DVec2::new(w, h));
        match event {
            WindowEvent::MouseInput {
                state: ElementState::Pressed,
                button: MouseButton::Left,
                ..
            } => {
                let c = DVec2::new(at.cursor.0, at.cursor.1);
                let inside = c.x >= x && c.y >= y && c.x < x + w && c.y < y + h;
                if !(inside && at.overlay_shown && self.visible) {
                    return None;
                }
                let radius = 2.0 * HANDLE_RADIUS as f64 * at.pixels_per_point;
                self.drag = Some(pick(shared.doc, camera, &proj, c, radius)?);
                Some(true)
            }
            WindowEvent::CursorMoved { position, .. } => {
                let drag = self.drag?;
                let c = DVec2::new(position.x, position.y);
                let result = drag.drag_to(shared.doc, camera, &proj, c);
                shared.outcome(result, Change::Lights, "not moved");
                Some(true)
            }
            WindowEvent::MouseInput {
                state: ElementState::Released,
                button: MouseButton::Left,
                ..
            } => {
                self.drag.take()?;
                Some(true)
            }
            _ => None,
        }
    }
}
