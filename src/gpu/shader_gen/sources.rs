//! The WGSL sources, embedded at build time so the binary is
//! self-contained, each also reachable by its path under `shaders/`
//! ([`by_path`]: how the model table names a model's files).

/// One embedded file: its path relative to `shaders/` and its text.
macro_rules! embedded {
    ($($name:ident = $path:literal,)+) => {
        $(
            #[doc = concat!("`shaders/", $path, "`.")]
            pub const $name: &str = include_str!(concat!("../../../shaders/", $path));
        )+

        /// Every embedded file as `(path relative to shaders/, text)`.
        pub const ALL: &[(&str, &str)] = &[$(($path, $name),)+];
    };
}

embedded! {
    COMMON = "common.wgsl",
    SURFACE = "surface.wgsl",
    BRDF_VARIANT = "brdf/variant.wgsl",
    BRDF_LAMBERT = "brdf/lambert.wgsl",
    BRDF_PHONG = "brdf/phong.wgsl",
    BRDF_FRESNEL = "brdf/fresnel.wgsl",
    BRDF_MICROFACET = "brdf/microfacet.wgsl",
    BRDF_WARD = "brdf/ward.wgsl",
    BRDF_EVAL = "brdf/eval.wgsl",
    LIGHT_INVERSE_SQUARE = "lights/inverse_square.wgsl",
    LIGHT_POINT = "lights/point.wgsl",
    LIGHT_DIRECTIONAL = "lights/directional.wgsl",
    LIGHT_SPOT = "lights/spot.wgsl",
    LIGHT_AREA_SAMPLE = "lights/area_sample.wgsl",
    SHADOW_LOOKUP = "shadows.wgsl",
    SHADOW_PASS = "shadow_pass.wgsl",
    SHADING = "shading.wgsl",
    RASTER_VERTEX_SHADED = "raster_vertex_shaded.wgsl",
    RASTER_PIXEL_SHADED = "raster_pixel_shaded.wgsl",
}

/// The BRDF term and model files in dependency order (each may use the
/// ones before); a scene's shader includes those its models need, in this
/// order.
pub const BRDF_ORDER: [&str; 5] = [
    "brdf/lambert.wgsl",
    "brdf/phong.wgsl",
    "brdf/fresnel.wgsl",
    "brdf/microfacet.wgsl",
    "brdf/ward.wgsl",
];

/// The embedded file at `path` relative to `shaders/` (e.g.
/// `"brdf/phong.wgsl"`), if there is one.
pub fn by_path(path: &str) -> Option<&'static str> {
    ALL.iter().find(|(p, _)| *p == path).map(|(_, text)| *text)
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
                "shaders/{path} is not embedded (src/gpu/shader_gen/sources.rs)"
            );
        }
        for path in BRDF_ORDER {
            assert!(by_path(path).is_some(), "{path}");
        }
        assert_eq!(by_path("brdf/phong.wgsl"), Some(BRDF_PHONG));
        assert_eq!(by_path("brdf/none.wgsl"), None);
    }
}
