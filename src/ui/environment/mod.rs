//! The environment map in the viewer, every part in one place: the
//! panel's Environment section ([`section`], a state struct with its
//! `ui`), the editor of the map's keys ([`editor`]), and the document's
//! environment edits, switching the map off and on and keeping the edits
//! across a reload ([`document`]).
//!
//! Inside the folder: `section -> editor document`, `editor -> document`.

pub mod document;
pub mod editor;
pub mod section;
