//! Vertex streams for each shading mode, built from the scene's meshes.
//!
//! All meshes go into one vertex buffer, ordered by material: each
//! material's triangles are one contiguous [`Batch`], which the renderer
//! draws with that material bound (src/gpu/bindings.rs) and a pipeline
//! compiled for its BRDF variant alone; the shadow passes draw the whole
//! stream with one call. Attributes a scene does not need (tangents without
//! an anisotropic model, shading points outside flat shading, face normals
//! outside per-vertex shadow coordinates) are not in the stream at all; the
//! shader locations match `shaders/raster_*.wgsl` (location 2, once the
//! material index, is unused).

use crate::scene::mesh::{Mesh, centroid, face_normal};
use crate::scene::{Scene, ShadingMode};

/// Which optional attributes the stream has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexLayout {
    /// `@location(3) tangent` (anisotropic models).
    pub tangents: bool,
    /// `@location(4) shading_point` (flat shading: the centroid).
    pub shading_point: bool,
    /// `@location(5) face_normal` (Phong shading with its shadow-map
    /// coordinates computed per vertex: the triangle's geometric normal,
    /// the offset normal of the lookup; the stream is then de-indexed).
    pub face_normal: bool,
    /// `@location(6) uv0`, `@location(7) uv1` (a material has textures;
    /// flat shading: the centroid's UVs at every corner).
    pub tex_coords: bool,
    /// `@location(8) bitangent_sign` (a material has a normal map: the
    /// sign of `B = sign · N × T`; flat shading: the triangle's first
    /// corner's).
    pub bitangent_signs: bool,
    /// `@location(9) color` (a mesh has vertex colours, RGBA; white for
    /// the others; flat shading: the corners' mean).
    pub colors: bool,
}

impl VertexLayout {
    /// The wgpu attributes, tightly packed in location order.
    pub fn attributes(&self) -> Vec<wgpu::VertexAttribute> {
        let mut attributes = Vec::new();
        let mut offset = 0;
        let mut push = |location, format: wgpu::VertexFormat| {
            attributes.push(wgpu::VertexAttribute {
                format,
                offset,
                shader_location: location,
            });
            offset += format.size();
        };
        push(0, wgpu::VertexFormat::Float32x3);
        push(1, wgpu::VertexFormat::Float32x3);
        if self.tangents {
            push(3, wgpu::VertexFormat::Float32x3);
        }
        if self.shading_point {
            push(4, wgpu::VertexFormat::Float32x3);
        }
        if self.face_normal {
            push(5, wgpu::VertexFormat::Float32x3);
        }
        if self.tex_coords {
            push(6, wgpu::VertexFormat::Float32x2);
            push(7, wgpu::VertexFormat::Float32x2);
        }
        if self.bitangent_signs {
            push(8, wgpu::VertexFormat::Float32);
        }
        if self.colors {
            push(9, wgpu::VertexFormat::Float32x4);
        }
        attributes
    }

    /// Bytes per vertex.
    pub fn stride(&self) -> u64 {
        4 * (6
            + 3 * self.tangents as u64
            + 3 * self.shading_point as u64
            + 3 * self.face_normal as u64
            + 4 * self.tex_coords as u64
            + self.bitangent_signs as u64
            + 4 * self.colors as u64)
    }
}

/// Where a stream's 32-bit words go: a `Vec` (the bench, the tests) or
/// a buffer filled chunk by chunk (`gpu::upload`), so that the renderer
/// never holds the whole `f32` stream on the CPU.
pub trait Words {
    fn put(&mut self, words: &[u32]);
}

impl Words for Vec<u32> {
    fn put(&mut self, words: &[u32]) {
        self.extend_from_slice(words);
    }
}

/// Vertex words (f32 bits and u32), optional indices and the layout.
pub struct GeometryData {
    /// 32-bit words, `stride / 4` per vertex.
    pub words: Vec<u32>,
    /// `None` for a non-indexed draw (flat shading).
    pub indices: Option<Vec<u32>>,
    /// Vertices to draw (non-indexed) or indices to draw (indexed).
    pub draw_count: u32,
    /// The stream's material runs, in order; together `0..draw_count`.
    pub batches: Vec<Batch>,
    /// The stream's meshes, in order; together `0..draw_count`: what the
    /// shadow passes cull per cube face (src/gpu/shadow_culling.rs).
    pub objects: Vec<ObjectRange>,
    pub layout: VertexLayout,
}

/// One mesh's part of the stream: a range of indices (indexed streams)
/// or vertices (de-indexed), inside its material's [`Batch`], with the
/// bounding box of the vertices its triangles use (taken when the stream
/// is planned, before a GPU-only run frees the `f64` mesh).
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectRange {
    /// Index in `Scene::meshes`.
    pub mesh: u32,
    pub material: u32,
    pub range: std::ops::Range<u32>,
    /// World-space box `(min, max)` of the used vertices.
    pub bounds: (glam::DVec3, glam::DVec3),
}

/// The triangles of one material: a range of indices (indexed streams)
/// or vertices (flat shading).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Batch {
    pub material: u32,
    pub range: std::ops::Range<u32>,
    /// Alpha BLEND or transmissive: the one mesh (index in
    /// `Scene::meshes`) this batch draws, so that the renderer can draw
    /// such batches back to front per object; `None` for the others.
    pub object: Option<u32>,
    /// The draw's first instance: per-draw data with no buffer. An
    /// object's batch carries the bits of its mesh's `volume_scale` as
    /// f32 (`Mesh::volume_scale`; shaders/transmission.wgsl reads it as
    /// `bitcast<f32>(instance_index)`), 0 ("none", read as 1) otherwise.
    pub instance: u32,
}

/// Whether `mesh` is drawn as an object of its own: alpha BLEND, or
/// transmissive (`Material::transmits_specularly`), both sorted back to
/// front by the renderer.
fn per_object(scene: &Scene, mesh: &Mesh) -> bool {
    let material = &scene.materials[mesh.material];
    material.alpha_mode == crate::material::AlphaMode::Blend || material.transmits_specularly()
}

/// The scene's meshes (index, whether it is drawn per object) in material
/// order (stable), so each material's triangles are contiguous, alpha
/// BLEND and transmissive meshes last (drawn over everything else).
fn meshes_by_material(scene: &Scene) -> Vec<(usize, bool)> {
    let mut meshes: Vec<_> = scene
        .meshes
        .iter()
        .enumerate()
        .map(|(i, m)| (i, per_object(scene, m), m.material))
        .collect();
    meshes.sort_by_key(|&(_, blend, material)| (blend, material));
    meshes.into_iter().map(|(i, blend, _)| (i, blend)).collect()
}

/// Appends `count` elements of mesh `index` (of `material`, drawn per
/// object or not) to `batches`, merging with the last run of the same
/// material unless it is drawn per object (a batch per such mesh).
fn extend_batches(
    batches: &mut Vec<Batch>,
    (index, blend): (usize, bool),
    mesh: &Mesh,
    count: usize,
) {
    let material = mesh.material as u32;
    let object = blend.then_some(index as u32);
    let instance = if blend {
        (mesh.volume_scale as f32).to_bits()
    } else {
        0
    };
    let start = batches.last().map_or(0, |b| b.range.end);
    let end = start + count as u32;
    match batches.last_mut() {
        Some(last) if last.material == material && object.is_none() && last.object.is_none() => {
            last.range.end = end
        }
        _ => batches.push(Batch {
            material,
            range: start..end,
            object,
            instance,
        }),
    }
}

fn push3(words: &mut impl Words, v: glam::DVec3) {
    words.put(&v.as_vec3().to_array().map(f32::to_bits));
}

/// Both UV sets of a vertex (or of a centroid), if the stream has them.
fn push_uvs(words: &mut impl Words, layout: &VertexLayout, uvs: [glam::DVec2; 2]) {
    if layout.tex_coords {
        for uv in uvs {
            words.put(&uv.as_vec2().to_array().map(f32::to_bits));
        }
    }
}

/// A bitangent sign, if the stream has them.
fn push_sign(words: &mut impl Words, layout: &VertexLayout, sign: f64) {
    if layout.bitangent_signs {
        words.put(&[(sign as f32).to_bits()]);
    }
}

/// A vertex colour, if the stream has them.
fn push_color(words: &mut impl Words, layout: &VertexLayout, c: glam::DVec4) {
    if layout.colors {
        words.put(&c.as_vec4().to_array().map(f32::to_bits));
    }
}

/// Whether some mesh of `scene` has vertex colours.
fn has_colors(scene: &Scene) -> bool {
    scene.meshes.iter().any(|m| !m.colors.is_empty())
}

/// The UV sets of vertex `v` of `mesh`.
fn vertex_uvs(mesh: &Mesh, v: usize) -> [glam::DVec2; 2] {
    [mesh.tex_coord(0, v), mesh.tex_coord(1, v)]
}

/// The meshes a stream is written from: kept (the viewer, the bench, a
/// run that also renders the reference), or released: each array is
/// freed as soon as its words are written (a GPU-only render, where
/// nothing reads the `f64` meshes after the upload; the meshes stay in
/// the scene with their material and name, their arrays empty).
pub enum Meshes<'a> {
    Keep(&'a [Mesh]),
    Release(&'a mut [Mesh]),
}

impl Meshes<'_> {
    fn get(&self, i: usize) -> &Mesh {
        match self {
            Meshes::Keep(m) => &m[i],
            Meshes::Release(m) => &m[i],
        }
    }

    /// Frees the triangles of mesh `i` (released meshes only).
    fn release_indices(&mut self, i: usize) {
        if let Meshes::Release(m) = self {
            m[i].indices = Vec::new();
        }
    }

    /// Frees every per-vertex array of mesh `i` (released meshes only).
    fn release_vertices(&mut self, i: usize) {
        if let Meshes::Release(m) = self {
            let mesh = &mut m[i];
            mesh.positions = Vec::new();
            mesh.normals = Vec::new();
            release_unused(mesh, None);
        }
    }
}

/// Frees the per-vertex arrays of `mesh` that `layout` does not stream
/// (all but positions and normals with `None`).
fn release_unused(mesh: &mut Mesh, layout: Option<&VertexLayout>) {
    let keeps = |f: fn(&VertexLayout) -> bool| layout.is_some_and(f);
    if !keeps(|l| l.tangents) {
        mesh.tangents = Vec::new();
    }
    if !keeps(|l| l.tex_coords) {
        mesh.tex_coords = Vec::new();
    }
    if !keeps(|l| l.bitangent_signs) {
        mesh.bitangent_signs = Vec::new();
    }
    if !keeps(|l| l.colors) {
        mesh.colors = Vec::new();
    }
}

/// How a scene's stream is laid out, known from the meshes' counts
/// before any word is written: the layout, the batches, the byte sizes.
/// [`StreamPlan::write`] then writes the words into any [`Words`].
pub struct StreamPlan {
    pub layout: VertexLayout,
    /// An index buffer (Gouraud, Phong without per-vertex shadow
    /// coordinates) or three vertices per triangle.
    pub indexed: bool,
    /// The meshes (index, whether it blends) in stream order.
    order: Vec<(usize, bool)>,
    pub batches: Vec<Batch>,
    /// The meshes' parts of the stream ([`GeometryData::objects`]).
    pub objects: Vec<ObjectRange>,
    /// Vertices to draw (non-indexed) or indices to draw (indexed).
    pub draw_count: u32,
    pub vertex_bytes: u64,
    pub index_bytes: u64,
}

impl StreamPlan {
    /// The stream of `scene` for `scene.shading`, with tangents if asked,
    /// and with face normals (de-indexed) if asked and shaded per pixel.
    /// The UV sets are in the stream when a material has textures.
    pub fn new(scene: &Scene, tangents: bool, face_normals: bool) -> Self {
        let (shading_point, face_normal) = match scene.shading {
            ShadingMode::Flat => (true, false),
            ShadingMode::Phong if face_normals => (false, true),
            ShadingMode::Gouraud | ShadingMode::Phong => (false, false),
        };
        let layout = VertexLayout {
            tangents,
            shading_point,
            face_normal,
            tex_coords: scene.has_textures(),
            bitangent_signs: crate::gpu::textures::has_normal_maps(scene),
            colors: has_colors(scene),
        };
        let indexed = !(shading_point || face_normal);
        let order = meshes_by_material(scene);
        let mut batches = Vec::new();
        let mut objects = Vec::new();
        for &(i, blend) in &order {
            let mesh = &scene.meshes[i];
            extend_batches(&mut batches, (i, blend), mesh, 3 * mesh.indices.len());
            let end = batches.last().map_or(0, |b| b.range.end);
            // Only the vertices the triangles use (a glTF mesh may carry
            // others).
            let used = mesh
                .indices
                .iter()
                .flatten()
                .map(|&v| mesh.positions[v as usize]);
            objects.push(ObjectRange {
                mesh: i as u32,
                material: mesh.material as u32,
                range: end - 3 * mesh.indices.len() as u32..end,
                bounds: crate::scene::mesh::bounds(used)
                    .unwrap_or((glam::DVec3::ZERO, glam::DVec3::ZERO)),
            });
        }
        let triangles = scene.triangle_count() as u64;
        let (vertex_bytes, index_bytes) = if indexed {
            let vertices: u64 = scene.meshes.iter().map(|m| m.positions.len() as u64).sum();
            (vertices * layout.stride(), 3 * triangles * 4)
        } else {
            (3 * triangles * layout.stride(), 0)
        };
        StreamPlan {
            layout,
            indexed,
            order,
            batches,
            objects,
            draw_count: (3 * triangles) as u32,
            vertex_bytes,
            index_bytes,
        }
    }

    /// Writes the stream of `meshes` (the meshes of the scene this plan
    /// was made for) into `vertices` and, if indexed, `indices`.
    pub fn write(&self, mut meshes: Meshes, vertices: &mut impl Words, indices: &mut impl Words) {
        match (self.layout.shading_point, self.layout.face_normal) {
            (true, _) => self.flat(meshes, vertices),
            (_, true) => self.phong_faces(meshes, vertices),
            _ => {
                if let Meshes::Release(m) = &mut meshes {
                    for mesh in m.iter_mut() {
                        release_unused(mesh, Some(&self.layout));
                    }
                }
                self.indexed(meshes, vertices, indices)
            }
        }
    }

    /// Indices first, then vertices: a released mesh's triangles are
    /// freed before its vertices are streamed, and each vertex array once
    /// streamed, so the `f64` mesh shrinks as the buffers fill.
    fn indexed(&self, mut meshes: Meshes, words: &mut impl Words, indices: &mut impl Words) {
        let layout = self.layout;
        let mut base = 0u32;
        for &(i, _) in &self.order {
            let mesh = meshes.get(i);
            for triangle in &mesh.indices {
                indices.put(&triangle.map(|v| base + v));
            }
            base += mesh.positions.len() as u32;
            meshes.release_indices(i);
        }
        for &(i, _) in &self.order {
            let mesh = meshes.get(i);
            for v in 0..mesh.positions.len() {
                push3(words, mesh.positions[v]);
                push3(words, mesh.normals[v]);
                if layout.tangents {
                    push3(words, mesh.tangent(v));
                }
                push_uvs(words, &layout, vertex_uvs(mesh, v));
                push_sign(words, &layout, mesh.bitangent_sign(v));
                push_color(words, &layout, mesh.color(v));
            }
            meshes.release_vertices(i);
        }
    }

    /// De-indexed: every corner carries the triangle's frame and centroid
    /// (computed in f64 exactly as the reference's flat shading does).
    fn flat(&self, meshes: Meshes, words: &mut impl Words) {
        let layout = self.layout;
        self.de_indexed(meshes, words, |mesh, t, words| {
            let corners = mesh.triangle(t);
            let frame = mesh.flat_frame(t);
            let shading_point = centroid(corners);
            let sign = mesh.bitangent_sign(mesh.indices[t][0] as usize);
            let color = mesh.indices[t]
                .iter()
                .map(|&v| mesh.color(v as usize))
                .sum::<glam::DVec4>()
                / 3.0;
            let uvs = [0, 1].map(|set| {
                mesh.indices[t]
                    .iter()
                    .map(|&v| mesh.tex_coord(set, v as usize))
                    .sum::<glam::DVec2>()
                    / 3.0
            });
            for p in corners {
                push3(words, p);
                push3(words, frame.n);
                if layout.tangents {
                    push3(words, frame.t);
                }
                push3(words, shading_point);
                push_uvs(words, &layout, uvs);
                push_sign(words, &layout, sign);
                push_color(words, &layout, color);
            }
        })
    }

    /// De-indexed, for per-pixel shading: every corner carries its own
    /// vertex's position, normal (and tangent) and the triangle's
    /// geometric normal (`mesh::face_normal`, as the reference's offset
    /// normal), from which the vertex shader computes the shadow-map
    /// coordinates (shaders/shadows.wgsl `shadow_ortho_ndc`).
    fn phong_faces(&self, meshes: Meshes, words: &mut impl Words) {
        let layout = self.layout;
        self.de_indexed(meshes, words, |mesh, t, words| {
            let face = face_normal(mesh.triangle(t));
            for v in mesh.indices[t].map(|v| v as usize) {
                push3(words, mesh.positions[v]);
                push3(words, mesh.normals[v]);
                if layout.tangents {
                    push3(words, mesh.tangent(v));
                }
                push3(words, face);
                push_uvs(words, &layout, vertex_uvs(mesh, v));
                push_sign(words, &layout, mesh.bitangent_sign(v));
                push_color(words, &layout, mesh.color(v));
            }
        })
    }

    /// A non-indexed stream in material order: `triangle(mesh, t, words)`
    /// writes the three corners of triangle `t`; a released mesh is freed
    /// once all its triangles are written (they read its vertices in any
    /// order).
    fn de_indexed<W: Words>(
        &self,
        mut meshes: Meshes,
        words: &mut W,
        triangle: impl Fn(&Mesh, usize, &mut W),
    ) {
        for &(i, _) in &self.order {
            let mesh = meshes.get(i);
            for t in 0..mesh.indices.len() {
                triangle(mesh, t, words);
            }
            meshes.release_indices(i);
            meshes.release_vertices(i);
        }
    }
}

impl GeometryData {
    /// Lays out `scene`'s meshes ([`StreamPlan::new`]) into vectors.
    pub fn new(scene: &Scene, tangents: bool, face_normals: bool) -> Self {
        let plan = StreamPlan::new(scene, tangents, face_normals);
        let mut words = Vec::with_capacity((plan.vertex_bytes / 4) as usize);
        let mut indices = Vec::with_capacity((plan.index_bytes / 4) as usize);
        plan.write(Meshes::Keep(&scene.meshes), &mut words, &mut indices);
        GeometryData {
            words,
            indices: plan.indexed.then_some(indices),
            draw_count: plan.draw_count,
            batches: plan.batches,
            objects: plan.objects,
            layout: plan.layout,
        }
    }

    /// Bytes of the vertex stream and of the index buffer that
    /// [`Self::new`] would lay out, computed from the counts alone so a
    /// stream over the GPU's limits is refused before it is built.
    pub fn byte_sizes(scene: &Scene, tangents: bool, face_normals: bool) -> (u64, u64) {
        let plan = StreamPlan::new(scene, tangents, face_normals);
        (plan.vertex_bytes, plan.index_bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::{self, SceneSource};

    fn built_in(shading: &str) -> Scene {
        scene_file::load(
            &SceneSource::BuiltIn,
            &[format!("shading.mode=\"{shading}\"")],
        )
        .unwrap()
    }

    /// Every stream is cut into one batch per material, in order, covering
    /// the whole draw.
    #[test]
    fn batches_cover_the_stream_once_per_material() {
        for (shading, faces) in [("phong", false), ("phong", true), ("flat", false)] {
            let scene = built_in(shading);
            let g = GeometryData::new(&scene, false, faces);
            let mut end = 0;
            let mut seen = Vec::new();
            for b in &g.batches {
                assert_eq!(b.range.start, end, "{shading}: contiguous");
                end = b.range.end;
                assert!(
                    !seen.contains(&b.material),
                    "{shading}: one batch per material"
                );
                seen.push(b.material);
            }
            assert_eq!(end, g.draw_count, "{shading}: the whole stream");
            let triangles: usize = scene
                .meshes
                .iter()
                .filter(|m| m.material as u32 == g.batches[0].material)
                .map(|m| m.indices.len())
                .sum();
            assert_eq!(g.batches[0].range.len(), 3 * triangles);
            // The objects tile the stream too, one per mesh, each inside
            // its material's batch.
            let mut end = 0;
            for o in &g.objects {
                assert_eq!(o.range.start, end, "{shading}: objects contiguous");
                end = o.range.end;
                let mesh = &scene.meshes[o.mesh as usize];
                assert_eq!(o.range.len(), 3 * mesh.indices.len());
                assert!(g.batches.iter().any(|b| b.material == o.material
                    && b.range.start <= o.range.start
                    && o.range.end <= b.range.end));
            }
            assert_eq!(end, g.draw_count, "{shading}: objects cover the stream");
            assert_eq!(g.objects.len(), scene.meshes.len());
        }
    }

    /// The de-indexed Phong stream carries each corner's own normal and its
    /// triangle's geometric normal.
    #[test]
    fn face_normal_stream_carries_the_triangle_normal() {
        let scene = built_in("phong");
        let g = GeometryData::new(&scene, false, true);
        assert!(g.indices.is_none() && g.layout.face_normal);
        let words = (g.layout.stride() / 4) as usize;
        assert_eq!(g.words.len(), words * 3 * scene.triangle_count());
        let mesh = &scene.meshes[meshes_by_material(&scene)[0].0];
        let read = |corner: usize, at: usize| {
            let w = &g.words[corner * words + at..corner * words + at + 3];
            glam::DVec3::new(
                f32::from_bits(w[0]) as f64,
                f32::from_bits(w[1]) as f64,
                f32::from_bits(w[2]) as f64,
            )
        };
        for t in [0, mesh.indices.len() / 2, mesh.indices.len() - 1] {
            let face = face_normal(mesh.triangle(t));
            for c in 0..3 {
                let corner = 3 * t + c;
                let v = mesh.indices[t][c] as usize;
                assert!((read(corner, 0) - mesh.positions[v]).length() < 1e-6);
                assert!((read(corner, 3) - mesh.normals[v]).length() < 1e-6);
                assert!((read(corner, 6) - face).length() < 1e-6);
            }
        }
    }

    /// Writing from released meshes gives the same words as from kept
    /// ones, in every layout, and leaves the meshes with their materials
    /// and no arrays.
    #[test]
    fn released_meshes_stream_the_same_words_and_are_freed() {
        for (shading, tangents, faces) in [
            ("phong", false, false),
            ("gouraud", true, false),
            ("phong", false, true),
            ("flat", true, false),
        ] {
            let scene = built_in(shading);
            let kept = GeometryData::new(&scene, tangents, faces);
            let mut released = scene.clone();
            let plan = StreamPlan::new(&released, tangents, faces);
            let (mut words, mut indices) = (Vec::new(), Vec::new());
            plan.write(
                Meshes::Release(&mut released.meshes),
                &mut words,
                &mut indices,
            );
            assert_eq!(words, kept.words, "{shading}: vertex words");
            assert_eq!(
                Some(indices).filter(|_| plan.indexed),
                kept.indices,
                "{shading}: indices"
            );
            assert_eq!(plan.batches, kept.batches, "{shading}: batches");
            for (m, before) in released.meshes.iter().zip(&scene.meshes) {
                assert_eq!(m.material, before.material);
                assert!(
                    m.positions.is_empty()
                        && m.normals.is_empty()
                        && m.tangents.is_empty()
                        && m.tex_coords.is_empty()
                        && m.indices.is_empty(),
                    "{shading}: {} not freed",
                    m.name
                );
            }
        }
    }
}
