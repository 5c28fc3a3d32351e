//! A bounding volume hierarchy over every triangle of a scene, in `f64`.
//!
//! Built top-down with a binned surface-area heuristic (SAH): a split is
//! worth what it costs to test the two children, i.e. the probability that a
//! ray hitting the parent hits a child (the ratio of surface areas) times the
//! triangles in it. Nodes live in one flat array in depth-first order (the
//! left child directly follows its parent), and both building and traversal
//! use explicit stacks, so neither recurses.
//!
//! Ray–triangle tests are Möller–Trumbore, slightly inclusive at the edges so
//! that a ray exactly on an edge shared by two triangles hits at least one of
//! them: the GPU's rasterization rules never leave such a pixel uncovered,
//! and neither may the reference. Both faces are hit; back faces are the
//! shading's business, not visibility's.

use crate::scene::Mesh;
use crate::scene::camera::Ray;
use glam::DVec3;

/// At most this many triangles per leaf.
const MAX_LEAF: usize = 4;
/// SAH bins per axis.
const BINS: usize = 16;
/// Below this depth the SAH decides; from here on the median split halves
/// every node, which bounds the depth by this plus log2 of the triangle
/// count and so the traversal stack below.
const SAH_MAX_DEPTH: usize = 64;
/// Traversal stack size: more than `SAH_MAX_DEPTH + 32` levels can hold.
const STACK: usize = 128;
/// Barycentric slack at the edges (dimensionless).
const EDGE_EPS: f64 = 1e-12;
/// Relative widening of a box's exit distance, far above the few ulps of
/// rounding in the slab test, so a ray that grazes a box face where a
/// triangle lies (axis-aligned geometry) still enters the box.
const SLAB_EPS: f64 = 1e-12;

/// Which triangle: `Scene::meshes[mesh].indices[triangle]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TriangleId {
    pub mesh: u32,
    pub triangle: u32,
}

/// A ray–triangle hit. The point is `origin + t · direction`, or, as the
/// barycentric form, `(1 − u − v)·a + u·b + v·c` for corners `a, b, c` of
/// the triangle in index order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub id: TriangleId,
    /// Weight of corner `b`.
    pub u: f64,
    /// Weight of corner `c`.
    pub v: f64,
}

/// Bytes the hierarchy holds per triangle at the peak of its build, an
/// upper bound: while building, an id, the bounds and the order entry; then
/// the prepared triangle beside the id and order; plus the nodes, fewer
/// than two per triangle (a binary tree whose leaves hold at least one).
pub const BUILD_BYTES_PER_TRIANGLE: u64 = {
    let building = size_of::<TriangleId>() + size_of::<Prim>() + 4;
    let finishing = size_of::<TriangleId>() + size_of::<Triangle>() + 4;
    let peak = if building > finishing {
        building
    } else {
        finishing
    };
    (peak + 2 * size_of::<Node>()) as u64
};

/// A triangle prepared for Möller–Trumbore: corner `a` and the edges
/// `b − a`, `c − a`.
#[derive(Clone, Copy, Debug)]
struct Triangle {
    a: DVec3,
    e1: DVec3,
    e2: DVec3,
    id: TriangleId,
}

/// A node: a leaf holds `count > 0` triangles from `offset`; an interior
/// node (`count == 0`) has its left child at the next index and its right
/// child at `offset`.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    offset: u32,
    count: u32,
}

/// The hierarchy. Empty scenes give an empty one that nothing hits.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    triangles: Vec<Triangle>,
}

/// Bounds and centroid of a triangle, used while building.
#[derive(Clone, Copy)]
struct Prim {
    lo: DVec3,
    hi: DVec3,
    centroid: DVec3,
}

/// A range of `order` still to be turned into a node.
struct Task {
    start: usize,
    end: usize,
    depth: usize,
    /// Interior node whose right child this task becomes.
    parent: Option<usize>,
}

impl Bvh {
    /// Builds the hierarchy over all triangles of `meshes`. Triangles with
    /// zero area or non-finite corners are left out: no ray (and no GPU
    /// rasterizer) can hit them.
    pub fn new(meshes: &[Mesh]) -> Self {
        // Only the ids and the bounds are held while building; the
        // Möller–Trumbore triangles are made once, in leaf order, after the
        // bounds are gone. That keeps the peak at about
        // [`BUILD_BYTES_PER_TRIANGLE`] instead of holding both plus a
        // reordered copy (236 bytes a triangle, 10.5 GB for the 33.5 M
        // triangles of a 4096-segment plane).
        let capacity = meshes.iter().map(|m| m.indices.len()).sum();
        let mut ids = Vec::with_capacity(capacity);
        let mut prims = Vec::with_capacity(capacity);
        for (m, mesh) in meshes.iter().enumerate() {
            for t in 0..mesh.indices.len() {
                let [a, b, c] = mesh.triangle(t);
                let cross = (b - a).cross(c - a);
                if !(a.is_finite() && b.is_finite() && c.is_finite()) || cross == DVec3::ZERO {
                    continue;
                }
                ids.push(TriangleId {
                    mesh: u32::try_from(m).expect("mesh count fits u32"),
                    triangle: u32::try_from(t).expect("triangle count fits u32"),
                });
                let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
                prims.push(Prim {
                    lo,
                    hi,
                    centroid: 0.5 * (lo + hi),
                });
            }
        }
        let mut order: Vec<u32> = (0..ids.len() as u32).collect();
        let nodes = build(&prims, &mut order);
        drop(prims);
        let triangles = order
            .iter()
            .map(|&i| {
                let id = ids[i as usize];
                let [a, b, c] = meshes[id.mesh as usize].triangle(id.triangle as usize);
                Triangle {
                    a,
                    e1: b - a,
                    e2: c - a,
                    id,
                }
            })
            .collect();
        Bvh { nodes, triangles }
    }

    /// Number of triangles the hierarchy holds.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True if nothing can be hit.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The closest hit with `t` in `[t_min, t_max]`.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.intersect_where(ray, t_min, t_max, |_| true)
    }

    /// The closest hit with `t` in `[t_min, t_max]` on a triangle that
    /// `keeps_back(id)` keeps when the ray meets its back (clockwise seen
    /// from the origin): back-face culling of single-sided materials
    /// (glTF `doubleSided: false`), as the rasterizer culls by winding.
    pub fn intersect_where(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        keeps_back: impl Fn(TriangleId) -> bool,
    ) -> Option<Hit> {
        let inv = ray.direction.recip();
        let mut best: Option<Hit> = None;
        let mut t_far = t_max;
        self.traverse(ray, inv, t_min, &mut t_far, |tri, t_lo, t_hi| {
            if let Some(hit) = intersect_triangle(tri, ray, t_lo, *t_hi) {
                // Möller–Trumbore's determinant is −d·(e1 × e2): the back
                // is met where the direction has a positive component
                // along the counter-clockwise normal.
                let back = ray.direction.dot(tri.e1.cross(tri.e2)) > 0.0;
                if !back || keeps_back(tri.id) {
                    best = Some(hit);
                    *t_hi = hit.t;
                }
            }
            false
        });
        best
    }

    /// Whether anything lies along the ray with `t` in the open interval
    /// `(0, t_max)`: the any-hit query of shadow rays. Callers offset the
    /// origin off the surface themselves.
    pub fn occluded(&self, ray: &Ray, t_max: f64) -> bool {
        self.occluded_where(ray, t_max, |_| true)
    }

    /// [`Self::occluded`] counting only the hits `blocks(hit)` keeps: a
    /// shadow ray passes through what alpha MASK cuts out.
    ///
    /// Any hit will do, so the walk visits children in tree order (left
    /// first) without comparing their entry distances and keeps no
    /// distances on its stack: `t_max` never shrinks, so the leaves
    /// visited are those of the nearest-first walk of
    /// [`Self::intersect_where`] and the answer is the same.
    pub fn occluded_where(&self, ray: &Ray, t_max: f64, blocks: impl Fn(&Hit) -> bool) -> bool {
        let inv = ray.direction.recip();
        let Some(root) = self.nodes.first() else {
            return false;
        };
        if enter(root, ray.origin, inv, 0.0, t_max).is_none() {
            return false;
        }
        let mut stack = [0u32; STACK];
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let mut index = stack[sp];
            loop {
                let node = &self.nodes[index as usize];
                if node.count > 0 {
                    let start = node.offset as usize;
                    for tri in &self.triangles[start..start + node.count as usize] {
                        if intersect_triangle(tri, ray, 0.0, t_max)
                            .is_some_and(|h| h.t > 0.0 && h.t < t_max && blocks(&h))
                        {
                            return true;
                        }
                    }
                    break;
                }
                let (left, right) = (index + 1, node.offset);
                let hits_left = enter(&self.nodes[left as usize], ray.origin, inv, 0.0, t_max);
                let hits_right = enter(&self.nodes[right as usize], ray.origin, inv, 0.0, t_max);
                index = match (hits_left, hits_right) {
                    (Some(_), Some(_)) => {
                        stack[sp] = right;
                        sp += 1;
                        left
                    }
                    (Some(_), None) => left,
                    (None, Some(_)) => right,
                    (None, None) => break,
                };
            }
        }
        false
    }

    /// Visits the triangles of every leaf whose box the ray enters within
    /// `[t_min, t_far]`, nearer child first. `visit(triangle, t_min, t_far)`
    /// may shrink `t_far`, which prunes what is left; it returns `true` to
    /// stop.
    fn traverse(
        &self,
        ray: &Ray,
        inv: DVec3,
        t_min: f64,
        t_far: &mut f64,
        mut visit: impl FnMut(&Triangle, f64, &mut f64) -> bool,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let Some(t_root) = enter(root, ray.origin, inv, t_min, *t_far) else {
            return;
        };
        // Nodes and entry distances in two arrays: zeroed, they are one
        // `memset` each, where an array of `(u32, f64)` pairs was filled
        // element by element (its padding), 290 instructions a ray, a
        // fifth of a primary ray's walk (docs/notes/reference-timing.md).
        let mut stack = [0u32; STACK];
        let mut stack_t = [0.0f64; STACK];
        stack_t[0] = t_root;
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let (mut index, t_enter) = (stack[sp], stack_t[sp]);
            if t_enter > *t_far {
                continue;
            }
            loop {
                let node = &self.nodes[index as usize];
                if node.count > 0 {
                    let start = node.offset as usize;
                    for tri in &self.triangles[start..start + node.count as usize] {
                        if visit(tri, t_min, t_far) {
                            return;
                        }
                    }
                    break;
                }
                let (left, right) = (index + 1, node.offset);
                let t_left = enter(&self.nodes[left as usize], ray.origin, inv, t_min, *t_far);
                let t_right = enter(&self.nodes[right as usize], ray.origin, inv, t_min, *t_far);
                index = match (t_left, t_right) {
                    (Some(tl), Some(tr)) => {
                        let (near, far, t_other) = if tl <= tr {
                            (left, right, tr)
                        } else {
                            (right, left, tl)
                        };
                        (stack[sp], stack_t[sp]) = (far, t_other);
                        sp += 1;
                        near
                    }
                    (Some(_), None) => left,
                    (None, Some(_)) => right,
                    (None, None) => break,
                };
            }
        }
    }
}

/// Slab test: the distance at which the ray enters the node's box, if its
/// span inside the box meets `[t_min, t_max]`. A zero direction component
/// gives infinite slab distances, or NaN for an origin on the slab plane,
/// which `f64::min`/`max` ignore (the test stays conservative).
fn enter(node: &Node, origin: DVec3, inv: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
    let t0 = (node.lo - origin) * inv;
    let t1 = (node.hi - origin) * inv;
    let t_near = t0.min(t1).max_element().max(t_min);
    let t_exit = t0.max(t1).min_element();
    let t_far = (t_exit + t_exit.abs() * SLAB_EPS).min(t_max);
    (t_near <= t_far).then_some(t_near)
}

/// Möller–Trumbore with `t` in `[t_min, t_max]`, edges inclusive up to
/// [`EDGE_EPS`]; a ray in the triangle's plane misses.
fn intersect_triangle(tri: &Triangle, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let p = ray.direction.cross(tri.e2);
    let det = tri.e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = ray.origin - tri.a;
    let u = s.dot(p) * inv_det;
    if !(-EDGE_EPS..=1.0 + EDGE_EPS).contains(&u) {
        return None;
    }
    let q = s.cross(tri.e1);
    let v = ray.direction.dot(q) * inv_det;
    if v < -EDGE_EPS || u + v > 1.0 + EDGE_EPS {
        return None;
    }
    let t = tri.e2.dot(q) * inv_det;
    (t >= t_min && t <= t_max).then_some(Hit {
        t,
        id: tri.id,
        u,
        v,
    })
}

/// Builds the flat node array and reorders `order` so every leaf's
/// triangles are contiguous.
fn build(prims: &[Prim], order: &mut [u32]) -> Vec<Node> {
    let mut nodes = Vec::with_capacity(2 * prims.len().div_ceil(MAX_LEAF));
    if prims.is_empty() {
        return nodes;
    }
    // Popping the left task right after its parent makes it the next node.
    let mut tasks = vec![Task {
        start: 0,
        end: order.len(),
        depth: 0,
        parent: None,
    }];
    while let Some(task) = tasks.pop() {
        let index = nodes.len();
        if let Some(parent) = task.parent {
            nodes[parent].offset = index as u32;
        }
        let range = &mut order[task.start..task.end];
        let (lo, hi) = range
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &i| {
                (lo.min(prims[i as usize].lo), hi.max(prims[i as usize].hi))
            });
        let count = range.len();
        if count <= MAX_LEAF {
            nodes.push(Node {
                lo,
                hi,
                offset: task.start as u32,
                count: count as u32,
            });
            continue;
        }
        nodes.push(Node {
            lo,
            hi,
            offset: 0,
            count: 0,
        });
        let mid = task.start + split(prims, range, task.depth);
        tasks.push(Task {
            start: mid,
            end: task.end,
            depth: task.depth + 1,
            parent: Some(index),
        });
        tasks.push(Task {
            start: task.start,
            end: mid,
            depth: task.depth + 1,
            parent: None,
        });
    }
    nodes
}

/// Partitions `range` (more than [`MAX_LEAF`] triangles) in two non-empty
/// parts and returns the size of the first.
fn split(prims: &[Prim], range: &mut [u32], depth: usize) -> usize {
    let centroid = |i: u32| prims[i as usize].centroid;
    let (c_lo, c_hi) = range
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &i| {
            (lo.min(centroid(i)), hi.max(centroid(i)))
        });
    let extent = c_hi - c_lo;
    let axis = extent.max_position();
    let half = range.len() / 2;
    if extent[axis] <= 0.0 {
        // All centroids coincide: any partition is as good as another.
        return half;
    }
    if depth < SAH_MAX_DEPTH
        && let Some((axis, bin)) = best_sah_split(prims, range, c_lo, extent)
    {
        let bin_of = |i: u32| bin_index(centroid(i)[axis], c_lo[axis], extent[axis]);
        return partition(range, |&i| bin_of(i) <= bin);
    }
    range.select_nth_unstable_by(half, |&a, &b| {
        centroid(a)[axis].total_cmp(&centroid(b)[axis])
    });
    half
}

/// Bin of a centroid coordinate along an axis of positive extent.
fn bin_index(c: f64, lo: f64, extent: f64) -> usize {
    (((c - lo) / extent * BINS as f64) as usize).min(BINS - 1)
}

/// The cheapest binned SAH split over all three axes: the axis and the last
/// bin of the left part. `None` if no axis separates the centroids.
fn best_sah_split(
    prims: &[Prim],
    range: &[u32],
    c_lo: DVec3,
    extent: DVec3,
) -> Option<(usize, usize)> {
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in (0..3).filter(|&a| extent[a] > 0.0) {
        let mut bins = [(0usize, DVec3::INFINITY, DVec3::NEG_INFINITY); BINS];
        for &i in range {
            let p = &prims[i as usize];
            let b = &mut bins[bin_index(p.centroid[axis], c_lo[axis], extent[axis])];
            *b = (b.0 + 1, b.1.min(p.lo), b.2.max(p.hi));
        }
        // Sweep from the right: cost of everything right of each plane.
        let mut right_cost = [0.0; BINS];
        let mut acc = (0usize, DVec3::INFINITY, DVec3::NEG_INFINITY);
        for b in (1..BINS).rev() {
            acc = (
                acc.0 + bins[b].0,
                acc.1.min(bins[b].1),
                acc.2.max(bins[b].2),
            );
            right_cost[b] = acc.0 as f64 * half_area(acc.1, acc.2);
        }
        let mut acc = (0usize, DVec3::INFINITY, DVec3::NEG_INFINITY);
        for b in 0..BINS - 1 {
            acc = (
                acc.0 + bins[b].0,
                acc.1.min(bins[b].1),
                acc.2.max(bins[b].2),
            );
            if acc.0 == 0 || acc.0 == range.len() {
                continue;
            }
            let cost = acc.0 as f64 * half_area(acc.1, acc.2) + right_cost[b + 1];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, b));
            }
        }
    }
    best.map(|(_, axis, bin)| (axis, bin))
}

/// Half the surface area of a box (the SAH only compares ratios).
fn half_area(lo: DVec3, hi: DVec3) -> f64 {
    let d = (hi - lo).max(DVec3::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// Moves the elements satisfying `left` to the front; returns their count.
fn partition(range: &mut [u32], left: impl Fn(&u32) -> bool) -> usize {
    let mut mid = 0;
    for k in 0..range.len() {
        if left(&range[k]) {
            range.swap(mid, k);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Marsaglia's xorshift64: deterministic and dependency-free.
    struct XorShift(u64);

    impl XorShift {
        fn next_f64(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }

        fn in_cube(&mut self, half: f64) -> DVec3 {
            DVec3::new(self.next_f64(), self.next_f64(), self.next_f64()) * (2.0 * half)
                - DVec3::splat(half)
        }
    }

    fn brute_force(bvh: &Bvh, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for tri in &bvh.triangles {
            let limit = best.map_or(t_max, |h| h.t);
            if let Some(h) = intersect_triangle(tri, ray, t_min, limit) {
                best = Some(h);
            }
        }
        best
    }

    /// Small and large triangles mixed, in two meshes.
    fn soup(rng: &mut XorShift, n: usize) -> Vec<Mesh> {
        (0..2)
            .map(|m| {
                let mut positions = Vec::new();
                for k in 0..n {
                    let centre = rng.in_cube(5.0);
                    let size = if k % 10 == 0 { 2.0 } else { 0.3 };
                    for _ in 0..3 {
                        positions.push(centre + rng.in_cube(size));
                    }
                }
                let indices = (0..n as u32)
                    .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
                    .collect();
                Mesh::with_generated_normals(format!("soup{m}"), positions, indices, 0)
            })
            .collect()
    }

    #[test]
    fn closest_hit_and_any_hit_match_brute_force() {
        let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
        let meshes = soup(&mut rng, 1000);
        let bvh = Bvh::new(&meshes);
        assert_eq!(bvh.len(), 2000);
        let mut hits = 0;
        for _ in 0..4000 {
            let ray = Ray {
                origin: rng.in_cube(8.0),
                direction: rng.in_cube(1.0).normalize(),
            };
            let t_max = 20.0 * rng.next_f64();
            let got = bvh.intersect(&ray, 0.0, t_max);
            let want = brute_force(&bvh, &ray, 0.0, t_max);
            assert_eq!(got.map(|h| h.t), want.map(|h| h.t), "ray {ray:?}");
            if let (Some(g), Some(w)) = (got, want) {
                hits += 1;
                if g.id != w.id {
                    // A tie: the other triangle must hit at the same t.
                    let tri = bvh.triangles.iter().find(|t| t.id == g.id).unwrap();
                    assert_eq!(intersect_triangle(tri, &ray, 0.0, t_max).unwrap().t, w.t);
                } else {
                    assert_eq!((g.u, g.v), (w.u, w.v));
                }
            }
            let blocked = want.is_some_and(|h| h.t > 0.0 && h.t < t_max);
            assert_eq!(bvh.occluded(&ray, t_max), blocked, "ray {ray:?}");
        }
        assert!(hits > 500, "only {hits} hits: the test says little");
    }

    #[test]
    fn rays_on_a_shared_edge_do_not_fall_through() {
        // A unit quad in z = 0 split along its diagonal, rays straight down
        // onto points of the diagonal and of the outer edges.
        let quad = Mesh::with_generated_normals(
            "quad",
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            vec![[0, 1, 2], [0, 2, 3]],
            0,
        );
        let bvh = Bvh::new(&[quad]);
        for k in 0..=64 {
            let s = k as f64 / 64.0 * 0.999 + 0.0005;
            for p in [DVec3::new(s, s, 0.0), DVec3::new(s, 0.0, 0.0)] {
                let ray = Ray {
                    origin: p + DVec3::Z,
                    direction: -DVec3::Z,
                };
                let hit = bvh
                    .intersect(&ray, 0.0, 2.0)
                    .expect("edge ray fell through");
                assert!((hit.t - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn coincident_triangles_build_and_hit() {
        // Identical centroids defeat every split plane; the build must still
        // produce leaves of at most MAX_LEAF triangles.
        let n = 100u32;
        let positions = (0..n)
            .flat_map(|_| [DVec3::ZERO, DVec3::X, DVec3::Y])
            .collect();
        let indices = (0..n).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let bvh = Bvh::new(&[Mesh::with_generated_normals("c", positions, indices, 0)]);
        assert!(bvh.nodes.iter().all(|n| n.count as usize <= MAX_LEAF));
        let ray = Ray {
            origin: DVec3::new(0.25, 0.25, -1.0),
            direction: DVec3::Z,
        };
        assert!(bvh.intersect(&ray, 0.0, 10.0).is_some());
        assert!(bvh.occluded(&ray, 10.0));
        assert!(!bvh.occluded(&ray, 0.5));
    }

    #[test]
    fn empty_hierarchy_hits_nothing() {
        let bvh = Bvh::new(&[]);
        let ray = Ray {
            origin: DVec3::ZERO,
            direction: DVec3::X,
        };
        assert!(bvh.is_empty());
        assert!(bvh.intersect(&ray, 0.0, f64::INFINITY).is_none());
        assert!(!bvh.occluded(&ray, f64::INFINITY));
    }
}
