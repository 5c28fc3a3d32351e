//! Punctual lights in the contract's radiometric units.
//!
//! Each light answers one question for a surface point x: from which
//! direction ω_i does light arrive, and with what irradiance `E` on a
//! surface facing it ([`Light::incidence`]). The reflection equation then
//! adds `f_r(ω_i, ω_o) · E · cosθ_i · V` (V: the light's visibility, ray
//! traced by the reference, read from a shadow map on the GPU; see
//! [`ShadowSettings`] and `docs/shadows.md`).

use crate::scene::Rgb;
use glam::DVec3;

/// A light of the scene. Area lights ([`crate::scene::area_light`]) are
/// expanded into [`Light::AreaSample`] point lights when the scene is
/// assembled, so both renderers see the same list.
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
    /// One of the N point lights that stand in for an area light (lecture:
    /// "Area light sources ... replacing it with some point light
    /// sources"). It emits with the area light's cosine distribution:
    /// `I(ω) = L · (A/N) · max(0, n_l · ω)`, ω from the sample towards the
    /// surface, so `E = I(ω) / d²`.
    AreaSample {
        position: DVec3,
        /// Unit normal of the emitting side.
        normal: DVec3,
        /// `L · A / N` per channel [W/sr along the normal].
        intensity: Rgb,
        /// Index of the area light in [`crate::scene::Scene::area_lights`].
        area: usize,
        /// The area light's centre: where the GPU's shadow map shared by
        /// all its samples sits (the reference traces to `position`).
        center: DVec3,
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
            Light::AreaSample {
                position,
                normal,
                intensity,
                ..
            } => {
                let (wi, scale) = inverse_square(position - x, None);
                let cosine = normal.dot(-wi).max(0.0);
                Incidence {
                    wi,
                    irradiance: intensity * (scale * cosine),
                }
            }
        }
    }

    /// Whether the light asks for shadows.
    pub fn casts_shadows(&self) -> bool {
        match *self {
            Light::Point { shadows, .. }
            | Light::Directional { shadows, .. }
            | Light::Spot { shadows, .. }
            | Light::AreaSample { shadows, .. } => shadows,
        }
    }

    /// Turns shadows on or off.
    pub fn set_shadows(&mut self, on: bool) {
        match self {
            Light::Point { shadows, .. }
            | Light::Directional { shadows, .. }
            | Light::Spot { shadows, .. }
            | Light::AreaSample { shadows, .. } => *shadows = on,
        }
    }

    /// Where a shadow ray from a surface point ends: the light's position,
    /// or `None` for a directional light (the ray goes to infinity).
    pub fn position(&self) -> Option<DVec3> {
        match *self {
            Light::Directional { .. } => None,
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::AreaSample { position, .. } => Some(position),
        }
    }

    /// The light's kind.
    pub fn kind(&self) -> LightKind {
        match self {
            Light::Point { .. } => LightKind::Point,
            Light::Directional { .. } => LightKind::Directional,
            Light::Spot { .. } => LightKind::Spot,
            Light::AreaSample { .. } => LightKind::AreaSample,
        }
    }
}

/// How a light's shadow map is made and read on the GPU (the reference
/// ray-traces every shadow and ignores these). Derivations of the defaults:
/// `docs/shadows.md`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowSettings {
    /// Side of the (square) shadow map in texels; a point light (and an
    /// area light) has six of them, one per cube face.
    pub map_size: u32,
    /// Constant depth bias, in world units (metres) along the light ray:
    /// a receiver counts as lit when it is at most this much behind the
    /// occluder depth the map stores.
    pub bias: f64,
    /// Slope-scaled bias, in shadow-map texels: adds
    /// `slope_bias · texel · tanθ` to the constant bias (θ between the
    /// surface's geometric normal and the direction to the light, `texel`
    /// the world size of one map texel at the receiver).
    pub slope_bias: f64,
    /// Normal offset, in shadow-map texels: the map is read at
    /// `x + normal_offset · texel · n_g` (n_g the geometric normal turned
    /// towards the light).
    pub normal_offset: f64,
    pub filter: ShadowFilter,
    /// Whether `map_size` is the side or the upper bound of a side fitted
    /// to the screen (`src/gpu/shadow_fit.rs`).
    pub resolution: MapResolution,
    /// Whether the light's markers (`crate::scene::light_markers`) cast
    /// its shadow.
    pub markers: LightMarkers,
}

crate::base::named_enum!(
    /// What a light's markers do to its shadow (`shadow_markers`): the
    /// emissive or alpha-blended geometry whose box holds the light (a
    /// bulb, a lamp's glowing shade, an exporter's light gizmo), which
    /// would otherwise shadow everything the light reaches.
    #[derive(Default)]
    LightMarkers, "light-marker rule" {
        /// They let the light through (the default).
        #[default]
        Pass = "pass",
        /// They cast its shadow like any other surface.
        Cast = "cast",
    }
);

/// How a shadow map's side is chosen (`shadow_resolution`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MapResolution {
    /// `map_size` texels (the default).
    Fixed,
    /// Fitted to the screen footprint of what the light reaches, at most
    /// `map_size`: about `texels_per_pixel` map texels per pixel along
    /// each axis.
    Fit { texels_per_pixel: f64 },
}

impl MapResolution {
    /// Accepted `texels_per_pixel`.
    pub const TEXELS_PER_PIXEL: std::ops::RangeInclusive<f64> = 0.0625..=16.0;

    /// The scene file's name.
    pub fn name(self) -> &'static str {
        match self {
            MapResolution::Fixed => "fixed",
            MapResolution::Fit { .. } => "fit",
        }
    }
}

/// How the shadow map is filtered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShadowFilter {
    /// One hardware depth comparison at the nearest texel: V ∈ {0, 1}.
    None,
    /// Percentage-closer filtering: the mean of `kernel × kernel` nearest
    /// comparisons one texel apart (`kernel` odd).
    Pcf { kernel: u32 },
}

impl ShadowFilter {
    /// Side of the comparison footprint in texels (1 without filtering).
    pub fn kernel(self) -> u32 {
        match self {
            ShadowFilter::None => 1,
            ShadowFilter::Pcf { kernel } => kernel,
        }
    }

    /// The scene file's name.
    pub fn name(self) -> &'static str {
        match self {
            ShadowFilter::None => "none",
            ShadowFilter::Pcf { .. } => "pcf",
        }
    }
}

impl ShadowSettings {
    /// Default map side.
    pub const DEFAULT_MAP_SIZE: u32 = 2048;
    /// Default PCF kernel.
    pub const DEFAULT_PCF_KERNEL: u32 = 3;
    /// Smallest and largest map side accepted.
    pub const MAP_SIZES: std::ops::RangeInclusive<u32> = 16..=8192;
    /// Largest PCF kernel accepted.
    pub const MAX_PCF_KERNEL: u32 = 15;

    /// The normal offset (texels) that keeps a plane free of shadow acne at
    /// every incidence angle for `filter`: the `k × k` comparisons read
    /// texel centres up to `k/2` texels per axis from the lookup point, so
    /// the stored depth of the receiver's own plane is at most
    /// `(k/√2) · texel · tanθ` nearer the light; an offset `c` texels along
    /// the normal moves the lookup `c · texel / cosθ` nearer, which covers
    /// it for every θ < 90° when `c ≥ k/√2`. Half a texel more absorbs the
    /// curvature of tessellated surfaces and f32 rounding.
    pub fn default_normal_offset(filter: ShadowFilter) -> f64 {
        filter.kernel() as f64 / std::f64::consts::SQRT_2 + 0.5
    }
}

impl Default for ShadowSettings {
    fn default() -> Self {
        let filter = ShadowFilter::Pcf {
            kernel: Self::DEFAULT_PCF_KERNEL,
        };
        ShadowSettings {
            map_size: Self::DEFAULT_MAP_SIZE,
            bias: 0.0,
            slope_bias: 0.0,
            normal_offset: Self::default_normal_offset(filter),
            filter,
            resolution: MapResolution::Fixed,
            markers: LightMarkers::Pass,
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
    /// A point light standing in for part of an area light.
    AreaSample,
}

impl LightKind {
    /// Every kind.
    pub const ALL: [LightKind; 4] = [
        LightKind::Point,
        LightKind::Directional,
        LightKind::Spot,
        LightKind::AreaSample,
    ];

    /// The contract's name (an area sample is a part of an `area` light).
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Directional => "directional",
            LightKind::Spot => "spot",
            LightKind::AreaSample => "area",
        }
    }

    /// A stable small integer shared with WGSL (`Light.kind`).
    pub fn id(self) -> u32 {
        match self {
            LightKind::Point => 0,
            LightKind::Directional => 1,
            LightKind::Spot => 2,
            LightKind::AreaSample => 3,
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
