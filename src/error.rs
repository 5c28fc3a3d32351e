//! One error type for the whole crate.
//!
//! Every failure a user can cause (a bad file, a bad parameter, an
//! unwritable output, no GPU) becomes one of these, is printed as one
//! paragraph that names the file or argument and the problem, and makes the
//! process exit with status 2 (see [`Error::exit_code`]).

use std::path::{Path, PathBuf};

/// Result alias used across gonio.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with enough context to name the culprit.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An input file (scene `.toml`, `.gltf`, `.glb`, a buffer) is unusable.
    #[error("{}: {problem}", path.display())]
    Input { path: PathBuf, problem: String },
    /// A command-line argument is unusable (e.g. an unknown `--set` key).
    #[error("{argument}: {problem}")]
    Argument { argument: String, problem: String },
    /// The output file cannot be written.
    #[error("{}: cannot write the output: {problem}", path.display())]
    Output { path: PathBuf, problem: String },
    /// No GPU adapter, or the requested one is not there.
    #[error("{0}")]
    NoAdapter(String),
    /// The viewer cannot open a window (no display server).
    #[error("{0}")]
    NoDisplay(String),
    /// The scene as assembled cannot be rendered (no material, no light):
    /// the input's fault, so exit status 2 like every input error.
    #[error("the scene cannot be rendered: {0}")]
    Scene(String),
    /// The GPU failed while rendering (device lost, out of memory, ...).
    #[error("GPU error: {0}")]
    Gpu(String),
}

impl Error {
    /// An input-file error.
    pub fn input(path: impl AsRef<Path>, problem: impl Into<String>) -> Self {
        Error::Input {
            path: path.as_ref().to_path_buf(),
            problem: clip(problem.into(), MAX_PROBLEM_CHARS),
        }
    }

    /// A command-line argument error.
    pub fn argument(argument: impl Into<String>, problem: impl Into<String>) -> Self {
        Error::Argument {
            argument: clip(argument.into(), MAX_ARGUMENT_CHARS),
            problem: clip(problem.into(), MAX_PROBLEM_CHARS),
        }
    }

    /// An output error.
    pub fn output(path: impl AsRef<Path>, problem: impl Into<String>) -> Self {
        Error::Output {
            path: path.as_ref().to_path_buf(),
            problem: problem.into(),
        }
    }

    /// The process exit status for this error: 2 for everything the user
    /// can fix (bad input, bad arguments, missing adapter), 1 for GPU
    /// failures that are not the input's fault.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Gpu(_) => 1,
            _ => 2,
        }
    }
}

/// Longest problem text kept. Messages quote values from the input, and a
/// hostile input's values can be megabytes long; a message must stay a
/// readable paragraph.
const MAX_PROBLEM_CHARS: usize = 1000;
/// Longest argument text kept (a `--set` can be as long as the OS allows).
const MAX_ARGUMENT_CHARS: usize = 200;

/// `text` if it has at most `max` characters; otherwise its beginning and
/// end around ` … `, since both usually matter (what is wrong, and what was
/// expected).
fn clip(text: String, max: usize) -> String {
    let count = text.chars().count();
    if count <= max {
        return text;
    }
    let tail = max / 4;
    let head: String = text.chars().take(max - tail).collect();
    let end: String = text.chars().skip(count - tail).collect();
    format!("{head} … {end}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Only a GPU failure that is not the input's fault exits with 1; a
    /// scene that cannot be rendered (no material, no light) is input.
    #[test]
    fn input_errors_exit_with_2() {
        assert_eq!(Error::Scene("no light".into()).exit_code(), 2);
        assert_eq!(Error::input("f.toml", "bad").exit_code(), 2);
        assert_eq!(Error::argument("--set", "bad").exit_code(), 2);
        assert_eq!(Error::Gpu("device lost".into()).exit_code(), 1);
    }

    #[test]
    fn long_problems_are_clipped_at_both_ends() {
        let long = format!("start {} end", "x".repeat(10_000));
        let e = Error::input("f.toml", long).to_string();
        assert!(e.starts_with("f.toml: start xxx"), "{e}");
        assert!(e.ends_with("xxx end"), "{e}");
        assert!(e.contains(" … ") && e.chars().count() < 1100, "{e}");
        assert_eq!(clip("short".into(), 10), "short");
    }
}
