//! Third-party decoders (the `gltf` crate, Draco, Basis Universal) can
//! panic on malformed data their authors did not anticipate. gonio turns
//! such a panic into an error naming the file; the panic's own text
//! ("thread 'main' panicked at …") must not reach the user first.

use std::panic::{self, AssertUnwindSafe};

thread_local!(static QUIET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) });

/// Runs `f`; a panic inside it becomes `None`, with the process's panic
/// hook silent on this thread while `f` runs (the hook is wrapped once;
/// panics elsewhere still print).
pub fn catch_quietly<T>(f: impl FnOnce() -> T) -> Option<T> {
    static WRAP_HOOK: std::sync::Once = std::sync::Once::new();
    WRAP_HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(|q| q.get()) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    result.ok()
}
