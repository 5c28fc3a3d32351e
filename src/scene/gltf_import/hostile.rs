//! What every step of the import shares against hostile files: a panic
//! inside the `gltf` crate made into an error ([`guarded`]), and text from
//! the file cut short for messages ([`abbreviate`]).

use std::borrow::Cow;

/// The prefix of a note that is a warning ([`crate::scene::scene_file::WARNING`]).
pub(super) const WARNING: &str = "warning: ";

/// Message for a panic caught inside the `gltf` crate.
pub(super) const PARSER_PANICKED: &str = "the glTF parser failed on malformed data";

/// Runs `f`, turning a panic into the "malformed data" error. Only code of
/// the `gltf` crate (and the Draco decoder) is expected to panic here, and
/// only on inputs our own checks did not anticipate.
/// The panic's own message stays off stderr (the user gets the error,
/// not "thread 'main' panicked at …gltf…": `base::quiet_panic`).
pub(super) fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    crate::base::quiet_panic::catch_quietly(f).ok_or_else(|| PARSER_PANICKED.to_string())
}

/// The first 80 characters of a text from the file, for messages (data:
/// URIs can be megabytes long).
pub(super) fn abbreviate(text: &str) -> Cow<'_, str> {
    const KEEP: usize = 80;
    match text.char_indices().nth(KEEP) {
        Some((cut, _)) => Cow::Owned(format!("{}…", &text[..cut])),
        None => Cow::Borrowed(text),
    }
}
