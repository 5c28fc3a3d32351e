//! Meshes gonio generates itself (so the built-in scene ships no assets).

use crate::scene::Mesh;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// Vertices and triangles [`uv_sphere`] builds for `segments`, known
/// before anything is allocated (so limits are checked first).
pub fn uv_sphere_size(segments: u32) -> (u64, u64) {
    let slices = segments.max(3) as u64;
    let stacks = (segments / 2).max(2) as u64;
    ((stacks + 1) * (slices + 1), 2 * slices * (stacks - 1))
}

/// Vertices and triangles [`plane`] builds for `divisions`.
pub fn plane_size(divisions: u32) -> (u64, u64) {
    let n = divisions.max(1) as u64;
    ((n + 1) * (n + 1), 2 * n * n)
}

/// A UV sphere: `segments` slices around +Y and `segments / 2` stacks.
/// Normals are the exact sphere normals (not averaged), so every shading
/// mode sees the true surface orientation at the vertices.
pub fn uv_sphere(center: DVec3, radius: f64, segments: u32, material: usize) -> Mesh {
    let slices = segments.max(3);
    let stacks = (segments / 2).max(2);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut tangents = Vec::new();
    let mut uvs = Vec::new();
    for s in 0..=stacks {
        let theta = PI * s as f64 / stacks as f64; // from +Y down
        for k in 0..=slices {
            let phi = TAU * k as f64 / slices as f64;
            let n = DVec3::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                theta.sin() * phi.cos(),
            );
            positions.push(center + radius * n);
            normals.push(n);
            // ∂n/∂φ: along the parallels, so anisotropic lobes stretch
            // around the sphere like brushed metal on a lathe.
            tangents.push(DVec3::new(phi.cos(), 0.0, -phi.sin()));
            // Latitude-longitude UVs: u around +Y, v from the north pole.
            uvs.push(DVec2::new(
                k as f64 / slices as f64,
                s as f64 / stacks as f64,
            ));
        }
    }
    let row = slices + 1;
    let mut indices = Vec::new();
    for s in 0..stacks {
        for k in 0..slices {
            let a = s * row + k;
            let (b, c, d) = (a + row, a + row + 1, a + 1);
            // Counter-clockwise seen from outside; skip the degenerate
            // triangles at the poles.
            if s != 0 {
                indices.push([a, b, d]);
            }
            if s != stacks - 1 {
                indices.push([d, b, c]);
            }
        }
    }
    Mesh {
        name: "sphere".into(),
        positions,
        normals,
        tangents,
        bitangent_signs: Vec::new(),
        indices,
        material,
        tex_coords: vec![uvs],
        colors: Vec::new(),
        volume_scale: 1.0,
    }
}

/// A square in the plane y = `center.y`, facing +Y, `size` wide along X and
/// Z, split into `divisions²` quads (finer tessellation helps Gouraud).
pub fn plane(center: DVec3, size: f64, divisions: u32, material: usize) -> Mesh {
    let n = divisions.max(1);
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let x = (j as f64 / n as f64 - 0.5) * size;
            let z = (i as f64 / n as f64 - 0.5) * size;
            positions.push(center + DVec3::new(x, 0.0, z));
            // u along +X, v along +Z: the image lies on the plane as seen
            // from above with −Z at its top.
            uvs.push(DVec2::new(j as f64 / n as f64, i as f64 / n as f64));
        }
    }
    let row = n + 1;
    let mut indices = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let a = i * row + j;
            // a at (x, z); a+1 at (x+dx, z); a+row at (x, z+dz).
            indices.push([a, a + row, a + row + 1]);
            indices.push([a, a + row + 1, a + 1]);
        }
    }
    let normals = vec![DVec3::Y; positions.len()];
    let tangents = vec![DVec3::X; positions.len()];
    Mesh {
        name: "plane".into(),
        positions,
        normals,
        tangents,
        bitangent_signs: Vec::new(),
        indices,
        material,
        tex_coords: vec![uvs],
        colors: Vec::new(),
        volume_scale: 1.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::mesh::{centroid, face_normal};

    #[test]
    fn sizes_are_known_before_building() {
        for segments in [1, 2, 3, 4, 7, 48, 101] {
            let m = uv_sphere(DVec3::ZERO, 1.0, segments, 0);
            let size = (m.positions.len() as u64, m.indices.len() as u64);
            assert_eq!(uv_sphere_size(segments), size, "sphere {segments}");
            let p = plane(DVec3::ZERO, 1.0, segments, 0);
            let size = (p.positions.len() as u64, p.indices.len() as u64);
            assert_eq!(plane_size(segments), size, "plane {segments}");
        }
    }

    #[test]
    fn sphere_faces_point_outwards() {
        let m = uv_sphere(DVec3::new(1.0, 2.0, 3.0), 2.0, 24, 0);
        for t in 0..m.indices.len() {
            let tri = m.triangle(t);
            let out = centroid(tri) - DVec3::new(1.0, 2.0, 3.0);
            assert!(face_normal(tri).dot(out) > 0.0, "triangle {t}");
        }
    }

    #[test]
    fn plane_faces_up() {
        let m = plane(DVec3::ZERO, 4.0, 3, 0);
        assert_eq!(m.indices.len(), 18);
        for t in 0..m.indices.len() {
            assert!((face_normal(m.triangle(t)) - DVec3::Y).length() < 1e-12);
        }
    }
}
