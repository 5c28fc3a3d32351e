//! Vertex streams for each shading mode, built from the scene's meshes.
//!
//! All meshes go into one vertex buffer drawn with one call: each vertex
//! carries its material index, so one pipeline and one draw render the
//! whole scene.

use crate::scene::mesh::{centroid, face_normal};
use crate::scene::{Scene, ShadingMode};
use bytemuck::{Pod, Zeroable};

/// Vertex of Gouraud and Phong shading (indexed, shared between triangles).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub material: u32,
}

/// Vertex of flat shading: de-indexed, every corner carries the face normal
/// and the triangle's centroid, where the colour is evaluated.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FlatVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub material: u32,
    pub shading_point: [f32; 3],
}

/// Vertex bytes, optional indices and the vertex layout for a mode.
pub struct GeometryData {
    pub vertices: Vec<u8>,
    /// `None` for a non-indexed draw (flat shading).
    pub indices: Option<Vec<u32>>,
    /// Vertices to draw (non-indexed) or indices to draw (indexed).
    pub draw_count: u32,
    pub stride: u64,
    pub attributes: &'static [wgpu::VertexAttribute],
}

const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32];
const FLAT_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Uint32, 3 => Float32x3];

impl GeometryData {
    /// Lays out `scene`'s meshes for `scene.shading`.
    pub fn new(scene: &Scene) -> Self {
        match scene.shading {
            ShadingMode::Flat => Self::flat(scene),
            ShadingMode::Gouraud | ShadingMode::Phong => Self::indexed(scene),
        }
    }

    fn indexed(scene: &Scene) -> Self {
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        for mesh in &scene.meshes {
            let base = vertices.len() as u32;
            vertices.extend(
                mesh.positions
                    .iter()
                    .zip(&mesh.normals)
                    .map(|(p, n)| Vertex {
                        position: p.as_vec3().to_array(),
                        normal: n.as_vec3().to_array(),
                        material: mesh.material as u32,
                    }),
            );
            indices.extend(mesh.indices.iter().flatten().map(|i| base + i));
        }
        GeometryData {
            vertices: bytemuck::cast_slice(&vertices).to_vec(),
            draw_count: indices.len() as u32,
            indices: Some(indices),
            stride: std::mem::size_of::<Vertex>() as u64,
            attributes: &VERTEX_ATTRIBUTES,
        }
    }

    fn flat(scene: &Scene) -> Self {
        let mut vertices = Vec::with_capacity(3 * scene.triangle_count());
        for mesh in &scene.meshes {
            for t in 0..mesh.indices.len() {
                let tri = mesh.triangle(t);
                let normal = face_normal(tri).as_vec3().to_array();
                let shading_point = centroid(tri).as_vec3().to_array();
                vertices.extend(tri.iter().map(|p| FlatVertex {
                    position: p.as_vec3().to_array(),
                    normal,
                    material: mesh.material as u32,
                    shading_point,
                }));
            }
        }
        GeometryData {
            draw_count: vertices.len() as u32,
            vertices: bytemuck::cast_slice(&vertices).to_vec(),
            indices: None,
            stride: std::mem::size_of::<FlatVertex>() as u64,
            attributes: &FLAT_ATTRIBUTES,
        }
    }
}
