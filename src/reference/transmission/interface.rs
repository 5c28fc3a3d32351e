//! What happens where a ray meets the boundary of a volume
//! (`KHR_materials_volume`): the media a ray is inside, the index of
//! refraction on each side (per wavelength with `KHR_materials_dispersion`),
//! Fresnel's split between the refracted and the reflected ray at a smooth
//! interface, and Beer–Lambert attenuation along a segment.

use crate::base::Rgb;
use crate::material::Material;
use crate::material::brdf::gltf_layers::transmission::dispersion_ior;
use glam::DVec3;

/// A homogeneous medium: the inside of a closed mesh whose material has
/// `thickness > 0` (and `transmission > 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    /// The mesh that bounds it.
    pub mesh: usize,
    /// `n_d` (the material's `ior`) and `dispersion` (`20 / V_d`).
    pub ior: f64,
    pub dispersion: f64,
    pub attenuation_color: Rgb,
    pub attenuation_distance: f64,
}

impl Medium {
    /// The medium behind a surface of `material` on mesh `mesh`.
    pub fn of(material: &Material, mesh: usize) -> Medium {
        let l = &material.layers;
        Medium {
            mesh,
            ior: l.ior,
            dispersion: l.dispersion,
            attenuation_color: l.attenuation_color,
            attenuation_distance: l.attenuation_distance,
        }
    }

    /// Its index of refraction at `lambda` nm (`None`: the material's
    /// `ior`, `n_d`, used where no dispersive medium has split the ray).
    /// `ior = 0` (the specular-glossiness mode) is taken as 1.
    pub fn ior_at(&self, lambda: Option<f64>) -> f64 {
        let n = match lambda {
            Some(l) => dispersion_ior(self.ior, self.dispersion, l),
            None => self.ior,
        };
        n.max(1.0)
    }

    /// Beer–Lambert over a path of length `d` inside:
    /// `attenuation_color^(d / attenuation_distance)` per channel
    /// (`KHR_materials_volume`, "Attenuation"), 1 for a clear medium
    /// (`attenuation_distance = ∞`), 0 for a zero channel over `d > 0`.
    pub fn transmittance(&self, d: f64) -> Rgb {
        beer_lambert(self.attenuation_color, self.attenuation_distance, d)
    }
}

/// `c^(d / distance)` per channel: the transmittance of a path of length
/// `d` through a medium keeping `c` after `distance`.
pub fn beer_lambert(c: Rgb, distance: f64, d: f64) -> Rgb {
    if distance == f64::INFINITY || d <= 0.0 {
        return Rgb::ONE;
    }
    let k = d / distance;
    Rgb::new(c.x.powf(k), c.y.powf(k), c.z.powf(k))
}

/// The media a ray is inside, innermost last (nested volumes: a liquid in
/// a glass). Outside every volume the index is 1 (air).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Media(pub Vec<Medium>);

impl Media {
    /// The innermost medium, if any.
    pub fn current(&self) -> Option<&Medium> {
        self.0.last()
    }

    /// The index of refraction the ray travels in (1 outside every volume).
    pub fn ior_at(&self, lambda: Option<f64>) -> f64 {
        self.current().map_or(1.0, |m| m.ior_at(lambda))
    }

    /// Entering `medium`.
    pub fn entered(&self, medium: Medium) -> Media {
        let mut m = self.clone();
        m.0.push(medium);
        m
    }

    /// Leaving the volume of mesh `mesh` (the innermost one of that mesh;
    /// unchanged if the ray was not inside it, e.g. a camera inside a
    /// volume).
    pub fn left(&self, mesh: usize) -> Media {
        let mut m = self.clone();
        if let Some(at) = m.0.iter().rposition(|x| x.mesh == mesh) {
            m.0.remove(at);
        }
        m
    }

    /// Whether the ray is inside the volume of mesh `mesh`.
    pub fn inside(&self, mesh: usize) -> bool {
        self.0.iter().any(|x| x.mesh == mesh)
    }
}

/// The mirror direction of `wi` (pointing away from the surface) about
/// `n`: `2 (n·wi) n − wi`.
pub fn reflect(wi: DVec3, n: DVec3) -> DVec3 {
    2.0 * n.dot(wi) * n - wi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beer_lambert_keeps_the_colour_after_the_distance() {
        let c = Rgb::new(0.5, 0.25, 1.0);
        assert_eq!(beer_lambert(c, 2.0, 2.0), c);
        let half = beer_lambert(c, 2.0, 1.0);
        assert!(
            (half - Rgb::new(0.5f64.sqrt(), 0.5, 1.0))
                .abs()
                .max_element()
                < 1e-15
        );
        assert_eq!(beer_lambert(c, f64::INFINITY, 10.0), Rgb::ONE);
        assert_eq!(beer_lambert(Rgb::ZERO, 1.0, 1e-9), Rgb::ZERO);
    }

    #[test]
    fn media_nest_and_unnest() {
        let glass = Medium {
            mesh: 0,
            ior: 1.5,
            dispersion: 0.0,
            attenuation_color: Rgb::ONE,
            attenuation_distance: f64::INFINITY,
        };
        let water = Medium {
            mesh: 1,
            ior: 1.33,
            ..glass
        };
        let air = Media::default();
        assert_eq!(air.ior_at(None), 1.0);
        let both = air.entered(glass).entered(water);
        assert_eq!(both.ior_at(None), 1.33);
        assert_eq!(both.left(1).ior_at(None), 1.5);
        assert_eq!(air.left(3), air);
    }
}
