//! The walk over the scene's nodes that gathers meshes, lights and the
//! camera into a [`GltfScene`]. It runs after the document, the forest and
//! the cost have been checked, on buffers already loaded.

use super::GltfScene;
use super::accessors::read_primitive;
use super::convert::{
    convert_camera, convert_light, local_transform, material_from_metallic_roughness,
    material_from_pbr,
};
use super::hostile::WARNING;
use crate::material::texture::TextureTarget;
use crate::scene::limits::Limits;
use crate::scene::mesh::area_weighted_normals;
use crate::scene::texture::Encoding;
use crate::scene::{MAX_COORDINATE, Mesh, Rgb};
use glam::DMat4;
use std::borrow::Cow;

/// One import: the document, its loaded buffers and what has been gathered.
pub(super) struct Importer<'a> {
    document: &'a gltf::Document,
    buffers: &'a [Cow<'a, [u8]>],
    /// Caps for accessors not fully backed by data (see `check_accessor`).
    max_vertices: usize,
    max_corners: usize,
    scene: GltfScene,
    /// Index of `gltf-default` in `scene.materials`, once a primitive needs it.
    default_material: Option<usize>,
    /// Texture images, decoded as materials ask for them.
    images: super::images::ImageSource<'a>,
    /// The file uses `KHR_mesh_quantization`: integer vertex attributes
    /// are allowed (`accessors::Usage::accepts`).
    quantized: bool,
}

impl<'a> Importer<'a> {
    pub(super) fn new(
        document: &'a gltf::Document,
        buffers: &'a [Cow<'a, [u8]>],
        limits: &Limits,
        notes: Vec<String>,
        folder: &'a std::path::Path,
    ) -> Self {
        let clamp = |v: u64| usize::try_from(v).unwrap_or(usize::MAX);
        Importer {
            document,
            buffers,
            max_vertices: clamp(limits.vertices),
            max_corners: clamp(limits.triangles.saturating_mul(3).saturating_add(2)),
            scene: GltfScene {
                meshes: Vec::new(),
                materials: Vec::new(),
                lights: Vec::new(),
                camera: None,
                skipped_primitives: 0,
                notes,
                images: Vec::new(),
                variants: Vec::new(),
                variant_materials: Vec::new(),
            },
            default_material: None,
            images: super::images::ImageSource {
                buffers,
                folder,
                store: crate::scene::texture::store::ImageStore::new(limits),
            },
            quantized: document
                .extensions_used()
                .any(|e| e == "KHR_mesh_quantization"),
        }
    }

    /// Imports the trees below `roots`, which must be roots of a forest
    /// (see `graph::check_forest`).
    pub(super) fn run(mut self, roots: &[usize]) -> Result<GltfScene, String> {
        self.scene.variants = super::variants::names(self.document)?;
        for material in self.document.materials() {
            let index = material.index().unwrap_or_default();
            let name = material
                .name()
                .map_or_else(|| format!("material {index}"), str::to_string);
            let converted = self
                .material(name, &material)
                .map_err(|e| format!("material {index}: {e}"))?;
            // What alpha does and does not do here (docs/gltf.md, "alphaMode").
            match converted.alpha_mode {
                crate::material::AlphaMode::Opaque => {}
                crate::material::AlphaMode::Mask { cutoff } => self.scene.notes.push(format!(
                    "material {index}: alphaMode MASK (cutoff {cutoff}); its shadows ignore alpha"
                )),
                crate::material::AlphaMode::Blend => self.scene.notes.push(format!(
                    "material {index}: alphaMode BLEND, sorted back to front per object (not per triangle); its shadows ignore alpha"
                )),
            }
            self.scene.materials.push(converted);
        }

        // Depth-first, children in order, with an explicit stack: a chain
        // of a million nodes must not exhaust the call stack.
        let node = |n: usize| {
            self.document
                .nodes()
                .nth(n)
                .ok_or_else(|| format!("node {n} does not exist"))
        };
        let mut stack = Vec::with_capacity(roots.len());
        for &root in roots.iter().rev() {
            stack.push((node(root)?, DMat4::IDENTITY));
        }
        while let Some((node, parent)) = stack.pop() {
            let world = parent * local_transform(&node)?;
            if !world.is_finite() {
                return Err(format!(
                    "node {}: the composed world transform is not finite",
                    node.index()
                ));
            }
            self.visit(&node, world)?;
            let children: Vec<_> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|child| (child, world)));
        }
        self.scene.images = self.images.store.images.clone();
        Ok(self.scene)
    }

    /// glTF material `material` as a gonio material: `unlit` (the
    /// `unlit` module), or `gltf-pbr`: specular-glossiness (`spec_gloss`) or
    /// metallic-roughness, with the layer extensions (`layers`) and the
    /// core's textures.
    fn material(
        &mut self,
        name: String,
        material: &gltf::Material,
    ) -> Result<crate::material::Material, String> {
        let mut converted = material_from_pbr(name, material)?;
        if super::unlit::is_unlit(material) {
            super::unlit::convert(material, &mut self.images, &mut converted)?;
            converted.validate()?;
            return Ok(converted);
        }
        super::layers::read(material, self.document, &mut self.images, &mut converted)?;
        super::transmission::read(material, self.document, &mut self.images, &mut converted)?;
        let spec_gloss =
            super::spec_gloss::convert(material, self.document, &mut self.images, &mut converted)?;
        if !spec_gloss {
            self.metallic_roughness_textures(&material.pbr_metallic_roughness(), &mut converted)?;
        }
        self.textures(material, &mut converted)?;
        converted.validate()?;
        Ok(converted)
    }

    /// The textures of the metallic-roughness workflow on `converted`:
    /// base colour (sRGB) on `base_color` and on the ambient `k_a` (which
    /// the import sets to the base colour), metallic-roughness (linear)
    /// on `roughness` (G) and `metallic` (B).
    fn metallic_roughness_textures(
        &mut self,
        pbr: &gltf::material::PbrMetallicRoughness,
        converted: &mut crate::material::Material,
    ) -> Result<(), String> {
        if let Some(info) = pbr.base_color_texture() {
            for key in ["base_color", "k_a"] {
                let t = self.images.texture(&info, key, Encoding::Srgb, 0);
                converted
                    .textures
                    .push(t.map_err(|e| format!("baseColorTexture: {e}"))?);
            }
        }
        if let Some(info) = pbr.metallic_roughness_texture() {
            for (key, channel) in [("roughness", 1), ("metallic", 2)] {
                let t = self.images.texture(&info, key, Encoding::Linear, channel);
                converted
                    .textures
                    .push(t.map_err(|e| format!("metallicRoughnessTexture: {e}"))?);
            }
        }
        Ok(())
    }

    /// The textures every lit workflow shares, on `converted`: emissive
    /// (sRGB) on `emission`, normal (linear, a tangent-space normal map
    /// with its `scale`) and occlusion (linear, R, on the ambient term
    /// with its `strength`).
    fn textures(
        &mut self,
        material: &gltf::Material,
        converted: &mut crate::material::Material,
    ) -> Result<(), String> {
        if let Some(info) = material.emissive_texture() {
            let t = self.images.texture(&info, "emission", Encoding::Srgb, 0);
            converted
                .textures
                .push(t.map_err(|e| format!("emissiveTexture: {e}"))?);
        }
        if let Some(normal) = material.normal_texture() {
            let scale = f64::from(normal.scale());
            if !scale.is_finite() {
                return Err(format!("normalTexture: scale {scale} is not finite"));
            }
            let t = self
                .images
                .texture_with_raw_transform(
                    &normal.texture(),
                    normal.tex_coord(),
                    TextureTarget::Normal { scale },
                    Encoding::Linear,
                    normal.extension_value("KHR_texture_transform"),
                )
                .map_err(|e| format!("normalTexture: {e}"))?;
            converted.textures.push(t);
        }
        if let Some(occlusion) = material.occlusion_texture() {
            let strength = f64::from(occlusion.strength());
            if !strength.is_finite() {
                return Err(format!(
                    "occlusionTexture: strength {strength} is not finite"
                ));
            }
            // glTF: the occlusion values are in R.
            let t = self
                .images
                .texture_with_raw_transform(
                    &occlusion.texture(),
                    occlusion.tex_coord(),
                    TextureTarget::Occlusion { strength },
                    Encoding::Linear,
                    occlusion.extension_value("KHR_texture_transform"),
                )
                .map_err(|e| format!("occlusionTexture: {e}"))?;
            converted.textures.push(t);
        }
        Ok(())
    }

    fn visit(&mut self, node: &gltf::Node, world: DMat4) -> Result<(), String> {
        if let Some(mesh) = node.mesh() {
            self.add_mesh(node, &mesh, world)?;
        }
        if let Some(light) = node.light() {
            let light = convert_light(&light, world)
                .map_err(|p| format!("node {}: light {}: {p}", node.index(), light.index()))?;
            self.scene.lights.push(light);
        }
        if self.scene.camera.is_none()
            && let Some(camera) = node.camera()
        {
            self.scene.camera = convert_camera(&camera, world);
        }
        Ok(())
    }

    fn add_mesh(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        world: DMat4,
    ) -> Result<(), String> {
        let primitive_count = mesh.primitives().len();
        let mesh_name = mesh
            .name()
            .map_or_else(|| format!("mesh {}", mesh.index()), str::to_string);
        for primitive in mesh.primitives() {
            let context = || {
                format!(
                    "mesh {} primitive {} (node {})",
                    mesh.index(),
                    primitive.index(),
                    node.index()
                )
            };
            let Some(raw) = read_primitive(
                &primitive,
                self.buffers,
                self.max_vertices,
                self.max_corners,
                self.quantized,
            )
            .map_err(|p| format!("{}: {p}", context()))?
            else {
                self.scene.skipped_primitives += 1;
                continue;
            };
            let name = if primitive_count > 1 {
                format!("{mesh_name}/primitive {}", primitive.index())
            } else {
                mesh_name.clone()
            };
            let material = match primitive.material().index() {
                Some(index) => index,
                None => self.default_material(),
            };
            let variant_materials = super::variants::mappings(
                &primitive,
                self.scene.variants.len(),
                self.document.materials().len(),
            )
            .map_err(|p| format!("{}: {p}", context()))?;
            let mut mesh = match raw.normals {
                Some(normals) => Mesh {
                    name,
                    positions: raw.positions,
                    normals,
                    tangents: Vec::new(),
                    bitangent_signs: Vec::new(),
                    indices: raw.indices,
                    material,
                    tex_coords: Vec::new(),
                    colors: Vec::new(),
                    volume_scale: 1.0,
                },
                None => Mesh::with_generated_normals(name, raw.positions, raw.indices, material),
            };
            // glTF tangents where present (zero-length ones fall back to
            // a tangent derived from the normal); otherwise derived ones.
            if let Some(tangents) = raw.tangents {
                mesh.tangents = tangents;
                mesh.bitangent_signs = raw.bitangent_signs.unwrap_or_default();
            }
            mesh.tex_coords = raw.tex_coords;
            // A texture reading a UV set the primitive lacks is invalid
            // glTF (3.7.2.1): said, not passed over.
            if let Some(t) = self.scene.materials.get(material).and_then(|m| {
                m.textures.iter().find(|t| {
                    mesh.tex_coords
                        .get(t.tex_coord)
                        .is_none_or(|s| s.is_empty())
                })
            }) {
                self.scene.notes.push(format!(
                    "{WARNING}{}: material {material} reads TEXCOORD_{} for a texture and the primitive has no TEXCOORD_{} (invalid glTF, 3.7.2.1)",
                    context(),
                    t.tex_coord,
                    t.tex_coord
                ));
            }
            mesh.colors = raw.colors.unwrap_or_default();
            // A normal map without TANGENT: MikkTSpace in object space,
            // as glTF asks (`scene::tangents`).
            if mesh.tangents.is_empty()
                && let Some(set) = self
                    .scene
                    .materials
                    .get(material)
                    .and_then(crate::scene::tangents::normal_map_set)
            {
                crate::scene::tangents::generate(&mut mesh, set);
            }
            mesh.transform(world);
            // The GPU draws in f32 and squares distances: a position
            // beyond ±1e18 overflows there even though it is finite here.
            if let Some(p) = mesh
                .positions
                .iter()
                .find(|p| !p.is_finite() || p.abs().max_element() > MAX_COORDINATE)
            {
                return Err(format!(
                    "{}: a vertex lands at [{:e}, {:e}, {:e}] in the world, beyond ±{MAX_COORDINATE:e}: the GPU computes in f32 and squares distances (largest 3.4e38), so the asset cannot be drawn or framed; scale it down (its node transforms or positions)",
                    context(),
                    p.x,
                    p.y,
                    p.z
                ));
            }
            // A singular transform (a zero scale) has no normal matrix;
            // fall back to normals of the flattened geometry.
            repair_normals(&mut mesh);
            self.scene.meshes.push(mesh);
            self.scene.variant_materials.push(variant_materials);
        }
        Ok(())
    }

    fn default_material(&mut self) -> usize {
        *self.default_material.get_or_insert_with(|| {
            // glTF's default: base colour 1, metallic 1, roughness 1,
            // single-sided.
            let mut material = material_from_metallic_roughness("gltf-default", Rgb::ONE, 1.0, 1.0);
            material.sides = crate::material::Sides::Front;
            // Compensated, as every glTF material (convert::material_from_pbr).
            material.energy_compensation = true;
            material.facing_normals = true;
            self.scene.materials.push(material);
            self.scene.materials.len() - 1
        })
    }
}

/// Replaces zero normals (left by a singular transform or a zero-length
/// `NORMAL`) with area-weighted ones of the world-space geometry.
fn repair_normals(mesh: &mut Mesh) {
    if mesh.normals.iter().all(|n| n.length_squared() > 0.5) {
        return;
    }
    let generated = area_weighted_normals(&mesh.positions, &mesh.indices);
    for (n, g) in mesh.normals.iter_mut().zip(generated) {
        if n.length_squared() <= 0.5 {
            *n = g;
        }
    }
}
