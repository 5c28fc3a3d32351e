//! The layer parameters of a `gltf-pbr` material: the keys of the
//! glTF material extensions (contract, "Layered glTF materials"), a plain
//! value the material holds and its BRDF (`brdf::gltf_layers`) reads.

use crate::base::{Rgb, named_enum};
use glam::{DVec2, DVec3};

named_enum!(
    /// One additive term of a `gltf-pbr` material's layered `f_r`, as the
    /// explorer shows it apart (`gonio brdf --layer`, the viewer's
    /// `plots.layer`): the composition (contract, "Composition")
    /// `f_r = (1 − k F_c)(c_sh D_sh V_sh + σ · material) + k F_c G_{α_c}`
    /// is a sum of three terms, each layer's lobe weighted by what the
    /// layers above let through. `brdf::gltf_layers::stack::gltf_layer_term`
    /// evaluates them; their sum is `f_r`.
    LayerTerm, "layer" {
        /// The whole `f_r`.
        All = "all",
        /// The base `material` (with ior, specular, iridescence and
        /// anisotropy inside it) times `σ (1 − k F_c)`; the whole `f_r` of
        /// a model without layers.
        Base = "base",
        /// The sheen lobe `c_sh D_sh V_sh` times `1 − k F_c`.
        Sheen = "sheen",
        /// The coat's lobe `k F_c G_{α_c}`.
        Clearcoat = "clearcoat",
    }
);

/// The layer parameters of a `gltf-pbr` material (the contract's keys,
/// with its defaults); the core's `base_color`, `metallic` and
/// `roughness` are passed beside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfLayers {
    /// `KHR_materials_ior.ior`; 0 is the specular-glossiness mode (the
    /// Fresnel term of the IOR is 1).
    pub ior: f64,
    /// `KHR_materials_specular.specularFactor`, `s_w`.
    pub specular: f64,
    /// `…specularColorFactor`, `c_s` (may exceed 1).
    pub specular_color: Rgb,
    /// `KHR_materials_clearcoat.clearcoatFactor`, `k`.
    pub clearcoat: f64,
    /// `…clearcoatRoughnessFactor`, perceptual `r_c` (α_c = r_c²).
    pub clearcoat_roughness: f64,
    /// `KHR_materials_sheen.sheenColorFactor`, `c_sh`.
    pub sheen_color: Rgb,
    /// `…sheenRoughnessFactor`, perceptual `r_sh`.
    pub sheen_roughness: f64,
    /// `KHR_materials_iridescence.iridescenceFactor`, `ι`.
    pub iridescence: f64,
    /// `…iridescenceIor`, the film's index `η_f`.
    pub iridescence_ior: f64,
    /// The film's thickness `d` \[nm\].
    pub iridescence_thickness: f64,
    /// `KHR_materials_anisotropy.anisotropyStrength`, `s_a`.
    pub anisotropy_strength: f64,
    /// `…anisotropyRotation`, `ρ` \[rad\] from `t` towards `b`. An
    /// `anisotropy_texture` adds its direction's angle per point
    /// (`material::texture::decode_anisotropy`).
    pub anisotropy_rotation: f64,
    /// The coat's normal in the shading frame's coordinates `(t, b, n)`:
    /// `(0, 0, 1)` (the shading normal) unless a `clearcoat_normal_texture`
    /// gives the coat its own normal at a point (the reference's renderer
    /// and the GPU's fragment stage write it there). Not a scene-file key.
    pub clearcoat_normal: DVec3,
    /// `KHR_materials_transmission.transmissionFactor`: the share of the
    /// dielectric base's diffuse part replaced by the specular BTDF.
    pub transmission: f64,
    /// `KHR_materials_volume.thicknessFactor` (mesh space): 0 is a thin
    /// wall, `> 0` makes the closed mesh bound a volume.
    pub thickness: f64,
    /// `…attenuationDistance`: the path length after which light keeps
    /// `attenuation_color` (Beer–Lambert); `∞` is a clear medium.
    pub attenuation_distance: f64,
    /// `…attenuationColor`.
    pub attenuation_color: Rgb,
    /// `KHR_materials_dispersion.dispersion`, `20 / V_d` (Abbe number
    /// `V_d`); 0 is no dispersion.
    pub dispersion: f64,
    /// `KHR_materials_diffuse_transmission.diffuseTransmissionFactor`: the
    /// share of the diffuse part transmitted as Lambert on the far side.
    pub diffuse_transmission: f64,
    /// `…diffuseTransmissionColorFactor`.
    pub diffuse_transmission_color: Rgb,
}

impl GltfLayers {
    /// `(cos ρ, sin ρ)`: the anisotropy direction in the frame `(t, b)`
    /// (what the GPU is given, computed here in `f64`).
    pub fn anisotropy_direction(&self) -> DVec2 {
        let (s, c) = self.anisotropy_rotation.sin_cos();
        DVec2::new(c, s)
    }
}

impl Default for GltfLayers {
    /// The glTF defaults: every layer off, the core BRDF unchanged.
    fn default() -> Self {
        GltfLayers {
            ior: 1.5,
            specular: 1.0,
            specular_color: Rgb::ONE,
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            sheen_color: Rgb::ZERO,
            sheen_roughness: 0.0,
            iridescence: 0.0,
            iridescence_ior: 1.3,
            iridescence_thickness: 400.0,
            anisotropy_strength: 0.0,
            anisotropy_rotation: 0.0,
            clearcoat_normal: DVec3::Z,
            transmission: 0.0,
            thickness: 0.0,
            attenuation_distance: f64::INFINITY,
            attenuation_color: Rgb::ONE,
            dispersion: 0.0,
            diffuse_transmission: 0.0,
            diffuse_transmission_color: Rgb::ONE,
        }
    }
}

/// Which layers a material's [`GltfLayers`] switch on (each layer's
/// contract condition; a texture multiplies a constant, so a layer whose
/// constant switches it off stays off, except the base's ior and
/// specular, whose defaults are not zero).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LayersUsed {
    /// `ior`, `specular` or `specular_color` off their defaults, or textured.
    pub ior_specular: bool,
    pub clearcoat: bool,
    pub sheen: bool,
    pub iridescence: bool,
    pub anisotropy: bool,
}

impl LayersUsed {
    /// No layer: the core BRDF.
    pub fn is_empty(&self) -> bool {
        *self == LayersUsed::default()
    }
}

impl GltfLayers {
    /// The layers these parameters switch on; `textured(key)` says whether
    /// a texture multiplies the parameter of scene-file key `key`.
    pub fn used(&self, textured: impl Fn(&str) -> bool) -> LayersUsed {
        let d = GltfLayers::default();
        LayersUsed {
            ior_specular: self.ior != d.ior
                || self.specular != d.specular
                || self.specular_color != d.specular_color
                || ["ior", "specular", "specular_color"]
                    .into_iter()
                    .any(textured),
            clearcoat: self.clearcoat > 0.0,
            sheen: self.sheen_color != Rgb::ZERO,
            iridescence: self.iridescence > 0.0 && self.iridescence_thickness > 0.0,
            anisotropy: self.anisotropy_strength > 0.0,
        }
    }
}

impl GltfLayers {
    /// Whether light passes through the surface: `transmission > 0` or
    /// `diffuse_transmission > 0` (a texture multiplies the constant, so
    /// a zero constant stays off). `thickness`, `attenuation_*` and
    /// `dispersion` act only on transmitted light.
    pub fn transmits(&self) -> bool {
        self.transmission > 0.0 || self.diffuse_transmission > 0.0
    }

    /// Whether any key of light through surfaces is off its default
    /// (`transmission`, `thickness`, `attenuation_distance`,
    /// `attenuation_color`, `dispersion`, `diffuse_transmission`,
    /// `diffuse_transmission_color`): what a renderer that does not draw
    /// them must say it ignores.
    pub fn sets_transmission_keys(&self) -> bool {
        let d = GltfLayers::default();
        self.transmission != d.transmission
            || self.thickness != d.thickness
            || self.attenuation_distance != d.attenuation_distance
            || self.attenuation_color != d.attenuation_color
            || self.dispersion != d.dispersion
            || self.diffuse_transmission != d.diffuse_transmission
            || self.diffuse_transmission_color != d.diffuse_transmission_color
    }

    /// Whether the surface bounds a volume (`thickness > 0` with
    /// `transmission > 0`, `KHR_materials_volume`: the volume needs a
    /// transmission to let light in).
    pub fn is_volume(&self) -> bool {
        self.thickness > 0.0 && self.transmission > 0.0
    }
}
