//! The peer gonio's viewer is measured against (issue 18): Bevy 0.19
//! drawing what a gonio scene file describes, in a real window, vsync off,
//! and printing its frame times as `gonio view --frame-times` does.
//!
//! It reads the subset of the scene file that
//! `assets/scenes/viewer-bevy-match.toml` uses, and refuses anything else
//! rather than drawing something different: `[image]`, `[camera]`,
//! `[shadows] map_size`, `[[objects]]` (one glTF's first primitive, planes)
//! with `gltf-pbr` or `lambert` materials (untextured, so both renderers do
//! the same work per pixel), and point `[[lights]]` with shadows.
//!
//! Matching: one shadow cube map of `map_size`² per face per light (Bevy's
//! `PointLightShadowMap`), MSAA off, no tone mapping, exposure 1 (EV100 =
//! log2(1/1.2)), a point light of `intensity` W/sr given 4π·intensity lm so
//! that both images have about the same brightness. Bevy redraws its shadow
//! maps every frame; gonio keeps static ones, so `--spin-lights` is the fair
//! comparison with a moving light.
//!
//! ```text
//! bevy-peer SCENE.toml [--frames N] [--warmup N] [--lights N]
//!           [--spin DEG] [--spin-lights DEG] [--screenshot PNG]
//! ```

use bevy::camera::Exposure;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::PointLightShadowMap;
use bevy::prelude::*;
use bevy::render::view::Msaa;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy::window::{PresentMode, WindowResolution};
use std::path::{Path, PathBuf};
use std::time::Instant;

mod scene;

use scene::{Object, PeerScene};

/// What the command line asked for.
#[derive(Resource, Clone)]
struct Run {
    frames: usize,
    warmup: usize,
    spin_deg: f32,
    spin_lights_deg: f32,
    screenshot: Option<PathBuf>,
}

/// Frame clock: the wall time between successive `Last` schedules, which
/// with Bevy's pipelined rendering is its frame period, present included.
#[derive(Resource, Default)]
struct Clock {
    last: Option<Instant>,
    times_ms: Vec<f64>,
    frame: usize,
}

fn main() {
    let (path, run, lights) = match parse_args() {
        Ok(v) => v,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let mut scene = match PeerScene::load(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            std::process::exit(2);
        }
    };
    if let Some(n) = lights {
        scene.lights.truncate(n);
    }
    let (width, height) = scene.size;
    App::new()
        .add_plugins(
            DefaultPlugins
                .set(WindowPlugin {
                    primary_window: Some(Window {
                        title: "bevy-peer".into(),
                        resolution: WindowResolution::new(width, height)
                            .with_scale_factor_override(1.0),
                        present_mode: PresentMode::AutoNoVsync,
                        ..default()
                    }),
                    ..default()
                })
                .set(AssetPlugin {
                    file_path: "/".into(),
                    ..default()
                }),
        )
        .insert_resource(PointLightShadowMap {
            size: scene.map_size as usize,
        })
        .insert_resource(GlobalAmbientLight::NONE)
        .insert_resource(ClearColor(Color::BLACK))
        .insert_resource(run)
        .insert_resource(Clock::default())
        .insert_resource(scene)
        .add_systems(Startup, setup)
        .add_systems(Update, (spin_camera, spin_lights))
        .add_systems(Last, clock)
        .run();
}

fn parse_args() -> Result<(PathBuf, Run, Option<usize>), String> {
    let mut args = std::env::args().skip(1);
    let mut path = None;
    let mut run = Run {
        frames: 300,
        warmup: 30,
        spin_deg: 0.0,
        spin_lights_deg: 0.0,
        screenshot: None,
    };
    let mut lights = None;
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
        let number = |name: &str, v: String| {
            v.parse::<f64>()
                .map_err(|_| format!("{name}: `{v}` is not a number"))
        };
        match a.as_str() {
            "--frames" => run.frames = number("--frames", value("--frames")?)? as usize,
            "--warmup" => run.warmup = number("--warmup", value("--warmup")?)? as usize,
            "--lights" => lights = Some(number("--lights", value("--lights")?)? as usize),
            "--spin" => run.spin_deg = number("--spin", value("--spin")?)? as f32,
            "--spin-lights" => {
                run.spin_lights_deg = number("--spin-lights", value("--spin-lights")?)? as f32
            }
            "--screenshot" => run.screenshot = Some(PathBuf::from(value("--screenshot")?)),
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => path = Some(PathBuf::from(s)),
        }
    }
    let path = path.ok_or("usage: bevy-peer SCENE.toml [--frames N] [--warmup N] [--lights N] [--spin DEG] [--spin-lights DEG] [--screenshot PNG]")?;
    if run.frames <= run.warmup {
        return Err("--frames must exceed --warmup".into());
    }
    Ok((path, run, lights))
}

fn setup(
    mut commands: Commands,
    scene: Res<PeerScene>,
    assets: Res<AssetServer>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let cam = &scene.camera;
    commands.spawn((
        Camera3d::default(),
        Msaa::Off,
        Tonemapping::None,
        // Exposure scale 1/(1.2·2^ev100) = 1.
        Exposure {
            ev100: (1.0f32 / 1.2).log2(),
        },
        Projection::Perspective(PerspectiveProjection {
            fov: cam.fov_y_deg.to_radians(),
            near: 0.05,
            ..default()
        }),
        Transform::from_translation(cam.position).looking_at(cam.target, cam.up),
    ));
    for object in &scene.objects {
        let (mesh, transform, material) = match object {
            Object::Gltf { path, material } => (
                assets.load(
                    GltfAssetLabel::Primitive {
                        mesh: 0,
                        primitive: 0,
                    }
                    .from_asset(absolute(path)),
                ),
                Transform::IDENTITY,
                material,
            ),
            Object::Plane {
                center,
                size,
                material,
            } => (
                meshes.add(Plane3d::default().mesh().size(*size, *size)),
                Transform::from_translation(*center),
                material,
            ),
        };
        commands.spawn((
            Mesh3d(mesh),
            MeshMaterial3d(materials.add(StandardMaterial {
                base_color: Color::linear_rgb(material.base[0], material.base[1], material.base[2]),
                perceptual_roughness: material.roughness,
                metallic: material.metallic,
                ..default()
            })),
            transform,
        ));
    }
    for light in &scene.lights {
        commands.spawn((
            PointLight {
                // W/sr at display scale 1 → lumens over the sphere.
                intensity: 4.0 * std::f32::consts::PI * light.intensity.max_element(),
                color: Color::linear_rgb(
                    light.intensity.x / light.intensity.max_element(),
                    light.intensity.y / light.intensity.max_element(),
                    light.intensity.z / light.intensity.max_element(),
                ),
                range: 100.0,
                shadow_maps_enabled: true,
                ..default()
            },
            Transform::from_translation(light.position),
        ));
    }
}

fn absolute(path: &Path) -> String {
    path.to_string_lossy().trim_start_matches('/').to_string()
}

/// Orbits the camera about its target's vertical axis, as `gonio view
/// --spin` does.
fn spin_camera(run: Res<Run>, scene: Res<PeerScene>, mut q: Query<&mut Transform, With<Camera3d>>) {
    if run.spin_deg == 0.0 {
        return;
    }
    let target = scene.camera.target;
    for mut t in &mut q {
        t.rotate_around(target, Quat::from_rotation_y(run.spin_deg.to_radians()));
        *t = t.looking_at(target, scene.camera.up);
    }
}

/// Orbits every light about the vertical axis through the camera's target,
/// as `gonio view --spin-lights` does.
fn spin_lights(
    run: Res<Run>,
    scene: Res<PeerScene>,
    mut q: Query<&mut Transform, With<PointLight>>,
) {
    if run.spin_lights_deg == 0.0 {
        return;
    }
    let target = scene.camera.target;
    for mut t in &mut q {
        t.rotate_around(
            Vec3::new(target.x, 0.0, target.z),
            Quat::from_rotation_y(run.spin_lights_deg.to_radians()),
        );
    }
}

fn clock(
    mut clock: ResMut<Clock>,
    run: Res<Run>,
    mut commands: Commands,
    mut exit: MessageWriter<AppExit>,
) {
    let now = Instant::now();
    if let Some(last) = clock.last {
        let frame = clock.frame;
        if frame >= run.warmup {
            clock.times_ms.push((now - last).as_secs_f64() * 1e3);
        }
    }
    clock.last = Some(now);
    clock.frame += 1;
    if clock.frame == run.frames {
        if let Some(path) = &run.screenshot {
            commands
                .spawn(Screenshot::primary_window())
                .observe(save_to_disk(path.clone()));
        }
        let mut t = clock.times_ms.clone();
        t.sort_by(f64::total_cmp);
        let q = |p: f64| t[((t.len() - 1) as f64 * p).round() as usize];
        println!(
            "frame times over {} frames after {} warm-up (bevy 0.19.1): median {:.2} ms, p10 {:.2} ms, p90 {:.2} ms, min {:.2} ms, max {:.2} ms",
            t.len(),
            run.warmup,
            q(0.5),
            q(0.1),
            q(0.9),
            t[0],
            t[t.len() - 1]
        );
    }
    // A few frames more for the screenshot to be read back and written.
    if clock.frame >= run.frames + if run.screenshot.is_some() { 8 } else { 0 } {
        exit.write(AppExit::Success);
    }
}
