//! What every view draws from: the plotted materials ([`Series`], each
//! with its [`colour`]), the settings all views share ([`Settings`]) and a
//! material's integrals ([`Integrals`]).

use crate::explore::albedo::AlbedoEstimate;
use crate::explore::gloss::GlossReading;
use crate::explore::slice::Quantity;
use crate::explore::{Channel, LayerChoice, MaterialPart};
use crate::material::Material;
use crate::material::layers::LayerTerm;

/// One plotted material: its name in the table, the material and the
/// term of its `f_r` drawn (the whole, or one layer's: `plots.layer`).
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub material: Material,
    pub term: LayerTerm,
}

impl Series {
    /// The whole of `material`.
    pub fn whole(label: String, material: Material) -> Series {
        Series {
            label,
            material,
            term: LayerTerm::All,
        }
    }

    /// What the explorer evaluates.
    pub fn part(&self) -> MaterialPart<'_> {
        MaterialPart::new(&self.material, self.term)
    }

    /// The series `layer` makes of the materials `series`: each
    /// material's chosen term, or (`each`) its whole and every term it
    /// has, labelled `name [term]`.
    pub fn terms(series: &[Series], layer: LayerChoice) -> Vec<Series> {
        series
            .iter()
            .flat_map(|one| {
                layer.terms(&one.material).into_iter().map(|term| Series {
                    label: crate::explore::part::term_label(&one.label, term),
                    material: one.material.clone(),
                    term,
                })
            })
            .collect()
    }
}

/// What the plots show: the incidence direction and how values are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Incidence polar angle, degrees from the normal.
    pub theta_i_deg: f64,
    /// Incidence azimuth, degrees from the tangent (anisotropic models).
    pub phi_i_deg: f64,
    /// `f_r` or `f_r · cos θ_o` as the slice's radius.
    pub quantity: Quantity,
    /// Which number of RGB is drawn (mean, luminance, R, G or B).
    pub channel: Channel,
    /// Logarithmic radius over `decades` decades.
    pub log: bool,
    pub decades: u32,
    /// The θ_h × θ_d image's difference azimuth, degrees.
    pub phi_d_deg: f64,
    /// Which term of a layered material is drawn: the whole, one layer's
    /// term, or each apart.
    pub layer: LayerChoice,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            theta_i_deg: 45.0,
            phi_i_deg: 0.0,
            quantity: Quantity::ProjectedFr,
            channel: Channel::Mean,
            log: false,
            decades: 6,
            phi_d_deg: 90.0,
            layer: LayerChoice::default(),
        }
    }
}

/// The albedo curve and gloss readings of one material at one φ_i.
pub struct Integrals {
    pub albedo: Vec<(f64, AlbedoEstimate)>,
    /// The transmitted albedo `τ(θ_i)` at the same angles, for a material
    /// that lets light through (`MaterialPart::transmits`); empty
    /// otherwise.
    pub transmitted: Vec<(f64, AlbedoEstimate)>,
    pub gloss: Vec<GlossReading>,
}

/// The colour of series `i` (the selected material first), the same in
/// every plot and in the table.
pub fn colour(i: usize) -> egui::Color32 {
    const PALETTE: [egui::Color32; 6] = [
        egui::Color32::from_rgb(90, 170, 255),
        egui::Color32::from_rgb(255, 150, 60),
        egui::Color32::from_rgb(110, 205, 110),
        egui::Color32::from_rgb(225, 110, 225),
        egui::Color32::from_rgb(235, 215, 80),
        egui::Color32::from_rgb(90, 220, 220),
    ];
    PALETTE[i % PALETTE.len()]
}
