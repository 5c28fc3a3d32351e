//! Punctual lights in the contract's radiometric units.
//!
//! Each light answers one question for a surface point x: from which
//! direction ω_i does light arrive, and with what irradiance `E` on a
//! surface facing it ([`Light::incidence`]). The reflection equation then
//! adds `f_r(ω_i, ω_o) · E · cosθ_i`.

use crate::scene::Rgb;
use glam::DVec3;

/// A light of the scene. Area lights (issue #5) are expanded into point
/// lights before rendering, so renderers only see these kinds.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Radiant intensity `I` [W/sr] per channel; `E = I / d²`.
    Point {
        position: DVec3,
        intensity: Rgb,
        /// glTF `range`: beyond it the light contributes nothing.
        range: Option<f64>,
        shadows: bool,
    },
    /// Irradiance `E` [W/m²] on a surface facing the light.
    Directional {
        /// Unit direction the light travels (world space).
        direction: DVec3,
        irradiance: Rgb,
        shadows: bool,
    },
    /// A point light restricted to a cone with glTF's smooth falloff.
    Spot {
        position: DVec3,
        /// Unit direction of the cone axis (the way the light travels).
        direction: DVec3,
        /// Radiant intensity on the axis [W/sr].
        intensity: Rgb,
        inner_cone_deg: f64,
        outer_cone_deg: f64,
        range: Option<f64>,
        shadows: bool,
    },
}

/// Light arriving at a point: unit direction towards the light and the
/// irradiance on a surface facing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incidence {
    /// ω_i: from the surface towards the light.
    pub wi: DVec3,
    /// `E_l` [W/m²] on a surface perpendicular to ω_i.
    pub irradiance: Rgb,
}

impl Light {
    /// The light's contribution at `x`.
    pub fn incidence(&self, x: DVec3) -> Incidence {
        match *self {
            Light::Directional {
                direction,
                irradiance,
                ..
            } => Incidence {
                wi: -direction,
                irradiance,
            },
            Light::Point {
                position,
                intensity,
                range,
                ..
            } => {
                let (wi, scale) = inverse_square(position - x, range);
                Incidence {
                    wi,
                    irradiance: intensity * scale,
                }
            }
            Light::Spot {
                position,
                direction,
                intensity,
                inner_cone_deg,
                outer_cone_deg,
                range,
                ..
            } => {
                let (wi, scale) = inverse_square(position - x, range);
                let cone = spot_attenuation(-wi.dot(direction), inner_cone_deg, outer_cone_deg);
                Incidence {
                    wi,
                    irradiance: intensity * (scale * cone),
                }
            }
        }
    }

    /// Whether the light asks for shadows.
    pub fn casts_shadows(&self) -> bool {
        match *self {
            Light::Point { shadows, .. }
            | Light::Directional { shadows, .. }
            | Light::Spot { shadows, .. } => shadows,
        }
    }

    /// The light's kind.
    pub fn kind(&self) -> LightKind {
        match self {
            Light::Point { .. } => LightKind::Point,
            Light::Directional { .. } => LightKind::Directional,
            Light::Spot { .. } => LightKind::Spot,
        }
    }
}

/// The kinds of punctual light; the GPU compiles code only for the kinds a
/// scene has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LightKind {
    Point,
    Directional,
    Spot,
}

impl LightKind {
    /// The contract's name.
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Directional => "directional",
            LightKind::Spot => "spot",
        }
    }

    /// A stable small integer shared with WGSL (`Light.kind`).
    pub fn id(self) -> u32 {
        match self {
            LightKind::Point => 0,
            LightKind::Directional => 1,
            LightKind::Spot => 2,
        }
    }
}

/// Unit direction along `to_light` and the factor `1/d²`, times glTF's
/// recommended range window `clamp(1 − (d/range)⁴, 0, 1)²` when a range is
/// given (KHR_lights_punctual, "Range Property").
/// A point exactly at the light gets no light instead of an infinity.
pub fn inverse_square(to_light: DVec3, range: Option<f64>) -> (DVec3, f64) {
    let d2 = to_light.length_squared();
    if d2 == 0.0 {
        return (DVec3::Y, 0.0);
    }
    let d = d2.sqrt();
    let window = match range {
        Some(r) => {
            let q = d / r;
            (1.0 - q * q * q * q).clamp(0.0, 1.0).powi(2)
        }
        None => 1.0,
    };
    (to_light / d, window / d2)
}

/// glTF's spot cone attenuation (KHR_lights_punctual, "Inner and Outer Cone
/// Angles"): linear in cosθ between the cones, squared.
/// `cos_angle` is the cosine between the cone axis and the direction from
/// the light to the point.
pub fn spot_attenuation(cos_angle: f64, inner_cone_deg: f64, outer_cone_deg: f64) -> f64 {
    let cos_outer = outer_cone_deg.to_radians().cos();
    let cos_inner = inner_cone_deg.to_radians().cos();
    // The spec's 0.001 floor keeps the scale finite when the cones coincide.
    let scale = 1.0 / (cos_inner - cos_outer).max(0.001);
    let offset = -cos_outer * scale;
    let t = (cos_angle * scale + offset).clamp(0.0, 1.0);
    t * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_light_falls_off_with_inverse_square() {
        let light = Light::Point {
            position: DVec3::new(0.0, 2.0, 0.0),
            intensity: Rgb::splat(8.0),
            range: None,
            shadows: false,
        };
        let inc = light.incidence(DVec3::ZERO);
        assert_eq!(inc.wi, DVec3::Y);
        assert!((inc.irradiance - Rgb::splat(2.0)).length() < 1e-12);
    }

    #[test]
    fn spot_cone_is_full_inside_and_zero_outside() {
        assert_eq!(spot_attenuation(1.0, 10.0, 20.0), 1.0);
        assert_eq!(spot_attenuation(30f64.to_radians().cos(), 10.0, 20.0), 0.0);
        let mid = spot_attenuation(15f64.to_radians().cos(), 10.0, 20.0);
        assert!(mid > 0.0 && mid < 1.0);
    }
}
