//! Writing a scene's WGSL module: the files its key needs, each with its
//! conditional blocks resolved, after the generated constants.

use super::features::Feature;
use super::key::ShaderKey;
use super::preprocess::preprocess;
use super::sources;
use super::specialization;
use crate::gpu::bindings::UniformArrays;
use crate::material::{BrdfVariant, ReflectanceModel};
use crate::scene::{LightKind, ShadingMode};
use std::collections::BTreeSet;
use std::fmt::Write;

/// The embedded file at `path` (relative to `shaders/`) for `features`.
/// Panics on a bad block: the files are embedded at build time and the
/// test `every_shader_file_has_known_features_and_balanced_blocks` checks
/// every one, so an error here is a bug in gonio, not in its input.
fn file(path: &str, features: &[Feature]) -> String {
    preprocess(&format!("shaders/{path}"), sources::get(path), features)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// `shaders/common.wgsl` for `features`, after the capacities of its
/// uniform arrays (src/gpu/bindings.rs). Every scene shader starts with it;
/// the bench's hand-written shaders too.
pub fn common(features: &[Feature]) -> String {
    let mut out = UniformArrays::wgsl_capacities();
    out.push_str(&file("common.wgsl", features));
    // `Material.layers`' struct, where the layers are declared.
    if features.contains(&Feature::GltfLayers) {
        out.push_str(&file("brdf/gltf_layers/mod.wgsl", features));
    }
    out
}

/// The BRDF part of a shader: shared declarations, the codes and
/// specialization defaults of `variants`, the shading frame, the files
/// their models need and `eval_brdf` / `mirror_reflectance`
/// (shaders/brdf/eval.wgsl) with the arms of those models. The renderer
/// and the GPU-vs-CPU test harness both compile exactly this code.
pub fn compose_brdf_library(variants: &BTreeSet<BrdfVariant>, features: &[Feature]) -> String {
    let models: BTreeSet<ReflectanceModel> = variants.iter().map(|v| v.model).collect();
    let mut features = features.to_vec();
    for feature in specialization::brdf_features(variants) {
        if !features.contains(&feature) {
            features.push(feature);
        }
    }
    let mut out = common(&features);
    out.push('\n');
    out.push_str(&specialization::wgsl_codes());
    out.push_str(&specialization::wgsl_defaults(variants));
    out.push('\n');
    out.push_str(&file("surface.wgsl", &features));
    out.push('\n');
    out.push_str(&file("brdf/variant.wgsl", &features));
    out.push('\n');
    let mut needed: BTreeSet<&str> = models
        .iter()
        .flat_map(|&m| m.row().wgsl.iter().copied())
        .collect();
    // The sampled mode's lobes (shaders/environment_sampled.wgsl) use
    // phong.wgsl's cosine powers and mirror direction, whatever the models.
    if features.contains(&Feature::EnvironmentSampled) {
        needed.insert("brdf/phong.wgsl");
    }
    for path in brdf_file_order().into_iter().filter(|p| needed.contains(p)) {
        out.push_str(&file(path, &features));
        out.push('\n');
    }
    for path in layer_files(&models, &features) {
        out.push_str(&file(path, &features));
        out.push('\n');
    }
    out.push_str(&file("brdf/eval.wgsl", &features));
    out.push('\n');
    out
}

/// The files of gltf-pbr's layers (shaders/brdf/gltf_layers/) the
/// features compile, in dependency order: each layer's only where a drawn
/// material uses it (`MaterialsKey::layer_*`; their struct comes with
/// `Material.layers`, [`common`]). Nothing without a layer.
fn layer_files(models: &BTreeSet<ReflectanceModel>, features: &[Feature]) -> Vec<&'static str> {
    let on = |f: Feature| features.contains(&f);
    if !on(Feature::GltfLayers) || !models.contains(&ReflectanceModel::GltfPbr) {
        return Vec::new();
    }
    let mut files = Vec::new();
    let base = [
        Feature::LayerIorSpecular,
        Feature::LayerIridescence,
        Feature::LayerAnisotropy,
        Feature::LayerTransmission,
        Feature::LayerDiffuseTransmission,
    ];
    let layers = [
        (
            on(Feature::LayerIridescence),
            "brdf/gltf_layers/iridescence.wgsl",
        ),
        (
            base.into_iter().any(on),
            "brdf/gltf_layers/base_ior_specular.wgsl",
        ),
        (on(Feature::LayerSheen), "brdf/gltf_layers/sheen.wgsl"),
        (
            on(Feature::LayerSheen),
            "brdf/gltf_layers/sheen_albedo.wgsl",
        ),
        (
            on(Feature::LayerClearcoat),
            "brdf/gltf_layers/clearcoat.wgsl",
        ),
        (
            on(Feature::LayerDiffuseTransmission),
            "brdf/gltf_layers/transmission.wgsl",
        ),
        (true, "brdf/gltf_layers/stack.wgsl"),
    ];
    files.extend(layers.into_iter().filter_map(|(o, path)| o.then_some(path)));
    files
}

/// Every model's BRDF files in one order that respects each row's
/// dependency order (a row lists its files so that each may use the ones
/// before): the rows' lists merged, each file placed right after its
/// predecessor in the first row that names it. A scene's module includes
/// the files its models need in this order.
pub fn brdf_file_order() -> Vec<&'static str> {
    let mut order: Vec<&'static str> = Vec::new();
    for row in crate::material::table::ROWS {
        let mut after: Option<usize> = None;
        for &path in row.wgsl {
            let at = match order.iter().position(|&p| p == path) {
                Some(at) => at,
                None => {
                    let at = after.map_or(0, |a| a + 1);
                    order.insert(at, path);
                    at
                }
            };
            after = Some(at);
        }
    }
    order
}

/// What a scene pipeline writes, decided by its colour target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Output {
    /// Linear radiance and coverage in `Rgba32Float`, read back exactly
    /// (`gonio render`, tests, bench).
    #[default]
    Radiance,
    /// The same f32 values as their bits in `Rgba32Uint` (`#if
    /// radiance_bits`), read back as the same bytes: for adapters that
    /// cannot render into `Rgba32Float` (wgpu's GL backend on llvmpipe).
    RadianceBits,
    /// What a PNG holds, for an 8-bit window surface: exposure, clamp,
    /// sRGB encoding in the shader (`#if display`), so the viewer draws
    /// straight into the swapchain with no extra pass.
    Display,
}

impl Output {
    /// The shader feature that selects this output, if any.
    fn feature(self) -> Option<Feature> {
        match self {
            Output::Radiance => None,
            Output::RadianceBits => Some(Feature::RadianceBits),
            Output::Display => Some(Feature::Display),
        }
    }

    /// The output a colour target of `format` takes.
    pub fn for_format(format: wgpu::TextureFormat) -> Output {
        match format {
            wgpu::TextureFormat::Rgba32Float | super::super::formats::TRANSMISSION_FORMAT => {
                Output::Radiance
            }
            wgpu::TextureFormat::Rgba32Uint => Output::RadianceBits,
            _ => Output::Display,
        }
    }
}

/// The files under `shaders/lights/` a light kind's incidence function
/// needs, each after the ones it uses.
fn light_files(kind: LightKind) -> &'static [&'static str] {
    match kind {
        LightKind::Point => &["lights/inverse_square.wgsl", "lights/point.wgsl"],
        LightKind::Directional => &["lights/directional.wgsl"],
        LightKind::Spot => &["lights/inverse_square.wgsl", "lights/spot.wgsl"],
        LightKind::AreaSample => &["lights/inverse_square.wgsl", "lights/area_sample.wgsl"],
    }
}

/// The WGSL constants naming the light kinds' codes (`LIGHT_POINT`, ...:
/// `LightKind::id`, the value of `Light.kind`), so the `switch` of
/// shaders/lights/incidence.wgsl names them and no number is kept in sync
/// by hand.
fn light_codes() -> String {
    let mut out = String::from(
        "// Codes of the light kinds (Light.kind: LightKind::id, src/scene/light.rs).\n",
    );
    for kind in LightKind::ALL {
        let name = specialization::constant_name(kind.name());
        let _ = writeln!(out, "const LIGHT_{name}: u32 = {}u;", kind.id());
    }
    out
}

/// The light files of `kinds`, then `light_incidence`
/// (shaders/lights/incidence.wgsl) with the arms of those kinds.
fn lights(kinds: &BTreeSet<LightKind>, features: &[Feature]) -> String {
    let mut out = String::new();
    let mut included: Vec<&str> = Vec::new();
    for path in kinds.iter().flat_map(|&kind| light_files(kind)) {
        if !included.contains(path) {
            included.push(path);
            out.push_str(&file(path, features));
            out.push('\n');
        }
    }
    out.push_str(&light_codes());
    out.push_str(&file("lights/incidence.wgsl", features));
    out.push('\n');
    out
}

/// The complete WGSL module for `key`, writing linear radiance.
pub fn compose(key: &ShaderKey) -> String {
    compose_for(key, Output::Radiance)
}

/// The complete WGSL module for `key` writing `output`.
pub fn compose_for(key: &ShaderKey, output: Output) -> String {
    let mut features = key.features();
    features.extend(output.feature());
    let mut out = String::new();
    let _ = writeln!(out, "// Generated by gonio for: {}", key.describe());
    let spelt: Vec<String> = features.iter().map(|f| f.spelling()).collect();
    let _ = writeln!(out, "// Features: {}\n", spelt.join(", "));
    if output == Output::Display {
        let _ = writeln!(out, "const TONE_MAP: u32 = {}u;", key.tone_map.code());
    }
    let counts = &key.counts;
    if counts.lights > 0 {
        let _ = writeln!(out, "const LIGHT_COUNT: u32 = {}u;", counts.lights);
    }
    if key.shadows.any() {
        // An array needs at least one element; index 0 is then unused.
        let _ = writeln!(
            out,
            "const SHADOW_MAP_COUNT: u32 = {}u;",
            counts.shadow_maps.max(1)
        );
        if let Some(r) = counts.pcf_radius {
            let _ = writeln!(out, "const PCF_RADIUS: u32 = {r}u;");
        }
    }
    if key.materials.texture_slots > 0 {
        let _ = writeln!(
            out,
            "const TEXTURE_SLOTS: u32 = {}u;\nconst MAX_TEXTURE_SLOTS: u32 = {}u;",
            key.materials.texture_slots,
            crate::gpu::textures::MAX_TEXTURE_SLOTS
        );
    }
    out.push_str(&compose_brdf_library(&key.variants, &features));
    if key.materials.texture_slots > 0 {
        out.push_str(&file("textures.wgsl", &features));
        out.push_str(&crate::gpu::textures::wgsl_bindings(
            key.materials.texture_bindings,
        ));
        out.push('\n');
    }
    out.push_str(&lights(&key.lights.kinds, &features));
    if key.environment.map {
        out.push_str(&file("environment.wgsl", &features));
        out.push('\n');
        if key.environment.sh {
            out.push_str(&file("environment_sh.wgsl", &features));
            out.push('\n');
        }
        if key.environment.sampled {
            out.push_str(&file("environment_sampled.wgsl", &features));
            out.push('\n');
        }
    }
    // Shadow-map lookups, only when a light casts shadows.
    if key.shadows.any() {
        out.push_str(&file("shadows.wgsl", &features));
        out.push('\n');
    }
    // Light through surfaces (screen space), only where a drawn material
    // transmits and the scene's transmission mode draws it.
    if key.materials.layer_transmission {
        out.push_str(&file("transmission.wgsl", &features));
        out.push('\n');
        // The volumes' exit traced in screen space, only where asked.
        if key.materials.transmission_exit_traced {
            out.push_str(&file("transmission_traced.wgsl", &features));
            out.push('\n');
        }
    }
    out.push_str(&file("shading.wgsl", &features));
    out.push('\n');
    let raster = match key.shading {
        ShadingMode::Flat | ShadingMode::Gouraud => "raster_vertex_shaded.wgsl",
        ShadingMode::Phong => "raster_pixel_shaded.wgsl",
    };
    out.push_str(&file(raster, &features));
    out
}

/// The background pass's module (shaders/environment_background.wgsl)
/// writing `output`: the shared declarations, the environment map and the
/// full-screen triangle.
pub fn compose_background(output: Output, tone_map: crate::output::tone_map::ToneMap) -> String {
    let mut features = vec![Feature::Environment];
    features.extend(output.feature());
    let mut out = String::new();
    if output == Output::Display {
        let _ = writeln!(out, "const TONE_MAP: u32 = {}u;", tone_map.code());
    }
    out.push_str(&common(&features));
    out.push('\n');
    out.push_str(&file("environment.wgsl", &features));
    out.push('\n');
    out.push_str(&file("environment_background.wgsl", &features));
    out
}

/// Parses and validates WGSL with naga, as wgpu will; the error text names
/// the line. Used before pipeline creation and by the shader tests.
pub fn validate(wgsl: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| e.emit_to_string(wgsl))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(wgsl))?;
    Ok(module)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row's files appear once, in the row's own order.
    #[test]
    fn brdf_file_order_keeps_every_rows_dependencies() {
        let order = brdf_file_order();
        for row in crate::material::table::ROWS {
            let at: Vec<usize> = row
                .wgsl
                .iter()
                .map(|p| order.iter().position(|q| q == p).unwrap())
                .collect();
            assert!(
                at.windows(2).all(|w| w[0] < w[1]),
                "{:?}: {order:?}",
                row.model
            );
        }
        let unique: BTreeSet<_> = order.iter().collect();
        assert_eq!(unique.len(), order.len());
    }
}
