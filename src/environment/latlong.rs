//! The lat-long (equirectangular) direction convention of the contract
//! (`[environment]`, also Mitsuba 3's `envmap`): for a unit world
//! direction `d` pointing from the scene towards the sky,
//! `u = atan2(d.x, −d.z) / (2π)` wrapped into [0, 1), `v = acos(d.y) / π`;
//! texel column `u·W`, row `v·H`, row 0 at the top (+Y), texel centres at
//! `((col + ½)/W, (row + ½)/H)`.
//!
//! WGSL twin: `latlong_uv` in `shaders/environment.wgsl`.

use crate::base::Rgb;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// `(u, v)` of unit direction `d`: `u` in [0, 1), `v` in [0, 1].
pub fn uv(d: DVec3) -> (f64, f64) {
    let mut u = d.x.atan2(-d.z) / TAU;
    if u < 0.0 {
        u += 1.0;
    }
    if u >= 1.0 {
        u -= 1.0;
    }
    (u, d.y.clamp(-1.0, 1.0).acos() / PI)
}

/// The unit direction of `(u, v)`, the inverse of [`uv`]:
/// `d = (sin θ sin φ, cos θ, −sin θ cos φ)` with `φ = 2πu`, `θ = πv`.
pub fn direction(u: f64, v: f64) -> DVec3 {
    direction_phi_cos(TAU * u, (PI * v).cos())
}

/// The unit direction of azimuth `φ = 2πu` and `cos θ = d.y`.
pub fn direction_phi_cos(phi: f64, cos_theta: f64) -> DVec3 {
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    DVec3::new(sin_theta * phi.sin(), cos_theta, -sin_theta * phi.cos())
}

/// `cos θ` at the top and bottom edges of row `row` of `height` rows: the
/// row covers `cos θ` in `[bottom, top]`, solid angle `(2π/W)(top − bottom)`
/// per texel (the rows' solid angles sum to exactly 4π).
pub fn row_cos_bounds(row: u32, height: u32) -> (f64, f64) {
    let top = (PI * row as f64 / height as f64).cos();
    let bottom = (PI * (row + 1) as f64 / height as f64).cos();
    (top, bottom)
}

/// The centre direction of texel `(col, row)` of a `width × height` map.
pub fn texel_direction(col: u32, row: u32, width: u32, height: u32) -> DVec3 {
    direction(
        (col as f64 + 0.5) / width as f64,
        (row as f64 + 0.5) / height as f64,
    )
}

/// Texels of a `width` × `width/2` lat-long map of `radiance`, each the
/// mean of 4 × 4 samples uniform in `(u, v)` over the texel (so a sharp
/// edge is antialiased): the built-in maps' generator.
pub fn supersampled_texels(width: u32, radiance: impl Fn(DVec3) -> Rgb) -> Vec<[f32; 3]> {
    let (w, h) = (width, width / 2);
    let n = 4;
    (0..h)
        .flat_map(|row| (0..w).map(move |col| (row, col)))
        .map(|(row, col)| {
            let mut sum = Rgb::ZERO;
            for a in 0..n {
                for b in 0..n {
                    let u = (col as f64 + (b as f64 + 0.5) / n as f64) / w as f64;
                    let v = (row as f64 + (a as f64 + 0.5) / n as f64) / h as f64;
                    sum += radiance(direction(u, v));
                }
            }
            (sum / (n * n) as f64).as_vec3().to_array()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_axes_land_where_the_contract_says() {
        // −Z is u = 0 (the seam), +X a quarter turn on, +Z the middle, −X
        // three quarters; +Y the top row, −Y the bottom.
        let cases = [
            (DVec3::NEG_Z, 0.0, 0.5),
            (DVec3::X, 0.25, 0.5),
            (DVec3::Z, 0.5, 0.5),
            (DVec3::NEG_X, 0.75, 0.5),
        ];
        for (d, u, v) in cases {
            let (gu, gv) = uv(d);
            assert!(
                (gu - u).abs() < 1e-12 && (gv - v).abs() < 1e-12,
                "{d}: {gu} {gv}"
            );
        }
        // At the poles u is arbitrary; v is 0 at +Y and 1 at −Y.
        assert!(uv(DVec3::Y).1.abs() < 1e-12);
        assert!((uv(DVec3::NEG_Y).1 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn direction_inverts_uv() {
        for i in 0..17 {
            for j in 1..9 {
                let (u, v) = (i as f64 / 17.0, j as f64 / 9.5);
                let d = direction(u, v);
                assert!((d.length() - 1.0).abs() < 1e-12);
                let (gu, gv) = uv(d);
                assert!((gu - u).abs() < 1e-12 && (gv - v).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn row_solid_angles_sum_to_the_sphere() {
        let h = 7;
        let total: f64 = (0..h)
            .map(|r| {
                let (top, bottom) = row_cos_bounds(r, h);
                TAU * (top - bottom)
            })
            .sum();
        assert!((total - 4.0 * PI).abs() < 1e-12);
    }
}
