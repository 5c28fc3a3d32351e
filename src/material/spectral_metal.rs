//! The material key `spectral_metal`: a conductor whose Fresnel term the
//! f64 reference evaluates from the metal's published spectral `n(λ) +
//! i k(λ)` (Johnson & Christy 1972 for Au, Ag, Cu; 1974 for Fe; Rakić 1995
//! for Al), integrated per wavelength against the CIE 1931 observer
//! (`crate::reference::spectral`), where the three-channel presets
//! (`gold-rgb`, …, [`super::conductors`]) keep only three η, κ. The lecture:
//! η and κ depend on the wavelength.
//!
//! The material carries the name only; the spectral physics lives in the
//! reference (`reference::spectral::fresnel_tables`), which the material
//! does not import. What the key sets on the material is the metal's
//! three-channel preset (η, κ, `fresnel = "conductor"`): the GPU, which has
//! no spectral Fresnel, renders that preset, and so does every f64 path
//! that does not ask the reference for the spectral term.
//!
//! Combined with other keys (nothing typed is ignored without a word):
//! `preset` may only name the metal's own preset (`gold-rgb` with
//! `gold`: they agree, the preset is what the GPU renders, so a scene
//! written with the preset renders spectrally with one `--set`); `eta`,
//! `kappa`, their textures and a `fresnel` other than `conductor` are
//! refused (the reference would ignore them). A model without a Fresnel
//! term ([`super::table::Terms::fresnel`]) does not read the key: a
//! warning, as for any parameter the model does not read.

use super::conductors::Metal;
use super::{Fresnel, Material, ReflectanceModel};

/// The scene-file key.
pub const KEY: &str = "spectral_metal";

/// The keys a `spectral_metal` material refuses: what the reference's
/// spectral Fresnel would ignore.
const REFUSED: [&str; 4] = ["eta", "kappa", "eta_texture", "kappa_texture"];

/// Sets `metal` on `m`: its preset's η, κ, the exact conductor Fresnel,
/// and the name the reference reads.
pub fn set(m: &mut Material, metal: Metal) {
    metal.coloured().preset().apply(m);
    m.spectral_metal = Some(metal);
}

/// Whether `model` reads the key: its Fresnel term is selectable, so it
/// can be the exact conductor's (Cook-Torrance, the mirror).
pub fn applies(model: ReflectanceModel) -> bool {
    model.row().terms.fresnel
}

/// The keys given beside `spectral_metal = "metal"` checked against it:
/// `preset` as given, `given(k)` whether parameter or texture key `k` is
/// given, `fresnel` the Fresnel term as given. Else the problem.
pub fn check_keys(
    metal: Metal,
    preset: Option<&str>,
    given: impl Fn(&str) -> bool,
    fresnel: Option<&str>,
) -> Result<(), String> {
    let own = metal.preset_name();
    if let Some(p) = preset.filter(|p| *p != own) {
        return Err(format!(
            "`{KEY} = \"{metal}\"` sets η and κ to the preset `{own}` (the GPU renders it; the reference evaluates {metal}'s spectral Fresnel), but `preset = \"{p}\"` names other ones; remove `preset` or set it to \"{own}\""
        ));
    }
    if let Some(k) = REFUSED.into_iter().find(|k| given(k)) {
        return Err(format!(
            "`{k}` cannot be combined with `{KEY} = \"{metal}\"`: the reference evaluates {metal}'s Fresnel from its spectral table and the GPU its preset `{own}`, so `{k}` would be ignored; remove one of the two"
        ));
    }
    if let Some(f) = fresnel.filter(|f| *f != Fresnel::Conductor.name()) {
        return Err(format!(
            "`fresnel = \"{f}\"` cannot be combined with `{KEY} = \"{metal}\"`: the spectral table is the exact conductor Fresnel; remove `fresnel` or set it to \"conductor\""
        ));
    }
    Ok(())
}

/// Whether `m`'s spectral metal still describes it: its η, κ are the
/// preset's and its Fresnel the exact conductor's. An edit that changes
/// them (the viewer, `[gltf_materials]`) drops the metal.
pub fn still_holds(m: &Material) -> bool {
    let Some(metal) = m.spectral_metal else {
        return true;
    };
    let c = metal.coloured();
    m.fresnel == Fresnel::Conductor
        && m.eta.to_array() == c.eta
        && m.kappa.to_array() == c.kappa
        && !m.is_textured("eta")
        && !m.is_textured("kappa")
}
