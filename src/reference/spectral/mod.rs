//! Spectral truth for the three-channel forms: the thin film of
//! `KHR_materials_iridescence` and the coloured conductor presets, each
//! evaluated per wavelength (380–780 nm, 5 nm) from its physics and
//! integrated against the CIE 1931 observer under D65 to linear Rec.709,
//! then compared with what the renderer evaluates in three channels.
//!
//! [`cie`] integrates a spectrum to a colour; [`metals`] holds the
//! published `n(λ) + i k(λ)`; [`thin_film`] is the Airy reflectance of a
//! film and the error of the specification's RGB form; [`conductors`] the
//! exact Fresnel of the metals and the error of their three-channel
//! presets, and [`fresnel_tables`] that Fresnel tabulated over the angle
//! for rendering (the material key `spectral_metal`); [`error_table`] the
//! statistics both report; [`film_plot`]
//! draws the film's colour against thickness; [`complex`] the arithmetic
//! of complex indices. Results: `docs/spectral.md`.

pub mod cie;
pub mod complex;
pub mod conductors;
pub mod error_table;
pub mod film_plot;
pub mod fresnel_tables;
pub mod metals;
pub mod thin_film;
