//! The window's layout: the side panel (the message line, then each
//! section in its collapsible header, laid out by the section's own
//! `ui`), the overlay over the 3D area, and the File section's open
//! dialog. Returns the 3D area (what the panel leaves), which the scene
//! fills.

use super::file::section::FileContext;
use super::shared::Shared;
use super::state::ViewerState;

/// The [`Shared`] part of `state` (its fields borrowed one by one, so a
/// section of `state` can be borrowed beside it).
macro_rules! shared {
    ($state:expr) => {
        Shared {
            doc: &mut $state.doc,
            changes: &mut $state.changes,
            message: &mut $state.message,
        }
    };
}

/// The [`FileContext`] part of `state`, borrowed field by field as
/// `shared!` is.
macro_rules! file_context {
    ($state:expr) => {
        FileContext {
            doc: &$state.doc,
            replace: &mut $state.replace,
            message: &mut $state.message,
            screenshot_requested: &mut $state.screenshot_requested,
        }
    };
}

/// Lays out one frame of the UI; returns the 3D area in points.
pub fn ui(ui: &mut egui::Ui, state: &mut ViewerState, panel_width: f32) -> egui::Rect {
    let mut area = ui.available_rect_before_wrap();
    if state.show_panel {
        // Resizable (drag its left edge): the plots grow with it.
        let panel = egui::Panel::right("panel")
            .default_size(panel_width)
            .size_range(300.0..=1200.0)
            .resizable(true)
            .show(ui, |ui| {
                ui.set_max_width(ui.available_width());
                egui::ScrollArea::vertical().show(ui, |ui| side_panel(ui, state));
            });
        // The panel's frame (with its margins and border) is what it
        // covers; the 3D area ends where it begins.
        // Content wider than the panel would widen the root and push the
        // panel right, so the screen's edge bounds it too.
        let screen = ui.ctx().content_rect();
        area.max.x = area
            .max
            .x
            .min(panel.response.rect.min.x)
            .min(screen.max.x - panel.response.rect.width());
    }
    if state.view.show_overlay {
        overlay(ui, state, area);
    }
    state.file.dialog(ui.ctx(), &mut file_context!(state));
    area
}

fn side_panel(ui: &mut egui::Ui, state: &mut ViewerState) {
    if let Some(message) = state.message.clone() {
        ui.horizontal_wrapped(|ui| {
            ui.colored_label(egui::Color32::from_rgb(255, 190, 90), message);
            if ui.small_button("×").clicked() {
                state.message = None;
            }
        });
        ui.separator();
    }
    let requests = std::mem::take(&mut state.section_requests);
    for &name in SECTIONS {
        let request = requests.iter().rev().find(|(n, _)| *n == name).map(|r| r.1);
        let header = egui::CollapsingHeader::new(name)
            .default_open(true)
            .open(request);
        let shown = header.show(ui, |ui| match name {
            "File" => state.file.ui(ui, &mut file_context!(state)),
            "View" => state.view.ui(ui, &mut shared!(state), &mut state.orbit),
            "Environment" => state.environment.ui(ui, &mut shared!(state)),
            "Material" => state.material.ui(
                ui,
                &mut shared!(state),
                &mut state.selected_material,
                &mut state.replace,
            ),
            "Compare" => {
                let mut cx = super::compare::section::CompareContext {
                    compare: &mut state.doc.compare,
                    selected: state.doc.scene.materials.get(state.selected_material),
                    changes: &mut state.changes,
                    message: &mut state.message,
                };
                state.compare.ui(ui, &mut cx)
            }
            "Plots" => state.plots.ui(
                ui,
                state.doc.scene.materials.get(state.selected_material),
                &state.doc.compare.materials,
            ),
            _ => state.lights.ui(ui, &mut shared!(state)),
        });
        if request == Some(true) {
            shown.header_response.scroll_to_me(Some(egui::Align::Min));
        }
    }
}

/// The panel's sections, top to bottom.
pub const SECTIONS: &[&str] = &[
    "File",
    "View",
    "Environment",
    "Material",
    "Compare",
    "Plots",
    "Lights",
];

/// `panel.show=SECTION` (open it and scroll it to the top of the panel)
/// or `panel.hide=SECTION` (close it), for scripted runs (at the
/// default window size the plots are below the fold).
pub fn section_request(key: &str, value: &str) -> Result<(&'static str, bool), String> {
    let open = match key {
        "show" => true,
        "hide" => false,
        other => {
            return Err(format!(
                "unknown panel setting `panel.{other}`{}; the panel takes show=SECTION and hide=SECTION",
                crate::base::did_you_mean(other, ["show", "hide"])
            ));
        }
    };
    let wanted = value.trim().trim_matches('"');
    SECTIONS
        .iter()
        .find(|s| s.eq_ignore_ascii_case(wanted))
        .map(|s| (*s, open))
        .ok_or_else(|| {
            format!(
                "the panel has no section `{wanted}`{}; its sections are {}",
                crate::base::did_you_mean(wanted, SECTIONS.iter().copied()),
                SECTIONS.join(", ")
            )
        })
}

fn overlay(ui: &mut egui::Ui, state: &ViewerState, area: egui::Rect) {
    if state.lights.visible {
        // The orbit's camera: the scene's is set from it after the panel.
        let camera = state.orbit.camera();
        let active = state.lights.drag.map(|d| d.index);
        let pointer = ui.ctx().pointer_hover_pos();
        super::lights::overlay::draw(ui.painter(), &state.doc, &camera, area, active, pointer);
    }
    let gpu = state
        .gpu_ms
        .map(|ms| format!(" · GPU scene pass {ms:.1} ms"))
        .unwrap_or_default();
    let text = format!(
        "frame {:.1} ms{gpu} · {} triangles · {}",
        state.frame_ms,
        state.doc.scene.triangle_count(),
        state.adapter
    );
    ui.painter().text(
        area.min + egui::vec2(8.0, 6.0),
        egui::Align2::LEFT_TOP,
        text,
        egui::FontId::monospace(12.0),
        egui::Color32::from_gray(230),
    );
    // Compare mode's split: the seam and the two materials' names, in
    // their plot colours.
    if let (Some(right), Some(left)) = (
        state.doc.compare.right_half(),
        state.doc.scene.materials.get(state.selected_material),
    ) {
        let x = area.min.x + (area.width() / 2.0).floor();
        let painter = ui.painter();
        painter.line_segment(
            [egui::pos2(x, area.min.y), egui::pos2(x, area.max.y)],
            egui::Stroke::new(1.0, egui::Color32::from_gray(200)),
        );
        let font = egui::FontId::proportional(14.0);
        painter.text(
            egui::pos2(x - 8.0, area.min.y + 26.0),
            egui::Align2::RIGHT_TOP,
            &left.name,
            font.clone(),
            super::plots::colour(0),
        );
        painter.text(
            egui::pos2(x + 8.0, area.min.y + 26.0),
            egui::Align2::LEFT_TOP,
            &right.name,
            font,
            super::plots::colour(state.doc.compare.shown + 1),
        );
    }
}
