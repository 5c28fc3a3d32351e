//! Embeds every `.wgsl` file under `shaders/` into the binary (a list of
//! `(path relative to shaders/, include_str!(...))`, included by
//! `src/gpu/shader_gen/sources.rs`), so a new shader file — a new model's
//! WGSL twin — is embedded by being there, with no list to extend.

use std::fmt::Write;
use std::path::{Path, PathBuf};

fn main() {
    let root = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap()).join("shaders");
    println!("cargo:rerun-if-changed={}", root.display());
    let mut files = Vec::new();
    walk(&root, &root, &mut files);
    files.sort();
    let mut out = String::from(
        "/// Every `.wgsl` file under `shaders/`, sorted by path: (path relative\n/// to `shaders/`, text).\npub const ALL: &[(&str, &str)] = &[\n",
    );
    for (relative, absolute) in &files {
        writeln!(out, "    ({relative:?}, include_str!({absolute:?})),").unwrap();
    }
    out.push_str("];\n");
    let dest = PathBuf::from(std::env::var_os("OUT_DIR").unwrap()).join("embedded_shaders.rs");
    std::fs::write(dest, out).unwrap();
}

/// The `.wgsl` files under `dir` as (path relative to `root` with `/`,
/// absolute path); every folder is watched for new files.
fn walk(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            walk(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            println!("cargo:rerun-if-changed={}", path.display());
            let relative = path
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push((relative, path.display().to_string()));
        }
    }
}
