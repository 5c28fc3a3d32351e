//! The one way gonio reads an input file: a regular file, of bounded size.
//!
//! Every input path a user names (scene files, glTF files and their
//! buffers and images, textures, environment maps, MERL tables, fit
//! shards) goes through [`read_regular_file`] or [`open_regular_file`]:
//! a FIFO would block the open until a writer appears, a device such as
//! `/dev/zero` never ends, and a symbolic link may point at either, so the
//! type is checked before opening and again on the open handle (what is
//! read is the file that was checked); the size is checked against a cap
//! the caller derives from `--limit bytes` or the format's largest file,
//! and the read itself is capped in case the file grows.

use std::fs::{self, File};
use std::io::Read;
use std::path::Path;

/// Why [`read_regular_file`] failed.
#[derive(Debug)]
pub enum ReadError {
    /// Not there, not permitted, an I/O error: the message.
    Io(String),
    /// A directory, FIFO, device or other special file.
    NotRegular,
    /// Larger than the cap given; its size in bytes.
    TooLarge(u64),
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::Io(e) => write!(f, "cannot read the file: {e}"),
            ReadError::NotRegular => {
                f.write_str("is not a regular file (a directory, FIFO, device or socket)")
            }
            ReadError::TooLarge(len) => write!(f, "the file has {len} bytes, too many"),
        }
    }
}

/// Opens an input file that must be a regular file of at most `max_bytes`
/// bytes; the open file and its size.
pub fn open_regular_file(path: &Path, max_bytes: u64) -> Result<(File, u64), ReadError> {
    let io = |e: std::io::Error| ReadError::Io(e.to_string());
    require_regular(&fs::metadata(path).map_err(io)?, max_bytes)?;
    let file = File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    require_regular(&meta, max_bytes)?;
    Ok((file, meta.len()))
}

/// Reads a whole input file that must be a regular file of at most
/// `max_bytes` bytes ([`open_regular_file`]).
pub fn read_regular_file(path: &Path, max_bytes: u64) -> Result<Vec<u8>, ReadError> {
    let (file, len) = open_regular_file(path, max_bytes)?;
    let mut bytes = Vec::new();
    // Reserve what the file has now, which the check above bounded.
    bytes
        .try_reserve_exact(len as usize)
        .map_err(|e| ReadError::Io(e.to_string()))?;
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| ReadError::Io(e.to_string()))?;
    if bytes.len() as u64 > max_bytes {
        return Err(ReadError::TooLarge(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read_regular_file`] of a text file, which must be UTF-8.
pub fn read_regular_text(path: &Path, max_bytes: u64) -> Result<String, ReadError> {
    String::from_utf8(read_regular_file(path, max_bytes)?)
        .map_err(|e| ReadError::Io(format!("it is not UTF-8 text ({e})")))
}

fn require_regular(meta: &fs::Metadata, max_bytes: u64) -> Result<(), ReadError> {
    if !meta.is_file() {
        return Err(ReadError::NotRegular);
    }
    if meta.len() > max_bytes {
        return Err(ReadError::TooLarge(meta.len()));
    }
    Ok(())
}

/// The message for a declared amount over its limit: names what, how much,
/// the limit, and the flag that raises it.
pub fn exceeded(what: &str, amount: impl std::fmt::Display, key: &str, limit: u64) -> String {
    format!(
        "{what} is {amount}, over the limit of {limit} (raise it with `--limit {key}=N` if the file is trusted)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn special_files_are_refused() {
        for path in ["/dev/zero", "/dev/null", "/"] {
            let err = read_regular_file(Path::new(path), 1 << 20).unwrap_err();
            assert!(matches!(err, ReadError::NotRegular), "{path}: {err}");
        }
    }

    #[test]
    fn size_is_capped() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        fs::write(&path, [0u8; 100]).unwrap();
        assert_eq!(read_regular_file(&path, 100).unwrap().len(), 100);
        let err = read_regular_file(&path, 99).unwrap_err();
        assert!(matches!(err, ReadError::TooLarge(100)), "{err}");
    }
}
