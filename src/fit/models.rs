//! The models a fit can take, each with its free parameters and their
//! bounds. A model is named as `gonio brdf --compare` names a material:
//! `MODEL[,distribution=D][,fresnel=F][,geometry=G]`, e.g.
//! `cook-torrance,distribution=ggx,fresnel=dielectric`.
//!
//! Bounds are the table's parameter ranges ([`Param::range`]), narrowed
//! where a range is open or unbounded to an interval a search can use
//! (tests: `bounds_lie_in_the_table_ranges`). What is held fixed, and why:
//! Cook-Torrance with a conductor Fresnel has a grey `k_s` (its colour is
//! the Fresnel's, η and κ per channel free; a grey scale lets a measured
//! highlight stay below the Fresnel's rise to 1 at grazing, which the
//! MERL data show: chrome with GGX, 0.78 → 0.32 relative error); the dielectric has `η_i = 1` (air) and a free
//! grey `η_t` with a free `k_s` per channel; the geometry is Smith matched
//! to the distribution. `abc` (Löw et al. 2012) is fitted in the form of
//! its published fits: `k_s = 1`, `A` per channel, `B`, `C`, and `η_i = 1`
//! with a free `η_t` (the published `ior`); `abc-published` is no fit but
//! those published parameters (`published.rs`), scored alike.
//!
//! Layered models: `gltf-pbr,layers=clearcoat` fits a `KHR_materials_clearcoat`
//! coat (`clearcoat`, `clearcoat_roughness`) over the metallic-roughness
//! base, the two-lobe structure of paints and varnished surfaces (the
//! contract's "Layered glTF materials"); `layers=sheen` a
//! `KHR_materials_sheen` sheen (`sheen_color`, `sheen_roughness`), the
//! fabrics' grazing rim; `layers=clearcoat+sheen` both. The sheen's
//! roughness is searched from 0.1: below it the albedo table the search
//! reads errs by up to 0.22 (`terms.rs` says why the search reads it).

use crate::material::param::{
    ABC_A, ABC_B, ABC_C, BASE_COLOR, CLEARCOAT, CLEARCOAT_ROUGHNESS, ETA, ETA_T, K_D, K_E, K_S,
    KAPPA, METALLIC, PERCEPTUAL_ROUGHNESS, Param, ROUGHNESS, SHEEN_COLOR, SHEEN_ROUGHNESS, Value,
    WARD_SIGMA,
};
use crate::material::{
    Distribution, Fresnel, Geometry, Material, ROUGHNESS_FLOOR, ReflectanceModel,
};

/// One free number: a parameter (one channel of a triple, or a scalar)
/// searched over `[lo, hi]`, in `ln` where `log`.
#[derive(Clone, Debug)]
pub struct Free {
    pub param: &'static Param,
    /// The channel of a triple; `None` for a scalar.
    pub channel: Option<usize>,
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    /// A lobe's shape (width, exponent, index), as opposed to a colour: the
    /// multi-start varies shapes and starts colours at one value.
    pub shape: bool,
}

impl Free {
    /// The value at fraction `t ∈ [0, 1]` of the (log-)interval.
    pub fn at(&self, t: f64) -> f64 {
        if self.log {
            (self.lo.ln() + t * (self.hi.ln() - self.lo.ln())).exp()
        } else {
            self.lo + t * (self.hi - self.lo)
        }
        .clamp(self.lo, self.hi)
    }

    /// The fraction of the (log-)interval at which `v` lies, clamped to
    /// [0, 1] (the inverse of [`Self::at`]).
    pub fn fraction(&self, v: f64) -> f64 {
        let v = v.clamp(self.lo, self.hi);
        if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// The value in `m`.
    pub fn read(&self, m: &Material) -> f64 {
        let v = self.param.read(m);
        match self.channel {
            None => v.scalar(),
            Some(c) => v.color()[c],
        }
    }

    /// Writes `v` into `m`.
    pub fn write(&self, m: &mut Material, v: f64) {
        let value = match self.channel {
            None => Value::Scalar(v),
            Some(c) => {
                let mut rgb = self.param.read(m).color();
                rgb[c] = v;
                Value::Color(rgb)
            }
        };
        self.param.write(m, value);
    }
}

/// A model to fit: the starting material (model and terms) and its free
/// numbers.
#[derive(Clone, Debug)]
pub struct FitModel {
    /// The spec it was made from, normalized (`cook-torrance,distribution=ggx,fresnel=conductor`).
    pub spec: String,
    pub base: Material,
    pub free: Vec<Free>,
    /// Which of [`Self::free`] is the lobe's width (`k_e`, σ, roughness):
    /// the multi-start scans it (`problem.rs`).
    pub width: Option<usize>,
    /// Further numbers the multi-start scans with the width: (indices into
    /// [`Self::free`] set together, the fractions of their interval tried).
    /// abc scans its `A` (three channels together) and `C`.
    pub scans: Vec<(Vec<usize>, Vec<f64>)>,
}

/// The models `gonio fit --all` fits (the lecture's, normalized and as
/// written, and the modern ones), in the ranking's order.
pub const ALL: &[&str] = &[
    "lambert",
    "phong",
    "phong-normalized",
    "blinn-phong",
    "blinn-phong-normalized",
    "ward",
    "cook-torrance,distribution=beckmann,fresnel=conductor",
    "cook-torrance,distribution=blinn-normalized,fresnel=conductor",
    "cook-torrance,distribution=gaussian-normalized,fresnel=conductor",
    "cook-torrance,distribution=ggx,fresnel=conductor",
    "cook-torrance,distribution=beckmann,fresnel=dielectric",
    "cook-torrance,distribution=blinn-normalized,fresnel=dielectric",
    "cook-torrance,distribution=gaussian-normalized,fresnel=dielectric",
    "cook-torrance,distribution=ggx,fresnel=dielectric",
    "gltf-pbr",
    "gltf-pbr,layers=clearcoat",
    "gltf-pbr,layers=sheen",
    "abc",
    "abc,start=published",
    ABC_PUBLISHED,
];

/// The spec of the published ABC parameters (no free numbers: the
/// material comes from `published::abc`).
pub const ABC_PUBLISHED: &str = "abc-published";

/// The models a fit can take (what an unknown `--model` lists).
const FITTABLE: &[ReflectanceModel] = &[
    ReflectanceModel::Lambert,
    ReflectanceModel::Phong,
    ReflectanceModel::PhongNormalized,
    ReflectanceModel::BlinnPhong,
    ReflectanceModel::BlinnPhongNormalized,
    ReflectanceModel::Ward,
    ReflectanceModel::CookTorrance,
    ReflectanceModel::GltfPbr,
    ReflectanceModel::Abc,
];

fn colour(param: &'static Param, lo: f64, hi: f64) -> impl Iterator<Item = Free> {
    (0..3).map(move |c| Free {
        param,
        channel: Some(c),
        lo,
        hi,
        log: false,
        shape: false,
    })
}

fn shape(param: &'static Param, lo: f64, hi: f64, log: bool) -> Free {
    Free {
        param,
        channel: None,
        lo,
        hi,
        log,
        shape: true,
    }
}

fn log_colour(param: &'static Param, lo: f64, hi: f64) -> impl Iterator<Item = Free> {
    (0..3).map(move |c| Free {
        param,
        channel: Some(c),
        lo,
        hi,
        log: true,
        shape: true,
    })
}

/// Narrowed bounds (see the module doc): `k_e` from 0.1 (a lobe wider than
/// a cosine) to the table's 1e6; slopes from the renderers' floor to 1;
/// glTF's perceptual roughness from 0.01 (α = 1e-4); a conductor's η in
/// [0.02, 10] and κ in [1e-3, 10] (the metals of the lecture's table lie
/// well inside); a dielectric's η_t in [1, 3] (air to beyond diamond).
const K_E_BOUNDS: (f64, f64) = (0.1, 1e6);
const SLOPE_BOUNDS: (f64, f64) = (ROUGHNESS_FLOOR, 1.0);
const PERCEPTUAL_BOUNDS: (f64, f64) = (0.01, 1.0);
const ETA_BOUNDS: (f64, f64) = (0.02, 10.0);
const KAPPA_BOUNDS: (f64, f64) = (1e-3, 10.0);
const ETA_T_BOUNDS: (f64, f64) = (1.0, 3.0);
/// abc's bounds: `A` in [1e-3, 1e6] (the published fits: 0.08 to 5710),
/// `B` in [1, 1e8] (11 to 8.1e6), `C` in [0.01, 10] (0.024 to 2.7), `η_t`
/// in [1, 100] (1.04 to 99.99: an `ior` of 100 is a Fresnel of ≈ 1, a
/// metal's flat F).
const ABC_A_BOUNDS: (f64, f64) = (1e-3, 1e6);
const ABC_B_BOUNDS: (f64, f64) = (1.0, 1e8);
const ABC_C_BOUNDS: (f64, f64) = (0.01, 10.0);
const ABC_ETA_T_BOUNDS: (f64, f64) = (1.0, 100.0);

impl FitModel {
    /// The model `spec` names, or a message saying what is accepted.
    pub fn parse(spec: &str) -> Result<FitModel, String> {
        if spec.trim() == ABC_PUBLISHED {
            return Ok(FitModel {
                spec: ABC_PUBLISHED.into(),
                base: Material::new("fit", ReflectanceModel::Abc),
                free: Vec::new(),
                width: None,
                scans: Vec::new(),
            });
        }
        let mut parts = spec.split(',').map(str::trim);
        let name = parts.next().unwrap_or_default();
        let model: ReflectanceModel = name.parse().map_err(|_| unknown(name))?;
        if !FITTABLE.contains(&model) {
            return Err(unknown(name));
        }
        let mut base = Material::new("fit", model);
        let mut from_published = false;
        let mut layers = Layers::default();
        (base.geometry, base.fresnel) = (Geometry::Smith, Fresnel::Conductor);
        for part in parts {
            let Some((key, value)) = part.split_once('=') else {
                return Err(format!("`{part}` is not KEY=VALUE"));
            };
            if model == ReflectanceModel::Abc && part == "start=published" {
                from_published = true;
                continue;
            }
            if model == ReflectanceModel::GltfPbr && key.trim() == "layers" {
                layers = parse_layers(value)?;
                continue;
            }
            if model != ReflectanceModel::CookTorrance {
                return Err(format!(
                    "`{key}` is a Cook-Torrance term; `{name}` takes none"
                ));
            }
            match key.trim() {
                "distribution" => base.distribution = value.trim().parse::<Distribution>()?,
                "fresnel" => base.fresnel = value.trim().parse::<Fresnel>()?,
                "geometry" => base.geometry = value.trim().parse::<Geometry>()?,
                other => {
                    return Err(format!(
                        "`{other}` is not a term a fit chooses (distribution, fresnel, geometry)"
                    ));
                }
            }
        }
        let mut free = free_numbers(&mut base);
        free.extend(layer_numbers(layers));
        let spec = if model == ReflectanceModel::CookTorrance {
            format!(
                "{name},distribution={},fresnel={}{}",
                base.distribution,
                base.fresnel,
                if base.geometry == Geometry::Smith {
                    String::new()
                } else {
                    format!(",geometry={}", base.geometry)
                }
            )
        } else if from_published {
            format!("{name},start=published")
        } else if let Some(names) = layers.names() {
            format!("{name},layers={names}")
        } else {
            name.to_string()
        };
        let width = free.iter().position(|f| {
            [&K_E, &WARD_SIGMA, &ROUGHNESS, &PERCEPTUAL_ROUGHNESS, &ABC_B]
                .iter()
                .any(|p| std::ptr::eq(*p, f.param))
        });
        let of = |p: &'static Param| -> Vec<usize> {
            (0..free.len())
                .filter(|&k| std::ptr::eq(free[k].param, p))
                .collect()
        };
        let scans = if model == ReflectanceModel::Abc {
            // A = 0.06, 4, 250, 1.6e4; C = 0.01 … 10 at 7 points (log);
            // η_t = 1.58, 3.98, 15.8 (log): a start on the wrong side of
            // the Fresnel's rise stalls at η_t's bound once A is solved
            // (`linear.rs`), where the A scan no longer moves the start.
            vec![
                (of(&ABC_A), vec![0.2, 0.4, 0.6, 0.8]),
                (of(&ABC_C), (0..=6).map(|k| k as f64 / 6.0).collect()),
                (of(&ETA_T), vec![0.1, 0.3, 0.6]),
            ]
        } else {
            // The coat's width, like the base's: a wide and a narrow
            // lobe are told apart by where they start. The sheen's: a
            // rim that hugs the horizon or spreads over the hemisphere.
            let mut scans = Vec::new();
            if layers.clearcoat {
                scans.push((of(&CLEARCOAT_ROUGHNESS), vec![0.1, 0.4, 0.8]));
            }
            if layers.sheen {
                scans.push((of(&SHEEN_ROUGHNESS), vec![0.2, 0.7]));
            }
            scans
        };
        Ok(FitModel {
            spec,
            base,
            free,
            width,
            scans,
        })
    }

    /// A short label for tables: `ct-ggx-conductor`, `ward`, ...
    pub fn label(&self) -> String {
        if self.is_published() {
            return ABC_PUBLISHED.into();
        }
        if self.starts_from_published() {
            return "abc-from-published".into();
        }
        let m = &self.base;
        if let Some((_, names)) = self.spec.split_once(",layers=") {
            return format!("{}+{names}", m.model.name());
        }
        if m.model != ReflectanceModel::CookTorrance {
            return m.model.name().to_string();
        }
        let d = match m.distribution {
            Distribution::BlinnNormalized => "blinn",
            Distribution::GaussianNormalized => "gaussian",
            Distribution::Blinn => "blinn-lecture",
            Distribution::Gaussian => "gaussian-lecture",
            other => other.name(),
        };
        let mut label = format!("ct-{d}-{}", m.fresnel);
        if m.geometry != Geometry::Smith {
            label.push_str(&format!("-{}", m.geometry));
        }
        label
    }

    /// Whether this is the published ABC parameters, not a fit.
    pub fn is_published(&self) -> bool {
        self.spec == ABC_PUBLISHED
    }

    /// Whether the fit also starts from the published ABC parameters
    /// (`abc,start=published`).
    pub fn starts_from_published(&self) -> bool {
        self.spec.ends_with(",start=published")
    }

    /// The material at the free numbers `values` (one per [`Self::free`]).
    pub fn material(&self, values: &[f64]) -> Material {
        let mut m = self.base.clone();
        for (f, &v) in self.free.iter().zip(values) {
            f.write(&mut m, v);
        }
        m
    }
}

/// The layers a `gltf-pbr` fit adds (`layers=clearcoat`, `layers=sheen`,
/// `layers=clearcoat+sheen`).
#[derive(Clone, Copy, Debug, Default)]
struct Layers {
    clearcoat: bool,
    sheen: bool,
}

impl Layers {
    /// `clearcoat`, `sheen` or `clearcoat+sheen`; `None` without layers.
    fn names(self) -> Option<String> {
        let names: Vec<&str> = [(self.clearcoat, "clearcoat"), (self.sheen, "sheen")]
            .into_iter()
            .filter_map(|(on, name)| on.then_some(name))
            .collect();
        (!names.is_empty()).then(|| names.join("+"))
    }
}

fn parse_layers(value: &str) -> Result<Layers, String> {
    let mut layers = Layers::default();
    for name in value.split('+').map(str::trim) {
        match name {
            "clearcoat" => layers.clearcoat = true,
            "sheen" => layers.sheen = true,
            other => {
                return Err(format!(
                    "`{other}` is not a layer a fit adds: it adds `clearcoat`, `sheen` or both (`clearcoat+sheen`)"
                ));
            }
        }
    }
    Ok(layers)
}

/// The sheen's perceptual roughness searched (module doc: the table the
/// search reads errs by up to 0.22 below 0.1, 2.5·10⁻³ above).
const SHEEN_ROUGHNESS_BOUNDS: (f64, f64) = (0.1, 1.0);

/// The free numbers of the layers: a coat's weight and perceptual
/// roughness (from 0.01, as the base's); a sheen's colour and perceptual
/// roughness ([`SHEEN_ROUGHNESS_BOUNDS`]).
fn layer_numbers(layers: Layers) -> Vec<Free> {
    let mut free = Vec::new();
    if layers.clearcoat {
        free.push(Free {
            channel: None,
            ..colour(&CLEARCOAT, 0.0, 1.0).next().expect("three channels")
        });
        free.push(shape(
            &CLEARCOAT_ROUGHNESS,
            PERCEPTUAL_BOUNDS.0,
            PERCEPTUAL_BOUNDS.1,
            true,
        ));
    }
    if layers.sheen {
        free.extend(colour(&SHEEN_COLOR, 0.0, 1.0));
        free.push(shape(
            &SHEEN_ROUGHNESS,
            SHEEN_ROUGHNESS_BOUNDS.0,
            SHEEN_ROUGHNESS_BOUNDS.1,
            false,
        ));
    }
    free
}

fn unknown(name: &str) -> String {
    let names: Vec<&str> = FITTABLE.iter().map(|m| m.name()).collect();
    let hint = crate::base::did_you_mean(name, names.iter().copied());
    format!(
        "`{name}` is not a model gonio fits{hint}; it fits {} (Cook-Torrance with `,distribution=D,fresnel=F`), and scores {ABC_PUBLISHED} (the published ABC parameters of a MERL material)",
        names.join(", ")
    )
}

/// The free numbers of `base`'s model; fixes what is held (module doc).
fn free_numbers(base: &mut Material) -> Vec<Free> {
    use ReflectanceModel as M;
    let mut free: Vec<Free> = Vec::new();
    match base.model {
        M::Lambert => free.extend(colour(&K_D, 0.0, 1.0)),
        M::Phong | M::PhongNormalized | M::BlinnPhong | M::BlinnPhongNormalized => {
            free.extend(colour(&K_D, 0.0, 1.0));
            free.extend(colour(&K_S, 0.0, 1.0));
            free.push(shape(&K_E, K_E_BOUNDS.0, K_E_BOUNDS.1, true));
        }
        M::Ward => {
            free.extend(colour(&K_D, 0.0, 1.0));
            free.extend(colour(&K_S, 0.0, 1.0));
            free.push(shape(&WARD_SIGMA, SLOPE_BOUNDS.0, SLOPE_BOUNDS.1, true));
        }
        M::CookTorrance => {
            free.extend(colour(&K_D, 0.0, 1.0));
            free.push(shape(&ROUGHNESS, SLOPE_BOUNDS.0, SLOPE_BOUNDS.1, true));
            match base.fresnel {
                Fresnel::Dielectric => {
                    base.eta_i = 1.0;
                    free.extend(colour(&K_S, 0.0, 1.0));
                    free.push(shape(&ETA_T, ETA_T_BOUNDS.0, ETA_T_BOUNDS.1, false));
                }
                Fresnel::None => free.extend(colour(&K_S, 0.0, 1.0)),
                Fresnel::Conductor | Fresnel::ConductorLecture | Fresnel::Schlick => {
                    free.push(Free {
                        channel: None,
                        ..colour(&K_S, 0.0, 1.0).next().expect("three channels")
                    });
                    free.extend(log_colour(&ETA, ETA_BOUNDS.0, ETA_BOUNDS.1));
                    free.extend(log_colour(&KAPPA, KAPPA_BOUNDS.0, KAPPA_BOUNDS.1));
                }
            }
        }
        M::GltfPbr => {
            free.extend(colour(&BASE_COLOR, 0.0, 1.0));
            free.push(shape(&METALLIC, 0.0, 1.0, false));
            free.push(shape(
                &PERCEPTUAL_ROUGHNESS,
                PERCEPTUAL_BOUNDS.0,
                PERCEPTUAL_BOUNDS.1,
                true,
            ));
        }
        M::Abc => {
            base.k_s = crate::base::Rgb::ONE;
            base.eta_i = 1.0;
            free.extend(colour(&K_D, 0.0, 1.0));
            free.extend(log_colour(&ABC_A, ABC_A_BOUNDS.0, ABC_A_BOUNDS.1));
            free.push(shape(&ABC_B, ABC_B_BOUNDS.0, ABC_B_BOUNDS.1, true));
            free.push(shape(&ABC_C, ABC_C_BOUNDS.0, ABC_C_BOUNDS.1, true));
            free.push(shape(&ETA_T, ABC_ETA_T_BOUNDS.0, ABC_ETA_T_BOUNDS.1, true));
        }
        _ => unreachable!("FITTABLE lists the models above"),
    }
    free
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_model_parses_and_its_spec_reads_back() {
        for spec in ALL {
            let m = FitModel::parse(spec).unwrap();
            assert_eq!(&m.spec, spec);
            assert_eq!(FitModel::parse(&m.spec).unwrap().free.len(), m.free.len());
        }
    }

    #[test]
    fn bounds_lie_in_the_table_ranges() {
        for spec in ALL {
            for f in FitModel::parse(spec).unwrap().free {
                assert!(f.lo < f.hi, "{spec}: {}", f.param.key);
                for v in [f.lo, f.hi, f.at(0.5)] {
                    assert!(f.param.range.contains(v), "{spec}: {} = {v}", f.param.key);
                }
            }
        }
    }

    #[test]
    fn bad_specs_say_what_is_accepted() {
        let e = FitModel::parse("mirror").unwrap_err();
        assert!(e.contains("ward") && e.contains("gltf-pbr"), "{e}");
        assert!(FitModel::parse("ward,distribution=ggx").is_err());
        let e = FitModel::parse("cook-torrance,distribution=gauss").unwrap_err();
        assert!(e.contains("beckmann"), "{e}");
    }
}
