//! The compare section: the compared materials, each editable like the
//! selected one, which one the right half of the split 3D view shows, and
//! buttons to add a copy of the selected material or (for a measured
//! one) a model's fit ([`super::fitted`]).

use super::materials::Compare;
use crate::ui::panels::material_editor;

/// What the section asks the caller to do.
pub enum Request {
    /// Compare a copy of the selected material.
    AddCopy,
    /// Compare the selected (measured) material's fit under this model.
    AddFit(String),
}

/// Edits `c` (returns whether it changed and a request). `measured`: the
/// selected material is measured, so fits can be added; `fit_choice` is
/// the fit model's combo; `fitting` names a fit under way.
pub fn compare_editor(
    ui: &mut egui::Ui,
    c: &mut Compare,
    measured: bool,
    fit_choice: &mut String,
    fitting: Option<&str>,
) -> (bool, Option<Request>, Option<String>) {
    let (mut changed, mut request, mut problem) = (false, None, None);
    if !c.materials.is_empty() {
        ui.horizontal(|ui| {
            changed |= ui
                .checkbox(&mut c.split, "split 3D view: right half shows")
                .changed();
            let shown = c.materials.get(c.shown).map_or("", |m| m.name.as_str());
            egui::ComboBox::from_id_salt("shown")
                .selected_text(short(shown))
                .show_ui(ui, |ui| {
                    for (i, m) in c.materials.iter().enumerate() {
                        changed |= ui
                            .selectable_value(&mut c.shown, i, short(&m.name))
                            .on_hover_text(&m.name)
                            .changed();
                    }
                });
        });
    }
    let mut remove = None;
    for i in 0..c.materials.len() {
        let mut edited = c.materials[i].clone();
        let colour = crate::ui::plots::colour(i + 1);
        ui.push_id(("compared", i), |ui| {
            egui::CollapsingHeader::new(
                egui::RichText::new(format!("— {}", short(&edited.name))).color(colour),
            )
            .id_salt(("compared header", i))
            .default_open(false)
            .show(ui, |ui| {
                if material_editor(ui, &mut edited) {
                    match edited.validate() {
                        Ok(()) => {
                            c.materials[i] = edited.clone();
                            changed = true;
                        }
                        Err(p) => problem = Some(format!("not applied: {p}")),
                    }
                }
                if ui.button("remove from the comparison").clicked() {
                    remove = Some(i);
                }
            });
        });
    }
    if let Some(i) = remove {
        c.remove(i);
        changed = true;
    }
    ui.horizontal(|ui| {
        if ui.button("+ compare a copy").clicked() {
            request = Some(Request::AddCopy);
        }
        if measured {
            egui::ComboBox::from_id_salt("fit model")
                .selected_text(fit_choice.as_str())
                .show_ui(ui, |ui| {
                    for label in super::fitted::labels() {
                        ui.selectable_value(fit_choice, label.clone(), label);
                    }
                });
            let busy = fitting.is_some();
            if ui
                .add_enabled(!busy, egui::Button::new("+ its fit"))
                .on_hover_text("the fitted parameters of docs/fit/fits.toml, or a fit run now (seconds to a minute)")
                .clicked()
            {
                request = Some(Request::AddFit(fit_choice.clone()));
            }
        }
    });
    if let Some(f) = fitting {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(format!("fitting {f}…"));
        });
    }
    (changed, request, problem)
}

/// A name cut to fit the panel (a long one would widen it: the panel is
/// resizable and grows to its content).
pub fn short(name: &str) -> String {
    const CHARS: usize = 30;
    if name.chars().count() > CHARS {
        let head: String = name.chars().take(CHARS - 1).collect();
        format!("{head}…")
    } else {
        name.to_string()
    }
}
