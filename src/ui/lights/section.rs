//! The side panel's Lights section: the overlay switch, the `[[lights]]`
//! list ([`super::list`]) and what it asks for applied to the document,
//! each validated as the scene file is (a refused value is a message and
//! nothing changes). Its state is the overlay's: shown or not, and the
//! handle being dragged ([`super::input`] moves it).

use super::drag::LightDrag;
use super::list::{LightAction, light_list};
use crate::scene::change::Change;
use crate::ui::shared::Shared;

/// The Lights section and the lights drawn over the 3D view.
#[derive(Debug)]
pub struct LightsSection {
    /// The lights are drawn over the 3D view (`L`, *show lights*).
    pub visible: bool,
    /// The handle being dragged.
    pub drag: Option<LightDrag>,
}

impl Default for LightsSection {
    fn default() -> Self {
        LightsSection {
            visible: true,
            drag: None,
        }
    }
}

impl LightsSection {
    /// Lays out the section; an applied edit marks the lights changed.
    pub fn ui(&mut self, ui: &mut egui::Ui, shared: &mut Shared) {
        ui.horizontal(|ui| {
            ui.checkbox(&mut self.visible, "show lights (L)");
            ui.small("drag a marker to move its light");
        });
        let doc = &*shared.doc;
        let effective = |i: usize| doc.lights.shadow_settings(i);
        let dragged = self.drag.map(|d| d.index);
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
            let doc = &mut *shared.doc;
            let result = match action {
                LightAction::Edit(i, entry) => doc.set_light(i, *entry),
                LightAction::Retype(i, kind) => doc.retype_light(i, kind),
                LightAction::Remove(i) => doc.remove_light(i),
                LightAction::Add(kind) => doc.add_light_of_kind(kind).map(|_| ()),
            };
            shared.outcome(result, Change::Lights, "not applied");
        }
    }
}
