//! The one way gonio writes an output file, and a set of them.
//!
//! A file appears complete or not at all: its bytes go to a temporary
//! `.gonio-PID-N.partial` in the destination's folder, which is renamed
//! over the destination only after everything succeeded. The temporary is
//! created before any work is done, so an unwritable destination fails
//! first; its name is the one the interrupt handler and the stale-file
//! sweep know ([`super::interrupt`]); it is created with mode 0644 (less
//! the umask), so the file that appears is an ordinary one however the
//! process ends.
//!
//! A destination that exists and is not a regular file is never replaced
//! (as root a rename would turn `/dev/null` into a regular file):
//! - a character device (`/dev/null`, `/dev/stdout` on a terminal) is
//!   written in place;
//! - a FIFO is written in place when a reader has it open, and refused
//!   when none has (the write would block for ever);
//! - a directory, block device or socket is refused;
//! - a symbolic link is followed: to a regular file, the file it points
//!   to is replaced atomically (the link stays); to anything else, the
//!   rules above apply to what it points to; a link to nothing is refused.
//!
//! A missing folder is an error, for every command alike (`-o
//! missing/dir/f.toml`); commands that fill a folder (`--out-dir`) create
//! it themselves.
//!
//! A set of files ([`commit_all`]) appears together: every temporary is
//! written and synced before the first rename, so a full disk or any
//! other write error leaves none of them.

use super::interrupt;
use crate::{Error, Result};
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A file that appears complete or not at all (module docs).
pub struct AtomicFile {
    /// The path the user gave (for messages).
    path: PathBuf,
    target: Target,
}

enum Target {
    /// A new file at `temp`, renamed to `dest` on commit.
    Replace {
        file: File,
        temp: PathBuf,
        dest: PathBuf,
        /// Declared after `file`: unregistered once the file is gone.
        _pending: interrupt::Pending,
        /// Removed on drop unless committed.
        armed: bool,
    },
    /// An existing device or FIFO, written as it is.
    InPlace { file: File },
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Target::Replace { temp, armed, .. } = &self.target
            && *armed
        {
            let _ = std::fs::remove_file(temp);
        }
    }
}

impl AtomicFile {
    /// Claims `path` for a new file (module docs for what it may be).
    pub fn create(path: &Path) -> Result<Self> {
        let refuse = |why: &str| Err(Error::output(path, why.to_string()));
        let dest = match std::fs::symlink_metadata(path) {
            Err(_) => path.to_path_buf(),
            Ok(meta) if meta.file_type().is_symlink() => match std::fs::canonicalize(path) {
                Ok(real) => real,
                Err(_) => {
                    return refuse(
                        "it is a symbolic link to nothing; remove it or name the file itself",
                    );
                }
            },
            Ok(_) => path.to_path_buf(),
        };
        if let Ok(meta) = std::fs::metadata(&dest) {
            let kind = meta.file_type();
            if kind.is_dir() {
                return refuse("it is a directory");
            }
            if !kind.is_file() {
                return Self::in_place(path, &dest, kind);
            }
        }
        let dir = match dest.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !dir.is_dir() {
            return refuse(&format!(
                "the folder {} does not exist (gonio does not create folders for -o; create it first)",
                dir.display()
            ));
        }
        interrupt::remove_stale(dir);
        let (file, temp, pending) = create_temporary(dir).map_err(|e| {
            Error::output(
                path,
                format!("cannot create a file in {}: {e}", dir.display()),
            )
        })?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            target: Target::Replace {
                file,
                temp,
                dest,
                _pending: pending,
                armed: true,
            },
        })
    }

    /// A destination that is a device or a FIFO: opened for writing as it
    /// is, or refused.
    fn in_place(path: &Path, dest: &Path, kind: std::fs::FileType) -> Result<Self> {
        let refuse = |why: String| Err(Error::output(path, why));
        #[cfg(unix)]
        {
            use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
            if kind.is_char_device() {
                let file = OpenOptions::new()
                    .write(true)
                    .open(dest)
                    .map_err(|e| Error::output(path, format!("cannot write to the device: {e}")))?;
                return Ok(AtomicFile {
                    path: path.to_path_buf(),
                    target: Target::InPlace { file },
                });
            }
            if kind.is_fifo() {
                // A non-blocking open fails (ENXIO) without a reader
                // instead of waiting for ever; with one, the ordinary
                // (blocking) open below returns at once.
                let probe = OpenOptions::new()
                    .write(true)
                    .custom_flags(libc::O_NONBLOCK)
                    .open(dest)
                    .map_err(|e| {
                        Error::output(
                            path,
                            format!("it is a FIFO (named pipe) that no process reads ({e})"),
                        )
                    })?;
                let file = OpenOptions::new()
                    .write(true)
                    .open(dest)
                    .map_err(|e| Error::output(path, format!("cannot write to the FIFO: {e}")))?;
                drop(probe);
                return Ok(AtomicFile {
                    path: path.to_path_buf(),
                    target: Target::InPlace { file },
                });
            }
            if kind.is_block_device() {
                return refuse(
                    "it is a block device (a disk); gonio writes files, not disks".into(),
                );
            }
            if kind.is_socket() {
                return refuse("it is a socket; name a file".into());
            }
        }
        let _ = (dest, kind);
        refuse("it exists and is not a regular file; name a file".into())
    }

    /// The path the user gave.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes `bytes`, syncs, and moves the file into place.
    pub fn commit(self, bytes: &[u8]) -> Result<()> {
        commit_all(vec![(self, bytes)])
    }

    /// Writes `bytes` to the temporary file and syncs it (a replaced
    /// file); an in-place destination is written by [`Self::finish`].
    fn stage(&mut self, bytes: &[u8]) -> Result<()> {
        if let Target::Replace { file, .. } = &mut self.target {
            let fail = |e: std::io::Error| Error::output(&self.path, e.to_string());
            file.write_all(bytes).map_err(fail)?;
            file.sync_all().map_err(fail)?;
        }
        Ok(())
    }

    /// Writes an in-place destination.
    fn write_in_place(&mut self, bytes: &[u8]) -> Result<()> {
        if let Target::InPlace { file } = &mut self.target {
            let fail = |e: std::io::Error| Error::output(&self.path, e.to_string());
            file.write_all(bytes).map_err(fail)?;
            file.flush().map_err(fail)?;
        }
        Ok(())
    }

    /// Moves a staged temporary into place.
    fn rename(&mut self) -> Result<()> {
        if let Target::Replace {
            temp, dest, armed, ..
        } = &mut self.target
        {
            std::fs::rename(&*temp, &*dest)
                .map_err(|e| Error::output(&self.path, e.to_string()))?;
            *armed = false;
        }
        Ok(())
    }
}

/// Writes a set of files so that they appear together or not at all:
/// every temporary is written and synced, then the in-place destinations
/// (devices, FIFOs) are written, then the temporaries are renamed into
/// place. The first error stops it, and the temporaries not yet renamed
/// are removed.
pub fn commit_all<B: AsRef<[u8]>>(files: Vec<(AtomicFile, B)>) -> Result<()> {
    let mut files = files;
    for (file, bytes) in &mut files {
        file.stage(bytes.as_ref())?;
    }
    for (file, bytes) in &mut files {
        file.write_in_place(bytes.as_ref())?;
    }
    for (file, _) in &mut files {
        file.rename()?;
    }
    Ok(())
}

/// Creates `dir/.gonio-PID-N.partial` (new, mode 0644 less the umask) and
/// registers it with the interrupt handler.
fn create_temporary(dir: &Path) -> std::io::Result<(File, PathBuf, interrupt::Pending)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(
            "{}{n}{}",
            interrupt::own_prefix(),
            interrupt::SUFFIX
        ));
        // Registered before it exists: a signal between the two removes
        // nothing, one after removes it.
        let pending = interrupt::Pending::register(&temp);
        let mut options = OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            options.mode(0o644);
        }
        match options.open(&temp) {
            Ok(file) => return Ok((file, temp, pending)),
            // Left by an earlier process with this id, or another thread.
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_set_appears_together_and_a_dropped_file_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let a = AtomicFile::create(&dir.path().join("a.txt")).unwrap();
        let b = AtomicFile::create(&dir.path().join("b.txt")).unwrap();
        assert_eq!(names(dir.path()).len(), 2, "two temporaries");
        assert!(names(dir.path()).iter().all(|n| n.starts_with(".gonio-")));
        commit_all(vec![(a, b"1".as_slice()), (b, b"2".as_slice())]).unwrap();
        assert_eq!(names(dir.path()), ["a.txt", "b.txt"]);
        drop(AtomicFile::create(&dir.path().join("c.txt")).unwrap());
        assert_eq!(names(dir.path()), ["a.txt", "b.txt"]);
    }

    #[cfg(unix)]
    #[test]
    fn the_final_file_is_not_private() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.txt");
        AtomicFile::create(&path).unwrap().commit(b"x").unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o644 & !umask(), "mode {mode:o}");
    }

    /// The process's umask, from `/proc/self/status` (Linux); 0o022
    /// where that is not there.
    #[cfg(unix)]
    fn umask() -> u32 {
        std::fs::read_to_string("/proc/self/status")
            .ok()
            .and_then(|s| {
                let line = s.lines().find(|l| l.starts_with("Umask:"))?;
                u32::from_str_radix(line["Umask:".len()..].trim(), 8).ok()
            })
            .unwrap_or(0o022)
    }

    #[test]
    fn a_missing_folder_is_named_without_the_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let err = AtomicFile::create(&dir.path().join("missing/dir/f.toml"))
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("does not exist"), "{err}");
        assert!(
            !err.contains(".partial") && !err.contains(".gonio-"),
            "{err}"
        );
        assert!(!dir.path().join("missing").exists());
    }

    #[cfg(unix)]
    #[test]
    fn dev_null_is_written_in_place() {
        AtomicFile::create(Path::new("/dev/null"))
            .unwrap()
            .commit(b"x")
            .unwrap();
        let err = AtomicFile::create(Path::new("/dev/full"))
            .unwrap()
            .commit(b"x")
            .unwrap_err()
            .to_string();
        assert!(err.contains("/dev/full"), "{err}");
        assert!(Path::new("/dev/full").exists());
    }
}
