//! The part of a gonio scene file the peer draws (see main.rs): anything
//! else in the file is refused, so the two renderers never quietly draw
//! different scenes.

use bevy::prelude::*;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Resource)]
pub struct PeerScene {
    pub size: (u32, u32),
    pub camera: CameraDesc,
    pub map_size: u32,
    pub objects: Vec<Object>,
    pub lights: Vec<PointDesc>,
}

pub struct CameraDesc {
    pub position: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub fov_y_deg: f32,
}

pub struct MaterialDesc {
    pub base: [f32; 3],
    pub roughness: f32,
    pub metallic: f32,
}

pub enum Object {
    Gltf {
        path: PathBuf,
        material: MaterialDesc,
    },
    Plane {
        center: Vec3,
        size: f32,
        material: MaterialDesc,
    },
}

pub struct PointDesc {
    pub position: Vec3,
    pub intensity: Vec3,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    image: Image,
    camera: Camera,
    shading: Option<toml::Table>,
    shadows: Option<Shadows>,
    objects: Vec<ObjectEntry>,
    materials: BTreeMap<String, MaterialEntry>,
    lights: Vec<LightEntry>,
    ambient: Option<toml::Table>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Image {
    width: u32,
    height: u32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Camera {
    position: [f32; 3],
    target: [f32; 3],
    up: [f32; 3],
    fov_y_deg: f32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Shadows {
    map_size: u32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectEntry {
    gltf: Option<PathBuf>,
    shape: Option<String>,
    center: Option<[f32; 3]>,
    size: Option<f32>,
    segments: Option<u32>,
    material: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialEntry {
    model: String,
    base_color: Option<[f32; 3]>,
    k_d: Option<[f32; 3]>,
    roughness: Option<f32>,
    metallic: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightEntry {
    kind: String,
    position: [f32; 3],
    intensity: [f32; 3],
    shadows: bool,
}

impl PeerScene {
    pub fn load(path: &Path) -> Result<PeerScene, String> {
        let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
        let file: File = toml::from_str(&text).map_err(|e| e.to_string())?;
        let dir = path
            .parent()
            .unwrap_or(Path::new("."))
            .canonicalize()
            .map_err(|e| e.to_string())?;
        let material = |name: &str| -> Result<MaterialDesc, String> {
            let m = file
                .materials
                .get(name)
                .ok_or(format!("no material `{name}`"))?;
            match m.model.as_str() {
                "gltf-pbr" => Ok(MaterialDesc {
                    base: m.base_color.ok_or("gltf-pbr needs base_color")?,
                    roughness: m.roughness.ok_or("gltf-pbr needs roughness")?,
                    metallic: m.metallic.unwrap_or(0.0),
                }),
                // Bevy has no Lambert-only material: its roughest dielectric.
                "lambert" => Ok(MaterialDesc {
                    base: m.k_d.ok_or("lambert needs k_d")?,
                    roughness: 1.0,
                    metallic: 0.0,
                }),
                other => Err(format!(
                    "material `{name}`: the peer draws gltf-pbr and lambert, not {other}"
                )),
            }
        };
        let mut objects = Vec::new();
        for o in &file.objects {
            let material = material(&o.material)?;
            objects.push(match (&o.gltf, o.shape.as_deref()) {
                (Some(g), None) => Object::Gltf {
                    path: dir
                        .join(g)
                        .canonicalize()
                        .map_err(|e| format!("{}: {e}", g.display()))?,
                    material,
                },
                (None, Some("plane")) if o.segments.unwrap_or(1) == 1 => Object::Plane {
                    center: Vec3::from(o.center.ok_or("a plane needs center")?),
                    size: o.size.ok_or("a plane needs size")?,
                    material,
                },
                _ => return Err("objects: the peer draws a glTF or a one-segment plane".into()),
            });
        }
        let mut lights = Vec::new();
        for l in &file.lights {
            if l.kind != "point" || !l.shadows {
                return Err("lights: the peer draws shadowed point lights only".into());
            }
            lights.push(PointDesc {
                position: Vec3::from(l.position),
                intensity: Vec3::from(l.intensity),
            });
        }
        let _ = (&file.shading, &file.ambient);
        Ok(PeerScene {
            size: (file.image.width, file.image.height),
            camera: CameraDesc {
                position: Vec3::from(file.camera.position),
                target: Vec3::from(file.camera.target),
                up: Vec3::from(file.camera.up),
                fov_y_deg: file.camera.fov_y_deg,
            },
            map_size: file.shadows.map(|s| s.map_size).unwrap_or(1024),
            objects,
            lights,
        })
    }
}
