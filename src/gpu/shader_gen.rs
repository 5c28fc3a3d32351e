//! Scene-specialized WGSL: only what a scene uses is compiled.
//!
//! A [`ShaderKey`] lists the features a scene needs: shading mode, BRDF
//! variants (a model with its chosen terms), light kinds, shadow-map
//! projections and filtering. [`compose`]
//! concatenates the WGSL files for exactly those features, keeps only the
//! lines marked `// #if FEATURE` whose feature is on, and generates the
//! dispatch functions (`eval_brdf`, `mirror_reflectance`,
//! `light_incidence`) with one `switch` arm per feature present (no switch
//! at all when there is only one). A Lambert-only scene with a point light
//! therefore contains no glossy lobe, no Fresnel, no spot-light code.
//! Parameter values live in buffers, so changing them never rebuilds a
//! pipeline; changing the key does.

use super::bindings::UniformArrays;
use super::shadows::{Projection, ShadowFeatures};
use crate::material::{BrdfVariant, Distribution, Fresnel, Geometry, ReflectanceModel};
use crate::scene::{LightKind, Scene, ShadingMode};
use std::collections::BTreeSet;
use std::fmt::Write;

/// The WGSL sources, embedded at build time so the binary is self-contained.
pub mod sources {
    pub const COMMON: &str = include_str!("../../shaders/common.wgsl");
    pub const BRDF_LAMBERT: &str = include_str!("../../shaders/brdf/lambert.wgsl");
    pub const BRDF_PHONG: &str = include_str!("../../shaders/brdf/phong.wgsl");
    pub const BRDF_FRESNEL: &str = include_str!("../../shaders/brdf/fresnel.wgsl");
    pub const BRDF_MICROFACET: &str = include_str!("../../shaders/brdf/microfacet.wgsl");
    pub const BRDF_WARD: &str = include_str!("../../shaders/brdf/ward.wgsl");
    pub const LIGHT_INVERSE_SQUARE: &str = include_str!("../../shaders/lights/inverse_square.wgsl");
    pub const LIGHT_POINT: &str = include_str!("../../shaders/lights/point.wgsl");
    pub const LIGHT_DIRECTIONAL: &str = include_str!("../../shaders/lights/directional.wgsl");
    pub const LIGHT_SPOT: &str = include_str!("../../shaders/lights/spot.wgsl");
    pub const LIGHT_AREA_SAMPLE: &str = include_str!("../../shaders/lights/area_sample.wgsl");
    pub const SHADOW_LOOKUP: &str = include_str!("../../shaders/shadows.wgsl");
    pub const SHADOW_PASS: &str = include_str!("../../shaders/shadow_pass.wgsl");
    pub const SURFACE: &str = include_str!("../../shaders/surface.wgsl");
    pub const SHADING: &str = include_str!("../../shaders/shading.wgsl");
    pub const RASTER_VERTEX_SHADED: &str = include_str!("../../shaders/raster_vertex_shaded.wgsl");
    pub const RASTER_PIXEL_SHADED: &str = include_str!("../../shaders/raster_pixel_shaded.wgsl");

    /// The BRDF files in dependency order (each may use the ones before).
    pub const BRDF_ORDER: [&str; 5] = [
        BRDF_LAMBERT,
        BRDF_PHONG,
        BRDF_FRESNEL,
        BRDF_MICROFACET,
        BRDF_WARD,
    ];
}

/// What a scene's shader must contain. Equal keys share a pipeline.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    pub shading: ShadingMode,
    /// Sorted; a material's `variant` index points into this order.
    pub variants: BTreeSet<BrdfVariant>,
    pub light_kinds: BTreeSet<LightKind>,
    /// Shadow-map projections and filtering in use (empty: no shadow code).
    pub shadows: ShadowFeatures,
    /// Loop counts compiled in as constants.
    pub counts: LoopCounts,
    /// Which arrays are bound as uniform buffers (src/gpu/bindings.rs).
    pub arrays: UniformArrays,
    /// Compute the shadow-map coordinates per vertex where the key allows
    /// it ([`ShaderKey::shadow_coords_per_vertex`]); `false`: always per
    /// pixel (for tests and measurements of the difference).
    pub vertex_shadow_coords: bool,
}

/// The counts of the shader's loops, compiled in as WGSL constants so the
/// compiler can unroll them. A software rasterizer pays for every dynamic
/// loop and every private array per pixel: with the light count read from
/// a uniform and a 64-entry visibility array, lavapipe's scene pass took
/// about twice as long as with constants (measured on the viewer's 1080p
/// benchmark scene). Changing a count selects another pipeline; changing
/// a value never does.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct LoopCounts {
    /// Punctual lights (area-light samples included); 0: read from the
    /// globals at run time (an uber shader for any light count).
    pub lights: u32,
    /// Shadow maps looked up per pixel (one per shadowed light; the
    /// samples of an area light share one). 0 without shadows.
    pub shadow_maps: u32,
    /// The PCF kernel radius, `(k − 1) / 2`, when every shadowed light
    /// uses the same one; `None`: read per light.
    pub pcf_radius: Option<u32>,
}

impl ShaderKey {
    /// The features `scene` uses: the variants of materials that some mesh
    /// references, the kinds of lights present.
    pub fn for_scene(scene: &Scene) -> ShaderKey {
        let shadows = ShadowFeatures::for_scene(scene);
        let (shadow_maps, shadow_views) = if shadows.any() {
            let plan = super::shadows::ShadowPlan::new(scene);
            (plan.casters.len() as u32, plan.layers.len())
        } else {
            (0, 0)
        };
        ShaderKey {
            shading: scene.shading,
            variants: scene
                .meshes
                .iter()
                .map(|m| scene.materials[m.material].variant())
                .collect(),
            light_kinds: scene.lights.iter().map(|l| l.kind()).collect(),
            shadows,
            counts: LoopCounts {
                lights: scene.lights.len() as u32,
                shadow_maps,
                pcf_radius: ShadowFeatures::uniform_pcf_radius(scene),
            },
            arrays: UniformArrays::for_counts(scene.lights.len(), shadow_views),
            vertex_shadow_coords: true,
        }
    }

    /// Index of `variant` in this key (what `Material.variant` holds on the
    /// GPU); variants no mesh uses map past the end (the switch's default).
    pub fn variant_index(&self, variant: &BrdfVariant) -> u32 {
        self.variants
            .iter()
            .position(|v| v == variant)
            .unwrap_or(self.variants.len()) as u32
    }

    /// Whether any variant needs a tangent frame in the vertex stream.
    pub fn needs_tangents(&self) -> bool {
        self.variants.iter().any(|v| v.model.needs_tangents())
    }

    /// Whether the vertex shader computes the shadow-map coordinates
    /// (feature `shadow_vertex`, else `shadow_pixel`): per-pixel (Phong)
    /// shading whose one shadow map is orthographic. The lookup point is
    /// then `x` plus an offset that depends only on the light and the
    /// triangle's geometric normal, so its map coordinates are an affine
    /// function of `x` over each triangle and interpolating them from the
    /// corners (perspective-correct, as `x` itself) gives what the
    /// fragment shader would compute, without a matrix, the offset and the
    /// position derivatives per pixel: on lavapipe, the 1080p viewer
    /// benchmark's scene pass went from about 28 to about 25 ms
    /// (tests/shadows.rs (e) checks that the images are the same). The
    /// vertex stream is then de-indexed, each corner with its triangle's
    /// normal (`VertexLayout::face_normal`).
    pub fn shadow_coords_per_vertex(&self) -> bool {
        self.vertex_shadow_coords
            && self.shading == ShadingMode::Phong
            && self.counts.shadow_maps == 1
            && self.shadows.projections.len() == 1
            && self.shadows.projections.contains(&Projection::Ortho)
    }

    /// Whether any variant is a mirror (environment reflection code).
    pub fn has_mirror(&self) -> bool {
        self.variants
            .iter()
            .any(|v| v.model == ReflectanceModel::Mirror)
    }

    /// The `#if` features on for this key.
    pub fn features(&self) -> Vec<&'static str> {
        let mut f = Vec::new();
        if self.shading == ShadingMode::Flat {
            f.push("flat");
        }
        if self.needs_tangents() {
            f.push("tangents");
        }
        if self.has_mirror() {
            f.push("mirror");
        }
        f.extend(self.shadows.features());
        if self.shadow_coords_per_vertex() {
            f.push("shadow_vertex");
        } else if self.shadows.any() {
            f.push("shadow_pixel");
        }
        if self.counts.lights > 0 {
            f.push("light_count");
        }
        if self.shadows.pcf && self.counts.pcf_radius.is_some() {
            f.push("pcf_uniform");
        }
        f.extend(self.arrays.features());
        f
    }

    /// A one-line description for logs.
    pub fn describe(&self) -> String {
        let variants: Vec<_> = self.variants.iter().map(|v| v.describe()).collect();
        let lights: Vec<_> = self.light_kinds.iter().map(|k| k.name()).collect();
        format!(
            "shading {}, models [{}], lights [{}], {}",
            self.shading,
            variants.join(", "),
            lights.join(", "),
            self.shadows.describe()
        )
    }
}

/// Keeps the lines of `source` whose `// #if FEATURE` / `// #if !FEATURE`
/// condition holds for `features`; unmarked lines are kept.
pub fn preprocess(source: &str, features: &[&str]) -> String {
    let mut out = String::with_capacity(source.len());
    for line in source.lines() {
        let keep = match line.rsplit_once("// #if ") {
            None => true,
            Some((_, cond)) => match cond.trim().strip_prefix('!') {
                Some(f) => !features.contains(&f),
                None => features.contains(&cond.trim()),
            },
        };
        if keep {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The WGSL files a variant needs (by their index in `BRDF_ORDER`), from
/// its model's row in the table of models.
fn variant_files(v: &BrdfVariant) -> Vec<usize> {
    // The paths (under `shaders/`) of `sources::BRDF_ORDER`, index for index.
    const PATHS: [&str; 5] = [
        "brdf/lambert.wgsl",
        "brdf/phong.wgsl",
        "brdf/fresnel.wgsl",
        "brdf/microfacet.wgsl",
        "brdf/ward.wgsl",
    ];
    v.model
        .row()
        .wgsl
        .iter()
        .map(|path| {
            PATHS
                .iter()
                .position(|p| p == path)
                .unwrap_or_else(|| panic!("shaders/{path} is not embedded in sources::BRDF_ORDER"))
        })
        .collect()
}

/// WGSL for `D` — mirrors `brdf::distribution`.
fn distribution_wgsl(d: Distribution) -> &'static str {
    match d {
        Distribution::Beckmann => "d_beckmann(m.roughness, cos_h, sin2_h)",
        Distribution::Blinn => "d_blinn_lecture(m.blinn_e, cos_h, sin2_h)",
        Distribution::BlinnNormalized => "d_blinn_normalized(m.blinn_e, cos_h, sin2_h)",
        Distribution::Gaussian => "d_gaussian_lecture(m.roughness, cos_h, sin2_h)",
        Distribution::GaussianNormalized => {
            "d_gaussian_normalized(m.roughness, cos_h, sin2_h, m.d_norm)"
        }
        Distribution::Ggx => "d_ggx(m.roughness, cos_h, sin2_h)",
    }
}

/// WGSL for `G` — mirrors `brdf::geometry` and `brdf::smith_beckmann_slope`.
fn geometry_wgsl(g: Geometry, d: Distribution) -> String {
    match g {
        Geometry::None => "1.0".into(),
        Geometry::VGroove => "g_vgroove(cos_h, cos_o, cos_i, cos_oh)".into(),
        Geometry::Smith if d == Distribution::Ggx => {
            "g1_ggx(m.roughness, cos_i, cos_ih) * g1_ggx(m.roughness, cos_o, cos_oh)".into()
        }
        Geometry::Smith => {
            let slope = match d {
                Distribution::Blinn | Distribution::BlinnNormalized => {
                    "beckmann_slope_of_blinn(m.blinn_e)"
                }
                Distribution::Gaussian | Distribution::GaussianNormalized => {
                    "beckmann_slope_of_gaussian(m.roughness)"
                }
                Distribution::Beckmann | Distribution::Ggx => "m.roughness",
            };
            format!("g1_beckmann({slope}, cos_i, cos_ih) * g1_beckmann({slope}, cos_o, cos_oh)")
        }
    }
}

/// WGSL for `F(cos)` — mirrors `brdf::fresnel`.
fn fresnel_wgsl(f: Fresnel, cos: &str) -> String {
    match f {
        Fresnel::Conductor => format!("fresnel_conductor({cos}, m.eta, m.kappa)"),
        Fresnel::ConductorLecture => format!("fresnel_conductor_lecture({cos}, m.eta, m.kappa)"),
        Fresnel::Dielectric => format!("vec3<f32>(fresnel_dielectric({cos}, m.eta_i, m.eta_t))"),
        Fresnel::Schlick => format!("fresnel_schlick({cos}, f0_conductor(m.eta, m.kappa))"),
        Fresnel::None => "vec3<f32>(1.0)".into(),
    }
}

/// The body of the BRDF function of one variant — mirrors `brdf::eval`.
fn variant_body(v: &BrdfVariant) -> String {
    let lobe = |expr: &str| format!("    return lambert(m.k_d) + m.k_s * {expr};\n");
    match v.model {
        ReflectanceModel::Lambert | ReflectanceModel::Mirror => {
            "    return lambert(m.k_d);\n".into()
        }
        ReflectanceModel::Phong => lobe("phong_lecture(m.k_e, frame.n, wi, wo)"),
        ReflectanceModel::PhongNormalized => lobe("phong_normalized(m.k_e, frame.n, wi, wo)"),
        ReflectanceModel::BlinnPhong => lobe("blinn_phong_lecture(m.k_e, frame.n, wi, wo)"),
        ReflectanceModel::BlinnPhongNormalized => {
            lobe("blinn_phong_normalized(m.k_e, frame.n, wi, wo)")
        }
        ReflectanceModel::Ward => lobe("ward_isotropic(m.sigma_x, frame.n, wi, wo)"),
        ReflectanceModel::WardAnisotropic => {
            lobe("ward_anisotropic(m.sigma_x, m.sigma_y, frame.n, frame.t, frame.b, wi, wo)")
        }
        ReflectanceModel::CookTorrance => {
            let d = v.distribution.unwrap_or(Distribution::Beckmann);
            let g = v.geometry.unwrap_or(Geometry::Smith);
            let f = v.fresnel.unwrap_or(Fresnel::Conductor);
            let factor = match v.denominator {
                Some(crate::material::Denominator::Lecture) => "PI",
                _ => "4.0",
            };
            format!(
                "    let n = frame.n;\n    let h = half_vector(wi, wo);\n    let cos_i = dot(n, wi);\n    let cos_o = dot(n, wo);\n    let cos_h = dot(n, h);\n    let sin2_h = sin2_between(n, h);\n    let cos_ih = dot(wi, h);\n    let cos_oh = dot(wo, h);\n    let d = {};\n    let g = {};\n    let f = {};\n    return lambert(m.k_d) + m.k_s * cook_torrance_specular(d, g, f, cos_i, cos_o, {factor});\n",
                distribution_wgsl(d),
                geometry_wgsl(g, d),
                fresnel_wgsl(f, "cos_ih"),
            )
        }
    }
}

/// The pipeline constant that specializes a shader of several BRDF
/// variants to one of them (see [`BRDF_VARIANT`]).
const BRDF_VARIANT_WGSL: &str =
    "// The BRDF variant this pipeline draws: one (each material's batch is drawn
// by the pipeline of its variant, src/gpu/prepared.rs; the compiler then
// drops the other variants' code) or ALL_VARIANTS (the material decides).
const ALL_VARIANTS: u32 = 0xffffffffu;
override BRDF_VARIANT: u32 = ALL_VARIANTS;

fn brdf_variant(m: Material) -> u32 {
    if BRDF_VARIANT != ALL_VARIANTS {
        return BRDF_VARIANT;
    }
    return m.variant;
}

";

/// The name of the pipeline constant (WGSL `override`) that specializes a
/// shader of several variants to the one with this index in
/// [`ShaderKey::variants`]. Why: a software rasterizer runs every arm of
/// the `switch` for every pixel, so a scene of a glossy sphere on a
/// Lambert floor paid for Cook-Torrance on every floor pixel.
pub const BRDF_VARIANT: &str = "BRDF_VARIANT";

/// Generates a `switch` over `selector` with one arm per `(id, call)`; a
/// single arm is emitted without a switch.
fn dispatch(out: &mut String, selector: &str, arms: &[(u32, String)], fallback: &str) {
    if let [(_, call)] = arms {
        let _ = writeln!(out, "    return {call};");
        return;
    }
    let _ = writeln!(out, "    switch {selector} {{");
    for (id, call) in arms {
        let _ = writeln!(out, "        case {id}u: {{ return {call}; }}");
    }
    let _ = writeln!(out, "        default: {{ return {fallback}; }}");
    let _ = writeln!(out, "    }}");
}

/// `shaders/common.wgsl` for `features`, after the capacities of its
/// uniform arrays (src/gpu/bindings.rs). Every scene shader starts with it;
/// the bench's hand-written shaders too.
pub fn common(features: &[&str]) -> String {
    let mut out = UniformArrays::wgsl_capacities();
    out.push_str(&preprocess(sources::COMMON, features));
    out
}

/// The files a light kind needs and its incidence function's name.
fn light_wgsl(kind: LightKind) -> (&'static [&'static str], &'static str) {
    use sources::*;
    match kind {
        LightKind::Point => (&[LIGHT_INVERSE_SQUARE, LIGHT_POINT], "point_incidence"),
        LightKind::Directional => (&[LIGHT_DIRECTIONAL], "directional_incidence"),
        LightKind::Spot => (&[LIGHT_INVERSE_SQUARE, LIGHT_SPOT], "spot_incidence"),
        LightKind::AreaSample => (
            &[LIGHT_INVERSE_SQUARE, LIGHT_AREA_SAMPLE],
            "area_sample_incidence",
        ),
    }
}

/// The BRDF part of a shader: shared declarations, the shading frame, the
/// families the variants need, one `brdf_K` function per variant and the
/// `eval_brdf` / `mirror_reflectance` dispatch over `Material.variant`
/// (the index of the variant in `variants`' order). The renderer and the
/// GPU-vs-CPU test harness both compile exactly this code.
pub fn compose_brdf_library(variants: &BTreeSet<BrdfVariant>, features: &[&str]) -> String {
    let mut out = common(features);
    out.push_str(&preprocess(sources::SURFACE, features));

    // BRDF families in dependency order, only those some variant needs.
    let needed: BTreeSet<usize> = variants.iter().flat_map(variant_files).collect();
    for &file in &needed {
        out.push_str(&preprocess(sources::BRDF_ORDER[file], features));
        out.push('\n');
    }

    // One function per variant, then the dispatch.
    let mut arms = Vec::new();
    let mut mirror_arms = Vec::new();
    for (index, v) in variants.iter().enumerate() {
        let _ = writeln!(out, "// {}", v.describe());
        let _ = write!(
            out,
            "fn brdf_{index}(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {{\n{}}}\n\n",
            variant_body(v)
        );
        arms.push((index as u32, format!("brdf_{index}(m, wi, wo, frame)")));
        if v.model == ReflectanceModel::Mirror {
            // ρ_s(θ) = k_s · F(cos θ), zero below the horizon — mirrors brdf::mirror_reflectance.
            let _ = write!(
                out,
                "fn mirror_{index}(m: Material, cos_theta: f32) -> vec3<f32> {{\n    if cos_theta <= 0.0 {{\n        return vec3<f32>(0.0);\n    }}\n    return m.k_s * {};\n}}\n\n",
                fresnel_wgsl(v.fresnel.unwrap_or(Fresnel::None), "cos_theta")
            );
            mirror_arms.push((index as u32, format!("mirror_{index}(m, cos_theta)")));
        }
    }
    if arms.len() > 1 {
        out.push_str(BRDF_VARIANT_WGSL);
    }
    out.push_str("fn eval_brdf(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {\n");
    if arms.is_empty() {
        out.push_str("    return vec3<f32>(0.0);\n");
    } else {
        dispatch(&mut out, "brdf_variant(m)", &arms, "vec3<f32>(0.0)");
    }
    out.push_str("}\n\n");
    if !mirror_arms.is_empty() {
        // Non-mirror materials in the same scene reflect no environment:
        // the switch's default.
        out.push_str("fn mirror_reflectance(m: Material, cos_theta: f32) -> vec3<f32> {\n");
        let selector = if arms.len() > 1 {
            "brdf_variant(m)"
        } else {
            "m.variant"
        };
        let _ = writeln!(out, "    switch {selector} {{");
        for (id, call) in &mirror_arms {
            let _ = writeln!(out, "        case {id}u: {{ return {call}; }}");
        }
        let _ = writeln!(out, "        default: {{ return vec3<f32>(0.0); }}\n    }}");
        out.push_str("}\n\n");
    }
    out
}

/// What a scene pipeline writes, decided by its colour target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Output {
    /// Linear radiance and coverage in `Rgba32Float`, read back exactly
    /// (`gonio render`, tests, bench).
    #[default]
    Radiance,
    /// What a PNG holds, for an 8-bit window surface: exposure, clamp,
    /// sRGB encoding in the shader (`#if display`), so the viewer draws
    /// straight into the swapchain with no extra pass.
    Display,
}

impl Output {
    /// The output a colour target of `format` takes.
    pub fn for_format(format: wgpu::TextureFormat) -> Output {
        if format == wgpu::TextureFormat::Rgba32Float {
            Output::Radiance
        } else {
            Output::Display
        }
    }
}

/// The complete WGSL module for `key`, writing linear radiance.
pub fn compose(key: &ShaderKey) -> String {
    compose_for(key, Output::Radiance)
}

/// The complete WGSL module for `key` writing `output`.
pub fn compose_for(key: &ShaderKey, output: Output) -> String {
    let mut features = key.features();
    if output == Output::Display {
        features.push("display");
    }
    let mut out = String::new();
    let _ = writeln!(out, "// Generated by gonio for: {}\n", key.describe());
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
    out.push_str(&compose_brdf_library(&key.variants, &features));

    // Light kinds.
    let mut included: Vec<&str> = Vec::new();
    let mut arms = Vec::new();
    for &kind in &key.light_kinds {
        let (files, function) = light_wgsl(kind);
        for f in files {
            if !included.contains(f) {
                included.push(f);
                out.push_str(f);
                out.push('\n');
            }
        }
        arms.push((kind.id(), format!("{function}(light, x)")));
    }
    out.push_str("fn light_incidence(light: Light, x: vec3<f32>) -> Incidence {\n");
    let none = "Incidence(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0))";
    if arms.is_empty() {
        let _ = writeln!(out, "    return {none};");
    } else {
        dispatch(&mut out, "light.kind", &arms, none);
    }
    out.push_str("}\n\n");

    // Shadow-map lookups, only when a light casts shadows.
    if key.shadows.any() {
        out.push_str(&preprocess(sources::SHADOW_LOOKUP, &features));
        out.push('\n');
    }

    out.push_str(&preprocess(sources::SHADING, &features));
    out.push('\n');
    let raster = match key.shading {
        ShadingMode::Flat | ShadingMode::Gouraud => sources::RASTER_VERTEX_SHADED,
        ShadingMode::Phong => sources::RASTER_PIXEL_SHADED,
    };
    out.push_str(&preprocess(raster, &features));
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

/// Every BRDF variant gonio can compile: each model with every
/// combination of the terms its row in the table of models selects.
pub fn all_variants() -> Vec<BrdfVariant> {
    use crate::material::Denominator;
    fn each<T: Copy>(applies: bool, all: &[T]) -> Vec<Option<T>> {
        if applies {
            all.iter().copied().map(Some).collect()
        } else {
            vec![None]
        }
    }
    let mut out = Vec::new();
    for row in crate::material::table::ROWS {
        let terms = row.terms;
        for &distribution in &each(terms.distribution, &Distribution::ALL) {
            for &geometry in &each(terms.geometry, &Geometry::ALL) {
                for &fresnel in &each(terms.fresnel, &Fresnel::ALL) {
                    for &denominator in &each(terms.denominator, &Denominator::ALL) {
                        out.push(BrdfVariant {
                            model: row.model,
                            distribution,
                            geometry,
                            fresnel,
                            denominator,
                        });
                    }
                }
            }
        }
    }
    out
}

/// Keys that together compile every line of every WGSL file: each shading
/// mode with each variant alone (one light kind each, cycling), each
/// shadow projection alone with and without PCF, plus all variants, all
/// light kinds and all shadow code at once. Used by the shader validation
/// test.
pub fn representative_keys() -> Vec<ShaderKey> {
    let all_kinds = LightKind::ALL;
    let all_projections = [Projection::Ortho, Projection::Perspective, Projection::Cube];
    let variants = all_variants();
    // Uniform or storage buffers for every array, alternating.
    let arrays = |uniform: bool| UniformArrays {
        lights: uniform,
        shadow_views: uniform,
    };
    let mut keys = Vec::new();
    for shading in ShadingMode::ALL {
        for (i, v) in variants.iter().enumerate() {
            keys.push(ShaderKey {
                shading,
                variants: [*v].into(),
                light_kinds: [all_kinds[i % all_kinds.len()]].into(),
                shadows: ShadowFeatures::default(),
                counts: LoopCounts {
                    lights: 1,
                    ..Default::default()
                },
                arrays: arrays(i % 2 == 0),
                vertex_shadow_coords: false,
            });
        }
        for (i, projection) in all_projections.into_iter().enumerate() {
            for pcf in [false, true] {
                keys.push(ShaderKey {
                    shading,
                    variants: [variants[i]].into(),
                    light_kinds: [all_kinds[i]].into(),
                    shadows: ShadowFeatures {
                        projections: [projection].into(),
                        pcf,
                    },
                    counts: LoopCounts {
                        lights: 2,
                        shadow_maps: 1,
                        pcf_radius: (i % 2 == 0).then_some(1),
                    },
                    arrays: arrays(pcf),
                    // Orthographic with PCF: the coordinates per vertex.
                    vertex_shadow_coords: pcf,
                });
            }
        }
        for uniform in [false, true] {
            keys.push(ShaderKey {
                shading,
                variants: variants.iter().copied().collect(),
                light_kinds: all_kinds.into(),
                shadows: ShadowFeatures {
                    projections: all_projections.into(),
                    pcf: true,
                },
                counts: LoopCounts {
                    lights: 5,
                    shadow_maps: 3,
                    pcf_radius: None,
                },
                arrays: arrays(uniform),
                vertex_shadow_coords: false,
            });
        }
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    #[test]
    fn lambert_only_scene_has_no_glossy_or_spot_code() {
        let key = ShaderKey {
            shading: ShadingMode::Phong,
            variants: [Material::new("m", ReflectanceModel::Lambert).variant()].into(),
            light_kinds: [LightKind::Point].into(),
            shadows: ShadowFeatures::default(),
            ..Default::default()
        };
        let wgsl = compose(&key);
        for absent in [
            "blinn_phong_lecture",
            "fresnel_",
            "d_beckmann",
            "spot_attenuation",
            "switch m.variant",
            "switch light.kind",
            "environment_radiance",
            "tangent: vec3",
            "shadow_visibility",
            "shadow_maps",
            "textureSampleCompare",
            "area_sample",
            "dpdx",
        ] {
            assert!(
                !wgsl.contains(absent),
                "`{absent}` compiled into a Lambert-only shader"
            );
        }
        validate(&wgsl).unwrap();
    }

    #[test]
    fn shadow_code_only_for_the_projections_in_use() {
        let key = |projections: &[Projection], pcf| ShaderKey {
            shading: ShadingMode::Phong,
            variants: [Material::new("m", ReflectanceModel::Lambert).variant()].into(),
            light_kinds: [LightKind::Point].into(),
            shadows: ShadowFeatures {
                projections: projections.iter().copied().collect(),
                pcf,
            },
            ..Default::default()
        };
        let cube = compose(&key(&[Projection::Cube], false));
        for present in [
            "fn shadow_visibility",
            "fn shadow_cube",
            "textureSampleCompareLevel",
            "dpdx",
        ] {
            assert!(cube.contains(present), "`{present}` missing");
        }
        for absent in [
            "fn shadow_ortho",
            "fn shadow_perspective",
            "for (var i = -r",
        ] {
            assert!(
                !cube.contains(absent),
                "`{absent}` compiled without its feature"
            );
        }
        validate(&cube).unwrap();
        let ortho = compose(&key(&[Projection::Ortho], true));
        assert!(ortho.contains("fn shadow_ortho") && ortho.contains("for (var i = -r"));
        assert!(!ortho.contains("fn shadow_cube") && !ortho.contains("fn shadow_perspective"));
        validate(&ortho).unwrap();
    }

    #[test]
    fn preprocess_keeps_marked_lines_by_feature() {
        let src = "a\nb // #if x\nc // #if !x\n";
        assert_eq!(preprocess(src, &["x"]), "a\nb // #if x\n");
        assert_eq!(preprocess(src, &[]), "a\nc // #if !x\n");
    }

    #[test]
    fn every_representative_key_validates() {
        let keys = representative_keys();
        assert!(keys.len() > 3 * 180);
        for key in keys {
            if let Err(e) = validate(&compose_for(&key, Output::Display)) {
                panic!("display output of {}: {e}", key.describe());
            }
            if let Err(e) = validate(&compose(&key)) {
                panic!("{}:\n{e}", key.describe());
            }
        }
    }
}
