//! Measured reflectance: `model = "measured"` with `measured = NAME` (a
//! built-in MERL material, [`library`]) or `measured = "path.binary"` (a
//! MERL-format table, [`merl`]). Its `f_r` is the measured one in 1/sr;
//! `k_d`, `k_s` do not apply. Both sources are functions of Rusinkiewicz's
//! half/difference angles ([`coords`]); the built-in ones are Neural-BRDF
//! networks ([`network`]) evaluated in `f64` as defined, the truth the
//! GPU's filtered tables are checked against.

pub mod coords;
pub mod library;
pub mod merl;
pub mod network;

use crate::base::Rgb;
use crate::material::brdf::SurfaceFrame;
use glam::DVec3;
use std::path::Path;
use std::sync::Mutex;

/// One measured BRDF. Materials refer to it as `&'static` (the built-in
/// ones live in [`library`]; a file's table is read once per content and
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

/// Tables read from files, one per content (sha256).
static FILES: Mutex<Vec<&'static MeasuredBrdf>> = Mutex::new(Vec::new());

/// What `measured = TEXT` names: a built-in name, or (containing a `/` or
/// ending in `.binary`) a MERL file relative to `base_dir`.
pub fn resolve(text: &str, base_dir: &Path) -> Result<&'static MeasuredBrdf, String> {
    let is_path = text.contains('/') || text.contains('\\') || text.ends_with(".binary");
    if !is_path {
        return library::builtin(text);
    }
    let path = base_dir.join(text);
    let table = merl::MerlTable::read(&path)?;
    let mut files = FILES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(known) = files.iter().find(|m| match &m.source {
        Source::Table(t) => t.sha256 == table.sha256,
        Source::Network(_) => false,
    }) {
        return Ok(known);
    }
    let name = std::path::absolute(&path)
        .unwrap_or(path)
        .display()
        .to_string();
    let leaked: &'static MeasuredBrdf = Box::leak(Box::new(MeasuredBrdf {
        name,
        source: Source::Table(table),
    }));
    files.push(leaked);
    Ok(leaked)
}

/// The resolution `(n_h, n_d, n_φ)` of the GPU's tables when the scene
/// does not set one (`shading.measured_table`): MERL's own.
pub const DEFAULT_TABLE_RESOLUTION: [u32; 3] = [90, 90, 180];

/// The built-in material a new measured material starts as.
pub const DEFAULT_NAME: &str = "gold-metallic-paint";

/// [`DEFAULT_NAME`]'s BRDF.
pub fn default_brdf() -> &'static MeasuredBrdf {
    library::builtin(DEFAULT_NAME).expect("the default is a built-in name")
}
