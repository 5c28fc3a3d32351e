//! The built-in neutral studio (`[environment] map = "studio"`): a
//! generated 256 × 128 lat-long map of a grey room with soft light panels,
//! the light a glTF file without lights of its own is shown in (as
//! model-viewer's "neutral" environment and the Khronos sample viewer's
//! default studio do): every side of an object is lit, metals have
//! something to reflect, and a white diffuse surface stays below 1.
//!
//! The room is achromatic: a ceiling of radiance 0.6 falling to 0.45 at
//! the horizon and to the floor's 0.25 below, and three panels with
//! smooth edges (a raised-cosine falloff over a few degrees, so
//! prefiltering and sampling see no hard step): a key panel above the
//! front left, a fill to the right and a rim behind. "Front" is +Z,
//! where a camera framing an object from the default side stands.
//! Each texel is the mean of 4 × 4 samples over it, as the sky's.
//! Values in W/(m²·sr); a white Lambert surface reflects 0.89 facing up,
//! 0.66 facing the front (+Z), 0.57 facing the back, 0.59–0.65 facing
//! the sides and 0.29 facing down (the test below).

use super::latlong;
use super::map::MapData;
use crate::base::Rgb;
use glam::DVec3;

/// The `map` value that selects the neutral studio instead of a file.
pub const STUDIO: &str = "studio";

/// Width of the generated map (height: half of it).
pub const WIDTH: u32 = 256;

/// A light panel: a disc on the sphere of directions with a soft edge.
struct Panel {
    /// Elevation above the horizon and azimuth from +Z towards +X [deg].
    elevation_deg: f64,
    azimuth_deg: f64,
    /// Angular radius where the falloff starts, and its width [deg].
    radius_deg: f64,
    edge_deg: f64,
    radiance: f64,
}

const PANELS: [Panel; 3] = [
    // Key: above the front left.
    Panel {
        elevation_deg: 40.0,
        azimuth_deg: -45.0,
        radius_deg: 14.0,
        edge_deg: 6.0,
        radiance: 3.5,
    },
    // Fill: the right, lower and larger.
    Panel {
        elevation_deg: 15.0,
        azimuth_deg: 70.0,
        radius_deg: 18.0,
        edge_deg: 8.0,
        radiance: 1.6,
    },
    // Rim: behind.
    Panel {
        elevation_deg: 30.0,
        azimuth_deg: 170.0,
        radius_deg: 12.0,
        edge_deg: 6.0,
        radiance: 2.5,
    },
];

fn unit(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.sin(), e.sin(), e.cos() * a.cos())
}

/// The room without its panels, by the direction's height `y`.
fn room(y: f64) -> f64 {
    if y >= 0.0 {
        0.45 + (0.6 - 0.45) * y
    } else {
        0.45 + (0.25 - 0.45) * (-y).sqrt()
    }
}

/// The studio's radiance from unit direction `d` (point-sampled).
pub fn radiance(d: DVec3) -> Rgb {
    let mut l = room(d.y);
    for p in &PANELS {
        let angle = d
            .dot(unit(p.elevation_deg, p.azimuth_deg))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        let t = ((angle - p.radius_deg) / p.edge_deg).clamp(0.0, 1.0);
        l += p.radiance * 0.5 * (1.0 + (std::f64::consts::PI * t).cos());
    }
    Rgb::splat(l)
}

/// The generated map.
pub fn map() -> MapData {
    let texels = latlong::supersampled_texels(WIDTH, radiance);
    MapData::new(STUDIO, WIDTH, WIDTH / 2, texels).expect("the built-in studio is a valid map")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Radiance a white Lambert surface with normal `n` reflects:
    /// `(1/π) ∫ L(ω) max(0, n·ω) dω`, by a midpoint rule over the map's
    /// own texel grid (the radiance varies over degrees, the grid is
    /// 1.4°).
    fn white_lambert(n: DVec3) -> f64 {
        let (w, h) = (512u32, 256u32);
        let mut sum = 0.0;
        for row in 0..h {
            let (top, bottom) = latlong::row_cos_bounds(row, h);
            let solid_angle = std::f64::consts::TAU / w as f64 * (top - bottom);
            for col in 0..w {
                let d = latlong::direction(
                    (col as f64 + 0.5) / w as f64,
                    (row as f64 + 0.5) / h as f64,
                );
                sum += radiance(d).x * n.dot(d).max(0.0) * solid_angle;
            }
        }
        sum / std::f64::consts::PI
    }

    #[test]
    fn every_side_is_lit_and_white_stays_below_one() {
        for (n, lo, hi) in [
            (DVec3::Y, 0.8, 1.0),
            (DVec3::Z, 0.6, 0.75),
            (DVec3::NEG_Z, 0.5, 0.65),
            (DVec3::X, 0.55, 0.75),
            (DVec3::NEG_X, 0.5, 0.7),
            (DVec3::NEG_Y, 0.25, 0.35),
        ] {
            let l = white_lambert(n);
            assert!((lo..hi).contains(&l), "n = {n}: {l}");
        }
    }

    #[test]
    fn the_key_panel_adds_its_radiance_and_the_room_is_grey() {
        let key = radiance(unit(40.0, -45.0));
        assert!((key.x - 3.5 - room(unit(40.0, -45.0).y)).abs() < 1e-9);
        let c = radiance(DVec3::new(0.3, -0.2, 0.9).normalize());
        assert_eq!(c.x, c.y);
        assert_eq!(c.y, c.z);
    }
}
