//! The scenes the tests of light through surfaces in the f64 reference
//! look at (tests/transmission.rs, tests/rough_volume.rs): a camera on
//! +Z, emitters of known radiance behind glass, boxes and polyhedra with
//! exact face normals.
#![allow(dead_code)]

use glam::DVec3;
use gonio::material::{Material, ReflectanceModel};
use gonio::scene::{Camera, Environment, Light, Mesh, Rgb, Scene, ShadingMode};

/// [`scene`] as the GPU draws it: the GPU draws a scene only with a
/// light, so one directional light of no irradiance (adds nothing).
pub fn gpu_scene(size: u32, meshes: Vec<Mesh>, materials: Vec<Material>) -> Scene {
    let mut s = scene(size, meshes, materials);
    s.light_shadows = vec![Default::default()];
    s.lights = vec![Light::Directional {
        direction: DVec3::NEG_Z,
        irradiance: Rgb::ZERO,
        shadows: false,
    }];
    s
}

/// A scene of `size × size` pixels seen from `(0, 0, 5)` towards the
/// origin, no lights, no ambient light, no environment.
pub fn scene(size: u32, meshes: Vec<Mesh>, materials: Vec<Material>) -> Scene {
    Scene {
        width: size,
        height: size,
        msaa: 1,
        tone_map: Default::default(),
        camera: Camera {
            position: DVec3::new(0.0, 0.0, 5.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            fov_y_deg: 20.0,
            near: 0.1,
            far: 100.0,
        },
        shading: ShadingMode::Phong,
        meshes,
        materials,
        light_shadows: Vec::new(),
        lights: Vec::new(),
        area_lights: Vec::new(),
        ambient: Rgb::ZERO,
        environment: Environment::uniform(Rgb::ZERO),
        measured_table: gonio::material::measured::DEFAULT_TABLE_RESOLUTION,
        measured_network: false,
        smith_beckmann: Default::default(),
        shadow_coords: Default::default(),
        transmission: Default::default(),
        images: Vec::new(),
    }
}

/// A black emitter of radiance `radiance`: the background the tests look
/// at through the transmissive objects.
pub fn emitter(radiance: Rgb) -> Material {
    let mut m = Material::new("emitter", ReflectanceModel::Lambert);
    m.k_d = Rgb::ZERO;
    m.k_a = Rgb::ZERO;
    m.emission = radiance;
    m
}

/// A white, clear, smooth glass of index `ior` (gltf-pbr, transmission 1,
/// roughness 0: the pixel's roughness floor alone).
pub fn glass(ior: f64, thickness: f64) -> Material {
    let mut m = Material::new("glass", ReflectanceModel::GltfPbr);
    m.roughness = 0.0;
    m.base_color = Rgb::ONE;
    m.k_a = Rgb::ZERO;
    m.layers.ior = ior;
    m.layers.transmission = 1.0;
    m.layers.thickness = thickness;
    m
}

/// The square `[−s, s]²` at `z`, facing +Z (towards the camera).
pub fn quad(z: f64, s: f64, material: usize) -> Mesh {
    let p = [(-s, -s), (s, -s), (s, s), (-s, s)].map(|(x, y)| DVec3::new(x, y, z));
    Mesh::with_generated_normals("quad", p.to_vec(), vec![[0, 1, 2], [0, 2, 3]], material)
}

/// A closed convex polyhedron from its faces (each a convex polygon),
/// every face turned counter-clockwise seen from outside (its normal away
/// from the centre) and with its own vertices, so the generated normals
/// are the exact face normals.
pub fn polyhedron(faces: &[Vec<DVec3>], material: usize) -> Mesh {
    let all: Vec<DVec3> = faces.iter().flatten().copied().collect();
    let centre = all.iter().sum::<DVec3>() / all.len() as f64;
    let (mut positions, mut indices) = (Vec::new(), Vec::new());
    for face in faces {
        let base = positions.len() as u32;
        let normal = (face[1] - face[0]).cross(face[2] - face[0]);
        if normal.dot(face[0] - centre) > 0.0 {
            positions.extend(face.iter().copied());
        } else {
            positions.extend(face.iter().rev().copied());
        }
        for k in 1..face.len() as u32 - 1 {
            indices.push([base, base + k, base + k + 1]);
        }
    }
    Mesh::with_generated_normals("polyhedron", positions, indices, material)
}

/// The box `[lo, hi]`, outward faces.
pub fn cuboid(lo: DVec3, hi: DVec3, material: usize) -> Mesh {
    let c = |x: usize, y: usize, z: usize| {
        DVec3::new(
            if x == 0 { lo.x } else { hi.x },
            if y == 0 { lo.y } else { hi.y },
            if z == 0 { lo.z } else { hi.z },
        )
    };
    let faces = [
        vec![c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)], // +z
        vec![c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)], // −z
        vec![c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)], // +x
        vec![c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)], // −x
        vec![c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)], // +y
        vec![c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)], // −y
    ];
    polyhedron(&faces, material)
}

pub fn pixel(frame: &gonio::frame::Frame, i: u32, j: u32) -> Rgb {
    frame.radiance[frame.index(i, j)].map(f64::from).into()
}
