//! Material-parameter exploration: the numbers and pictures behind
//! `gonio brdf`.
//!
//! The lecture shows a BRDF "as a slice of the 6D function": for a given
//! incident direction, a 2D polar plot with "intensity as length of vector
//! from origin" ([`slice`](mod@slice)); it states energy conservation as
//! `∫ f_r cos θ_o dω_o ≤ 1` for every incident direction ([`albedo`]); and it
//! mentions the "Standardized Gloss Model" of industry, reflection measured
//! at a few angles in the plane of incidence ([`gloss`]). This module
//! computes all three from any [`Material`], with the `f64` reference BRDFs
//! (`Material::f_r`), and draws them ([`plot`]).
//!
//! Geometry everywhere in this module: the surface normal is `n = +Z`, the
//! tangent `t = +X` (the direction σ_x of anisotropic Ward runs along), the
//! bitangent `b = +Y`. Polar angles θ are measured from the normal, azimuths
//! φ from the tangent towards the bitangent, so a direction is
//! `(sin θ cos φ, sin θ sin φ, cos θ)` ([`geometry`]).

pub mod albedo;
pub mod cli;
pub mod geometry;
pub mod gloss;
pub mod halfdiff;
pub mod halfdiff_plot;
pub mod part;
pub mod plot;
pub mod quadrature;
pub mod slice;
pub mod spec;
pub mod table;

pub use albedo::{AlbedoEstimate, directional_albedo};
pub use geometry::{direction, frame};
pub use part::{LayerChoice, MaterialPart, Side};

use crate::material::Material;
use crate::scene::Rgb;
use std::fmt;
use std::str::FromStr;

/// A material with the name it is shown under (legend, tables, output).
#[derive(Clone, Debug)]
pub struct Labelled {
    pub label: String,
    pub material: Material,
}

/// How an RGB BRDF value becomes the one number a plot draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Channel {
    /// `(r + g + b) / 3`: the default, because it treats the three linear
    /// channels alike and equals each of them for grey materials, so a
    /// plotted albedo of 1 means an albedo of 1 in every channel.
    #[default]
    Mean,
    /// Relative luminance `Y = 0.2126 r + 0.7152 g + 0.0722 b` (Rec. 709 /
    /// linear sRGB primaries, the contract's colour space): what a
    /// photometric instrument such as a gloss meter weighs by.
    Luminance,
    R,
    G,
    B,
}

impl Channel {
    /// All channels, in the order `--channel` lists them.
    pub const ALL: [Channel; 5] = [
        Channel::Mean,
        Channel::Luminance,
        Channel::R,
        Channel::G,
        Channel::B,
    ];

    /// The name `--channel` takes.
    pub fn name(self) -> &'static str {
        match self {
            Channel::Mean => "mean",
            Channel::Luminance => "luminance",
            Channel::R => "r",
            Channel::G => "g",
            Channel::B => "b",
        }
    }

    /// What the plots say the numbers are.
    pub fn describe(self) -> &'static str {
        match self {
            Channel::Mean => "mean of R, G, B",
            Channel::Luminance => "luminance Y (Rec. 709)",
            Channel::R => "red channel",
            Channel::G => "green channel",
            Channel::B => "blue channel",
        }
    }

    /// The channel's value of `c`.
    pub fn of(self, c: Rgb) -> f64 {
        match self {
            Channel::Mean => (c.x + c.y + c.z) / 3.0,
            Channel::Luminance => 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z,
            Channel::R => c.x,
            Channel::G => c.y,
            Channel::B => c.z,
        }
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Channel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                format!("unknown channel `{s}`; expected one of mean, luminance, r, g, b")
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn directions_follow_the_frame() {
        let f = frame();
        assert_eq!((f.n, f.t, f.b), (DVec3::Z, DVec3::X, DVec3::Y));
        assert!((direction(0.0, 1.0) - DVec3::Z).length() < 1e-15);
        let d = direction(std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2);
        assert!((d - DVec3::Y).length() < 1e-15);
    }

    #[test]
    fn channels_reduce_rgb() {
        let c = Rgb::new(0.3, 0.6, 0.9);
        assert!((Channel::Mean.of(c) - 0.6).abs() < 1e-15);
        assert!((Channel::Luminance.of(Rgb::ONE) - 1.0).abs() < 1e-12);
        assert_eq!(Channel::B.of(c), 0.9);
        assert_eq!("luminance".parse::<Channel>(), Ok(Channel::Luminance));
        assert!("alpha".parse::<Channel>().is_err());
    }
}
