//! Shadow maps: which lights get which maps, their projections, and the
//! layers the depth-only passes fill.
//!
//! * A **directional** light gets one orthographic map fitted to the scene
//!   bounds (seen along the light; square texels).
//! * A **spot** light gets one perspective map whose square frustum holds
//!   the outer cone (up to [`MAX_PERSPECTIVE_CONE_DEG`]; a wider cone is
//!   shadowed like a point light).
//! * A **point** light gets a cube: six perspective layers a little wider
//!   than 90°, so that an offset lookup and its PCF taps near a face's edge
//!   still read texels of that face.
//! * An **area** light's samples share one cube at the light's centre:
//!   every sample sees the visibility of the centre (a hard shadow; the
//!   reference traces one ray per sample; error measured in
//!   `docs/shadows.md`), unless it sets `shadow_per_sample`: then each
//!   sample has its own cube (6N layers), which matches the reference up
//!   to the maps' resolution.
//!
//! Every layer stores *reversed* depth (1 nearest the light, 0 for an empty
//! texel), written by the rasterizer with no fragment shader: orthographic
//! layers linearly over the scene's extent along the light, perspective
//! layers `near / z` of an infinite reversed projection, whose `f32`
//! precision is relative and so the same at every distance (a conventional
//! projection with `near = 10⁻⁵ far` would resolve only about 1 % of the
//! distance far from the light). Offsets and biases move the lookup point
//! in world space before it is projected, so they are lengths for every
//! projection.
//!
//! All maps are layers of one `Depth32Float` 2D array whose side is the
//! largest `map_size` of the scene; a light with a smaller map uses the
//! top-left `map_size²` corner of its layers. Every frustum leaves a margin
//! of `kernel/2 + normal_offset + 2` texels (at most a quarter of the map)
//! so that no offset lookup or filter tap leaves the light's region.
//! Lookups (`shaders/shadows.wgsl`) compare with a nearest-texel
//! comparison sampler (`GreaterEqual`: 1 where lit).

use super::layout::{GpuLight, GpuShadowView};
use super::shadow_fit::ScreenSamples;
use crate::scene::{Light, MapResolution, Scene, ShadowFilter, ShadowSettings};
use glam::{DMat4, DVec3, DVec4};
use std::collections::{BTreeSet, HashMap};

/// Depth format of the maps (hardware depth comparison).
pub const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Widest spot cone (outer half-angle, degrees) drawn with one perspective
/// map; wider cones get a cube.
pub const MAX_PERSPECTIVE_CONE_DEG: f64 = 60.0;
/// Most shadow maps (lights with shadows; an area light's samples share
/// one unless `shadow_per_sample`) a scene may have: the shader keeps one
/// visibility per map (`MAX_SHADOW_MAPS` in `shaders/shadows.wgsl`).
pub const MAX_SHADOW_MAPS: usize = 64;
/// Largest total size of the shadow-map array.
pub const MAX_SHADOW_BYTES: u64 = 1 << 30;
/// Near plane of perspective layers, relative to the distance from the
/// light to the farthest corner of the scene bounds: geometry closer to
/// the light than this casts no shadow.
pub const NEAR_OVER_FAR: f64 = 1e-5;

/// How a light's map projects the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Projection {
    /// Directional: one orthographic layer.
    Ortho,
    /// Spot: one perspective layer.
    Perspective,
    /// Point and area: six perspective layers.
    Cube,
}

impl Projection {
    /// `Light.shadow_projection` in WGSL.
    pub fn id(self) -> u32 {
        match self {
            Projection::Ortho => 0,
            Projection::Perspective => 1,
            Projection::Cube => 2,
        }
    }

    /// Layers of the array this projection uses.
    pub fn layers(self) -> u32 {
        match self {
            Projection::Cube => 6,
            _ => 1,
        }
    }

    /// A name for logs.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Ortho => "orthographic",
            Projection::Perspective => "perspective",
            Projection::Cube => "cube",
        }
    }
}

/// The projection of `light`'s shadow map.
pub fn projection_of(light: &Light) -> Projection {
    match *light {
        Light::Directional { .. } => Projection::Ortho,
        Light::Spot { outer_cone_deg, .. } if outer_cone_deg <= MAX_PERSPECTIVE_CONE_DEG => {
            Projection::Perspective
        }
        Light::Spot { .. } | Light::Point { .. } | Light::AreaSample { .. } => Projection::Cube,
    }
}

/// What the shadow code of a shader must contain (part of
/// [`super::shader_gen::ShaderKey`]). Empty: no shadow code at all.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShadowFeatures {
    pub projections: BTreeSet<Projection>,
    /// Some light filters with PCF (the kernel loop is compiled).
    pub pcf: bool,
}

impl ShadowFeatures {
    /// The features `scene`'s shadow-casting lights need.
    pub fn for_scene(scene: &Scene) -> Self {
        let mut features = ShadowFeatures::default();
        for (l, light) in scene.lights.iter().enumerate() {
            if light.casts_shadows() {
                features.projections.insert(projection_of(light));
                features.pcf |= matches!(scene.shadow_settings(l).filter, ShadowFilter::Pcf { .. });
            }
        }
        features
    }

    /// The PCF radius `(k − 1) / 2` shared by every shadow-casting light
    /// that filters with PCF, if they all use the same kernel.
    pub fn uniform_pcf_radius(scene: &Scene) -> Option<u32> {
        let mut radii = (0..scene.lights.len())
            .filter(|&l| scene.lights[l].casts_shadows())
            .filter_map(|l| match scene.shadow_settings(l).filter {
                ShadowFilter::Pcf { kernel } => Some((kernel - 1) / 2),
                ShadowFilter::None => None,
            });
        let first = radii.next()?;
        radii.all(|r| r == first).then_some(first)
    }

    /// Whether any shadow code is compiled.
    pub fn any(&self) -> bool {
        !self.projections.is_empty()
    }

    /// For logs: `shadows [orthographic, cube; pcf]`.
    pub fn describe(&self) -> String {
        if !self.any() {
            return "no shadows".into();
        }
        let p: Vec<_> = self.projections.iter().map(|p| p.name()).collect();
        format!(
            "shadows [{}{}]",
            p.join(", "),
            if self.pcf { "; pcf" } else { "" }
        )
    }
}

/// One light's shadow map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightShadow {
    /// Index of the map (into [`ShadowPlan::casters`]).
    pub map: u32,
    pub projection: Projection,
    /// First layer in the array (cube faces follow: +X −X +Y −Y +Z −Z).
    pub first_layer: u32,
    pub settings: ShadowSettings,
    /// Orthographic: world size of a texel; perspective and cube: world
    /// size of a texel per metre of distance from `origin` (an upper
    /// bound over the map: the size at its centre).
    pub texel: f64,
    /// The light's position (perspective, cube; an area light's centre).
    pub origin: DVec3,
}

impl LightShadow {
    /// World size of one texel of this map at `x`.
    pub fn texel_at(&self, x: DVec3) -> f64 {
        match self.projection {
            Projection::Ortho => self.texel,
            _ => self.texel * (x - self.origin).length(),
        }
    }
}

/// One layer to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowLayer {
    /// World to clip space; clip z / w is the reversed depth.
    pub clip_from_world: DMat4,
    /// Side of the rendered square (the light's `map_size`).
    pub map_size: u32,
}

/// The shadow maps of a scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShadowPlan {
    /// Side of the array's layers (the largest map).
    pub side: u32,
    pub layers: Vec<ShadowLayer>,
    /// Per light of the scene: its map, if it casts shadows. The samples of
    /// one area light share one.
    pub lights: Vec<Option<LightShadow>>,
    /// Per map: the first light that uses it (the shader looks up each
    /// map's visibility once, through this light).
    pub casters: Vec<u32>,
}

impl ShadowPlan {
    /// Plans the maps of `scene`'s shadow-casting lights.
    pub fn new(scene: &Scene) -> Self {
        let mut plan = ShadowPlan {
            side: 0,
            layers: Vec::new(),
            lights: vec![None; scene.lights.len()],
            casters: Vec::new(),
        };
        // No shadows: no maps, and no pass over the vertices for the bounds.
        if !scene.lights.iter().any(|l| l.casts_shadows()) {
            return plan;
        }
        let Some((lo, hi)) = scene.bounds() else {
            return plan;
        };
        let mut areas: HashMap<usize, LightShadow> = HashMap::new();
        // The receivers on screen, traced once when some map is fitted.
        let mut screen: Option<ScreenSamples> = None;
        for (l, light) in scene.lights.iter().enumerate() {
            if !light.casts_shadows() {
                continue;
            }
            // The samples of an area light share the map at its centre
            // unless it asks for one per sample.
            let per_sample = |area: usize| {
                scene
                    .area_lights
                    .get(area)
                    .is_some_and(|a| a.shadow_per_sample)
            };
            if let Light::AreaSample { area, .. } = *light
                && !per_sample(area)
                && let Some(shared) = areas.get(&area)
            {
                plan.lights[l] = Some(*shared);
                continue;
            }
            let mut settings = scene.shadow_settings(l);
            let projection = projection_of(light);
            let first_layer = plan.layers.len() as u32;
            let origin = match *light {
                Light::AreaSample { center, area, .. } if !per_sample(area) => center,
                _ => light.position().unwrap_or_default(),
            };
            let mut layers = light_layers(light, projection, origin, &settings, (lo, hi));
            if let MapResolution::Fit { texels_per_pixel } = settings.resolution {
                let screen = screen.get_or_insert_with(|| ScreenSamples::new(scene));
                let cap = settings.map_size;
                let at_cap = |x: DVec3| match projection {
                    Projection::Ortho => layers.1,
                    _ => layers.1 * (x - origin).length(),
                };
                let side = screen.fitted_side(light, at_cap, cap, texels_per_pixel);
                if side != cap {
                    settings.map_size = side;
                    layers = light_layers(light, projection, origin, &settings, (lo, hi));
                }
            }
            let (light_layers, texel) = layers;
            plan.layers.extend(light_layers);
            let map_size = settings.map_size;
            let shadow = LightShadow {
                map: plan.casters.len() as u32,
                projection,
                first_layer,
                settings,
                texel,
                origin,
            };
            plan.casters.push(l as u32);
            plan.side = plan.side.max(map_size);
            if let Light::AreaSample { area, .. } = *light {
                areas.insert(area, shadow);
            }
            plan.lights[l] = Some(shadow);
        }
        plan
    }

    /// Whether there is any map to render.
    pub fn is_empty(&self) -> bool {
        self.layers.is_empty()
    }

    /// Bytes of the map array.
    pub fn bytes(&self) -> u64 {
        self.side as u64 * self.side as u64 * 4 * self.layers.len() as u64
    }

    /// World size of one texel of light `l`'s map at `x` (`None` without
    /// shadows): the unit of `normal_offset` and `slope_bias`.
    pub fn texel_at(&self, l: usize, x: DVec3) -> Option<f64> {
        self.lights.get(l).copied().flatten().map(|s| s.texel_at(x))
    }

    /// Writes light `l`'s shadow fields into its GPU record.
    pub fn apply(&self, l: usize, g: &mut GpuLight) {
        let Some(s) = self.lights.get(l).copied().flatten() else {
            g.shadow_layer = -1;
            g.shadow_map = u32::MAX;
            return;
        };
        g.shadow_map = s.map;
        g.shadow_layer = s.first_layer as i32;
        g.shadow_projection = s.projection.id();
        g.shadow_origin = s.origin.as_vec3().to_array();
        g.shadow_texel = s.texel as f32;
        g.shadow_bias = s.settings.bias as f32;
        g.shadow_slope_bias = s.settings.slope_bias as f32;
        g.shadow_normal_offset = s.settings.normal_offset as f32;
        g.shadow_pcf_radius = match s.settings.filter {
            ShadowFilter::None => 0,
            ShadowFilter::Pcf { kernel } => kernel / 2,
        };
        g.shadow_uv_scale = (s.settings.map_size as f64 / self.side.max(1) as f64) as f32;
        // As the shader computed it from textureDimensions before (f32).
        g.shadow_array_texel = 1.0 / self.side.max(1) as f32;
        if s.projection == Projection::Cube {
            let first = s.first_layer as usize;
            (g.shadow_cube_scale, g.shadow_cube_offset) =
                cube_scale_and_offset(&self.layers[first..first + 6]);
        }
    }

    /// Per layer: whether its lookup reads "lit" from an all-zero view
    /// matrix, as it would from a cleared layer (perspective and cube
    /// layers test clip `w ≤ 0` first; an orthographic layer does not).
    /// The layers [`super::shadow_maps::ShadowMaps::encode`] may skip.
    pub fn layers_read_lit_when_zeroed(&self) -> Vec<bool> {
        let mut lit = vec![false; self.layers.len()];
        for s in self.lights.iter().flatten() {
            let first = s.first_layer as usize;
            for l in &mut lit[first..first + s.projection.layers() as usize] {
                *l = s.projection != Projection::Ortho;
            }
        }
        lit
    }

    /// The layers as the GPU reads them.
    pub fn gpu_views(&self) -> Vec<GpuShadowView> {
        self.layers
            .iter()
            .map(|l| GpuShadowView {
                clip_from_world: l.clip_from_world.as_mat4().to_cols_array_2d(),
            })
            .collect()
    }
}

/// The layers of `light`'s map at `settings.map_size` (its `projection`,
/// centred on `origin` unless orthographic, over the scene bounds
/// `(lo, hi)`), and the map's texel: the world size of one texel
/// (orthographic) or per metre of distance from `origin`.
fn light_layers(
    light: &Light,
    projection: Projection,
    origin: DVec3,
    settings: &ShadowSettings,
    (lo, hi): (DVec3, DVec3),
) -> (Vec<ShadowLayer>, f64) {
    let map_size = settings.map_size;
    let size = map_size as f64;
    // Texels kept free around the light's region for the offset lookup
    // point and the filter taps.
    let margin =
        (settings.filter.kernel() as f64 / 2.0 + settings.normal_offset + 2.0).min(size / 4.0);
    let widen = 1.0 / (1.0 - 2.0 * margin / size);
    match *light {
        Light::Directional { direction, .. } => {
            let (clip_from_world, texel) = ortho_layer(direction, lo, hi, size, widen);
            (
                vec![ShadowLayer {
                    clip_from_world,
                    map_size,
                }],
                texel,
            )
        }
        Light::Spot {
            position,
            direction,
            outer_cone_deg,
            ..
        } if projection == Projection::Perspective => {
            let tan_half = outer_cone_deg.to_radians().tan().max(1e-3) * widen;
            let near = NEAR_OVER_FAR * far_corner(position, lo, hi);
            (
                vec![perspective_layer(
                    position, direction, tan_half, near, map_size,
                )],
                2.0 * tan_half / size,
            )
        }
        _ => {
            let near = NEAR_OVER_FAR * far_corner(origin, lo, hi);
            let faces = CUBE_FACES
                .iter()
                .map(|&forward| perspective_layer(origin, forward, widen, near, map_size))
                .collect();
            (faces, 2.0 * widen / size)
        }
    }
}

/// Cube faces in layer order (+X −X +Y −Y +Z −Z), the order the lookup's
/// major-axis test picks them in.
pub const CUBE_FACES: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

/// A cube's `s` and `s · origin` as the f32 entries of its faces'
/// matrices hold them (`shadow_cube_clip` in shaders/shadows.wgsl
/// writes each face's clip coordinates from these): `s` is +X's right
/// row's z entry, `s·o.z` and `s·o.y` are minus its x and y offsets,
/// `s·o.x` is +Z's x offset. Rounding to f32 is symmetric, so the negated
/// entries are the rounded products exactly.
fn cube_scale_and_offset(faces: &[ShadowLayer]) -> (f32, [f32; 3]) {
    let (plus_x, plus_z) = (faces[0].clip_from_world, faces[4].clip_from_world);
    let scale = plus_x.z_axis.x as f32;
    let offset = [
        plus_z.w_axis.x as f32,
        -(plus_x.w_axis.y as f32),
        -(plus_x.w_axis.x as f32),
    ];
    (scale, offset)
}

/// Eight corners of a box.
fn corners(lo: DVec3, hi: DVec3) -> [DVec3; 8] {
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Distance from `origin` to the farthest corner of the bounds.
fn far_corner(origin: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    corners(lo, hi)
        .iter()
        .map(|c| (*c - origin).length())
        .fold(0.0, f64::max)
        .max(1e-6)
}

/// An orthonormal basis (right, up) across `forward`.
fn basis(forward: DVec3) -> (DVec3, DVec3) {
    let helper = if forward.y.abs() < 0.99 {
        DVec3::Y
    } else {
        DVec3::X
    };
    let right = forward.cross(helper).normalize();
    (right, right.cross(forward))
}

/// The orthographic layer of a directional light travelling along
/// `direction`: square, holding the bounds widened by `widen` (the
/// margin), reversed depth 1..0 over the bounds' extent along the light
/// (+1 % each way). Returns the matrix and the world size of a texel.
fn ortho_layer(direction: DVec3, lo: DVec3, hi: DVec3, size: f64, widen: f64) -> (DMat4, f64) {
    let d = direction.normalize();
    let (r, u) = basis(d);
    let c = 0.5 * (lo + hi);
    let (mut x0, mut x1, mut y0, mut y1, mut z0, mut z1) =
        (f64::MAX, f64::MIN, f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in corners(lo, hi) {
        let q = p - c;
        let (x, y, z) = (r.dot(q), u.dot(q), d.dot(q));
        (x0, x1) = (x0.min(x), x1.max(x));
        (y0, y1) = (y0.min(y), y1.max(y));
        (z0, z1) = (z0.min(z), z1.max(z));
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let half = (0.5 * (x1 - x0)).max(0.5 * (y1 - y0)).max(1e-6) * widen;
    let pad = 0.01 * (z1 - z0) + 1e-6;
    let (z0, z1) = (z0 - pad, z1 + pad);
    // Row `axis · (p − c) − offset`, scaled.
    let row = |axis: DVec3, offset: f64, scale: f64| {
        DVec4::from((axis * scale, -(axis.dot(c) + offset) * scale))
    };
    let rows = [
        row(r, cx, 1.0 / half),
        row(u, cy, 1.0 / half),
        // Reversed depth (z1 − d · (p − c)) / (z1 − z0).
        row(-d, -z1, 1.0 / (z1 - z0)),
        DVec4::W,
    ];
    let m = DMat4::from_cols(rows[0], rows[1], rows[2], rows[3]).transpose();
    (m, 2.0 * half / size)
}

/// A square perspective layer at `origin` looking along `forward` with
/// half-angle `atan(tan_half)`: infinite, reversed (depth = near / z).
fn perspective_layer(
    origin: DVec3,
    forward: DVec3,
    tan_half: f64,
    near: f64,
    map_size: u32,
) -> ShadowLayer {
    let forward = forward.normalize();
    let (_, up) = basis(forward);
    let view = glam::dcamera::rh::view::look_at_mat4(origin, origin + forward, up);
    let proj = glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
        2.0 * tan_half.atan(),
        1.0,
        near,
    );
    ShadowLayer {
        clip_from_world: proj * view,
        map_size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec4;

    fn depth(m: DMat4, p: DVec3) -> f64 {
        let c = m * DVec4::from((p, 1.0));
        c.z / c.w
    }

    /// What `shadow_cube_clip` (shaders/shadows.wgsl) assumes of a
    /// cube face's f32 matrix: per face (right, up, forward) axes and
    /// signs as listed there, entries ±s, s, ±1 and offsets ∓(s·o), −(s·o),
    /// near, ∓o, every other entry zero, with s and s·o the light's
    /// `shadow_cube_scale` and `shadow_cube_offset` and o its f32
    /// `shadow_origin`. Origins off the dyadic grid, far and near, small
    /// and large fields.
    #[test]
    fn cube_faces_are_their_sparse_form() {
        // (right axis, right sign, up axis), forward = (k / 2, ±).
        const ROWS: [(usize, f32, usize); 6] = [
            (2, 1.0, 1),
            (2, -1.0, 1),
            (2, -1.0, 0),
            (2, 1.0, 0),
            (0, -1.0, 1),
            (0, 1.0, 1),
        ];
        let origins = [
            DVec3::new(2.5, 2.5, 2.0),
            DVec3::new(-0.1, 0.3, 1.0 / 3.0),
            DVec3::new(1234.567, -0.000123, 98765.4321),
            DVec3::ZERO,
        ];
        for origin in origins {
            for (widen, near) in [
                (1.0, 1e-3),
                (1.0 / (1.0 - 2.0 * 2.7 / 1024.0), 0.0371),
                (1.37, 5.0),
            ] {
                let faces: Vec<ShadowLayer> = CUBE_FACES
                    .iter()
                    .map(|&f| perspective_layer(origin, f, widen, near, 1024))
                    .collect();
                let (scale, offset) = cube_scale_and_offset(&faces);
                let o = origin.as_vec3().to_array();
                for (k, face) in faces.iter().enumerate() {
                    let (right, sign, up) = ROWS[k];
                    let (forward, forward_sign) = (k / 2, if k % 2 == 0 { 1.0 } else { -1.0 });
                    let mut rows = [[0.0f32; 4]; 4];
                    rows[0][right] = sign * scale;
                    rows[0][3] = -sign * offset[right];
                    rows[1][up] = scale;
                    rows[1][3] = -offset[up];
                    rows[2][3] = near as f32;
                    rows[3][forward] = forward_sign;
                    rows[3][3] = -forward_sign * o[forward];
                    let m = face
                        .clip_from_world
                        .as_mat4()
                        .transpose()
                        .to_cols_array_2d();
                    assert_eq!(
                        m, rows,
                        "face {k} of a cube at {origin}, widen {widen}, near {near}"
                    );
                }
            }
        }
    }

    #[test]
    fn depth_is_reversed_and_inside_the_unit_range() {
        let (lo, hi) = (DVec3::new(-4.0, 0.0, -4.0), DVec3::new(4.0, 2.0, 4.0));
        let (m, texel) = ortho_layer(DVec3::new(0.3, -1.0, 0.2), lo, hi, 1024.0, 1.01);
        assert!(texel > 0.0);
        for c in corners(lo, hi) {
            let clip = m * DVec4::from((c, 1.0));
            assert!(clip.x.abs() < 1.0 && clip.y.abs() < 1.0);
            assert!(clip.z > 0.0 && clip.z < 1.0, "{clip}");
        }
        // Nearer the light (higher up) is larger.
        assert!(depth(m, DVec3::new(0.0, 2.0, 0.0)) > depth(m, DVec3::ZERO));
        let layer = perspective_layer(DVec3::new(0.0, 5.0, 0.0), DVec3::NEG_Y, 1.0, 1e-4, 256);
        let (near, far) = (DVec3::new(0.0, 4.0, 0.0), DVec3::new(0.3, 0.0, 0.2));
        assert!(depth(layer.clip_from_world, near) > depth(layer.clip_from_world, far));
        assert!((depth(layer.clip_from_world, near) - 1e-4).abs() < 1e-12);
    }

    #[test]
    fn area_samples_share_one_cube() {
        let mut scene = crate::scene::scene_file::load(
            &crate::scene::scene_file::SceneSource::BuiltIn,
            &["lights=[{kind = \"area\", shape = \"disk\", position = [0.0, 3.0, 0.0], normal = [0.0, -1.0, 0.0], radius = 0.5, radiance = 1.0, samples = 4, shadows = true}, {kind = \"directional\", direction = [0.0, -1.0, 0.0], irradiance = 1.0, shadows = true, shadow_map_size = 512}]".into()],
        )
        .unwrap();
        let plan = ShadowPlan::new(&scene);
        assert_eq!(plan.layers.len(), 7);
        assert_eq!(plan.side, ShadowSettings::DEFAULT_MAP_SIZE);
        let first: Vec<_> = plan.lights.iter().map(|s| s.unwrap().first_layer).collect();
        assert_eq!(first, [0, 0, 0, 0, 6]);
        let maps: Vec<_> = plan.lights.iter().map(|s| s.unwrap().map).collect();
        assert_eq!(maps, [0, 0, 0, 0, 1]);
        assert_eq!(plan.casters, [0, 4]);
        assert_eq!(plan.lights[4].unwrap().projection, Projection::Ortho);
        // The cube's faces may be skipped when empty, the sun's map not.
        let mut skippable = vec![true; 6];
        skippable.push(false);
        assert_eq!(plan.layers_read_lit_when_zeroed(), skippable);
        scene.lights.iter_mut().for_each(|l| l.set_shadows(false));
        assert!(ShadowPlan::new(&scene).is_empty());
        assert!(!ShadowFeatures::for_scene(&scene).any());
    }
}
