//! The side panel's Compare section: the compared materials' editor
//! ([`super::editor`]) and what it asks for: a copy of the selected
//! material, or a measured material's fit ([`super::fitted`]), stored or
//! fitted on a background thread while the viewer draws on.

use super::editor::{Request, compare_editor};
use super::materials::Compare;
use crate::material::{Material, ReflectanceModel};
use crate::scene::change::{Change, Changes};
use std::sync::mpsc::{Receiver, TryRecvError};

/// A fit under way: its label and where its result arrives.
type Fitting = (String, Receiver<Result<Material, String>>);

/// The Compare section's state.
pub struct CompareSection {
    /// The fit model the combo shows.
    pub fit_choice: String,
    /// A fit under way in the background.
    fitting: Option<Fitting>,
}

impl Default for CompareSection {
    fn default() -> Self {
        CompareSection {
            fit_choice: "ct-ggx-conductor".into(),
            fitting: None,
        }
    }
}

/// What the section edits besides its own state.
pub struct CompareContext<'a> {
    /// The compared materials (the document's).
    pub compare: &'a mut Compare,
    /// The scene's selected material, if any.
    pub selected: Option<&'a Material>,
    pub changes: &'a mut Changes,
    pub message: &'a mut Option<String>,
}

impl CompareSection {
    /// Lays out the section (collecting a finished fit first) and applies
    /// what it asks for.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut CompareContext) {
        self.collect_fit(cx);
        let measured = cx
            .selected
            .is_some_and(|m| m.model == ReflectanceModel::Measured);
        let fitting = self.fitting.as_ref().map(|(label, _)| label.clone());
        let (changed, request, problem) = compare_editor(
            ui,
            cx.compare,
            measured,
            &mut self.fit_choice,
            fitting.as_deref(),
        );
        if changed {
            cx.changes.mark(Change::Compared);
        }
        if problem.is_some() {
            *cx.message = problem;
        }
        match request {
            Some(Request::AddCopy) => {
                if let Some(m) = cx.selected {
                    let mut m = m.clone();
                    m.name = format!("{} (copy)", m.name);
                    cx.compare.add(m);
                    cx.changes.mark(Change::Compared);
                }
            }
            Some(Request::AddFit(model)) => self.add_fit(ui.ctx(), &model, cx),
            None => {}
        }
        if cx.compare.materials.is_empty() {
            ui.small("Compare the selected material with others: every plot overlays them, and the 3D view splits (left: as it is, right: the compared material in its place).");
        }
    }

    /// Whether a fit is under way (the window waits for its result).
    pub fn busy(&self) -> bool {
        self.fitting.is_some()
    }

    /// Starts fitting `model` to the selected material (measured) in the
    /// background, or adds the stored fit at once.
    pub fn add_fit(&mut self, ctx: &egui::Context, model: &str, cx: &mut CompareContext) {
        let fitted = super::fitted::model(model);
        let (model, brdf) = match (fitted, cx.selected.and_then(|m| m.measured_brdf())) {
            (Ok(model), Some(brdf)) => (model, brdf),
            (Err(p), _) => return *cx.message = Some(p),
            (_, None) => {
                return *cx.message = Some("the selected material is not measured".into());
            }
        };
        if let Some(m) = super::fitted::stored(&brdf.name, &model) {
            cx.compare.add(m);
            cx.changes.mark(Change::Compared);
            return;
        }
        let label = format!("{} to {}", model.label(), brdf.name);
        let (tx, rx) = std::sync::mpsc::channel();
        let ctx = ctx.clone();
        crate::ui::background::spawn(move || {
            let _ = tx.send(super::fitted::fit_now(brdf, &model));
            ctx.request_repaint();
        });
        self.fitting = Some((label, rx));
    }

    /// A finished background fit joins the compared materials.
    fn collect_fit(&mut self, cx: &mut CompareContext) {
        let Some((_, rx)) = &self.fitting else {
            return;
        };
        match rx.try_recv() {
            Ok(Ok(m)) => {
                cx.compare.add(m);
                cx.changes.mark(Change::Compared);
                self.fitting = None;
            }
            Ok(Err(p)) => {
                *cx.message = Some(format!("no fit: {p}"));
                self.fitting = None;
            }
            Err(TryRecvError::Empty) => {}
            Err(TryRecvError::Disconnected) => {
                *cx.message = Some("the fit stopped without a result".into());
                self.fitting = None;
            }
        }
    }
}
