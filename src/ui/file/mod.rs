//! The scene file in the viewer: the panel's File section ([`section`], a
//! state struct with its `ui`: the scene's title, open, reload,
//! screenshot and save) and the open-a-scene window it opens
//! ([`dialog`]).
//!
//! Inside the folder: `dialog -> section`. The section is handed the
//! document and where a replacing document goes ([`section::FileContext`]),
//! so nothing here uses the viewer's state.

pub mod dialog;
pub mod section;
