//! The panel's plots of the selected material and of every material it is
//! compared with, from the same f64 reference functions as `gonio brdf`
//! (`crate::explore`): the lecture's polar slice for an adjustable
//! incidence direction (θ_i and φ_i) with a linear or logarithmic radius
//! ([`polar`], [`radius`]), the directional albedo against θ_i in the
//! plane φ_i ([`albedo`]), and a table with each material's colour, its
//! albedo at the current ω_i and a gloss meter's readings at 20°, 60° and
//! 85° (ISO 2813 / ASTM D523) with the sample turned to φ_i ([`readout`]).
//! It stands below the plots, so no legend covers data. The θ_h × θ_d
//! image ([`halfdiff`]) shows f_r over Rusinkiewicz's half/difference
//! angles at the panel's φ_d, each material's image beside the others'.
//!
//! The slice is cheap (about 800 evaluations per material) and follows
//! every edit at once. Albedo and gloss are adaptive integrals, so they
//! run in the background ([`worker`]); the panel shows the last finished
//! result, marked stale until the new one arrives.
//!
//! The plots take the panel's width (the panel's left edge can be dragged)
//! and keep their aspect, so they grow with it.

pub mod albedo;
pub mod halfdiff;
pub mod lobe;
pub mod polar;
pub mod radius;
pub mod readout;
pub mod section;
pub mod series;
pub mod worker;

pub use series::{Integrals, Series, Settings, colour};

use crate::explore::Channel;
use crate::explore::albedo::{AlbedoEstimate, albedo_curve, albedo_towards};
use crate::explore::gloss::{GEOMETRIES, gloss_at};
use crate::explore::slice::{Quantity, Slice, slice};
use crate::explore::{LayerChoice, MaterialPart, direction, frame};
use crate::material::Material;
use crate::material::layers::LayerTerm;
use worker::Slot;

/// Incidence angles of the albedo curve, degrees.
const ALBEDO_ANGLES: usize = 31;

/// A plotted material and the term of its `f_r` drawn.
type Term = (Material, LayerTerm);
type CurveKey = (Term, u64);
type PointKey = (Term, u64, u64);
type SliceKey = (Term, Settings);
type LobeKey = (Term, u64, u64, Quantity, Channel);
type HalfDiffKey = (Term, u64);

/// The cached results of one series.
#[derive(Default)]
struct SeriesCache {
    slice: Option<(SliceKey, Slice)>,
    curve: Slot<CurveKey, Integrals>,
    point: Slot<PointKey, AlbedoEstimate>,
    lobe: Slot<LobeKey, lobe::Mesh>,
    halfdiff: Slot<HalfDiffKey, halfdiff::Image>,
}

/// The plots' state: settings and each series' cached results.
pub struct Plots {
    pub settings: Settings,
    /// Which views are drawn (and computed): the slice, the albedo
    /// curve, the θ_h × θ_d image and the 3D lobe.
    pub show_slice: bool,
    pub show_albedo: bool,
    pub show_halfdiff: bool,
    pub show_lobe: bool,
    turn: lobe::Turn,
    halfdiff_view: halfdiff::View,
    caches: Vec<SeriesCache>,
}

impl Default for Plots {
    fn default() -> Self {
        Plots {
            settings: Settings::default(),
            show_slice: true,
            show_albedo: true,
            show_halfdiff: true,
            show_lobe: true,
            turn: lobe::Turn::default(),
            halfdiff_view: halfdiff::View::default(),
            caches: Vec::new(),
        }
    }
}

impl Plots {
    /// Draws the controls, the views shown and the table of `series`
    /// into `ui`.
    pub fn show(&mut self, ui: &mut egui::Ui, series: &[Series]) {
        let layered = series
            .iter()
            .any(|one| one.material.model == crate::material::ReflectanceModel::GltfPbr);
        controls(ui, &mut self.settings, layered);
        let series = &Series::terms(series, self.settings.layer);
        ui.horizontal_wrapped(|ui| {
            ui.label("views");
            ui.checkbox(&mut self.show_slice, "slice");
            ui.checkbox(&mut self.show_albedo, "albedo");
            ui.checkbox(&mut self.show_halfdiff, "θ_h × θ_d");
            ui.checkbox(&mut self.show_lobe, "3D lobe");
        });
        self.caches.resize_with(series.len(), SeriesCache::default);
        let s = self.settings;
        for (cache, one) in self.caches.iter_mut().zip(series) {
            cache.refresh(one, &s, self.show_lobe, ui.ctx());
            if self.show_halfdiff {
                cache
                    .halfdiff
                    .request(&halfdiff_key(one, &s), ui.ctx(), |((m, t), phi_d)| {
                        halfdiff::image(part(&m, t), f64::from_bits(phi_d))
                    });
            }
        }
        let slices: Vec<&Slice> = self
            .caches
            .iter()
            .map(|c| &c.slice.as_ref().expect("refreshed above").1)
            .collect();
        if self.show_slice {
            polar::show(ui, &s, &slices);
        }
        let curves: Vec<Option<(&Integrals, bool)>> = self
            .caches
            .iter()
            .zip(series)
            .map(|(c, one)| c.curve.latest(&curve_key(one, &s)))
            .collect();
        if self.show_albedo {
            albedo::show(ui, &s, &curves);
        }
        if self.show_halfdiff {
            let images: Vec<Option<(&halfdiff::Image, bool)>> = self
                .caches
                .iter()
                .zip(series)
                .map(|(c, one)| c.halfdiff.latest(&halfdiff_key(one, &s)))
                .collect();
            halfdiff::show(ui, &s, &mut self.halfdiff_view, series, &images);
        }
        let points: Vec<Option<(&AlbedoEstimate, bool)>> = self
            .caches
            .iter()
            .zip(series)
            .map(|(c, one)| c.point.latest(&point_key(one, &s)))
            .collect();
        readout::show(ui, &s, series, &slices, &points, &curves);
        if self.show_lobe {
            let meshes: Vec<Option<(&lobe::Mesh, bool)>> = self
                .caches
                .iter()
                .zip(series)
                .map(|(c, one)| c.lobe.latest(&lobe_key(one, &s)))
                .collect();
            lobe::show(ui, &s, &mut self.turn, &meshes);
        }
    }

    /// A scripted `--edit FRAME:plots.KEY=VALUE` (`key` without
    /// `plots.`): `theta_i`, `phi_i`, `phi_d` (degrees), `quantity`
    /// (`f_r-cos` or `f_r`), `channel` (`mean`, `luminance`, `r`, `g`,
    /// `b`), `log` (bool), `decades` (1 to 10), `layer` (`all`, `base`,
    /// `sheen`, `clearcoat` or `each`: a layered material's whole, one
    /// layer's term or all apart), the views shown `slice`,
    /// `albedo`, `halfdiff`, `lobe` (bool), and `probe` (`TH,TD`: the θ_h ×
    /// θ_d image's readout point in degrees, or `none`).
    pub fn edit(&mut self, key: &str, value: &str) -> Result<(), String> {
        let text = value.trim().trim_matches('"');
        let number = || -> Result<f64, String> {
            text.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("plots.{key}: `{value}` is not a number"))
        };
        let boolean = || -> Result<bool, String> {
            text.parse::<bool>()
                .map_err(|_| format!("plots.{key}: `{value}` is not true or false"))
        };
        let s = &mut self.settings;
        match key {
            "theta_i" => {
                let v = number()?;
                if !(0.0..=89.0).contains(&v) {
                    return Err(format!(
                        "plots.theta_i = {v}: the plots take θ_i in [0, 89]°"
                    ));
                }
                s.theta_i_deg = v;
            }
            "phi_i" => s.phi_i_deg = number()?,
            "phi_d" => s.phi_d_deg = number()?,
            "quantity" => s.quantity = text.parse()?,
            "channel" => s.channel = text.parse()?,
            "layer" => s.layer = text.parse().map_err(|e| format!("plots.layer: {e}"))?,
            "log" => s.log = boolean()?,
            "decades" => {
                let v = number()?;
                if !(1.0..=10.0).contains(&v) || v.fract() != 0.0 {
                    return Err(format!(
                        "plots.decades = {v}: give a whole number from 1 to 10"
                    ));
                }
                s.decades = v as u32;
            }
            "slice" => self.show_slice = boolean()?,
            "albedo" => self.show_albedo = boolean()?,
            "halfdiff" => self.show_halfdiff = boolean()?,
            "lobe" => self.show_lobe = boolean()?,
            "probe" => self.halfdiff_view.probe = probe(key, text)?,
            _ => {
                return Err(format!(
                    "unknown plot setting `plots.{key}`; the plots take theta_i, phi_i, phi_d, quantity, channel, log, decades, layer, slice, albedo, halfdiff, lobe, probe"
                ));
            }
        }
        Ok(())
    }

    /// Whether background integrals are under way or finished but not yet
    /// shown.
    pub fn busy(&self) -> bool {
        self.caches
            .iter()
            .any(|c| c.curve.busy() || c.point.busy() || c.lobe.busy() || c.halfdiff.busy())
    }
}

/// `plots.probe=TH,TD` (degrees, each in [0, 90]) or `none`.
fn probe(key: &str, text: &str) -> Result<Option<(f64, f64)>, String> {
    if text == "none" {
        return Ok(None);
    }
    let angles: Vec<Option<f64>> = text
        .split(',')
        .map(|a| {
            a.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| (0.0..=90.0).contains(v))
        })
        .collect();
    match angles[..] {
        [Some(th), Some(td)] => Ok(Some((th, td))),
        _ => Err(format!(
            "plots.{key} = {text}: give θ_h,θ_d in degrees, each in [0, 90] (e.g. `20,40`), or `none`"
        )),
    }
}

/// The explorer's view of a cached term.
fn part(m: &Material, term: LayerTerm) -> MaterialPart<'_> {
    MaterialPart::new(m, term)
}

fn term(one: &Series) -> Term {
    (one.material.clone(), one.term)
}

fn halfdiff_key(one: &Series, s: &Settings) -> HalfDiffKey {
    (term(one), s.phi_d_deg.to_bits())
}

fn curve_key(one: &Series, s: &Settings) -> CurveKey {
    (term(one), s.phi_i_deg.to_bits())
}

fn point_key(one: &Series, s: &Settings) -> PointKey {
    (term(one), s.theta_i_deg.to_bits(), s.phi_i_deg.to_bits())
}

fn lobe_key(one: &Series, s: &Settings) -> LobeKey {
    (
        term(one),
        s.theta_i_deg.to_bits(),
        s.phi_i_deg.to_bits(),
        s.quantity,
        s.channel,
    )
}

impl SeriesCache {
    /// The slice now (if its inputs changed); the integrals (and the 3D
    /// lobe, if shown) requested.
    fn refresh(&mut self, one: &Series, s: &Settings, lobe: bool, ctx: &egui::Context) {
        if lobe {
            let settings = *s;
            self.lobe
                .request(&lobe_key(one, s), ctx, move |((m, t), ..)| {
                    lobe::mesh(part(&m, t), &settings)
                });
        }
        let key = (term(one), *s);
        if self.slice.as_ref().map(|(k, _)| k) != Some(&key) {
            let (t, p) = (s.theta_i_deg.to_radians(), s.phi_i_deg.to_radians());
            let computed = slice(one.part(), t, p, s.quantity, s.channel);
            self.slice = Some((key, computed));
        }
        self.curve
            .request(&curve_key(one, s), ctx, |((m, t), phi)| {
                let m = part(&m, t);
                let phi = f64::from_bits(phi).to_radians();
                let thetas: Vec<f64> = (0..ALBEDO_ANGLES)
                    .map(|k| (k as f64 * 89.0 / (ALBEDO_ANGLES - 1) as f64).to_radians())
                    .collect();
                let albedo = albedo_curve(m, &thetas, phi);
                let degrees = || thetas.iter().map(|t| t.to_degrees());
                let transmitted = if m.transmits() {
                    degrees()
                        .zip(albedo_curve(m.transmitted(), &thetas, phi))
                        .collect()
                } else {
                    Vec::new()
                };
                Integrals {
                    albedo: degrees().zip(albedo).collect(),
                    transmitted,
                    gloss: GEOMETRIES.iter().map(|g| gloss_at(m, *g, phi)).collect(),
                }
            });
        self.point
            .request(&point_key(one, s), ctx, |((m, t), theta, phi)| {
                let wi = direction(
                    f64::from_bits(theta).to_radians(),
                    f64::from_bits(phi).to_radians(),
                );
                albedo_towards(part(&m, t), wi, &frame())
            });
    }
}

/// θ_i, φ_i, the radius quantity, channel and scale; the layer choice
/// where a plotted material is `gltf-pbr` (`layered`).
fn controls(ui: &mut egui::Ui, s: &mut Settings, layered: bool) {
    egui::Grid::new("plot settings")
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("θ_i (°)");
            ui.add(egui::Slider::new(&mut s.theta_i_deg, 0.0..=89.0).step_by(0.5));
            ui.end_row();
            ui.label("φ_i (°)");
            ui.add(egui::Slider::new(&mut s.phi_i_deg, 0.0..=180.0).step_by(1.0));
            ui.end_row();
            ui.label("φ_d (°)").on_hover_text(
                "difference azimuth of the θ_h × θ_d image (BRDF Explorer's default 90°)",
            );
            ui.add(egui::Slider::new(&mut s.phi_d_deg, 0.0..=180.0).step_by(1.0));
            ui.end_row();
            ui.label("radius");
            ui.horizontal(|ui| {
                ui.selectable_value(&mut s.quantity, Quantity::ProjectedFr, "f_r·cos θ_o");
                ui.selectable_value(&mut s.quantity, Quantity::Fr, "f_r");
            });
            ui.end_row();
            ui.label("channel");
            ui.horizontal(|ui| {
                for c in Channel::ALL {
                    let name = match c {
                        Channel::Mean => "mean",
                        Channel::Luminance => "Y",
                        Channel::R => "R",
                        Channel::G => "G",
                        Channel::B => "B",
                    };
                    ui.selectable_value(&mut s.channel, c, name)
                        .on_hover_text(c.describe());
                }
            });
            ui.end_row();
            if layered {
                ui.label("layer").on_hover_text(
                    "a gltf-pbr material's whole f_r, one layer's term (its lobe times what the layers above let through: the terms sum to the whole), or each apart",
                );
                ui.horizontal_wrapped(|ui| {
                    for c in LayerChoice::ALL {
                        ui.selectable_value(&mut s.layer, c, c.name());
                    }
                });
                ui.end_row();
            }
            ui.label("scale");
            ui.horizontal(|ui| {
                ui.selectable_value(&mut s.log, false, "linear");
                ui.selectable_value(&mut s.log, true, "log");
                if s.log {
                    ui.add(egui::Slider::new(&mut s.decades, 1..=10).suffix(" decades"));
                }
            });
            ui.end_row();
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scripted_plot_settings_are_checked() {
        let mut p = Plots::default();
        p.edit("theta_i", "60").unwrap();
        p.edit("log", "true").unwrap();
        p.edit("decades", "4").unwrap();
        p.edit("channel", "\"r\"").unwrap();
        p.edit("quantity", "f_r").unwrap();
        p.edit("phi_d", "45").unwrap();
        p.edit("halfdiff", "false").unwrap();
        p.edit("probe", "20, 40").unwrap();
        let s = p.settings;
        assert_eq!(
            (
                s.theta_i_deg,
                s.log,
                s.decades,
                s.channel,
                s.quantity,
                s.phi_d_deg
            ),
            (60.0, true, 4, Channel::R, Quantity::Fr, 45.0)
        );
        assert!(!p.show_halfdiff);
        assert_eq!(p.halfdiff_view.probe, Some((20.0, 40.0)));
        for (k, v) in [
            ("theta_i", "95"),
            ("decades", "0"),
            ("log", "yes"),
            ("channel", "alpha"),
            ("colour", "1"),
            ("probe", "20"),
            ("probe", "20,95"),
            ("phi_d", "x"),
        ] {
            assert!(p.edit(k, v).is_err(), "{k}={v}");
        }
        assert_eq!(p.settings, s, "refused edits change nothing");
        assert_eq!(p.halfdiff_view.probe, Some((20.0, 40.0)));
    }
}
