//! glTF 2.0 import (`.gltf` with external or embedded buffers, and `.glb`).
//!
//! [`load`] turns the default scene of a glTF file into world-space meshes,
//! gonio materials, punctual lights and at most one camera. It is written
//! for files that may come from anywhere, so nothing in the file can make
//! it panic, hang, read outside the file's folder, or allocate without
//! bound. It validates before it trusts, in this order:
//!
//! 1. The file must be a regular file within the byte limit; a GLB is
//!    split into its chunks here, each length checked against the file
//!    (`container`).
//! 2. The JSON is counted before it is parsed (values, objects, nodes,
//!    images), because parsing can multiply its size a hundredfold; then
//!    it is parsed, required extensions are checked, and gltf-json's
//!    validation runs (every index in range, every enum value known).
//! 3. The nodes must form a forest: no cycle, no node with two parents,
//!    checked over all nodes iteratively in linear time (`graph`). The
//!    vertices, triangles and lights the scene will draw are added up from
//!    the declared counts, once per mesh instance, and checked against the
//!    [`Limits`] before anything is read.
//! 4. Buffers are loaded here, not by the `gltf` crate: the GLB `BIN`
//!    chunk, base64 `data:` URIs, or files given as relative references,
//!    which must stay inside the glTF's folder after canonicalization (no
//!    absolute paths, no escaping `..`, no URI schemes, no symlinks that
//!    lead out) and be regular files. At most the declared `byteLength` is
//!    read; a shorter file is an error (`buffers`).
//! 5. Every accessor is checked against its buffer view and buffer (types,
//!    offsets, strides, counts, with overflow-checked arithmetic) before
//!    the `gltf` crate's reader touches it, because that reader slices and
//!    indexes without checking; indices are checked against the vertex
//!    count, and positions and normals must be finite (`accessors`).
//!
//! A panic inside the `gltf` crate is caught as a last line of defence and
//! reported like any other malformed input, but every panic the fuzzers
//! found is prevented by a check above.
//!
//! Degenerate (zero-area) triangles are kept: they cover no pixel in the
//! GPU rasterizer and the CPU reference's intersection test rejects them,
//! so they draw nothing.
//!
//! # What is imported
//!
//! The default scene (scene 0 if none is marked default; every root node if
//! there are no scenes), with node transforms composed into world space.
//! Triangle lists, strips and fans become indexed triangles; points and
//! lines are skipped and counted in [`GltfScene::skipped_primitives`].
//! Optional extensions gonio does not implement are ignored, named in one
//! warning in [`GltfScene::notes`] (shown without `--verbose`).
//! `NORMAL` is used when present, otherwise normals are generated
//! (area-weighted). `TEXCOORD_0` and `TEXCOORD_1` are read, and the
//! base colour, metallic-roughness and emissive textures with their
//! samplers and `KHR_texture_transform` (`images`: a buffer view, a
//! `data:` URI or a file inside the glTF's folder, decoded within the
//! limits); the normal texture (with `scale`) and the occlusion texture
//! (R, with `strength`, on the ambient and environment terms) with their samplers
//! and `KHR_texture_transform` too (read from the raw extension object:
//! the `gltf` crate parses it on `textureInfo` only); a rotation also
//! turns the normal map's tangent-space normals with the map
//! (`material::texture::rotated_normal`). `TANGENT` is read with its w (the bitangent's
//! sign); a primitive with a normal texture and no `TANGENT` gets
//! MikkTSpace tangents in object space (`scene::tangents`). `COLOR_0`
//! (FLOAT, or normalized UNSIGNED_BYTE / UNSIGNED_SHORT; VEC3 or VEC4)
//! multiplies the base colour (its RGB scales `k_a`, `k_d` and
//! `base_color`, its A the alpha). `alphaMode` (OPAQUE, MASK with
//! `alphaCutoff`, BLEND) with the alpha `baseColorFactor.a ×
//! baseColorTexture.a × COLOR_0.a` becomes [`crate::material::AlphaMode`].
//! `doubleSided` becomes
//! [`crate::material::Sides`]: back faces culled when false (glTF's
//! default, also the default material's), lit with the flipped normal
//! when true. Skins and morph targets are ignored; skinned meshes are
//! drawn in their rest pose.
//!
//! # Materials: metallic-roughness → `gltf-pbr`
//!
//! Each material becomes a `gltf-pbr` material, glTF 2.0's own BRDF
//! (Appendix B, `material::brdf::gltf_pbr`), from its factors: base colour
//! `b` (linear RGB; its alpha is the material's `alpha`), metallic `m` and roughness `r`, each
//! clamped to [0, 1] (`r` kept ≥ 10⁻⁴, the contract's (0, 1]); `roughness`
//! keeps glTF's perceptual meaning (α = r²). `k_a = b` (an ambient light
//! lights the base colour) and `k_d = b·(1 − m)` (where a lecture model
//! chosen in the viewer starts). `emission = emissiveFactor ×
//! emissiveStrength` (`KHR_materials_emissive_strength`, 1 without it).
//! The material extensions that layer this BRDF (`KHR_materials_ior`,
//! `_specular`, `_clearcoat`, `_sheen`, `_iridescence`, `_anisotropy`) set
//! [`crate::material::Material::layers`] and put their textures on the
//! layer keys (`layers`); `KHR_materials_unlit` becomes a material of
//! model `unlit`, which shows its base colour (`unlit`); the archived
//! `KHR_materials_pbrSpecularGlossiness` is converted into `gltf-pbr` with
//! `ior = 0` (`spec_gloss`); `KHR_materials_variants` loads every
//! variant's materials and draws the file's default ones until one is
//! chosen ([`GltfScene::choose_variant`], `variants`). The optional
//! extensions gonio ignores are named in one warning.
//! A scene file's `material =` on the object replaces all of this with any
//! model.
//!
//! Primitives without a material get glTF's default material (`b = 1`,
//! `m = 1`, `r = 1`), named `gltf-default`.
//!
//! # Lights (`KHR_lights_punctual`)
//!
//! glTF gives photometric units; gonio's contract is radiometric. The import
//! takes 1 cd as 1 W/sr (point and spot: `intensity = color · intensity`)
//! and 1 lx as 1 W/m² (directional: `irradiance = color · intensity`), with
//! no luminous-efficacy factor, so a file's relative light levels carry
//! over unchanged. Lights shine along the node's world −Z axis; spot cone
//! angles are converted from radians to degrees; `range` is kept. They
//! are imported without shadows; the scene's light setup turns shadows on
//! when the scene has no light of its own, or as `shadows.imported_lights`
//! says (`scene_file::lights`).
//!
//! # Camera
//!
//! The first perspective camera met in scene order (depth-first, children in
//! order) becomes [`GltfScene::camera`]: it sits at the node's world origin,
//! looks along world −Z of the node with the node's +Y as up, and keeps
//! `yfov`. Its near/far are left at 0 for the caller to fit to the scene.
//! Orthographic cameras, and perspective ones whose transform or `yfov`
//! cannot give a valid camera, are skipped without error: the caller frames
//! the scene itself when there is none.

mod accessors;
mod buffers;
mod census;
mod compressed;
mod container;
mod convert;
mod draco;
mod draco_counts;
mod gltf_scene;
mod graph;
mod hostile;
mod images;
mod import;
#[cfg(test)]
mod layer_tests;
mod layers;
mod meshopt;
mod spec_gloss;
#[cfg(test)]
mod tests;
mod transmission;
mod unlit;
mod variants;

pub use crate::scene::limits::Limits;
pub use convert::material_from_metallic_roughness;
pub use gltf_scene::GltfScene;

use crate::scene::limits::{ReadError, exceeded, read_regular_file};
use crate::{Error, Result};
use hostile::{WARNING, guarded};
use std::path::Path;

/// Loads the default scene of a `.gltf` or `.glb` file within the default
/// [`Limits`]. See the module documentation for what is imported and how.
///
/// Every problem with the file (or a buffer it references) is an
/// [`Error::Input`] naming `path`.
pub fn load(path: &Path) -> Result<GltfScene> {
    load_with_limits(path, &Limits::default())
}

/// [`load`] within the given limits.
pub fn load_with_limits(path: &Path, limits: &Limits) -> Result<GltfScene> {
    let input = |problem: String| Error::input(path, problem);
    let bytes = read_regular_file(path, limits.bytes).map_err(|e| match e {
        ReadError::TooLarge(len) => input(exceeded(
            "the file size",
            format!("{len} bytes"),
            "bytes",
            limits.bytes,
        )),
        other => input(other.to_string()),
    })?;
    let expect_glb = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    load_bytes(&bytes, folder_of(path), expect_glb, limits).map_err(input)
}

/// Loads a glTF or GLB held in memory, as if it were a file in `base_dir`
/// (which relative buffer URIs are resolved in, and confined to). Errors
/// name `base_dir/<memory>`. Meant for fuzzing and embedding.
pub fn load_from_bytes(bytes: &[u8], base_dir: &Path, limits: &Limits) -> Result<GltfScene> {
    load_bytes(bytes, base_dir, false, limits)
        .map_err(|problem| Error::input(base_dir.join("<memory>"), problem))
}

/// Loads the glTF files of one scene against one budget: the vertices,
/// triangles and lights of every file loaded count against the same
/// [`Limits`], so a scene cannot exceed them by referencing a model many
/// times. Notes are collected with the file they are about.
#[derive(Debug)]
pub struct GltfLoader {
    remaining: Limits,
    notes: Vec<String>,
    /// The scene's texture images, held to the same limits.
    pub images: crate::scene::texture::store::ImageStore,
}

impl GltfLoader {
    /// A loader with the whole of `limits` to spend.
    pub fn new(limits: Limits) -> Self {
        GltfLoader {
            remaining: limits,
            notes: Vec::new(),
            images: crate::scene::texture::store::ImageStore::new(&limits),
        }
    }

    /// Loads `path` within what remains of the budget, and spends it.
    pub fn load(&mut self, path: &Path) -> Result<GltfScene> {
        let scene = load_with_limits(path, &self.remaining)?;
        // Within the remaining budget by construction, so this cannot fail.
        let _ = self.charge(
            scene.vertex_count(),
            scene.triangle_count(),
            scene.lights.len() as u64,
        );
        self.notes.extend(
            scene
                .notes
                .iter()
                .map(|note| match note.strip_prefix(WARNING) {
                    // A warning stays one (shown without --verbose).
                    Some(w) => format!("{WARNING}{}: {w}", path.display()),
                    None => format!("{}: {note}", path.display()),
                }),
        );
        Ok(scene)
    }

    /// Spends budget on what the scene adds besides glTF files (generated
    /// shapes, its own lights); an error if it does not fit.
    pub fn charge(&mut self, vertices: u64, triangles: u64, lights: u64) -> Result<(), String> {
        let r = &mut self.remaining;
        for (what, amount, left, key) in [
            ("vertices", vertices, &mut r.vertices, "vertices"),
            ("triangles", triangles, &mut r.triangles, "triangles"),
            ("lights", lights, &mut r.lights, "lights"),
        ] {
            *left = left.checked_sub(amount).ok_or_else(|| {
                format!(
                    "{amount} more {what} exceed what is left of the limit ({left}); raise it with `--limit {key}=N` if the input is trusted"
                )
            })?;
        }
        Ok(())
    }

    /// The notes of every file loaded, each naming its file.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }
}

/// The folder a file's relative references are resolved in.
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The whole import of one file's bytes; see the module documentation for
/// the order of the checks.
fn load_bytes(
    bytes: &[u8],
    folder: &Path,
    expect_glb: bool,
    limits: &Limits,
) -> Result<GltfScene, String> {
    let mut notes = Vec::new();
    let container = container::split(bytes, expect_glb, &mut notes)?;
    let mut used_bytes = bytes.len() as u64;
    let document = container::parse(container.json, &mut used_bytes, limits, &mut notes)?;
    images::check_sources(document.as_json())?;
    let parents = graph::check_forest(&document)?;
    let roots = graph::scene_roots(&document, &parents)?;
    graph::check_cost(&document, &graph::descendants(&document, &roots), limits)?;
    let buffers = buffers::load(&document, container.bin, folder, &mut used_bytes, limits)?;
    let (document, buffers) = compressed::decode(document, buffers, &mut used_bytes, limits)?;
    guarded(|| import::Importer::new(&document, &buffers, limits, notes, folder).run(&roots))
        .and_then(|result| result)
}
