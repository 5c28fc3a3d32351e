//! The groups of a [`super::ShaderKey`], by what decides them: the lights,
//! the shadow maps, the environment, the materials the scene draws. Each
//! group is derived from the scene here (`for_scene`) and lists the
//! features it switches; a boolean that switches one feature is declared
//! once, as a flag of its group ([`key_group!`]).

use super::features::Feature;
use crate::environment::map::Specular;
use crate::gpu::shadows::{Projection, ShadowFeatures};
use crate::material::{AlphaMode, Material, ReflectanceModel, Sides, SmithBeckmann};
use crate::scene::{Light, LightKind, Scene, TransmissionExitRay, TransmissionMode};
use std::collections::BTreeSet;

/// Declares a group of the key: its plain fields, then its flags, each a
/// `bool` that switches one [`Feature`] (`field => Feature,`), so that
/// declaring a flag here is all the key needs to compile its `#if` blocks
/// ([`super::ShaderKey::features`] reads [`Self::flag_features`]).
macro_rules! key_group {
    (
        $(#[$doc:meta])*
        pub struct $name:ident {
            $($(#[$field_doc:meta])* pub $field:ident: $ty:ty,)*
        }
        flags {
            $($(#[$flag_doc:meta])* $flag:ident => $feature:ident,)+
        }
    ) => {
        $(#[$doc])*
        #[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
        pub struct $name {
            $($(#[$field_doc])* pub $field: $ty,)*
            $(
                $(#[$flag_doc])*
                #[doc = concat!("\n\nSwitches [`Feature::", stringify!($feature), "`].")]
                pub $flag: bool,
            )+
        }

        impl $name {
            /// The features of the flags that are on, in declaration order.
            pub fn flag_features(&self) -> Vec<Feature> {
                [$((self.$flag, Feature::$feature),)+]
                    .into_iter()
                    .filter_map(|(on, feature)| on.then_some(feature))
                    .collect()
            }

            /// `self` with every flag set to `on` (keys that compile every
            /// block: the uber shader, the validation test).
            pub fn with_flags(mut self, on: bool) -> Self {
                $(self.$flag = on;)+
                self
            }
        }
    };
}

key_group! {
    /// The lights' part of the key: which kinds' code is compiled and
    /// which parts of the inverse-square law.
    pub struct LightsKey {
        /// The kinds present (feature `light=KIND` each; `light_dispatch`
        /// when there are several).
        pub kinds: BTreeSet<LightKind>,
    }
    flags {
        /// Some light has a glTF range: the range window of the
        /// inverse-square law is compiled; without, every light's window
        /// is 1 and the code is left out.
        range => LightRange,
        /// Some light may coincide with a shaded point (`light_guard`):
        /// the inverse-square law's zero-distance guard is compiled;
        /// without, no shaded point is at a light, `d² > 0` and the guard
        /// could never fire.
        guard => LightGuard,
    }
}

impl LightsKey {
    /// The lights' part of `scene`'s key.
    pub fn for_scene(scene: &Scene) -> Self {
        LightsKey {
            kinds: scene.lights.iter().map(|l| l.kind()).collect(),
            range: scene.lights.iter().any(|l| {
                matches!(
                    l,
                    Light::Point { range: Some(_), .. } | Light::Spot { range: Some(_), .. }
                )
            }),
            guard: light_guard(scene),
        }
    }

    /// The features of the lights: each kind's, the dispatch between
    /// several, and the flags.
    pub fn features(&self) -> Vec<Feature> {
        let mut f: Vec<Feature> = self.kinds.iter().map(|&k| Feature::Light(k)).collect();
        if self.kinds.len() > 1 {
            f.push(Feature::LightDispatch);
        }
        f.extend(self.flag_features());
        f
    }
}

/// The shadow maps' part of the key.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShadowKey {
    /// Shadow-map projections and filtering in use (empty: no shadow code).
    pub maps: ShadowFeatures,
    /// Compute the shadow-map coordinates per vertex where the key allows
    /// it ([`super::ShaderKey::shadow_coords_per_vertex`]); `false`: always per
    /// pixel (for tests and measurements of the difference).
    pub vertex_coords: bool,
    /// `shading.shadow_coords = "vertex"`: also per vertex where that is
    /// an approximation (one perspective map; see
    /// [`super::ShaderKey::shadow_coords_per_vertex`]).
    pub approximate_coords: bool,
}

impl ShadowKey {
    /// Whether some light casts shadows (else no shadow code at all).
    pub fn any(&self) -> bool {
        self.maps.any()
    }

    /// The features of the shadow maps' projections and filtering (none
    /// without shadows).
    pub fn map_features(&self) -> Vec<Feature> {
        let mut f = Vec::new();
        if self.any() {
            f.push(Feature::Shadows);
            if self.maps.pcf {
                f.push(Feature::ShadowPcf);
            }
        }
        f.extend(self.maps.projections.iter().map(|p| match p {
            Projection::Ortho => Feature::ShadowOrtho,
            Projection::Perspective => Feature::ShadowPerspective,
            Projection::Cube => Feature::ShadowCube,
        }));
        // Perspective and cube layers: the w divide (a spot's lookup calls
        // `shadow_read`, the cube's divides its written-out coordinates).
        if self
            .maps
            .projections
            .iter()
            .any(|p| matches!(p, Projection::Perspective | Projection::Cube))
        {
            f.push(Feature::ShadowProjective);
        }
        f
    }
}

key_group! {
    /// The environment map's part of the key: whether there is one, and
    /// how it lights the glossy part.
    pub struct EnvironmentKey {
        /// The scene has an environment map ([`Feature::Environment`]);
        /// without, the flags below compile nothing.
        pub map: bool,
    }
    flags {
        /// It lights through the whole BRDF, sampled.
        sampled => EnvironmentSampled,
        /// Its glossy part by the split-sum approximation.
        prefiltered => EnvironmentPrefiltered,
        /// Its Phong lobes by SH convolution.
        sh => EnvironmentSh,
    }
}

impl EnvironmentKey {
    /// The environment's part of `scene`'s key.
    pub fn for_scene(scene: &Scene) -> Self {
        let specular = scene.environment.map.as_ref().map(|m| m.settings.specular);
        EnvironmentKey {
            map: specular.is_some(),
            sampled: specular == Some(Specular::Sampled),
            prefiltered: specular == Some(Specular::Prefiltered),
            sh: specular == Some(Specular::Sh),
        }
    }

    /// The environment's features (none without a map).
    pub fn features(&self) -> Vec<Feature> {
        if !self.map {
            return Vec::new();
        }
        let mut f = vec![Feature::Environment];
        f.extend(self.flag_features());
        f
    }
}

key_group! {
    /// What the materials the scene draws (and their meshes) need beyond
    /// their BRDF variants: textures, sides, vertex colours, alpha, how
    /// some terms are evaluated, emission and occlusion.
    pub struct MaterialsKey {
        /// Texture slots read per pixel: the most textures of one material
        /// the scene draws (0: no texture code, else [`Feature::Textures`];
        /// `crate::gpu::textures`).
        pub texture_slots: u32,
        /// Image and sampler pairs of group 2 the shader declares and
        /// reads: the most one material the scene draws binds
        /// (`crate::gpu::textures::binding_count`).
        pub texture_bindings: u32,
        /// Some material has a normal map ([`Feature::NormalMap`], with
        /// textures; tangents and bitangent signs in the vertex stream).
        pub normal_maps: bool,
        /// Some material the scene draws is alpha BLEND: its batches are
        /// drawn last, back to front, by pipelines that blend and keep the
        /// depth (`PipelineCache::compile_scene`); no shader feature of its
        /// own.
        pub alpha_blend: bool,
    }
    flags {
        /// Some material the scene draws is double-sided: vertex shading
        /// computes both sides.
        two_sided => TwoSided,
        /// Some material the scene draws is single-sided.
        culling => Culling,
        /// Some mesh has vertex colours (location 9).
        vertex_colors => VertexColors,
        /// Some material the scene draws reads its alpha (glTF `alphaMode`
        /// MASK or BLEND).
        alpha => Alpha,
        /// Measured materials evaluate their network in WGSL
        /// (`shading.measured_mode = "network"`; only with a measured
        /// variant).
        measured_network => MeasuredNetwork,
        /// Some material the scene draws has energy compensation.
        energy_compensation => EnergyCompensation,
        /// Smith-Beckmann's G1 and Λ by Walter's rational approximation
        /// (`shading.smith_beckmann = "rational"`; only with a variant that
        /// uses them); else the exact erf form.
        smith_beckmann_rational => SmithBeckmannRational,
        /// Some material the scene draws emits (`emission` ≠ 0): without,
        /// the emission add is left out of `reflected_radiance` (adding 0
        /// changes no pixel).
        emission => Emission,
        /// Some material the scene draws has an ambient occlusion other
        /// than 1 (a constant or an occlusion texture): without, the
        /// occlusion multiplies are left out (multiplying by 1 changes no
        /// pixel). The two cost about 6 % of the bench's specialized
        /// Lambert frame on lavapipe (docs/bench/report.md).
        occlusion => Occlusion,
        /// Some material the scene draws turns its shading normal toward
        /// the viewer where it faces away (glTF materials by default):
        /// without, `reflected_radiance` shades the frame it is given.
        facing_normals => FacingNormals,
        /// Some gltf-pbr material the scene draws has one of the layers
        /// below ([`crate::material::layers::GltfLayers`]); without, the
        /// gltf-pbr arm is the core BRDF and no layer code is compiled.
        gltf_layers => GltfLayers,
        /// ... with `ior`, `specular` or `specular_color` off their
        /// defaults or textured.
        layer_ior_specular => LayerIorSpecular,
        /// ... with a clearcoat.
        layer_clearcoat => LayerClearcoat,
        /// ... with a sheen.
        layer_sheen => LayerSheen,
        /// ... with a thin film.
        layer_iridescence => LayerIridescence,
        /// ... anisotropic.
        layer_anisotropy => LayerAnisotropy,
        /// ... transmissive, drawn in screen space (`shading.transmission
        /// = "screen"`): its batches per object, after the transmission
        /// image (src/gpu/transmission.rs), with bind group 4.
        layer_transmission => LayerTransmission,
        /// ... and a volume's light crosses its second interface
        /// (`shading.transmission_exit`).
        transmission_exit => TransmissionExit,
        /// ... and a volume among them disperses.
        transmission_dispersion => TransmissionDispersion,
        /// ... and a volume's refracted ray is traced past its exit
        /// (`shading.transmission_exit_ray = "traced"`).
        transmission_exit_traced => TransmissionExitTraced,
        /// ... transmitting diffusely, with light through surfaces drawn.
        layer_diffuse_transmission => LayerDiffuseTransmission,
    }
}

impl MaterialsKey {
    /// The materials' part of `scene`'s key (before
    /// [`super::ShaderKey::new`] drops the flags its variants cannot use).
    pub fn for_scene(scene: &Scene) -> Self {
        let drawn = || scene.meshes.iter().map(|m| &scene.materials[m.material]);
        let any = |test: fn(&Material) -> bool| drawn().any(test);
        let screen = scene.transmission.mode == TransmissionMode::Screen;
        let transmission = screen && any(Material::transmits_specularly);
        let diffuse_transmission = screen
            && any(|m| m.model == ReflectanceModel::GltfPbr && m.layers.diffuse_transmission > 0.0);
        MaterialsKey {
            texture_slots: crate::gpu::textures::slot_count(scene),
            texture_bindings: crate::gpu::textures::binding_count(scene),
            normal_maps: crate::gpu::textures::has_normal_maps(scene),
            alpha_blend: any(|m| m.alpha_mode == AlphaMode::Blend),
            two_sided: any(|m| m.sides == Sides::Both),
            culling: any(|m| m.sides == Sides::Front),
            vertex_colors: scene.meshes.iter().any(|m| !m.colors.is_empty()),
            alpha: any(|m| m.alpha_mode != AlphaMode::Opaque),
            measured_network: scene.measured_network,
            energy_compensation: any(|m| m.energy_compensation),
            smith_beckmann_rational: scene.smith_beckmann == SmithBeckmann::Rational,
            emission: any(Material::emits),
            occlusion: any(Material::has_occlusion),
            facing_normals: any(|m| m.facing_normals),
            gltf_layers: any(|m| !m.gltf_layers_used().is_empty())
                || transmission
                || diffuse_transmission,
            layer_ior_specular: any(|m| m.gltf_layers_used().ior_specular),
            layer_clearcoat: any(|m| m.gltf_layers_used().clearcoat),
            layer_sheen: any(|m| m.gltf_layers_used().sheen),
            layer_iridescence: any(|m| m.gltf_layers_used().iridescence),
            layer_anisotropy: any(|m| m.gltf_layers_used().anisotropy),
            layer_transmission: transmission,
            transmission_exit: transmission && scene.transmission.exit,
            transmission_dispersion: transmission
                && any(|m| m.transmits_specularly() && m.layers.dispersion > 0.0),
            transmission_exit_traced: transmission
                && scene.transmission.exit_ray == TransmissionExitRay::Traced
                && any(|m| m.transmits_specularly() && m.layers.thickness > 0.0),
            layer_diffuse_transmission: diffuse_transmission,
        }
    }

    /// The materials' features: textures (and normal maps with them), then
    /// the flags.
    pub fn features(&self) -> Vec<Feature> {
        let mut f = Vec::new();
        if self.texture_slots > 0 {
            f.push(Feature::Textures);
            if self.normal_maps {
                f.push(Feature::NormalMap);
            }
        }
        f.extend(self.flag_features());
        f
    }
}

/// Whether some light of `scene` with a position (point, spot, area
/// sample) may coincide with a point the GPU shades, so that its
/// inverse-square law needs the zero-distance guard (`d² = 0`: no light
/// instead of 0/0). A shaded point is interpolated between a triangle's
/// corners, so it lies in the triangle's mesh's bounding box up to f32
/// rounding (a few units in the last place of the coordinates, about
/// 10⁻⁷ relative); a light outside every mesh's box grown by a margin
/// far above that (10⁻⁴ of the box's size plus its largest coordinate)
/// is at a distance of at least the margin from every shaded point, so
/// its `d²` is positive and the guard would never fire. The guard stays
/// for a light inside or on some box (an area light lying on a wall, a
/// light inside a room): the per-mesh boxes are a cheap test, not the
/// exact distance to the triangles. The left-out guard changes no
/// pixel.
pub fn light_guard(scene: &Scene) -> bool {
    let boxes: Vec<_> = scene
        .meshes
        .iter()
        .filter_map(|m| crate::scene::mesh::bounds(m.positions.iter().copied()))
        .map(|(lo, hi)| {
            let margin = 1e-4 * ((hi - lo).max_element() + lo.abs().max(hi.abs()).max_element());
            (lo - margin, hi + margin)
        })
        .collect();
    scene.lights.iter().filter_map(|l| l.position()).any(|p| {
        !p.is_finite()
            || boxes
                .iter()
                .any(|(lo, hi)| p.cmpge(*lo).all() && p.cmple(*hi).all())
    })
}
