//! The side panel's Plots section: the selected material and the compared
//! ones plotted ([`super::Plots`]) as the renderers evaluate them, as
//! `gonio brdf` does (`crate::explore::spec`): roughness no smaller than
//! the floor. Unfloored, a roughness of 1e-6 kept the albedo worker busy
//! for minutes.

use super::{Plots, Series};
use crate::material::{Material, ROUGHNESS_FLOOR};

/// The Plots section's state: the plots' settings and cached results.
#[derive(Default)]
pub struct PlotsSection {
    pub plots: Plots,
}

impl PlotsSection {
    /// Lays out the section for the `selected` material (nothing without
    /// one) and the `compared` ones.
    pub fn ui(&mut self, ui: &mut egui::Ui, selected: Option<&Material>, compared: &[Material]) {
        let Some(given) = selected else {
            return;
        };
        let mut series = vec![floored_series(given)];
        series.extend(compared.iter().map(floored_series));
        if series.iter().any(|s| s.1) {
            ui.label(format!(
                "Roughness below the floor {ROUGHNESS_FLOOR:e}: plotted at the floor, as rendered."
            ));
        }
        let series: Vec<Series> = series.into_iter().map(|s| s.0).collect();
        self.plots.show(ui, &series);
    }

    /// Whether the plots' background integrals are under way (the window
    /// waits for their results).
    pub fn busy(&self) -> bool {
        self.plots.busy()
    }
}

/// A plotted material (floored) and whether the floor changed it.
fn floored_series(m: &Material) -> (Series, bool) {
    let floored = m.with_roughness_floor(0.0);
    let changed = floored != *m;
    (Series::whole(m.name.clone(), floored), changed)
}
