//! The features a WGSL block can be conditional on (`#if NAME`, see
//! [`super::preprocess`]): a closed set, so that a misspelt name in a
//! shader is an error rather than a line silently kept or dropped.

use crate::gpu::shadows::{Projection, ShadowFeatures};
use crate::material::{Distribution, Fresnel, Geometry, ReflectanceModel};
use std::fmt;

/// One condition of the shader sources, with its WGSL spelling
/// ([`Feature::spelling`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// Flat shading: one colour per triangle (`flat`).
    Flat,
    /// Some model needs a tangent frame in the vertex stream (`tangents`).
    Tangents,
    /// The scene uses this reflectance model (spelt as the model's
    /// contract name, e.g. `cook-torrance`): its `eval_brdf` arm and its
    /// helpers are compiled.
    Model(ReflectanceModel),
    /// Some Cook-Torrance material uses this distribution
    /// (`distribution=ggx`): its `switch` arm is compiled.
    Distribution(Distribution),
    /// Some Cook-Torrance material uses this geometry term
    /// (`geometry=smith`).
    Geometry(Geometry),
    /// Some Cook-Torrance or mirror material uses this Fresnel term
    /// (`fresnel=schlick`).
    Fresnel(Fresnel),
    /// Some light casts shadows (`shadows`).
    Shadows,
    /// Some shadowed light filters with PCF (`shadow_pcf`).
    ShadowPcf,
    /// Every PCF light has the same kernel, compiled in as `PCF_RADIUS`
    /// (`pcf_uniform`).
    PcfUniform,
    /// Orthographic shadow maps (directional lights) (`shadow_ortho`).
    ShadowOrtho,
    /// Perspective shadow maps (spot lights) (`shadow_perspective`).
    ShadowPerspective,
    /// Cube shadow maps (point and area lights) (`shadow_cube`).
    ShadowCube,
    /// Perspective or cube maps: the lookup with the w divide
    /// (`shadow_projective`; only spot maps call it since the cube lookup
    /// writes its clip coordinates out, a cube-only shader compiles it
    /// unused).
    ShadowProjective,
    /// The shadow-map coordinates are computed per vertex
    /// (`shadow_vertex`; `ShaderKey::shadow_coords_per_vertex`).
    ShadowVertex,
    /// The shadow-map coordinates are computed per pixel (`shadow_pixel`).
    ShadowPixel,
    /// The light count is compiled in as `LIGHT_COUNT` (`light_count`).
    LightCount,
    /// Some light has a glTF range: the inverse-square law's range window
    /// is compiled (`light_range`; `ShaderKey::light_range`).
    LightRange,
    /// Some light may sit on a shaded point: the inverse-square law's
    /// zero-distance guard is compiled (`light_guard`;
    /// `ShaderKey::light_guard`).
    LightGuard,
    /// The lights are a uniform array (`uniform_lights`; else storage).
    UniformLights,
    /// The shadow views are a uniform array (`uniform_shadow_views`).
    UniformShadowViews,
    /// The target is a display surface: exposure and sRGB in the shader
    /// (`display`).
    Display,
    /// The target is `Rgba32Uint` holding the radiance's f32 bits, for
    /// adapters that cannot render into `Rgba32Float` (`radiance_bits`).
    RadianceBits,
    /// The scene has an environment map: group 3, the map lights every
    /// surface and is the background (`environment`).
    Environment,
    /// The environment lights through the whole BRDF with N sampled
    /// directions (`environment_sampled`).
    EnvironmentSampled,
    /// The environment's glossy part by the split-sum approximation
    /// (`environment_prefiltered`).
    EnvironmentPrefiltered,
    /// The Phong lobes by SH convolution (`environment_sh`).
    EnvironmentSh,
    /// Some material has textures: UVs in the vertex stream, bind group 2
    /// and shaders/textures.wgsl (`textures`).
    Textures,
    /// Some material has a normal map: tangents and their bitangent signs
    /// in the vertex stream, the frame turned per pixel (`normal_map`).
    NormalMap,
    /// Some material is double-sided (glTF `doubleSided`): vertex shading
    /// computes both sides (`two_sided`).
    TwoSided,
    /// Some material is single-sided (glTF `doubleSided: false`): back
    /// faces are discarded (`culling`).
    Culling,
    /// Some mesh has vertex colours (glTF `COLOR_0`; `vertex_colors`).
    VertexColors,
    /// Some material reads its alpha (glTF `alphaMode` MASK or BLEND):
    /// discard below the cutoff, the alpha as the output's (`alpha`).
    Alpha,
    /// Some material the scene draws has energy compensation: the
    /// microfacet lobes read the albedo table of the globals
    /// (`energy_compensation`; shaders/brdf/energy.wgsl).
    EnergyCompensation,
    /// Measured materials evaluate their Neural-BRDF network per pixel
    /// instead of looking up a table (`shading.measured_mode = "network"`;
    /// `measured_network`).
    MeasuredNetwork,
    /// Smith's G1 and Λ for Beckmann by Walter et al. 2007's rational
    /// approximation instead of the exact erf form
    /// (`shading.smith_beckmann = "rational"`; `smith_beckmann_rational`).
    SmithBeckmannRational,
    /// Some material emits: `L_e` is added (`emission`).
    Emission,
    /// Some material's ambient occlusion is not 1: it multiplies the
    /// ambient and environment terms (`occlusion`).
    Occlusion,
}

impl Feature {
    /// Every feature, models included.
    pub fn all() -> Vec<Feature> {
        use Feature::*;
        let mut all = vec![
            Flat,
            Tangents,
            Shadows,
            ShadowPcf,
            PcfUniform,
            ShadowOrtho,
            ShadowPerspective,
            ShadowCube,
            ShadowProjective,
            ShadowVertex,
            ShadowPixel,
            LightCount,
            LightRange,
            LightGuard,
            UniformLights,
            UniformShadowViews,
            Display,
            RadianceBits,
            Environment,
            EnvironmentSampled,
            EnvironmentPrefiltered,
            EnvironmentSh,
            Textures,
            NormalMap,
            TwoSided,
            Culling,
            VertexColors,
            Alpha,
            MeasuredNetwork,
            EnergyCompensation,
            SmithBeckmannRational,
            Emission,
            Occlusion,
        ];
        all.extend(ReflectanceModel::ALL.into_iter().map(Model));
        all.extend(
            crate::material::Distribution::ALL
                .iter()
                .map(|&d| Distribution(d)),
        );
        all.extend(crate::material::Geometry::ALL.iter().map(|&g| Geometry(g)));
        all.extend(crate::material::Fresnel::ALL.iter().map(|&f| Fresnel(f)));
        all
    }

    /// How `#if` names this feature in a WGSL file.
    pub fn spelling(self) -> String {
        let term = |kind: &str, name: &str| format!("{kind}={name}");
        let flag = match self {
            Feature::Model(model) => return model.name().into(),
            Feature::Distribution(d) => return term("distribution", d.name()),
            Feature::Geometry(g) => return term("geometry", g.name()),
            Feature::Fresnel(f) => return term("fresnel", f.name()),
            Feature::Flat => "flat",
            Feature::Tangents => "tangents",
            Feature::Shadows => "shadows",
            Feature::ShadowPcf => "shadow_pcf",
            Feature::PcfUniform => "pcf_uniform",
            Feature::ShadowOrtho => "shadow_ortho",
            Feature::ShadowPerspective => "shadow_perspective",
            Feature::ShadowCube => "shadow_cube",
            Feature::ShadowProjective => "shadow_projective",
            Feature::ShadowVertex => "shadow_vertex",
            Feature::ShadowPixel => "shadow_pixel",
            Feature::LightCount => "light_count",
            Feature::LightRange => "light_range",
            Feature::LightGuard => "light_guard",
            Feature::UniformLights => "uniform_lights",
            Feature::UniformShadowViews => "uniform_shadow_views",
            Feature::Display => "display",
            Feature::RadianceBits => "radiance_bits",
            Feature::Environment => "environment",
            Feature::EnvironmentSampled => "environment_sampled",
            Feature::EnvironmentPrefiltered => "environment_prefiltered",
            Feature::EnvironmentSh => "environment_sh",
            Feature::Textures => "textures",
            Feature::NormalMap => "normal_map",
            Feature::TwoSided => "two_sided",
            Feature::Culling => "culling",
            Feature::VertexColors => "vertex_colors",
            Feature::Alpha => "alpha",
            Feature::MeasuredNetwork => "measured_network",
            Feature::EnergyCompensation => "energy_compensation",
            Feature::SmithBeckmannRational => "smith_beckmann_rational",
            Feature::Emission => "emission",
            Feature::Occlusion => "occlusion",
        };
        flag.into()
    }

    /// The feature spelt `name`, if there is one.
    pub fn parse(name: &str) -> Option<Feature> {
        Feature::all().into_iter().find(|f| f.spelling() == name)
    }
}

impl fmt::Display for Feature {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.spelling())
    }
}

impl Feature {
    /// The feature of a shadow projection's lookup code.
    pub fn of_projection(p: Projection) -> Feature {
        match p {
            Projection::Ortho => Feature::ShadowOrtho,
            Projection::Perspective => Feature::ShadowPerspective,
            Projection::Cube => Feature::ShadowCube,
        }
    }

    /// The features of a scene's shadow code (none without shadows).
    pub fn of_shadows(shadows: &ShadowFeatures) -> Vec<Feature> {
        let mut f = Vec::new();
        if shadows.any() {
            f.push(Feature::Shadows);
            if shadows.pcf {
                f.push(Feature::ShadowPcf);
            }
        }
        f.extend(
            shadows
                .projections
                .iter()
                .map(|&p| Feature::of_projection(p)),
        );
        // Perspective and cube layers: the w divide (a spot's lookup calls
        // `shadow_read`, the cube's divides its written-out coordinates).
        if shadows
            .projections
            .iter()
            .any(|p| matches!(p, Projection::Perspective | Projection::Cube))
        {
            f.push(Feature::ShadowProjective);
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_are_distinct_and_parse_back() {
        let all = Feature::all();
        for f in &all {
            assert_eq!(Feature::parse(&f.spelling()), Some(*f));
        }
        assert_eq!(
            Feature::parse("distribution=ggx"),
            Some(Feature::Distribution(Distribution::Ggx))
        );
        let mut names: Vec<_> = all.iter().map(|f| f.spelling()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), all.len(), "two features share a spelling");
        assert_eq!(Feature::parse("shadow"), None);
    }
}
