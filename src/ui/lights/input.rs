//! The window's mouse for the light handles (`super::drag`): a
//! press on a handle grabs it, a move drags it, a release lets go, before
//! the orbit sees the event.

use super::drag::pick;
use super::overlay::HANDLE_RADIUS;
use super::projection::ScreenProjection;
use crate::ui::state::ViewerState;
use glam::DVec2;
use winit::event::{ElementState, MouseButton, WindowEvent};

/// The window's mouse, for the light handles, before the orbit sees it:
/// `Some(redraw)` when the event was theirs (a press on a handle, a move
/// or release while dragging one), `None` otherwise. `view_rect` is the 3D
/// area in window pixels, `cursor` the last cursor position,
/// `pixels_per_point` egui's scale (the handles are sized in points).
pub fn on_input(
    state: &mut ViewerState,
    view_rect: [u32; 4],
    cursor: (f64, f64),
    pixels_per_point: f64,
    event: &WindowEvent,
) -> Option<bool> {
    let [x, y, w, h] = view_rect.map(f64::from);
    let camera = state.orbit.camera();
    let proj = ScreenProjection::new(&camera, DVec2::new(x, y), DVec2::new(w, h));
    match event {
        WindowEvent::MouseInput {
            state: ElementState::Pressed,
            button: MouseButton::Left,
            ..
        } => {
            let c = DVec2::new(cursor.0, cursor.1);
            let inside = c.x >= x && c.y >= y && c.x < x + w && c.y < y + h;
            if !(inside && state.show_overlay && state.lights_view.visible) {
                return None;
            }
            let radius = 2.0 * HANDLE_RADIUS as f64 * pixels_per_point;
            let drag = pick(&state.doc, &camera, &proj, c, radius)?;
            state.lights_view.drag = Some(drag);
            Some(true)
        }
        WindowEvent::CursorMoved { position, .. } => {
            let drag = state.lights_view.drag?;
            let c = DVec2::new(position.x, position.y);
            match drag.drag_to(&mut state.doc, &camera, &proj, c) {
                Ok(()) => state.changes.mark(crate::scene::change::Change::Lights),
                Err(e) => state.message = Some(format!("not moved: {e}")),
            }
            Some(true)
        }
        WindowEvent::MouseInput {
            state: ElementState::Released,
            button: MouseButton::Left,
            ..
        } => {
            state.lights_view.drag.take()?;
            Some(true)
        }
        _ => None,
    }
}
