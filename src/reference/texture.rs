//! Texture sampling in f64, the twin of `shaders/textures.wgsl` (which
//! leaves the same steps to the GPU's sampler): the same half-float texels
//! (`scene::texture::Image`), the same wrap rule, the same bilinear blend,
//! the same mip level from the same footprint rule, so that a textured
//! GPU frame can be checked against the reference.
//!
//! The rules are Vulkan's (the specification's "Texel Filtering" and
//! "LOD Operation", which lavapipe implements):
//!
//! * level of detail `λ = log₂ ρ`, `ρ = max(|∂uv/∂x ⊙ size|, |∂uv/∂y ⊙ size|)`
//!   in texels of level 0 per pixel; magnified (the mag filter) where
//!   `λ ≤ 0`, minified (the min filter) elsewhere;
//! * with mipmaps, `λ` clamped to `[0, levels − 1]`; linear mipmapping
//!   blends levels `⌊λ⌋` and `⌊λ⌋ + 1` by `λ − ⌊λ⌋`, nearest takes level
//!   `⌈λ + ½⌉ − 1`; without (glTF's minFilter NEAREST / LINEAR), level 0
//!   (the GPU binds a one-level view, so the mag/min choice still sees
//!   the true `λ`);
//! * in a level of `w × h`, nearest reads texel `⌊u·w⌋, ⌊v·h⌋`; linear
//!   blends the four around `u·w − ½, v·h − ½` by their fractions;
//!   indices outside the level wrap per axis (repeat, clamp, mirror).
//!
//! Where the footprint comes from ([`Footprint`]) is the renderer's
//! business: see `reference::renderer` (the rasterizer's 2×2-quad
//! differences, reproduced on the hit triangle's plane).

use crate::material::brdf::SurfaceFrame;
use crate::material::texture::{Filter, Sampler, Wrap};
use crate::scene::texture::{Image, Level};
use glam::{DVec2, DVec3, DVec4};

/// The UV derivatives of a pixel: how far UV moves per pixel step in x
/// and in y (already through the texture's UV transform).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    pub duv_dx: DVec2,
    pub duv_dy: DVec2,
}

/// The texel value of `image` at `uv` for a pixel of `footprint` (zero:
/// level 0 with the mag filter, as the GPU's vertex stage samples with
/// `textureSampleLevel(…, 0)`).
pub fn sample(image: &Image, sampler: &Sampler, uv: DVec2, footprint: Footprint) -> DVec4 {
    let base = &image.levels[0];
    let size = DVec2::new(base.width as f64, base.height as f64);
    let rho = (footprint.duv_dx * size)
        .length()
        .max((footprint.duv_dy * size).length());
    let lambda = if rho > 0.0 { rho.log2() } else { 0.0 };
    let (filter, mipmap) = if lambda <= 0.0 {
        (sampler.mag, None)
    } else {
        (sampler.min, sampler.mipmap)
    };
    let top = (image.levels.len() - 1) as f64;
    let at = |level: usize| sample_level(&image.levels[level], sampler, filter, uv);
    match mipmap {
        None => at(0),
        Some(Filter::Nearest) => {
            let d = ((lambda.clamp(0.0, top) + 0.5).ceil() - 1.0).max(0.0);
            at(d as usize)
        }
        Some(Filter::Linear) => {
            let l = lambda.clamp(0.0, top);
            let d = l.floor();
            let f = l - d;
            let lo = at(d as usize);
            if f == 0.0 {
                lo
            } else {
                lo + (at(d as usize + 1) - lo) * f
            }
        }
    }
}

/// One level read with `filter`.
fn sample_level(level: &Level, sampler: &Sampler, filter: Filter, uv: DVec2) -> DVec4 {
    let (w, h) = (level.width as i64, level.height as i64);
    let (s, t) = (uv.x * w as f64, uv.y * h as f64);
    let texel = |i: i64, j: i64| {
        level.texel(
            wrap(sampler.wrap_u, i, w) as u32,
            wrap(sampler.wrap_v, j, h) as u32,
        )
    };
    match filter {
        Filter::Nearest => texel(s.floor() as i64, t.floor() as i64),
        Filter::Linear => {
            let (s, t) = (s - 0.5, t - 0.5);
            let (i, j) = (s.floor(), t.floor());
            let (a, b) = (s - i, t - j);
            let (i, j) = (i as i64, j as i64);
            let top = texel(i, j) * (1.0 - a) + texel(i + 1, j) * a;
            let bottom = texel(i, j + 1) * (1.0 - a) + texel(i + 1, j + 1) * a;
            top * (1.0 - b) + bottom * b
        }
    }
}

/// Texel index `i` wrapped into `0..size` (Vulkan's wrapping operations).
pub fn wrap(mode: Wrap, i: i64, size: i64) -> i64 {
    match mode {
        Wrap::Repeat => i.rem_euclid(size),
        Wrap::ClampToEdge => i.clamp(0, size - 1),
        Wrap::MirroredRepeat => {
            let t = i.rem_euclid(2 * size);
            if t < size { t } else { 2 * size - 1 - t }
        }
    }
}

/// A material at a surface point: its textures applied, and the
/// tangent-space normals of its normal map and of its coat's normal map
/// (`None` without one).
pub struct Textured {
    pub material: crate::material::Material,
    pub normal: Option<DVec3>,
    pub clearcoat_normal: Option<DVec3>,
}

/// `material` with its textures applied at a surface point whose UV sets
/// are `uv` (and their footprints `footprint`): each texture multiplies
/// the parameter it names, a colour by the texel's RGB, a scalar by the
/// texture's channel (the base colour's also the alpha by its A); an
/// occlusion texture scales the occlusion `o` by `1 + strength·(R − 1)`
/// (`Material::occlusion`); a normal texture gives the tangent-space
/// normal (`decode_normal`, turned by its transform's rotation:
/// `rotated_normal`), a coat normal texture the coat's (the same way);
/// an anisotropy texture adds its direction's angle to
/// `anisotropy_rotation` and multiplies `anisotropy_strength` by its B
/// (`decode_anisotropy`) (GPU twin: `textured_surface` in
/// shaders/textures.wgsl).
pub fn textured(
    material: &crate::material::Material,
    images: &[std::sync::Arc<Image>],
    uv: [DVec2; 2],
    footprint: [Footprint; 2],
) -> Textured {
    use crate::material::param::Value;
    use crate::material::texture::{
        TextureTarget, decode_anisotropy, decode_normal, rotated_normal,
    };
    let mut m = material.clone();
    let mut normal = None;
    let mut clearcoat_normal = None;
    for t in &material.textures {
        let texel = texel_of(t, images, uv, footprint);
        if t.carries_alpha() {
            m.alpha *= texel.w;
        }
        match t.target {
            TextureTarget::Param(key) => {
                let Some(p) = crate::material::table::param_for(m.model, key) else {
                    continue;
                };
                let v = match p.read(&m) {
                    Value::Color(c) => Value::Color(c * texel.truncate()),
                    Value::Scalar(v) => Value::Scalar(v * texel[t.channel]),
                };
                p.write(&mut m, v);
            }
            TextureTarget::Occlusion { strength } => {
                m.occlusion *= TextureTarget::with_strength(texel.x, strength);
            }
            TextureTarget::Normal { scale } => {
                let n = decode_normal(texel.truncate(), scale);
                normal = Some(rotated_normal(n, t.transform.rotation));
            }
            TextureTarget::ClearcoatNormal { scale } => {
                let n = decode_normal(texel.truncate(), scale);
                clearcoat_normal = Some(rotated_normal(n, t.transform.rotation));
            }
            TextureTarget::Anisotropy => {
                let (angle, strength) = decode_anisotropy(texel.truncate(), t.transform.rotation);
                m.layers.anisotropy_rotation += angle;
                m.layers.anisotropy_strength *= strength;
            }
        }
    }
    Textured {
        material: m,
        normal,
        clearcoat_normal,
    }
}

/// Texture `t`'s texel at a point whose UV sets are `uv` (footprints
/// `footprint`), through its UV transform.
fn texel_of(
    t: &crate::material::texture::MaterialTexture,
    images: &[std::sync::Arc<Image>],
    uv: [DVec2; 2],
    footprint: [Footprint; 2],
) -> DVec4 {
    let set = t.tex_coord.min(1);
    let fp = Footprint {
        duv_dx: t.transform.apply_vector(footprint[set].duv_dx),
        duv_dy: t.transform.apply_vector(footprint[set].duv_dy),
    };
    sample(&images[t.image], &t.sampler, t.transform.apply(uv[set]), fp)
}

/// The alpha at a point (UV sets `uv`, footprints `footprint`) of a
/// material with alpha `alpha` (vertex colour's A already applied) and
/// textures `textures`: `alpha` times the A of its base colour texture,
/// read exactly as [`textured`] reads it (GPU twin: the `alpha` of
/// `textured_surface` in shaders/textures.wgsl).
pub fn alpha(
    alpha: f64,
    textures: &[crate::material::texture::MaterialTexture],
    images: &[std::sync::Arc<Image>],
    uv: [DVec2; 2],
    footprint: [Footprint; 2],
) -> f64 {
    textures
        .iter()
        .filter(|t| t.carries_alpha())
        .fold(alpha, |a, t| a * texel_of(t, images, uv, footprint).w)
}

/// The shading frame with a normal map's tangent-space normal `n_t`
/// applied: `n' = normalize(n_t.x·T + n_t.y·B + n_t.z·N)` in the frame's
/// orthonormal T and N with `B = sign · N × T` (glTF 2.0's normal
/// texture; the tangent made orthogonal to the interpolated normal first,
/// as both renderers build the frame), then the frame rebuilt around n'
/// with the same tangent. GPU twin: `normal_mapped_frame` in
/// shaders/textures.wgsl.
pub fn normal_mapped_frame(frame: &SurfaceFrame, sign: f64, n_t: DVec3) -> SurfaceFrame {
    let b = sign * frame.n.cross(frame.t);
    let n = (frame.t * n_t.x + b * n_t.y + frame.n * n_t.z).normalize_or_zero();
    SurfaceFrame::new(n, frame.t)
}

/// The coat's normal map applied: its world normal
/// `n_c = normalize(n_t.x·T + n_t.y·B + n_t.z·N)` in the mesh's frame
/// `vertex_frame` (before any base normal map, as the Khronos Sample
/// Renderer's `getClearcoatNormal` uses the vertex TBN), then written in
/// the coordinates of the shading frame `shading` (what
/// `GltfLayers::clearcoat_normal` holds). GPU twin:
/// `clearcoat_normal_coords` in shaders/textures.wgsl.
pub fn clearcoat_normal_coords(
    vertex_frame: &SurfaceFrame,
    sign: f64,
    n_t: DVec3,
    shading: &SurfaceFrame,
) -> DVec3 {
    let n_c = normal_mapped_frame(vertex_frame, sign, n_t).n;
    DVec3::new(n_c.dot(shading.t), n_c.dot(shading.b), n_c.dot(shading.n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::texture::decode::Decoded;
    use crate::scene::texture::{Encoding, Image};

    /// A 4×1 image with texels 0, 1, 2, 3 (in R).
    fn ramp() -> Image {
        let rgba = (0..4).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect();
        Image::new(
            "ramp",
            Encoding::Linear,
            Decoded {
                width: 4,
                height: 1,
                rgba,
            },
        )
    }

    #[test]
    fn wrap_modes_fold_indices_as_vulkan() {
        let got: Vec<i64> = (-3..7).map(|i| wrap(Wrap::MirroredRepeat, i, 3)).collect();
        assert_eq!(got, [2, 1, 0, 0, 1, 2, 2, 1, 0, 0]);
        assert_eq!(wrap(Wrap::Repeat, -1, 3), 2);
        assert_eq!(wrap(Wrap::ClampToEdge, 5, 3), 2);
    }

    #[test]
    fn bilinear_blends_between_texel_centres_and_nearest_picks_one() {
        let image = ramp();
        let mut s = Sampler::default();
        let at =
            |s: &Sampler, u: f64| sample(&image, s, DVec2::new(u, 0.5), Footprint::default()).x;
        // Texel centres at u = (i + ½)/4.
        assert_eq!(at(&s, 0.375), 1.0);
        assert_eq!(at(&s, 0.5), 1.5);
        // Repeat: left of texel 0's centre blends with texel 3.
        assert_eq!(at(&s, 0.0), 1.5);
        s.wrap_u = Wrap::ClampToEdge;
        assert_eq!(at(&s, 0.0), 0.0);
        s.mag = Filter::Nearest;
        assert_eq!(at(&s, 0.49), 1.0);
        assert_eq!(at(&s, 0.51), 2.0);
    }

    #[test]
    fn minification_blends_mip_levels_by_the_footprint() {
        let image = ramp();
        let s = Sampler::default();
        // Two texels per pixel: λ = 1, level 1 = (0.5, 2.5).
        let fp = Footprint {
            duv_dx: DVec2::new(0.5, 0.0),
            duv_dy: DVec2::ZERO,
        };
        assert_eq!(sample(&image, &s, DVec2::new(0.25, 0.5), fp).x, 0.5);
        // λ = 1.5: halfway to level 2 (the mean, 1.5).
        let fp = Footprint {
            duv_dx: DVec2::new(2f64.powf(1.5) / 4.0, 0.0),
            duv_dy: DVec2::ZERO,
        };
        let v = sample(&image, &s, DVec2::new(0.25, 0.5), fp).x;
        assert!((v - 1.0).abs() < 1e-12, "{v}");
    }
}
