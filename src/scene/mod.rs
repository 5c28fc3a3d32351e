//! What is drawn: meshes in world space, materials, lights, a camera.
//!
//! A [`Scene`] is the one input both renderers take. Everything in it is
//! already validated and in world space (node transforms applied at load
//! time), in `f64`: the GPU converts to `f32` on upload, the CPU reference
//! uses it as is.

pub mod camera;
pub mod default_scene;
pub mod environment;
pub mod gltf_import;
pub mod limits;
pub mod light;
pub mod mesh;
pub mod primitives;
pub mod scene_file;

pub use camera::Camera;
pub use environment::Environment;
pub use light::{Light, LightKind};
pub use mesh::Mesh;

use crate::material::Material;
use glam::DVec3;
use std::fmt;
use std::str::FromStr;

/// How normals and shading are distributed over a triangle (lecture:
/// "Surface Normals – Triangle Mesh").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ShadingMode {
    /// One normal per triangle (the geometric face normal); the reflection
    /// equation is evaluated once, at the triangle's centroid, and the
    /// colour is constant over the triangle.
    Flat,
    /// Shade at the vertices with the vertex normals, interpolate the
    /// shaded colours (perspective-correct barycentrics).
    Gouraud,
    /// Interpolate the vertex normals, renormalize, shade every pixel.
    #[default]
    Phong,
}

impl ShadingMode {
    /// All modes, in the contract's order.
    pub const ALL: [ShadingMode; 3] = [ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong];

    /// The contract's name.
    pub fn name(self) -> &'static str {
        match self {
            ShadingMode::Flat => "flat",
            ShadingMode::Gouraud => "gouraud",
            ShadingMode::Phong => "phong",
        }
    }
}

impl fmt::Display for ShadingMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ShadingMode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        ShadingMode::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown shading mode `{s}`; expected flat, gouraud or phong"))
    }
}

/// Linear RGB triple (radiance, reflectance, intensity, ...).
pub type Rgb = DVec3;

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Output size in pixels.
    pub width: u32,
    pub height: u32,
    pub camera: Camera,
    pub shading: ShadingMode,
    /// World-space meshes; each names its material by index.
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    /// Constant incoming ambient radiance `L_a`; reflected as `k_a · L_a`.
    pub ambient: Rgb,
    /// What mirrors reflect (defaults to the constant `L_a`).
    pub environment: Environment,
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
        self.materials.iter().map(|m| m.with_roughness_floor(floor)).collect()
    }

    /// Total triangle count.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len()).sum()
    }
}
