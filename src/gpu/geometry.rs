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
/// or vertices (de-indexed), inside its material's [`Batch`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjectRange {
    /// Index in `Scene::meshes`.
    pub mesh: u32,
    pub material: u32,
    pub range: std::ops::Range<u32>,
}

/// The triangles of one material: a range of indices (indexed streams)
/// or vertices (flat shading).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Batch {
    pub material: u32,
    pub range: std::ops::Range<u32>,
    /// Alpha BLEND: the one mesh (index in `Scene::meshes`) this batch
    /// draws, so that the renderer can draw such batches back to front
    /// per object; `None` for the others.
    pub object: Option<u32>,
}

/// Whether `mesh` is drawn with alpha BLEND.
fn blends(scene: &Scene, mesh: &Mesh) -> bool {
    scene.materials[mesh.material].alpha_mode == crate::material::AlphaMode::Blend
}

/// The scene's meshes (with their indices) in material order (stable),
/// so each material's triangles are contiguous, alpha BLEND meshes last
/// (drawn over everything else).
fn meshes_by_material(scene: &Scene) -> Vec<(usize, &Mesh)> {
    let mut meshes: Vec<_> = scene.meshes.iter().enumerate().collect();
    meshes.sort_by_key(|(_, m)| (blends(scene, m), m.material));
    meshes
}

/// Appends `count` elements of mesh `index` to `batches`, merging with
/// the last run of the same material unless it blends (a batch per
/// BLEND mesh).
fn extend_batches(
    batches: &mut Vec<Batch>,
    scene: &Scene,
    (index, mesh): (usize, &Mesh),
    count: usize,
) {
    let material = mesh.material as u32;
    let object = blends(scene, mesh).then_some(index as u32);
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
        }),
    }
}

/// Records mesh `index`, just appended to `batches`, as the last
/// `3 · triangles` elements of the stream.
fn push_object(objects: &mut Vec<ObjectRange>, batches: &[Batch], (index, mesh): (usize, &Mesh)) {
    let end = batches.last().map_or(0, |b| b.range.end);
    objects.push(ObjectRange {
        mesh: index as u32,
        material: mesh.material as u32,
        range: end - 3 * mesh.indices.len() as u32..end,
    });
}

fn push3(words: &mut Vec<u32>, v: glam::DVec3) {
    words.extend(v.as_vec3().to_array().map(f32::to_bits));
}

/// Both UV sets of a vertex (or of a centroid), if the stream has them.
fn push_uvs(words: &mut Vec<u32>, layout: &VertexLayout, uvs: [glam::DVec2; 2]) {
    if layout.tex_coords {
        for uv in uvs {
            words.extend(uv.as_vec2().to_array().map(f32::to_bits));
        }
    }
}

/// A bitangent sign, if the stream has them.
fn push_sign(words: &mut Vec<u32>, layout: &VertexLayout, sign: f64) {
    if layout.bitangent_signs {
        words.push((sign as f32).to_bits());
    }
}

/// A vertex colour, if the stream has them.
fn push_color(words: &mut Vec<u32>, layout: &VertexLayout, c: glam::DVec4) {
    if layout.colors {
        words.extend(c.as_vec4().to_array().map(f32::to_bits));
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

impl GeometryData {
    /// Lays out `scene`'s meshes for `scene.shading`, with tangents if
    /// asked, and with face normals (de-indexed) if asked and shaded per
    /// pixel.
    /// The UV sets are in the stream when a material has textures.
    pub fn new(scene: &Scene, tangents: bool, face_normals: bool) -> Self {
        let tex_coords = scene.has_textures();
        let signs = crate::gpu::textures::has_normal_maps(scene);
        match scene.shading {
            ShadingMode::Flat => Self::flat(scene, tangents, tex_coords, signs),
            ShadingMode::Phong if face_normals => {
                Self::phong_faces(scene, tangents, tex_coords, signs)
            }
            ShadingMode::Gouraud | ShadingMode::Phong => {
                Self::indexed(scene, tangents, tex_coords, signs)
            }
        }
    }

    /// Bytes of the vertex stream and of the index buffer that
    /// [`Self::new`] would lay out, computed from the counts alone so a
    /// stream over the GPU's limits is refused before it is built.
    pub fn byte_sizes(scene: &Scene, tangents: bool, face_normals: bool) -> (u64, u64) {
        let triangles = scene.triangle_count() as u64;
        let tex_coords = scene.has_textures();
        let layout = |shading_point, face_normal| VertexLayout {
            tangents,
            shading_point,
            face_normal,
            tex_coords,
            bitangent_signs: crate::gpu::textures::has_normal_maps(scene),
            colors: has_colors(scene),
        };
        match scene.shading {
            ShadingMode::Flat => (3 * triangles * layout(true, false).stride(), 0),
            ShadingMode::Phong if face_normals => (3 * triangles * layout(false, true).stride(), 0),
            ShadingMode::Gouraud | ShadingMode::Phong => {
                let vertices: u64 = scene.meshes.iter().map(|m| m.positions.len() as u64).sum();
                (vertices * layout(false, false).stride(), 3 * triangles * 4)
            }
        }
    }

    fn indexed(scene: &Scene, tangents: bool, tex_coords: bool, signs: bool) -> Self {
        let layout = VertexLayout {
            tangents,
            shading_point: false,
            face_normal: false,
            tex_coords,
            bitangent_signs: signs,
            colors: has_colors(scene),
        };
        let vertex_count: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
        let mut words = Vec::with_capacity(vertex_count * layout.stride() as usize / 4);
        let mut indices = Vec::with_capacity(3 * scene.triangle_count());
        let mut base = 0u32;
        let mut batches = Vec::new();
        let mut objects = Vec::new();
        for (index, mesh) in meshes_by_material(scene) {
            extend_batches(&mut batches, scene, (index, mesh), 3 * mesh.indices.len());
            push_object(&mut objects, &batches, (index, mesh));
            for v in 0..mesh.positions.len() {
                push3(&mut words, mesh.positions[v]);
                push3(&mut words, mesh.normals[v]);
                if tangents {
                    push3(&mut words, mesh.tangent(v));
                }
                push_uvs(&mut words, &layout, vertex_uvs(mesh, v));
                push_sign(&mut words, &layout, mesh.bitangent_sign(v));
                push_color(&mut words, &layout, mesh.color(v));
            }
            indices.extend(mesh.indices.iter().flatten().map(|i| base + i));
            base += mesh.positions.len() as u32;
        }
        GeometryData {
            words,
            draw_count: indices.len() as u32,
            indices: Some(indices),
            batches,
            objects,
            layout,
        }
    }

    /// De-indexed: every corner carries the triangle's frame and centroid
    /// (computed in f64 exactly as the reference's flat shading does).
    fn flat(scene: &Scene, tangents: bool, tex_coords: bool, signs: bool) -> Self {
        let layout = VertexLayout {
            tangents,
            shading_point: true,
            face_normal: false,
            tex_coords,
            bitangent_signs: signs,
            colors: has_colors(scene),
        };
        Self::de_indexed(scene, layout, |mesh, t, words| {
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
                if tangents {
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
    fn phong_faces(scene: &Scene, tangents: bool, tex_coords: bool, signs: bool) -> Self {
        let layout = VertexLayout {
            tangents,
            shading_point: false,
            face_normal: true,
            tex_coords,
            bitangent_signs: signs,
            colors: has_colors(scene),
        };
        Self::de_indexed(scene, layout, |mesh, t, words| {
            let face = face_normal(mesh.triangle(t));
            for v in mesh.indices[t].map(|v| v as usize) {
                push3(words, mesh.positions[v]);
                push3(words, mesh.normals[v]);
                if tangents {
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
    /// appends the three corners of triangle `t` in `layout`.
    fn de_indexed(
        scene: &Scene,
        layout: VertexLayout,
        triangle: impl Fn(&Mesh, usize, &mut Vec<u32>),
    ) -> Self {
        let mut words =
            Vec::with_capacity(3 * scene.triangle_count() * layout.stride() as usize / 4);
        let mut batches = Vec::new();
        let mut objects = Vec::new();
        for (index, mesh) in meshes_by_material(scene) {
            extend_batches(&mut batches, scene, (index, mesh), 3 * mesh.indices.len());
            push_object(&mut objects, &batches, (index, mesh));
            for t in 0..mesh.indices.len() {
                triangle(mesh, t, &mut words);
            }
        }
        GeometryData {
            draw_count: (words.len() as u64 * 4 / layout.stride()) as u32,
            words,
            indices: None,
            batches,
            objects,
            layout,
        }
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
        let mesh = meshes_by_material(&scene)[0].1;
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
}
