//! The WGSL sources, embedded at build time so the binary is
//! self-contained (`build.rs` lists every file under `shaders/`: a new
//! file is embedded by being there), each reachable by its path under
//! `shaders/` ([`by_path`], [`get`]: how the model table names a model's
//! files).

include!(concat!(env!("OUT_DIR"), "/embedded_shaders.rs"));

/// The embedded file at `path` relative to `shaders/` (e.g.
/// `"brdf/phong.wgsl"`), if there is one.
pub fn by_path(path: &str) -> Option<&'static str> {
    ALL.iter().find(|(p, _)| *p == path).map(|(_, text)| *text)
}

/// The embedded file at `path` relative to `shaders/`; panics if there is
/// none (the paths gonio names are fixed at build time, and the tests
/// compose every file: a missing one is a bug, not an input error).
pub fn get(path: &str) -> &'static str {
    by_path(path).unwrap_or_else(|| panic!("shaders/{path} is not embedded"))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Every `.wgsl` file under `shaders/`, relative to it.
    pub(crate) fn files_on_disk() -> Vec<String> {
        fn walk(dir: &std::path::Path, root: &std::path::Path, out: &mut Vec<String>) {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    walk(&path, root, out);
                } else if path.extension().is_some_and(|e| e == "wgsl") {
                    let relative = path.strip_prefix(root).unwrap();
                    out.push(relative.to_string_lossy().replace('\\', "/"));
                }
            }
        }
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut out = Vec::new();
        walk(&root, &root, &mut out);
        out.sort();
        out
    }

    #[test]
    fn every_file_under_shaders_is_embedded() {
        for path in files_on_disk() {
            assert!(
                by_path(&path).is_some(),
                "shaders/{path} is not embedded (build.rs)"
            );
        }
        assert!(get("brdf/phong.wgsl").contains("fn phong_lecture"));
        assert_eq!(by_path("brdf/none.wgsl"), None);
    }
}
