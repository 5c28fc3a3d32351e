//! `shading.shadow_coords`: where Phong shading computes the shadow-map
//! coordinates of its lookup point, a knob of the GPU path.
//! The reference traces shadow rays and ignores it.

use crate::base::named_enum;

named_enum!(
    /// Where the GPU's per-pixel (Phong) shading computes the shadow-map
    /// coordinates (`ShaderKey::shadow_coords_per_vertex`; derivation and
    /// error bound in docs/shadows.md, "Coordinates per vertex").
    #[derive(Default)]
    ShadowCoords, "shadow_coords" {
        /// Per vertex where that is exact (one orthographic map: the
        /// lookup point is affine over a triangle), per pixel elsewhere.
        /// The default.
        #[default]
        Exact = "exact",
        /// Also per vertex for one perspective (spot) map: the corners'
        /// homogeneous map coordinates interpolated, exact for the plain
        /// projection but not for the offsets along the normal and the
        /// light ray, which are not affine over a triangle; off by at most
        /// the bound of docs/shadows.md.
        Vertex = "vertex",
    }
);

use glam::DVec3;

/// A light's lookup-point settings, as the shader reads them
/// (`Light.shadow_*`): `normal_offset` and `slope_bias` in texels, `bias`
/// in metres, `texel` the map's texel per metre of distance from the
/// light (`LightShadow::texel` of a perspective map).
#[derive(Clone, Copy, Debug)]
pub struct LookupOffsets {
    pub normal_offset: f64,
    pub bias: f64,
    pub slope_bias: f64,
    pub texel: f64,
}

/// Where `x` reads a perspective map of the light at `light` (`n`: the
/// triangle's face normal, any length and orientation). f64 twin of
/// `shadow_perspective` / `shadow_point` in shaders/shadows.wgsl:
/// `p = x + c·t·n + (b + s·t·tanθ)·ω`, `t = texel·|light − x|`, `n` turned
/// towards the light, tanθ capped at 1000.
pub fn lookup_point(o: &LookupOffsets, light: DVec3, x: DVec3, n: DVec3) -> DVec3 {
    let to_light = light - x;
    let r = to_light.length();
    let wi = to_light / r.max(1e-30);
    let t = o.texel * r;
    let mut n = n.normalize_or_zero();
    let mut c = n.dot(wi);
    if c < 0.0 {
        n = -n;
        c = -c;
    }
    let tan_theta = (1.0 - c * c).max(0.0).sqrt() / c.max(1e-3);
    x + n * (o.normal_offset * t) + wi * (o.bias + o.slope_bias * t * tan_theta)
}

/// Upper bound (metres) on `|Σ λ_i p(x_i) − p(x)|`, the distance between
/// the lookup point `shading.shadow_coords = "vertex"` reads (the corners'
/// lookup points `p(x_i)` interpolated with the barycentrics `λ` of `x`)
/// and the exact one `p(x)`, for the triangle `corners` lit by a spot
/// light at `light` (docs/shadows.md, "Coordinates per vertex", derives
/// each term). `None` where the derivation does not hold: the light within
/// `10⁻³·r` of the triangle's plane somewhere on it (tanθ capped), or a
/// degenerate triangle.
pub fn displacement_bound(
    o: &LookupOffsets,
    light: DVec3,
    corners: [DVec3; 3],
    lambda: [f64; 3],
) -> Option<f64> {
    let [a, b, c] = corners;
    let n = (b - a).cross(c - a).try_normalize()?;
    // Distance from the light to the plane: the same at every point of it.
    let d = n.dot(light - a).abs();
    let r_max = corners
        .iter()
        .map(|&p| (light - p).length())
        .fold(0.0, f64::max);
    if d < 1e-3 * r_max {
        return None;
    }
    let x = lambda[0] * a + lambda[1] * b + lambda[2] * c;
    // s2 = Σ λ_i |x_i − x|² = Σ_{i<j} λ_i λ_j |x_i − x_j|² (≤ h²/3).
    let s2: f64 = (0..3)
        .map(|i| lambda[i] * (corners[i] - x).length_squared())
        .sum();
    let s1: f64 = (0..3).map(|i| lambda[i] * (corners[i] - x).length()).sum();
    let r_min = point_triangle_distance(light, corners);
    let foot = light - n * n.dot(light - a);
    let rho_min = point_triangle_distance(foot, corners);
    let rho_term = if rho_min > 0.0 {
        s1.min(s2 / (2.0 * rho_min))
    } else {
        s1
    };
    let t = o.texel;
    Some(
        o.normal_offset * t * s2 / (2.0 * r_min)
            + o.slope_bias * t * rho_term
            + o.bias * s2 / (3f64.sqrt() * r_min * r_min)
            + o.slope_bias * t * s2 / d,
    )
}

/// Distance from `p` to the triangle `[a, b, c]` (Ericson, Real-Time
/// Collision Detection, 5.1.5: the closest point by Voronoi regions).
pub fn point_triangle_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).length();
    }
    let denom = 1.0 / (va + vb + vc);
    (p - (a + ab * (vb * denom) + ac * (vc * denom))).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift), so the test needs no
    /// crate and always draws the same cases.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn vec(&mut self, s: f64) -> DVec3 {
            DVec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * (2.0 * s)
        }
    }

    /// The interpolated lookup point is within the bound of the exact
    /// one for random triangles, lights and offsets (each term alone and
    /// all together), and the bound is not loose by more than a factor
    /// the derivation explains (the worst case reaches a sizeable part of
    /// it). With only the normal offset the displacement is along the
    /// normal, towards the light (r is convex).
    #[test]
    fn per_vertex_lookup_points_stay_within_the_bound() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let settings = [
            (2.62, 0.0, 0.0),
            (0.0, 0.05, 0.0),
            (0.0, 0.0, 2.0),
            (2.62, 0.02, 1.5),
        ];
        for (c, b, s) in settings {
            let o = LookupOffsets {
                normal_offset: c,
                bias: b,
                slope_bias: s,
                texel: 2.0 * 0.8f64.tan() / 2048.0,
            };
            let mut worst: f64 = 0.0;
            for _ in 0..20_000 {
                let light = rng.vec(1.0) + DVec3::new(0.0, 4.0, 0.0);
                let size = 0.05 + 6.0 * rng.next();
                let centre = rng.vec(2.0);
                let corners = [
                    centre + rng.vec(size),
                    centre + rng.vec(size),
                    centre + rng.vec(size),
                ];
                let (u, v) = (rng.next(), rng.next());
                let (u, v) = if u + v > 1.0 {
                    (1.0 - u, 1.0 - v)
                } else {
                    (u, v)
                };
                let lambda = [1.0 - u - v, u, v];
                let Some(bound) = displacement_bound(&o, light, corners, lambda) else {
                    continue;
                };
                let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
                let x = lambda[0] * corners[0] + lambda[1] * corners[1] + lambda[2] * corners[2];
                let interpolated: DVec3 = (0..3)
                    .map(|i| lambda[i] * lookup_point(&o, light, corners[i], n))
                    .sum();
                let exact = lookup_point(&o, light, x, n);
                let e = interpolated - exact;
                assert!(
                    e.length() <= bound * (1.0 + 1e-9) + 1e-12,
                    "c {c} b {b} s {s}: |e| = {} > bound {bound}",
                    e.length()
                );
                if b == 0.0 && s == 0.0 {
                    // Along the normal turned to the light, never against.
                    let towards = n * n.dot(light - x).signum();
                    assert!(e.dot(towards) >= -1e-12 * bound.max(1.0));
                    assert!(
                        (e - towards.normalize() * e.length()).length()
                            <= 1e-9 * bound.max(1e-9) + 1e-12
                    );
                }
                if bound > 1e-9 {
                    worst = worst.max(e.length() / bound);
                }
            }
            println!("c {c} b {b} s {s}: worst |e| / bound = {worst:.3}");
            assert!(
                worst > 0.2,
                "c {c} b {b} s {s}: the bound is never approached ({worst})"
            );
        }
    }
}
