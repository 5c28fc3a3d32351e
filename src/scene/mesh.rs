//! Triangle meshes in world space, and the normals the lecture's shading
//! modes need.

use crate::base::SurfaceFrame;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// An indexed triangle mesh, already in world space.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// A human-readable name (glTF mesh name or a generated one).
    pub name: String,
    pub positions: Vec<DVec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<DVec3>,
    /// Unit tangents (the direction of σ_x for anisotropic models), one per
    /// position, or empty: then [`Mesh::tangent`] derives one from the
    /// normal (`brdf::any_tangent`).
    pub tangents: Vec<DVec3>,
    /// The bitangent's sign per vertex (glTF `TANGENT.w`, ±1):
    /// `B = sign · N × T`, the frame a tangent-space normal map is read in
    /// (`material::texture::TextureTarget::Normal`); empty: +1 everywhere.
    /// Anisotropic models do not need it (they depend on (H·b)² only).
    pub bitangent_signs: Vec<f64>,
    /// Counter-clockwise triangles (glTF's front face).
    pub indices: Vec<[u32; 3]>,
    /// Index into [`crate::scene::Scene::materials`].
    pub material: usize,
    /// Texture coordinates per UV set (`TEXCOORD_0`, `TEXCOORD_1`), one
    /// per position each; glTF's convention, (0, 0) at the image's top-left
    /// corner. A set the mesh lacks reads as (0, 0).
    pub tex_coords: Vec<Vec<DVec2>>,
    /// Vertex colours (glTF `COLOR_0`, linear RGBA), one per position, or
    /// empty: white. Their RGB multiplies the material's colours
    /// (`Material::vertex_coloured`).
    pub colors: Vec<DVec4>,
    /// How much the glTF node's transform scales lengths, `∛|det M|` of
    /// its 3 × 3 part (exactly `s` for a uniform scale `s`; 1 outside
    /// glTF): `KHR_materials_volume` gives `thicknessFactor` in mesh space
    /// ("any transformations applied to the mesh's node will also be
    /// applied to the thickness"), and the positions here are already in
    /// world space. The GPU's screen-space transmission multiplies the
    /// thickness by it; the reference needs none (it follows the true path
    /// through the scaled mesh).
    pub volume_scale: f64,
}

impl Mesh {
    /// A mesh from positions and triangles, with normals generated as
    /// area-weighted averages of the adjacent face normals.
    pub fn with_generated_normals(
        name: impl Into<String>,
        positions: Vec<DVec3>,
        indices: Vec<[u32; 3]>,
        material: usize,
    ) -> Self {
        let normals = area_weighted_normals(&positions, &indices);
        Mesh {
            name: name.into(),
            positions,
            normals,
            tangents: Vec::new(),
            bitangent_signs: Vec::new(),
            indices,
            material,
            tex_coords: Vec::new(),
            colors: Vec::new(),
            volume_scale: 1.0,
        }
    }

    /// The UV of vertex `v` in set `set`, (0, 0) where the mesh has none.
    pub fn tex_coord(&self, set: usize, v: usize) -> DVec2 {
        self.tex_coords
            .get(set)
            .and_then(|s| s.get(v))
            .copied()
            .unwrap_or(DVec2::ZERO)
    }

    /// The tangent of vertex `v`: the stored one, or one derived from the
    /// normal.
    pub fn tangent(&self, v: usize) -> DVec3 {
        match self.tangents.get(v) {
            Some(t) => *t,
            None => crate::base::any_tangent(self.normals[v]),
        }
    }

    /// The colour of vertex `v` (white where the mesh has none).
    pub fn color(&self, v: usize) -> DVec4 {
        self.colors.get(v).copied().unwrap_or(DVec4::ONE)
    }

    /// The bitangent sign of vertex `v` (+1 where none is stored).
    pub fn bitangent_sign(&self, v: usize) -> f64 {
        self.bitangent_signs.get(v).copied().unwrap_or(1.0)
    }

    /// A copy of vertex `v` (every attribute) appended, its index
    /// returned: for splitting a vertex whose corners need different
    /// tangents (`scene::tangents`).
    pub fn duplicate_vertex(&mut self, v: usize) -> u32 {
        self.positions.push(self.positions[v]);
        self.normals.push(self.normals[v]);
        if let Some(&t) = self.tangents.get(v) {
            self.tangents.push(t);
        }
        if let Some(&s) = self.bitangent_signs.get(v) {
            self.bitangent_signs.push(s);
        }
        for set in &mut self.tex_coords {
            if let Some(&uv) = set.get(v) {
                set.push(uv);
            }
        }
        if let Some(&c) = self.colors.get(v) {
            self.colors.push(c);
        }
        (self.positions.len() - 1) as u32
    }

    /// Flat shading's frame of triangle `t`: the face normal and the
    /// corners' summed tangents made orthogonal to it. Both renderers
    /// shade a flat triangle in this frame (the GPU's flat vertices carry
    /// it, `gpu::geometry`; the reference evaluates it per hit).
    pub fn flat_frame(&self, t: usize) -> SurfaceFrame {
        let [a, b, c] = self.indices[t];
        let tangent =
            self.tangent(a as usize) + self.tangent(b as usize) + self.tangent(c as usize);
        SurfaceFrame::new(face_normal(self.triangle(t)), tangent)
    }

    /// Applies `world_from_object` to positions and its inverse transpose to
    /// normals (which stay unit length; a mirroring transform also flips the
    /// winding so front faces stay counter-clockwise), and multiplies
    /// [`Mesh::volume_scale`] by the transform's length scale.
    pub fn transform(&mut self, world_from_object: DMat4) {
        let normal_matrix = world_from_object.inverse().transpose();
        for p in &mut self.positions {
            *p = world_from_object.transform_point3(*p);
        }
        for n in &mut self.normals {
            *n = normal_matrix.transform_vector3(*n).normalize_or_zero();
        }
        // Tangents lie in the surface: they transform like positions' differences.
        for t in &mut self.tangents {
            *t = world_from_object.transform_vector3(*t).normalize_or_zero();
        }
        // Lengths scale by ∛|det| (exactly for a uniform scale; a
        // non-uniform one scales each direction differently, and this is
        // their geometric mean).
        let det = glam::DMat3::from_mat4(world_from_object).determinant();
        if det.is_finite() {
            self.volume_scale *= det.abs().cbrt();
        }
        if world_from_object.determinant() < 0.0 {
            for t in &mut self.indices {
                t.swap(1, 2);
            }
            // A mirror turns N × T against the mirrored bitangent.
            for s in &mut self.bitangent_signs {
                *s = -*s;
            }
        }
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.indices[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
}

/// Unit normal of a counter-clockwise triangle; zero for a degenerate one.
pub fn face_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a).normalize_or_zero()
}

/// Centroid of a triangle: where flat shading evaluates the reflection
/// equation.
pub fn centroid([a, b, c]: [DVec3; 3]) -> DVec3 {
    (a + b + c) / 3.0
}

/// Vertex normals as area-weighted averages of the adjacent face normals:
/// the unnormalized cross product of two edges has length twice the
/// triangle's area, so summing cross products weights by area.
/// Vertices used by no (non-degenerate) triangle get `+Y`.
pub fn area_weighted_normals(positions: &[DVec3], indices: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for &[a, b, c] in indices {
        let (pa, pb, pc) = (
            positions[a as usize],
            positions[b as usize],
            positions[c as usize],
        );
        let weighted = (pb - pa).cross(pc - pa);
        for v in [a, b, c] {
            sums[v as usize] += weighted;
        }
    }
    sums.into_iter()
        .map(|s| s.try_normalize().unwrap_or(DVec3::Y))
        .collect()
}

/// Axis-aligned bounds of a set of points, `None` if it is empty.
pub fn bounds(points: impl IntoIterator<Item = DVec3>) -> Option<(DVec3, DVec3)> {
    points.into_iter().fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_normals_of_a_flat_quad_point_up() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, -1.0),
            DVec3::new(0.0, 0.0, -1.0),
        ];
        let normals = area_weighted_normals(&positions, &[[0, 1, 2], [0, 2, 3]]);
        for n in normals {
            assert!((n - DVec3::Y).length() < 1e-12, "{n}");
        }
    }

    #[test]
    fn area_weighting_prefers_the_larger_face() {
        // A shared vertex between a big face (normal +Y) and a small one (+X).
        let positions = vec![
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, 10.0),
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let n = area_weighted_normals(&positions, &[[0, 1, 2], [0, 4, 3]])[0];
        // Areas 50 and 0.5: the normal is (0.5, 50, 0)/|...|.
        let expected = DVec3::new(0.5, 50.0, 0.0).normalize();
        assert!((n - expected).length() < 1e-12, "{n} vs {expected}");
    }

    /// The length scale composes over nested transforms: a uniform 2
    /// then a mirror with scales (−1, 4, 0.5) (det −2, ∛2 in length)
    /// give 2 · ∛2; rotations and translations leave it alone.
    #[test]
    fn volume_scale_is_the_transforms_length_scale() {
        let mut m = Mesh::with_generated_normals(
            "t",
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            vec![[0, 1, 2]],
            0,
        );
        assert_eq!(m.volume_scale, 1.0);
        m.transform(DMat4::from_rotation_translation(
            glam::DQuat::from_rotation_y(0.7),
            DVec3::new(3.0, -1.0, 2.0),
        ));
        assert!((m.volume_scale - 1.0).abs() < 1e-15);
        m.transform(DMat4::from_scale(DVec3::splat(2.0)));
        m.transform(DMat4::from_scale(DVec3::new(-1.0, 4.0, 0.5)));
        let want = 2.0 * 2f64.cbrt();
        assert!((m.volume_scale - want).abs() < 1e-14, "{}", m.volume_scale);
    }

    #[test]
    fn mirroring_transform_keeps_front_faces_ccw() {
        let mut m = Mesh::with_generated_normals(
            "t",
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            vec![[0, 1, 2]],
            0,
        );
        m.transform(DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0)));
        let n = face_normal(m.triangle(0));
        assert!((n - DVec3::Z).length() < 1e-12);
        assert!((m.normals[0] - DVec3::Z).length() < 1e-12);
    }
}
