//! The GPU renderer against the f64 CPU reference, pixel by pixel, for each
//! shading mode, on the built-in scene and on real glTF models.
//!
//! Tolerance (derivation in `gonio::output::compare`):
//! * geometric: the reference is re-rendered with the sample point moved by
//!   δ = 1/128 px along ±x and ±y. lavapipe snaps vertices to a 1/256 px
//!   grid (8 sub-pixel bits), which moves a triangle by at most 1/512 px per
//!   axis; f32 clip-space arithmetic adds ~10⁻⁴ px at these sizes. δ = 1/128
//!   covers both with a factor of 2 to spare.
//! * arithmetic, relative to |L|: with ε = 2⁻²⁴ (f32 unit roundoff),
//!   - 64ε for the inputs rounded to f32 and the ~20 operations of the
//!     light loop (each at most 1 ulp in WGSL's correctly-rounded + − × ÷),
//!   - k_e·(8ε + 2⁻²¹·ln 2) for the cosine lobe `c^k_e`: an error δc in the
//!     cosine (≤ 8ε: a dot product of normalized vectors) becomes a relative
//!     error k_e·δc/c, and Vulkan allows `pow` = `exp2(k_e·log2 c)` with
//!     an absolute `log2` error of 2⁻²¹ near 1, i.e. a relative result error
//!     of k_e·2⁻²¹·ln 2;
//!
//!   Plus an absolute 64ε·L_max for channels near zero.

mod common;

use gonio::frame::Frame;
use gonio::output::compare::{Comparison, JITTER_OFFSETS};
use gonio::reference;
use gonio::scene::scene_file::{self, SceneSource};
use gonio::scene::{Scene, ShadingMode};

use common::JITTER_PX;

// The tolerance (`common::tolerance`, `common::arithmetic_rel`) is shared
// with tests/shadows.rs; its derivation is in this file's module docs.
use common::tolerance;

fn no_nan(frame: &Frame) -> bool {
    frame.radiance.iter().flatten().all(|v| v.is_finite())
}

/// Renders `scene` on both sides and compares; prints one table row.
fn gpu_vs_cpu(label: &str, scene: &Scene) -> Comparison {
    let mut renderer = common::gpu_renderer();
    let (gpu, _) = renderer.render(scene).expect("GPU render");
    let center = reference::render(scene);
    let jittered = JITTER_OFFSETS
        .map(|(dx, dy)| reference::render_offset(scene, dx * JITTER_PX, dy * JITTER_PX));
    assert!(no_nan(&gpu), "{label}: the GPU frame has NaN or Inf");
    assert!(
        no_nan(&center),
        "{label}: the reference frame has NaN or Inf"
    );
    let tol = tolerance(scene, &center);
    // Textured scenes (Suzanne's base colour and metallic-roughness) add
    // the level-of-detail spread (common::compare_to_reference).
    let c = common::compare_to_reference(scene, &gpu, &center, &jittered);
    eprintln!("{label:<28} rel tol {:.2e} | {}", tol.rel, c.summary());
    // The comparison must have had something to compare.
    assert!(
        c.compared > scene.width as usize * scene.height as usize / 10,
        "{label}: too few covered pixels"
    );
    common::assert_agrees(label, "GPU and reference disagree", &c, &gpu, &center);
    c
}

fn load(source: SceneSource, mode: ShadingMode, extra: &[&str]) -> Scene {
    let mut sets = vec![
        "image.width=200".to_string(),
        "image.height=150".to_string(),
        format!("shading.mode={mode}"),
        // A glTF without lights under the directional default light, not
        // the studio: both renderers evaluate it exactly (the studio's
        // split sum is the GPU's approximation; tests/default_look.rs).
        "gltf.default_light=\"directional\"".to_string(),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    scene_file::load(&source, &sets).expect("scene loads")
}

#[test]
fn built_in_scene_flat() {
    gpu_vs_cpu(
        "built-in, flat",
        &load(SceneSource::BuiltIn, ShadingMode::Flat, &[]),
    );
}

#[test]
fn built_in_scene_gouraud() {
    gpu_vs_cpu(
        "built-in, gouraud",
        &load(SceneSource::BuiltIn, ShadingMode::Gouraud, &[]),
    );
}

#[test]
fn built_in_scene_phong() {
    gpu_vs_cpu(
        "built-in, phong",
        &load(SceneSource::BuiltIn, ShadingMode::Phong, &[]),
    );
}

#[test]
fn built_in_scene_lecture_phong_and_spot_light() {
    let scene = load(
        SceneSource::BuiltIn,
        ShadingMode::Phong,
        &[
            "materials.ball.model=phong",
            "lights.0={kind = \"spot\", position = [2.0, 4.0, 2.0], direction = [-0.4, -1.0, -0.4], intensity = 40.0, inner_cone_deg = 15.0, outer_cone_deg = 30.0}",
        ],
    );
    gpu_vs_cpu("built-in, phong lobe, spot", &scene);
}

#[test]
fn suzanne_every_shading_mode() {
    for mode in ShadingMode::ALL {
        let scene = load(
            SceneSource::File(common::gltf_asset("Suzanne/Suzanne.gltf")),
            mode,
            &[],
        );
        gpu_vs_cpu(&format!("Suzanne.gltf, {mode}"), &scene);
    }
}

#[test]
fn box_glb_with_point_light() {
    let scene = load(
        SceneSource::File(common::gltf_asset("Box/Box.glb")),
        ShadingMode::Phong,
        &[
            "lights=[{kind = \"point\", position = [1.0, 2.0, 2.0], intensity = 5.0}]",
            "ambient.radiance=0.05",
        ],
    );
    gpu_vs_cpu("Box.glb, phong, point", &scene);
}

/// One image per reflectance model of the table (and several per model
/// with terms): the built-in scene's ball with each model (a mirror
/// reflecting a sky gradient), Phong shading.
#[test]
fn every_reflectance_model_renders_like_the_reference() {
    let models: &[(&str, &[&str])] = &[
        ("lambert", &[]),
        ("phong", &[]),
        ("phong-normalized", &[]),
        ("blinn-phong", &[]),
        ("blinn-phong-normalized", &[]),
        ("ward", &["materials.ball.sigma=0.15"]),
        (
            "ward-anisotropic",
            &["materials.ball.sigma_x=0.05", "materials.ball.sigma_y=0.4"],
        ),
        (
            "cook-torrance",
            &[
                "materials.ball.preset=gold",
                "materials.ball.k_d=0.1",
                "materials.ball.roughness=0.25",
            ],
        ),
        (
            "cook-torrance",
            &[
                "materials.ball.distribution=ggx",
                "materials.ball.fresnel=schlick",
                "materials.ball.roughness=0.2",
            ],
        ),
        // Per-channel η, κ: copper's red differs from its blue.
        (
            "cook-torrance",
            &[
                "materials.ball.preset=copper-rgb",
                "materials.ball.k_d=0",
                "materials.ball.roughness=0.3",
            ],
        ),
        (
            "cook-torrance",
            &[
                "materials.ball.distribution=blinn",
                "materials.ball.geometry=v-groove",
                "materials.ball.denominator=lecture",
                "materials.ball.fresnel=conductor-lecture",
                "materials.ball.roughness=0.3",
            ],
        ),
        (
            "cook-torrance",
            &[
                "materials.ball.distribution=gaussian-normalized",
                "materials.ball.preset=glass",
                "materials.ball.roughness=0.2",
            ],
        ),
        (
            "cook-torrance",
            &[
                "materials.ball.distribution=ggx",
                "materials.ball.geometry=smith-correlated",
                "materials.ball.fresnel=schlick",
                "materials.ball.roughness=0.2",
            ],
        ),
        (
            "gltf-pbr",
            &[
                "materials.ball.base_color=[0.9, 0.6, 0.2]",
                "materials.ball.metallic=0.5",
                "materials.ball.roughness=0.4",
                "materials.ball.emission=[0.05, 0.0, 0.1]",
            ],
        ),
        (
            "gltf-pbr",
            &[
                "materials.ball.base_color=[0.95, 0.64, 0.54]",
                "materials.ball.metallic=1",
                "materials.ball.roughness=0.15",
            ],
        ),
        (
            "mirror",
            &[
                "materials.ball.preset=silver",
                "materials.ball.fresnel=conductor",
                "environment.zenith=[0.2, 0.4, 1.0]",
                "environment.horizon=[1.0, 0.9, 0.8]",
                "environment.ground=[0.1, 0.08, 0.05]",
            ],
        ),
    ];
    // Every model of the table renders: those not listed above with their
    // defaults (a new model is checked without an edit here). Except
    // `measured`: it takes no k_d, k_s (the built-in ball has them), and
    // its GPU renders a filtered table, checked against the table's f64
    // twin in tests/measured.rs (`gpu_tables_match_their_reference_twin`).
    let unlisted: Vec<(&str, &[&str])> = gonio::material::table::ROWS
        .iter()
        .map(|row| row.model.name())
        .filter(|name| !models.iter().any(|(m, _)| m == name))
        .filter(|name| *name != "measured")
        .map(|name| (name, &[][..]))
        .collect();
    for &(model, extra) in models.iter().chain(&unlisted) {
        let mut sets = vec![format!("materials.ball.model={model}")];
        sets.extend(extra.iter().map(|s| s.to_string()));
        let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
        let scene = load(SceneSource::BuiltIn, ShadingMode::Phong, &sets);
        gpu_vs_cpu(&format!("ball: {model} {}", extra.join(" ")), &scene);
    }
}

/// Roughness → 0 under a point light: a perfectly smooth surface reflects
/// the light into a single direction that falls between pixel centres, so
/// without the pixel-footprint floor (`Scene::roughness_floor`) a Beckmann
/// highlight at roughness 10⁻⁴ is exactly 0 at every pixel (e⁻¹³² and less).
/// With it the highlight is a bright, finite spot of about a pixel, and the
/// GPU and the reference agree on it.
#[test]
fn mirror_smooth_highlight_stays_visible_and_finite() {
    let scene = load(
        SceneSource::BuiltIn,
        ShadingMode::Phong,
        &[
            "materials.ball.model=cook-torrance",
            "materials.ball.distribution=beckmann",
            "materials.ball.roughness=0.0001",
            "materials.ball.k_d=0.2",
            "materials.ball.k_s=1",
            "materials.ball.preset=gold",
        ],
    );
    let floor = scene.roughness_floor();
    assert!(floor > 1e-3 && floor < 1e-2, "floor {floor}");
    let c = gpu_vs_cpu("ball: beckmann roughness 1e-4", &scene);
    let reference = reference::render(&scene);
    let peak = reference.max_radiance();
    // Diffuse alone is below 1; the mirror image of the light is far brighter.
    assert!(peak > 100.0 && peak.is_finite(), "highlight peak {peak}");
    eprintln!(
        "roughness 1e-4: floor {floor:.3e}, highlight peak {peak:.3e}, {}",
        c.summary()
    );
}

/// Emission adds to L_o on both sides: with the light and the ambient
/// term off, the ball's centre pixel is its emission exactly (in f32, as
/// the GPU holds it), and the floor, which emits nothing, is black.
#[test]
fn emission_is_what_an_unlit_surface_shows() {
    let emission = [0.25f32, 0.5, 1.0];
    let scene = load(
        SceneSource::BuiltIn,
        ShadingMode::Phong,
        &[
            "materials.ball.model=gltf-pbr",
            "materials.ball.emission=[0.25, 0.5, 1.0]",
            "lights.0.intensity=0.0",
            "ambient.radiance=0.0",
        ],
    );
    let mut renderer = common::gpu_renderer();
    let (gpu, _) = renderer.render(&scene).expect("GPU render");
    let reference = reference::render(&scene);
    let (w, h) = (scene.width as usize, scene.height as usize);
    let centre = (h / 2) * w + w / 2;
    for frame in [&gpu, &reference] {
        assert_eq!(frame.radiance[centre], emission, "centre pixel");
        let bottom = (h - 2) * w + w / 2;
        assert_eq!(frame.radiance[bottom], [0.0; 3], "floor pixel");
    }
}

/// Energy compensation on under the built-in scene's
/// point light: the GPU reads the same f32 albedo nodes as the f64
/// reference (`Globals::albedo`, `DfgTable::albedo`), so they agree
/// within the shared tolerance plus the lookup's own f32 error
/// (`energy::F32_ERROR`, in `common::arithmetic_rel`): gltf-pbr metal and
/// dielectric, Cook-Torrance of the table's own terms and the lecture's
/// Beckmann gold (a GGX stand-in), and a compensated material beside an
/// uncompensated one (the feature is per scene, the weight per material).
#[test]
fn energy_compensation_renders_like_the_reference() {
    let cases: &[&[&str]] = &[
        &[
            "materials.ball.model=gltf-pbr",
            "materials.ball.base_color=[0.95, 0.64, 0.54]",
            "materials.ball.metallic=1",
            "materials.ball.roughness=0.8",
        ],
        &[
            "materials.ball.model=gltf-pbr",
            "materials.ball.base_color=[0.2, 0.5, 0.9]",
            "materials.ball.metallic=0",
            "materials.ball.roughness=0.5",
        ],
        &[
            "materials.ball.model=cook-torrance",
            "materials.ball.distribution=ggx",
            "materials.ball.geometry=smith-correlated",
            "materials.ball.fresnel=schlick",
            "materials.ball.k_d=0",
            "materials.ball.k_s=1",
            "materials.ball.roughness=0.6",
        ],
        &[
            "materials.ball.model=cook-torrance",
            "materials.ball.preset=gold",
            "materials.ball.k_d=0.1",
            "materials.ball.roughness=0.4",
        ],
    ];
    for extra in cases {
        let mut sets: Vec<&str> = extra.to_vec();
        sets.push("materials.ball.energy_compensation=true");
        let scene = load(SceneSource::BuiltIn, ShadingMode::Phong, &sets);
        assert!(scene.materials.iter().any(|m| m.energy_compensation));
        gpu_vs_cpu(&format!("compensated: {}", extra.join(" ")), &scene);
    }
}

/// A one-frame render (`gonio render`) draws a scene of several BRDF
/// variants with the one pipeline that switches per material (one
/// compilation), the viewer with one pipeline specialized per variant.
/// Both run the same WGSL expressions for a material's own arm (the
/// specialization constants only remove the others, and WGSL compilers do
/// not reassociate floating point), so the frames must agree to the last
/// bits: 4 f32 ulps relative (2⁻²¹) or 10⁻⁷ absolute.
#[test]
fn one_switching_pipeline_draws_what_the_specialized_ones_draw() {
    // The built-in scene: a Cook-Torrance ball on a Lambert floor.
    let scene = load(
        SceneSource::BuiltIn,
        ShadingMode::Phong,
        &[
            "materials.ball.model=\"cook-torrance\"",
            "materials.ball.k_s=[0.5, 0.5, 0.5]",
            "materials.ball.roughness=0.2",
        ],
    );
    let mut specialized = common::gpu_renderer();
    let mut switching = common::gpu_renderer();
    switching.set_one_pipeline(true);
    let a = specialized.render(&scene).unwrap().0;
    let b = switching.render(&scene).unwrap().0;
    let mut worst = 0.0f64;
    let mut lit = 0;
    for (p, q) in a.radiance.iter().zip(&b.radiance) {
        for c in 0..3 {
            let (p, q) = (f64::from(p[c]), f64::from(q[c]));
            lit += usize::from(p > 1e-3);
            worst = worst.max((p - q).abs() / (2f64.powi(-21) * p.abs().max(q.abs()) + 1e-7));
        }
    }
    eprintln!("{lit} lit channels; worst difference {worst:.3} × the bound");
    assert!(lit > 1000, "{lit} lit channels");
    assert!(
        worst <= 1.0,
        "switching and specialized pipelines differ: {worst:.3} × the bound"
    );
}

/// Facing normals (`Material::facing_normals`, glTF materials): a floor
/// whose every vertex normal points down, away from the camera above it,
/// lit by a light from the camera's side and slightly below, is shaded with its normals turned toward the viewer
/// (`SurfaceFrame::facing`) alike on the GPU and in the reference, per
/// pixel and per vertex; without them the floor is its ambient term
/// alone (the one-sided reflection equation is 0 there), which the turned
/// normals must exceed.
#[test]
fn facing_normals_render_like_the_reference() {
    for mode in [ShadingMode::Phong, ShadingMode::Gouraud] {
        let mut scene = load(
            SceneSource::BuiltIn,
            mode,
            &[
                "materials.floor.model=gltf-pbr",
                "materials.floor.base_color=[0.6, 0.5, 0.4]",
                "materials.floor.metallic=0",
                "materials.floor.roughness=0.5",
            ],
        );
        let floor = scene
            .materials
            .iter()
            .position(|m| m.name == "floor")
            .expect("the built-in scene has a floor");
        for mesh in scene.meshes.iter_mut().filter(|m| m.material == floor) {
            mesh.normals.iter_mut().for_each(|n| *n = -glam::DVec3::Y);
        }
        let (eye, ambient) = (scene.camera.position, scene.ambient);
        // A turned normal lies just past the silhouette, facing the
        // camera's side, so a light from above cannot reach it; one from
        // the camera's side, slightly below the floor, does.
        let v = eye - scene.camera.target;
        scene.lights.push(gonio::scene::Light::Directional {
            direction: -glam::DVec3::new(v.x, -0.3 * v.length(), v.z).normalize(),
            irradiance: glam::DVec3::splat(2.0),
            shadows: false,
        });
        let facing_away = scene
            .meshes
            .iter()
            .filter(|m| m.material == floor)
            .flat_map(|m| m.positions.iter().zip(&m.normals))
            .all(|(x, n)| n.dot(eye - *x) < 0.0);
        assert!(facing_away, "every floor normal faces away from the eye");

        let mut renderer = common::gpu_renderer();
        let (without, _) = renderer.render(&scene).expect("GPU render");
        scene.materials[floor].facing_normals = true;
        let with = gpu_vs_cpu(&format!("facing normals, {mode}"), &scene);
        let (turned, _) = common::gpu_renderer().render(&scene).expect("GPU render");
        // The floor's pixels: the bottom row, centre (the ball is above).
        let (w, h) = (scene.width as usize, scene.height as usize);
        let at = |f: &Frame| f.radiance[(h - 2) * w + w / 2];
        let k_a = scene.materials[floor].k_a;
        let ambient_only = [k_a.x * ambient.x, k_a.y * ambient.y, k_a.z * ambient.z];
        for c in 0..3 {
            assert!(
                (at(&without)[c] as f64 - ambient_only[c]).abs() <= 1e-6 * ambient_only[c].max(1.0),
                "{mode}: without facing normals the floor is its ambient term: {:?} vs {ambient_only:?}",
                at(&without)
            );
        }
        assert!(
            at(&turned).iter().sum::<f32>() > 2.0 * at(&without).iter().sum::<f32>() + 0.01,
            "{mode}: the turned normals light the floor: {:?} vs {:?}",
            at(&turned),
            at(&without)
        );
        assert!(with.compared > 0);
    }
}
