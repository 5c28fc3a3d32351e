//! The peer's second mode: a whole glTF file as Bevy loads it (every node
//! of its first scene, its materials and textures, tangents generated
//! where a normal map needs them) under an environment map, at the camera
//! gonio frames a glTF without a camera with.
//!
//! The environment: a lat-long `.exr` / `.hdr` in gonio's direction
//! convention (`u = atan2(d.x, −d.z)/2π`, `v = acos(d.y)/π`, row 0 at +Y,
//! bilinear, `u` wraps), resampled on the CPU into a cube map (Bevy has no
//! lat-long source), filtered by Bevy's `GeneratedEnvironmentMapLight`
//! (GGX-prefiltered specular mips and an irradiance cube) and drawn as
//! the background by `Skybox`, both at intensity 1 (with exposure 1, map
//! values are radiance as gonio reads them). Bevy 0.19 filters that map
//! anew every frame; gonio filters its map once, so by default the peer
//! removes the `GeneratedEnvironmentMapLight` once the scene is ready and
//! a few frames have drawn, and keeps the filtered maps it produced
//! (`--refilter` keeps Bevy's per-frame filtering).

use bevy::asset::RenderAssetUsages;
use bevy::light::Skybox;
use bevy::prelude::*;
use bevy::render::render_resource::{
    Extent3d, TextureDimension, TextureFormat, TextureViewDescriptor, TextureViewDimension,
};
use bevy::world_serialization::{WorldAsset, WorldAssetRoot};
use std::path::Path;

/// What the glTF mode loads, and where the scene stands.
#[derive(Resource)]
pub struct GltfRun {
    pub scene: Handle<WorldAsset>,
    pub cube: Handle<Image>,
    pub stage: Stage,
    pub refilter: bool,
}

#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Stage {
    /// The file and its images are still loading.
    Loading,
    /// Loaded and spawned: transforms propagate this frame.
    Spawned,
    /// Framed; the frame number (of `Clock`) at which that happened.
    Ready(usize),
}

/// The camera gonio's `Camera::framing` gives the world-space bounds
/// `(lo, hi)` at `aspect` (src/scene/camera.rs): 45° vertical field of
/// view, the bounding sphere fitted to the narrower half-angle with a
/// 10 % margin, seen from direction (0.35, 0.45, 1) normalized, +Y up;
/// near plane as gonio fits it. Returns (position, target, fov_y_deg,
/// near).
pub fn framing(lo: Vec3, hi: Vec3, aspect: f32) -> (Vec3, Vec3, f32, f32) {
    let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
    let fov_y_deg: f64 = 45.0;
    let center = 0.5 * (lo + hi);
    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let half = 0.5 * fov_y_deg.to_radians();
    let half_narrow = if aspect < 1.0 {
        (half.tan() * aspect as f64).atan()
    } else {
        half
    };
    let distance = 1.1 * radius / half_narrow.sin();
    let direction = bevy::math::DVec3::new(0.35, 0.45, 1.0).normalize();
    let position = center + direction * distance;
    let far = (distance + radius) * 1.01 + 1e-6;
    let near = ((distance - radius) * 0.99).max(far * 1e-4);
    (
        position.as_vec3(),
        center.as_vec3(),
        fov_y_deg as f32,
        near as f32,
    )
}

/// Reads a lat-long map as linear RGB, row-major, row 0 at the top.
pub fn read_latlong(path: &Path) -> Result<(u32, u32, Vec<[f32; 3]>), String> {
    let img = image::open(path)
        .map_err(|e| format!("{}: {e}", path.display()))?
        .into_rgb32f();
    let (w, h) = img.dimensions();
    let texels = img.pixels().map(|p| p.0).collect();
    Ok((w, h, texels))
}

/// Bilinear lookup of unit direction `d` in gonio's convention: texel
/// centres at `(col + ½)/W`, `u` wraps, `v` clamps.
fn lookup(map: &(u32, u32, Vec<[f32; 3]>), d: Vec3) -> [f32; 3] {
    let (w, h, texels) = map;
    let (w, h) = (*w as i64, *h as i64);
    let mut u = d.x.atan2(-d.z) / std::f32::consts::TAU;
    if u < 0.0 {
        u += 1.0;
    }
    let v = d.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI;
    let x = u * w as f32 - 0.5;
    let y = (v * h as f32 - 0.5).clamp(0.0, (h - 1) as f32);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |cx: i64, cy: i64| texels[(cy.clamp(0, h - 1) * w + cx.rem_euclid(w)) as usize];
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (a, b, c, e) = (
        at(x0, y0),
        at(x0 + 1, y0),
        at(x0, y0 + 1),
        at(x0 + 1, y0 + 1),
    );
    let mut out = [0.0; 3];
    for i in 0..3 {
        let top = a[i] + (b[i] - a[i]) * fx;
        let bottom = c[i] + (e[i] - c[i]) * fx;
        out[i] = top + (bottom - top) * fy;
    }
    out
}

/// The cube map Bevy samples for the lat-long map: faces +X, −X, +Y, −Y,
/// +Z, −Z of `size`² texels in wgpu's face orientation, each texel the map
/// at its centre's direction. Bevy looks its cube maps up at `(x, y, −z)`
/// for world direction `(x, y, z)` ("cube maps are left-handed"), so the
/// texel at lookup direction `c` holds the map at `(c.x, c.y, −c.z)`.
pub fn cube_image(map: &(u32, u32, Vec<[f32; 3]>), size: u32) -> Image {
    let n = size as usize;
    let mut data = Vec::with_capacity(6 * n * n * 8);
    for face in 0..6 {
        for j in 0..n {
            for i in 0..n {
                let a = 2.0 * (i as f32 + 0.5) / size as f32 - 1.0;
                let b = 2.0 * (j as f32 + 0.5) / size as f32 - 1.0;
                let c = match face {
                    0 => Vec3::new(1.0, -b, -a),
                    1 => Vec3::new(-1.0, -b, a),
                    2 => Vec3::new(a, 1.0, b),
                    3 => Vec3::new(a, -1.0, -b),
                    4 => Vec3::new(a, -b, 1.0),
                    _ => Vec3::new(-a, -b, -1.0),
                };
                let world = Vec3::new(c.x, c.y, -c.z).normalize();
                let l = lookup(map, world);
                for v in [l[0], l[1], l[2], 1.0] {
                    data.extend_from_slice(&f16_bits(v).to_le_bytes());
                }
            }
        }
    }
    let mut image = Image::new(
        Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 6,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba16Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_view_descriptor = Some(TextureViewDescriptor {
        dimension: Some(TextureViewDimension::Cube),
        ..default()
    });
    image
}

/// Spawns the scene and the environment on the camera.
pub fn spawn(commands: &mut Commands, run: &GltfRun, camera: Entity) {
    commands.spawn(WorldAssetRoot(run.scene.clone()));
    commands.entity(camera).insert((
        Skybox {
            image: Some(run.cube.clone()),
            brightness: 1.0,
            rotation: Quat::IDENTITY,
        },
        GeneratedEnvironmentMapLight {
            environment_map: run.cube.clone(),
            intensity: 1.0,
            ..default()
        },
    ));
}

/// The world-space bounds of every mesh drawn, from its vertices (as
/// gonio bounds the scene it frames).
pub fn bounds(
    meshes: &Assets<Mesh>,
    q: &Query<(&Mesh3d, &GlobalTransform)>,
) -> Option<(Vec3, Vec3, usize)> {
    let mut lo = Vec3::splat(f32::INFINITY);
    let mut hi = Vec3::splat(f32::NEG_INFINITY);
    let mut count = 0;
    for (mesh, t) in q {
        let mesh = meshes.get(&mesh.0)?;
        let positions = mesh.attribute(Mesh::ATTRIBUTE_POSITION)?.as_float3()?;
        for p in positions {
            let w = t.transform_point(Vec3::from(*p));
            lo = lo.min(w);
            hi = hi.max(w);
        }
        count += 1;
    }
    (count > 0).then_some((lo, hi, count))
}

/// IEEE half-precision bits of a finite `v ≥ 0` (rounded to nearest;
/// below 2⁻¹⁴ flushed to zero, above 65504 clamped): what a map of
/// radiances needs, without another crate.
fn f16_bits(v: f32) -> u16 {
    if !(v >= 6.103_515_6e-5) {
        return 0;
    }
    if v >= 65504.0 {
        return 0x7bff;
    }
    let bits = v.to_bits();
    let exp = ((bits >> 23) & 0xff) as i32 - 127 + 15;
    let mant = bits & 0x7f_ffff;
    let h = ((exp as u32) << 10) | (mant >> 13);
    (h + ((mant >> 12) & 1)) as u16
}

/// The 2D images Bevy holds for the file (its own 1×1 fallbacks, LUTs
/// and the environment's cube left out): how many, by format, and their
/// bytes on the GPU as Bevy creates them (size × texel size × the mip
/// levels the image has: glTF images load with one).
pub fn image_report(images: &Assets<Image>, cube: &Handle<Image>) -> String {
    let mut by_format: std::collections::BTreeMap<String, (usize, u64)> = Default::default();
    for (id, image) in images.iter() {
        let d = &image.texture_descriptor;
        if id == cube.id()
            || d.dimension != TextureDimension::D2
            || d.size.depth_or_array_layers != 1
            || d.size.width < 64
        {
            continue;
        }
        let texel = d.format.block_copy_size(None).unwrap_or(0) as u64;
        let bytes: u64 = (0..d.mip_level_count)
            .map(|l| (d.size.width >> l).max(1) as u64 * (d.size.height >> l).max(1) as u64 * texel)
            .sum();
        let e = by_format
            .entry(format!(
                "{:?} {}x{} mips {}",
                d.format, d.size.width, d.size.height, d.mip_level_count
            ))
            .or_default();
        e.0 += 1;
        e.1 += bytes;
    }
    let total: u64 = by_format.values().map(|v| v.1).sum();
    let parts: Vec<String> = by_format
        .iter()
        .map(|(k, (n, b))| format!("{n} x {k}: {b} B"))
        .collect();
    format!(
        "images as Bevy holds them: {total} bytes ({})",
        parts.join("; ")
    )
}
