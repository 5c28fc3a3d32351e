//! What every section of the panel edits besides its own state: the
//! document, the changes the GPU must see, and the message line. A
//! section is a struct with its own state and a `ui(&mut self, ui,
//! shared)` (as egui's demo windows are), so it reaches the rest of the
//! viewer only through this, and `ViewerState` holds the sections without
//! the sections knowing it.

use super::document::Document;
use crate::scene::change::{Change, Changes};

/// The document and what goes with editing it.
pub struct Shared<'a> {
    pub doc: &'a mut Document,
    /// What changed since the GPU last saw the scene.
    pub changes: &'a mut Changes,
    /// The last problem, shown until dismissed.
    pub message: &'a mut Option<String>,
}

impl Shared<'_> {
    /// Applies one `KEY=VALUE` edit to the document (`Document::edit`,
    /// the path of `--edit`): its change marked if it applies, else the
    /// reason shown and nothing changed.
    pub fn edit(&mut self, assignment: &str) {
        match self.doc.edit(assignment) {
            Ok(change) => self.changes.mark(change),
            Err(e) => *self.message = Some(format!("not applied: {e}")),
        }
    }

    /// An edit's outcome: `change` marked if it applied, else the reason
    /// shown after `refusal` ("not applied", "not moved").
    pub fn outcome(&mut self, result: Result<(), String>, change: Change, refusal: &str) {
        match result {
            Ok(()) => self.changes.mark(change),
            Err(e) => *self.message = Some(format!("{refusal}: {e}")),
        }
    }
}
