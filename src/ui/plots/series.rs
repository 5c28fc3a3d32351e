//! What every view draws from: the plotted materials ([`Series`], each
//! with its [`colour`]), the settings all views share ([`Settings`]) and a
//! material's integrals ([`Integrals`]).

use crate::explore::Channel;
use crate::explore::albedo::AlbedoEstimate;
use crate::explore::gloss::GlossReading;
use crate::explore::slice::Quantity;
use crate::material::Material;

/// One plotted material: its name in the table and the material.
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub material: Material,
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
        }
    }
}

/// The albedo curve and gloss readings of one material at one φ_i.
pub struct Integrals {
    pub albedo: Vec<(f64, AlbedoEstimate)>,
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
