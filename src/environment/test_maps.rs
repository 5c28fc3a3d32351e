//! Environment maps gonio makes for its tests and ships: small, with
//! features whose directions and integrals are known.

use super::latlong;
use super::map::MapData;
use super::sh;
use crate::base::Rgb;
use glam::DVec3;

/// The blobs: a dim blue-grey ground-and-sky base with three Gaussian
/// lights (red-ish above the front right, green at the horizon towards
/// −X, blue below towards −Z); 64 × 32 texels. Shipped as
/// `assets/environment/blobs.hdr` (a test checks the file is this map).
pub fn blobs() -> MapData {
    let lights = [
        (DVec3::new(0.5, 0.7, 0.5), Rgb::new(8.0, 3.0, 1.0), 0.25),
        (DVec3::new(-1.0, 0.0, 0.1), Rgb::new(0.5, 4.0, 0.5), 0.35),
        (DVec3::new(0.0, -0.6, -0.8), Rgb::new(0.5, 1.0, 6.0), 0.3),
    ];
    from_fn(64, |d| {
        let base = if d.y >= 0.0 {
            Rgb::new(0.3, 0.35, 0.45)
        } else {
            Rgb::new(0.15, 0.12, 0.1)
        };
        lights.iter().fold(base, |sum, (at, l, width)| {
            let angle = d.dot(at.normalize()).clamp(-1.0, 1.0).acos();
            sum + *l * (-(angle / width).powi(2)).exp()
        })
    })
}

/// A constant map of radiance `l` (the white furnace with `l = 1`).
pub fn uniform(width: u32, l: Rgb) -> MapData {
    from_fn(width, |_| l)
}

/// The map whose radiance is `Σ c_i Y_i(d)` at each texel centre.
pub fn from_sh(width: u32, c: &[Rgb; sh::COUNT]) -> MapData {
    from_fn(width, |d| sh::evaluate(c, d))
}

/// Black with one texel of radiance `l` at `(col, row)`: a marker.
pub fn marker(width: u32, col: u32, row: u32, l: Rgb) -> MapData {
    let h = width / 2;
    let mut texels = vec![[0.0f32; 3]; (width * h) as usize];
    texels[(row * width + col) as usize] = l.as_vec3().to_array();
    MapData::new("marker", width, h, texels).expect("a valid map")
}

/// A `width × width/2` map with `f` at each texel centre (f32).
pub fn from_fn(width: u32, f: impl Fn(DVec3) -> Rgb) -> MapData {
    let h = width / 2;
    let texels = (0..width * h)
        .map(|k| {
            let d = latlong::texel_direction(k % width, k / width, width, h);
            f(d).as_vec3().to_array()
        })
        .collect();
    MapData::new("generated", width, h, texels).expect("a valid map")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped `assets/environment/blobs.hdr` is [`blobs`] (within
    /// RGBE's 2⁻⁷ of the largest channel); `GONIO_UPDATE_ASSETS=1` rewrites it.
    #[test]
    fn the_shipped_blobs_map_is_the_generated_one() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/environment");
        let map = blobs();
        if std::env::var_os("GONIO_UPDATE_ASSETS").is_some() {
            std::fs::create_dir_all(&dir).unwrap();
            super::super::load::write_hdr(&map, &dir.join("blobs.hdr")).unwrap();
        }
        let shipped = super::super::load::load("blobs.hdr", &dir, u64::MAX).unwrap();
        assert_eq!((shipped.width, shipped.height), (64, 32));
        for (a, b) in shipped.texels.iter().zip(&map.texels) {
            // RGBE shares one exponent: 2⁻⁷ of the largest channel.
            let largest = b.iter().fold(0.0f32, |m, v| m.max(*v));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() <= largest / 128.0, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn a_map_made_from_sh_coefficients_projects_back_to_them() {
        let mut c = [Rgb::ZERO; sh::COUNT];
        c[0] = Rgb::new(2.0, 1.5, 1.0);
        c[2] = Rgb::new(0.3, -0.2, 0.1);
        c[4] = Rgb::new(-0.1, 0.05, 0.2);
        c[8] = Rgb::splat(0.15);
        c[12] = Rgb::new(0.05, 0.0, -0.05);
        c[20] = Rgb::splat(0.04);
        let map = from_sh(128, &c);
        let got = &map.truth.radiance_sh;
        // Texel-centre samples taken as constant over each texel: the
        // projection is off by the texel's curvature, O(1/H²) of the
        // coefficients' size; 2e-3 at 128 × 64.
        for i in 0..sh::COUNT {
            let err = (got[i] - c[i]).abs().max_element();
            assert!(err < 2e-3, "L_{i}: {} vs {}", got[i], c[i]);
        }
    }
}
