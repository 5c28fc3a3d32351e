//! The environment a mirror reflects: a sky gradient (lecture: "Mirror
//! BRDF" reflects `L_i` from the mirror direction; in a rasterizer that
//! radiance comes from an environment, not from other surfaces).

use crate::scene::Rgb;
use glam::DVec3;

/// Radiance arriving from infinitely far away, by direction: `zenith`
/// straight up (+Y), `horizon` at y = 0, `ground` straight down, linear in
/// the direction's y in between.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Environment {
    pub zenith: Rgb,
    pub horizon: Rgb,
    pub ground: Rgb,
}

impl Environment {
    /// A constant environment of radiance `l`.
    pub fn uniform(l: Rgb) -> Self {
        Environment {
            zenith: l,
            horizon: l,
            ground: l,
        }
    }

    /// Radiance arriving from unit direction `d` (pointing away from the
    /// surface, towards the sky). Twin: `environment_radiance` in
    /// `shaders/shading.wgsl`.
    pub fn radiance(&self, d: DVec3) -> Rgb {
        let y = d.y.clamp(-1.0, 1.0);
        if y >= 0.0 {
            self.horizon + (self.zenith - self.horizon) * y
        } else {
            self.horizon + (self.ground - self.horizon) * (-y)
        }
    }
}
