//! Where a material parameter varies over the surface: the lecture's
//! spatially varying BRDF `f_r(x, ω_i, ω_o)` as textures. A
//! [`MaterialTexture`] says which parameter an image multiplies and how
//! the image is read at a surface point: which UV set, the
//! `KHR_texture_transform` of it, and the glTF sampler (wrap modes,
//! filters). The images themselves are the scene's
//! (`crate::scene::texture::Image`, by index); both renderers read them
//! with the rules here (GPU: `shaders/textures.wgsl`, reference:
//! `crate::reference::texture`).

use glam::{DMat3, DVec2};

/// What a texture does to the material at a point.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureTarget {
    /// Multiplies the parameter with this scene-file key (`k_d`,
    /// `roughness`, ...): a colour parameter by the texel's RGB, a scalar
    /// one by one channel ([`MaterialTexture::channel`]).
    Param(&'static str),
    /// A tangent-space normal map (glTF's `normalTexture`, the scene
    /// file's `normal_texture`): the texel's RGB encodes
    /// `n_t = 2·rgb − 1`, scaled by `(scale, scale, 1)` and normalized,
    /// in the frame (T, B, N) of the interpolated tangent, bitangent
    /// (`sign · N × T`) and normal (glTF 2.0 §3.9.3, "normalTexture").
    Normal { scale: f64 },
    /// glTF's `occlusionTexture`: the material's occlusion `o` (see
    /// `Material::occlusion`) is multiplied by `1 + strength·(R − 1)`
    /// (glTF 2.0: `occludedColor = lerp(color, color * <sampled occlusion
    /// texture value>, <occlusion strength>)`); `o` scales the ambient
    /// term and the environment's light, not direct light.
    Occlusion { strength: f64 },
    /// The coat's own tangent-space normal map (`KHR_materials_clearcoat`'s
    /// `clearcoatNormalTexture`, the scene file's
    /// `clearcoat_normal_texture`): decoded as [`TextureTarget::Normal`]
    /// (glTF's encoding with its `scale`) in the mesh's frame (T, B, N)
    /// before any `normal_texture`, it gives the coat's normal, about which
    /// the coat's lobe and Fresnel are evaluated (the base keeps its own
    /// normal). Without it the coat's normal is the shading normal.
    ClearcoatNormal { scale: f64 },
    /// `KHR_materials_anisotropy`'s `anisotropyTexture` (the scene file's
    /// `anisotropy_texture`): RG is the anisotropy direction in tangent
    /// space, `[0, 1] → [−1, 1]`, turned by `anisotropy_rotation`; B
    /// multiplies `anisotropy_strength` ([`decode_anisotropy`]).
    Anisotropy,
}

impl TextureTarget {
    /// The factor a texture's value `v` (its channel) applies with
    /// `strength` (1 for a plain multiplier): `v` itself at strength 1
    /// (exactly, not `1 + (v − 1)`), else `1 + strength·(v − 1)`. GPU
    /// twin: `slot_factor` in shaders/textures.wgsl.
    pub fn with_strength(v: f64, strength: f64) -> f64 {
        if strength == 1.0 {
            v
        } else {
            1.0 + strength * (v - 1.0)
        }
    }
}

/// glTF's normal-texture decoding: `normalize((2·rgb − 1) ⊙ (scale,
/// scale, 1))`, the tangent-space normal; (0, 0, 1) for a texel that
/// decodes to zero length. GPU twin: `decoded_normal` in
/// shaders/textures.wgsl.
pub fn decode_normal(rgb: glam::DVec3, scale: f64) -> glam::DVec3 {
    let n = (2.0 * rgb - glam::DVec3::ONE) * glam::DVec3::new(scale, scale, 1.0);
    n.try_normalize().unwrap_or(glam::DVec3::Z)
}

/// `KHR_materials_anisotropy`'s texture decoding: the direction
/// `d = 2·(R, G) − 1` as its angle from `t` towards `b`, `atan2(d_y, d_x)`
/// (the extension rotates the normalized `d` by `anisotropyRotation`, so
/// the angles add; 0 for a texel that decodes to zero length, where the
/// extension's `normalize` is undefined), and the strength factor B.
/// The angle is taken after the texture transform's rotation turns `d`
/// as it turns a normal map's normal ([`rotated_normal`]). GPU twin:
/// `anisotropy_texel` in shaders/textures.wgsl (which keeps the direction
/// as a unit vector and multiplies it by `(cos ρ, sin ρ)`).
pub fn decode_anisotropy(rgb: glam::DVec3, rotation: f64) -> (f64, f64) {
    let d = rotated_normal(
        glam::DVec3::new(2.0 * rgb.x - 1.0, 2.0 * rgb.y - 1.0, 0.0),
        rotation,
    );
    let angle = if d.x == 0.0 && d.y == 0.0 {
        0.0
    } else {
        d.y.atan2(d.x)
    };
    (angle, rgb.z)
}

/// A normal map's tangent-space normal `n` in the mesh's tangent frame
/// when the map is read through a `KHR_texture_transform` rotation `r`
/// (radians): `(n'_x, n'_y) = R·(n_x, n_y)`, `n'_z = n_z`, with the
/// contract's `R = [[cos r, sin r], [−sin r, cos r]]`. Why: the map's +X
/// points along its own u' and +Y up its image (−v'); with
/// `uv' = R·uv`, `∂P/∂u' = cos r·T − sin r·B` and `−∂P/∂v' = sin r·T +
/// cos r·B` (T = ∂P/∂u, B = −∂P/∂v, glTF's bitangent), so
/// `n_x·T' + n_y·B' = (R·n_xy)·(T, B)`: the frame turns with the map, as
/// a tangent computed from the transformed UVs would (the Khronos sample
/// viewer's derivative frame). Only the rotation: a non-uniform scale
/// would also shear the frame, which is not followed. GPU twin:
/// `rotated_normal` in shaders/textures.wgsl.
pub fn rotated_normal(n: glam::DVec3, rotation: f64) -> glam::DVec3 {
    if rotation == 0.0 {
        return n;
    }
    let (s, c) = rotation.sin_cos();
    glam::DVec3::new(c * n.x + s * n.y, -s * n.x + c * n.y, n.z)
}

/// One texture of a material.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTexture {
    pub target: TextureTarget,
    /// Index into the scene's images.
    pub image: usize,
    /// The channel a scalar parameter reads (0 = R; glTF's metallic is B,
    /// its roughness G). Colour parameters read RGB.
    pub channel: usize,
    /// Which `TEXCOORD_n` (0 or 1).
    pub tex_coord: usize,
    pub transform: UvTransform,
    pub sampler: Sampler,
}

impl MaterialTexture {
    /// Whether the texel's A multiplies the material's alpha: the base
    /// colour's texture (glTF `baseColorTexture`: "the fourth component
    /// (A) is the linear alpha coverage").
    pub fn carries_alpha(&self) -> bool {
        self.target == TextureTarget::Param("base_color")
    }
}

/// How texel indices outside `0..size` wrap (glTF `wrapS` / `wrapT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// glTF 10497, the default.
    #[default]
    Repeat,
    /// glTF 33071.
    ClampToEdge,
    /// glTF 33648.
    MirroredRepeat,
}

/// One texel or a bilinear blend of four (glTF NEAREST / LINEAR).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Filter {
    Nearest,
    #[default]
    Linear,
}

/// A glTF sampler. `mipmap: None` reads level 0 only (glTF's minFilter
/// NEAREST or LINEAR); `Some(f)` chooses levels from the pixel footprint
/// and blends two (`Linear`) or takes the nearest (`Nearest`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sampler {
    pub wrap_u: Wrap,
    pub wrap_v: Wrap,
    pub mag: Filter,
    pub min: Filter,
    pub mipmap: Option<Filter>,
}

impl Default for Sampler {
    /// glTF leaves the filters of a texture without a sampler to the
    /// implementation; gonio takes what the Khronos sample viewer takes:
    /// repeat, bilinear magnification, trilinear minification.
    fn default() -> Self {
        Sampler {
            wrap_u: Wrap::Repeat,
            wrap_v: Wrap::Repeat,
            mag: Filter::Linear,
            min: Filter::Linear,
            mipmap: Some(Filter::Linear),
        }
    }
}

impl Sampler {
    /// The sampler of glTF's numeric codes (`None`: the default's).
    pub fn from_gltf(
        mag: Option<u32>,
        min: Option<u32>,
        wrap_s: u32,
        wrap_t: u32,
    ) -> Result<Self, String> {
        let wrap = |code: u32| match code {
            10497 => Ok(Wrap::Repeat),
            33071 => Ok(Wrap::ClampToEdge),
            33648 => Ok(Wrap::MirroredRepeat),
            other => Err(format!("wrap mode {other} is not one glTF defines")),
        };
        let d = Sampler::default();
        let mag = match mag {
            None => d.mag,
            Some(9728) => Filter::Nearest,
            Some(9729) => Filter::Linear,
            Some(other) => return Err(format!("magFilter {other} is not one glTF defines")),
        };
        use Filter::{Linear as L, Nearest as N};
        let (min, mipmap) = match min {
            None => (d.min, d.mipmap),
            Some(9728) => (N, None),
            Some(9729) => (L, None),
            Some(9984) => (N, Some(N)),
            Some(9985) => (L, Some(N)),
            Some(9986) => (N, Some(L)),
            Some(9987) => (L, Some(L)),
            Some(other) => return Err(format!("minFilter {other} is not one glTF defines")),
        };
        Ok(Sampler {
            wrap_u: wrap(wrap_s)?,
            wrap_v: wrap(wrap_t)?,
            mag,
            min,
            mipmap,
        })
    }
}

/// `KHR_texture_transform`: `uv' = offset + R·(scale ⊙ uv)` with
/// `R = [[cos r, sin r], [−sin r, cos r]]` (rows), the sign the Khronos
/// sample viewer, three.js and Babylon.js use (the extension's own GLSL
/// listing has it wrong: KhronosGroup/glTF#1563; the contract,
/// `shared/spec/conventions.md`). The identity without the extension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    pub offset: DVec2,
    /// Radians.
    pub rotation: f64,
    pub scale: DVec2,
}

impl Default for UvTransform {
    fn default() -> Self {
        UvTransform {
            offset: DVec2::ZERO,
            rotation: 0.0,
            scale: DVec2::ONE,
        }
    }
}

impl UvTransform {
    /// The affine map as a 3×3 matrix acting on `(u, v, 1)`.
    pub fn matrix(&self) -> DMat3 {
        let (s, c) = self.rotation.sin_cos();
        // Columns: images of (1,0), (0,1) and the translation.
        DMat3::from_cols(
            glam::DVec3::new(c * self.scale.x, -s * self.scale.x, 0.0),
            glam::DVec3::new(s * self.scale.y, c * self.scale.y, 0.0),
            glam::DVec3::new(self.offset.x, self.offset.y, 1.0),
        )
    }

    /// `uv` transformed.
    pub fn apply(&self, uv: DVec2) -> DVec2 {
        self.matrix().transform_point2(uv)
    }

    /// A UV difference (a derivative) transformed: no offset.
    pub fn apply_vector(&self, d: DVec2) -> DVec2 {
        self.matrix().transform_vector2(d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The contract's rotation: r = 90° takes (1, 0) to (0, −1) and
    /// (0, 1) to (1, 0), i.e. u' = v, v' = −u (rows of R).
    #[test]
    fn rotation_follows_the_contracts_sign() {
        let t = UvTransform {
            rotation: std::f64::consts::FRAC_PI_2,
            ..Default::default()
        };
        assert!((t.apply(DVec2::X) - DVec2::new(0.0, -1.0)).length() < 1e-12);
        assert!((t.apply(DVec2::Y) - DVec2::X).length() < 1e-12);
        let t = UvTransform {
            offset: DVec2::new(0.5, 0.25),
            rotation: 0.0,
            scale: DVec2::new(2.0, 3.0),
        };
        assert!((t.apply(DVec2::ONE) - DVec2::new(2.5, 3.25)).length() < 1e-12);
        assert!((t.apply_vector(DVec2::ONE) - DVec2::new(2.0, 3.0)).length() < 1e-12);
    }

    /// r = 90°: the map's +X is the mesh's −B and its +Y is +T, so the
    /// map's (1, 0) is (0, −1) in the mesh's frame and its (0, 1) is (1, 0).
    #[test]
    fn a_quarter_turn_of_the_map_turns_its_normal() {
        let r = std::f64::consts::FRAC_PI_2;
        let n = rotated_normal(glam::DVec3::new(1.0, 0.0, 0.0), r);
        assert!(
            (n - glam::DVec3::new(0.0, -1.0, 0.0)).length() < 1e-15,
            "{n}"
        );
        let n = rotated_normal(glam::DVec3::new(0.0, 1.0, 0.5), r);
        assert!(
            (n - glam::DVec3::new(1.0, 0.0, 0.5)).length() < 1e-15,
            "{n}"
        );
        assert_eq!(rotated_normal(glam::DVec3::ONE, 0.0), glam::DVec3::ONE);
    }

    /// RG is the direction in the frame (t, b), `[0, 1] → [−1, 1]`, as an
    /// angle from t towards b; B the strength factor; a transform's
    /// rotation turns the direction as it turns a normal map's normal;
    /// a zero direction is t.
    #[test]
    fn anisotropy_texels_decode_to_an_angle_and_a_strength() {
        use glam::DVec3;
        use std::f64::consts::FRAC_PI_2;
        let (a, s) = decode_anisotropy(DVec3::new(1.0, 0.5, 0.7), 0.0);
        assert_eq!((a, s), (0.0, 0.7));
        let (a, _) = decode_anisotropy(DVec3::new(0.5, 1.0, 1.0), 0.0);
        assert!((a - FRAC_PI_2).abs() < 1e-15, "{a}");
        let (a, _) = decode_anisotropy(DVec3::new(1.0, 0.5, 1.0), FRAC_PI_2);
        assert!((a + FRAC_PI_2).abs() < 1e-15, "{a}");
        assert_eq!(
            decode_anisotropy(DVec3::new(0.5, 0.5, 1.0), 0.0),
            (0.0, 1.0)
        );
    }

    #[test]
    fn gltf_codes_map_to_samplers() {
        let s = Sampler::from_gltf(Some(9728), Some(9986), 33648, 33071).unwrap();
        assert_eq!(s.mag, Filter::Nearest);
        assert_eq!((s.min, s.mipmap), (Filter::Nearest, Some(Filter::Linear)));
        assert_eq!(
            (s.wrap_u, s.wrap_v),
            (Wrap::MirroredRepeat, Wrap::ClampToEdge)
        );
        assert_eq!(
            Sampler::from_gltf(None, None, 10497, 10497).unwrap(),
            Sampler::default()
        );
        assert!(Sampler::from_gltf(Some(1), None, 10497, 10497).is_err());
    }
}
