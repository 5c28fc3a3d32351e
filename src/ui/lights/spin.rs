//! `gonio view --spin-lights DEG`: every `[[lights]]` entry orbits the
//! vertical axis through the camera's target by DEG per frame, so its
//! shadow maps are drawn anew every frame. This is what a moving light
//! costs, and it is the fair comparison with a renderer that redraws its
//! maps every frame (`scripts/viewer-frame-time.sh`). Each move
//! goes through [`Document::set_light`], as a dragged light does.

use crate::scene::scene_file::LightEntry;
use crate::ui::document::Document;
use glam::{DMat3, DVec3};

/// Turns every light entry of `doc` by `deg` about the vertical axis
/// through `target`: positions about the axis, directions, normals and
/// tangents with them.
pub fn spin_lights(doc: &mut Document, target: DVec3, deg: f64) -> Result<(), String> {
    let turn = DMat3::from_rotation_y(deg.to_radians());
    let about = |p: [f64; 3]| {
        let axis = DVec3::new(target.x, 0.0, target.z);
        (axis + turn * (DVec3::from(p) - axis)).to_array()
    };
    let dir = |d: [f64; 3]| (turn * DVec3::from(d)).to_array();
    for index in 0..doc.lights.entries.len() {
        let mut entry = doc.lights.entries[index].clone();
        match &mut entry {
            LightEntry::Point(e) => e.position = about(e.position),
            LightEntry::Directional(e) => e.direction = dir(e.direction),
            LightEntry::Spot(e) => {
                e.position = about(e.position);
                e.direction = dir(e.direction);
            }
            LightEntry::Area(e) => {
                e.position = about(e.position);
                e.normal = dir(e.normal);
                e.tangent = e.tangent.map(dir);
            }
        }
        doc.set_light(index, entry)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_light_turns_about_the_vertical_axis_through_the_target() {
        let path = std::env::temp_dir().join(format!("gonio-spin-{}.toml", std::process::id()));
        std::fs::write(
            &path,
            "[[objects]]\nshape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n\
             [materials.m]\nmodel = \"lambert\"\n\
             [[lights]]\nkind = \"point\"\nposition = [3.0, 2.0, 1.0]\nintensity = 1.0\n\
             [[lights]]\nkind = \"directional\"\ndirection = [1.0, -1.0, 0.0]\nirradiance = 1.0\n",
        )
        .unwrap();
        let mut doc = Document::load(
            crate::scene::scene_file::SceneSource::File(path.clone()),
            vec![],
            Default::default(),
        )
        .unwrap();
        std::fs::remove_file(&path).unwrap();
        spin_lights(&mut doc, DVec3::new(1.0, 5.0, 1.0), 90.0).unwrap();
        let LightEntry::Point(p) = &doc.lights.entries[0] else {
            panic!("point")
        };
        // (3, 2, 1) about the axis x = 1, z = 1: offset (2, 0) turns by
        // +90° about +y to (0, -2).
        let want = [1.0, 2.0, -1.0];
        for (a, b) in p.position.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{:?}", p.position);
        }
        let LightEntry::Directional(d) = &doc.lights.entries[1] else {
            panic!("directional")
        };
        let want = [0.0, -1.0, -1.0];
        for (a, b) in d.direction.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{:?}", d.direction);
        }
        // The assembled scene light moved too.
        assert!(doc.scene.lights.iter().any(|l| matches!(
            l,
            crate::scene::Light::Point { position, .. } if (position.z + 1.0).abs() < 1e-12
        )));
    }
}
