//! Measured reflectance: `model = "measured"` with `measured = NAME` (a
//! built-in MERL material, [`library`]) or `measured = "path.binary"` (a
//! MERL-format table, [`merl`]). Its `f_r` is the measured one in 1/sr;
//! `k_d`, `k_s` do not apply. Both sources are functions of Rusinkiewicz's
//! half/difference angles ([`coords`]); the built-in ones are Neural-BRDF
//! networks ([`network`]) evaluated in `f64` as defined, the truth the
//! GPU's filtered tables are checked against. One measured BRDF and
//! where its values come from: [`MeasuredBrdf`], [`Source`] (`source.rs`).

pub mod coords;
pub mod library;
pub mod merl;
pub mod network;
mod source;

pub use source::{MeasuredBrdf, Source};

use std::path::Path;
use std::sync::Mutex;

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
