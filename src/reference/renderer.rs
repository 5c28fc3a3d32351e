//! The reference image: one primary ray per pixel sample, the closest hit
//! inside the camera's depth range, and the shading mode the GPU uses.
//!
//! Every choice here mirrors the rasterizer, so that a difference between
//! the two frames is a bug in one of them and not a difference of method:
//! the same near/far clipping, the same shading points and normals, the
//! same interpolation of per-vertex results.
//!
//! With an environment map, rays that miss see the map (the background),
//! and the diffuse term integrates it (`super::shading`).
//!
//! Shadows are ray traced ([`visibility`]): the truth the GPU's shadow maps
//! are measured against. Visibility is evaluated at the shading point of
//! the mode (flat: the centroid; Gouraud: the vertex, then interpolated
//! with the colour; Phong: the pixel's interpolated position), exactly
//! where the GPU reads its shadow map.

use super::shading::reflected_radiance;
use super::texture::{self, Footprint};
use crate::frame::Frame;
use crate::material::brdf::SurfaceFrame;
use crate::material::{Material, Sides};
use crate::scene::bvh::{Bvh, Hit};
use crate::scene::camera::Ray;
use crate::scene::{Light, Mesh, Rgb, Scene, ShadingMode, mesh};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// How the reference treats area lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum AreaLights {
    /// As the GPU does: through their N point lights (`Light::AreaSample`),
    /// one shadow ray each.
    #[default]
    Samples,
    /// Exactly, unoccluded, by Lambert's polygon formula for the
    /// irradiance (`AreaLight::exact_irradiance`). Exact for Lambertian
    /// receivers only (`f_r` constant over the light); ignores shadows of
    /// area lights. See [`super::area`] for when it applies.
    ExactUnoccluded,
}

/// Renders `scene` with one sample at every pixel centre.
pub fn render(scene: &Scene) -> Frame {
    render_offset(scene, 0.0, 0.0)
}

/// Renders `scene` with the sample of pixel (row i, column j) at
/// `(j + 0.5 + offset_x, i + 0.5 + offset_y)` pixels (row 0 at the top);
/// shifted samples let callers supersample or probe edges.
pub fn render_offset(scene: &Scene, offset_x: f64, offset_y: f64) -> Frame {
    render_with(scene, offset_x, offset_y, AreaLights::Samples)
}

/// [`render`] with every texture's level of detail moved by `bias`
/// (λ + bias; the pixel footprint scaled by 2^bias): how far the GPU's
/// mip choice may move the image (tests/textures.rs).
pub fn render_with_lod_bias(scene: &Scene, bias: f64) -> Frame {
    render_inner(scene, 0.0, 0.0, AreaLights::Samples, bias)
}

/// Bytes [`render`] allocates for `scene` beyond the scene itself, an
/// upper bound checked against `--limit memory` before it starts: the
/// hierarchy at the peak of its build and the frame.
pub fn memory_estimate(scene: &Scene) -> u64 {
    let pixels = u64::from(scene.width) * u64::from(scene.height);
    let per_pixel = (size_of::<[f32; 3]>() + size_of::<bool>()) as u64;
    (scene.triangle_count() as u64)
        .saturating_mul(crate::scene::bvh::BUILD_BYTES_PER_TRIANGLE)
        .saturating_add(pixels.saturating_mul(per_pixel))
}

/// [`render_offset`] with a choice of how area lights are evaluated.
pub fn render_with(scene: &Scene, offset_x: f64, offset_y: f64, area: AreaLights) -> Frame {
    render_inner(scene, offset_x, offset_y, area, 0.0)
}

/// The image rows `rows` (row 0 at the top) of [`render`], stacked in
/// that order: a frame of `scene.width × rows.len()` pixels, each equal
/// bit for bit to the same pixel of the whole image. A pixel depends on
/// the scene and its own position only (one ray, no random numbers, the
/// per-triangle and per-vertex tables computed the same way for every
/// subset), which is what lets `gonio render --shard` split an image
/// over processes and machines (`crate::cluster`).
pub fn render_rows(scene: &Scene, rows: &[u32]) -> Frame {
    render_rows_inner(scene, rows, 0.0, 0.0, AreaLights::Samples, 0.0)
}

fn render_inner(
    scene: &Scene,
    offset_x: f64,
    offset_y: f64,
    area: AreaLights,
    lod_bias: f64,
) -> Frame {
    let rows: Vec<u32> = (0..scene.height).collect();
    render_rows_inner(scene, &rows, offset_x, offset_y, area, lod_bias)
}

/// [`render`] and the largest share of a pixel's transmitted light the
/// paths through transmissive surfaces left untraced (bounce limit;
/// `super::transmission::Traced::lost`, per unit radiance behind; 0
/// without transmission).
pub fn render_reporting(scene: &Scene) -> (Frame, f64) {
    let rows: Vec<u32> = (0..scene.height).collect();
    render_rows_reporting(scene, &rows, 0.0, 0.0, AreaLights::Samples, 0.0)
}

fn render_rows_inner(
    scene: &Scene,
    rows: &[u32],
    offset_x: f64,
    offset_y: f64,
    area: AreaLights,
    lod_bias: f64,
) -> Frame {
    render_rows_reporting(scene, rows, offset_x, offset_y, area, lod_bias).0
}

fn render_rows_reporting(
    scene: &Scene,
    rows: &[u32],
    offset_x: f64,
    offset_y: f64,
    area: AreaLights,
    lod_bias: f64,
) -> (Frame, f64) {
    let (width, height) = (scene.width, scene.height);
    let mut frame = Frame::new(width, rows.len() as u32);
    if frame.is_empty() {
        return (frame, 0.0);
    }
    let bvh = Bvh::new(&scene.meshes);
    let mut shader = Shader::new(scene, &bvh, area);
    shader.offset = (offset_x, offset_y);
    shader.footprint_scale = lod_bias.exp2();
    let camera = &scene.camera;
    let forward = camera.forward();
    let rays = camera.rays(width, height);
    let row = width as usize;
    frame
        .radiance
        .par_chunks_mut(row)
        .zip(frame.coverage.par_chunks_mut(row))
        .zip(rows.par_iter())
        .for_each(|((radiance, coverage), &i)| {
            let i = i as usize;
            let y = i as f64 + 0.5 + offset_y;
            for (j, (out, covered)) in radiance.iter_mut().zip(coverage).enumerate() {
                let ray = rays.ray(j as f64 + 0.5 + offset_x, y);
                // The GPU clips at view depths near and far; along this ray
                // depth grows as t · cos(angle to the viewing axis).
                let cos = ray.direction.dot(forward);
                if cos <= 0.0 {
                    continue;
                }
                let (t_near, t_far) = (camera.near / cos, camera.far / cos);
                let (radiance, opacity) = shader.trace(&ray, t_near, t_far, (i, j));
                *out = radiance.as_vec3().to_array();
                // The GPU's coverage: the blended alpha over a clear of 0,
                // read as covered above ½ (gpu::readback).
                *covered = opacity > 0.5;
            }
        });
    let lost = f64::from_bits(shader.lost.load(Ordering::Relaxed));
    (frame, lost)
}

/// The scene and what its shading mode needs, computed once before any
/// pixel is traced.
struct Shader<'a> {
    scene: &'a Scene,
    bvh: &'a Bvh,
    /// The materials as rendered (roughness floor applied), as on the GPU.
    materials: Vec<Material>,
    precomputed: Precomputed,
    /// Shadow-ray origin offset (see [`shadow_epsilon`]).
    epsilon: f64,
    /// Per light, per mesh: whether the mesh lets the light through as
    /// its marker (`crate::scene::light_markers::passing`).
    markers: Vec<Vec<bool>>,
    area: AreaLights,
    /// The sample offset of every pixel (for the texture footprint).
    offset: (f64, f64),
    /// Multiplies every texture footprint (1; 2^bias for a LOD bias).
    footprint_scale: f64,
    /// The largest share of a pixel's transmitted light left untraced
    /// ([`super::transmission::Traced::lost`]), as `f64` bits (positive
    /// floats order as their bits).
    lost: AtomicU64,
}

enum Precomputed {
    /// Radiance per triangle, `[mesh][triangle]`, of its front and its
    /// back (the back's differs for double-sided materials only).
    Flat(Vec<Vec<[Rgb; 2]>>),
    /// Radiance per vertex, `[mesh][vertex]`, front and back.
    Gouraud(Vec<Vec<[Rgb; 2]>>),
    /// Nothing: shaded per hit.
    Phong,
}

impl<'a> Shader<'a> {
    /// What the pixel `(row, column)` of primary ray `ray` sees within
    /// `[t_near, t_far]`, and its opacity (0: nothing, or only what is
    /// fully transparent; 1: an opaque surface): the ray walks from hit to
    /// hit, front to back. A point that alpha MASK removes is passed
    /// through (the GPU discards its fragment); a BLEND point adds
    /// `T·a·L` and leaves `T·(1 − a)` for what lies behind (`T` the
    /// transmittance so far), the same sum as the GPU's back-to-front
    /// "over" blending (`L = a·L_s + (1 − a)·L_behind`); an opaque point
    /// ends the walk, and a ray that leaves the scene sees the
    /// environment map (if any) through `T`. Within one BLEND object
    /// the order here is the exact depth order; the GPU draws an
    /// object's triangles in index order (sorted per object only), so
    /// the two differ where a ray meets one BLEND object twice.
    ///
    /// The walk goes on from `t + ε` (ε = [`shadow_epsilon`]): a ray
    /// through the shared edge of two triangles meets both at the same
    /// `t`, and the rasterizer draws one of them (its fill rule), so hits
    /// closer than ε count as one surface.
    fn trace(&self, ray: &Ray, t_near: f64, t_far: f64, pixel: (usize, usize)) -> (Rgb, f64) {
        let scene = self.scene;
        let mut sum = Rgb::ZERO;
        let mut transmittance = 1.0;
        let mut t_from = t_near;
        // Single-sided materials' back faces are culled, as the GPU
        // discards them.
        let keeps_back = |id: crate::scene::bvh::TriangleId| {
            let m = &scene.meshes[id.mesh as usize];
            self.materials[m.material].sides != Sides::Front
        };
        loop {
            let Some(hit) = self.bvh.intersect_where(ray, t_from, t_far, keeps_back) else {
                if let Some(map) = &scene.environment.map {
                    // Contract: a ray that misses sees scale · L_env(d)
                    // (coverage stays 0, as on the GPU).
                    sum += transmittance * map.radiance(ray.direction);
                }
                break;
            };
            let object = &scene.meshes[hit.id.mesh as usize];
            let mode = self.materials[object.material].alpha_mode;
            let a = match mode {
                crate::material::AlphaMode::Opaque => 1.0,
                _ => self.alpha(&hit, pixel),
            };
            t_from = hit.t + self.epsilon;
            if mode.discards(a) {
                continue;
            }
            let opacity = mode.opacity(a);
            let face = mesh::face_normal(object.triangle(hit.id.triangle as usize));
            let back = ray.direction.dot(face) > 0.0;
            sum += transmittance * opacity * self.radiance(&hit, pixel, back);
            if self.materials[object.material].layers.transmits() {
                // Light through the surface (`super::transmission`).
                let c = self.crossing(&hit, ray, Some(pixel));
                let traced = super::transmission::through(self, &c);
                sum += transmittance * opacity * traced.radiance;
                self.lost
                    .fetch_max(traced.lost.to_bits(), Ordering::Relaxed);
            }
            transmittance *= 1.0 - opacity;
            if transmittance <= 0.0 {
                break;
            }
        }
        (sum, 1.0 - transmittance)
    }

    /// The alpha at `hit` (of pixel `pixel`), where the GPU evaluates it:
    /// per pixel (Phong: interpolated UVs and colour, the pixel's texture
    /// footprint), or per vertex at texture level 0 and interpolated
    /// (Gouraud), or once per triangle at its centroid's UVs with the
    /// corners' mean colour (flat), as its vertex stage does.
    fn alpha(&self, hit: &Hit, pixel: (usize, usize)) -> f64 {
        let (m, t) = (hit.id.mesh as usize, hit.id.triangle as usize);
        let object = &self.scene.meshes[m];
        let idx = object.indices[t];
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let at = |uv: [DVec2; 2], color: glam::DVec4, footprint: [Footprint; 2]| {
            let base = &self.materials[object.material];
            let a = if object.colors.is_empty() {
                base.alpha
            } else {
                base.alpha * color.w
            };
            texture::alpha(a, &base.textures, &self.scene.images, uv, footprint)
        };
        let vertex = |v: u32| {
            let v = v as usize;
            at(
                [0, 1].map(|set| object.tex_coord(set, v)),
                object.color(v),
                [Footprint::default(); 2],
            )
        };
        match self.scene.shading {
            ShadingMode::Phong => {
                let uv = [0, 1].map(|set| interpolate_uv(w, object, set, idx));
                let colors = idx.map(|v| object.color(v as usize));
                let color = w[0] * colors[0] + w[1] * colors[1] + w[2] * colors[2];
                let footprint = if self.materials[object.material].textures.is_empty() {
                    [Footprint::default(); 2]
                } else {
                    [0, 1].map(|set| self.footprint(object, t, set, pixel))
                };
                at(uv, color, footprint)
            }
            ShadingMode::Gouraud => {
                let corner = idx.map(vertex);
                w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2]
            }
            ShadingMode::Flat => {
                let uv = [0, 1].map(|set| {
                    idx.iter()
                        .map(|&v| object.tex_coord(set, v as usize))
                        .sum::<DVec2>()
                        / 3.0
                });
                let color = idx
                    .iter()
                    .map(|&v| object.color(v as usize))
                    .sum::<glam::DVec4>()
                    / 3.0;
                at(uv, color, [Footprint::default(); 2])
            }
        }
    }

    /// Whether a shadow ray's `hit` occludes light `l`: as [`Self::blocks`],
    /// but a marker of the light lets it through
    /// (`crate::scene::light_markers`).
    fn blocks_light(&self, l: usize, hit: &Hit) -> bool {
        let marker = self
            .markers
            .get(l)
            .and_then(|m| m.get(hit.id.mesh as usize))
            .copied()
            .unwrap_or(false);
        !marker && self.blocks(hit)
    }

    /// Whether a shadow ray's `hit` occludes: everywhere but where alpha
    /// MASK cuts the surface out. The alpha there is what the GPU's
    /// masked shadow pass reads (shaders/shadow_pass.wgsl): the factor
    /// times `COLOR_0`'s A and the base colour texture's A at the hit's
    /// interpolated UVs, at level 0 with the magnification filter (a
    /// zero footprint: the pass samples with `textureSampleLevel(…, 0)`).
    /// BLEND surfaces occlude as opaque ones (docs/gltf-surfaces.md), but for
    /// a light's markers ([`Self::blocks_light`]).
    fn blocks(&self, hit: &Hit) -> bool {
        let object = &self.scene.meshes[hit.id.mesh as usize];
        let base = &self.materials[object.material];
        if !matches!(base.alpha_mode, crate::material::AlphaMode::Mask { .. }) {
            return true;
        }
        let idx = object.indices[hit.id.triangle as usize];
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let uv = [0, 1].map(|set| interpolate_uv(w, object, set, idx));
        let a = if object.colors.is_empty() {
            base.alpha
        } else {
            let c = idx.map(|v| object.color(v as usize));
            base.alpha * (w[0] * c[0] + w[1] * c[1] + w[2] * c[2]).w
        };
        let a = texture::alpha(
            a,
            &base.textures,
            &self.scene.images,
            uv,
            [Footprint::default(); 2],
        );
        !base.alpha_mode.discards(a)
    }

    fn new(scene: &'a Scene, bvh: &'a Bvh, area: AreaLights) -> Self {
        let mut shader = Shader {
            scene,
            bvh,
            materials: scene.effective_materials(),
            precomputed: Precomputed::Phong,
            epsilon: shadow_epsilon(scene),
            markers: crate::scene::light_markers::passing(scene),
            area,
            offset: (0.0, 0.0),
            footprint_scale: 1.0,
            lost: AtomicU64::new(0),
        };
        shader.precomputed = match scene.shading {
            // Lecture: Shading Model: Flat. One evaluation of the reflection
            // equation per triangle, at its centroid with its face normal:
            // the colour is constant over the triangle, as on the GPU.
            ShadingMode::Flat => Precomputed::Flat(
                scene
                    .meshes
                    .iter()
                    .map(|m| {
                        (0..m.indices.len())
                            .into_par_iter()
                            .map(|t| {
                                let corners = m.triangle(t);
                                let uv = [0, 1].map(|set| {
                                    m.indices[t]
                                        .iter()
                                        .map(|&v| m.tex_coord(set, v as usize))
                                        .sum::<DVec2>()
                                        / 3.0
                                });
                                // The corners' mean colour, as the GPU's
                                // flat stream carries it.
                                let color = m.indices[t]
                                    .iter()
                                    .map(|&v| m.color(v as usize))
                                    .sum::<glam::DVec4>()
                                    / 3.0;
                                shader.both_sides(m, |flip| {
                                    let frame = flipped(&m.flat_frame(t), flip);
                                    let (material, frame) = shader.material_at(
                                        m,
                                        uv,
                                        color,
                                        None,
                                        frame,
                                        flip * m.bitangent_sign(m.indices[t][0] as usize),
                                    );
                                    shader.shade(
                                        &material,
                                        mesh::centroid(corners),
                                        &frame,
                                        m_face(m, t),
                                    )
                                })
                            })
                            .collect()
                    })
                    .collect(),
            ),
            // Lecture: Shading Model: Gouraud. Shade at the vertices with the
            // vertex normals (what the GPU's vertex shader computes), then
            // interpolate the colours.
            ShadingMode::Gouraud => Precomputed::Gouraud(
                scene
                    .meshes
                    .iter()
                    .map(|m| {
                        (0..m.positions.len())
                            .into_par_iter()
                            .map(|v| {
                                let uv = [0, 1].map(|set| m.tex_coord(set, v));
                                shader.both_sides(m, |flip| {
                                    let frame =
                                        SurfaceFrame::new(flip * m.normals[v], flip * m.tangent(v));
                                    let (material, frame) = shader.material_at(
                                        m,
                                        uv,
                                        m.color(v),
                                        None,
                                        frame,
                                        flip * m.bitangent_sign(v),
                                    );
                                    shader.shade(&material, m.positions[v], &frame, m.normals[v])
                                })
                            })
                            .collect()
                    })
                    .collect(),
            ),
            ShadingMode::Phong => Precomputed::Phong,
        };
        shader
    }

    /// `shade(1)` for the front and, for a double-sided material,
    /// `shade(−1)` for the back (else the front's again).
    fn both_sides(&self, m: &Mesh, shade: impl Fn(f64) -> Rgb) -> [Rgb; 2] {
        let front = shade(1.0);
        if self.materials[m.material].sides == Sides::Both {
            [front, shade(-1.0)]
        } else {
            [front, front]
        }
    }

    /// Reflected radiance seen at `hit`, the hit of pixel `(row, column)`,
    /// on the triangle's back if `back` (lit with the flipped frame for a
    /// double-sided material).
    fn radiance(&self, hit: &Hit, pixel: (usize, usize), back: bool) -> Rgb {
        let (m, t) = (hit.id.mesh as usize, hit.id.triangle as usize);
        let object = &self.scene.meshes[m];
        let idx = object.indices[t];
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let side = usize::from(back);
        let flip = if back && self.materials[object.material].sides == Sides::Both {
            -1.0
        } else {
            1.0
        };
        match &self.precomputed {
            Precomputed::Flat(per_triangle) => per_triangle[m][t][side],
            Precomputed::Gouraud(per_vertex) => {
                let corner = idx.map(|v| per_vertex[m][v as usize][side]);
                w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2]
            }
            Precomputed::Phong => {
                // Lecture: Shading Model: Phong. Interpolate the vertex
                // normals, renormalize, shade every pixel. The position is
                // the barycentric blend of the corners, as the GPU
                // interpolates world positions, not origin + t·direction.
                let x = interpolate(w, &object.positions, idx);
                // Opposite normals can interpolate to zero: no direction,
                // so only the ambient term remains (as on the GPU).
                let n = flip * interpolate(w, &object.normals, idx).normalize_or_zero();
                let tangents = idx.map(|v| object.tangent(v as usize));
                let t = flip * (w[0] * tangents[0] + w[1] * tangents[1] + w[2] * tangents[2]);
                let geometric = mesh::face_normal(object.triangle(hit.id.triangle as usize));
                let uv = [0, 1].map(|set| interpolate_uv(w, object, set, idx));
                // The bitangent sign interpolated as the GPU interpolates
                // its vertex attribute (±1 at the corners; only its sign
                // is used).
                let sign = idx
                    .iter()
                    .zip(w)
                    .map(|(&v, w)| w * object.bitangent_sign(v as usize))
                    .sum::<f64>();
                let colors = idx.map(|v| object.color(v as usize));
                let color = w[0] * colors[0] + w[1] * colors[1] + w[2] * colors[2];
                let (material, frame) = self.material_at(
                    object,
                    uv,
                    color,
                    Some((t_index(hit), pixel)),
                    SurfaceFrame::new(n, t),
                    flip * if sign < 0.0 { -1.0 } else { 1.0 },
                );
                self.shade(&material, x, &frame, geometric)
            }
        }
    }

    /// The material of mesh `m` at a point with UV sets `uv`, vertex
    /// colour `color` (used if the mesh has colours) and shading frame
    /// `frame`: its textures applied, read with the footprint of
    /// the pixel when one is given (`(triangle, (row, column))`,
    /// per-pixel shading), else at level 0 (per-vertex shading, as the
    /// GPU's vertex stage); the frame with the normal map applied
    /// (bitangent sign `sign`), if the material has one.
    fn material_at(
        &self,
        m: &Mesh,
        uv: [DVec2; 2],
        color: glam::DVec4,
        pixel: Option<(usize, (usize, usize))>,
        frame: SurfaceFrame,
        sign: f64,
    ) -> (std::borrow::Cow<'_, Material>, SurfaceFrame) {
        let base = &self.materials[m.material];
        // Vertex colours multiply the colours first (GPU: vertex_coloured).
        let coloured =
            (!m.colors.is_empty()).then(|| base.vertex_coloured(color.truncate(), color.w));
        if base.textures.is_empty() {
            return match coloured {
                Some(c) => (std::borrow::Cow::Owned(c), frame),
                None => (std::borrow::Cow::Borrowed(base), frame),
            };
        }
        let material = coloured.as_ref().unwrap_or(base);
        let footprint = match pixel {
            Some((t, pixel)) => [0, 1].map(|set| self.footprint(m, t, set, pixel)),
            None => [Footprint::default(); 2],
        };
        let textured = texture::textured(material, &self.scene.images, uv, footprint);
        let vertex_frame = frame;
        let frame = match textured.normal {
            Some(n_t) => texture::normal_mapped_frame(&frame, sign, n_t),
            None => frame,
        };
        // The pixel footprint's roughness floor on the textured widths
        // (the others had it in `effective_materials`).
        let mut floored = textured
            .material
            .with_textured_widths_floored(self.scene.roughness_floor());
        // The coat's normal map, in the mesh's frame, written in the
        // shading frame's coordinates.
        if let Some(n_t) = textured.clearcoat_normal {
            floored.layers.clearcoat_normal =
                texture::clearcoat_normal_coords(&vertex_frame, sign, n_t, &frame);
        }
        (std::borrow::Cow::Owned(floored), frame)
    }

    /// The UV derivatives of UV set `set` at pixel `(row, column)` on
    /// triangle `t` of `m`, as the rasterizer forms them: within the 2×2
    /// quad of pixels the pixel belongs to, `∂/∂x` is the difference
    /// between the quad's two pixel centres in the pixel's row and `∂/∂y`
    /// between the two in its column (WGSL's `dpdx`/`dpdy` as lavapipe
    /// computes them, "fine"), the attribute taken on the triangle's plane
    /// even where a pixel of the quad lies outside the triangle (helper
    /// invocations extrapolate). An analytic derivative at the pixel
    /// itself would differ from it by the change of the perspective
    /// derivative across one pixel (second order); this rule follows the
    /// GPU's. Measured on assets/scenes/textured: the "coarse" rule (the
    /// quad's top-left pixel for all four) left errors of 1.9·10⁻² where
    /// this one leaves 5·10⁻³, within the level-of-detail tolerance of
    /// tests/textures.rs.
    fn footprint(
        &self,
        m: &Mesh,
        t: usize,
        set: usize,
        (row, column): (usize, usize),
    ) -> Footprint {
        let (ox, oy) = self.offset;
        let (i0, j0) = ((row & !1) as f64, (column & !1) as f64);
        let (w, h) = (self.scene.width, self.scene.height);
        let idx = m.indices[t];
        let corners = m.triangle(t);
        let uv_at = |x: f64, y: f64| {
            let ray = self.scene.camera.ray(x, y, w, h);
            plane_weights(&ray, corners).map(|b| interpolate_uv(b, m, set, idx))
        };
        // The pixel's own row and column of its quad ("fine").
        let (x0, y0) = (j0 + 0.5 + ox, i0 + 0.5 + oy);
        let (x, y) = (column as f64 + 0.5 + ox, row as f64 + 0.5 + oy);
        match (
            uv_at(x0, y),
            uv_at(x0 + 1.0, y),
            uv_at(x, y0),
            uv_at(x, y0 + 1.0),
        ) {
            (Some(left), Some(right), Some(top), Some(bottom)) => Footprint {
                duv_dx: (right - left) * self.footprint_scale,
                duv_dy: (bottom - top) * self.footprint_scale,
            },
            _ => Footprint::default(),
        }
    }

    /// The reflection equation at `x` in `frame`, for `material`,
    /// seen from the camera, with ray-traced visibility; shadow rays leave
    /// from `x` offset along `n_offset` (see [`visibility`]).
    fn shade(&self, material: &Material, x: DVec3, frame: &SurfaceFrame, n_offset: DVec3) -> Rgb {
        self.shade_from(material, x, frame, n_offset, self.scene.camera.position)
    }

    /// [`Self::shade`] seen from `eye` (a ray's origin).
    fn shade_from(
        &self,
        material: &Material,
        x: DVec3,
        frame: &SurfaceFrame,
        n_offset: DVec3,
        eye: DVec3,
    ) -> Rgb {
        let exact = self.area == AreaLights::ExactUnoccluded;
        let lights = &self.scene.lights;
        let mut radiance = reflected_radiance(
            self.scene,
            material,
            x,
            frame,
            eye,
            |l, x| {
                if exact && matches!(lights[l], Light::AreaSample { .. }) {
                    return 0.0;
                }
                visibility_where(self.bvh, &lights[l], x, n_offset, self.epsilon, |hit| {
                    self.blocks_light(l, hit)
                })
            },
            |wi| {
                environment_visible(self.bvh, x, n_offset, wi, self.epsilon, |hit| {
                    self.blocks(hit)
                })
            },
        );
        if exact {
            // f_r of a Lambertian receiver is the same for every direction
            // above the surface; any such direction evaluates it.
            let wo = (eye - x).normalize_or_zero();
            let f_r = super::brdf::reference_brdf(material).f_r(frame.n, wo, frame);
            for area in &self.scene.area_lights {
                radiance += f_r * area.exact_irradiance(x, frame.n);
            }
        }
        radiance
    }
}

impl Shader<'_> {
    /// The crossing of `ray` at `hit` for the transmission paths: the
    /// point, the Phong-interpolated shading frame (front side, normal map
    /// applied), the face normal and the material at the point (textures
    /// read with the pixel's footprint when `pixel` is given, else at
    /// level 0).
    fn crossing(
        &self,
        hit: &Hit,
        ray: &Ray,
        pixel: Option<(usize, usize)>,
    ) -> super::transmission::Crossing<'_> {
        let (m, t) = (hit.id.mesh as usize, hit.id.triangle as usize);
        let object = &self.scene.meshes[m];
        let idx = object.indices[t];
        let w = [1.0 - hit.u - hit.v, hit.u, hit.v];
        let point = interpolate(w, &object.positions, idx);
        let n = interpolate(w, &object.normals, idx).normalize_or_zero();
        let face = mesh::face_normal(object.triangle(t));
        let n = if n == DVec3::ZERO { face } else { n };
        let tangents = idx.map(|v| object.tangent(v as usize));
        let tangent = w[0] * tangents[0] + w[1] * tangents[1] + w[2] * tangents[2];
        let uv = [0, 1].map(|set| interpolate_uv(w, object, set, idx));
        let sign = idx
            .iter()
            .zip(w)
            .map(|(&v, w)| w * object.bitangent_sign(v as usize))
            .sum::<f64>();
        let colors = idx.map(|v| object.color(v as usize));
        let color = w[0] * colors[0] + w[1] * colors[1] + w[2] * colors[2];
        let (material, frame) = self.material_at(
            object,
            uv,
            color,
            pixel.map(|p| (t, p)),
            SurfaceFrame::new(n, tangent),
            if sign < 0.0 { -1.0 } else { 1.0 },
        );
        super::transmission::Crossing {
            mesh: m,
            ray: *ray,
            t: hit.t,
            point,
            frame,
            face,
            material,
        }
    }
}

/// What the transmission paths see of the scene: the same hits, materials,
/// lights and visibility as the primary rays (back faces of a volume's
/// boundary kept, whatever its `doubleSided`: "The doubleSided property
/// has no effect on volume boundaries", `KHR_materials_volume`).
impl super::transmission::Scenery for Shader<'_> {
    fn cross(&self, ray: &Ray, t_min: f64) -> Option<super::transmission::Crossing<'_>> {
        let keeps_back = |id: crate::scene::bvh::TriangleId| {
            let m = &self.materials[self.scene.meshes[id.mesh as usize].material];
            m.sides != Sides::Front || m.layers.is_volume()
        };
        let mut t_from = t_min;
        loop {
            let hit = self
                .bvh
                .intersect_where(ray, t_from, f64::INFINITY, keeps_back)?;
            if self.blocks(&hit) {
                return Some(self.crossing(&hit, ray, None));
            }
            t_from = hit.t + self.epsilon;
        }
    }

    fn surface_radiance(&self, c: &super::transmission::Crossing) -> Rgb {
        let back = c.ray.direction.dot(c.face) > 0.0;
        let flip = back && c.material.sides == Sides::Both;
        let frame = flipped(&c.frame, if flip { -1.0 } else { 1.0 });
        self.shade_from(&c.material, c.point, &frame, c.face, c.ray.origin)
    }

    fn background(&self, direction: DVec3) -> Rgb {
        self.scene
            .environment
            .map
            .as_ref()
            .map_or(Rgb::ZERO, |map| map.radiance(direction))
    }

    fn epsilon(&self) -> f64 {
        self.epsilon
    }

    fn roughness_floor(&self) -> f64 {
        self.scene.roughness_floor()
    }

    fn lights(&self) -> &[Light] {
        &self.scene.lights
    }

    fn light_visible(&self, l: usize, x: DVec3, face: DVec3) -> f64 {
        let light = &self.scene.lights[l];
        if self.area == AreaLights::ExactUnoccluded && matches!(light, Light::AreaSample { .. }) {
            return 0.0;
        }
        visibility_where(self.bvh, light, x, face, self.epsilon, |hit| {
            self.blocks_light(l, hit)
        })
    }
}

/// The refracted path of `ray` through the volumes of `scene`
/// ([`super::transmission::path::refracted_path`]) at wavelength `lambda`
/// (`None`: each medium's `n_d`).
pub fn refracted_path(scene: &Scene, ray: Ray, lambda: Option<f64>) -> Vec<Ray> {
    let bvh = Bvh::new(&scene.meshes);
    let shader = Shader::new(scene, &bvh, AreaLights::Samples);
    super::transmission::path::refracted_path(&shader, ray, lambda)
}

/// The shadow-ray offset of `scene`: 10⁻⁷ of its bounding-box diagonal
/// (at least 10⁻¹²). Far below anything a shadow map resolves, far above
/// the f64 rounding of a hit point (~10⁻¹⁶ of the coordinates).
pub fn shadow_epsilon(scene: &Scene) -> f64 {
    let diagonal = scene.bounds().map_or(1.0, |(lo, hi)| (hi - lo).length());
    (1e-7 * diagonal).max(1e-12)
}

/// `V_l` at `x`, ray traced: 1 if nothing lies between `x` and the light,
/// else 0 (and 1 for a light without shadows). The ray leaves from
/// `x + ε · n`, with `n` the offset normal (`n_offset`, turned towards the
/// light) and ε = [`shadow_epsilon`], so it cannot hit the surface it
/// starts on; it ends ε before a point, spot or area-sample light, and goes
/// to infinity for a directional light. The offset normal is the
/// geometric (face) normal for Phong and flat shading and the vertex
/// normal for Gouraud (a vertex has no single face). Every surface
/// occludes (see [`visibility_where`] for alpha MASK).
pub fn visibility(bvh: &Bvh, light: &Light, x: DVec3, n_offset: DVec3, epsilon: f64) -> f64 {
    visibility_where(bvh, light, x, n_offset, epsilon, |_| true)
}

/// [`visibility`] where only the hits `blocks(hit)` keeps occlude: the
/// renderer passes through what alpha MASK cuts out
/// (`Shader::blocks`), as the GPU's shadow pass discards it.
pub fn visibility_where(
    bvh: &Bvh,
    light: &Light,
    x: DVec3,
    n_offset: DVec3,
    epsilon: f64,
    blocks: impl Fn(&Hit) -> bool,
) -> f64 {
    if !light.casts_shadows() {
        return 1.0;
    }
    let to_light = match (light.position(), light) {
        (Some(p), _) => p - x,
        (None, Light::Directional { direction, .. }) => -*direction,
        (None, _) => return 1.0,
    };
    let side = if n_offset.dot(to_light) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let origin = x + n_offset * (side * epsilon);
    let (direction, t_max) = match light.position() {
        Some(p) => {
            let d = p - origin;
            let len = d.length();
            if len <= epsilon {
                return 1.0;
            }
            (d / len, len - epsilon)
        }
        None => (to_light.normalize(), f64::INFINITY),
    };
    let ray = Ray { origin, direction };
    if bvh.occluded_where(&ray, t_max, blocks) {
        0.0
    } else {
        1.0
    }
}

/// Whether the environment is seen from `x` towards `wi` (the
/// environment's ray-traced visibility, `environment.visibility`): a ray
/// from `x + ε·n` (the offset normal turned towards `wi`, as [`visibility`]
/// leaves) to infinity hits nothing that `blocks` keeps (what alpha
/// MASK cuts out lets the map through, as it lets a light through).
pub fn environment_visible(
    bvh: &Bvh,
    x: DVec3,
    n_offset: DVec3,
    wi: DVec3,
    epsilon: f64,
    blocks: impl Fn(&Hit) -> bool,
) -> bool {
    let side = if n_offset.dot(wi) < 0.0 { -1.0 } else { 1.0 };
    let ray = Ray {
        origin: x + n_offset * (side * epsilon),
        direction: wi,
    };
    !bvh.occluded_where(&ray, f64::INFINITY, blocks)
}

/// `frame` turned over (`flip` −1: normal, tangent and bitangent
/// negated) or kept (`flip` 1).
fn flipped(frame: &SurfaceFrame, flip: f64) -> SurfaceFrame {
    SurfaceFrame::new(flip * frame.n, flip * frame.t)
}

/// The face normal of triangle `t` of `m` (flat shading's offset normal).
fn m_face(m: &Mesh, t: usize) -> DVec3 {
    mesh::face_normal(m.triangle(t))
}

/// The triangle index of a hit.
fn t_index(hit: &Hit) -> usize {
    hit.id.triangle as usize
}

/// The barycentric weights of where `ray` meets the plane of `corners`
/// (outside the triangle too), `None` if it runs parallel to it.
fn plane_weights(ray: &Ray, [a, b, c]: [DVec3; 3]) -> Option<[f64; 3]> {
    let (e1, e2) = (b - a, c - a);
    let p = ray.direction.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let s = ray.origin - a;
    let u = s.dot(p) / det;
    let v = ray.direction.dot(s.cross(e1)) / det;
    Some([1.0 - u - v, u, v])
}

/// The UV of set `set` interpolated with weights `w` over corners `idx`.
fn interpolate_uv(w: [f64; 3], m: &Mesh, set: usize, idx: [u32; 3]) -> DVec2 {
    w[0] * m.tex_coord(set, idx[0] as usize)
        + w[1] * m.tex_coord(set, idx[1] as usize)
        + w[2] * m.tex_coord(set, idx[2] as usize)
}

/// `Σ w_k · values[idx_k]`: barycentric interpolation over one triangle.
fn interpolate(w: [f64; 3], values: &[DVec3], idx: [u32; 3]) -> DVec3 {
    w[0] * values[idx[0] as usize] + w[1] * values[idx[1] as usize] + w[2] * values[idx[2] as usize]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, ReflectanceModel};
    use crate::scene::{Camera, Light};
    use std::f64::consts::PI;

    const K_D: f64 = 0.8;

    /// The square [-1, 1]² in the plane z = `z`, facing +Z (counter-clockwise
    /// seen from the camera), split along the diagonal from (-1,-1) to (1,1).
    fn quad(z: f64) -> Mesh {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        Mesh::with_generated_normals(
            "quad",
            corners.iter().map(|&(x, y)| DVec3::new(x, y, z)).collect(),
            vec![[0, 1, 2], [0, 2, 3]],
            0,
        )
    }

    /// A 63×63 image (odd, so the middle pixel's ray is the viewing axis)
    /// from (0, 0, 3) towards the origin, the quad at z = 0.
    fn scene(shading: ShadingMode, lights: Vec<Light>) -> Scene {
        let mut material = Material::new("m", ReflectanceModel::Lambert);
        material.k_d = Rgb::splat(K_D);
        Scene {
            width: 63,
            height: 63,
            msaa: 1,
            tone_map: Default::default(),
            camera: Camera {
                position: DVec3::new(0.0, 0.0, 3.0),
                target: DVec3::ZERO,
                up: DVec3::Y,
                fov_y_deg: 45.0,
                near: 0.1,
                far: 10.0,
            },
            shading,
            meshes: vec![quad(0.0)],
            materials: vec![material],
            light_shadows: vec![Default::default(); lights.len()],
            lights,
            area_lights: Vec::new(),
            ambient: Rgb::ZERO,
            environment: crate::scene::Environment::uniform(Rgb::ZERO),
            measured_table: crate::material::measured::DEFAULT_TABLE_RESOLUTION,
            measured_network: false,
            smith_beckmann: Default::default(),
            shadow_coords: Default::default(),
            transmission: Default::default(),
            images: Vec::new(),
        }
    }

    fn directional() -> (Light, Rgb, f64) {
        let direction = DVec3::new(-1.0, -2.0, -3.0).normalize();
        let irradiance = Rgb::new(1.0, 2.0, 3.0);
        let light = Light::Directional {
            direction,
            irradiance,
            shadows: false,
        };
        (light, irradiance, -direction.z)
    }

    fn pixel(frame: &Frame, i: u32, j: u32) -> (bool, Rgb) {
        let k = frame.index(i, j);
        (frame.coverage[k], frame.radiance[k].map(f64::from).into())
    }

    fn assert_close(got: Rgb, want: Rgb) {
        let err = (got - want).abs().max_element();
        assert!(err <= 1e-6 * want.abs().max_element(), "{got} vs {want}");
    }

    #[test]
    fn lambert_quad_under_a_directional_light_in_every_mode() {
        let (light, e, cos) = directional();
        for mode in ShadingMode::ALL {
            let frame = render(&scene(mode, vec![light.clone()]));
            let want = K_D / PI * e * cos;
            for (i, j) in [(31, 31), (20, 40), (45, 25)] {
                let (covered, radiance) = pixel(&frame, i, j);
                assert!(covered, "{mode}: ({i}, {j}) uncovered");
                assert_close(radiance, want);
            }
            // The corners look past the quad (it spans ±1, the view ±1.24).
            for (i, j) in [(0, 0), (0, 62), (62, 0), (62, 62)] {
                assert_eq!(pixel(&frame, i, j), (false, Rgb::ZERO), "{mode}");
            }
        }
    }

    #[test]
    fn modes_differ_as_the_lecture_says_under_a_close_point_light() {
        // A point light at height h above the centre. The middle pixel sees
        // the centre, on the shared diagonal (half a, half c).
        let (h, intensity) = (0.5, 2.0);
        let light = Light::Point {
            position: DVec3::new(0.0, 0.0, h),
            intensity: Rgb::splat(intensity),
            range: None,
            shadows: false,
        };
        // Irradiance times cosθ at in-plane distance r from the centre.
        let lit = |r2: f64| {
            let d2 = r2 + h * h;
            K_D / PI * intensity / d2 * (h / d2.sqrt())
        };
        let cases = [
            // Phong: shaded exactly at the centre.
            (ShadingMode::Phong, lit(0.0)),
            // Gouraud: every corner (r² = 2) has the same colour.
            (ShadingMode::Gouraud, lit(2.0)),
            // Flat: both centroids are at (±1/3, ∓1/3), r² = 2/9.
            (ShadingMode::Flat, lit(2.0 / 9.0)),
        ];
        for (mode, want) in cases {
            let frame = render(&scene(mode, vec![light.clone()]));
            let (covered, radiance) = pixel(&frame, 31, 31);
            assert!(covered, "{mode}");
            assert_close(radiance, Rgb::splat(want));
        }
    }

    #[test]
    fn geometry_outside_near_and_far_is_clipped() {
        let (light, ..) = directional();
        let mut s = scene(ShadingMode::Phong, vec![light]);
        s.camera.far = 2.5;
        assert!(render(&s).coverage.iter().all(|&c| !c), "beyond far");
        s.camera.far = 10.0;
        s.camera.near = 3.5;
        assert!(render(&s).coverage.iter().all(|&c| !c), "before near");
        // A second quad behind: with the front one clipped by near, the back
        // one is what the pixel sees.
        s.meshes.push(quad(-1.0));
        let frame = render(&s);
        assert!(pixel(&frame, 31, 31).0);
        s.camera.near = 0.1;
        s.meshes.pop();
        assert!(pixel(&render(&s), 31, 31).0);
    }

    #[test]
    fn offsets_move_the_samples() {
        let (light, ..) = directional();
        let mut s = scene(ShadingMode::Phong, vec![light]);
        s.width = 40;
        s.height = 30;
        let frame = render(&s);
        let shifted = render_offset(&s, 1.0, 2.0);
        for i in 0..28 {
            for j in 0..39 {
                assert_eq!(
                    pixel(&shifted, i, j),
                    pixel(&frame, i + 2, j + 1),
                    "({i}, {j})"
                );
            }
        }
        assert!(frame.coverage.iter().any(|&c| c) && frame.coverage.iter().any(|&c| !c));
    }

    #[test]
    fn empty_image_and_empty_scene() {
        let (light, ..) = directional();
        let mut s = scene(ShadingMode::Phong, vec![light]);
        s.meshes.clear();
        assert!(render(&s).coverage.iter().all(|&c| !c));
        s.width = 0;
        assert!(render(&s).is_empty());
    }
}
