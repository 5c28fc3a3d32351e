//! The side panel's Material section: the glTF files' material variant,
//! which material is selected, and its editor ([`super::panels`]), whose
//! edit is validated as the scene file's materials are (a refused value
//! is a message and nothing changes).

use super::document::Document;
use super::panels;
use super::shared::Shared;
use crate::scene::change::Change;

/// The Material section's state: none of its own. The selected material
/// is shared, since the Compare and Plots sections, the split view and a
/// reload use it too.
#[derive(Debug, Default)]
pub struct MaterialSection;

impl MaterialSection {
    /// Lays out the section: `selected` is clamped to the scene's
    /// materials and changed by the combo; a picked variant's document
    /// goes to `replace` (the next frame switches to it).
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        shared: &mut Shared,
        selected: &mut usize,
        replace: &mut Option<Document>,
    ) {
        variant_choice(ui, shared, replace);
        let doc = &mut *shared.doc;
        let materials = &mut doc.scene.materials;
        if materials.is_empty() {
            ui.label("no materials");
            return;
        }
        *selected = (*selected).min(materials.len() - 1);
        let before = *selected;
        egui::ComboBox::from_id_salt("which material")
            .selected_text(&materials[*selected].name)
            .show_ui(ui, |ui| {
                for (i, m) in materials.iter().enumerate() {
                    ui.selectable_value(selected, i, &m.name);
                }
            });
        if *selected != before && doc.compare.right_half().is_some() {
            // The split view's right half replaces the selected material:
            // the one selected before is its own again.
            shared.changes.mark(Change::Material(before));
            shared.changes.mark(Change::Compared);
        }
        let mut edited = doc.scene.materials[*selected].clone();
        let changed = panels::material_editor(ui, &mut edited);
        let images: Vec<&str> = doc.scene.images.iter().map(|i| i.name.as_str()).collect();
        panels::material::texture_notes(ui, &edited, &images);
        if changed {
            match edited.validate() {
                Ok(()) => {
                    doc.scene.materials[*selected] = edited;
                    shared.changes.mark(Change::Material(*selected));
                }
                Err(problem) => *shared.message = Some(format!("not applied: {problem}")),
            }
        }
    }
}

/// The material variant (`KHR_materials_variants`) the glTF files are
/// drawn in, where they have variants: the file's own materials until
/// one is picked (the scene key `gltf.variant`, which Save scene writes).
fn variant_choice(ui: &mut egui::Ui, shared: &mut Shared, replace: &mut Option<Document>) {
    let doc = &*shared.doc;
    if doc.variants.is_empty() {
        return;
    }
    let current = doc.variant().map(str::to_string);
    let mut picked = None;
    ui.horizontal(|ui| {
        ui.label("variant")
            .on_hover_text("KHR_materials_variants: the material variant the glTF files are drawn in (gltf.variant)");
        egui::ComboBox::from_id_salt("variant")
            .selected_text(current.as_deref().unwrap_or("(the file's own)"))
            .show_ui(ui, |ui| {
                for v in &doc.variants {
                    let chosen = current.as_deref() == Some(v.as_str());
                    if ui.selectable_label(chosen, v).clicked() && !chosen {
                        picked = Some(v.clone());
                    }
                }
            });
    });
    if let Some(name) = picked {
        // As `ViewerState::choose_variant`: the document reloaded in the
        // variant replaces this one (its meshes draw other materials).
        match doc.with_variant(&name) {
            Ok(doc) => *replace = Some(doc),
            Err(e) => *shared.message = Some(format!("not applied: {e}")),
        }
    }
}
