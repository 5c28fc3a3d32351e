//! One measured BRDF ([`MeasuredBrdf`]) and where its values come from
//! ([`Source`]): the type every material refers to, below the library and
//! the file reader that make them.

use super::{coords, merl, network};
use crate::base::Rgb;
use crate::material::brdf::SurfaceFrame;
use glam::DVec3;

/// One measured BRDF. Materials refer to it as `&'static` (the built-in
/// ones live in [`library`](super::library); a file's table is read once per content and
/// kept for the program's life), so a material stays a small value.
#[derive(Debug)]
pub struct MeasuredBrdf {
    /// The built-in name, or the file's path as it was resolved.
    pub name: String,
    pub source: Source,
}

/// Where the values come from.
#[derive(Debug)]
pub enum Source {
    /// A built-in Neural-BRDF network.
    Network(Box<network::Network>),
    /// A MERL-format table read from a file.
    Table(merl::MerlTable),
}

/// Two measured BRDFs are the same when they are the same object: one per
/// built-in name and one per file content.
impl PartialEq for MeasuredBrdf {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

impl MeasuredBrdf {
    /// `f_r` [1/sr] for `ω_i = wi`, `ω_o = wo` above the surface (the
    /// caller, `Material::f_r`, returns 0 below either horizon).
    pub fn f_r(&self, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        let c = coords::half_diff(wi, wo, frame);
        self.f_r_half_diff(&c)
    }

    /// `f_r` [1/sr] at given half/difference coordinates.
    pub fn f_r_half_diff(&self, c: &coords::HalfDiff) -> Rgb {
        match &self.source {
            Source::Network(n) => n.f_r(c.h, c.d),
            Source::Table(t) => t.f_r(c.theta_h, c.theta_d, c.phi_d),
        }
    }

    /// What the scene-file key `measured` says for it.
    pub fn key_text(&self) -> &str {
        &self.name
    }
}
