//! The viewer's state apart from the GPU: what is shared (the document,
//! the changes the GPU must see, the message line, the camera orbit, the
//! selected material, the window's switches and requests, the frame
//! statistics) and the panel's sections, each a struct with the state
//! only it keeps (file, view, environment, material, compare, plots,
//! lights), laid out by its own `ui`. The panel
//! ([`super::view`]) edits it; the window loop ([`super::app`]) acts on
//! it.

use super::cli::ViewArgs;
use super::document::Document;
use super::file::section::{FileContext, FileSection};
use super::material_section::MaterialSection;
use super::orbit::Orbit;
use super::plots::section::PlotsSection;
use super::view_section::ViewSection;
use crate::scene::change::Changes;
use crate::scene::scene_file::SceneSource;
use std::path::PathBuf;

/// Everything the panel edits, apart from the GPU.
pub struct ViewerState {
    pub doc: Document,
    pub orbit: Orbit,
    /// The material the Material section edits, which the Compare and
    /// Plots sections, the split view and a reload use too.
    pub selected_material: usize,
    /// The panel is shown (`P`).
    pub show_panel: bool,
    /// The last problem (rejected value, bad file), shown until dismissed.
    pub message: Option<String>,
    /// A new document to switch to (opened, dropped, reloaded).
    pub replace: Option<Document>,
    /// What changed since the GPU last saw the scene: each edit names
    /// its kind, and the GPU rewrites only that.
    pub changes: Changes,
    pub screenshot_path: PathBuf,
    pub screenshot_requested: bool,
    /// Frame-time statistics shown in the overlay.
    pub frame_ms: f64,
    pub gpu_ms: Option<f64>,
    pub adapter: String,
    /// Sections of the panel a script opens (and scrolls to the top) or
    /// closes at the next frame: `--edit N:panel.show=Plots`,
    /// `panel.hide=Lights` ([`super::view::SECTIONS`]).
    pub section_requests: Vec<(&'static str, bool)>,
    /// The File section (the save and open paths, the open dialog).
    pub file: FileSection,
    /// The View section (exposure, vsync, the overlay switch).
    pub view: ViewSection,
    /// The Environment section (its map path field).
    pub environment: super::environment::section::EnvironmentSection,
    /// The Material section (no state of its own).
    pub material: MaterialSection,
    /// The Compare section (the fit model's choice, a fit under way).
    pub compare: super::compare::section::CompareSection,
    /// The Plots section (the plots' settings and cached results).
    pub plots: PlotsSection,
    /// The Lights section: the lights drawn over the 3D view, and the one
    /// being dragged.
    pub lights: super::lights::section::LightsSection,
}

impl ViewerState {
    pub fn new(doc: Document, args: &ViewArgs) -> ViewerState {
        ViewerState {
            orbit: Orbit::from_camera(&doc.loaded_camera),
            doc,
            selected_material: 0,
            show_panel: !args.no_panel,
            message: None,
            replace: None,
            changes: Changes::everything(),
            screenshot_path: args
                .screenshot
                .clone()
                .unwrap_or_else(|| PathBuf::from("gonio-screenshot.png")),
            screenshot_requested: false,
            frame_ms: 0.0,
            gpu_ms: None,
            adapter: String::new(),
            section_requests: Vec::new(),
            file: FileSection::default(),
            view: ViewSection {
                exposure: args.exposure,
                vsync: !args.no_vsync,
                show_overlay: !args.no_overlay,
            },
            environment: Default::default(),
            material: MaterialSection,
            compare: Default::default(),
            plots: PlotsSection::default(),
            lights: Default::default(),
        }
    }

    /// Whether work is under way in the background (plots' integrals, a
    /// fit) whose result the window will show.
    pub fn busy(&self) -> bool {
        self.plots.busy() || self.compare.busy()
    }

    /// A file dropped on the window: a `.hdr` or `.exr` becomes the
    /// environment map, anything else is opened as a scene.
    pub fn drop_file(&mut self, path: PathBuf) {
        if super::environment::document::is_map_file(&path) {
            self.environment.path = path.display().to_string();
            self.edit(&super::environment::document::map_assignment(&path));
        } else {
            self.open(path);
        }
    }

    /// Applies one panel edit to the document (`Document::edit`): redrawn
    /// if it applies, else the reason is shown and nothing changes.
    pub fn edit(&mut self, assignment: &str) {
        self.shared().edit(assignment);
    }

    /// What every section edits: the document, the changes, the message.
    pub fn shared(&mut self) -> super::shared::Shared<'_> {
        super::shared::Shared {
            doc: &mut self.doc,
            changes: &mut self.changes,
            message: &mut self.message,
        }
    }

    /// Draws the glTF files in material variant `name`
    /// ([`Document::with_variant`]): the document reloaded with it
    /// replaces the current one at the next frame (its meshes draw other
    /// materials).
    pub fn choose_variant(&mut self, name: &str) -> crate::Result<()> {
        self.replace = Some(self.doc.with_variant(name)?);
        Ok(())
    }

    /// Opens `path` as the new document; a bad file leaves the current
    /// scene on screen and shows why.
    pub fn open(&mut self, path: PathBuf) {
        self.file_context().open(SceneSource::File(path));
    }

    /// What the File section edits besides its own state.
    pub fn file_context(&mut self) -> FileContext<'_> {
        FileContext {
            doc: &self.doc,
            replace: &mut self.replace,
            message: &mut self.message,
            screenshot_requested: &mut self.screenshot_requested,
        }
    }
}
