//! Caster culling for the shadow passes: each layer (a cube face, a spot's
//! or a sun's map) draws only the meshes whose bounding box can reach its
//! frustum, and a flat mesh (a floor) only over the texels other meshes'
//! lookups can read.
//!
//! A point light's cube renders the scene six times; a caster seen by one
//! face is clipped away entirely by the other five, at the cost of its
//! vertex work and the clipper. A box lies wholly outside a layer when all
//! eight corners are outside one of the half-spaces that bound wgpu's clip
//! volume (`−w ≤ x ≤ w`, `−w ≤ y ≤ w`, `0 ≤ z ≤ w`, depth clipping on:
//! `pipelines::shadow_depth_state`); the box holds every triangle of its
//! mesh (convex hull), so every one of them would be clipped, and the
//! layer's texels are exactly those of the unculled pass. The test is
//! conservative (a box outside the frustum but across no single plane is
//! drawn) and leaves a relative slack far above f32 rounding, so that a
//! vertex the f64 test finds just outside but the GPU's f32 transform puts
//! just inside is still drawn.
//!
//! A flat caster never shadows itself: with the normal offset at least
//! `k/√2` texels (docs/shadows.md, "Why these defaults") a lookup from
//! the plane never finds the plane's own depth nearer than itself. Its
//! depth in a layer matters only where another object's lookup may read:
//! [`LayerCaster::region`], the texels the other objects' boxes cover
//! once grown by the farthest their lookup point moves (normal offset and
//! biases) and the PCF kernel. Outside it the flat caster is not drawn
//! (a scissor); a lookup from it that lands there finds the texel nearer
//! the light than before by nothing but its own depth, which never
//! shadowed it, so every comparison gives what the whole caster gives;
//! a layer where no other object can look does not draw it at all. Under
//! a moving light this takes a floor out of most faces of a cube
//! (docs/shadows.md, "A floor drawn only under what stands on it").

use super::geometry::ObjectRange;
use super::shadows::{LightShadow, Projection, ShadowLayer, ShadowPlan};
use crate::scene::ShadowFilter;
use crate::scene::mesh::Flat;
use glam::{DMat4, DVec3, DVec4};

/// Relative slack of the plane test: a corner counts as outside only
/// when its signed distance is below `−SLACK ×` the sum of the magnitudes
/// of the terms that make it. f32 transforms round each term to about
/// 6·10⁻⁸ of its size (four terms, a few ulps), 100× below this.
const SLACK: f64 = 1e-5;

/// Texels added on every side of a region beyond the PCF kernel: the
/// nearest texel of a coordinate at a texel edge (1), and the GPU's f32
/// transform of a box corner, a few ulps of the coordinate off the f64
/// one here (1, far more than a few ulps of at most 8192 texels).
const REGION_MARGIN: f64 = 2.0;

/// The normal offset, in texels, a flat caster's lights must exceed the
/// kernel's `k/√2` by before its region applies: docs/shadows.md derives
/// no acne at `k/√2` exactly, the default adds ½; this keeps the f32
/// comparisons (relative 10⁻⁷, against the 10⁻³ of a quarter texel at
/// 1024 texels) and small bumps of the plane (below) far from the edge.
const FLAT_MARGIN_TEXELS: f64 = 0.25;

/// How near edge-on a light may see a flat caster for its region to
/// apply: docs/shadows.md's rule holds for every angle below 90°, its
/// test checks up to 85°; nearer 90° a plane's triangles thin to slivers
/// in the map, whose f32 rasterization this does not reason about.
const MAX_GRAZING_DEG: f64 = 89.0;

/// A caster's world box and flatness, taken when the stream was planned
/// (a GPU-only run frees the meshes as they upload).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CasterBox {
    pub lo: DVec3,
    pub hi: DVec3,
    /// [`ObjectRange::flatness`]: the plane a flat mesh lies in.
    pub flatness: Option<Flat>,
}

/// The box and flatness of each object of the stream.
pub fn object_boxes(objects: &[ObjectRange]) -> Vec<CasterBox> {
    objects
        .iter()
        .map(|o| CasterBox {
            lo: o.bounds.0,
            hi: o.bounds.1,
            flatness: o.flatness,
        })
        .collect()
}

/// A rectangle of a layer's texels, as a scissor takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexelRect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl TexelRect {
    /// The smallest rectangle holding both.
    fn union(self, other: TexelRect) -> TexelRect {
        let (x, y) = (self.x.min(other.x), self.y.min(other.y));
        let x1 = (self.x + self.width).max(other.x + other.width);
        let y1 = (self.y + self.height).max(other.y + other.height);
        TexelRect {
            x,
            y,
            width: x1 - x,
            height: y1 - y,
        }
    }
}

/// One object a layer draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LayerCaster {
    /// Index into the stream's objects.
    pub object: u32,
    /// The texels it must cover (a flat caster: what other objects'
    /// lookups may read); `None`: all of them.
    pub region: Option<TexelRect>,
}

/// Which objects each layer draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LayerCasters {
    /// Per layer of the plan, the objects (ascending) whose boxes may
    /// reach it.
    pub layers: Vec<Vec<LayerCaster>>,
    /// Object draws the culling removed, over all layers (a flat caster
    /// no other object's lookup reads included).
    pub culled: usize,
    /// Draws of flat casters limited to a region, over all layers.
    pub clipped: usize,
}

impl LayerCasters {
    /// The objects with `boxes` each layer of `plan` must draw, and where.
    /// `spot_coords_per_vertex`: the scene pass interpolates a spot map's
    /// coordinates from the corners (`shading.shadow_coords = "vertex"`),
    /// whose offsets are not exact: flat casters are then drawn whole
    /// into spot maps.
    pub fn new(plan: &ShadowPlan, boxes: &[CasterBox], spot_coords_per_vertex: bool) -> Self {
        let lookups = layer_lookups(plan);
        let mut culled = 0;
        let mut clipped = 0;
        let layers = plan
            .layers
            .iter()
            .zip(&lookups)
            .map(|(layer, lookup)| {
                let mut kept: Vec<LayerCaster> = (0..boxes.len() as u32)
                    .filter(|&o| {
                        let b = &boxes[o as usize];
                        !outside(layer.clip_from_world, b.lo, b.hi)
                    })
                    .map(|object| LayerCaster {
                        object,
                        region: None,
                    })
                    .collect();
                if let Some(light) = lookup {
                    let exact =
                        !(spot_coords_per_vertex && light.projection == Projection::Perspective);
                    if exact {
                        clipped += clip_flat_casters(layer, light, boxes, &mut kept);
                    }
                }
                culled += boxes.len() - kept.len();
                kept
            })
            .collect();
        LayerCasters {
            layers,
            culled,
            clipped,
        }
    }
}

/// Limits the flat casters among `kept` (the objects `layer` draws) to
/// the texels other objects' lookups through `light` may read, and drops
/// those no other object's lookup reads; returns how many were limited.
fn clip_flat_casters(
    layer: &ShadowLayer,
    light: &LightShadow,
    boxes: &[CasterBox],
    kept: &mut Vec<LayerCaster>,
) -> usize {
    let flat =
        |c: &LayerCaster| flat_and_safe(light, layer.clip_from_world, &boxes[c.object as usize]);
    if !kept.iter().any(flat) {
        return 0;
    }
    let others = regions_of_others(&read_regions(
        layer.clip_from_world,
        layer.map_size,
        light,
        boxes,
    ));
    let whole = |r: &TexelRect| r.width == layer.map_size && r.height == layer.map_size;
    let mut clipped = 0;
    kept.retain_mut(|c| {
        if !flat(c) {
            return true;
        }
        match others[c.object as usize] {
            None => false,
            Some(r) if whole(&r) => true,
            Some(r) => {
                c.region = Some(r);
                clipped += 1;
                true
            }
        }
    });
    clipped
}

/// Per layer of `plan`, the light whose lookup reads it (the shader reads
/// a map through its first light, `ShadowPlan::casters`).
fn layer_lookups(plan: &ShadowPlan) -> Vec<Option<LightShadow>> {
    let mut lookups = vec![None; plan.layers.len()];
    for &light in &plan.casters {
        if let Some(Some(shadow)) = plan.lights.get(light as usize) {
            let count = if shadow.projection == Projection::Cube {
                6
            } else {
                1
            };
            let first = shadow.first_layer as usize;
            for slot in lookups.iter_mut().skip(first).take(count) {
                *slot = Some(*shadow);
            }
        }
    }
    lookups
}

/// Whether `caster` is flat enough, and `light`'s lookup offset large
/// enough, that no lookup from the caster finds its own depth in the way
/// (module docs): the normal offset exceeds `k/√2` by
/// [`FLAT_MARGIN_TEXELS`], the plane's bumps stay below a tenth of that
/// margin's world size at the caster's nearest point to the light, and
/// the light sees the plane at most [`MAX_GRAZING_DEG`] from edge-on
/// (`clip_from_world`: the layer's view, whose depth row gives a sun's
/// direction).
fn flat_and_safe(light: &LightShadow, clip_from_world: DMat4, caster: &CasterBox) -> bool {
    let Some(flat) = caster.flatness else {
        return false;
    };
    let settings = &light.settings;
    let kernel = match settings.filter {
        ShadowFilter::None => 1.0,
        ShadowFilter::Pcf { kernel } => f64::from(kernel),
    };
    let margin = settings.normal_offset * (1.0 - 1e-6) - kernel / std::f64::consts::SQRT_2;
    // The cosine of the angle between the plane's normal and the light
    // ray, least over the caster: at its farthest corner from a point
    // light; the same everywhere for a sun.
    let (texel, least_cosine) = match light.projection {
        Projection::Ortho => {
            let along = clip_from_world.row(2).truncate().normalize_or_zero();
            (light.texel, flat.normal.dot(along).abs())
        }
        _ => {
            let height = (flat.normal.dot(light.origin) - flat.offset).abs();
            let far = corners(caster.lo, caster.hi)
                .iter()
                .map(|c| (c.truncate() - light.origin).length())
                .fold(0.0, f64::max);
            let near = distance_to_box(light.origin, caster.lo, caster.hi);
            (light.texel * near, height / far.max(f64::MIN_POSITIVE))
        }
    };
    margin >= FLAT_MARGIN_TEXELS
        && texel > 0.0
        && flat.bumps <= 0.1 * margin * texel
        && least_cosine >= MAX_GRAZING_DEG.to_radians().cos()
}

/// Distance from `p` to the box `[lo, hi]` (0 inside).
fn distance_to_box(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    (lo - p).max(p - hi).max(DVec3::ZERO).length()
}

/// Per object, the texels of the layer its lookups may read (`None`:
/// none): its box grown by the farthest a lookup point moves from its
/// receiver (`shaders/shadows.wgsl` `shadow_point`: the normal offset,
/// `normal_offset · texel`, and the biases along the light ray, `bias +
/// slope_bias · texel · tanθ` with tanθ at most 1000), projected, and
/// grown by the PCF kernel's reach and [`REGION_MARGIN`]. A cube face is
/// read only by lookup points in its frustum (the face is the major axis
/// of the point's direction, and faces overlap), so a box outside it adds
/// nothing; a spot's or sun's map clamps lookups beyond its edge to the
/// edge texels, which the clamped rectangle then holds.
fn read_regions(
    clip_from_world: DMat4,
    size: u32,
    light: &LightShadow,
    boxes: &[CasterBox],
) -> Vec<Option<TexelRect>> {
    let settings = &light.settings;
    let radius = match settings.filter {
        ShadowFilter::None => 0.0,
        ShadowFilter::Pcf { kernel } => f64::from(kernel / 2),
    };
    boxes
        .iter()
        .map(|b| {
            let texel = match light.projection {
                Projection::Ortho => light.texel,
                _ => {
                    let far = corners(b.lo, b.hi)
                        .iter()
                        .map(|c| (c.truncate() - light.origin).length())
                        .fold(0.0, f64::max);
                    light.texel * far
                }
            };
            let reach = settings.normal_offset * texel
                + settings.bias
                + settings.slope_bias * texel * 1000.0;
            // And the f32 rounding of the receiver and its offsets.
            let rounding = b.lo.abs().max(b.hi.abs()).max_element() * 1e-6;
            let grow = DVec3::splat(reach * (1.0 + 1e-6) + rounding);
            let (lo, hi) = (b.lo - grow, b.hi + grow);
            if light.projection == Projection::Cube && outside(clip_from_world, lo, hi) {
                return None;
            }
            texel_rect(clip_from_world, lo, hi, size, radius + REGION_MARGIN)
        })
        .collect()
}

/// Per object, the union of every other object's region: prefix and
/// suffix unions, linear in the number of objects.
fn regions_of_others(regions: &[Option<TexelRect>]) -> Vec<Option<TexelRect>> {
    let join = |a: Option<TexelRect>, b: Option<TexelRect>| match (a, b) {
        (Some(a), Some(b)) => Some(a.union(b)),
        (a, b) => a.or(b),
    };
    let mut before = Vec::with_capacity(regions.len());
    let mut acc = None;
    for r in regions {
        before.push(acc);
        acc = join(acc, *r);
    }
    let mut others = vec![None; regions.len()];
    let mut after = None;
    for o in (0..regions.len()).rev() {
        others[o] = join(before[o], after);
        after = join(after, regions[o]);
    }
    others
}

/// The texels of a `size`² layer that the part of the box `[lo, hi]` in
/// front of it (clip `w > 0`) projects to, grown by `grow` texels and
/// clamped to the layer (a projection beyond an edge keeps the edge's
/// texels); `None` if no part is in front. The projection of the box's
/// front part is the hull of its front corners and of the points where
/// its edges cross `w = 0`, which project to infinity in the direction of
/// their clip `(x, y)`.
fn texel_rect(
    clip_from_world: DMat4,
    lo: DVec3,
    hi: DVec3,
    size: u32,
    grow: f64,
) -> Option<TexelRect> {
    let clip = corners(lo, hi).map(|c| clip_from_world * c);
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    let mut widen = |x: f64, y: f64| {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    };
    for (i, a) in clip.iter().enumerate() {
        if a.w > 0.0 {
            widen(a.x / a.w, a.y / a.w);
        }
        // The box's edges: corners that differ in one bit.
        for bit in [1, 2, 4] {
            let b = clip[i ^ bit];
            if i & bit == 0 && (a.w > 0.0) != (b.w > 0.0) {
                let t = a.w / (a.w - b.w);
                let at = *a + (b - *a) * t;
                let towards = |v: f64| match v {
                    v if v > 0.0 => [f64::INFINITY, f64::INFINITY],
                    v if v < 0.0 => [f64::NEG_INFINITY, f64::NEG_INFINITY],
                    _ => [f64::NEG_INFINITY, f64::INFINITY],
                };
                for x in towards(at.x) {
                    for y in towards(at.y) {
                        widen(x, y);
                    }
                }
            }
        }
    }
    if x0 > x1 {
        return None;
    }
    // NDC to texels: x right, y down (wgpu's framebuffer).
    let side = f64::from(size);
    let to_texel = |ndc: f64, flip: f64| (flip * ndc * 0.5 + 0.5) * side;
    let span = |a: f64, b: f64| {
        let first = (a.floor() - grow).clamp(0.0, side - 1.0);
        let end = (b.floor() + 1.0 + grow).clamp(first + 1.0, side);
        (first as u32, (end - first) as u32)
    };
    let (x, width) = span(to_texel(x0, 1.0), to_texel(x1, 1.0));
    let (y, height) = span(to_texel(y1, -1.0), to_texel(y0, -1.0));
    Some(TexelRect {
        x,
        y,
        width,
        height,
    })
}

/// The eight corners of the box `[lo, hi]` as points `(p, 1)`.
fn corners(lo: DVec3, hi: DVec3) -> [DVec4; 8] {
    std::array::from_fn(|i| {
        DVec4::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
            1.0,
        )
    })
}

/// Whether the box `[lo, hi]` is wholly outside the clip volume of
/// `clip_from_world`: all its corners beyond one bounding plane.
pub fn outside(clip_from_world: DMat4, lo: DVec3, hi: DVec3) -> bool {
    let m = clip_from_world.transpose();
    let (x, y, z, w) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
    // The planes as rows acting on (p, 1): inside where row · (p, 1) ≥ 0.
    let planes = [w + x, w - x, w + y, w - y, z, w - z];
    let corners = corners(lo, hi);
    planes.iter().any(|plane| {
        corners
            .iter()
            .all(|c| plane.dot(*c) < -SLACK * plane.abs().dot(c.abs()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_is_culled_only_beyond_a_plane() {
        // A 90° face looking down −Z from the origin (reversed, infinite).
        let proj = glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
            std::f64::consts::FRAC_PI_2,
            1.0,
            1e-3,
        );
        let face = proj * DMat4::IDENTITY;
        let unit = DVec3::splat(0.5);
        let at = |c: DVec3| (c - unit, c + unit);
        let (lo, hi) = at(DVec3::new(0.0, 0.0, -5.0));
        assert!(!outside(face, lo, hi), "in front");
        let (lo, hi) = at(DVec3::new(0.0, 0.0, 5.0));
        assert!(outside(face, lo, hi), "behind the light");
        let (lo, hi) = at(DVec3::new(8.0, 0.0, -5.0));
        assert!(outside(face, lo, hi), "beyond the right plane");
        // Straddling the 45° plane x = −z: drawn.
        let (lo, hi) = at(DVec3::new(5.0, 0.0, -5.0));
        assert!(!outside(face, lo, hi), "across the right plane");
        // Touching the plane from outside within the slack: drawn.
        let (lo, hi) = (DVec3::new(5.0, -0.5, -5.0), DVec3::new(6.0, 0.5, -5.0));
        assert!(!outside(face, lo, hi), "on the plane");
    }

    /// A 90° reversed infinite face looking down −Z from the origin, as
    /// a cube face's.
    fn face() -> DMat4 {
        glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
            std::f64::consts::FRAC_PI_2,
            1.0,
            1e-3,
        )
    }

    #[test]
    fn a_box_in_front_projects_to_its_texels_grown() {
        // x, y ∈ [−0.9, 0.9] at z = −2: NDC ±0.45, texels [27.5, 72.5] of
        // 100, so the texels 27 to 72.
        let (lo, hi) = (DVec3::new(-0.9, -0.9, -2.0), DVec3::new(0.9, 0.9, -2.0));
        let rect = texel_rect(face(), lo, hi, 100, 0.0);
        assert_eq!(
            rect,
            Some(TexelRect {
                x: 27,
                y: 27,
                width: 46,
                height: 46
            })
        );
        // Grown by 3 texels on every side.
        let rect = texel_rect(face(), lo, hi, 100, 3.0);
        assert_eq!(
            rect,
            Some(TexelRect {
                x: 24,
                y: 24,
                width: 52,
                height: 52
            })
        );
        // y up in the world is up in the map: texel rows count downwards
        // (y ∈ [0, 0.9]: rows 27.5 to 50).
        let rect = texel_rect(face(), DVec3::new(-0.9, 0.0, -2.0), hi, 100, 0.0);
        assert_eq!(
            rect,
            Some(TexelRect {
                x: 27,
                y: 27,
                width: 46,
                height: 24
            })
        );
    }

    #[test]
    fn a_box_across_the_light_plane_reaches_the_edges_it_points_to() {
        // From z = −2 to z = +1 at x ∈ [1.1, 2]: the front part's lookups
        // run off to +x as w → 0 (clamped to the last column); y ∈ [−1, 1]
        // runs off both ways.
        let rect = texel_rect(
            face(),
            DVec3::new(1.1, -1.0, -2.0),
            DVec3::new(2.0, 1.0, 1.0),
            100,
            0.0,
        )
        .unwrap();
        assert_eq!((rect.x, rect.x + rect.width), (77, 100));
        assert_eq!((rect.y, rect.height), (0, 100));
        // Wholly behind: no lookup reads the face.
        assert_eq!(
            texel_rect(
                face(),
                DVec3::new(-1.0, -1.0, 1.0),
                DVec3::new(1.0, 1.0, 2.0),
                100,
                0.0
            ),
            None
        );
        // Beyond the right edge in front: the clamped lookups read the
        // edge column only.
        let rect = texel_rect(
            face(),
            DVec3::new(5.0, -1.0, -2.0),
            DVec3::new(6.0, 1.0, -2.0),
            100,
            0.0,
        )
        .unwrap();
        assert_eq!((rect.x, rect.width), (99, 1));
    }

    #[test]
    fn each_object_gets_the_union_of_the_others() {
        let r = |x, width| {
            Some(TexelRect {
                x,
                y: 0,
                width,
                height: 1,
            })
        };
        let others = regions_of_others(&[r(0, 2), None, r(10, 5), r(4, 1)]);
        assert_eq!(others, vec![r(4, 11), r(0, 15), r(0, 5), r(0, 15)]);
        assert_eq!(regions_of_others(&[r(3, 1)]), vec![None]);
    }

    #[test]
    fn a_flat_caster_is_clipped_only_when_its_lookups_clear_it() {
        let mut light = LightShadow {
            map: 0,
            projection: Projection::Cube,
            first_layer: 0,
            settings: crate::scene::ShadowSettings {
                map_size: 1024,
                bias: 0.0,
                slope_bias: 0.0,
                normal_offset: 3.0 / std::f64::consts::SQRT_2 + 0.5,
                filter: ShadowFilter::Pcf { kernel: 3 },
                resolution: crate::scene::MapResolution::Fixed,
            },
            texel: 2e-3,
            origin: DVec3::new(0.0, 2.0, 0.0),
        };
        let plane = |bumps| Flat {
            normal: DVec3::Y,
            offset: 0.0,
            bumps,
        };
        let floor = CasterBox {
            lo: DVec3::new(-1.0, 0.0, -1.0),
            hi: DVec3::new(1.0, 0.0, 1.0),
            flatness: Some(plane(0.0)),
        };
        let safe = |light: &LightShadow, caster: &CasterBox| flat_and_safe(light, face(), caster);
        assert!(safe(&light, &floor), "the default offset");
        assert!(
            !safe(
                &light,
                &CasterBox {
                    flatness: None,
                    ..floor
                }
            ),
            "not flat"
        );
        // Bumps: a tenth of the ½-texel margin at 2 m is 2·10⁻⁴ m.
        assert!(safe(
            &light,
            &CasterBox {
                flatness: Some(plane(1.9e-4)),
                ..floor
            }
        ));
        assert!(!safe(
            &light,
            &CasterBox {
                flatness: Some(plane(2.1e-4)),
                ..floor
            }
        ));
        // An offset within a quarter texel of k/√2 may let a plane shadow
        // itself: drawn whole.
        light.settings.normal_offset = 3.0 / std::f64::consts::SQRT_2 + 0.2;
        assert!(!safe(&light, &floor), "offset too small");
        light.settings.normal_offset = 5.0;
        assert!(safe(&light, &floor));
        // Seen within 1° of edge-on at the far corner: drawn whole.
        let wide = CasterBox {
            lo: DVec3::new(-100.0, 0.0, -100.0),
            hi: DVec3::new(100.0, 0.0, 100.0),
            ..floor
        };
        assert!(!safe(&light, &wide), "grazing");
        // A light in the plane: no texel to scale the margin, edge-on.
        light.origin = DVec3::new(3.0, 0.0, 0.0);
        assert!(!safe(&light, &floor), "light in the plane");
    }
}
