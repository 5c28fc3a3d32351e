//! The environment a mirror reflects: a sky gradient (lecture: "Mirror
//! BRDF" reflects `L_i` from the mirror direction; in a rasterizer that
//! radiance comes from an environment, not from other surfaces), or an
//! environment map (`[environment] map`, [`crate::environment`]), which
//! also lights every surface and is the background.

use crate::environment::EnvironmentMap;
use crate::scene::Rgb;
use glam::DVec3;

/// Radiance arriving from infinitely far away, by direction: `zenith`
/// straight up (+Y), `horizon` at y = 0, `ground` straight down, linear in
/// the direction's y in between; or, with a `map`, the map.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    pub zenith: Rgb,
    pub horizon: Rgb,
    pub ground: Rgb,
    /// `[environment] map`: replaces the gradient, lights every surface
    /// and is what camera rays that miss see.
    pub map: Option<EnvironmentMap>,
}

impl Environment {
    /// A constant environment of radiance `l`.
    pub fn uniform(l: Rgb) -> Self {
        Environment {
            zenith: l,
            horizon: l,
            ground: l,
            map: None,
        }
    }

    /// Radiance arriving from unit direction `d` (pointing away from the
    /// surface, towards the sky). Twin: `environment_radiance` in
    /// `shaders/shading.wgsl`.
    pub fn radiance(&self, d: DVec3) -> Rgb {
        if let Some(map) = &self.map {
            return map.radiance(d);
        }
        let y = d.y.clamp(-1.0, 1.0);
        if y >= 0.0 {
            self.horizon + (self.zenith - self.horizon) * y
        } else {
            self.horizon + (self.ground - self.horizon) * (-y)
        }
    }
}
