//! The open-a-scene window of the File section: a path field, the
//! folder's scene files and subfolders to click through, and the
//! built-in scene.

use super::section::{FileContext, FileSection};
use crate::scene::scene_file::SceneSource;
use std::path::{Path, PathBuf};

impl FileSection {
    /// Shows the open dialog if it is up; a chosen scene replaces the
    /// document at the next frame and closes it.
    pub fn dialog(&mut self, ctx: &egui::Context, cx: &mut FileContext) {
        if !self.open_dialog {
            return;
        }
        let mut open = true;
        let mut chosen: Option<PathBuf> = None;
        egui::Window::new("Open a scene")
            .open(&mut open)
            .default_width(420.0)
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    ui.text_edit_singleline(&mut self.open_path);
                    if ui.button("Open").clicked() {
                        chosen = Some(PathBuf::from(&self.open_path));
                    }
                });
                let dir = PathBuf::from(&self.open_path);
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
                            self.open_path = parent.display().to_string();
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
                                    self.open_path = path.display().to_string();
                                } else {
                                    chosen = Some(path);
                                }
                            }
                        }
                    });
                if ui.button("Built-in scene").clicked() {
                    cx.open(SceneSource::BuiltIn);
                    self.open_dialog = false;
                }
            });
        if let Some(path) = chosen {
            cx.open(SceneSource::File(path));
            self.open_dialog = false;
        }
        if !open {
            self.open_dialog = false;
        }
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
