//! New `[[lights]]` entries and changes of a light's kind, for the panel's
//! *Add* and *kind* controls and `--edit lights.add=KIND`,
//! `lights.N.kind=KIND`.
//!
//! A light is reduced to what every kind shares: where it sits, which way
//! it shines, and the irradiance `E` it puts on a surface facing it at the
//! point the camera looks at (the orbit's target, where the user is
//! looking). The new kind is built to keep those three, so retyping a
//! light moves neither its place nor (about) its brightness where one
//! looks:
//! - point, spot: `I = E · d²` (inverse square; on the spot's axis);
//! - directional: `E` itself;
//! - area: on its axis and far away an area light is a point of intensity
//!   `L · A` (its cosine lobe's peak), so `L = E · d² / A`.
//!
//! Entries are written as the scene file's keys and read back through its
//! schema, so they are exactly what a file holding them would give.

use crate::scene::scene_file::LightEntry;
use crate::scene::scene_file::schema::AreaEntry;
use glam::DVec3;
use serde::Deserialize;
use std::f64::consts::PI;

/// The kinds the scene file knows, in the panel's order.
pub const KINDS: [&str; 4] = ["point", "spot", "directional", "area"];

/// Irradiance a new light puts on the target [W/m²]: the default light's
/// (`scene_file::default_light`, 3 W/m²).
const NEW_IRRADIANCE: f64 = 3.0;
/// A new spot's cones: wide enough that its pool is plainly visible.
const NEW_INNER_CONE_DEG: f64 = 15.0;
const NEW_OUTER_CONE_DEG: f64 = 25.0;

/// What every kind shares: a place, an axis, the irradiance at the target.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Essentials {
    position: DVec3,
    /// Unit; the way the light travels (an area light's normal).
    axis: DVec3,
    /// `E` per channel on a surface facing the light at the target.
    irradiance: [f64; 3],
    /// Distance from `position` to the target (> 0).
    distance: f64,
}

/// A new light of `kind` for a camera at `eye` looking at `target`, where
/// the camera sees it: between the eye and the target (0.3 of the way
/// towards the eye), above the target by 0.2 of their distance and, for
/// the `slot`-th light, 0.2 of it to the left or right (so lights added
/// one after another do not coincide); aimed at the target and putting
/// 3 W/m² on it (the default light's irradiance).
pub fn new_light(kind: &str, eye: DVec3, target: DVec3, slot: usize) -> Result<LightEntry, String> {
    let reach = (eye - target).length().max(1e-3);
    let toward_eye = (eye - target).normalize_or(DVec3::Z);
    let right = DVec3::Y.cross(toward_eye).normalize_or(DVec3::X);
    let up = toward_eye.cross(right);
    // Slots 0, 1, 2, 3, 4, …: 0, +1, −1, +2, −2, … steps to the side.
    let step = slot.div_ceil(2) as f64 * if slot % 2 == 1 { 1.0 } else { -1.0 };
    let offset = toward_eye * 0.3 + up * 0.2 + right * (0.2 * step);
    let position = target + offset * reach;
    let essentials = Essentials {
        position,
        axis: (target - position).normalize(),
        irradiance: [NEW_IRRADIANCE; 3],
        distance: (target - position).length(),
    };
    build(kind, essentials, None)
}

/// Where the 3D view puts a directional light's handle (it has no place
/// of its own): up-light of the target, 0.3 of the eye's distance away
/// (in view for light from above or in front at the usual fields of
/// view).
pub fn directional_reach(eye: DVec3, target: DVec3) -> f64 {
    0.3 * (eye - target).length().max(1e-3)
}

/// `entry` as a light of `kind` with the same place, axis and irradiance
/// at `target` (see the module's notes), its shadows and shadow keys kept
/// (retyping to the same kind changes nothing). A directional light's
/// place is its handle's ([`directional_reach`]).
pub fn retype(
    entry: &LightEntry,
    kind: &str,
    eye: DVec3,
    target: DVec3,
) -> Result<LightEntry, String> {
    if entry.kind() == kind {
        return Ok(entry.clone());
    }
    let essentials = essentials(entry, directional_reach(eye, target), target);
    let mut new = build(kind, essentials, area_size(entry))?;
    new.set_shadows(entry.shadows());
    new.set_shadow_keys(entry.shadow_keys());
    Ok(new)
}

fn essentials(entry: &LightEntry, reach: f64, target: DVec3) -> Essentials {
    let dir = |v: [f64; 3]| DVec3::from_array(v).normalize_or(DVec3::NEG_Y);
    let distance_to = |p: DVec3| (target - p).length().max(1e-3);
    let scaled = |c: [f64; 3], k: f64| c.map(|v| v * k);
    match entry {
        LightEntry::Point(e) => {
            let p = DVec3::from_array(e.position);
            let d = distance_to(p);
            Essentials {
                position: p,
                axis: (target - p).normalize_or(DVec3::NEG_Y),
                irradiance: scaled(e.intensity.rgb().to_array(), 1.0 / (d * d)),
                distance: d,
            }
        }
        LightEntry::Spot(e) => {
            let p = DVec3::from_array(e.position);
            let d = distance_to(p);
            Essentials {
                position: p,
                axis: dir(e.direction),
                irradiance: scaled(e.intensity.rgb().to_array(), 1.0 / (d * d)),
                distance: d,
            }
        }
        LightEntry::Directional(e) => {
            let axis = dir(e.direction);
            Essentials {
                position: target - axis * reach,
                axis,
                irradiance: e.irradiance.rgb().to_array(),
                distance: reach,
            }
        }
        LightEntry::Area(e) => {
            let p = DVec3::from_array(e.position);
            let d = distance_to(p);
            let area = area_of(e).unwrap_or(1.0);
            Essentials {
                position: p,
                axis: dir(e.normal),
                irradiance: scaled(e.radiance.rgb().to_array(), area / (d * d)),
                distance: d,
            }
        }
    }
}

/// The area of an area entry's shape, if its keys give one.
fn area_of(e: &AreaEntry) -> Option<f64> {
    match (e.shape.as_str(), e.size, e.radius) {
        ("rect", Some([w, h]), _) => Some(w * h),
        ("disk", _, Some(r)) => Some(PI * r * r),
        _ => None,
    }
}

fn area_size(entry: &LightEntry) -> Option<[f64; 2]> {
    match entry {
        LightEntry::Area(e) => e.size,
        _ => None,
    }
}

/// The entry of `kind` with these essentials; an area light is a square
/// (or `size`) whose side is a quarter of the distance.
fn build(kind: &str, e: Essentials, size: Option<[f64; 2]>) -> Result<LightEntry, String> {
    let mut t = toml::Table::new();
    let arr = |v: DVec3| toml::Value::try_from(v.to_array()).expect("floats");
    let col = |c: [f64; 3]| toml::Value::try_from(c).expect("floats");
    let d2 = e.distance * e.distance;
    t.insert("kind".into(), kind.into());
    match kind {
        "point" => {
            t.insert("position".into(), arr(e.position));
            t.insert("intensity".into(), col(e.irradiance.map(|c| c * d2)));
        }
        "spot" => {
            t.insert("position".into(), arr(e.position));
            t.insert("direction".into(), arr(e.axis));
            t.insert("intensity".into(), col(e.irradiance.map(|c| c * d2)));
            t.insert("inner_cone_deg".into(), NEW_INNER_CONE_DEG.into());
            t.insert("outer_cone_deg".into(), NEW_OUTER_CONE_DEG.into());
        }
        "directional" => {
            t.insert("direction".into(), arr(e.axis));
            t.insert("irradiance".into(), col(e.irradiance));
        }
        "area" => {
            let side = 0.25 * e.distance;
            let [w, h] = size.unwrap_or([side, side]);
            t.insert("shape".into(), "rect".into());
            t.insert("position".into(), arr(e.position));
            t.insert("normal".into(), arr(e.axis));
            t.insert(
                "size".into(),
                toml::Value::try_from([w, h]).expect("floats"),
            );
            t.insert(
                "tangent".into(),
                arr(crate::base::any_tangent(e.axis).normalize_or(DVec3::X)),
            );
            t.insert(
                "radiance".into(),
                col(e.irradiance.map(|c| c * d2 / (w * h))),
            );
        }
        other => {
            return Err(format!(
                "`{other}` is not a light kind; expected one of {}",
                KINDS.join(", ")
            ));
        }
    }
    LightEntry::deserialize(toml::Value::Table(t)).map_err(|e| e.to_string())
}

/// An area entry switched to `shape` ("rect" or "disk") with the same
/// area, so it emits the same power: a disk of radius r becomes a square
/// of side `r·√π`, a `w × h` rectangle a disk of radius `√(w·h/π)`.
pub fn reshape(e: &mut AreaEntry, shape: &str) {
    if e.shape == shape {
        return;
    }
    let area = area_of(e).unwrap_or(1.0);
    match shape {
        "disk" => {
            e.radius = Some((area / PI).sqrt());
            e.size = None;
        }
        _ => {
            let side = area.sqrt();
            e.size = Some([side, side]);
            e.radius = None;
        }
    }
    e.shape = shape.into();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Light;
    use crate::scene::scene_file::LightSetup;

    /// The irradiance the assembled light puts on a surface at `x` facing
    /// it, summed over an area light's samples.
    fn irradiance_at(entry: &LightEntry, x: DVec3) -> f64 {
        let setup = LightSetup {
            entries: vec![entry.clone()],
            ..Default::default()
        };
        let lights = setup.assemble().expect("valid entry").lights;
        lights
            .iter()
            .map(|l: &Light| {
                let inc = l.incidence(x);
                inc.irradiance.x
            })
            .sum()
    }

    #[test]
    fn new_lights_of_every_kind_are_valid_and_light_the_target() {
        let (eye, target) = (DVec3::new(0.0, 1.0, 4.0), DVec3::new(0.0, 0.0, 0.0));
        for kind in KINDS {
            let entry = new_light(kind, eye, target, 3).unwrap();
            assert_eq!(entry.kind(), kind);
            let e = irradiance_at(&entry, target);
            // Point, spot, directional: exact. Area: the far-field value
            // L·A/d² against the exact sum over its 16 samples of a
            // square a quarter of the distance wide: the samples sit up to
            // (√2/8)·d off the axis, so 1/d'² · cos² falls by at most a few
            // per cent.
            let tolerance = if kind == "area" { 0.05 } else { 1e-9 };
            assert!(
                (e - NEW_IRRADIANCE).abs() <= tolerance * NEW_IRRADIANCE,
                "{kind}: {e}"
            );
        }
        assert!(new_light("lamp", eye, target, 0).is_err());
        // Lights added one after another do not coincide.
        let at = |slot| match new_light("point", eye, target, slot).unwrap() {
            LightEntry::Point(e) => DVec3::from_array(e.position),
            other => panic!("{other:?}"),
        };
        for (a, b) in [(0, 1), (1, 2), (0, 2), (2, 4)] {
            assert!((at(a) - at(b)).length() > 0.1, "{a} and {b}");
        }
    }

    #[test]
    fn retyping_keeps_place_axis_shadows_and_brightness_at_the_target() {
        let (eye, target) = (DVec3::new(1.0, 2.0, 3.0), DVec3::ZERO);
        let mut spot = new_light("spot", eye, target, 0).unwrap();
        spot.set_shadows(true);
        let mut keys = spot.shadow_keys();
        keys.map_size = Some(512);
        spot.set_shadow_keys(keys.clone());
        let before = irradiance_at(&spot, target);
        for kind in KINDS {
            let other = retype(&spot, kind, eye, target).unwrap();
            assert_eq!(other.kind(), kind);
            assert!(other.shadows(), "{kind}");
            assert_eq!(other.shadow_keys(), keys, "{kind}");
            let after = irradiance_at(&other, target);
            let tolerance = if kind == "area" { 0.05 } else { 1e-9 };
            assert!(
                (after - before).abs() <= tolerance * before,
                "{kind}: {after} vs {before}"
            );
            // And back: the same place and intensity.
            let back = retype(&other, "spot", eye, target).unwrap();
            let (LightEntry::Spot(a), LightEntry::Spot(b)) = (&spot, &back) else {
                panic!("{back:?}")
            };
            if kind != "directional" {
                let moved = DVec3::from_array(a.position) - DVec3::from_array(b.position);
                assert!(moved.length() < 1e-9, "{kind}: moved {moved}");
            }
            let turned = DVec3::from_array(a.direction).dot(DVec3::from_array(b.direction));
            assert!(turned > 1.0 - 1e-12, "{kind}: axis turned");
        }
    }

    #[test]
    fn reshaping_an_area_light_keeps_its_area() {
        let LightEntry::Area(mut e) = new_light("area", DVec3::Z * 4.0, DVec3::ZERO, 0).unwrap()
        else {
            panic!()
        };
        let area = area_of(&e).unwrap();
        reshape(&mut e, "disk");
        assert_eq!((e.shape.as_str(), e.size), ("disk", None));
        assert!((area_of(&e).unwrap() - area).abs() < 1e-12);
        reshape(&mut e, "rect");
        assert_eq!(e.radius, None);
        assert!((area_of(&e).unwrap() - area).abs() < 1e-12);
    }
}
