//! The knobs of the speed/accuracy trade, each a list of settings, and
//! every setting a list of `--set` overrides on top of the base scene.
//!
//! Knobs are varied one at a time from the base, so each configuration
//! differs from the base in exactly one choice and its error is the cost
//! of that choice alone. A setting equal to the base's own value is the
//! base configuration itself (measured once). Overrides go through the
//! scene loader like a user's `--set`, so a knob a scene cannot take
//! (a material key on a glTF-only scene, an `image.msaa` the adapter
//! cannot multisample) fails to load or render and is reported as not
//! measured, with the reason.

use crate::material::{Distribution, Fresnel, Geometry, ReflectanceModel, SmithBeckmann};
use crate::scene::{Light, MapResolution, Scene, ShadowFilter};

/// What the bench adds to the built-in scene so that every knob has
/// something to act on: the sphere becomes Cook-Torrance gold with the
/// exact conductor Fresnel, the point light casts shadows, and a
/// rectangular area light (unshadowed, 16 samples) lights the scene from
/// the left. Printed in the report.
pub const BUILTIN_BASE: &[&str] = &[
    "materials.ball.model=cook-torrance",
    "materials.ball.preset=gold",
    "materials.ball.distribution=beckmann",
    "materials.ball.geometry=smith",
    "materials.ball.fresnel=conductor",
    "materials.ball.roughness=0.25",
    "materials.ball.k_d=[0.05, 0.02, 0.0]",
    "materials.ball.k_s=0.9",
    "lights=[{kind=\"point\", position=[3.0, 5.0, 3.0], intensity=[60.0, 60.0, 60.0], shadows=true}, \
{kind=\"area\", shape=\"rect\", position=[-3.0, 2.5, 1.5], normal=[0.8, -0.3, -0.4], size=[1.5, 1.0], \
tangent=[0.0, 0.0, 1.0], radiance=[6.0, 6.0, 6.0], samples=16}]",
];

/// The gltf-pbr material every layer knob starts from (keys of the
/// bench's target material): a rough dielectric, as tests/layers_gpu.rs
/// draws the layers.
pub const LAYER_CORE: &[&str] = &[
    "model=gltf-pbr",
    "base_color=[0.6, 0.25, 0.1]",
    "metallic=0",
    "roughness=0.4",
];

/// The start of the layer knobs' names (`layer clearcoat`).
pub const LAYER_KNOB: &str = "layer ";

/// The layer knobs: each glTF layer (contract "Layered glTF materials")
/// on over [`LAYER_CORE`], by its keys; `core` is the core alone, which
/// the others' cost is a ratio to, and `all` every layer at once.
pub const LAYERS: &[(&str, &[&str])] = &[
    ("core", &[]),
    (
        "ior/specular",
        &["ior=1.7", "specular_color=[1.0, 0.8, 0.6]"],
    ),
    ("clearcoat", &["clearcoat=1", "clearcoat_roughness=0.1"]),
    (
        "sheen",
        &["sheen_color=[0.8, 0.8, 0.8]", "sheen_roughness=0.5"],
    ),
    (
        "iridescence",
        &["iridescence=1", "iridescence_thickness=400"],
    ),
    ("anisotropy", &["anisotropy_strength=0.6"]),
    (
        "all",
        &[
            "ior=1.7",
            "specular_color=[1.0, 0.8, 0.6]",
            "clearcoat=1",
            "clearcoat_roughness=0.1",
            "sheen_color=[0.8, 0.8, 0.8]",
            "sheen_roughness=0.5",
            "iridescence=1",
            "iridescence_thickness=400",
            "anisotropy_strength=0.6",
        ],
    ),
];

/// Each layer of the glTF material on material `name`
/// as a gltf-pbr material ([`LAYERS`]): its cost against the core
/// gltf-pbr ([`LAYER_CORE`]), its error against its own scene's
/// reference.
fn layer_configs(name: &str) -> Vec<Config> {
    LAYERS
        .iter()
        .map(|(layer, keys)| Config {
            knob: format!("{LAYER_KNOB}{layer}"),
            value: "on".into(),
            overrides: LAYER_CORE
                .iter()
                .chain(keys.iter())
                .map(|kv| format!("materials.{name}.{kv}"))
                .collect(),
            own_truth: true,
        })
        .collect()
}

/// Samples per area light of the truth image.
pub const TRUTH_AREA_SAMPLES: u32 = 256;

/// One configuration to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// The knob varied ("base" for the base configuration).
    pub knob: String,
    /// The knob's setting, as the report prints it.
    pub value: String,
    /// `--set` overrides on top of the base scene's.
    pub overrides: Vec<String>,
    /// Its error is measured against the reference of its own scene, not
    /// the base's truth: a knob that changes what is drawn (a glTF
    /// layer, [`LAYERS`]), whose error is then what the GPU gets wrong
    /// about it. `--max-error` never picks it (`results.csv` leaves it
    /// out).
    pub own_truth: bool,
}

impl Config {
    /// The base configuration.
    pub fn base() -> Self {
        Config {
            knob: "base".into(),
            value: "as loaded".into(),
            overrides: Vec::new(),
            own_truth: false,
        }
    }

    /// `knob=value` for labels.
    pub fn label(&self) -> String {
        if self.knob == "base" {
            "base".into()
        } else {
            format!("{}={}", self.knob, self.value)
        }
    }
}

/// A knob that was not measured, and why.
#[derive(Clone, Debug)]
pub struct Skipped {
    pub knob: String,
    pub reason: String,
}

/// The configurations for `base` (the loaded base scene): the base first,
/// then each knob's settings that differ from it. `smoke` keeps two
/// settings per knob.
pub fn configs(base: &Scene, smoke: bool) -> (Vec<Config>, Vec<Skipped>) {
    let mut out = vec![Config::base()];
    let mut skipped = Vec::new();
    let mut knob = |name: &str, settings: Vec<(String, Vec<String>, bool)>, missing: &str| {
        if settings.is_empty() {
            skipped.push(Skipped {
                knob: name.into(),
                reason: missing.into(),
            });
            return;
        }
        let mut settings: Vec<_> = settings
            .into_iter()
            .filter(|(.., is_base)| !is_base)
            .collect();
        if smoke {
            settings.truncate(1);
        }
        for (value, overrides, _) in settings {
            out.push(Config {
                knob: name.into(),
                value,
                overrides,
                own_truth: false,
            });
        }
    };

    let shading = crate::scene::ShadingMode::ALL
        .iter()
        .map(|m| {
            (
                m.name().to_string(),
                vec![format!("shading.mode={m}")],
                *m == base.shading,
            )
        })
        .collect();
    knob("shading", shading, "");

    // Light through surfaces (docs/transmission.md, "The GPU renderer"):
    // off (drawn as if opaque), screen space with one interface (the
    // Khronos sample renderer's), with a volume's exit interface and 1,
    // 2 and 4 layers of what lies behind, and one layer with the exit ray
    // traced in screen space; a knob only where a drawn material
    // transmits.
    let transmits = base
        .meshes
        .iter()
        .any(|m| base.materials[m.material].transmits_specularly());
    let transmission = if transmits {
        use crate::scene::{TransmissionExitRay, TransmissionMode};
        let current = base.transmission;
        let mut v = vec![(
            "off".to_string(),
            vec!["shading.transmission=\"off\"".to_string()],
            current.mode == TransmissionMode::Off,
        )];
        let thickness = TransmissionExitRay::Thickness;
        for (layers, exit, ray) in [
            (1u32, false, thickness),
            (1, true, thickness),
            (2, true, thickness),
            (4, true, thickness),
            (1, true, TransmissionExitRay::Traced),
        ] {
            v.push((
                format!(
                    "screen {layers}{}{}",
                    if exit { "" } else { " one interface" },
                    if ray == thickness { "" } else { " traced" }
                ),
                vec![
                    "shading.transmission=\"screen\"".to_string(),
                    format!("shading.transmission_layers={layers}"),
                    format!("shading.transmission_exit={exit}"),
                    format!("shading.transmission_exit_ray=\"{ray}\""),
                ],
                current.mode == TransmissionMode::Screen
                    && current.layers == layers
                    && current.exit == exit
                    && current.exit_ray == ray,
            ));
        }
        v
    } else {
        Vec::new()
    };
    knob("transmission", transmission, "no drawn material transmits");

    // Material knobs act on the glossy materials (all if none is glossy),
    // by name, as a user's `--set materials.NAME.KEY` would.
    let glossy: Vec<&crate::material::Material> = base
        .materials
        .iter()
        .filter(|m| m.model != ReflectanceModel::Lambert)
        .collect();
    let targets: Vec<&crate::material::Material> = if glossy.is_empty() {
        base.materials.iter().collect()
    } else {
        glossy
    };
    let set_all = |key: &str, value: &str| -> Vec<String> {
        targets
            .iter()
            .map(|m| format!("materials.{}.{key}={value}", m.name))
            .collect()
    };
    let first = targets.first().copied();
    // The models the table marks as benched, the later (more elaborate)
    // ones first: a smoke run measures the first that differs from the base.
    let models = crate::material::table::ROWS
        .iter()
        .rev()
        .filter(|row| row.benched)
        .map(|row| row.model);
    let model_settings = match first {
        Some(m) => models
            .map(|model| {
                (
                    model.name().to_string(),
                    set_all("model", model.name()),
                    model == m.model,
                )
            })
            .collect(),
        None => Vec::new(),
    };
    knob("model", model_settings, "the scene has no materials");

    let ct = first.filter(|m| m.model == ReflectanceModel::CookTorrance);
    let fresnel = match ct {
        Some(m) => [
            Fresnel::Conductor,
            Fresnel::ConductorLecture,
            Fresnel::Schlick,
        ]
        .iter()
        .map(|&f| {
            (
                f.name().to_string(),
                set_all("fresnel", f.name()),
                f == m.fresnel,
            )
        })
        .collect(),
        None => Vec::new(),
    };
    knob(
        "fresnel",
        fresnel,
        "no Cook-Torrance material in the base scene",
    );
    let distribution = match ct {
        Some(m) => [
            Distribution::Beckmann,
            Distribution::Ggx,
            Distribution::Blinn,
            Distribution::Gaussian,
        ]
        .iter()
        .map(|&d| {
            (
                d.name().to_string(),
                set_all("distribution", d.name()),
                d == m.distribution,
            )
        })
        .collect(),
        None => Vec::new(),
    };
    knob(
        "distribution",
        distribution,
        "no Cook-Torrance material in the base scene",
    );

    // How the GPU evaluates Smith's G1 for Beckmann:
    // the exact form with an f32 erf, or Walter's rational approximation
    // (no exp). The truth always takes the exact form, so the rational
    // setting's error is its cost in the image.
    let beckmann_g1 = targets.iter().any(|m| {
        m.model == ReflectanceModel::CookTorrance
            && matches!(m.geometry, Geometry::Smith | Geometry::SmithCorrelated)
            && m.distribution != Distribution::Ggx
    });
    let g1_forms = if beckmann_g1 {
        SmithBeckmann::ALL
            .iter()
            .map(|&f| {
                (
                    f.name().to_string(),
                    vec![format!("shading.smith_beckmann=\"{f}\"")],
                    f == base.smith_beckmann,
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    knob(
        "smith_beckmann",
        g1_forms,
        "no Cook-Torrance material with Smith's G over a Beckmann-like distribution in the base scene",
    );

    // Energy compensation on the targets that offer it:
    // its cost is the albedo-table lookup per light and pixel; its
    // "error" against the truth (the base's, uncompensated unless the
    // base has it) is the energy it adds back.
    let compensable: Vec<&&crate::material::Material> = targets
        .iter()
        .filter(|m| m.model.row().energy_compensation)
        .collect();
    let compensation = match compensable.first() {
        Some(m) => [false, true]
            .iter()
            .map(|&on| {
                (
                    if on { "on" } else { "off" }.to_string(),
                    compensable
                        .iter()
                        .map(|m| format!("materials.{}.energy_compensation={on}", m.name))
                        .collect(),
                    on == m.energy_compensation,
                )
            })
            .collect(),
        None => Vec::new(),
    };
    knob(
        "energy_compensation",
        compensation,
        "no gltf-pbr or Cook-Torrance material in the base scene",
    );

    let layers = first.map(|m| layer_configs(&m.name));

    // Shadow knobs go through `[shadows]`, the defaults of every light
    // that does not set its own.
    let shadowed = (0..base.lights.len()).find(|&l| base.lights[l].casts_shadows());
    let map_size = match shadowed {
        Some(l) => {
            let current = base.shadow_settings(l).map_size;
            let sizes: &[u32] = if smoke {
                &[64]
            } else {
                &[256, 512, 1024, 2048, 4096]
            };
            sizes
                .iter()
                .map(|&s| {
                    (
                        s.to_string(),
                        vec![format!("shadows.map_size={s}")],
                        s == current,
                    )
                })
                .collect()
        }
        None => Vec::new(),
    };
    knob("shadow_map_size", map_size, "no light casts shadows");
    let pcf = match shadowed {
        Some(l) => {
            let current = base.shadow_settings(l).filter;
            let mut v = vec![(
                "none".to_string(),
                vec!["shadows.filter=none".to_string()],
                current == ShadowFilter::None,
            )];
            for k in [3u32, 5, 7] {
                v.push((
                    format!("pcf {k}x{k}"),
                    vec![
                        "shadows.filter=pcf".into(),
                        format!("shadows.pcf_kernel={k}"),
                    ],
                    current == ShadowFilter::Pcf { kernel: k },
                ));
            }
            v
        }
        None => Vec::new(),
    };
    knob("shadow_filter", pcf, "no light casts shadows");
    // Fixed sides against sides fitted to the screen (src/gpu/shadow_fit.rs)
    // at one and at half a texel per pixel, capped by the map size.
    let resolution = match shadowed {
        Some(l) => {
            let current = base.shadow_settings(l).resolution;
            let mut v = vec![(
                "fixed".to_string(),
                vec!["shadows.resolution=fixed".to_string()],
                current == MapResolution::Fixed,
            )];
            for t in [1.0, 0.5] {
                v.push((
                    format!("fit {t}"),
                    vec![
                        "shadows.resolution=fit".into(),
                        format!("shadows.texels_per_pixel={t}"),
                    ],
                    current
                        == MapResolution::Fit {
                            texels_per_pixel: t,
                        },
                ));
            }
            v
        }
        None => Vec::new(),
    };
    knob("shadow_resolution", resolution, "no light casts shadows");
    // Shadow-map coordinates per vertex where that is an approximation:
    // a knob only where "vertex" compiles another
    // shader than "exact" (Phong shading, one perspective map: a spot
    // light), its error the lookup points' displacement
    // (docs/shadows.md, "Coordinates per vertex").
    let coords = if approximate_coords_apply(base) {
        crate::scene::ShadowCoords::ALL
            .iter()
            .map(|&c| {
                (
                    c.name().to_string(),
                    vec![format!("shading.shadow_coords=\"{c}\"")],
                    c == base.shadow_coords,
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    knob(
        "shadow_coords",
        coords,
        "no Phong-shaded scene whose one shadow map is a spot light's perspective map",
    );

    let area = area_entry(base);
    let samples = match area {
        Some((entry, current)) => [1u32, 4, 16, 64, TRUTH_AREA_SAMPLES]
            .iter()
            .map(|&n| {
                (
                    n.to_string(),
                    vec![format!("lights.{entry}.samples={n}")],
                    n == current,
                )
            })
            .collect(),
        None => Vec::new(),
    };
    knob("area_samples", samples, "no area light in the scene file");

    // How the environment lights the surfaces: the diffuse term by SH
    // alone, the whole BRDF with N directions, the split-sum glossy
    // term at three stack sizes, or the Phong lobes by SH convolution
    // (the SH order is the base's; the truth integrates
    // the whole BRDF: measure::truth).
    let specular = match &base.environment.map {
        Some(map) => {
            use crate::environment::map::Specular;
            let s = map.settings;
            let mut v = vec![(
                "sh diffuse".to_string(),
                vec!["environment.specular=none".to_string()],
                s.specular == Specular::None,
            )];
            for n in [16u32, 64, 256] {
                v.push((
                    format!("sampled {n}"),
                    vec![
                        "environment.specular=sampled".into(),
                        format!("environment.samples={n}"),
                    ],
                    s.specular == Specular::Sampled && s.samples == n,
                ));
            }
            for size in [64u32, 128, 256] {
                v.push((
                    format!("prefiltered {size}"),
                    vec![
                        "environment.specular=prefiltered".into(),
                        format!("environment.prefilter_size={size}"),
                    ],
                    s.specular == Specular::Prefiltered && s.prefilter_size == size,
                ));
            }
            v.push((
                "sh phong".to_string(),
                vec!["environment.specular=sh".to_string()],
                s.specular == Specular::Sh,
            ));
            v
        }
        None => Vec::new(),
    };
    knob(
        "environment_specular",
        specular,
        "the scene has no environment map",
    );

    // The SH bands of the diffuse term (and of the "sh" mode's lobes):
    // the error-vs-order trade on the Pareto front.
    let orders = match &base.environment.map {
        Some(map) => (0..=crate::environment::sh::MAX_ORDER)
            .map(|k| {
                (
                    format!("order {k}"),
                    vec![format!("environment.sh_order={k}")],
                    map.settings.sh_order == k,
                )
            })
            .collect(),
        None => Vec::new(),
    };
    knob(
        "environment_sh_order",
        orders,
        "the scene has no environment map",
    );

    // Not in the renderer yet: the loader refuses the key and the knob is
    // reported as not measured (see the module docs).
    knob(
        "msaa",
        vec![("4".into(), vec!["image.msaa=4".into()], false)],
        "",
    );

    let resolution = [(0.5, "0.5x"), (1.0, "1x"), (2.0, "2x")]
        .iter()
        .map(|&(s, label)| {
            let (w, h) = scaled(base.width, base.height, s);
            (
                format!("{label} ({w}x{h})"),
                vec![format!("image.width={w}"), format!("image.height={h}")],
                s == 1.0,
            )
        })
        .collect();
    knob("resolution", resolution, "");

    // Measured materials: the table's resolution and the network in WGSL
    // (docs/measured.md), against the reference's network in f64.
    let has_measured = base
        .materials
        .iter()
        .any(|m| m.model == ReflectanceModel::Measured);
    let modes = if has_measured {
        [("table", false), ("network", true)]
            .iter()
            .map(|&(name, network)| {
                (
                    name.to_string(),
                    vec![format!("shading.measured_mode=\"{name}\"")],
                    network == base.measured_network,
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    knob(
        "measured_mode",
        modes,
        "no measured material in the base scene",
    );
    let tables = if has_measured && !base.measured_network {
        [[16, 16, 32], [32, 32, 64], [45, 45, 90], [90, 90, 180]]
            .iter()
            .map(|&[h, d, p]| {
                (
                    format!("{h}x{d}x{p}"),
                    vec![format!("shading.measured_table=[{h}, {d}, {p}]")],
                    [h, d, p] == base.measured_table,
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    knob(
        "measured_table",
        tables,
        "no measured material looked up in a table in the base scene",
    );
    match layers {
        Some(layers) => out.extend(layers),
        None => skipped.push(Skipped {
            knob: LAYER_KNOB.trim().into(),
            reason: "the scene has no materials".into(),
        }),
    }
    (out, skipped)
}

/// The base scene's `[environment]` table after its overrides (`None`
/// without one): what [`whole_environment`] rewrites the specular mode's
/// settings against.
pub fn environment_section(
    source: &crate::scene::scene_file::SceneSource,
    base_overrides: &[String],
) -> crate::Result<Option<toml::Table>> {
    let (_, _, mut table) = crate::scene::scene_file::scene_table(source)?;
    for o in base_overrides {
        crate::scene::scene_file::overrides::apply_override(&mut table, o)?;
    }
    Ok(match table.remove("environment") {
        Some(toml::Value::Table(t)) => Some(t),
        _ => None,
    })
}

/// The keys of `[environment]` that belong to one specular mode: the
/// loader refuses each under another mode (nothing typed is ignored).
const MODE_KEYS: [&str; 3] = ["specular", "samples", "prefilter_size"];

/// The `environment_specular` settings as one override of the whole
/// `[environment]` table: the base's `section` without its mode keys,
/// plus the setting's own. As separate `--set`s they kept the base's
/// other mode keys, so a base with `samples = 32` (sampled) failed to
/// load every non-sampled setting ("environment.samples applies to
/// environment.specular = \"sampled\""), and one with `prefilter_size`
/// every non-prefiltered one. Other configurations are returned as they
/// are.
pub fn whole_environment(configs: Vec<Config>, section: Option<&toml::Table>) -> Vec<Config> {
    let Some(section) = section else {
        return configs;
    };
    configs
        .into_iter()
        .map(|mut c| {
            if c.knob != "environment_specular" {
                return c;
            }
            let mut table = section.clone();
            for key in MODE_KEYS {
                table.remove(key);
            }
            for o in &c.overrides {
                if let Some((key, value)) = o.split_once('=')
                    && let Some(key) = key.strip_prefix("environment.")
                {
                    table.insert(
                        key.to_string(),
                        crate::scene::scene_file::overrides::value_of(value),
                    );
                }
            }
            c.overrides = vec![format!("environment={}", toml::Value::Table(table))];
            c
        })
        .collect()
}

/// Whether `a` and `b` draw the same image: same size, shading, lights
/// and shadow settings, same triangles with the same material on each
/// mesh. An override that changes nothing drawn (a material key on a
/// glTF-only scene creates a material no mesh uses) is not a knob
/// setting worth timing.
pub fn draws_the_same(a: &Scene, b: &Scene) -> bool {
    let used = |s: &Scene| -> Vec<crate::material::Material> {
        s.meshes
            .iter()
            .map(|m| s.materials[m.material].clone())
            .collect()
    };
    a.width == b.width
        && a.height == b.height
        && a.msaa == b.msaa
        && a.shading == b.shading
        && a.lights == b.lights
        && a.light_shadows == b.light_shadows
        && a.area_lights == b.area_lights
        && a.triangle_count() == b.triangle_count()
        && used(a) == used(b)
        && a.environment.map.as_ref().map(|m| m.settings)
            == b.environment.map.as_ref().map(|m| m.settings)
        && a.measured_network == b.measured_network
        && a.measured_table == b.measured_table
        && a.smith_beckmann == b.smith_beckmann
        && a.shadow_coords == b.shadow_coords
        && a.transmission == b.transmission
}

/// Whether `shading.shadow_coords = "vertex"` would move some shadow
/// coordinates of `scene` per vertex that "exact" computes per pixel
/// (`ShaderKey::shadow_coords_per_vertex`).
fn approximate_coords_apply(scene: &Scene) -> bool {
    use crate::gpu::shader_gen::ShaderKey;
    let mut key = ShaderKey::new(scene, &crate::gpu::shadows::ShadowPlan::new(scene));
    key.shadows.approximate_coords = false;
    let exact = key.shadow_coords_per_vertex();
    key.shadows.approximate_coords = true;
    key.shadow_coords_per_vertex() != exact
}

/// `(width, height)` scaled by `s`, at least 1 pixel.
pub fn scaled(width: u32, height: u32, s: f64) -> (u32, u32) {
    let f = |v: u32| ((v as f64 * s).round() as u32).max(1);
    (f(width), f(height))
}

/// The `[[lights]]` index of the first area light and its sample count,
/// counting each area light's samples as the one file entry they came
/// from (lights imported from glTF files come after the file's own and
/// are never area lights).
fn area_entry(scene: &Scene) -> Option<(usize, u32)> {
    let mut entry = 0;
    let mut seen_area = None;
    for light in &scene.lights {
        match *light {
            Light::AreaSample { area, .. } => {
                if seen_area != Some(area) {
                    if let Some(a) = scene.area_lights.get(area) {
                        return Some((entry, a.samples));
                    }
                    seen_area = Some(area);
                }
            }
            _ => entry += 1,
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::{SceneSource, load};

    fn builtin_base() -> Scene {
        let overrides: Vec<String> = BUILTIN_BASE.iter().map(|s| s.to_string()).collect();
        load(&SceneSource::BuiltIn, &overrides).unwrap()
    }

    #[test]
    fn builtin_base_has_something_for_every_knob() {
        let base = builtin_base();
        let (configs, skipped) = configs(&base, false);
        // Every layer knob, each against its own reference.
        let layers: Vec<&Config> = configs
            .iter()
            .filter(|c| c.knob.starts_with(LAYER_KNOB))
            .collect();
        assert_eq!(layers.len(), LAYERS.len());
        assert!(layers.iter().all(|c| c.own_truth));
        assert!(
            configs
                .iter()
                .filter(|c| !c.knob.starts_with(LAYER_KNOB))
                .all(|c| !c.own_truth)
        );
        // The built-in base has no environment map (its truth would
        // integrate the map per pixel): environment_specular_is_a_knob;
        // and no measured material: measured_knobs_with_a_measured_base.
        let names: Vec<&str> = skipped.iter().map(|s| s.knob.as_str()).collect();
        assert_eq!(
            names,
            [
                "transmission",
                "shadow_coords",
                "environment_specular",
                "environment_sh_order",
                "measured_mode",
                "measured_table"
            ],
            "{skipped:?}"
        );
        let knobs: std::collections::BTreeSet<_> =
            configs.iter().map(|c| c.knob.as_str()).collect();
        for k in [
            "base",
            "shading",
            "model",
            "fresnel",
            "distribution",
            "shadow_map_size",
            "shadow_filter",
            "shadow_resolution",
            "area_samples",
            "msaa",
            "resolution",
            "energy_compensation",
            "smith_beckmann",
        ] {
            assert!(knobs.contains(k), "knob {k} missing");
        }
        // The base's own settings are not repeated.
        assert!(!configs.iter().any(|c| c.label() == "shading=phong"));
        assert!(!configs.iter().any(|c| c.label() == "fresnel=conductor"));
        assert!(!configs.iter().any(|c| c.label() == "smith_beckmann=erf"));
        assert!(
            configs
                .iter()
                .any(|c| c.label() == "smith_beckmann=rational")
        );
        assert!(!configs.iter().any(|c| c.label() == "area_samples=16"));
        assert!(
            !configs
                .iter()
                .any(|c| c.label() == "energy_compensation=off")
        );
        // Every knob setting loads (MSAA may still be refused at render
        // time by an adapter without multisampled float targets).
        for c in &configs {
            let overrides: Vec<String> = BUILTIN_BASE
                .iter()
                .map(|s| s.to_string())
                .chain(c.overrides.iter().cloned())
                .collect();
            let loaded = load(&SceneSource::BuiltIn, &overrides);
            if c.knob != "msaa" {
                loaded.unwrap_or_else(|e| panic!("{}: {e}", c.label()));
            }
        }
    }

    /// With one shadowed spot light (a perspective map) under Phong
    /// shading the shadow coordinates are a knob, and "vertex" draws
    /// something else than the base; a second shadowed light (two maps)
    /// or Gouraud shading leaves nothing for it to act on.
    #[test]
    fn shadow_coords_is_a_knob_with_one_spot_map() {
        let spot = r#"{kind="spot", position=[2.0, 4.0, 2.0], direction=[-0.4, -1.0, -0.4], intensity=[30.0, 30.0, 30.0], outer_cone_deg=40.0, shadows=true}"#;
        let with = |extra: &[&str]| {
            let overrides: Vec<String> = BUILTIN_BASE
                .iter()
                .map(|s| s.to_string())
                .chain(extra.iter().map(|s| s.to_string()))
                .collect();
            (load(&SceneSource::BuiltIn, &overrides).unwrap(), overrides)
        };
        let one = format!("lights=[{spot}]");
        let (base, overrides) = with(&[one.as_str()]);
        let (found, skipped) = configs(&base, false);
        assert!(!skipped.iter().any(|s| s.knob == "shadow_coords"));
        let settings: Vec<_> = found.iter().filter(|c| c.knob == "shadow_coords").collect();
        assert_eq!(settings.len(), 1, "{settings:?}");
        assert_eq!(settings[0].value, "vertex");
        let all: Vec<String> = overrides
            .iter()
            .chain(&settings[0].overrides)
            .cloned()
            .collect();
        let vertex = load(&SceneSource::BuiltIn, &all).unwrap();
        assert!(!draws_the_same(&base, &vertex));
        let two = format!(
            r#"lights=[{spot}, {{kind="point", position=[3.0, 5.0, 3.0], intensity=[1.0, 1.0, 1.0], shadows=true}}]"#
        );
        for extra in [
            vec![two.as_str()],
            vec![one.as_str(), "shading.mode=gouraud"],
        ] {
            let (base, _) = with(&extra);
            let (_, skipped) = configs(&base, false);
            assert!(
                skipped.iter().any(|s| s.knob == "shadow_coords"),
                "{extra:?}"
            );
        }
    }

    /// With an environment map the specular mode is a knob: every
    /// setting loads, and each draws something else than the base.
    #[test]
    fn environment_specular_is_a_knob() {
        let overrides: Vec<String> = BUILTIN_BASE
            .iter()
            .map(|s| s.to_string())
            .chain(["environment.map=\"sky\"".to_string()])
            .collect();
        let base = load(&SceneSource::BuiltIn, &overrides).unwrap();
        let (configs, skipped) = configs(&base, false);
        assert!(
            skipped.iter().all(|s| s.knob.starts_with("measured_")
                || s.knob == "shadow_coords"
                || s.knob == "transmission"),
            "{skipped:?}"
        );
        let settings: Vec<_> = configs
            .iter()
            .filter(|c| c.knob == "environment_specular")
            .collect();
        // The base (SH diffuse) is not repeated: the three sampled, the
        // three prefiltered ones and the SH Phong convolution.
        assert_eq!(settings.len(), 7, "{settings:?}");
        for c in settings {
            let all: Vec<String> = overrides.iter().chain(&c.overrides).cloned().collect();
            let scene =
                load(&SceneSource::BuiltIn, &all).unwrap_or_else(|e| panic!("{}: {e}", c.label()));
            assert!(!draws_the_same(&base, &scene), "{}", c.label());
        }
        // The SH order: the four orders other than the base's (2).
        let orders: Vec<_> = configs
            .iter()
            .filter(|c| c.knob == "environment_sh_order")
            .collect();
        assert_eq!(orders.len(), 4, "{orders:?}");
        for c in orders {
            let all: Vec<String> = overrides.iter().chain(&c.overrides).cloned().collect();
            let scene =
                load(&SceneSource::BuiltIn, &all).unwrap_or_else(|e| panic!("{}: {e}", c.label()));
            assert!(!draws_the_same(&base, &scene), "{}", c.label());
        }
    }

    /// A base that sets a mode's own key (`samples = 32` with "sampled",
    /// or `prefilter_size` with "prefiltered") loads every other setting
    /// of the knob (it failed: the base's key stayed beside the new
    /// mode), each with the base's other environment keys (scale,
    /// rotation, order) kept.
    #[test]
    fn environment_specular_loads_over_a_base_with_mode_keys() {
        for mode in [
            &["environment.specular=sampled", "environment.samples=32"][..],
            &[
                "environment.specular=prefiltered",
                "environment.prefilter_size=32",
            ][..],
        ] {
            let overrides: Vec<String> = BUILTIN_BASE
                .iter()
                .map(|s| s.to_string())
                .chain([
                    "environment.map=\"sky\"".to_string(),
                    "environment.scale=0.3".into(),
                    "environment.rotation_deg=40".into(),
                ])
                .chain(mode.iter().map(|s| s.to_string()))
                .collect();
            let source = SceneSource::BuiltIn;
            let base = load(&source, &overrides).unwrap();
            let section = environment_section(&source, &overrides).unwrap();
            let (all, _) = configs(&base, false);
            let settings: Vec<_> = whole_environment(all, section.as_ref())
                .into_iter()
                .filter(|c| c.knob == "environment_specular")
                .collect();
            // None is the base (32 is not a setting of the knob).
            assert_eq!(settings.len(), 8, "{mode:?}: {settings:?}");
            for c in settings {
                let all: Vec<String> = overrides.iter().chain(&c.overrides).cloned().collect();
                let scene =
                    load(&source, &all).unwrap_or_else(|e| panic!("{mode:?}, {}: {e}", c.label()));
                let settings = scene.environment.map.as_ref().unwrap().settings;
                assert_eq!(
                    (settings.scale, settings.rotation_deg),
                    (0.3, 40.0),
                    "{}",
                    c.label()
                );
                assert!(!draws_the_same(&base, &scene), "{}", c.label());
            }
        }
    }

    #[test]
    fn a_setting_that_changes_nothing_is_recognized() {
        let base = builtin_base();
        assert!(draws_the_same(&base, &base.clone()));
        let with = |o: &str| {
            let mut overrides: Vec<String> = BUILTIN_BASE.iter().map(|s| s.to_string()).collect();
            overrides.push(o.into());
            load(&SceneSource::BuiltIn, &overrides).unwrap()
        };
        assert!(!draws_the_same(&base, &with("shading.mode=flat")));
        assert!(!draws_the_same(&base, &with("shadows.map_size=512")));
        assert!(!draws_the_same(
            &base,
            &with("materials.ball.fresnel=schlick")
        ));
        assert!(!draws_the_same(
            &base,
            &with("shading.smith_beckmann=rational")
        ));
        // A material no mesh uses changes nothing drawn.
        assert!(draws_the_same(&base, &with("materials.unused.model=ward")));
    }

    /// With a measured material the table's resolution and the network
    /// mode are knobs, and each setting draws something else.
    #[test]
    fn measured_knobs_with_a_measured_base() {
        let overrides =
            vec!["materials.ball={model=\"measured\", measured=\"chrome\"}".to_string()];
        let base = load(&SceneSource::BuiltIn, &overrides).unwrap();
        let (configs, _) = configs(&base, false);
        let settings: Vec<_> = configs
            .iter()
            .filter(|c| c.knob.starts_with("measured_"))
            .collect();
        // network, and three tables besides the base's 90×90×180.
        assert_eq!(settings.len(), 4, "{settings:?}");
        for c in settings {
            let all: Vec<String> = overrides.iter().chain(&c.overrides).cloned().collect();
            let scene = load(&SceneSource::BuiltIn, &all).unwrap();
            assert!(!draws_the_same(&base, &scene), "{}", c.label());
        }
    }

    #[test]
    fn area_entry_counts_file_entries() {
        let base = builtin_base();
        assert_eq!(area_entry(&base), Some((1, 16)));
        let plain = load(&SceneSource::BuiltIn, &[]).unwrap();
        assert_eq!(area_entry(&plain), None);
    }
}
