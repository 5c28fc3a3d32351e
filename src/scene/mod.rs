//! What is drawn: meshes in world space, materials, lights, a camera.
//!
//! A [`Scene`] is the one input both renderers take. Everything in it is
//! already validated and in world space (node transforms applied at load
//! time), in `f64`: the GPU converts to `f32` on upload, the CPU reference
//! uses it as is.

pub mod area_light;
pub mod bvh;
pub mod camera;
pub mod change;
pub mod default_scene;
pub mod environment;
pub mod environment_mode;
pub mod gltf_import;
pub mod light;
pub mod light_markers;
pub mod limits;
pub mod mesh;
pub mod primitives;
pub mod scene_file;
pub mod shadow_coords;
pub mod sheen_stack;
pub mod tangents;
pub mod texture;
pub mod transmission_settings;

pub use area_light::AreaLight;
pub use camera::Camera;
pub use environment::Environment;
pub use light::{Light, LightKind, LightMarkers, MapResolution, ShadowFilter, ShadowSettings};
pub use mesh::Mesh;
pub use shadow_coords::ShadowCoords;
pub use transmission_settings::{TransmissionExitRay, TransmissionMode, TransmissionSettings};

use crate::base::named_enum;
use crate::material::Material;
use glam::DVec3;

named_enum!(
    /// How normals and shading are distributed over a triangle (lecture:
    /// "Surface Normals – Triangle Mesh").
    #[derive(Default)]
    ShadingMode, "shading mode" {
        /// One normal per triangle (the geometric face normal); the reflection
        /// equation is evaluated once, at the triangle's centroid, and the
        /// colour is constant over the triangle.
        Flat = "flat",
        /// Shade at the vertices with the vertex normals, interpolate the
        /// shaded colours (perspective-correct barycentrics).
        Gouraud = "gouraud",
        /// Interpolate the vertex normals, renormalize, shade every pixel.
        #[default]
        Phong = "phong",
    }
);

pub use crate::base::Rgb;

/// Largest coordinate of a position gonio draws (vertex, camera, light):
/// the GPU squares distances in f32, which overflows past about 1.8e19. A
/// camera at [1e300, …] was refused as "position and target coincide"
/// (the f64 direction overflowed), a light there gave Inf pixels and a
/// glTF with ±3e38 coordinates a blank image.
pub const MAX_COORDINATE: f64 = 1e18;

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Output size in pixels.
    pub width: u32,
    pub height: u32,
    /// GPU samples per pixel (1 or 4, `image.msaa`); the reference takes 1.
    pub msaa: u32,
    /// How PNG output and the viewer map radiance to [0, 1]
    /// (`image.tone_map`); EXR output ignores it.
    pub tone_map: crate::output::tone_map::ToneMap,
    pub camera: Camera,
    pub shading: ShadingMode,
    /// World-space meshes; each names its material by index.
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    /// Punctual lights, area lights already expanded into their
    /// [`Light::AreaSample`]s.
    pub lights: Vec<Light>,
    /// Shadow-map settings of `lights`, index for index (see
    /// [`Scene::shadow_settings`]).
    pub light_shadows: Vec<ShadowSettings>,
    /// The area lights the samples in `lights` stand for
    /// (`Light::AreaSample::area` indexes this).
    pub area_lights: Vec<AreaLight>,
    /// Constant incoming ambient radiance `L_a`; reflected as `k_a · L_a`.
    pub ambient: Rgb,
    /// What mirrors reflect (defaults to the constant `L_a`).
    pub environment: Environment,
    /// Sample counts `(n_h, n_d, n_φ)` of the tables the GPU renders
    /// measured materials from (`shading.measured_table`;
    /// src/gpu/measured_tables.rs). The reference evaluates the source.
    pub measured_table: [u32; 3],
    /// `shading.measured_mode = "network"`: the GPU evaluates each
    /// measured material's Neural-BRDF network per pixel (its 675 weights
    /// in the measured buffer) instead of a table; `false` ("table", the
    /// default): the table of `measured_table`.
    pub measured_network: bool,
    /// `shading.smith_beckmann`: how the GPU evaluates Smith's G1 and Λ
    /// for Beckmann (exact with an f32 erf, the default, or Walter's
    /// rational approximation); the reference always evaluates the exact
    /// form.
    pub smith_beckmann: crate::material::SmithBeckmann,
    /// `shading.shadow_coords`: where Phong shading computes shadow-map
    /// coordinates on the GPU (per vertex only where exact, the default,
    /// or also where approximate); the reference traces shadow rays.
    pub shadow_coords: ShadowCoords,
    /// `shading.transmission`, `shading.transmission_layers`: how the GPU
    /// draws light through surfaces; the reference traces it.
    pub transmission: TransmissionSettings,
    /// The images materials' textures read (`MaterialTexture::image`
    /// indexes this); shared, so cloning a scene does not copy texels.
    pub images: Vec<std::sync::Arc<texture::Image>>,
}

impl Scene {
    /// Axis-aligned bounds of all geometry, `None` if there is none.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        mesh::bounds(self.meshes.iter().flat_map(|m| m.positions.iter().copied()))
    }

    /// The roughness floor of this view: half the angle one pixel subtends
    /// vertically, `½ · fov_y / height` (radians ≈ slope for small angles).
    /// A mirror-reflected direction sweeps the pixel's angle, the half
    /// vector half of it, so lobes narrower than this fall between pixel
    /// centres (see `Material::with_roughness_floor`).
    pub fn roughness_floor(&self) -> f64 {
        0.5 * self.camera.fov_y_deg.to_radians() / self.height as f64
    }

    /// Materials as the renderers evaluate them (the roughness floor
    /// applied), index for index.
    pub fn effective_materials(&self) -> Vec<Material> {
        let floor = self.roughness_floor();
        self.materials
            .iter()
            .map(|m| m.with_roughness_floor(floor))
            .collect()
    }

    /// Total triangle count.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len()).sum()
    }

    /// The shadow-map settings of light `l` (the defaults where none were
    /// given).
    pub fn shadow_settings(&self, l: usize) -> ShadowSettings {
        self.light_shadows.get(l).copied().unwrap_or_default()
    }

    /// Whether a material some mesh uses has a texture.
    pub fn has_textures(&self) -> bool {
        self.meshes
            .iter()
            .any(|m| !self.materials[m.material].textures.is_empty())
    }

    /// Whether any light casts shadows.
    pub fn has_shadows(&self) -> bool {
        self.lights.iter().any(Light::casts_shadows)
    }

    /// The same scene with every area light rendered by `n` point lights
    /// (its samples replaced in place; other lights keep their order).
    pub fn with_area_samples(&self, n: u32) -> Scene {
        let mut scene = self.clone();
        scene.lights.clear();
        scene.light_shadows.clear();
        let mut done = vec![false; self.area_lights.len()];
        for (l, light) in self.lights.iter().enumerate() {
            let settings = self.shadow_settings(l);
            match *light {
                Light::AreaSample { area, .. } => {
                    if !std::mem::replace(&mut done[area], true) {
                        scene.area_lights[area].samples = n;
                        for sample in self.area_lights[area].point_lights(area, n) {
                            scene.lights.push(sample);
                            scene.light_shadows.push(settings);
                        }
                    }
                }
                _ => {
                    scene.lights.push(light.clone());
                    scene.light_shadows.push(settings);
                }
            }
        }
        scene
    }
}
