//! The environment section: the map (a path, the built-in sky, or a
//! file dropped on the window), on/off, rotation, scale, SH order,
//! specular mode and its samples or prefilter size. It returns the edits
//! as `environment.KEY=VALUE` assignments, which the caller applies
//! through `Document::edit` (the same path as `--edit`), so every value
//! is checked as the scene file checks it.

use crate::environment::map::{MapSettings, Specular};
use crate::environment::sh;
use crate::scene::scene_file::environment_keys::MAX_SAMPLES;

/// The map's current settings (`None`: no map, or switched off), whether
/// it is switched off, and the path field; returns the edits to apply.
pub fn environment_editor(
    ui: &mut egui::Ui,
    settings: Option<MapSettings>,
    off: bool,
    path: &mut String,
) -> Vec<String> {
    let mut edits = Vec::new();
    ui.horizontal(|ui| {
        ui.add(
            egui::TextEdit::singleline(path)
                .hint_text(".hdr / .exr path")
                .desired_width(200.0),
        );
        if ui.button("Set map").clicked() && !path.trim().is_empty() {
            edits.push(match path.trim() {
                "sky" => "environment.map=\"sky\"".into(),
                p => super::document::map_assignment(std::path::Path::new(p)),
            });
        }
        if ui.button("Sky").clicked() {
            edits.push("environment.map=\"sky\"".into());
        }
    });
    ui.small("Drop a .hdr or .exr on the window to light the scene with it.");
    if settings.is_none() && !off {
        return edits;
    }
    let mut on = !off;
    if ui.checkbox(&mut on, "environment map on").changed() {
        edits.push(format!("environment.enabled={on}"));
    }
    let Some(s) = settings else {
        return edits;
    };
    egui::Grid::new("environment")
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("rotation (°)");
            let mut deg = s.rotation_deg;
            if ui
                .add(egui::Slider::new(&mut deg, -180.0..=180.0))
                .changed()
            {
                edits.push(format!("environment.rotation_deg={deg}"));
            }
            ui.end_row();
            ui.label("scale");
            let mut scale = s.scale;
            if crate::ui::panels::widgets::log_slider(ui, &mut scale, 1e-3..=1e3) {
                edits.push(format!("environment.scale={scale}"));
            }
            ui.end_row();
            ui.label("SH order");
            let mut order = s.sh_order;
            if ui
                .add(egui::Slider::new(&mut order, 0..=sh::MAX_ORDER))
                .changed()
            {
                edits.push(format!("environment.sh_order={order}"));
            }
            ui.end_row();
            ui.label("specular");
            let mut mode = s.specular;
            let all = [
                Specular::None,
                Specular::Sampled,
                Specular::Prefiltered,
                Specular::Sh,
            ];
            if crate::ui::panels::widgets::combo(
                ui,
                "environment.specular",
                &mut mode,
                all,
                Specular::name,
            ) {
                edits.push(format!("environment.specular=\"{}\"", mode.name()));
            }
            ui.end_row();
            match s.specular {
                Specular::Sampled => {
                    ui.label("samples N");
                    let mut n = s.samples;
                    if ui
                        .add(egui::Slider::new(&mut n, 1..=MAX_SAMPLES as u32).logarithmic(true))
                        .changed()
                    {
                        edits.push(format!("environment.samples={n}"));
                    }
                    ui.end_row();
                }
                Specular::Prefiltered => {
                    ui.label("prefilter size");
                    let mut size = s.prefilter_size;
                    egui::ComboBox::from_id_salt("environment.prefilter_size")
                        .selected_text(size.to_string())
                        .show_ui(ui, |ui| {
                            for v in [32u32, 64, 128, 256, 512, 1024, 2048] {
                                ui.selectable_value(&mut size, v, v.to_string());
                            }
                        });
                    if size != s.prefilter_size {
                        edits.push(format!("environment.prefilter_size={size}"));
                    }
                    ui.end_row();
                }
                Specular::None | Specular::Sh => {}
            }
        });
    edits
}
