//! The side panel's File section: the scene's title, Open… (the dialog,
//! [`super::dialog`]), Reload, Screenshot, and Save scene, which writes
//! the document as a scene file ([`crate::ui::save`]) that `gonio render`
//! draws as shown.

use crate::scene::scene_file::SceneSource;
use crate::ui::document::Document;
use std::path::PathBuf;

/// The File section's state: the paths being typed and whether the open
/// dialog is up.
pub struct FileSection {
    /// Where Save scene writes.
    pub save_path: String,
    /// The open dialog's path field (a folder listed, or a file).
    pub open_path: String,
    /// The open dialog is shown (the window then draws the panel afresh,
    /// not from its cache).
    pub open_dialog: bool,
}

impl Default for FileSection {
    fn default() -> Self {
        FileSection {
            save_path: "gonio-view.toml".into(),
            open_path: String::new(),
            open_dialog: false,
        }
    }
}

/// What the section edits besides its own state.
pub struct FileContext<'a> {
    pub doc: &'a Document,
    /// A new document to switch to at the next frame.
    pub replace: &'a mut Option<Document>,
    pub message: &'a mut Option<String>,
    /// A screenshot is taken at the next frame.
    pub screenshot_requested: &'a mut bool,
}

impl FileContext<'_> {
    /// Loads `source` as the new document; a bad file leaves the current
    /// scene on screen and shows why.
    pub fn open(&mut self, source: SceneSource) {
        match Document::load(source, Vec::new(), self.doc.limits) {
            Ok(doc) => *self.replace = Some(doc),
            Err(e) => *self.message = Some(e.to_string()),
        }
    }
}

impl FileSection {
    /// Lays out the section and applies what it asks for.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut FileContext) {
        ui.label(cx.doc.title());
        ui.horizontal(|ui| {
            if ui.button("Open…").clicked() {
                self.open_dialog = true;
                if self.open_path.is_empty() {
                    self.open_path = cx.doc.base_dir().display().to_string();
                }
            }
            if ui.button("Reload").clicked() {
                match cx.doc.reload() {
                    Ok(doc) => *cx.replace = Some(doc),
                    Err(e) => *cx.message = Some(e.to_string()),
                }
            }
            if ui.button("Screenshot (F12)").clicked() {
                *cx.screenshot_requested = true;
            }
        });
        ui.horizontal(|ui| {
            ui.add(egui::TextEdit::singleline(&mut self.save_path).desired_width(220.0));
            if ui.button("Save scene").clicked() {
                self.save_scene(cx);
            }
        });
        ui.small(
            "Drop a .gltf, .glb or .toml on the window to open it (a .hdr or .exr: the environment).",
        );
    }

    fn save_scene(&self, cx: &mut FileContext) {
        let path = PathBuf::from(&self.save_path);
        let result = crate::ui::save::scene_file_text(cx.doc).and_then(|text| {
            crate::output::write::AtomicFile::create(&path)?.commit(text.as_bytes())
        });
        *cx.message = Some(match result {
            Ok(()) => format!(
                "saved {}; `gonio render {} -o out.png` draws this view",
                path.display(),
                path.display()
            ),
            Err(e) => e.to_string(),
        });
    }
}
