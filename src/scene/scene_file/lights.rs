//! Step 4b of loading, the lights: the `[[lights]]` entries, the lights the
//! glTF files brought and `[shadows]` become the scene's light list (area
//! lights expanded into their samples) and each light's shadow settings.
//!
//! This is its own step so the viewer can run it again after a light edit
//! without reading the scene file or importing its glTF files again.

use super::schema::{AreaEntry, LightEntry};
use super::shadow_keys::{ShadowsSection, shadow_settings};
use super::values::{finite_vec, gpu_coordinate, non_negative, range, unit_vec};
use crate::scene::{AreaLight, Light, Rgb, Scene, ShadowSettings, area_light};
use glam::DVec3;

/// Most point lights a scene may have once its area lights are expanded.
pub const MAX_POINT_LIGHTS: usize = 65536;

/// What the scene's lights are made from.
#[derive(Clone, Debug, Default)]
pub struct LightSetup {
    /// The lights of the glTF files (`KHR_lights_punctual`), in file order,
    /// as imported (before `[shadows].imported_lights`).
    pub imported: Vec<Light>,
    /// `[shadows]`.
    pub shadows: ShadowsSection,
    /// `[[lights]]`.
    pub entries: Vec<LightEntry>,
    /// The scene has an `[environment] map`: it lights the scene, so no
    /// default light is added (the contract's `[environment]` section).
    /// Kept here so that the viewer's re-assembly after an edit or a
    /// reload keeps the rule too.
    pub environment_map: bool,
    /// The map is the built-in studio given to a glTF scene without
    /// lights (`[gltf] default_light = "studio"`), said in the notes.
    pub default_studio: bool,
}

/// The scene's lights, as [`Scene`] holds them.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLights {
    pub lights: Vec<Light>,
    pub light_shadows: Vec<ShadowSettings>,
    pub area_lights: Vec<AreaLight>,
}

impl SceneLights {
    /// Puts these lights into `scene` (replacing its lights).
    pub fn install(self, scene: &mut Scene) {
        scene.lights = self.lights;
        scene.light_shadows = self.light_shadows;
        scene.area_lights = self.area_lights;
    }
}

impl LightSetup {
    /// Validates the entries and builds the light list: the imported
    /// lights first, then the entries in order (an area light as its
    /// samples); a scene without any and without an environment map gets
    /// [`default_light`]. `[shadows]`
    /// gives the shadow defaults (and decides for the imported lights),
    /// each entry's own keys override. Errors name the key.
    pub fn assemble(&self) -> std::result::Result<SceneLights, String> {
        let section_keys = self.shadows.keys();
        let shadow_defaults = shadow_settings(&section_keys, &|key| format!("shadows.{key}"))?;
        let mut lights = self.imported.clone();
        let mut light_shadows = vec![shadow_defaults; lights.len()];
        if self.imported_lights_cast_shadows() {
            lights.iter_mut().for_each(|l| l.set_shadows(true));
        }
        let mut area_lights: Vec<AreaLight> = Vec::new();
        for (k, entry) in self.entries.iter().enumerate() {
            let at = |p: String| format!("lights[{k}]: {p}");
            let keys = entry.shadow_keys().or(&section_keys);
            let settings = shadow_settings(&keys, &|key| format!("shadow_{key}")).map_err(at)?;
            match light_from_entry(entry).map_err(at)? {
                LightSource::Punctual(light) => {
                    lights.push(light);
                    light_shadows.push(settings);
                }
                LightSource::Area(area) => {
                    let index = area_lights.len();
                    for sample in area.point_lights(index, area.samples) {
                        lights.push(sample);
                        light_shadows.push(settings);
                    }
                    area_lights.push(area);
                    if lights.len() > MAX_POINT_LIGHTS {
                        return Err(at(format!(
                            "the area lights expand into more than {MAX_POINT_LIGHTS} point lights; use fewer samples"
                        )));
                    }
                }
            }
        }
        if self.gets_default_light() {
            lights.push(default_light());
            light_shadows.push(shadow_defaults);
        }
        Ok(SceneLights {
            lights,
            light_shadows,
            area_lights,
        })
    }

    /// Whether the glTF files' lights cast shadows: `[shadows]
    /// imported_lights` when given, else when the scene has no
    /// `[[lights]]` entry (the file's lights are then all the scene has).
    pub fn imported_lights_cast_shadows(&self) -> bool {
        self.shadows
            .imported_lights
            .unwrap_or(self.entries.is_empty())
    }

    /// Whether [`LightSetup::assemble`] adds the [`default_light`]: only
    /// to a scene without any light (imported or `[[lights]]`) and without
    /// an environment map (the contract: "No default light or sky is added
    /// to a scene that has any `[[lights]]` entry or an `[environment]
    /// map`").
    pub fn gets_default_light(&self) -> bool {
        self.imported.is_empty() && self.entries.is_empty() && !self.environment_map
    }

    /// What [`LightSetup::assemble`] decided without being asked, one
    /// sentence each, for `--verbose`: the default light of a scene
    /// without lights, and shadows of imported lights by default.
    pub fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        if self.default_studio {
            notes.push(
                "the glTF scene has no light: lit by the built-in neutral studio environment (`--set gltf.default_light=directional` for a directional light instead)"
                    .to_string(),
            );
        }
        if self.gets_default_light() {
            notes.push(
                "the scene has no light: added the default light (directional, 3 W/m² from the upper front left)"
                    .to_string(),
            );
        }
        if !self.imported.is_empty()
            && self.shadows.imported_lights.is_none()
            && self.entries.is_empty()
        {
            notes.push(format!(
                "the {} KHR_lights_punctual light(s) of the glTF file(s) cast shadows, as the scene has no other light (`--set shadows.imported_lights=false` turns that off)",
                self.imported.len()
            ));
        }
        notes
    }

    /// The shadow settings entry `k` renders with: its own keys over
    /// `[shadows]` over the built-in defaults (the defaults if they are
    /// invalid, which assembly would have refused).
    pub fn shadow_settings(&self, k: usize) -> ShadowSettings {
        self.entries
            .get(k)
            .map(|e| e.shadow_keys().or(&self.shadows.keys()))
            .and_then(|keys| shadow_settings(&keys, &|key| key.to_string()).ok())
            .unwrap_or_default()
    }
}

/// The light a scene without lights gets, so a bare glTF is visible: a
/// directional light from the upper front left, irradiance 3 W/m².
pub fn default_light() -> Light {
    Light::Directional {
        direction: DVec3::new(0.4, -1.0, -0.6).normalize(),
        irradiance: Rgb::splat(3.0),
        shadows: false,
    }
}

/// What one `[[lights]]` entry becomes.
enum LightSource {
    Punctual(Light),
    Area(AreaLight),
}

fn light_from_entry(e: &LightEntry) -> std::result::Result<LightSource, String> {
    Ok(match e {
        LightEntry::Point(e) => LightSource::Punctual(Light::Point {
            position: gpu_coordinate("position", finite_vec("position", e.position)?)?,
            intensity: non_negative("intensity", e.intensity.rgb())?,
            range: range(e.range)?,
            shadows: e.shadows,
        }),
        LightEntry::Directional(e) => LightSource::Punctual(Light::Directional {
            direction: unit_vec("direction", e.direction)?,
            irradiance: non_negative("irradiance", e.irradiance.rgb())?,
            shadows: e.shadows,
        }),
        LightEntry::Spot(e) => {
            // glTF's defaults: inner 0, outer π/4.
            let inner = e.inner_cone_deg.unwrap_or(0.0);
            let outer = e.outer_cone_deg.unwrap_or(45.0);
            if !(0.0..=90.0).contains(&outer) || !(0.0..=outer).contains(&inner) {
                return Err(format!(
                    "cones must satisfy 0 ≤ inner_cone_deg ≤ outer_cone_deg ≤ 90 (got {inner}, {outer})"
                ));
            }
            LightSource::Punctual(Light::Spot {
                position: gpu_coordinate("position", finite_vec("position", e.position)?)?,
                direction: unit_vec("direction", e.direction)?,
                intensity: non_negative("intensity", e.intensity.rgb())?,
                inner_cone_deg: inner,
                outer_cone_deg: outer,
                range: range(e.range)?,
                shadows: e.shadows,
            })
        }
        LightEntry::Area(e) => LightSource::Area(area_light_from_entry(e)?),
    })
}

fn area_light_from_entry(e: &AreaEntry) -> std::result::Result<AreaLight, String> {
    let normal = unit_vec("normal", e.normal)?;
    let tangent = match e.tangent {
        None => crate::base::any_tangent(normal),
        Some(t) => {
            let t = unit_vec("tangent", t)?;
            (t - normal * normal.dot(t))
                .try_normalize()
                .filter(|_| t.cross(normal).length() > 1e-6)
                .ok_or_else(|| format!("tangent = {:?} is parallel to the normal", t.to_array()))?
        }
    };
    let positive = |key: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(format!("{key} = {v} must be a positive number"))
        }
    };
    let shape = match (e.shape.as_str(), e.size, e.radius) {
        ("rect", Some([w, h]), None) => area_light::AreaShape::Rect {
            width: positive("size[0]", w)?,
            height: positive("size[1]", h)?,
        },
        ("disk", None, Some(r)) => area_light::AreaShape::Disk {
            radius: positive("radius", r)?,
        },
        ("rect", _, _) => {
            return Err("shape = \"rect\" needs `size = [w, h]` and no `radius`".into());
        }
        ("disk", _, _) => return Err("shape = \"disk\" needs `radius` and no `size`".into()),
        (other, _, _) => {
            return Err(format!(
                "shape = \"{other}\" is not an area light shape; expected rect or disk"
            ));
        }
    };
    let samples = e.samples.unwrap_or(area_light::DEFAULT_SAMPLES);
    if !(1..=area_light::MAX_SAMPLES).contains(&samples) {
        return Err(format!(
            "samples = {samples} is outside 1..={}",
            area_light::MAX_SAMPLES
        ));
    }
    Ok(AreaLight {
        shape,
        position: gpu_coordinate("position", finite_vec("position", e.position)?)?,
        normal,
        tangent,
        radiance: non_negative("radiance", e.radiance.rgb())?,
        samples,
        shadows: e.shadows,
        shadow_per_sample: e.shadow_per_sample,
    })
}
