//! The lights section's list: each `[[lights]]` entry under a header with
//! its kind (a selector that retypes it) and a remove button, its keys
//! below ([`super::editor::light_editor`]), and *Add* with a kind. Hands back what
//! the user asked for; the caller applies it through the document, which
//! validates it as the scene file does.

use super::kinds::KINDS;
use crate::scene::ShadowSettings;
use crate::scene::scene_file::LightEntry;

/// What the user asked the list for.
#[derive(Clone, Debug)]
pub enum LightAction {
    /// Entry N edited (the new value, not yet validated).
    Edit(usize, Box<LightEntry>),
    /// Entry N becomes a light of this kind.
    Retype(usize, &'static str),
    Remove(usize),
    /// A new light of this kind.
    Add(&'static str),
}

/// Lays out the entries; `effective(i)` is entry i's shadow settings and
/// `highlighted` the light the 3D view is dragging (its header is
/// marked).
pub fn light_list(
    ui: &mut egui::Ui,
    entries: &[LightEntry],
    effective: &dyn Fn(usize) -> ShadowSettings,
    highlighted: Option<usize>,
) -> Vec<LightAction> {
    let mut actions = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let mut edited = entry.clone();
        let marker = if highlighted == Some(i) { " ◆" } else { "" };
        let id = ui.make_persistent_id(format!("light header {i}"));
        egui::collapsing_header::CollapsingState::load_with_default_open(ui.ctx(), id, i == 0)
            .show_header(ui, |ui| {
                ui.label(format!("light {i}{marker}"));
                let mut kind = entry.kind();
                egui::ComboBox::from_id_salt(format!("light{i}.kind"))
                    .selected_text(kind)
                    .width(100.0)
                    .show_ui(ui, |ui| {
                        for k in KINDS {
                            ui.selectable_value(&mut kind, k, k);
                        }
                    })
                    .response
                    .on_hover_text("another kind at the same place, aimed the same way, about as bright where the camera looks");
                if kind != entry.kind() {
                    actions.push(LightAction::Retype(i, kind));
                }
                if ui.small_button("remove").clicked() {
                    actions.push(LightAction::Remove(i));
                }
            })
            .body(|ui| {
                if super::editor::light_editor(ui, i, &mut edited, effective(i)) {
                    actions.push(LightAction::Edit(i, Box::new(edited)));
                }
            });
    }
    ui.horizontal(|ui| {
        ui.label("add");
        for k in KINDS {
            if ui
                .button(k)
                .on_hover_text(format!("a new {k} light aimed at what the camera looks at"))
                .clicked()
            {
                actions.push(LightAction::Add(k));
            }
        }
    });
    actions
}
