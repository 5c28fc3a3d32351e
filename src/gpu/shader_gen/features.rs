//! The features a WGSL block can be conditional on (`#if NAME`, see
//! [`super::preprocess`]): a closed set, so that a misspelt name in a
//! shader is an error rather than a line silently kept or dropped.
//!
//! Each feature is declared once, in the list given to [`features!`]
//! below: a flag is one line (variant and spelling), a family of terms
//! (the reflectance models, the Cook-Torrance terms, the light kinds) is
//! one line naming its enum and the prefix of its spellings. Which
//! features a scene's shader has on is derived from its
//! [`super::ShaderKey`] ([`super::ShaderKey::features`]).

use crate::material::{Distribution, Fresnel, Geometry, ReflectanceModel};
use crate::scene::LightKind;
use std::fmt;

/// Declares [`Feature`] from its flags (`Variant = "spelling",`) and its
/// families of terms (`Variant(Enum) = "prefix",`: one feature per value
/// of `Enum::ALL`, spelt the prefix and the value's `name()`), with
/// [`Feature::all`] and [`Feature::spelling`].
macro_rules! features {
    (
        terms {
            $($(#[$term_doc:meta])* $term:ident($ty:ty) = $prefix:literal,)+
        }
        flags {
            $($(#[$flag_doc:meta])* $flag:ident = $spelling:literal,)+
        }
    ) => {
        /// One condition of the shader sources, with its WGSL spelling
        /// ([`Feature::spelling`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Feature {
            $(
                $(#[$term_doc])*
                #[doc = concat!("\n\nSpelt `", $prefix, "NAME`.")]
                $term($ty),
            )+
            $(
                $(#[$flag_doc])*
                #[doc = concat!("\n\nSpelt `", $spelling, "`.")]
                $flag,
            )+
        }

        impl Feature {
            /// Every feature: the flags, then each family's terms.
            pub fn all() -> Vec<Feature> {
                let mut all = vec![$(Feature::$flag,)+];
                $(all.extend(<$ty>::ALL.iter().map(|&value| Feature::$term(value)));)+
                all
            }

            /// How `#if` names this feature in a WGSL file.
            pub fn spelling(self) -> String {
                match self {
                    $(Feature::$term(value) => format!("{}{}", $prefix, value.name()),)+
                    $(Feature::$flag => $spelling.into(),)+
                }
            }
        }
    };
}

features! {
    terms {
        /// The scene uses this reflectance model (spelt as the model's
        /// contract name, e.g. `cook-torrance`): its `eval_brdf` arm and its
        /// helpers are compiled.
        Model(ReflectanceModel) = "",
        /// Some Cook-Torrance material uses this distribution
        /// (`distribution=ggx`): its `switch` arm is compiled.
        Distribution(Distribution) = "distribution=",
        /// Some Cook-Torrance material uses this geometry term
        /// (`geometry=smith`).
        Geometry(Geometry) = "geometry=",
        /// Some Cook-Torrance or mirror material uses this Fresnel term
        /// (`fresnel=schlick`).
        Fresnel(Fresnel) = "fresnel=",
        /// Some light is of this kind (`light=spot`): its arm of
        /// `light_incidence` is compiled (shaders/lights/incidence.wgsl).
        Light(LightKind) = "light=",
    }
    flags {
        /// Flat shading: one colour per triangle.
        Flat = "flat",
        /// Some model needs a tangent frame in the vertex stream.
        Tangents = "tangents",
        /// Some light casts shadows.
        Shadows = "shadows",
        /// Some shadowed light filters with PCF.
        ShadowPcf = "shadow_pcf",
        /// Every PCF light has the same kernel, compiled in as `PCF_RADIUS`.
        PcfUniform = "pcf_uniform",
        /// Orthographic shadow maps (directional lights).
        ShadowOrtho = "shadow_ortho",
        /// Perspective shadow maps (spot lights).
        ShadowPerspective = "shadow_perspective",
        /// Cube shadow maps (point and area lights).
        ShadowCube = "shadow_cube",
        /// Perspective or cube maps: the lookup with the w divide (only
        /// spot maps call it since the cube lookup writes its clip
        /// coordinates out, a cube-only shader compiles it unused).
        ShadowProjective = "shadow_projective",
        /// The shadow-map coordinates are computed per vertex
        /// ([`super::ShaderKey::shadow_coords_per_vertex`]).
        ShadowVertex = "shadow_vertex",
        /// The shadow-map coordinates are computed per pixel.
        ShadowPixel = "shadow_pixel",
        /// The light count is compiled in as `LIGHT_COUNT`.
        LightCount = "light_count",
        /// The lights are of several kinds: `light_incidence` switches on
        /// `Light.kind` (a one-kind scene calls its kind's function).
        LightDispatch = "light_dispatch",
        /// Some light has a glTF range: the inverse-square law's range
        /// window is compiled ([`super::LightsKey::range`]).
        LightRange = "light_range",
        /// Some light may sit on a shaded point: the inverse-square law's
        /// zero-distance guard is compiled ([`super::LightsKey::guard`]).
        LightGuard = "light_guard",
        /// The lights are a uniform array (else storage).
        UniformLights = "uniform_lights",
        /// The shadow views are a uniform array.
        UniformShadowViews = "uniform_shadow_views",
        /// The target is a display surface: exposure and sRGB in the shader.
        Display = "display",
        /// The target is `Rgba32Uint` holding the radiance's f32 bits, for
        /// adapters that cannot render into `Rgba32Float`.
        RadianceBits = "radiance_bits",
        /// The scene has an environment map: group 3, the map lights every
        /// surface and is the background.
        Environment = "environment",
        /// The environment lights through the whole BRDF with N sampled
        /// directions.
        EnvironmentSampled = "environment_sampled",
        /// The environment's glossy part by the split-sum approximation.
        EnvironmentPrefiltered = "environment_prefiltered",
        /// The Phong lobes by SH convolution.
        EnvironmentSh = "environment_sh",
        /// Some material has textures: UVs in the vertex stream, bind group
        /// 2 and shaders/textures.wgsl.
        Textures = "textures",
        /// Some material has a normal map: tangents and their bitangent
        /// signs in the vertex stream, the frame turned per pixel.
        NormalMap = "normal_map",
        /// Some material is double-sided (glTF `doubleSided`): vertex
        /// shading computes both sides.
        TwoSided = "two_sided",
        /// Some material is single-sided (glTF `doubleSided: false`): back
        /// faces are discarded.
        Culling = "culling",
        /// Some mesh has vertex colours (glTF `COLOR_0`).
        VertexColors = "vertex_colors",
        /// Some material reads its alpha (glTF `alphaMode` MASK or BLEND):
        /// discard below the cutoff, the alpha as the output's.
        Alpha = "alpha",
        /// Measured materials evaluate their Neural-BRDF network per pixel
        /// instead of looking up a table (`shading.measured_mode =
        /// "network"`).
        MeasuredNetwork = "measured_network",
        /// Some material the scene draws has energy compensation: the
        /// microfacet lobes read the albedo table of the globals
        /// (shaders/brdf/energy.wgsl).
        EnergyCompensation = "energy_compensation",
        /// Smith's G1 and Λ for Beckmann by Walter et al. 2007's rational
        /// approximation instead of the exact erf form
        /// (`shading.smith_beckmann = "rational"`).
        SmithBeckmannRational = "smith_beckmann_rational",
        /// Some material emits: `L_e` is added.
        Emission = "emission",
        /// Some material's ambient occlusion is not 1: it multiplies the
        /// ambient and environment terms.
        Occlusion = "occlusion",
        /// Some material turns its shading normal toward the viewer where
        /// it faces away (`Material::facing_normals`, glTF materials):
        /// `facing_frame` in shaders/surface.wgsl.
        FacingNormals = "facing_normals",
        /// Some gltf-pbr material the scene draws has a layer (any of the
        /// five below): `Material.layers`, the layer files
        /// (shaders/brdf/gltf_layers/) and the layered stack in the
        /// gltf-pbr arm.
        GltfLayers = "gltf_layers",
        /// Some gltf-pbr material has `KHR_materials_ior` or
        /// `KHR_materials_specular` off their defaults (or a texture on
        /// their keys): the layered base.
        LayerIorSpecular = "layer_ior_specular",
        /// Some gltf-pbr material has a clearcoat (`clearcoat > 0`).
        LayerClearcoat = "layer_clearcoat",
        /// Some gltf-pbr material has a sheen (`sheen_color ≠ 0`): the
        /// sheen lobe and its albedo table (group 0, binding 4).
        LayerSheen = "layer_sheen",
        /// Some gltf-pbr material has a thin film (`iridescence > 0` and a
        /// thickness > 0).
        LayerIridescence = "layer_iridescence",
        /// Some gltf-pbr material is anisotropic (`anisotropy_strength >
        /// 0`): the anisotropic lobe, and tangents in the vertex stream.
        LayerAnisotropy = "layer_anisotropy",
        /// Some gltf-pbr material transmits (`transmission > 0`) and the
        /// scene draws light through surfaces (`shading.transmission =
        /// "screen"`): the diffuse part's `1 − T`, the transmission
        /// image (group 4) and the light read from it
        /// (shaders/transmission.wgsl).
        LayerTransmission = "layer_transmission",
        /// The light leaving a transmissive volume is weighted by its
        /// second interface (`shading.transmission_exit`, with
        /// `layer_transmission`).
        TransmissionExit = "transmission_exit",
        /// Some transmissive volume disperses (`dispersion > 0`, with
        /// `layer_transmission`): the image is read three times, one
        /// index of refraction per channel.
        TransmissionDispersion = "transmission_dispersion",
        /// A volume's refracted ray is traced in screen space to its exit
        /// and past it (`shading.transmission_exit_ray = "traced"`, with
        /// `layer_transmission` and a transmissive volume drawn): the
        /// back faces' and the opaque scene's depth in group 4
        /// (shaders/transmission_traced.wgsl).
        TransmissionExitTraced = "transmission_exit_traced",
        /// Some gltf-pbr material transmits diffusely
        /// (`diffuse_transmission > 0`) and the scene draws light through
        /// surfaces (`shading.transmission = "screen"`): the diffuse
        /// part's `1 − D`, Lambert on the far side for the lights behind
        /// and the environment's irradiance there
        /// (shaders/brdf/gltf_layers/transmission.wgsl).
        LayerDiffuseTransmission = "layer_diffuse_transmission",
    }
}

impl Feature {
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
        assert_eq!(
            Feature::parse("light=area"),
            Some(Feature::Light(LightKind::AreaSample))
        );
        let mut names: Vec<_> = all.iter().map(|f| f.spelling()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), all.len(), "two features share a spelling");
        assert_eq!(Feature::parse("shadow"), None);
    }
}
