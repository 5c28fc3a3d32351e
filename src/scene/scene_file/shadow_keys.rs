//! The shadow-map keys, defined once.
//!
//! Every `[[lights]]` entry takes `shadows` and nine shadow-map keys
//! (`shadow_map_size`, ...); `[shadows]` takes the same nine without the
//! prefix as the defaults of every entry that does not set its own. The
//! one list below (`with_shadow_keys!`) generates the entries' fields,
//! the `[shadows]` section, [`ShadowKeys`] (the six as one value, which
//! assembly merges and validates and the viewer's light panel edits) and
//! the keys' text form, so a new key is one row. Meanings and the
//! derivations of the defaults: `docs/shadows.md`.

use super::toml_value::TomlValue;
use crate::scene::{LightMarkers, MapResolution, ShadowFilter, ShadowSettings};
use serde::Deserialize;

/// Calls `$then! { { $args } rows }` with the one list of shadow-map keys;
/// a row is `[shadows] name`, `[[lights]] name`, `: value type`, in the
/// order the scene file documents them (serde's "expected one of" lists
/// follow it).
macro_rules! with_shadow_keys {
    ($then:ident! { $($args:tt)* }) => {
        $then! {
            { $($args)* }
            map_size shadow_map_size: u32,
            bias shadow_bias: f64,
            slope_bias shadow_slope_bias: f64,
            normal_offset shadow_normal_offset: f64,
            filter shadow_filter: String,
            pcf_kernel shadow_pcf_kernel: u32,
            resolution shadow_resolution: String,
            texels_per_pixel shadow_texels_per_pixel: f64,
            markers shadow_markers: String,
        }
    };
}
pub(crate) use with_shadow_keys;

/// Generates [`ShadowKeys`] and [`ShadowsSection`] from the list.
macro_rules! shadow_key_types {
    ({} $($key:ident $light_key:ident: $ty:ty,)*) => {
        /// The shadow-map keys of one `[[lights]]` entry or of `[shadows]`;
        /// `None` where the file does not set the key.
        #[derive(Clone, Debug, Default, PartialEq)]
        pub struct ShadowKeys {
            $(pub $key: Option<$ty>,)*
        }

        impl ShadowKeys {
            /// These keys where set, `defaults` elsewhere (a light's own
            /// key wins over `[shadows]`).
            pub fn or(self, defaults: &ShadowKeys) -> ShadowKeys {
                ShadowKeys {
                    $($key: self.$key.or_else(|| defaults.$key.clone()),)*
                }
            }

            /// The keys that are set as `(name, value)`, named by `name`
            /// (`shadow_map_size` in a `[[lights]]` entry, `map_size` in
            /// `[shadows]`).
            pub fn to_toml(&self, light_entry: bool) -> Vec<(&'static str, toml::Value)> {
                let mut out = Vec::new();
                $(
                    if let Some(v) = self.$key.to_toml() {
                        out.push((
                            if light_entry { stringify!($light_key) } else { stringify!($key) },
                            v,
                        ));
                    }
                )*
                out
            }
        }

        /// `[shadows]`: shadow-map defaults for every light that does not
        /// set its own (gonio's extension), and whether lights imported
        /// from glTF files cast shadows.
        #[derive(Clone, Debug, Default, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct ShadowsSection {
            /// `KHR_lights_punctual` lights cast shadows. Unset: they do
            /// when the scene has no `[[lights]]` entry (the file's own
            /// lights are then the only ones), else not.
            #[serde(default)]
            pub imported_lights: Option<bool>,
            $(pub $key: Option<$ty>,)*
        }

        impl ShadowsSection {
            /// The section's shadow-map keys.
            pub fn keys(&self) -> ShadowKeys {
                ShadowKeys {
                    $($key: self.$key.clone(),)*
                }
            }
        }
    };
}
with_shadow_keys!(shadow_key_types! {});

/// Validated shadow settings from `keys` (the built-in defaults where
/// unset); `name(key)` is how the scene file spells `key` where the keys
/// came from.
pub fn shadow_settings(
    keys: &ShadowKeys,
    name: &dyn Fn(&str) -> String,
) -> std::result::Result<ShadowSettings, String> {
    let map_size = keys.map_size.unwrap_or(ShadowSettings::DEFAULT_MAP_SIZE);
    let sizes = ShadowSettings::MAP_SIZES;
    if !sizes.contains(&map_size) {
        return Err(format!(
            "{} = {map_size} is outside {}..={}",
            name("map_size"),
            sizes.start(),
            sizes.end()
        ));
    }
    let kernel = keys
        .pcf_kernel
        .unwrap_or(ShadowSettings::DEFAULT_PCF_KERNEL);
    if kernel.is_multiple_of(2) || !(1..=ShadowSettings::MAX_PCF_KERNEL).contains(&kernel) {
        return Err(format!(
            "{} = {kernel} must be an odd number in 1..={}",
            name("pcf_kernel"),
            ShadowSettings::MAX_PCF_KERNEL
        ));
    }
    let filter = match keys.filter.as_deref() {
        None | Some("pcf") => ShadowFilter::Pcf { kernel },
        Some("none") => ShadowFilter::None,
        Some(other) => {
            return Err(format!(
                "{} = \"{other}\" is not a shadow filter; expected none or pcf",
                name("filter")
            ));
        }
    };
    let resolution = match keys.resolution.as_deref() {
        None | Some("fixed") => {
            if let Some(t) = keys.texels_per_pixel {
                return Err(format!(
                    "{} = {t} applies only to fitted maps, and {} is \"fixed\" (the default); set {} = \"fit\" or remove {}",
                    name("texels_per_pixel"),
                    name("resolution"),
                    name("resolution"),
                    name("texels_per_pixel")
                ));
            }
            MapResolution::Fixed
        }
        Some("fit") => {
            let t = keys.texels_per_pixel.unwrap_or(1.0);
            let range = MapResolution::TEXELS_PER_PIXEL;
            if !(t.is_finite() && range.contains(&t)) {
                return Err(format!(
                    "{} = {t} is outside {}..={} (map texels per screen pixel along each axis)",
                    name("texels_per_pixel"),
                    range.start(),
                    range.end()
                ));
            }
            MapResolution::Fit {
                texels_per_pixel: t,
            }
        }
        Some(other) => {
            return Err(format!(
                "{} = \"{other}\" is not a shadow-map resolution; expected fixed (the side is {}) or fit (fitted to the screen, at most {})",
                name("resolution"),
                name("map_size"),
                name("map_size")
            ));
        }
    };
    let length = |key: &str, v: Option<f64>, default: f64, max: f64| match v {
        None => Ok(default),
        Some(v) if v.is_finite() && (0.0..=max).contains(&v) => Ok(v),
        Some(v) => Err(format!("{} = {v} is outside 0..={max}", name(key))),
    };
    Ok(ShadowSettings {
        map_size,
        bias: length("bias", keys.bias, 0.0, 1e6)?,
        slope_bias: length("slope_bias", keys.slope_bias, 0.0, 1e3)?,
        normal_offset: length(
            "normal_offset",
            keys.normal_offset,
            ShadowSettings::default_normal_offset(filter),
            1e3,
        )?,
        filter,
        resolution,
        markers: match keys.markers.as_deref() {
            None => LightMarkers::Pass,
            Some(text) => text
                .parse::<LightMarkers>()
                .map_err(|e| format!("{}: {e} (pass: the light's markers let its light through; cast: they shadow it)", name("markers")))?,
        },
    })
}
