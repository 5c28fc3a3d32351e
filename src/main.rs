//! The `gonio` binary: see `gonio --help` and the README.

// The only unsafe code in gonio: one environment write before any thread
// exists (see below).
#![allow(unsafe_code)]

fn main() -> std::process::ExitCode {
    // Mesa's implicit Vulkan layer VK_LAYER_MESA_device_select connects to
    // a Wayland display to guess the default GPU, and without
    // XDG_RUNTIME_DIR (headless machines, CI) libwayland prints
    // "error: XDG_RUNTIME_DIR is invalid" several times per run. gonio picks
    // its adapter itself (--adapter, GONIO_ADAPTER), so the layer has nothing
    // to add there: switch it off unless the user set it either way.
    if std::env::var_os("XDG_RUNTIME_DIR").is_none()
        && std::env::var_os("NODEVICE_SELECT").is_none()
    {
        // SAFETY: first statement of main, before any other thread is
        // started, so no concurrent reader of the environment exists.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
    gonio::cli::main()
}
