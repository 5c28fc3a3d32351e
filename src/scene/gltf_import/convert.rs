//! The parts of a glTF that are not geometry: materials, lights, cameras,
//! node transforms, each turned into gonio's types.

use crate::material::{Material, ROUGHNESS_FLOOR, ReflectanceModel};
use crate::scene::{Camera, Light, Rgb};
use glam::{DMat4, DQuat, DVec3, DVec4};
use gltf::khr_lights_punctual::Kind as LightKind;

/// glTF's metallic-roughness factors as a `gltf-pbr` material, glTF 2.0's
/// own BRDF (see the module documentation). Inputs outside [0, 1] are
/// clamped; a roughness of 0 becomes 10⁻⁴ (the contract's range is
/// (0, 1]; the renderers' floor widens α further).
pub fn material_from_metallic_roughness(
    name: impl Into<String>,
    base_color: Rgb,
    metallic: f64,
    roughness: f64,
) -> Material {
    let b = base_color.clamp(Rgb::ZERO, Rgb::ONE);
    let m = metallic.clamp(0.0, 1.0);
    let r = roughness.clamp(0.0, 1.0);
    let mut material = Material::new(name, ReflectanceModel::GltfPbr);
    material.base_color = b;
    material.metallic = m;
    material.roughness = r.max(ROUGHNESS_FLOOR);
    // An ambient light lights the base colour; a lecture model chosen
    // in the viewer starts from the diffuse part.
    material.k_a = b;
    material.k_d = b * (1.0 - m);
    material
}

/// A glTF material's factors: base colour, metallic, roughness, emission
/// = `emissiveFactor` × `emissive_strength`
/// (`KHR_materials_emissive_strength`, 1 without it), and the base
/// colour's alpha with `alphaMode` / `alphaCutoff` (alpha clamped to
/// [0, 1]; a cutoff must be a finite number ≥ 0).
pub(super) fn material_from_pbr(
    name: String,
    material: &gltf::Material,
) -> Result<Material, String> {
    let pbr = material.pbr_metallic_roughness();
    let [r, g, b, alpha] = pbr.base_color_factor().map(f64::from);
    let mut out = material_from_metallic_roughness(
        name,
        Rgb::new(r, g, b),
        f64::from(pbr.metallic_factor()),
        f64::from(pbr.roughness_factor()),
    );
    // Multiple scattering compensated, as three.js, Filament and
    // Babylon.js render glTF (the contract's measured-reflectance
    // section; `[gltf] energy_compensation = false` for the
    // specification's BRDF exactly).
    out.energy_compensation = true;
    // Silhouettes as the other glTF renderers draw them (`[gltf]
    // facing_normals = false` for the one-sided shading as written).
    out.facing_normals = true;
    let strength = f64::from(material.emissive_strength().unwrap_or(1.0));
    out.emission = Rgb::from(material.emissive_factor().map(f64::from)) * strength;
    out.sides = if material.double_sided() {
        crate::material::Sides::Both
    } else {
        crate::material::Sides::Front
    };
    out.alpha = alpha.clamp(0.0, 1.0);
    out.alpha_mode = match material.alpha_mode() {
        gltf::material::AlphaMode::Opaque => crate::material::AlphaMode::Opaque,
        gltf::material::AlphaMode::Blend => crate::material::AlphaMode::Blend,
        gltf::material::AlphaMode::Mask => {
            // glTF: "alphaCutoff ... minimum: 0.0", default 0.5.
            let cutoff = f64::from(material.alpha_cutoff().unwrap_or(0.5));
            if !(cutoff.is_finite() && cutoff >= 0.0) {
                return Err(format!("alphaCutoff {cutoff} is not a finite number ≥ 0"));
            }
            crate::material::AlphaMode::Mask { cutoff }
        }
    };
    if !alpha.is_finite() {
        return Err(format!("baseColorFactor's alpha {alpha} is not finite"));
    }
    // Clamping leaves only non-finite factors and a negative emission to
    // fail here.
    out.validate()?;
    Ok(out)
}

pub(super) fn convert_light(
    light: &gltf::khr_lights_punctual::Light,
    world: DMat4,
) -> Result<Light, String> {
    let color = Rgb::from(light.color().map(f64::from));
    let intensity = f64::from(light.intensity());
    let power = color * intensity;
    if !power.is_finite() || power.min_element() < 0.0 {
        return Err(format!(
            "color {color} × intensity {intensity} is not a finite non-negative value"
        ));
    }
    let range = match light.range() {
        None => None,
        Some(r) if r.is_finite() && r > 0.0 => Some(f64::from(r)),
        Some(r) => return Err(format!("range {r} is not a positive number")),
    };
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world_axis(world, DVec3::NEG_Z)
        .ok_or("the node's transform gives the light no direction (zero scale)")?;
    Ok(match light.kind() {
        LightKind::Directional => Light::Directional {
            direction,
            irradiance: power,
            shadows: false,
        },
        LightKind::Point => Light::Point {
            position,
            intensity: power,
            range,
            shadows: false,
        },
        LightKind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
            // glTF asks 0 ≤ inner < outer ≤ π/2; equal cones are harmless
            // (the falloff has a floor), so only an inverted or out-of-range
            // pair is refused. π/2 is compared in f32, as the file wrote it.
            if !(0.0 <= inner && inner <= outer && outer_cone_angle <= std::f32::consts::FRAC_PI_2)
            {
                return Err(format!(
                    "spot cone angles inner {inner_cone_angle} and outer {outer_cone_angle} (radians) are not 0 ≤ inner ≤ outer ≤ π/2"
                ));
            }
            Light::Spot {
                position,
                direction,
                intensity: power,
                inner_cone_deg: inner.to_degrees(),
                outer_cone_deg: outer.to_degrees(),
                range,
                shadows: false,
            }
        }
    })
}

/// A node's local axis in world space, unit length, or `None` if the
/// transform collapses it. The threshold is absolute, not zero: a zero
/// scale combined with a rotation leaves rounding residue of ~1e-17 that
/// would otherwise normalize into an arbitrary direction.
fn world_axis(world: DMat4, local: DVec3) -> Option<DVec3> {
    let v = world.transform_vector3(local);
    (v.length() > 1e-12).then(|| v.normalize())
}

/// The node's camera, if it is perspective and gives a usable frame.
pub(super) fn convert_camera(camera: &gltf::Camera, world: DMat4) -> Option<Camera> {
    let gltf::camera::Projection::Perspective(perspective) = camera.projection() else {
        return None;
    };
    let fov_y_deg = f64::from(perspective.yfov()).to_degrees();
    if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
        return None;
    }
    let position = world.transform_point3(DVec3::ZERO);
    let forward = world_axis(world, DVec3::NEG_Z)?;
    let up = world_axis(world, DVec3::Y)?;
    if forward.cross(up).length_squared() < 1e-12 {
        return None;
    }
    Some(Camera {
        position,
        target: position + forward,
        up,
        fov_y_deg,
        near: 0.0,
        far: 0.0,
    })
}

/// A node's local transform, in `f64` from the file's `f32`s.
pub(super) fn local_transform(node: &gltf::Node) -> Result<DMat4, String> {
    let matrix = match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            let matrix = DMat4::from_cols_array_2d(&matrix.map(|column| column.map(f64::from)));
            // glTF requires a matrix that decomposes into TRS; a projective
            // bottom row would be silently dropped by affine transforms.
            let bottom = matrix.row(3);
            let off = (bottom - DVec4::W).abs().max_element();
            if off.is_nan() || off > 1e-5 {
                return Err(format!(
                    "node {}: the matrix's bottom row is {bottom}, not [0, 0, 0, 1]; node matrices must be affine",
                    node.index()
                ));
            }
            matrix
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let [x, y, z, w] = rotation.map(f64::from);
            let q = DQuat::from_xyzw(x, y, z, w);
            let length = q.length();
            if !(length.is_finite() && length > 0.0) {
                return Err(format!(
                    "node {}: rotation {rotation:?} is not a usable quaternion",
                    node.index()
                ));
            }
            // The file's f32 quaternion is only nearly unit length.
            DMat4::from_scale_rotation_translation(
                DVec3::from(scale.map(f64::from)),
                q / length,
                DVec3::from(translation.map(f64::from)),
            )
        }
    };
    if !matrix.is_finite() {
        return Err(format!(
            "node {}: the transform is not finite",
            node.index()
        ));
    }
    Ok(matrix)
}
