//! Unlit: no reflection, the surface shows its base colour as radiance
//! (glTF `KHR_materials_unlit`: "the material's base color is the final
//! color of the fragment"; contract "Other glTF material extensions").
//! WGSL twin: `shaders/brdf/unlit.wgsl`.
//!
//! The reflection equation of an unlit surface keeps only its own terms,
//! `L_o = L_e + k_a·L_a·o + b` (`crate::reference::shading`): every light
//! and the environment add nothing, as the extension asks. `L_e` and `k_a`
//! are every model's keys and default to 0; a glTF import leaves them 0
//! (the extension ignores `emissiveFactor`).

use crate::base::Rgb;

/// `f_r = 0`: no light and no environment reaches the viewer by
/// reflection.
pub fn unlit_f_r() -> Rgb {
    Rgb::ZERO
}

/// The radiance the surface shows, `L = b`, with the base colour's texture
/// and `COLOR_0` already multiplied into `b` (the effective material).
pub fn unlit_radiance(base_color: Rgb) -> Rgb {
    base_color
}
