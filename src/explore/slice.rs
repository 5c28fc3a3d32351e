//! The lecture's picture of a BRDF: "a slice of the 6D function ... Given
//! point x and given incident direction ω_i, show 2D polar plot (intensity
//! as length of vector from origin)". The slice is the plane of incidence.
//!
//! Outgoing directions are `ω_o(θ_o) = (sin θ_o cos φ_i, sin θ_o sin φ_i,
//! cos θ_o)` for a *signed* `θ_o ∈ [−90°, 90°]`: positive on the light's side
//! (`φ_o = φ_i`), negative on the mirror side (`φ_o = φ_i + π`), so the
//! mirror direction is `θ_o = −θ_i`.

use super::part::MaterialPart;
use super::{Channel, direction, frame};
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;
use std::str::FromStr;

/// What the radius of the polar plot is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quantity {
    /// `f_r · cos θ_o` [1/sr]: reflected radiance per unit irradiance
    /// from ω_i, i.e. `dL_o / dE_i` weighted by the projected area the
    /// viewer sees; the lecture's polar figures draw this (the Lambert
    /// lobe is the circle `(k_d/π) cos θ_o` touching the origin). Default.
    #[default]
    ProjectedFr,
    /// `f_r` [1/sr] itself (the Lambert lobe is a half circle of radius
    /// `k_d/π` around the origin).
    Fr,
}

impl Quantity {
    /// The name `--quantity` takes.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::ProjectedFr => "f_r-cos",
            Quantity::Fr => "f_r",
        }
    }

    /// What the plot says the radius is.
    pub fn describe(self) -> &'static str {
        match self {
            Quantity::ProjectedFr => {
                "radius: f_r·cos θ_o [1/sr], reflected radiance per unit irradiance, projected"
            }
            Quantity::Fr => "radius: f_r [1/sr]",
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Quantity {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "f_r-cos" | "f_r_cos" | "projected" => Ok(Quantity::ProjectedFr),
            "f_r" | "fr" => Ok(Quantity::Fr),
            _ => Err(format!("unknown quantity `{s}`; expected f_r-cos or f_r")),
        }
    }
}

/// One model's slice: `(θ_o signed, radians; value)` in ascending θ_o, and
/// the reflectance of a Dirac lobe in the mirror direction, if the model
/// has one (the ideal mirror; its `f_r` there is infinite). For a
/// material that lets light through, `transmitted` is the BTDF's slice
/// below the surface, `|θ_o| > 90°` (`±180°` straight down, the sign the
/// side as above: the light's straight line `−ω_i` at `θ_i − 180°`), in
/// order along the curve from the mirror side's horizon (−90°) through
/// straight down to the light side's (+90°); empty otherwise.
#[derive(Clone, Debug)]
pub struct Slice {
    pub points: Vec<(f64, f64)>,
    pub dirac: Option<f64>,
    pub transmitted: Vec<(f64, f64)>,
}

/// A point of the polar plot: signed `θ` (radians) at `radius`, with the
/// normal up (`+y`) and the light's side right (`+x`), the same in
/// `gonio brdf` and the viewer.
pub fn polar(radius: f64, theta: f64) -> [f64; 2] {
    [radius * theta.sin(), radius * theta.cos()]
}

/// Where the plot marks ω_i at `radius`: `θ = +θ_i`, the light's side.
/// (The viewer once drew it along the reflection lobe.)
pub fn light_marker(theta_i: f64, radius: f64) -> [f64; 2] {
    polar(radius, theta_i)
}

/// Where the plot marks the mirror direction at `radius`: `θ = −θ_i`.
pub fn mirror_marker(theta_i: f64, radius: f64) -> [f64; 2] {
    polar(radius, -theta_i)
}

impl Slice {
    /// The lobe as polar-plot points (non-finite values left out).
    pub fn polar_points(&self) -> Vec<[f64; 2]> {
        finite_polar(&self.points)
    }

    /// The transmitted lobe as polar-plot points (below the surface).
    pub fn transmitted_polar_points(&self) -> Vec<[f64; 2]> {
        finite_polar(&self.transmitted)
    }

    /// The largest value of either lobe (and the Dirac's reflectance).
    pub fn peak(&self) -> f64 {
        self.points
            .iter()
            .chain(&self.transmitted)
            .map(|p| p.1)
            .chain(self.dirac)
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }
}

fn finite_polar(points: &[(f64, f64)]) -> Vec<[f64; 2]> {
    points
        .iter()
        .filter(|(_, v)| v.is_finite())
        .map(|&(t, v)| polar(v, t))
        .collect()
}

/// The slice of `material` for light at `theta_i` (radians) in the plane
/// `φ = phi_i`.
pub fn slice<'a>(
    material: impl Into<MaterialPart<'a>>,
    theta_i: f64,
    phi_i: f64,
    quantity: Quantity,
    channel: Channel,
) -> Slice {
    let material = material.into();
    let upper = |part: MaterialPart| -> Vec<(f64, f64)> {
        let wi = direction(theta_i, phi_i);
        let f = frame();
        sample_angles(theta_i)
            .into_iter()
            .map(|t| {
                let wo = direction(t.abs(), if t < 0.0 { phi_i + PI } else { phi_i });
                let mut v = channel.of(part.f_r(wi, wo, &f));
                if quantity == Quantity::ProjectedFr {
                    v *= wo.z.max(0.0);
                }
                (t, v)
            })
            .collect()
    };
    let points = upper(material);
    // The far side is evaluated at the directions mirrored through the
    // surface (`Side::Transmitted`): the upper sample at signed t is the
    // direction below at (π − |t|) on the same side.
    let transmitted = if material.transmits() {
        upper(material.transmitted())
            .into_iter()
            .map(|(t, v)| (if t < 0.0 { -PI - t } else { PI - t }, v))
            .collect()
    } else {
        Vec::new()
    };
    let dirac = material
        .is_dirac()
        .then(|| channel.of(material.dirac(theta_i.cos())));
    Slice {
        points,
        dirac,
        transmitted,
    }
}

/// Signed θ_o samples: every 0.25°, plus points that close in geometrically
/// (to 10⁻⁶ rad) on the mirror direction `−θ_i` (narrow lobes) and on the
/// horizons ±90° (off-specular peaks of microfacet lobes at grazing).
pub fn sample_angles(theta_i: f64) -> Vec<f64> {
    let mut t: Vec<f64> = (0..=720)
        .map(|k| (k as f64 * 0.25 - 90.0).to_radians())
        .collect();
    let offsets: Vec<f64> = (0..=120)
        .map(|k| 10f64.powf(-6.0 + k as f64 / 20.0))
        .collect();
    let mirror = -theta_i;
    t.push(mirror);
    for &o in &offsets {
        t.extend([mirror - o, mirror + o, FRAC_PI_2 - o, o - FRAC_PI_2]);
    }
    t.retain(|x| x.abs() <= FRAC_PI_2);
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{Material, ReflectanceModel};

    #[test]
    fn lambert_slice_is_a_circle() {
        let m = Material::new("l", ReflectanceModel::Lambert);
        let s = slice(&m, 0.5, 0.0, Quantity::ProjectedFr, Channel::Mean);
        for (t, v) in s.points {
            assert!((v - 0.8 / PI * t.cos()).abs() < 1e-15);
        }
        assert!(s.dirac.is_none());
    }

    #[test]
    fn samples_hit_the_mirror_direction() {
        let t = sample_angles(0.3);
        assert!(t.contains(&-0.3));
        assert!(t.windows(2).all(|p| p[0] < p[1]));
        assert_eq!((t[0], *t.last().unwrap()), (-FRAC_PI_2, FRAC_PI_2));
    }

    /// The markers land where the directions say (the viewer once
    /// drew the light along the lobe and the mirror on the light's side).
    /// ω_i at φ_i = 0 has x = sin θ_i > 0; a glossy lobe peaks at the
    /// mirror direction, so its farthest point and the mirror marker point
    /// the same way, and the light marker the opposite way in x.
    #[test]
    fn light_and_mirror_markers_point_where_the_directions_are() {
        let mut m = Material::new("p", ReflectanceModel::PhongNormalized);
        (m.k_d, m.k_s, m.k_e) = (crate::base::Rgb::ZERO, crate::base::Rgb::ONE, 200.0);
        let theta_i = 40f64.to_radians();
        // f_r itself peaks at the mirror direction (f_r·cos θ_o a little
        // towards the normal).
        let s = slice(&m, theta_i, 0.0, Quantity::Fr, Channel::Mean);
        let peak = s
            .polar_points()
            .into_iter()
            .max_by(|a, b| a[0].hypot(a[1]).total_cmp(&b[0].hypot(b[1])))
            .unwrap();
        let r = peak[0].hypot(peak[1]);
        let light = light_marker(theta_i, r);
        let mirror = mirror_marker(theta_i, r);
        let wi = super::super::direction(theta_i, 0.0);
        assert!((light[0] - r * wi.x).abs() < 1e-12 && (light[1] - r * wi.z).abs() < 1e-12);
        let angle = |p: [f64; 2]| p[0].atan2(p[1]);
        assert!(
            (angle(peak) - angle(mirror)).abs() < 1e-3,
            "{peak:?} vs {mirror:?}"
        );
        assert!(light[0] > 0.0 && mirror[0] < 0.0 && peak[0] < 0.0);
    }
}
