//! The side panel's Environment section: the map's path field and the
//! editor of its keys ([`super::editor`]), whose edits go through
//! `Document::edit` as `--edit environment.KEY=VALUE` does.

use crate::ui::shared::Shared;

/// The Environment section's state: the map path being typed.
#[derive(Debug, Default)]
pub struct EnvironmentSection {
    /// The path field (the map's name until one is typed; a dropped file
    /// fills it too).
    pub path: String,
}

impl EnvironmentSection {
    /// Lays out the section and applies what it asks for.
    pub fn ui(&mut self, ui: &mut egui::Ui, shared: &mut Shared) {
        let doc = &*shared.doc;
        let off = super::document::is_off(doc);
        let settings = doc.scene.environment.map.as_ref().map(|m| m.settings);
        if let Some(m) = &doc.scene.environment.map
            && self.path.is_empty()
        {
            self.path = m.data.name.clone();
        }
        for edit in super::editor::environment_editor(ui, settings, off, &mut self.path) {
            shared.edit(&edit);
        }
    }
}
