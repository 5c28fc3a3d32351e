//! An environment map: linear RGB radiance [W/(m²·sr)] by direction, a
//! latitude-longitude image in the contract's convention ([`super::latlong`]),
//! looked up with bilinear filtering (`u` wraps, `v` clamps), times
//! `scale`.
//!
//! The GPU samples the same f32 texels with the same arithmetic
//! (`environment_lookup` in `shaders/environment.wgsl`), so a mirror or
//! the background differ between the renderers only by f32 rounding.

use super::importance::ImportanceTable;
use super::prefiltered::Prefiltered;
use super::prefiltered_zonal::{ZonalKernel, ZonalStack};
use super::quadrature::Truth;
use super::{latlong, sh};
use crate::base::Rgb;
use crate::base::range;
use glam::DVec3;
use std::sync::Arc;
use std::sync::atomic::AtomicU64;

/// Largest map side gonio accepts (a 16k × 8k map is 1.5 GiB of f32 RGB).
pub const MAX_SIDE: u32 = 16384;

/// How the CPU reference evaluates the environment's diffuse term
/// (`environment.reference`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ReferenceDiffuse {
    /// The integrated truth ([`Truth`]): what SH is measured against.
    #[default]
    Integrated,
    /// The GPU's approximation in f64: SH irradiance of `sh_order`
    /// (proves the GPU's arithmetic, to f32 rounding).
    Sh,
}

impl ReferenceDiffuse {
    /// The scene-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            ReferenceDiffuse::Integrated => "integrated",
            ReferenceDiffuse::Sh => "sh",
        }
    }

    /// Parses the scene-file spelling.
    pub fn parse(s: &str) -> Option<Self> {
        [ReferenceDiffuse::Integrated, ReferenceDiffuse::Sh]
            .into_iter()
            .find(|r| r.name() == s)
    }
}

/// The `[environment]` keys that decide how a map is used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSettings {
    /// Multiplies the map (`environment.scale`).
    pub scale: f64,
    /// Highest SH band of the diffuse term, 0..=4 (`environment.sh_order`,
    /// default 2: 9 coefficients).
    pub sh_order: u32,
    /// What the CPU reference integrates (`environment.reference`).
    pub reference: ReferenceDiffuse,
    /// Turns the map about +Y by this many degrees
    /// (`environment.rotation_deg`; counter-clockwise seen from above):
    /// what the file holds towards `d₀` arrives from `R_y(θ) d₀`.
    pub rotation_deg: f64,
    /// How the environment lights surfaces (`environment.specular`).
    pub specular: Specular,
    /// `specular` was not chosen by the user (`environment.specular`
    /// absent or `"auto"`): the scene picks the mode that lights the whole
    /// BRDF of every material it draws (`scene::environment_mode`), and
    /// picks again when a material changes. `false`: `specular` is the
    /// user's and is kept.
    pub specular_auto: bool,
    /// Directions per shading point of [`Specular::Sampled`]
    /// (`environment.samples`, default 64).
    pub samples: u32,
    /// Width of each level of [`Specular::Prefiltered`]'s stack
    /// (`environment.prefilter_size`, default 64; height half of it).
    pub prefilter_size: u32,
    /// The CPU reference's environment term with ray-traced visibility
    /// (`environment.visibility`, default false: unshadowed, as the GPU's
    /// raster path; [`super::visibility`]). The GPU ignores it.
    pub visibility: bool,
}

/// How the environment lights surfaces (`environment.specular`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Specular {
    /// The diffuse term only, by SH irradiance (`"none"`; the whole BRDF
    /// of Lambert and the mirror, which is what `"auto"` picks for them).
    #[default]
    None,
    /// The whole BRDF integrated with `samples` directions per shading
    /// point (`"sampled"`, [`crate::reference::environment::sampled`]).
    Sampled,
    /// Diffuse by SH, glossy by the split-sum approximation: a prefiltered
    /// map times the environment BRDF (`"prefiltered"`,
    /// [`super::prefiltered`]).
    Prefiltered,
    /// Diffuse by SH, the Phong lobes by SH convolution, a zonal product
    /// (`"sh"`, [`super::sh_phong`]).
    Sh,
}

impl Specular {
    /// The scene-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            Specular::None => "none",
            Specular::Sampled => "sampled",
            Specular::Prefiltered => "prefiltered",
            Specular::Sh => "sh",
        }
    }

    /// Parses the scene-file spelling.
    pub fn parse(s: &str) -> Option<Self> {
        [
            Specular::None,
            Specular::Sampled,
            Specular::Prefiltered,
            Specular::Sh,
        ]
        .into_iter()
        .find(|m| m.name() == s)
    }
}

impl Default for MapSettings {
    fn default() -> Self {
        MapSettings {
            scale: 1.0,
            sh_order: 2,
            reference: ReferenceDiffuse::Integrated,
            rotation_deg: 0.0,
            specular: Specular::None,
            specular_auto: true,
            samples: 64,
            prefilter_size: super::prefiltered::DEFAULT_SIZE,
            visibility: false,
        }
    }
}

/// The pixels of a map and what is derived from them once.
#[derive(Debug, PartialEq)]
pub struct MapData {
    /// Where it came from (a path, or `sky`), for messages.
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Row-major, row 0 at +Y, linear radiance.
    pub texels: Vec<[f32; 3]>,
    /// The integrated truth and the radiance's SH coefficients.
    pub truth: Truth,
    /// The texel quadrature's nodes (the sampled mode's truth).
    pub nodes: Vec<super::quadrature::Node>,
    /// Prefiltered stacks made so far, by size (made on first use).
    pub prefiltered: PrefilteredCache,
    /// The distribution the sampled mode draws directions by (made on
    /// first use, [`MapData::importance`]).
    pub importance: ImportanceCache,
    /// Zonal stacks made so far, by kernel name ([`MapData::zonal_stack`]).
    pub zonal: ZonalCache,
}

/// A map's zonal stacks, made when a scene first asks for a kernel's.
/// Equal whatever it holds, as [`PrefilteredCache`].
#[derive(Debug, Default)]
pub struct ZonalCache(std::sync::Mutex<Vec<Arc<ZonalStack>>>);

impl PartialEq for ZonalCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The prefiltered stacks of a map, made when a scene first asks for a
/// size (loading a map costs nothing extra in the other modes). Equal
/// whatever it holds: it is derived from the texels.
#[derive(Debug, Default)]
pub struct PrefilteredCache(std::sync::Mutex<Vec<Arc<Prefiltered>>>);

impl PartialEq for PrefilteredCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// A map's importance table, made when a scene in the sampled mode first
/// asks for it. Equal whatever it holds, as [`PrefilteredCache`].
#[derive(Debug, Default)]
pub struct ImportanceCache(std::sync::OnceLock<Arc<ImportanceTable>>);

impl ImportanceCache {
    /// A cache already holding `table` (a test's map whose light is drawn
    /// by another map's distribution).
    pub fn holding(table: Arc<ImportanceTable>) -> Self {
        ImportanceCache(std::sync::OnceLock::from(table))
    }
}

impl PartialEq for ImportanceCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// An environment map with its settings. The pixels are shared: changing
/// a setting (an override, a viewer edit) does not copy them.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentMap {
    pub data: Arc<MapData>,
    pub settings: MapSettings,
}

impl MapData {
    /// Checks and wraps `width × height` texels named `name`: the width
    /// must be twice the height (lat-long), every value finite and ≥ 0.
    /// The error is one sentence naming the problem (the caller names the
    /// file).
    pub fn new(
        name: &str,
        width: u32,
        height: u32,
        texels: Vec<[f32; 3]>,
    ) -> Result<MapData, String> {
        Self::check_dimensions(width, height)?;
        assert_eq!(texels.len(), (width * height) as usize);
        if let Some(k) = texels
            .iter()
            .position(|t| t.iter().any(|&v| !range::is_radiance(v as f64)))
        {
            let (row, col) = (k as u32 / width, k as u32 % width);
            return Err(format!(
                "texel (column {col}, row {row}) is {:?}: radiance must be finite and non-negative, and at most {:e} (the range rule of every radiance source: the GPU computes in f32, largest 3.4e38)",
                texels[k],
                range::MAX_RADIANCE
            ));
        }
        let truth = Truth::new(width, height, &texels);
        let nodes = super::quadrature::nodes(width, height, &texels);
        Ok(MapData {
            name: name.into(),
            width,
            height,
            texels,
            truth,
            nodes,
            prefiltered: PrefilteredCache::default(),
            importance: ImportanceCache::default(),
            zonal: ZonalCache::default(),
        })
    }

    /// The prefiltered stack `size` wide, made on the first call for that
    /// size (adding its texels to `done` as they are computed) and then
    /// shared. The cache is not locked while a stack is made: a viewer
    /// frame asking for another size is never held behind it (two threads
    /// asking for the same new size both compute it; the first kept wins).
    pub fn prefiltered_stack(&self, size: u32, done: &AtomicU64) -> Arc<Prefiltered> {
        if let Some(p) = self.cached_prefiltered(size) {
            return p;
        }
        let made = Arc::new(Prefiltered::with_progress(
            self.width,
            self.height,
            &self.texels,
            size,
            done,
        ));
        let mut cache = self.prefiltered.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(p) = cache.iter().find(|p| p.width == size) {
            return p.clone();
        }
        cache.push(made.clone());
        made
    }

    /// The stack of `kernel` ([`ZonalStack`]), made on the first call for
    /// its name and then shared (made outside the lock, as
    /// [`Self::prefiltered_stack`]).
    pub fn zonal_stack(&self, kernel: &ZonalKernel) -> Arc<ZonalStack> {
        let find =
            |cache: &[Arc<ZonalStack>]| cache.iter().find(|s| s.name == kernel.name).cloned();
        if let Some(s) = find(&self.zonal.0.lock().unwrap_or_else(|e| e.into_inner())) {
            return s;
        }
        let made = Arc::new(ZonalStack::new(
            kernel,
            self.width,
            self.height,
            &self.texels,
        ));
        let mut cache = self.zonal.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(s) = find(&cache) {
            return s;
        }
        cache.push(made.clone());
        made
    }

    /// The prefiltered stack `size` wide if it has been made.
    pub fn cached_prefiltered(&self, size: u32) -> Option<Arc<Prefiltered>> {
        let cache = self.prefiltered.0.lock().unwrap_or_else(|e| e.into_inner());
        cache.iter().find(|p| p.width == size).cloned()
    }

    /// The distribution of directions by the texels' light (made on the
    /// first call, then shared).
    pub fn importance(&self) -> Arc<ImportanceTable> {
        self.importance
            .0
            .get_or_init(|| Arc::new(ImportanceTable::new(self.width, self.height, &self.texels)))
            .clone()
    }

    /// The bytes its texels hold (f32 RGB), charged to `--limit bytes`.
    pub fn texel_bytes(&self) -> u64 {
        std::mem::size_of_val(self.texels.as_slice()) as u64
    }

    /// The largest texel component (unscaled), which `environment.scale`
    /// multiplies: their product is held to [`range::MAX_RADIANCE`].
    pub fn max_texel(&self) -> f64 {
        self.texels.iter().flatten().fold(0.0f32, |m, &v| m.max(v)) as f64
    }

    /// Refuses dimensions that are not a 2 : 1 lat-long map or exceed
    /// [`MAX_SIDE`] (checked from a file's header before decoding).
    pub fn check_dimensions(width: u32, height: u32) -> Result<(), String> {
        // In u64: a header's height near 2³² overflowed `2 * height`
        // (found by the environment_map fuzz target).
        if height == 0 || u64::from(width) != 2 * u64::from(height) {
            return Err(format!(
                "a latitude-longitude map is twice as wide as high, and this one is {width} × {height}"
            ));
        }
        if width > MAX_SIDE {
            return Err(format!(
                "the map is {width} × {height}; the largest side gonio accepts is {MAX_SIDE}"
            ));
        }
        Ok(())
    }

    /// The bilinear lookup of unit direction `d` (unscaled). Twin:
    /// `environment_lookup` in `shaders/environment.wgsl`.
    pub fn lookup(&self, d: DVec3) -> Rgb {
        let (u, v) = latlong::uv(d);
        let x = u * self.width as f64 - 0.5;
        let y = v * self.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let w = self.width as i64;
        let h = self.height as i64;
        let col = |c: i64| c.rem_euclid(w) as u32;
        let row = |r: i64| r.clamp(0, h - 1) as u32;
        let (c0, c1) = (col(x0 as i64), col(x0 as i64 + 1));
        let (r0, r1) = (row(y0 as i64), row(y0 as i64 + 1));
        let t =
            |c: u32, r: u32| Rgb::from(self.texels[(r * self.width + c) as usize].map(f64::from));
        let top = t(c0, r0) * (1.0 - fx) + t(c1, r0) * fx;
        let bottom = t(c0, r1) * (1.0 - fx) + t(c1, r1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

impl EnvironmentMap {
    /// The direction in the file's frame of world direction `d`:
    /// `R_y(−θ) d`. Twin: `environment_to_map` in shaders/environment.wgsl
    /// (with the cosine and sine rounded to f32 on the CPU).
    pub fn to_map(&self, d: DVec3) -> DVec3 {
        let (sin, cos) = self.settings.rotation_deg.to_radians().sin_cos();
        DVec3::new(cos * d.x - sin * d.z, d.y, sin * d.x + cos * d.z)
    }

    /// The world direction of direction `d` in the file's frame:
    /// `R_y(θ) d`, the inverse of [`Self::to_map`].
    pub fn from_map(&self, d: DVec3) -> DVec3 {
        let (sin, cos) = self.settings.rotation_deg.to_radians().sin_cos();
        DVec3::new(cos * d.x + sin * d.z, d.y, -sin * d.x + cos * d.z)
    }

    /// Radiance arriving from unit direction `d`: `scale · L_env(d)`.
    pub fn radiance(&self, d: DVec3) -> Rgb {
        self.data.lookup(self.to_map(d)) * self.settings.scale
    }

    /// `scale · Â_l · L_lm` up to `sh_order` (zero above): what the GPU's
    /// `sh_irradiance` sums, `E(n) = Σ c_i Y_i(n)`.
    pub fn irradiance_coefficients(&self) -> [Rgb; sh::COUNT] {
        let mut c =
            sh::irradiance_coefficients(&self.data.truth.radiance_sh, self.settings.sh_order);
        c.iter_mut().for_each(|c| *c *= self.settings.scale);
        c
    }

    /// `scale · L_lm` up to `sh_order` (zero above): the radiance the
    /// `"sh"` mode convolves with the Phong lobes ([`super::sh_phong`]).
    pub fn radiance_coefficients(&self) -> [Rgb; sh::COUNT] {
        let mut c = [Rgb::ZERO; sh::COUNT];
        let order = self.settings.sh_order;
        for (i, c) in c.iter_mut().enumerate().take(sh::count(order)) {
            *c = self.data.truth.radiance_sh[i] * self.settings.scale;
        }
        c
    }

    /// Irradiance by SH of `sh_order` (the GPU's diffuse term), clamped at
    /// zero per channel.
    ///
    /// Why the clamp: the band-limited expansion rings below zero on the
    /// side facing away from a small bright source (a sun), where the
    /// true irradiance is small but never negative; a negative diffuse
    /// term would darken, or with several channels tint, what the sun does
    /// not reach. Since the truth is `≥ 0`, `max(E_SH, 0)` is never farther
    /// from it than `E_SH` (`sh_error::tests` measures both). GPU twin:
    /// `sh_irradiance` in shaders/environment.wgsl.
    pub fn irradiance_sh(&self, n: DVec3) -> Rgb {
        self.irradiance_sh_unclamped(n).max(Rgb::ZERO)
    }

    /// The SH expansion itself, `Σ c_i Y_i(n)` (may be negative; see
    /// [`Self::irradiance_sh`]).
    pub fn irradiance_sh_unclamped(&self, n: DVec3) -> Rgb {
        sh::evaluate(&self.irradiance_coefficients(), self.to_map(n))
    }

    /// The integrated irradiance `scale · ∫ L max(0, n·ω) dω`.
    pub fn irradiance_integrated(&self, n: DVec3) -> Rgb {
        self.data.truth.irradiance(self.to_map(n)) * self.settings.scale
    }

    /// The prefiltered stack of `settings.prefilter_size` (made on the
    /// first call for that size, then shared).
    pub fn prefiltered(&self) -> Arc<Prefiltered> {
        self.data
            .prefiltered_stack(self.settings.prefilter_size, &AtomicU64::new(0))
    }

    /// The irradiance the CPU reference uses (`settings.reference`).
    pub fn irradiance_reference(&self, n: DVec3) -> Rgb {
        match self.settings.reference {
            ReferenceDiffuse::Integrated => self.irradiance_integrated(n),
            ReferenceDiffuse::Sh => self.irradiance_sh(n),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(w: u32, h: u32) -> MapData {
        let texels = (0..w * h)
            .map(|k| [(k % w) as f32, (k / w) as f32, 1.0])
            .collect();
        MapData::new("ramp", w, h, texels).unwrap()
    }

    #[test]
    fn texel_centres_return_the_texel_and_u_wraps() {
        let map = ramp(8, 4);
        for (col, row) in [(0, 0), (3, 1), (7, 3)] {
            let d = latlong::texel_direction(col, row, 8, 4);
            let got = map.lookup(d);
            assert!(
                (got - Rgb::new(col as f64, row as f64, 1.0)).length() < 1e-9,
                "{got}"
            );
        }
        // Half-way between the last column and the first (the seam, u = 0):
        // the mean of columns 7 and 0.
        let seam = latlong::direction(0.0, 1.5 / 4.0);
        assert!((map.lookup(seam).x - 3.5).abs() < 1e-9);
        // Above the first row's centre: clamped to row 0.
        assert!((map.lookup(DVec3::Y).y).abs() < 1e-12);
    }

    #[test]
    fn rotation_moves_what_arrives_from_where() {
        let data = Arc::new(ramp(8, 4));
        let map = |deg| EnvironmentMap {
            data: data.clone(),
            settings: MapSettings {
                rotation_deg: deg,
                ..Default::default()
            },
        };
        let d0 = latlong::texel_direction(1, 1, 8, 4);
        // A quarter turn counter-clockwise seen from above (+Y) takes
        // −Z to −X: R_y(90°) d₀.
        let (s, c) = 90f64.to_radians().sin_cos();
        let turned = DVec3::new(c * d0.x + s * d0.z, d0.y, -s * d0.x + c * d0.z);
        assert!((map(90.0).radiance(turned) - map(0.0).radiance(d0)).length() < 1e-9);
        assert!((map(90.0).to_map(DVec3::NEG_X) - DVec3::NEG_Z).length() < 1e-12);
        let n = DVec3::new(0.3, 0.5, -0.8).normalize();
        let e0 = map(0.0).irradiance_integrated(n);
        let e1 = map(90.0).irradiance_integrated(map(0.0).to_map(n));
        assert!(e0.is_finite() && e1.is_finite());
    }

    #[test]
    fn bad_maps_are_refused_with_the_reason() {
        let e = MapData::new("m", 6, 4, vec![[0.0; 3]; 24]).unwrap_err();
        assert!(e.contains("6 × 4"), "{e}");
        let mut t = vec![[0.0; 3]; 8];
        t[5] = [0.0, f32::NAN, 0.0];
        let e = MapData::new("m", 4, 2, t).unwrap_err();
        assert!(e.contains("column 1, row 1") && e.contains("finite"), "{e}");
        let e = MapData::new("m", 4, 2, vec![[-1.0, 0.0, 0.0]; 8]).unwrap_err();
        assert!(e.contains("non-negative"), "{e}");
    }
}
