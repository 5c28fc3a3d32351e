//! The side panel's View section: how the scene is shown (shading, tone
//! map, ambient light: the document's, so Save scene writes them) and how
//! the window shows it (exposure, vsync, the overlay: the section's own,
//! read by the window loop), and the camera's reset.

use super::orbit::Orbit;
use super::panels;
use super::shared::Shared;
use crate::scene::change::Change;

/// The View section's state: the window's display settings.
pub struct ViewSection {
    /// Display exposure in stops (`--exposure`), applied when the frame
    /// is shown, not stored in the scene.
    pub exposure: f64,
    pub vsync: bool,
    /// The frame statistics and the lights are drawn over the 3D view.
    pub show_overlay: bool,
}

impl ViewSection {
    /// Lays out the section; a scene edit marks what it changed, and
    /// Reset view puts the camera back where the scene placed it.
    pub fn ui(&mut self, ui: &mut egui::Ui, shared: &mut Shared, orbit: &mut Orbit) {
        let doc = &mut *shared.doc;
        let changes = &mut *shared.changes;
        egui::Grid::new("view").num_columns(2).show(ui, |ui| {
            ui.label("shading");
            if panels::shading_mode(ui, &mut doc.scene.shading) {
                changes.mark(Change::Scene);
            }
            ui.end_row();
            ui.label("exposure (stops)");
            ui.add(egui::Slider::new(&mut self.exposure, -10.0..=10.0));
            ui.end_row();
            ui.label("tone map");
            let tone_map = &mut doc.scene.tone_map;
            let before = *tone_map;
            egui::ComboBox::from_id_salt("tone_map")
                .selected_text(tone_map.name())
                .show_ui(ui, |ui| {
                    for t in crate::output::tone_map::ToneMap::ALL {
                        ui.selectable_value(tone_map, t, t.name());
                    }
                });
            if *tone_map != before {
                // Compiled into the background's module: compared in full.
                changes.mark(Change::Scene);
            }
            ui.end_row();
            ui.label("ambient L_a");
            if panels::radiance(ui, &mut doc.scene.ambient) {
                changes.mark(Change::View);
            }
            ui.end_row();
            ui.label("vsync");
            ui.checkbox(&mut self.vsync, "");
            ui.end_row();
            ui.label("overlay");
            ui.checkbox(&mut self.show_overlay, "");
            ui.end_row();
        });
        ui.horizontal(|ui| {
            if ui.button("Reset view (R)").clicked() {
                orbit.reset();
            }
            ui.small("drag: orbit · right drag: pan · wheel: zoom");
        });
    }
}
