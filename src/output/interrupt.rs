//! Interrupted writes leave nothing behind.
//!
//! Every file gonio writes goes through a temporary `.gonio-PID-XXXX.partial`
//! in the destination's folder ([`super::AtomicFile`]). Dropping it removes
//! it, but a signal ends the process without running destructors, and an
//! interrupted 4096² reference render left its partial file behind for
//! SIGINT, SIGTERM and SIGHUP alike. Two remedies:
//! - **Catchable signals**: the temporaries alive are registered here, and
//!   a thread waiting on SIGINT, SIGTERM and SIGHUP (`signal-hook`, which
//!   does the async-signal-safe part) removes them, then lets the signal
//!   take its default action, so the exit status still says "killed by".
//! - **SIGKILL** cannot be caught: the temporary's name carries the
//!   writer's process id, and the next write into the same folder removes
//!   the partial files whose process is gone (Linux: `/proc/PID`), naming
//!   each on stderr. A live writer's file is never touched, so concurrent
//!   writers into one folder stay safe.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, Once};

/// The prefix of every temporary file gonio writes.
pub const PREFIX: &str = ".gonio-";
/// The suffix of every temporary file gonio writes.
pub const SUFFIX: &str = ".partial";

/// Temporaries that a signal must remove.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
static HANDLER: Once = Once::new();

/// The prefix of this process's temporaries: `.gonio-PID-`.
pub fn own_prefix() -> String {
    format!("{PREFIX}{}-", std::process::id())
}

/// Removes `path` when the process is interrupted, until [`Pending`] drops.
pub struct Pending(PathBuf);

impl Pending {
    /// Registers `path` (and installs the signal handler on first use).
    pub fn register(path: &Path) -> Pending {
        HANDLER.call_once(install_handler);
        lock().push(path.to_path_buf());
        Pending(path.to_path_buf())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        let mut pending = lock();
        if let Some(i) = pending.iter().position(|p| *p == self.0) {
            pending.swap_remove(i);
        }
    }
}

fn lock() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A panic while holding the lock leaves a valid Vec behind.
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

#[cfg(unix)]
fn install_handler() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return; // Without the handler only the SIGKILL remedy remains.
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            for path in lock().drain(..) {
                let _ = std::fs::remove_file(path);
            }
            let _ = signal_hook::low_level::emulate_default_handler(signal);
            // Only reached if the default action does not end the process.
            std::process::exit(128 + signal);
        }
    });
}

#[cfg(not(unix))]
fn install_handler() {}

/// Removes the partial files in `dir` that a killed gonio left behind
/// (their process is gone), saying so on stderr.
pub fn remove_stale(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(writer_pid) else {
            continue;
        };
        if pid != std::process::id() && !process_alive(pid) {
            let path = entry.path();
            if std::fs::remove_file(&path).is_ok() {
                eprintln!(
                    "gonio: removed {}, left by an interrupted gonio (process {pid} is gone)",
                    path.display()
                );
            }
        }
    }
}

/// The process id in a temporary's name `.gonio-PID-XXXX.partial`.
fn writer_pid(name: &str) -> Option<u32> {
    let middle = name.strip_prefix(PREFIX)?.strip_suffix(SUFFIX)?;
    middle.split_once('-')?.0.parse().ok()
}

#[cfg(target_os = "linux")]
fn process_alive(pid: u32) -> bool {
    Path::new(&format!("/proc/{pid}")).exists()
}

/// Without `/proc` a process cannot be checked cheaply: assume it lives.
#[cfg(not(target_os = "linux"))]
fn process_alive(_pid: u32) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_writers_pid_is_read_from_the_name() {
        assert_eq!(writer_pid(".gonio-123-AbC9.partial"), Some(123));
        assert_eq!(writer_pid(".gonio-AbC9.partial"), None);
        assert_eq!(writer_pid(".gonio-123-AbC9.png"), None);
        assert_eq!(writer_pid("gonio-123-AbC9.partial"), None);
    }

    #[test]
    fn stale_files_go_and_live_ones_stay() {
        let dir = tempfile::tempdir().unwrap();
        // No process has the largest pid Linux allows (4194304) + 1.
        let stale = dir.path().join(".gonio-4194305-x.partial");
        let live = dir.path().join(format!("{}x.partial", own_prefix()));
        let other = dir.path().join(".gonio-x.partial");
        for p in [&stale, &live, &other] {
            std::fs::write(p, b"").unwrap();
        }
        remove_stale(dir.path());
        assert_eq!(!stale.exists(), cfg!(target_os = "linux"));
        assert!(live.exists() && other.exists());
    }

    #[test]
    fn pending_files_are_registered_until_dropped() {
        let path = PathBuf::from("/nonexistent/.gonio-1-x.partial");
        let pending = Pending::register(&path);
        assert!(lock().contains(&path));
        drop(pending);
        assert!(!lock().contains(&path));
    }
}
