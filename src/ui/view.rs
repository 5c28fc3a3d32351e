//! The window's layout: the side panel (file, view, material, plots,
//! lights), the overlay over the 3D area, and the open-file dialog.
//! Returns the 3D area (what the panel leaves), which the scene fills.

use super::panels;
use super::shared::Shared;
use super::state::ViewerState;
use crate::material::ROUGHNESS_FLOOR;
use crate::scene::change::Change;
use crate::scene::scene_file::SceneSource;
use std::path::{Path, PathBuf};

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
    if state.show_overlay {
        overlay(ui, state, area);
    }
    if state.open_dialog {
        open_dialog(ui.ctx(), state);
    }
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
            "File" => file_section(ui, state),
            "View" => view_section(ui, state),
            "Environment" => state.environment.ui(ui, &mut shared!(state)),
            "Material" => material_section(ui, state),
            "Compare" => {
                let mut cx = super::compare::section::CompareContext {
                    compare: &mut state.doc.compare,
                    selected: state.doc.scene.materials.get(state.selected_material),
                    changes: &mut state.changes,
                    message: &mut state.message,
                };
                state.compare.ui(ui, &mut cx)
            }
            "Plots" => plots_section(ui, state),
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
/// or `panel.hide=SECTION` (close it), for scripted runs (issue 38: at the
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

fn file_section(ui: &mut egui::Ui, state: &mut ViewerState) {
    ui.label(state.doc.title());
    ui.horizontal(|ui| {
        if ui.button("Open…").clicked() {
            state.open_dialog = true;
            if state.open_path.is_empty() {
                state.open_path = state.doc.base_dir().display().to_string();
            }
        }
        if ui.button("Reload").clicked() {
            match state.doc.reload() {
                Ok(doc) => state.replace = Some(doc),
                Err(e) => state.message = Some(e.to_string()),
            }
        }
        if ui.button("Screenshot (F12)").clicked() {
            state.screenshot_requested = true;
        }
    });
    ui.horizontal(|ui| {
        ui.add(egui::TextEdit::singleline(&mut state.save_path).desired_width(220.0));
        if ui.button("Save scene").clicked() {
            save_scene(state);
        }
    });
    ui.small(
        "Drop a .gltf, .glb or .toml on the window to open it (a .hdr or .exr: the environment).",
    );
}

fn save_scene(state: &mut ViewerState) {
    let path = PathBuf::from(&state.save_path);
    let result = super::save::scene_file_text(&state.doc)
        .and_then(|text| crate::output::write::AtomicFile::create(&path)?.commit(text.as_bytes()));
    state.message = Some(match result {
        Ok(()) => format!(
            "saved {}; `gonio render {} -o out.png` draws this view",
            path.display(),
            path.display()
        ),
        Err(e) => e.to_string(),
    });
}

fn view_section(ui: &mut egui::Ui, state: &mut ViewerState) {
    egui::Grid::new("view").num_columns(2).show(ui, |ui| {
        ui.label("shading");
        if panels::shading_mode(ui, &mut state.doc.scene.shading) {
            state.changes.mark(Change::Scene);
        }
        ui.end_row();
        ui.label("exposure (stops)");
        ui.add(egui::Slider::new(&mut state.exposure, -10.0..=10.0));
        ui.end_row();
        ui.label("tone map");
        let tone_map = &mut state.doc.scene.tone_map;
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
            state.changes.mark(Change::Scene);
        }
        ui.end_row();
        ui.label("ambient L_a");
        if panels::radiance(ui, &mut state.doc.scene.ambient) {
            state.changes.mark(Change::View);
        }
        ui.end_row();
        ui.label("vsync");
        ui.checkbox(&mut state.vsync, "");
        ui.end_row();
        ui.label("overlay");
        ui.checkbox(&mut state.show_overlay, "");
        ui.end_row();
    });
    ui.horizontal(|ui| {
        if ui.button("Reset view (R)").clicked() {
            state.orbit.reset();
        }
        ui.small("drag: orbit · right drag: pan · wheel: zoom");
    });
}

fn material_section(ui: &mut egui::Ui, state: &mut ViewerState) {
    variant_choice(ui, state);
    let materials = &mut state.doc.scene.materials;
    if materials.is_empty() {
        ui.label("no materials");
        return;
    }
    state.selected_material = state.selected_material.min(materials.len() - 1);
    let before = state.selected_material;
    egui::ComboBox::from_id_salt("which material")
        .selected_text(&materials[state.selected_material].name)
        .show_ui(ui, |ui| {
            for (i, m) in materials.iter().enumerate() {
                ui.selectable_value(&mut state.selected_material, i, &m.name);
            }
        });
    if state.selected_material != before && state.doc.compare.right_half().is_some() {
        // The split view's right half replaces the selected material:
        // the one selected before is its own again.
        state.changes.mark(Change::Material(before));
        state.changes.mark(Change::Compared);
    }
    let mut edited = materials[state.selected_material].clone();
    let changed = panels::material_editor(ui, &mut edited);
    let images: Vec<&str> = state
        .doc
        .scene
        .images
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    panels::material::texture_notes(ui, &edited, &images);
    let materials = &mut state.doc.scene.materials;
    if changed {
        match edited.validate() {
            Ok(()) => {
                materials[state.selected_material] = edited;
                state
                    .changes
                    .mark(Change::Material(state.selected_material));
            }
            Err(problem) => state.message = Some(format!("not applied: {problem}")),
        }
    }
}

/// The material variant (`KHR_materials_variants`) the glTF files are
/// drawn in, where they have variants: the file's own materials until
/// one is picked (the scene key `gltf.variant`, which Save scene writes).
fn variant_choice(ui: &mut egui::Ui, state: &mut ViewerState) {
    if state.doc.variants.is_empty() {
        return;
    }
    let current = state.doc.variant().map(str::to_string);
    let mut picked = None;
    ui.horizontal(|ui| {
        ui.label("variant")
            .on_hover_text("KHR_materials_variants: the material variant the glTF files are drawn in (gltf.variant)");
        egui::ComboBox::from_id_salt("variant")
            .selected_text(current.as_deref().unwrap_or("(the file's own)"))
            .show_ui(ui, |ui| {
                for v in &state.doc.variants {
                    let chosen = current.as_deref() == Some(v.as_str());
                    if ui.selectable_label(chosen, v).clicked() && !chosen {
                        picked = Some(v.clone());
                    }
                }
            });
    });
    if let Some(name) = picked
        && let Err(e) = state.choose_variant(&name)
    {
        state.message = Some(format!("not applied: {e}"));
    }
}

/// The plots of the selected material and the compared ones, as the
/// renderers evaluate them, as `gonio brdf` does (explore::spec):
/// roughness no smaller than the floor. Unfloored, a roughness of 1e-6
/// kept the albedo worker busy for minutes (issue 19).
fn plots_section(ui: &mut egui::Ui, state: &mut ViewerState) {
    let Some(given) = state.doc.scene.materials.get(state.selected_material) else {
        return;
    };
    let mut series = vec![panels_series(given)];
    series.extend(state.doc.compare.materials.iter().map(panels_series));
    if series.iter().any(|s| s.1) {
        ui.label(format!(
            "Roughness below the floor {ROUGHNESS_FLOOR:e}: plotted at the floor, as rendered."
        ));
    }
    let series: Vec<super::plots::Series> = series.into_iter().map(|s| s.0).collect();
    state.plots.show(ui, &series);
}

/// A plotted material (floored) and whether the floor changed it.
fn panels_series(m: &crate::material::Material) -> (super::plots::Series, bool) {
    let floored = m.with_roughness_floor(0.0);
    let changed = floored != *m;
    (
        super::plots::Series::whole(m.name.clone(), floored),
        changed,
    )
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

fn open_dialog(ctx: &egui::Context, state: &mut ViewerState) {
    let mut open = true;
    let mut chosen: Option<PathBuf> = None;
    egui::Window::new("Open a scene")
        .open(&mut open)
        .default_width(420.0)
        .show(ctx, |ui| {
            ui.horizontal(|ui| {
                ui.text_edit_singleline(&mut state.open_path);
                if ui.button("Open").clicked() {
                    chosen = Some(PathBuf::from(&state.open_path));
                }
            });
            let dir = PathBuf::from(&state.open_path);
            let dir = if dir.is_dir() {
                dir
            } else {
                dir.parent().map(Path::to_path_buf).unwrap_or_default()
            };
            egui::ScrollArea::vertical()
                .max_height(300.0)
                .show(ui, |ui| {
                    if let Some(parent) = dir.parent()
                        && ui.selectable_label(false, "📁 ..").clicked()
                    {
                        state.open_path = parent.display().to_string();
                    }
                    for (path, is_dir) in listing(&dir) {
                        let name = path.file_name().unwrap_or_default().to_string_lossy();
                        let label = if is_dir {
                            format!("📁 {name}")
                        } else {
                            name.to_string()
                        };
                        if ui.selectable_label(false, label).clicked() {
                            if is_dir {
                                state.open_path = path.display().to_string();
                            } else {
                                chosen = Some(path);
                            }
                        }
                    }
                });
            if ui.button("Built-in scene").clicked() {
                match super::document::Document::load(
                    SceneSource::BuiltIn,
                    Vec::new(),
                    state.doc.limits,
                ) {
                    Ok(doc) => state.replace = Some(doc),
                    Err(e) => state.message = Some(e.to_string()),
                }
                state.open_dialog = false;
            }
        });
    if let Some(path) = chosen {
        state.open(path);
        state.open_dialog = false;
    }
    if !open {
        state.open_dialog = false;
    }
}

/// Folders and scene files in `dir`, folders first, by name.
fn listing(dir: &Path) -> Vec<(PathBuf, bool)> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut items: Vec<(PathBuf, bool)> = entries
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let path = e.path();
            let is_dir = path.is_dir();
            let ext = path
                .extension()
                .and_then(|x| x.to_str())
                .map(str::to_ascii_lowercase);
            let scene = matches!(ext.as_deref(), Some("toml" | "gltf" | "glb"));
            (is_dir || scene).then_some((path, is_dir))
        })
        .take(2000)
        .collect();
    items.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    items
}
