//! The side panel's Lights section: the overlay switch, the `[[lights]]`
//! list ([`super::list`]) and what it asks for applied to the
//! document, each validated as the scene file is (a refused value is a
//! message and nothing changes).

use super::list::{LightAction, light_list};
use crate::ui::state::ViewerState;

pub fn lights_section(ui: &mut egui::Ui, state: &mut ViewerState) {
    ui.horizontal(|ui| {
        ui.checkbox(&mut state.lights_view.visible, "show lights (L)");
        ui.small("drag a marker to move its light");
    });
    let doc = &state.doc;
    let effective = |i: usize| doc.lights.shadow_settings(i);
    let dragged = state.lights_view.drag.map(|d| d.index);
    let actions = light_list(ui, &doc.lights.entries, &effective, dragged);
    if !doc.lights.imported.is_empty() || doc.lights.gets_default_light() {
        let what = if doc.lights.imported.is_empty() {
            "the default light (the scene has no other)".to_string()
        } else {
            format!("{} lights from the glTF file", doc.lights.imported.len())
        };
        ui.small(format!(
            "Also lit by {what}, drawn grey in the view; the file's lights are not editable here, and adding one removes the default light, as in a scene file."
        ));
    }
    for action in actions {
        let doc = &mut state.doc;
        let result = match action {
            LightAction::Edit(i, entry) => doc.set_light(i, *entry),
            LightAction::Retype(i, kind) => doc.retype_light(i, kind),
            LightAction::Remove(i) => doc.remove_light(i),
            LightAction::Add(kind) => doc.add_light_of_kind(kind).map(|_| ()),
        };
        match result {
            Ok(()) => state.changes.mark(crate::scene::change::Change::Lights),
            Err(e) => state.message = Some(format!("not applied: {e}")),
        }
    }
}
