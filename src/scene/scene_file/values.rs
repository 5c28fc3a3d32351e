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

pub fn non_negative(key: &str, c: Rgb) -> std::result::Result<Rgb, String> {
    if c.is_finite() && c.min_element() >= 0.0 {
        Ok(c)
    } else {
        Err(format!(
            "{key} = [{}, {}, {}] must be finite and ≥ 0",
            c.x, c.y, c.z
        ))
    }
}

pub fn range(v: Option<f64>) -> std::result::Result<Option<f64>, String> {
    match v {
        Some(r) if !(r.is_finite() && r > 0.0) => Err(format!("range = {r} must be positive")),
        other => Ok(other),
    }
}
