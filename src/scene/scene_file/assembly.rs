//! Step 4 of loading, the assembly: validated values of the scene file
//! (after overrides) become a [`Scene`]: materials, meshes of glTF files
//! and generated shapes, lights ([`super::lights`]), ambient light and
//! environment, and the camera (the file's, the first glTF camera, or one
//! framing the geometry). Range errors name the key.

use super::lights::LightSetup;
use super::schema::{CameraSection, ObjectEntry, SceneFile};
use super::values::{finite_vec, gpu_coordinate, non_negative, unit_vec};
use crate::base::ColorValue;
use crate::material::{Material, ReflectanceModel, material_from_entry_in};
use crate::scene::transmission_settings::MAX_TRANSMISSION_LAYERS;
use crate::scene::{
    Camera, Environment, Light, Mesh, Rgb, Scene, ShadingMode, TransmissionSettings, gltf_import,
    primitives,
};
use crate::{Error, Result};
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::Path;

/// Largest image side gonio accepts (a 16k render is ~3 GiB of f32 RGBA).
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Validated assembly of the scene; also returns what its lights were
/// made from (for [`LightSetup::assemble`] after a viewer edit) and the
/// glTF files' material variants (`KHR_materials_variants`). The steps
/// run in the file's order (image, shading, materials, objects, lights,
/// ambient, camera), so of several problems the first is reported.
pub fn assemble(
    origin: &Path,
    base_dir: &Path,
    file: SceneFile,
    gltf_files: &mut gltf_import::GltfLoader,
) -> Result<(Scene, LightSetup, Vec<String>)> {
    let bad = |problem: String| Error::input(origin, problem);
    let (width, height, msaa) = image_size(&file).map_err(bad)?;
    let shading = match &file.shading.mode {
        None => ShadingMode::default(),
        Some(s) => s.parse().map_err(|e| bad(format!("shading.mode: {e}")))?,
    };

    // Named materials first, in name order; glTF materials are appended.
    let mut materials = Vec::new();
    let mut material_index = BTreeMap::new();
    for (name, entry) in &file.materials {
        material_index.insert(name.clone(), materials.len());
        let mut material = material_from_entry_in(name, entry, base_dir).map_err(bad)?;
        super::textures::attach(&mut material, name, entry, base_dir, &mut gltf_files.images)
            .map_err(bad)?;
        materials.push(material);
    }
    let objects = objects(
        origin,
        base_dir,
        &file,
        &material_index,
        &mut materials,
        gltf_files,
    )?;

    gltf_files
        .charge(0, 0, file.lights.len() as u64)
        .map_err(|p| bad(format!("lights: {p}")))?;
    let gltf = super::gltf_keys::GltfKeys::read(&file.gltf).map_err(bad)?;
    gltf.apply(&mut materials[file.materials.len()..]);
    // A glTF file that brings no light, in a scene without lights or a
    // map, is shown in the neutral studio (`[gltf] default_light`).
    let studio = gltf.default_light == super::gltf_keys::DefaultLight::Studio
        && file.objects.iter().any(|o| o.gltf.is_some())
        && objects.lights.is_empty()
        && file.lights.is_empty()
        && file.environment.map.is_none();
    let (ambient, environment) = ambient_and_environment(
        &file,
        base_dir,
        studio.then_some(crate::environment::studio::STUDIO),
        &mut gltf_files.images,
    )
    .map_err(bad)?;
    let light_setup = LightSetup {
        imported: objects.lights,
        shadows: file.shadows.clone(),
        entries: file.lights.clone(),
        environment_map: environment.map.is_some(),
        default_studio: studio,
    };
    let lights = light_setup.assemble().map_err(bad)?;

    let meshes = objects.meshes;
    let scene_bounds =
        crate::scene::mesh::bounds(meshes.iter().flat_map(|m| m.positions.iter().copied()))
            .filter(|_| meshes.iter().any(|m| !m.indices.is_empty()))
            .ok_or_else(|| bad("the scene has no triangles to draw".into()))?;
    let aspect = width as f64 / height as f64;
    let automatic = match objects.camera {
        Some(mut c) => {
            c.fit_clip_planes(scene_bounds.0, scene_bounds.1);
            c
        }
        None => Camera::framing(scene_bounds.0, scene_bounds.1, aspect),
    };
    let camera = match &file.camera {
        Some(section) => camera_from_section(section, automatic, scene_bounds).map_err(bad)?,
        None => automatic,
    };

    let tone_map = match &file.image.tone_map {
        None => Default::default(),
        Some(name) => name
            .parse()
            .map_err(|e| bad(format!("image.tone_map: {e}")))?,
    };
    let measured_network = measured_network(&file, &materials).map_err(bad)?;
    let smith_beckmann = match &file.shading.smith_beckmann {
        None => Default::default(),
        Some(s) => s.parse().map_err(|e| {
            bad(format!(
                "shading.smith_beckmann: {e} (\"erf\": the exact G1 with an f32 erf; \"rational\": Walter et al.'s approximation, up to 0.31 % off)"
            ))
        })?,
    };
    let shadow_coords = match &file.shading.shadow_coords {
        None => Default::default(),
        Some(s) => s.parse().map_err(|e| {
            bad(format!(
                "shading.shadow_coords: {e} (\"exact\": shadow-map coordinates per vertex only where that is exact; \"vertex\": also for a spot light's map, approximately, docs/shadows.md)"
            ))
        })?,
    };
    let transmission = transmission_settings(&file.shading).map_err(bad)?;
    let mut scene = Scene {
        width,
        height,
        msaa,
        tone_map,
        camera,
        shading,
        meshes,
        materials,
        lights: lights.lights,
        light_shadows: lights.light_shadows,
        area_lights: lights.area_lights,
        ambient,
        environment,
        measured_table: measured_table(&file).map_err(bad)?,
        measured_network,
        smith_beckmann,
        shadow_coords,
        transmission,
        images: gltf_files.images.images.clone(),
    };
    // A scene-file normal map on a mesh without tangents (a glTF mesh
    // given a scene-file material): MikkTSpace, in world space.
    crate::scene::tangents::generate_where_needed(&mut scene);
    Ok((scene, light_setup, objects.variants))
}

/// `shading.transmission` (a mode name) and `shading.transmission_layers`
/// (1 to [`MAX_TRANSMISSION_LAYERS`]), `shading.transmission_exit`,
/// `shading.transmission_exit_ray` (a name), each error naming the key and
/// what it takes.
fn transmission_settings(
    shading: &super::schema::ShadingSection,
) -> std::result::Result<TransmissionSettings, String> {
    let mut settings = TransmissionSettings::default();
    if let Some(s) = &shading.transmission {
        settings.mode = s.parse().map_err(|e| {
            format!(
                "shading.transmission: {e} (\"screen\": the GPU reads the opaque scene's image behind a transmissive surface; \"off\": drawn as if opaque)"
            )
        })?;
    }
    if let Some(n) = shading.transmission_layers {
        if !(1..=MAX_TRANSMISSION_LAYERS).contains(&n) {
            return Err(format!(
                "shading.transmission_layers = {n}: takes 1 to {MAX_TRANSMISSION_LAYERS} (images of what lies behind transmissive objects; more let glass be seen behind glass)"
            ));
        }
        settings.layers = n;
    }
    if let Some(exit) = shading.transmission_exit {
        settings.exit = exit;
    }
    if let Some(s) = &shading.transmission_exit_ray {
        settings.exit_ray = s.parse().map_err(|e| {
            format!(
                "shading.transmission_exit_ray: {e} (\"thickness\": read where the refracted ray has gone the material's thickness; \"traced\": marched in screen space to the volume's back face, refracted out, and on to what it meets)"
            )
        })?;
    }
    Ok(settings)
}

/// `shading.measured_mode`: "table" (the default) or "network" (the GPU
/// evaluates each measured material's Neural-BRDF network; a MERL file
/// has no network, so a scene with one is refused in that mode).
fn measured_network(
    file: &SceneFile,
    materials: &[crate::material::Material],
) -> std::result::Result<bool, String> {
    match file.shading.measured_mode.as_deref() {
        None | Some("table") => Ok(false),
        Some("network") => {
            if let Some(m) = materials.iter().find(|m| {
                m.measured_brdf().is_some_and(|b| {
                    !matches!(b.source, crate::material::measured::Source::Network(_))
                })
            }) {
                return Err(format!(
                    "shading.measured_mode = \"network\": material `{}` is a MERL table ({}), which has no network to evaluate; use measured_mode = \"table\" or a built-in material",
                    m.name,
                    m.measured_brdf().map_or("", |b| b.name.as_str())
                ));
            }
            Ok(true)
        }
        Some(other) => Err(format!(
            "shading.measured_mode = \"{other}\": expected \"table\" (look-up in a table of shading.measured_table samples) or \"network\" (the Neural-BRDF network evaluated per pixel)"
        )),
    }
}

/// `shading.measured_table`: the GPU's measured-table resolution, each
/// count in 2..=`MAX_SAMPLES_PER_AXIS` (a table of 2 × 2 × 2 samples is
/// the smallest that interpolates).
fn measured_table(file: &SceneFile) -> std::result::Result<[u32; 3], String> {
    use crate::material::measured::merl::MAX_SAMPLES_PER_AXIS;
    let Some(dims) = file.shading.measured_table else {
        return Ok(crate::material::measured::DEFAULT_TABLE_RESOLUTION);
    };
    if dims
        .iter()
        .any(|&n| n < 2 || n as usize > MAX_SAMPLES_PER_AXIS)
    {
        return Err(format!(
            "shading.measured_table = {dims:?}: each sample count (θ_h, θ_d, φ_d) must be in 2..={MAX_SAMPLES_PER_AXIS}"
        ));
    }
    let bytes = 12 * dims.iter().map(|&n| n as u64).product::<u64>();
    if bytes > 1 << 27 {
        return Err(format!(
            "shading.measured_table = {dims:?}: a table of {bytes} bytes is over the 128 MiB a storage buffer binding is guaranteed"
        ));
    }
    Ok(dims)
}

/// `[image]`: width, height and samples per pixel, range-checked.
fn image_size(file: &SceneFile) -> std::result::Result<(u32, u32, u32), String> {
    let (width, height) = (file.image.width, file.image.height);
    for (key, v) in [("image.width", width), ("image.height", height)] {
        if v == 0 || v > MAX_IMAGE_SIDE {
            return Err(format!("{key} = {v} is outside 1..={MAX_IMAGE_SIDE}"));
        }
    }
    let msaa = file.image.msaa.unwrap_or(1);
    if msaa != 1 && msaa != 4 {
        return Err(format!(
            "image.msaa = {msaa}: the GPU renderer takes 1 (no multisampling) or 4 samples per pixel"
        ));
    }
    Ok((width, height, msaa))
}

/// What the `[[objects]]` bring besides materials.
struct Objects {
    meshes: Vec<Mesh>,
    /// The glTF files' lights, in file order.
    lights: Vec<Light>,
    /// The first glTF camera.
    camera: Option<Camera>,
    /// The glTF files' material variants, each once.
    variants: Vec<String>,
}

/// The meshes of every `[[objects]]` entry: glTF files (their materials
/// appended to `materials` unless the entry names one) and generated
/// shapes (a default Lambert material each unless the entry names one),
/// all charged to the budget of `gltf_files`.
fn objects(
    origin: &Path,
    base_dir: &Path,
    file: &SceneFile,
    material_index: &BTreeMap<String, usize>,
    materials: &mut Vec<Material>,
    gltf_files: &mut gltf_import::GltfLoader,
) -> Result<Objects> {
    let bad = |problem: String| Error::input(origin, problem);
    let mut variant = super::gltf_keys::VariantChoice::new(&file.gltf);
    let mut out = Objects {
        meshes: Vec::new(),
        lights: Vec::new(),
        camera: None,
        variants: Vec::new(),
    };
    for (k, object) in file.objects.iter().enumerate() {
        let forced_material = match &object.material {
            None => None,
            Some(name) => Some(*material_index.get(name).ok_or_else(|| {
                bad(format!(
                    "objects[{k}].material = \"{name}\" names no material; defined: {}",
                    names(&file.materials)
                ))
            })?),
        };
        match (&object.gltf, &object.shape) {
            (Some(gltf), None) => {
                let path = base_dir.join(gltf);
                let mut imported = gltf_files.load(&path)?;
                variant.apply(&path, &mut imported)?;
                let image_offset = gltf_files
                    .images
                    .append(std::mem::take(&mut imported.images));
                for m in &mut imported.materials {
                    for t in &mut m.textures {
                        t.image += image_offset;
                    }
                }
                let offset = materials.len();
                for mut mesh in imported.meshes {
                    mesh.material = forced_material.unwrap_or(mesh.material + offset);
                    out.meshes.push(mesh);
                }
                if forced_material.is_none() {
                    materials.extend(imported.materials);
                }
                out.lights.extend(imported.lights);
                out.camera = out.camera.or(imported.camera);
            }
            (None, Some(shape)) => {
                let material = forced_material.unwrap_or_else(|| {
                    let name = format!("objects[{k}] default");
                    materials.push(Material::new(name, ReflectanceModel::Lambert));
                    materials.len() - 1
                });
                // Charged to the budget before it is built: a fine
                // tessellation must not allocate past the limits first.
                let (vertices, triangles) = shape_size(k, object, shape).map_err(bad)?;
                gltf_files
                    .charge(vertices, triangles, 0)
                    .map_err(|p| bad(format!("objects[{k}]: {p}")))?;
                out.meshes
                    .push(shape_mesh(k, object, shape, material).map_err(bad)?);
            }
            _ => {
                return Err(bad(format!(
                    "objects[{k}] needs exactly one of `gltf = \"file.gltf\"` or `shape = \"sphere\" | \"plane\"`"
                )));
            }
        }
    }
    variant.finish().map_err(bad)?;
    out.variants = variant.names;
    Ok(out)
}

/// `[ambient]` and `[environment]` (whose gradient keys default to the
/// ambient radiance; its map is read relative to `base_dir`, and is
/// `default_map` when the section names none).
fn ambient_and_environment(
    file: &SceneFile,
    base_dir: &Path,
    default_map: Option<&str>,
    images: &mut crate::scene::texture::store::ImageStore,
) -> std::result::Result<(Rgb, Environment), String> {
    let ambient = match file.ambient.radiance {
        None => Rgb::ZERO,
        Some(c) => non_negative("ambient.radiance", c.rgb())?,
    };
    let e = &file.environment;
    let get = |key: &str, c: Option<ColorValue>| match c {
        None => Ok(ambient),
        Some(c) => non_negative(&format!("environment.{key}"), c.rgb()),
    };
    let environment = Environment {
        zenith: get("zenith", e.zenith)?,
        horizon: get("horizon", e.horizon)?,
        ground: get("ground", e.ground)?,
        map: super::environment_keys::environment_map(
            e,
            base_dir,
            default_map,
            images.bytes_left(),
        )?,
    };
    if let Some(map) = &environment.map {
        images.charge(map.data.texel_bytes());
    }
    Ok((ambient, environment))
}

fn names<V>(map: &BTreeMap<String, V>) -> String {
    if map.is_empty() {
        "none".into()
    } else {
        map.keys()
            .map(|k| format!("`{k}`"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The `segments` of a generated shape, range-checked.
fn shape_segments(k: usize, o: &ObjectEntry) -> std::result::Result<u32, String> {
    let segments = o.segments.unwrap_or(48);
    if !(1..=4096).contains(&segments) {
        return Err(format!(
            "objects[{k}].segments = {segments} is outside 1..=4096"
        ));
    }
    Ok(segments)
}

/// Vertices and triangles of the shape `shape_mesh` would build.
fn shape_size(k: usize, o: &ObjectEntry, shape: &str) -> std::result::Result<(u64, u64), String> {
    let segments = shape_segments(k, o)?;
    Ok(match shape {
        "sphere" => primitives::uv_sphere_size(segments.max(3)),
        "plane" => primitives::plane_size(segments),
        // shape_mesh names the problem.
        _ => (0, 0),
    })
}

fn shape_mesh(
    k: usize,
    o: &ObjectEntry,
    shape: &str,
    material: usize,
) -> std::result::Result<Mesh, String> {
    let center = finite_vec(
        &format!("objects[{k}].center"),
        o.center.unwrap_or([0.0; 3]),
    )?;
    let positive = |key: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(format!(
                "objects[{k}].{key} = {v} must be a positive number"
            ))
        }
    };
    let segments = shape_segments(k, o)?;
    match shape {
        "sphere" => Ok(primitives::uv_sphere(
            center,
            positive("radius", o.radius.unwrap_or(1.0))?,
            segments.max(3),
            material,
        )),
        "plane" => Ok(primitives::plane(
            center,
            positive("size", o.size.unwrap_or(10.0))?,
            segments,
            material,
        )),
        other => Err(format!(
            "objects[{k}].shape = \"{other}\" is not a known shape; expected sphere or plane"
        )),
    }
}

/// The camera of `[camera]`: each key given replaces the `automatic`
/// camera's (the one the scene has without the section).
fn camera_from_section(
    s: &CameraSection,
    automatic: Camera,
    (lo, hi): (DVec3, DVec3),
) -> std::result::Result<Camera, String> {
    let given = |v: Option<[f64; 3]>, fallback: DVec3| v.unwrap_or(fallback.to_array());
    let position = finite_vec("camera.position", given(s.position, automatic.position))?;
    let target = finite_vec("camera.target", given(s.target, automatic.target))?;
    for (key, v) in [("camera.position", position), ("camera.target", target)] {
        gpu_coordinate(key, v)?;
    }
    let up = unit_vec("camera.up", given(s.up, automatic.up))?;
    let fov_y_deg = s.fov_y_deg.unwrap_or(automatic.fov_y_deg);
    let forward = (target - position)
        .try_normalize()
        .ok_or("camera.position and camera.target coincide")?;
    if forward.cross(up).length() < 1e-9 {
        return Err("camera.up is parallel to the viewing direction".into());
    }
    if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
        return Err(format!(
            "camera.fov_y_deg = {fov_y_deg} is outside (0, 180)"
        ));
    }
    let mut camera = Camera {
        position,
        target,
        up,
        fov_y_deg,
        near: 0.0,
        far: 0.0,
    };
    camera.fit_clip_planes(lo, hi);
    Ok(camera)
}
