//! The viewer's memory stays flat across edits.
//!
//! A viewer session allocates and frees many blocks of a few to a hundred
//! MiB: GPU buffers and textures (lavapipe's device memory is host memory
//! from `malloc`), shadow cube maps, measured tables. glibc serves blocks
//! above its mmap threshold with `mmap` and returns them on `free`, but the
//! threshold is *dynamic*: freeing such a block raises it to the block's
//! size (up to 32 MiB), so later blocks of that size come from the heap,
//! where a freed hole stays resident while anything above it lives. The
//! soak test (tests/viewer_soak.rs) saw the resident set climb in steps
//! from 216 to 284 MiB over a run that edits every model, toggles a
//! shadowed light and switches measured tables, then stay there; with the
//! threshold fixed at 4 MiB it stays flat after the first cycle (206 →
//! 238 MiB, measured with `MALLOC_MMAP_THRESHOLD_`).
//!
//! Fixing the threshold (which also turns the dynamic rule off) at 4 MiB
//! keeps per-frame allocations (egui's meshes, uniforms: far smaller) on
//! the fast heap and puts every large block on its own mapping.

/// Blocks at least this large get their own mapping.
pub const MMAP_THRESHOLD: usize = 4 << 20;

/// Sets the allocator's mmap threshold to [`MMAP_THRESHOLD`] (glibc; a
/// no-op elsewhere). A user's `MALLOC_MMAP_THRESHOLD_` is respected.
#[allow(unsafe_code)] // One FFI call, no memory handed over (see below).
pub fn return_large_blocks_to_the_system() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if std::env::var_os("MALLOC_MMAP_THRESHOLD_").is_none() {
        // SAFETY: mallopt only sets a tuning parameter of the allocator;
        // it is called before the viewer's threads start.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD as libc::c_int);
        }
    }
}
