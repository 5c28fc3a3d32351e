//! Tangents for normal maps where a mesh has none: MikkTSpace, as glTF
//! 2.0 asks ("When tangents are not specified, client implementations
//! SHOULD calculate tangents using default MikkTSpace algorithms with the
//! specified vertex positions, normals, and texture coordinates associated
//! with the normal texture"), through `bevy_mikktspace` (a safe port,
//! byte-identical to Mikkelsen's reference C implementation on x86).
//!
//! MikkTSpace's bitangent follows +v of the UVs it is given; glTF's v
//! points down the image while a normal map's green channel points up it
//! (glTF: "+Y is up"), so the generator sees `(u, 1 − v)`: a plain quad
//! with u to the right and v down then gets the sign +1 and `B = N × T`
//! pointing up the image, as glTF's own tangents and the Khronos sample
//! viewer's derivative-based frame have it.
//!
//! MikkTSpace gives a tangent per triangle corner; a vertex whose corners
//! got different tangents (a mirrored seam sharing a vertex) is split, one
//! copy per distinct tangent, so no corner's frame is averaged away.

use super::{Mesh, Scene};
use crate::material::texture::TextureTarget;
use glam::DVec3;
use std::collections::HashMap;

/// The normal-map UV set of a material's textures, if it has a normal map
/// (or a map read in the tangent frame as one is: the coat's normal map,
/// the anisotropy direction).
pub fn normal_map_set(m: &crate::material::Material) -> Option<usize> {
    m.textures
        .iter()
        .find(|t| {
            matches!(
                t.target,
                TextureTarget::Normal { .. }
                    | TextureTarget::ClearcoatNormal { .. }
                    | TextureTarget::Anisotropy
            )
        })
        .map(|t| t.tex_coord)
}

/// Generates MikkTSpace tangents and signs for every mesh of `scene`
/// whose material has a normal map and that has no tangents of its own.
pub fn generate_where_needed(scene: &mut Scene) {
    let materials = scene.effective_materials();
    for mesh in &mut scene.meshes {
        if let Some(set) = normal_map_set(&materials[mesh.material])
            && mesh.tangents.is_empty()
        {
            generate(mesh, set);
        }
    }
}

struct Corners<'a> {
    mesh: &'a Mesh,
    set: usize,
    /// The encoded tangent (xyz, sign) of every corner, `[triangle][corner]`.
    out: Vec<[[f32; 4]; 3]>,
}

impl bevy_mikktspace::Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len()
    }
    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }
    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        let v = self.mesh.indices[face][vert] as usize;
        self.mesh.positions[v].as_vec3().to_array()
    }
    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        let v = self.mesh.indices[face][vert] as usize;
        self.mesh.normals[v].as_vec3().to_array()
    }
    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let v = self.mesh.indices[face][vert] as usize;
        let uv = self.mesh.tex_coord(self.set, v);
        [uv.x as f32, (1.0 - uv.y) as f32]
    }
    fn set_tangent(
        &mut self,
        tangent_space: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        // A corner MikkTSpace could not give a frame (a degenerate
        // triangle without neighbours): any tangent, sign +1.
        self.out[face][vert] = tangent_space.map_or([0.0, 0.0, 0.0, 1.0], |t| t.tangent_encoded());
    }
}

/// MikkTSpace tangents for `mesh` from UV set `set`, into
/// `mesh.tangents` and `mesh.bitangent_signs`; vertices whose corners
/// disagree are split.
pub fn generate(mesh: &mut Mesh, set: usize) {
    let mut corners = Corners {
        mesh,
        set,
        out: vec![[[0.0; 4]; 3]; mesh.indices.len()],
    };
    // The error type has no variants: generation cannot fail.
    let _ = bevy_mikktspace::generate_tangents(&mut corners);
    let out = corners.out;
    let n = mesh.positions.len();
    mesh.tangents = vec![DVec3::ZERO; n];
    mesh.bitangent_signs = vec![1.0; n];
    let mut assigned: Vec<Option<[u32; 4]>> = vec![None; n];
    // Extra copies of a vertex, by (vertex, tangent bits).
    let mut copies: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    for (t, corner_tangents) in out.iter().enumerate() {
        for (c, encoded) in corner_tangents.iter().enumerate() {
            let v = mesh.indices[t][c];
            let bits = encoded.map(f32::to_bits);
            let target = match assigned[v as usize] {
                None => {
                    assigned[v as usize] = Some(bits);
                    v
                }
                Some(b) if b == bits => v,
                Some(_) => *copies
                    .entry((v, bits))
                    .or_insert_with(|| mesh.duplicate_vertex(v as usize)),
            };
            let tangent = DVec3::new(encoded[0].into(), encoded[1].into(), encoded[2].into());
            // Zero-length (no frame found): derived from the normal later.
            mesh.tangents[target as usize] = tangent
                .try_normalize()
                .unwrap_or_else(|| crate::base::any_tangent(mesh.normals[target as usize]));
            mesh.bitangent_signs[target as usize] = if encoded[3] < 0.0 { -1.0 } else { 1.0 };
            mesh.indices[t][c] = target;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// A unit quad in z = 0 facing +Z, u to the right (+X), v down (−Y):
    /// glTF's image orientation seen from the front.
    fn quad(flip_u: bool) -> Mesh {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let mut m = Mesh::with_generated_normals("q", positions, vec![[0, 1, 2], [0, 2, 3]], 0);
        let u = |x: f64| if flip_u { 1.0 - x } else { x };
        m.tex_coords = vec![vec![
            DVec2::new(u(0.0), 1.0),
            DVec2::new(u(1.0), 1.0),
            DVec2::new(u(1.0), 0.0),
            DVec2::new(u(0.0), 0.0),
        ]];
        m
    }

    /// T along +u, and B = sign·N×T along −v (up the image): +1 for the
    /// plain quad, −1 for the mirrored one, whose T points along −X.
    #[test]
    fn tangents_follow_u_and_the_sign_follows_the_image_up() {
        for (flip, t_want, sign) in [(false, DVec3::X, 1.0), (true, DVec3::NEG_X, -1.0)] {
            let mut m = quad(flip);
            generate(&mut m, 0);
            assert_eq!(m.positions.len(), 4, "no split needed");
            for v in 0..4 {
                assert!(
                    (m.tangents[v] - t_want).length() < 1e-6,
                    "{:?}",
                    m.tangents[v]
                );
                assert_eq!(m.bitangent_signs[v], sign);
                let b = sign * m.normals[v].cross(m.tangents[v]);
                // Up the image: v decreases along B.
                assert!((b - DVec3::Y).length() < 1e-6, "{b}");
            }
        }
    }

    /// Two quads mirrored about a shared edge whose vertices are shared:
    /// the shared vertices are split, each copy with its side's sign.
    #[test]
    fn a_mirrored_seam_splits_the_shared_vertices() {
        let positions = vec![
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        let indices = vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]];
        let mut m = Mesh::with_generated_normals("m", positions, indices, 0);
        // u runs 0 → 1 towards the seam from both sides.
        m.tex_coords = vec![vec![
            DVec2::new(0.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 0.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(0.0, 0.0),
        ]];
        generate(&mut m, 0);
        assert_eq!(m.positions.len(), 8, "the two seam vertices split");
        for tri in &m.indices {
            let signs: Vec<f64> = tri.iter().map(|&v| m.bitangent_sign(v as usize)).collect();
            assert!(signs.iter().all(|&s| s == signs[0]), "{signs:?}");
        }
        let right = m.indices[2][0] as usize;
        assert_eq!(m.bitangent_sign(right), -1.0);
        assert!((m.tangents[right] - DVec3::NEG_X).length() < 1e-6);
    }
}
