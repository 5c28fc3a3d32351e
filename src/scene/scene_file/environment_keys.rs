//! `[environment]`'s map keys: `map`, `scale`, `sh_order`, `reference`,
//! `rotation_deg`, `specular`, `samples`, `prefilter_size`, `visibility` (the contract's `[environment]`
//! section; gonio's keys beyond `map` and `scale` extend it). Errors name
//! the key.

use super::schema::EnvironmentSection;
use crate::base::range;
use crate::environment::map::{MapData, ReferenceDiffuse, Specular};
use crate::environment::{EnvironmentMap, MapSettings, load, sh};
use std::path::Path;
use std::sync::Arc;

/// The `environment.specular` value that lets the scene choose the mode
/// (the default; `scene::environment_mode`).
pub const AUTO: &str = "auto";

/// Most directions per shading point `environment.samples` takes.
pub const MAX_SAMPLES: i64 = 4096;

/// The range of `environment.prefilter_size` (a level's width in texels).
pub const MIN_PREFILTER_SIZE: i64 = 8;
pub const MAX_PREFILTER_SIZE: i64 = 2048;

/// The map `e` names, loaded relative to `base_dir` with its settings;
/// without `map`, `default_map` (the studio of a glTF scene without
/// lights) or `None`. A setting given without any map is an error (it
/// would be ignored).
pub fn environment_map(
    e: &EnvironmentSection,
    base_dir: &Path,
    default_map: Option<&str>,
    max_bytes: u64,
) -> Result<Option<EnvironmentMap>, String> {
    let Some(value) = e.map.as_deref().or(default_map) else {
        let given = [
            ("scale", e.scale.is_some()),
            ("sh_order", e.sh_order.is_some()),
            ("reference", e.reference.is_some()),
            ("rotation_deg", e.rotation_deg.is_some()),
            ("specular", e.specular.is_some()),
            ("samples", e.samples.is_some()),
            ("prefilter_size", e.prefilter_size.is_some()),
            ("visibility", e.visibility.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|(_, g)| *g) {
            return Err(format!(
                "environment.{key} applies to an environment map, and there is no environment.map (a .exr or .hdr file, or \"sky\")"
            ));
        }
        return Ok(None);
    };
    let settings = settings(e)?;
    let data =
        load::load(value, base_dir, max_bytes).map_err(|p| format!("environment.map: {p}"))?;
    check_scaled(&data, &settings)?;
    Ok(Some(EnvironmentMap {
        data: Arc::new(data),
        settings,
    }))
}

/// The range rule ([`crate::base::range`]) for the radiance a map gives:
/// its largest texel times `environment.scale` at most
/// [`range::MAX_RADIANCE`] (each factor alone is checked where it is read).
pub fn check_scaled(data: &MapData, settings: &MapSettings) -> Result<(), String> {
    let largest = data.max_texel() * settings.scale;
    if !range::is_radiance(largest) {
        return Err(format!(
            "environment.scale = {:e} times the map's largest texel {:.3e} is {largest:.3e}, over {:e}: the GPU computes in f32 (largest 3.4e38) and multiplies radiance by BRDF values up to about 4e16, so it would overflow to Inf; lower the scale",
            settings.scale,
            data.max_texel(),
            range::MAX_RADIANCE
        ));
    }
    Ok(())
}

/// The settings of `e`, range-checked (also the viewer's, which keeps a
/// map's texels when only a setting changes).
pub fn settings(e: &EnvironmentSection) -> Result<MapSettings, String> {
    let mut s = MapSettings::default();
    if let Some(scale) = e.scale {
        if !range::is_radiance(scale) {
            return Err(format!(
                "environment.scale = {scale:e} must be finite, non-negative and at most {:e} (the range rule of every radiance source)",
                range::MAX_RADIANCE
            ));
        }
        s.scale = scale;
    }
    if let Some(order) = e.sh_order {
        if !(0..=sh::MAX_ORDER as i64).contains(&order) {
            return Err(format!(
                "environment.sh_order = {order} is outside 0..={} (the SH bands gonio projects to)",
                sh::MAX_ORDER
            ));
        }
        s.sh_order = order as u32;
    }
    if let Some(deg) = e.rotation_deg {
        if !deg.is_finite() {
            return Err(format!("environment.rotation_deg = {deg} must be finite"));
        }
        s.rotation_deg = deg;
    }
    if let Some(m) = e.specular.as_deref().filter(|m| *m != AUTO) {
        s.specular = Specular::parse(m).ok_or_else(|| {
            format!(
                "environment.specular = \"{m}\" is none of \"{AUTO}\", \"none\", \"sampled\", \"prefiltered\", \"sh\""
            )
        })?;
        s.specular_auto = false;
    }
    if let Some(n) = e.samples {
        if !(1..=MAX_SAMPLES).contains(&n) {
            return Err(format!(
                "environment.samples = {n} is outside 1..={MAX_SAMPLES}"
            ));
        }
        if s.specular != Specular::Sampled && !s.specular_auto {
            return Err("environment.samples applies to environment.specular = \"sampled\"".into());
        }
        s.samples = n as u32;
    }
    if let Some(size) = e.prefilter_size {
        if !(MIN_PREFILTER_SIZE..=MAX_PREFILTER_SIZE).contains(&size) || size % 2 != 0 {
            return Err(format!(
                "environment.prefilter_size = {size} is not an even width in {MIN_PREFILTER_SIZE}..={MAX_PREFILTER_SIZE}"
            ));
        }
        if s.specular != Specular::Prefiltered && !s.specular_auto {
            return Err(
                "environment.prefilter_size applies to environment.specular = \"prefiltered\""
                    .into(),
            );
        }
        s.prefilter_size = size as u32;
    }
    if let Some(r) = &e.reference {
        s.reference = ReferenceDiffuse::parse(r).ok_or_else(|| {
            format!("environment.reference = \"{r}\" is neither \"integrated\" nor \"sh\"")
        })?;
    }
    if let Some(v) = e.visibility {
        if v && s.reference != ReferenceDiffuse::Integrated {
            return Err("environment.visibility = true applies to environment.reference = \"integrated\" (the truth integrates the map; \"sh\" is the GPU's unshadowed approximation in f64)".into());
        }
        s.visibility = v;
    }
    Ok(s)
}
