//! The panel's plots of the selected material, from the same f64
//! reference functions as `gonio brdf` (`crate::explore`): the lecture's
//! polar slice for an adjustable incidence angle, the directional albedo
//! against the incidence angle, and a gloss meter's readings at 20°, 60°
//! and 85° (ISO 2813 / ASTM D523 geometries).
//!
//! The slice is cheap (about 800 evaluations) and follows every edit at
//! once. Albedo and gloss are adaptive integrals (milliseconds to a second
//! for narrow lobes), so they run on a worker thread and the panel shows
//! the last finished result, marked stale until the new one arrives; the
//! frame rate never waits for them.

use crate::explore::albedo::albedo_curve;
use crate::explore::gloss::{GEOMETRIES, GlossReading, gloss};
use crate::explore::slice::{Quantity, Slice, light_marker, mirror_marker, slice};
use crate::explore::{Channel, albedo::AlbedoEstimate};
use crate::material::Material;
use egui_plot::{Legend, Line, Plot, PlotPoints, Points};
use std::sync::mpsc::{Receiver, channel};

/// Incidence angles of the albedo curve, degrees.
const ALBEDO_ANGLES: usize = 31;

/// What the worker computes for one material.
struct Integrals {
    material: Material,
    albedo: Vec<(f64, AlbedoEstimate)>,
    gloss: Vec<GlossReading>,
}

/// The plots' state: the incidence angle, the cached results.
pub struct Plots {
    /// Incidence angle of the slice, degrees from the normal.
    pub theta_i_deg: f64,
    integrals: Option<Integrals>,
    pending: Option<(Material, Receiver<Integrals>)>,
    /// The last slice and what it was computed for (the panel redraws
    /// every frame; the slice changes only with an edit).
    slice: Option<(Material, f64, Slice)>,
}

impl Default for Plots {
    fn default() -> Self {
        Plots {
            theta_i_deg: 45.0,
            integrals: None,
            pending: None,
            slice: None,
        }
    }
}

impl Plots {
    /// Draws the three plots of `material` into `ui`.
    pub fn show(&mut self, ui: &mut egui::Ui, material: &Material) {
        self.refresh(material, ui.ctx());
        ui.add(
            egui::Slider::new(&mut self.theta_i_deg, 0.0..=89.0)
                .text("θ_i (°)")
                .step_by(0.5),
        );
        self.show_slice(ui, material);
        self.show_albedo(ui, material);
        self.show_gloss(ui, material);
    }

    /// Starts the integrals for `material` unless they are done or under
    /// way; collects a finished result. The worker wakes the (otherwise
    /// idle) window when it is done, through egui's repaint request.
    fn refresh(&mut self, material: &Material, ctx: &egui::Context) {
        if let Some((_, rx)) = &self.pending
            && let Ok(done) = rx.try_recv()
        {
            self.integrals = Some(done);
            self.pending = None;
        }
        let current = self.integrals.as_ref().map(|i| &i.material);
        let running = self.pending.as_ref().map(|(m, _)| m);
        if current == Some(material) || running == Some(material) {
            return;
        }
        if running.is_some() {
            // One at a time: the newest edit starts when this one ends.
            return;
        }
        let (tx, rx) = channel();
        let m = material.clone();
        let ctx = ctx.clone();
        std::thread::spawn(move || {
            let thetas: Vec<f64> = (0..ALBEDO_ANGLES)
                .map(|k| (k as f64 * 89.0 / (ALBEDO_ANGLES - 1) as f64).to_radians())
                .collect();
            let albedo = albedo_curve(&m, &thetas, 0.0);
            let gloss = GEOMETRIES.iter().map(|g| gloss(&m, *g)).collect();
            let _ = tx.send(Integrals {
                albedo: thetas.iter().map(|t| t.to_degrees()).zip(albedo).collect(),
                gloss,
                material: m,
            });
            ctx.request_repaint();
        });
        self.pending = Some((material.clone(), rx));
    }

    /// Whether background integrals are under way or finished but not yet
    /// shown.
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }

    fn stale(&self, material: &Material) -> bool {
        self.integrals.as_ref().map(|i| &i.material) != Some(material)
    }

    fn show_slice(&mut self, ui: &mut egui::Ui, material: &Material) {
        let theta_i = self.theta_i_deg.to_radians();
        let cached = matches!(&self.slice, Some((m, t, _)) if m == material && *t == theta_i);
        if !cached {
            let s = slice(material, theta_i, 0.0, Quantity::ProjectedFr, Channel::Mean);
            self.slice = Some((material.clone(), theta_i, s));
        }
        let s = &self.slice.as_ref().expect("computed above").2;
        // θ_o signed in the plane of incidence, the light's side right,
        // as `gonio brdf` draws it (crate::explore::slice::polar).
        let lobe = s.polar_points();
        let peak = lobe
            .iter()
            .map(|p| p[0].hypot(p[1]))
            .fold(0.0_f64, f64::max)
            .max(s.dirac.unwrap_or(0.0))
            .max(1e-12);
        let incident = vec![light_marker(theta_i, peak), [0.0, 0.0]];
        ui.label("Polar slice: f_r·cos θ_o [1/sr] (mean of R, G, B)");
        Plot::new("slice")
            .width(ui.available_width() - 12.0)
            .height(170.0)
            .data_aspect(1.0)
            .allow_scroll(false)
            .legend(Legend::default())
            .show(ui, |p| {
                p.line(Line::new("f_r·cos θ_o", PlotPoints::from(lobe)));
                p.line(Line::new("light", PlotPoints::from(incident)));
                if let Some(d) = s.dirac {
                    p.points(
                        Points::new(
                            "mirror (Dirac) reflectance",
                            vec![mirror_marker(theta_i, d)],
                        )
                        .radius(4.0),
                    );
                }
            });
    }

    fn show_albedo(&self, ui: &mut egui::Ui, material: &Material) {
        let stale = if self.stale(material) {
            " (updating…)"
        } else {
            ""
        };
        ui.label(format!("Directional albedo ρ(θ_i), mean of R, G, B{stale}"));
        let curve: Vec<[f64; 2]> = self
            .integrals
            .iter()
            .flat_map(|i| &i.albedo)
            .map(|(deg, a)| [*deg, Channel::Mean.of(a.value)])
            .collect();
        Plot::new("albedo")
            .width(ui.available_width() - 12.0)
            .height(130.0)
            .include_y(0.0)
            .include_y(1.0)
            .allow_scroll(false)
            .x_axis_label("θ_i (°)")
            .show(ui, |p| {
                p.line(Line::new("ρ", PlotPoints::from(curve)));
            });
    }

    fn show_gloss(&self, ui: &mut egui::Ui, material: &Material) {
        let stale = if self.stale(material) {
            " (updating…)"
        } else {
            ""
        };
        ui.label(format!("Gloss meter (ISO 2813){stale}"));
        egui::Grid::new("gloss").striped(true).show(ui, |ui| {
            ui.label("angle");
            ui.label("reflectance Y");
            ui.label("gloss units");
            ui.end_row();
            if let Some(i) = &self.integrals {
                for r in &i.gloss {
                    ui.label(format!("{:.0}°", r.geometry.angle_deg));
                    ui.label(format!(
                        "{:.4}",
                        Channel::Luminance.of(r.aperture_reflectance)
                    ));
                    ui.label(format!("{:.1} GU", r.gloss_units));
                    ui.end_row();
                }
            }
        });
    }
}
