//! Checks of single values shared by the assembly steps; each error names
//! the key.

use crate::scene::Rgb;
use glam::DVec3;

pub fn finite_vec(key: &str, v: [f64; 3]) -> std::result::Result<DVec3, String> {
    let d = DVec3::from_array(v);
    if d.is_finite() {
        Ok(d)
    } else {
        Err(format!("{key} = {v:?} is not finite"))
    }
}

pub fn unit_vec(key: &str, v: [f64; 3]) -> std::result::Result<DVec3, String> {
    finite_vec(key, v)?
        .try_normalize()
        .ok_or_else(|| format!("{key} = {v:?} has no direction (zero length)"))
}

use crate::scene::MAX_COORDINATE;

/// The range rule of every radiance source ([`crate::base::range`]).
pub use crate::base::range::MAX_RADIANCE;

/// `v` as a position the GPU can compute with ([`MAX_COORDINATE`]).
pub fn gpu_coordinate(key: &str, v: DVec3) -> std::result::Result<DVec3, String> {
    if v.abs().max_element() > MAX_COORDINATE {
        return Err(format!(
            "{key} = [{:e}, {:e}, {:e}] is beyond ±{MAX_COORDINATE:e}: the GPU squares distances in f32 (largest 3.4e38), so coordinates this large overflow; scale the scene down",
            v.x, v.y, v.z
        ));
    }
    Ok(v)
}

pub fn non_negative(key: &str, c: Rgb) -> std::result::Result<Rgb, String> {
    if !(c.is_finite() && c.min_element() >= 0.0) {
        return Err(format!(
            "{key} = [{}, {}, {}] must be finite and ≥ 0",
            c.x, c.y, c.z
        ));
    }
    if c.max_element() > MAX_RADIANCE {
        return Err(format!(
            "{key} = [{:e}, {:e}, {:e}] is over {MAX_RADIANCE:e}: the GPU computes in f32 (largest 3.4e38) and multiplies it by BRDF values up to about 4e16, so it would overflow to Inf; scale the scene's units down",
            c.x, c.y, c.z
        ));
    }
    Ok(c)
}

pub fn range(v: Option<f64>) -> std::result::Result<Option<f64>, String> {
    match v {
        Some(r) if !(r.is_finite() && r > 0.0) => Err(format!("range = {r} must be positive")),
        other => Ok(other),
    }
}
