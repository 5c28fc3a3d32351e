//! What is drawn: meshes in world space, materials, lights, a camera.
//!
//! A [`Scene`] is the one input both renderers take. Everything in it is
//! already validated and in world space (node transforms applied at load
//! time), in `f64`: the GPU converts to `f32` on upload, the CPU reference
//! uses it as is.

pub mod camera;
pub mod default_scene;
pub mod gltf_import;
pub mod light;
pub mod mesh;
pub mod primitives;
pub mod scene_file;

pub use camera::Camera;
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
}

impl Scene {
    /// Axis-aligned bounds of all geometry, `None` if there is none.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        mesh::bounds(self.meshes.iter().flat_map(|m| m.positions.iter().copied()))
    }

    /// Total triangle count.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len()).sum()
    }
}
