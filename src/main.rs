//! The `gonio` binary: see `gonio --help` and the README.

fn main() -> std::process::ExitCode {
    gonio::cli::main()
}
