//! The peer gonio's viewer is measured against: Bevy 0.19
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
//! bevy-peer FILE.gltf|FILE.glb --environment MAP.exr [--size WxH]
//!           [--cube N] [--refilter] [--frames N] [--warmup N] [--spin DEG]
//!           [--screenshot PNG]
//! ```
//!
//! The second form (gltf_scene.rs) draws a whole textured glTF file as
//! Bevy loads it under a lat-long environment map, framed as gonio frames
//! a glTF without a camera, at 1920x1080 unless `--size` says otherwise;
//! its frames are counted from the frame the loaded scene is framed in,
//! and it prints when that was and when the first frame drew with every
//! pipeline compiled (time since the program started).

use bevy::camera::Exposure;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::PointLightShadowMap;
use bevy::prelude::*;
use bevy::render::view::Msaa;
use bevy::render::view::screenshot::{Screenshot, save_to_disk};
use bevy::window::{PresentMode, WindowResolution};
use std::path::{Path, PathBuf};
use std::time::Instant;

mod gltf_scene;
mod scene;

use gltf_scene::{GltfRun, Stage};
use scene::{Object, PeerScene};
use std::sync::{Arc, Mutex};

/// What the command line asked for.
#[derive(Resource, Clone)]
struct Run {
    frames: usize,
    warmup: usize,
    spin_deg: f32,
    spin_lights_deg: f32,
    screenshot: Option<PathBuf>,
    /// When `main` started: the origin of the first-frame times.
    start: Instant,
}

/// What to draw: a scene file's subset, or a whole glTF file.
enum Mode {
    Scene {
        path: PathBuf,
        lights: Option<usize>,
    },
    Gltf {
        path: PathBuf,
        environment: PathBuf,
        size: (u32, u32),
        cube: u32,
        refilter: bool,
    },
}

/// The camera's orbit centre and up (`--spin`), once known.
#[derive(Resource)]
struct Orbit {
    target: Vec3,
    up: Vec3,
}

/// Render-world frames after the glTF scene was framed: the time since
/// start at which each ended and the pipelines still compiling then.
#[derive(Resource, Clone)]
struct RenderLog(Arc<Mutex<RenderLogData>>);

struct RenderLogData {
    start: Instant,
    ready: bool,
    frames_since_ready: usize,
    first_complete_ms: Option<f64>,
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
    let start = Instant::now();
    let (mode, run) = match parse_args(start) {
        Ok(v) => v,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let mut app = App::new();
    let size = match &mode {
        Mode::Scene { path, lights } => {
            let mut scene = match PeerScene::load(path) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {}: {e}", path.display());
                    std::process::exit(2);
                }
            };
            if let Some(n) = lights {
                scene.lights.truncate(*n);
            }
            let size = scene.size;
            app.insert_resource(PointLightShadowMap {
                size: scene.map_size as usize,
            })
            .insert_resource(Orbit {
                target: scene.camera.target,
                up: scene.camera.up,
            })
            .insert_resource(scene)
            .add_systems(Startup, setup);
            size
        }
        Mode::Gltf { size, .. } => *size,
    };
    let (width, height) = size;
    app.add_plugins(
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
    .insert_resource(GlobalAmbientLight::NONE)
    .insert_resource(ClearColor(Color::BLACK))
    .insert_resource(run)
    .insert_resource(Clock::default())
    .add_systems(Update, (spin_camera, spin_lights))
    .add_systems(Last, clock);
    if let Mode::Gltf {
        path,
        environment,
        cube,
        refilter,
        ..
    } = &mode
    {
        let map = match gltf_scene::read_latlong(environment) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        };
        let cube_image = gltf_scene::cube_image(&map, *cube);
        let scene = app
            .world()
            .resource::<AssetServer>()
            .load(bevy::gltf::GltfAssetLabel::Scene(0).from_asset(absolute(path)));
        let cube_handle = app
            .world_mut()
            .resource_mut::<Assets<Image>>()
            .add(cube_image);
        let log = RenderLog(Arc::new(Mutex::new(RenderLogData {
            start,
            ready: false,
            frames_since_ready: 0,
            first_complete_ms: None,
        })));
        app.insert_resource(GltfRun {
            scene,
            cube: cube_handle,
            stage: Stage::Loading,
            refilter: *refilter,
        })
        .insert_resource(log.clone())
        .add_systems(Startup, setup_gltf)
        .add_systems(Update, gltf_progress.before(spin_camera));
        if let Some(render_app) = app.get_sub_app_mut(bevy::render::RenderApp) {
            render_app.insert_resource(log).add_systems(
                bevy::render::Render,
                log_render_frame.in_set(bevy::render::RenderSystems::Cleanup),
            );
        }
    }
    app.run();
}

fn parse_args(start: Instant) -> Result<(Mode, Run), String> {
    let mut args = std::env::args().skip(1);
    let mut path = None;
    let mut run = Run {
        frames: 300,
        warmup: 30,
        spin_deg: 0.0,
        spin_lights_deg: 0.0,
        screenshot: None,
        start,
    };
    let mut lights = None;
    let mut environment = None;
    let mut size = (1920, 1080);
    let mut cube = 256;
    let mut refilter = false;
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
            "--environment" => environment = Some(PathBuf::from(value("--environment")?)),
            "--size" => {
                let v = value("--size")?;
                let (w, h) = v
                    .split_once('x')
                    .ok_or(format!("--size: `{v}` is not WxH"))?;
                size = (
                    number("--size", w.into())? as u32,
                    number("--size", h.into())? as u32,
                );
            }
            "--cube" => cube = number("--cube", value("--cube")?)? as u32,
            "--refilter" => refilter = true,
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => path = Some(PathBuf::from(s)),
        }
    }
    let path = path.ok_or("usage: bevy-peer SCENE.toml [--frames N] [--warmup N] [--lights N] [--spin DEG] [--spin-lights DEG] [--screenshot PNG]\n       bevy-peer FILE.gltf|FILE.glb --environment MAP.exr [--size WxH] [--cube N] [--refilter] [--frames N] [--warmup N] [--spin DEG] [--screenshot PNG]")?;
    if run.frames <= run.warmup {
        return Err("--frames must exceed --warmup".into());
    }
    let is_gltf = matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("gltf" | "glb")
    );
    let mode = if is_gltf {
        if lights.is_some() || run.spin_lights_deg != 0.0 {
            return Err("--lights and --spin-lights are for scene files".into());
        }
        if !cube.is_power_of_two() {
            return Err("--cube must be a power of two".into());
        }
        Mode::Gltf {
            path: path
                .canonicalize()
                .map_err(|e| format!("{}: {e}", path.display()))?,
            environment: environment.ok_or("a glTF file needs --environment MAP.exr|.hdr")?,
            size,
            cube,
            refilter,
        }
    } else {
        if environment.is_some() || refilter {
            return Err("--environment and --refilter are for glTF files".into());
        }
        Mode::Scene { path, lights }
    };
    Ok((mode, run))
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
fn spin_camera(
    run: Res<Run>,
    orbit: Option<Res<Orbit>>,
    mut q: Query<&mut Transform, With<Camera3d>>,
) {
    let Some(orbit) = orbit else {
        return;
    };
    if run.spin_deg == 0.0 {
        return;
    }
    for mut t in &mut q {
        t.rotate_around(
            orbit.target,
            Quat::from_rotation_y(run.spin_deg.to_radians()),
        );
        *t = t.looking_at(orbit.target, orbit.up);
    }
}

/// Orbits every light about the vertical axis through the camera's target,
/// as `gonio view --spin-lights` does.
fn spin_lights(
    run: Res<Run>,
    scene: Option<Res<PeerScene>>,
    mut q: Query<&mut Transform, With<PointLight>>,
) {
    let Some(scene) = scene else {
        return;
    };
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
    gltf: Option<Res<GltfRun>>,
    log: Option<Res<RenderLog>>,
    mut commands: Commands,
    mut exit: MessageWriter<AppExit>,
) {
    let now = Instant::now();
    // A glTF file's frames count from the one it was framed in.
    if let Some(g) = &gltf
        && !matches!(g.stage, Stage::Ready(_))
    {
        return;
    }
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
        if let Some(log) = &log {
            let log = log.0.lock().unwrap();
            match log.first_complete_ms {
                Some(ms) => println!(
                    "first frame with the scene and every pipeline ready: {ms:.1} ms after start"
                ),
                None => println!("first frame with every pipeline ready: not seen"),
            }
        }
    }
    // A few frames more for the screenshot to be read back and written.
    if clock.frame >= run.frames + if run.screenshot.is_some() { 8 } else { 0 } {
        exit.write(AppExit::Success);
    }
}

/// The glTF mode's camera, spawned before the file has loaded; framed
/// by `gltf_progress`.
fn setup_gltf(mut commands: Commands, run: Res<GltfRun>) {
    let camera = commands
        .spawn((
            Camera3d::default(),
            Msaa::Off,
            Tonemapping::None,
            Exposure {
                ev100: (1.0f32 / 1.2).log2(),
            },
            Projection::Perspective(PerspectiveProjection {
                fov: 45f32.to_radians(),
                ..default()
            }),
            Transform::from_xyz(0.0, 0.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
        ))
        .id();
    gltf_scene::spawn(&mut commands, &run, camera);
}

/// Waits for the file, its images and its spawned meshes; then frames
/// the camera on the meshes' world bounds as gonio does, and later (once
/// the environment has been filtered a few frames) stops Bevy's per-frame
/// filtering unless `--refilter`.
#[allow(clippy::too_many_arguments)]
fn gltf_progress(
    mut gltf: ResMut<GltfRun>,
    run: Res<Run>,
    clock: Res<Clock>,
    assets: Res<AssetServer>,
    meshes: Res<Assets<Mesh>>,
    images: Res<Assets<Image>>,
    drawn: Query<(&Mesh3d, &GlobalTransform)>,
    materials: Query<&MeshMaterial3d<StandardMaterial>>,
    mut camera: Query<(Entity, &mut Transform, &mut Projection, &Camera)>,
    windows: Query<&Window>,
    log: Res<RenderLog>,
    mut commands: Commands,
) {
    match gltf.stage {
        Stage::Loading => {
            if assets.is_loaded_with_dependencies(&gltf.scene)
                && !drawn.is_empty()
                && materials
                    .iter()
                    .all(|m| assets.is_loaded_with_dependencies(&m.0))
            {
                gltf.stage = Stage::Spawned;
            }
        }
        Stage::Spawned => {
            let Some((lo, hi, count)) = gltf_scene::bounds(&meshes, &drawn) else {
                return;
            };
            let window = windows.single().expect("one window");
            let aspect = window.resolution.width() / window.resolution.height();
            let (position, target, fov, near) = gltf_scene::framing(lo, hi, aspect);
            let (_, mut t, mut p, _) = camera.single_mut().expect("one camera");
            *t = Transform::from_translation(position).looking_at(target, Vec3::Y);
            *p = Projection::Perspective(PerspectiveProjection {
                fov: fov.to_radians(),
                near,
                ..default()
            });
            commands.insert_resource(Orbit {
                target,
                up: Vec3::Y,
            });
            gltf.stage = Stage::Ready(clock.frame);
            log.0.lock().unwrap().ready = true;
            println!(
                "scene ready {:.1} ms after start: {count} meshes, bounds {lo} .. {hi}, camera at {position} looking at {target}, fov_y {fov} deg, near {near}",
                run.start.elapsed().as_secs_f64() * 1e3
            );
            println!("{}", gltf_scene::image_report(&images, &gltf.cube));
        }
        Stage::Ready(at) => {
            if !gltf.refilter && clock.frame == at + 5 {
                let (entity, ..) = camera.single().expect("one camera");
                commands
                    .entity(entity)
                    .remove::<GeneratedEnvironmentMapLight>();
            }
        }
    }
}

/// In the render world, after each frame's commands are submitted: the
/// first frame after the scene was framed with no pipeline still
/// compiling (Bevy skips what has no pipeline yet). The flag is set while
/// the render world draws the frame before the framed one, so a frame
/// counts from the second one after it.
fn log_render_frame(log: Res<RenderLog>, cache: Res<bevy::render::render_resource::PipelineCache>) {
    let mut log = log.0.lock().unwrap();
    if !log.ready || log.first_complete_ms.is_some() {
        return;
    }
    log.frames_since_ready += 1;
    if log.frames_since_ready >= 2 && cache.waiting_pipelines().next().is_none() {
        log.first_complete_ms = Some(log.start.elapsed().as_secs_f64() * 1e3);
    }
}
