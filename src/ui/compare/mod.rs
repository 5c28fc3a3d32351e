//! Compare mode, every part in one place: the compared materials and the
//! split view's swap ([`materials`], which the document holds so that
//! they survive a reload), the panel's Compare section ([`section`], a
//! state struct with its `ui`: the fit model's choice and a fit under
//! way), its editor ([`editor`]) and the fits it adds ([`fitted`]).
//!
//! Inside the folder: `section -> editor materials fitted`,
//! `editor -> materials fitted`. Nothing here uses the document or the
//! viewer's state: the section is handed the compared materials, the
//! selected material and where to note changes, so the document (which
//! holds [`materials::Compare`]) stays below it.

pub mod editor;
pub mod fitted;
pub mod materials;
pub mod section;
