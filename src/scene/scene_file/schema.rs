//! Step 1 of loading, the schema: the scene `.toml` of the contract as
//! serde types. Unknown keys anywhere are errors; serde's messages (with
//! their "expected one of" lists) are what a user sees, so the field order
//! here is the documented order.
//!
//! The `[[lights]]` entries can also be written back ([`LightEntry::to_table`]):
//! "Save scene" and the viewer's scripted light edits use that.

use super::shadow_keys::{ShadowKeys, ShadowsSection, with_shadow_keys};
use super::toml_value::TomlValue;
use crate::base::ColorValue;
use crate::material::MaterialEntry;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The whole scene file. Unknown keys anywhere are errors.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(default)]
    pub image: ImageSection,
    pub camera: Option<CameraSection>,
    #[serde(default)]
    pub shading: ShadingSection,
    #[serde(default)]
    pub objects: Vec<ObjectEntry>,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialEntry>,
    /// Edits of a glTF file's own materials by name
    /// ([`super::gltf_material_edits`]).
    #[serde(default)]
    pub gltf_materials: BTreeMap<String, toml::Table>,
    #[serde(default)]
    pub lights: Vec<LightEntry>,
    #[serde(default)]
    pub shadows: ShadowsSection,
    #[serde(default)]
    pub ambient: AmbientSection,
    #[serde(default)]
    pub environment: EnvironmentSection,
    #[serde(default)]
    pub gltf: GltfSection,
}

/// `[gltf]`: how glTF files are shown (their materials, and the light of
/// a file that brings none).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GltfSection {
    /// Multiple-scattering energy compensation of every glTF material
    /// (default true, as three.js, Filament and Babylon.js render glTF;
    /// false: the specification's BRDF exactly).
    pub energy_compensation: Option<bool>,
    /// Shading normals of every glTF material turned toward the viewer
    /// where they face away (default true: silhouettes as the other glTF
    /// renderers draw them; false: the one-sided shading as written, black
    /// where the normal faces away).
    pub facing_normals: Option<bool>,
    /// The light of a scene whose glTF files bring none and that has no
    /// `[[lights]]` and no map: `"studio"` (default, the built-in neutral
    /// studio environment) or `"directional"` (the scene files' default
    /// light).
    pub default_light: Option<String>,
    /// The material variant (`KHR_materials_variants`) the glTF files
    /// are drawn in, by name; their default materials without it.
    pub variant: Option<String>,
}

/// `[image]`: output size in pixels.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageSection {
    #[serde(default = "default_width")]
    pub width: u32,
    #[serde(default = "default_height")]
    pub height: u32,
    /// Samples per pixel of the GPU renderer's multisampling: 1 (none,
    /// the default) or 4. The CPU reference always takes one sample at
    /// the pixel centre.
    #[serde(default)]
    pub msaa: Option<u32>,
    /// How a PNG and the viewer map radiance to [0, 1]: `clamp` (the
    /// default), `reinhard`, `aces`, `pbr-neutral`
    /// (src/output/tone_map.rs). EXR output stays linear.
    #[serde(default)]
    pub tone_map: Option<String>,
}

fn default_width() -> u32 {
    640
}
fn default_height() -> u32 {
    480
}

impl Default for ImageSection {
    fn default() -> Self {
        ImageSection {
            width: default_width(),
            height: default_height(),
            msaa: None,
            tone_map: None,
        }
    }
}

/// `[camera]`: a perspective camera looking from `position` to `target`.
/// Every key is optional: a key not given is the scene's automatic
/// camera's (a glTF file's first camera, else one framing the scene from
/// +Y up with a 45° field of view), so `--set camera.fov_y_deg=30` on a
/// glTF keeps the rest of its camera, as the same key alone in a file does.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSection {
    pub position: Option<[f64; 3]>,
    pub target: Option<[f64; 3]>,
    pub up: Option<[f64; 3]>,
    pub fov_y_deg: Option<f64>,
}

/// `[shading]`: flat | gouraud | phong.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadingSection {
    #[serde(default)]
    pub mode: Option<String>,
    /// Sample counts `(n_h, n_d, n_φ)` of the GPU's measured tables
    /// (default `[90, 90, 180]`, MERL's own).
    #[serde(default)]
    pub measured_table: Option<[u32; 3]>,
    /// How the GPU evaluates measured materials: "table" (default) or
    /// "network".
    #[serde(default)]
    pub measured_mode: Option<String>,
    /// How the GPU evaluates Smith's G1 for Beckmann: "erf" (default,
    /// exact to f32) or "rational" (Walter et al. 2007's approximation).
    #[serde(default)]
    pub smith_beckmann: Option<String>,
    /// Where Phong shading computes shadow-map coordinates on the GPU:
    /// "exact" (default: per vertex where exact) or "vertex" (also for a
    /// spot light's map, approximately; docs/shadows.md).
    #[serde(default)]
    pub shadow_coords: Option<String>,
    /// How the GPU draws light through surfaces: "screen" (default) or
    /// "off" (docs/transmission.md).
    #[serde(default)]
    pub transmission: Option<String>,
    /// Images of what lies behind transmissive objects, 1 to 8 (default
    /// 1): with more, glass behind glass is seen.
    #[serde(default)]
    pub transmission_layers: Option<u32>,
    /// Whether the light leaving a volume is weighted by its second
    /// interface's transmittance (default true; docs/transmission.md).
    #[serde(default)]
    pub transmission_exit: Option<bool>,
    /// Where a volume's refracted ray is read past it: "thickness"
    /// (default) or "traced" (docs/transmission.md).
    #[serde(default)]
    pub transmission_exit_ray: Option<String>,
}

/// One `[[objects]]` entry: a glTF file or a generated shape.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectEntry {
    /// A `.gltf`/`.glb`, relative to the scene file.
    pub gltf: Option<String>,
    /// A generated shape: `sphere` or `plane` (gonio's extension).
    pub shape: Option<String>,
    /// Sphere centre or plane centre.
    pub center: Option<[f64; 3]>,
    /// Sphere radius.
    pub radius: Option<f64>,
    /// Plane side length.
    pub size: Option<f64>,
    /// Tessellation: sphere slices, or plane divisions per side.
    pub segments: Option<u32>,
    /// Material name in `[materials]`; overrides a glTF's own materials.
    pub material: Option<String>,
}

/// Generates a `[[lights]]` entry type: its own keys, then `shadows` and
/// the shadow-map keys of `with_shadow_keys!`.
macro_rules! light_entry {
    ({
        $(#[$meta:meta])*
        $name:ident {
            $($(#[$field_meta:meta])* $field:ident: $ty:ty,)*
        }
    }
    $($key:ident $light_key:ident: $key_ty:ty,)*) => {
        $(#[$meta])*
        #[derive(Clone, Debug, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $($(#[$field_meta])* pub $field: $ty,)*
            /// The light casts shadows.
            #[serde(default)]
            pub shadows: bool,
            $(#[serde(default)] pub $light_key: Option<$key_ty>,)*
        }

        impl $name {
            /// The entry's shadow-map keys.
            pub fn shadow_keys(&self) -> ShadowKeys {
                ShadowKeys {
                    $($key: self.$light_key.clone(),)*
                }
            }

            /// Replaces the entry's shadow-map keys.
            pub fn set_shadow_keys(&mut self, keys: ShadowKeys) {
                $(self.$light_key = keys.$key;)*
            }

            /// The entry's own keys and `shadows` as `(name, value)`,
            /// unset ones left out.
            fn own_keys(&self) -> Vec<(&'static str, toml::Value)> {
                let mut out = Vec::new();
                $(
                    if let Some(v) = self.$field.to_toml() {
                        out.push((stringify!($field), v));
                    }
                )*
                out.push(("shadows", toml::Value::Boolean(self.shadows)));
                out
            }
        }
    };
}

with_shadow_keys!(light_entry! {
    /// `kind = "point"`: radiant intensity `I` [W/sr].
    PointEntry {
        position: [f64; 3],
        intensity: ColorValue,
        #[serde(default)]
        range: Option<f64>,
    }
});

with_shadow_keys!(light_entry! {
    /// `kind = "directional"`: irradiance `E` [W/m²] facing the light.
    DirectionalEntry {
        direction: [f64; 3],
        irradiance: ColorValue,
    }
});

with_shadow_keys!(light_entry! {
    /// `kind = "spot"`: a point light in a cone (glTF's falloff).
    SpotEntry {
        position: [f64; 3],
        direction: [f64; 3],
        intensity: ColorValue,
        #[serde(default)]
        inner_cone_deg: Option<f64>,
        #[serde(default)]
        outer_cone_deg: Option<f64>,
        #[serde(default)]
        range: Option<f64>,
    }
});

with_shadow_keys!(light_entry! {
    /// `kind = "area"`: a rectangle or disk emitting radiance `L` with a
    /// cosine distribution about `normal`, rendered as `samples` point
    /// lights.
    AreaEntry {
        shape: String,
        position: [f64; 3],
        normal: [f64; 3],
        /// Rectangle: `[w, h]`, `w` along `tangent`.
        #[serde(default)]
        size: Option<[f64; 2]>,
        #[serde(default)]
        tangent: Option<[f64; 3]>,
        /// Disk radius.
        #[serde(default)]
        radius: Option<f64>,
        radiance: ColorValue,
        #[serde(default)]
        samples: Option<u32>,
        /// GPU: one shadow cube per sample instead of one shared at the
        /// centre.
        #[serde(default)]
        shadow_per_sample: bool,
    }
});

/// `[[lights]]`, tagged by `kind`. Every kind takes `shadows` and the
/// shadow-map keys (defaults from `[shadows]`; see
/// [`super::shadow_keys`]).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum LightEntry {
    Point(PointEntry),
    Directional(DirectionalEntry),
    Spot(SpotEntry),
    Area(AreaEntry),
}

/// Calls `$body` with the entry of any kind as `$e`.
macro_rules! any_kind {
    ($entry:expr, $e:ident => $body:expr) => {
        match $entry {
            LightEntry::Point($e) => $body,
            LightEntry::Directional($e) => $body,
            LightEntry::Spot($e) => $body,
            LightEntry::Area($e) => $body,
        }
    };
}

impl LightEntry {
    /// The scene file's `kind`.
    pub fn kind(&self) -> &'static str {
        match self {
            LightEntry::Point(_) => "point",
            LightEntry::Directional(_) => "directional",
            LightEntry::Spot(_) => "spot",
            LightEntry::Area(_) => "area",
        }
    }

    /// Whether the entry asks for shadows.
    pub fn shadows(&self) -> bool {
        any_kind!(self, e => e.shadows)
    }

    /// Turns shadows on or off.
    pub fn set_shadows(&mut self, on: bool) {
        any_kind!(self, e => e.shadows = on)
    }

    /// The entry's shadow-map keys.
    pub fn shadow_keys(&self) -> ShadowKeys {
        any_kind!(self, e => e.shadow_keys())
    }

    /// Replaces the entry's shadow-map keys.
    pub fn set_shadow_keys(&mut self, keys: ShadowKeys) {
        any_kind!(self, e => e.set_shadow_keys(keys))
    }

    /// The entry as the scene file writes it (keys it does not set left
    /// out), which reads back as the same entry.
    pub fn to_table(&self) -> toml::Table {
        let mut table = toml::Table::new();
        table.insert("kind".into(), toml::Value::String(self.kind().into()));
        let own = any_kind!(self, e => e.own_keys());
        for (key, value) in own.into_iter().chain(self.shadow_keys().to_toml(true)) {
            table.insert(key.into(), value);
        }
        table
    }
}

/// `[environment]`: the sky a mirror reflects (gonio's extension); the
/// gradient's keys default to the ambient radiance. With `map` (a lat-long
/// `.exr`/`.hdr` relative to the scene file, or `"sky"`, the built-in
/// sky) the map lights every surface and is the background
/// (src/environment).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    pub zenith: Option<ColorValue>,
    pub horizon: Option<ColorValue>,
    pub ground: Option<ColorValue>,
    pub map: Option<String>,
    /// Multiplies the map (default 1).
    pub scale: Option<f64>,
    /// Highest SH band of the diffuse term, 0..=4 (default 2).
    pub sh_order: Option<i64>,
    /// What the CPU reference integrates: `"integrated"` (default) or
    /// `"sh"` (the GPU's approximation in f64).
    pub reference: Option<String>,
    /// Turns the map about +Y (degrees, counter-clockwise from above).
    pub rotation_deg: Option<f64>,
    /// `"none"` (the diffuse term by SH, default), `"sampled"` (the
    /// whole BRDF integrated with `samples` directions), `"prefiltered"`
    /// (the split-sum approximation) or `"sh"` (the Phong lobes by SH
    /// convolution).
    pub specular: Option<String>,
    /// Directions per shading point of `specular = "sampled"` (default 64).
    pub samples: Option<i64>,
    /// Level width of `specular = "prefiltered"`'s stack (default 64).
    pub prefilter_size: Option<i64>,
    /// The reference's environment term with ray-traced visibility
    /// (default false).
    pub visibility: Option<bool>,
}

/// `[ambient]`: constant incoming radiance `L_a`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AmbientSection {
    #[serde(default)]
    pub radiance: Option<ColorValue>,
}
