//! The lights as objects of the viewer, every part in one place: the
//! panel's Lights section ([`section`], a state struct with its `ui`; its
//! list [`list`] and one entry's editor [`editor`]), new lights and changes of kind ([`kinds`]; the
//! document's list edits, [`document`]), the lights drawn over the 3D view
//! ([`overlay`]) and dragged by their handles ([`drag`], reached by the
//! mouse through [`input`]), both placed with the scene's camera
//! ([`projection`]), and `--spin-lights` ([`spin`]).
//!
//! Inside the folder (`a -> b`: `a` uses `b`):
//!
//! ```text
//! input    -> section drag overlay projection
//! section  -> list drag
//! drag     -> overlay kinds projection
//! overlay  -> kinds projection
//! list     -> editor kinds
//! document -> kinds
//! editor   -> kinds
//! spin, kinds, projection -> nothing in lights/
//! ```

pub mod document;
pub mod drag;
pub mod editor;
pub mod input;
pub mod kinds;
pub mod list;
pub mod overlay;
pub mod projection;
pub mod section;
pub mod spin;
