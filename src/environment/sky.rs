//! The built-in sky (`[environment] map = "sky"`): a generated 256 × 128
//! lat-long map, so a scene can be lit by a sky without a file, and
//! rendered by exactly the code a file map takes.
//!
//! Above the horizon a blue gradient, brightening towards the horizon
//! (`L = zenith + (horizon − zenith)(1 − y)⁴`), with a sun of angular
//! radius 2.5° and radiance [`SUN_RADIANCE`] towards [`sun_direction`] and a
//! glow around it; below, a dim ground that darkens towards the nadir.
//! Each texel is the mean of 4 × 4 samples over it (uniform in `(u, v)`),
//! so the sun's edge is antialiased. Values in W/(m²·sr); the sky alone
//! gives about 3 W/m² on a surface facing up, the sun about 8 more.

use super::latlong;
use super::map::MapData;
use crate::base::Rgb;
use glam::DVec3;

/// The `map` value that selects the procedural sky instead of a file.
pub const SKY: &str = "sky";

/// Width of the generated map (height: half of it).
pub const WIDTH: u32 = 256;
/// Radiance of the sun's disc.
pub const SUN_RADIANCE: f64 = 1400.0;
/// Angular radius of the sun's disc.
pub const SUN_RADIUS_DEG: f64 = 2.5;

/// Unit direction towards the sun: 35° above the horizon, from the
/// front right (+X, +Z).
pub fn sun_direction() -> DVec3 {
    let elevation = 35f64.to_radians();
    let azimuth = 40f64.to_radians();
    DVec3::new(
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
        elevation.cos() * azimuth.cos(),
    )
}

/// The sky's radiance from unit direction `d` (point-sampled).
pub fn radiance(d: DVec3) -> Rgb {
    let zenith = Rgb::new(0.10, 0.25, 0.65);
    let horizon = Rgb::new(0.85, 0.90, 1.0);
    let ground = Rgb::new(0.20, 0.17, 0.13);
    let y = d.y;
    let angle = d.dot(sun_direction()).clamp(-1.0, 1.0).acos();
    if y >= 0.0 {
        let sky = zenith + (horizon - zenith) * (1.0 - y).powi(4);
        let sun = if angle < SUN_RADIUS_DEG.to_radians() {
            Rgb::new(1.0, 0.95, 0.85) * SUN_RADIANCE
        } else {
            Rgb::ZERO
        };
        let glow = Rgb::new(1.0, 0.8, 0.5) * (2.0 * (-angle / 0.12).exp());
        sky + sun + glow
    } else {
        ground * (1.0 + y * 0.6)
    }
}

/// The generated map.
pub fn map() -> MapData {
    let texels = latlong::supersampled_texels(WIDTH, radiance);
    MapData::new(SKY, WIDTH, WIDTH / 2, texels).expect("the built-in sky is a valid map")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sun_is_where_it_is_said_to_be_and_brightest() {
        let map = map();
        let at_sun = map.lookup(sun_direction());
        assert!(at_sun.x > 0.5 * SUN_RADIANCE, "{at_sun}");
        let up = map.lookup(DVec3::Y);
        assert!(up.z > up.x && up.z < 1.0, "{up}");
        assert!(map.lookup(DVec3::NEG_Y).x < 0.2);
    }
}
