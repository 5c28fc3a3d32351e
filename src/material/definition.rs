//! The [`Material`] struct: every parameter of one material, validated
//! once and then trusted by both renderers, with how its alpha and faces
//! are read ([`AlphaMode`], [`Sides`]) and the part of it that decides the
//! shader code ([`BrdfVariant`]). Its methods here need nothing above it;
//! those that read the model's row in the table of models or evaluate the
//! BRDF (`Material::new`, `validate`, `brdf`, `f_r`, `variant`,
//! `follow_default_weights`) are in `material/mod.rs`, above the table
//! and the BRDFs.

use super::conductors::Metal;
use super::model::ReflectanceModel;
use super::terms::{Denominator, Distribution, Fresnel, Geometry};
use super::{measured, texture};
use crate::base::Rgb;

/// Smallest roughness (m, α or σ) the BRDFs evaluate: below it `1/α²`
/// leaves `f32`'s normal range on the GPU. Smaller values given by the user
/// are accepted and evaluated as this floor; lights of finite size widen
/// the lobe further (see `crate::reference::shading`).
pub const ROUGHNESS_FLOOR: f64 = 1e-4;

/// A validated material. Build it with [`Material::new`] and
/// [`Material::validate`]; renderers trust what they get.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub model: ReflectanceModel,
    /// Ambient coefficient: the reflected ambient term is `k_a · L_a`.
    pub k_a: Rgb,
    /// Diffuse albedo: Lambert `f_r = k_d / π`. The lecture's `k_d` is in
    /// 1/sr and equals gonio's `k_d / π`.
    pub k_d: Rgb,
    /// Specular coefficient of the glossy lobe (the mirror's reflectance).
    pub k_s: Rgb,
    /// Phong / Blinn-Phong exponent, in [0, 1e6].
    pub k_e: f64,
    /// Cook-Torrance `m`: Beckmann's RMS slope, GGX's α, the angle (radians)
    /// of the lecture's Blinn and Gaussian distributions; in (0, 1]. For
    /// gltf-pbr it is glTF's *perceptual* roughness r, and GGX's α is r².
    pub roughness: f64,
    /// Ward RMS slopes along the tangent and the bitangent (equal for the
    /// isotropic model); in (0, 1].
    pub sigma_x: f64,
    pub sigma_y: f64,
    /// Oren-Nayar's σ: the standard deviation of the facets' slope angle,
    /// in radians, in [0, π/2] (scene-file key `sigma` for those models).
    pub facet_sigma: f64,
    /// Conductor complex index of refraction η + iκ, per channel.
    pub eta: Rgb,
    pub kappa: Rgb,
    /// Dielectric indices of refraction, incident and transmitted side.
    pub eta_i: f64,
    pub eta_t: f64,
    pub distribution: Distribution,
    pub geometry: Geometry,
    pub fresnel: Fresnel,
    pub denominator: Denominator,
    /// The metal whose published spectral table the reference evaluates
    /// the Fresnel term from (scene-file key `spectral_metal`,
    /// [`super::spectral_metal`]); η, κ above then hold its three-channel
    /// preset, which the GPU renders. `None`: the three channels.
    pub spectral_metal: Option<Metal>,
    /// The measured BRDF of a `measured` material (scene-file key
    /// `measured`); `None` for the other models.
    pub measured: Option<&'static measured::MeasuredBrdf>,
    /// gltf-pbr's base colour `b` (glTF's `baseColorFactor`, linear), in
    /// [0, 1]³.
    pub base_color: Rgb,
    /// gltf-pbr's metallic `m` (glTF's `metallicFactor`), in [0, 1].
    pub metallic: f64,
    /// gltf-pbr's layers (`KHR_materials_ior`, `_specular`, `_clearcoat`,
    /// `_sheen`, `_iridescence`, `_anisotropy`; contract "Layered glTF
    /// materials"): the glTF defaults leave the core BRDF unchanged.
    pub layers: super::layers::GltfLayers,
    /// abc's distribution `D = A / (1 + B(1 − cos θ_h))^C`: `A` per
    /// channel (≥ 0, in 1/sr: the lobe's peak), `B` (> 0, the inverse
    /// width in `1 − cos θ_h`) and `C` (> 0, the tail's power).
    pub abc_a: Rgb,
    pub abc_b: f64,
    pub abc_c: f64,
    /// Emitted radiance [W/(m²·sr)], added to `L_o` (every model; glTF's
    /// `emissiveFactor` × `KHR_materials_emissive_strength`). It lights
    /// nothing else: gonio's lights are the scene's lights.
    pub emission: Rgb,
    /// Parameters that vary over the surface: each texture multiplies the
    /// constant above it names (empty: a uniform material).
    pub textures: Vec<texture::MaterialTexture>,
    /// Which faces are drawn and how a back face is lit (glTF
    /// `doubleSided`).
    pub sides: Sides,
    /// The base colour's alpha `a` (glTF `baseColorFactor[3]`), in
    /// [0, 1]; the base-colour texture's A and `COLOR_0`'s A multiply it
    /// per point. Read only as [`Self::alpha_mode`] says.
    pub alpha: f64,
    /// How alpha is read (glTF `alphaMode`; see [`AlphaMode`]).
    pub alpha_mode: AlphaMode,
    /// The ambient occlusion `o` at a point, in [0, 1]: 1 for the
    /// material, an occlusion texture sets it per point (glTF
    /// `occlusionTexture`, `1 + strength·(R − 1)`). It multiplies the
    /// ambient term and every environment term (diffuse and specular),
    /// never a direct light (`crate::reference::shading::reflected_radiance`).
    pub occlusion: f64,
    /// Energy compensation (multiple scattering, `brdf::energy`; scene key
    /// `energy_compensation`, off by default), for the models whose row
    /// offers it (`ModelRow::energy_compensation`).
    pub energy_compensation: bool,
    /// The shading normal turned toward the viewer where it faces away
    /// ([`crate::base::frame::SurfaceFrame::facing`]): on for glTF
    /// materials (`[gltf] facing_normals`, default true), as the other
    /// glTF renderers never draw such a silhouette black; off for a scene
    /// file's materials, whose shading is the lecture's as written.
    pub facing_normals: bool,
}

/// glTF 2.0 `alphaMode` (§3.9.4 "Alpha Coverage"): what the base colour's
/// alpha `a = baseColorFactor.a × baseColorTexture.a × COLOR_0.a` does.
/// Both renderers read it the same way (GPU: `surface_alpha` and
/// `fs_main` in shaders/raster_pixel_shaded.wgsl; reference:
/// `reference::renderer`, which continues a ray through what the GPU
/// discards or blends).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// `a` is ignored: fully opaque (glTF's default, every scene-file
    /// material).
    #[default]
    Opaque,
    /// Opaque where `a ≥ cutoff`, absent (the ray goes on) where
    /// `a < cutoff` (glTF `alphaCutoff`, default 0.5).
    Mask { cutoff: f64 },
    /// Composited over what lies behind: `L = a·L_surface + (1 − a)·L_behind`
    /// (straight, not premultiplied alpha: glTF's "over" operator, as the
    /// Khronos sample viewer blends with SRC_ALPHA, ONE_MINUS_SRC_ALPHA).
    Blend,
}

impl AlphaMode {
    /// The GPU's `Material.alpha_mode`: 0 opaque, 1 mask, 2 blend.
    pub fn code(self) -> u32 {
        match self {
            AlphaMode::Opaque => 0,
            AlphaMode::Mask { .. } => 1,
            AlphaMode::Blend => 2,
        }
    }

    /// The alpha below which a point is absent: the cutoff for MASK, 0
    /// (nothing) otherwise (`a < 0` never holds). The GPU's
    /// `Material.alpha_cutoff`.
    pub fn cutoff(self) -> f64 {
        match self {
            AlphaMode::Mask { cutoff } => cutoff,
            _ => 0.0,
        }
    }

    /// Whether a point of alpha `a` is absent (the GPU discards it, the
    /// reference's ray goes on): MASK below its cutoff.
    pub fn discards(self, a: f64) -> bool {
        a < self.cutoff()
    }

    /// The opacity a present point of alpha `a` composites with: `a` for
    /// BLEND, 1 otherwise.
    pub fn opacity(self, a: f64) -> f64 {
        match self {
            AlphaMode::Blend => a,
            _ => 1.0,
        }
    }
}

/// Which faces of a mesh with a material are drawn, and how a back face
/// is lit. The GPU's `Material.sides` holds [`Sides::code`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Sides {
    /// Both faces drawn, a back face lit with the front's normal (so the
    /// one-sided `f_r` leaves it ambient and emission only): the lecture's
    /// surfaces, every scene-file material.
    #[default]
    Unculled,
    /// glTF `doubleSided: false` (its default): back faces are culled.
    Front,
    /// glTF `doubleSided: true`: a back face is lit with the flipped
    /// normal (and tangent frame), as glTF asks.
    Both,
}

impl Sides {
    /// The GPU's code: 0 unculled, 1 front only, 2 both.
    pub fn code(self) -> u32 {
        match self {
            Sides::Unculled => 0,
            Sides::Front => 1,
            Sides::Both => 2,
        }
    }
}

impl Material {
    /// Whether the material emits anywhere: a non-zero `emission` (an
    /// emission texture only scales it). The GPU compiles the emission
    /// term only for a scene with such a material (`MaterialsKey::emission`).
    pub fn emits(&self) -> bool {
        self.emission != Rgb::ZERO
    }

    /// Whether its ambient occlusion may differ from 1 somewhere: the
    /// constant, or an occlusion texture (`MaterialsKey::occlusion`).
    pub fn has_occlusion(&self) -> bool {
        self.occlusion != 1.0
            || self
                .textures
                .iter()
                .any(|t| matches!(t.target, texture::TextureTarget::Occlusion { .. }))
    }

    /// Which glTF layers a `gltf-pbr` material uses (none for another
    /// model): the GPU compiles each layer only where a drawn material
    /// uses it (`MaterialsKey::layer_*`).
    pub fn gltf_layers_used(&self) -> crate::material::layers::LayersUsed {
        if self.model != crate::material::ReflectanceModel::GltfPbr {
            return Default::default();
        }
        self.layers.used(|key| self.is_textured(key))
    }

    /// Whether it is a `gltf-pbr` material with `transmission > 0` (the
    /// specular BTDF of `KHR_materials_transmission`): what the GPU's
    /// transmission pass draws (src/gpu/transmission.rs).
    pub fn transmits_specularly(&self) -> bool {
        self.model == crate::material::ReflectanceModel::GltfPbr && self.layers.transmission > 0.0
    }

    /// This material as the renderers evaluate it for a given roughness
    /// floor (the pixel footprint, [`crate::scene::Scene::roughness_floor`]):
    /// `roughness`, `sigma_x`, `sigma_y` become `sqrt(r² + floor²)`, never
    /// below [`ROUGHNESS_FLOOR`]. Adding in quadrature is the width of a
    /// lobe convolved with the footprint (both roughly Gaussian in slope),
    /// so a point light seen in a perfectly smooth surface still lights
    /// about one pixel instead of falling between pixel centres.
    ///
    /// gltf-pbr's `roughness` is the perceptual r (α = r²): its α is widened
    /// the same way, `r' = sqrt(α')`.
    ///
    /// A lobe width a texture multiplies is left as it is here: the floor
    /// widens the width at the pixel, texel included, so the renderers
    /// widen it after texturing ([`Material::with_textured_widths_floored`];
    /// widening first and then multiplying by a texel of 0 would take the
    /// floor away).
    pub fn with_roughness_floor(&self, floor: f64) -> Material {
        self.with_widths_floored(floor, |key| !self.is_textured(key))
    }

    /// The second half of [`Material::with_roughness_floor`] for a
    /// textured material: the floor applied to the lobe widths its
    /// textures multiplied (`self` is the material after texturing).
    /// GPU twin: `textured_widths_floored` in shaders/textures.wgsl.
    pub fn with_textured_widths_floored(&self, floor: f64) -> Material {
        self.with_widths_floored(floor, |key| self.is_textured(key))
    }

    /// Whether a texture multiplies the parameter with scene-file key `key`.
    pub fn is_textured(&self, key: &str) -> bool {
        self.textures
            .iter()
            .any(|t| matches!(t.target, texture::TextureTarget::Param(k) if k == key))
    }

    fn with_widths_floored(&self, floor: f64, applies: impl Fn(&str) -> bool) -> Material {
        let widen = |key: &str, r: f64| {
            if applies(key) {
                (r * r + floor * floor).sqrt().max(ROUGHNESS_FLOOR)
            } else {
                r
            }
        };
        let roughness = if self.model == ReflectanceModel::GltfPbr {
            widen("roughness", self.roughness * self.roughness).sqrt()
        } else {
            widen("roughness", self.roughness)
        };
        Material {
            roughness,
            sigma_x: widen("sigma_x", self.sigma_x),
            sigma_y: widen("sigma_y", self.sigma_y),
            ..self.clone()
        }
    }

    /// The material under a vertex colour `c` (glTF `COLOR_0`, RGB) of
    /// alpha `a`: the colours a base colour drives, `k_a`, `k_d` and
    /// `base_color`, multiplied by `c`, and its alpha by `a` (glTF:
    /// "COLOR_0 ... multiplies the base color").
    /// GPU twin: `vertex_coloured` in shaders/surface.wgsl.
    pub fn vertex_coloured(&self, c: Rgb, a: f64) -> Material {
        Material {
            k_a: self.k_a * c,
            k_d: self.k_d * c,
            base_color: self.base_color * c,
            alpha: self.alpha * a,
            ..self.clone()
        }
    }

    /// The measured BRDF a `measured` material renders (the default
    /// built-in one if none was chosen); `None` for the other models.
    pub fn measured_brdf(&self) -> Option<&'static measured::MeasuredBrdf> {
        (self.model == ReflectanceModel::Measured)
            .then(|| self.measured.unwrap_or_else(measured::default_brdf))
    }
}

/// A model with its chosen terms: the unit of shader specialization.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BrdfVariant {
    pub model: ReflectanceModel,
    pub distribution: Option<Distribution>,
    pub geometry: Option<Geometry>,
    pub fresnel: Option<Fresnel>,
    pub denominator: Option<Denominator>,
}

impl BrdfVariant {
    /// e.g. `cook-torrance(ggx, smith, conductor, microfacet)`.
    pub fn describe(&self) -> String {
        let terms: Vec<&str> = [
            self.distribution.map(|t| t.name()),
            self.geometry.map(|t| t.name()),
            self.fresnel.map(|t| t.name()),
            self.denominator.map(|t| t.name()),
        ]
        .into_iter()
        .flatten()
        .collect();
        if terms.is_empty() {
            self.model.name().to_string()
        } else {
            format!("{}({})", self.model.name(), terms.join(", "))
        }
    }
}
