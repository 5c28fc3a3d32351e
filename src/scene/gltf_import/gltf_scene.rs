//! What one glTF file imports as: [`GltfScene`], its meshes, materials,
//! lights, camera and images, ready to join a scene.

use crate::material::Material;
use crate::scene::{Camera, Light, Mesh};

/// The contents of a glTF file, ready to join a [`crate::scene::Scene`].
#[derive(Clone, Debug)]
pub struct GltfScene {
    /// World-space meshes; `mesh.material` indexes [`GltfScene::materials`].
    pub meshes: Vec<Mesh>,
    /// One per glTF material, in file order, plus `gltf-default` at the end
    /// if an imported primitive has no material.
    pub materials: Vec<Material>,
    /// `KHR_lights_punctual` lights, world space.
    pub lights: Vec<Light>,
    /// The first perspective camera reached in the scene; near/far are 0.0
    /// (the caller fits them to the scene bounds).
    pub camera: Option<Camera>,
    /// Primitives of the scene that were skipped because they draw points
    /// or lines, which gonio does not render.
    pub skipped_primitives: usize,
    /// What was ignored without being an error (optional extensions gonio
    /// does not implement, unknown GLB chunks, trailing bytes), one
    /// sentence each, for `--verbose`; those prefixed as warnings
    /// (`scene_file::WARNING`) are shown without it.
    pub notes: Vec<String>,
    /// The images its materials' textures index.
    pub images: Vec<std::sync::Arc<crate::scene::texture::Image>>,
    /// The names of its material variants (`KHR_materials_variants`), in
    /// the file's order; [`GltfScene::choose_variant`] picks one.
    pub variants: Vec<String>,
    /// Per mesh (parallel to [`GltfScene::meshes`]): the material of each
    /// variant that maps one, as `(variant, material)`.
    pub variant_materials: Vec<Vec<(usize, usize)>>,
}

impl GltfScene {
    pub(super) fn vertex_count(&self) -> u64 {
        self.meshes.iter().map(|m| m.positions.len() as u64).sum()
    }

    pub(super) fn triangle_count(&self) -> u64 {
        self.meshes.iter().map(|m| m.indices.len() as u64).sum()
    }
}
