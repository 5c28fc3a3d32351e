//! `gonio brdf`: the command-line face of [`crate::explore`]. `src/cli.rs`
//! only holds the subcommand variant; everything else is here.

use super::albedo::albedo_curve_with;
use super::gloss::{GEOMETRIES, gloss_at};
use super::part::term_label;
use super::plot::{AlbedoPlot, SlicePlot};
use super::slice::{Quantity, slice};
use super::{Channel, Labelled, LayerChoice, MaterialPart, direction, frame, spec, table};
use crate::material::ReflectanceModel;
use crate::material::layers::LayerTerm;
use crate::output::plot::{PlotFile, number};
use crate::{Error, Result};
use std::path::PathBuf;

/// `gonio brdf --model MODEL [--set KEY=VALUE]... [angles] [plots]`
#[derive(Debug, clap::Args)]
#[command(
    about = "Print BRDF values, plot polar slices and directional albedo, read gloss",
    long_about = "Print f_r [1/sr] of one or more materials for given directions, and plot \
the lecture's polar slice or the directional albedo. Frame: normal n = +Z, tangent t = +X; \
θ from the normal, φ from the tangent. Materials take the keys of a scene file's \
[materials.NAME] table; k_d, k_s left out take the model's defaults (Phong, Blinn-Phong, Ward: 0.5, 0.5; Cook-Torrance: k_s = 1 with k_d = 0 for a conductor's Fresnel term, the default and every metal preset, k_d = 0.5 for a dielectric; docs/brdf-models.md)."
)]
pub struct BrdfArgs {
    // Help texts that list models or keys are generated from the table of
    // models (`model_help`, `set_help`).
    #[arg(long = "model", value_name = "MODEL", help = model_help())]
    pub models: Vec<String>,
    /// A material as `MODEL[,KEY=VALUE]...`, e.g.
    /// `cook-torrance,preset=gold,roughness=0.1` (repeat to overlay; its
    /// keys win over --set).
    #[arg(long = "compare", value_name = "SPEC")]
    pub compare: Vec<String>,
    #[arg(long = "set", value_name = "KEY=VALUE", help = set_help())]
    pub set: Vec<String>,
    /// Incidence polar angle θ_i [°], from the normal.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 30.0,
        allow_negative_numbers = true
    )]
    pub theta_i: f64,
    /// Incidence azimuth φ_i [°], from the tangent.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub phi_i: f64,
    /// Outgoing polar angle θ_o [°]. Default: the mirror direction (θ_i).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub theta_o: Option<f64>,
    /// Outgoing azimuth φ_o [°]. Default: φ_i + 180 (the mirror side).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub phi_o: Option<f64>,
    /// Also print the directional albedo ρ(θ_i) = ∫ f_r cos θ_o dω_o.
    #[arg(long)]
    pub albedo: bool,
    /// Print the specular gloss (ISO 2813 / ASTM D523) at 20°, 60°, 85°,
    /// the sample turned so that the light is at azimuth --phi-i.
    #[arg(long)]
    pub gloss: bool,
    /// Write the polar slice in the plane of incidence at θ_i (.png or .svg).
    #[arg(long, value_name = "OUT")]
    pub plot_slice: Option<PathBuf>,
    /// Radius of the slice: f_r-cos (f_r·cos θ_o, default) or f_r.
    #[arg(long, value_name = "Q", default_value = "f_r-cos")]
    pub quantity: Quantity,
    /// Outer radius of the slice plot; larger values are clipped.
    #[arg(long, value_name = "R")]
    pub slice_max: Option<f64>,
    /// Write directional albedo against θ_i = 0…89° (.png or .svg).
    #[arg(long, value_name = "OUT")]
    pub plot_albedo: Option<PathBuf>,
    /// Write the θ_h × θ_d image slice (Rusinkiewicz 1998; at --phi-d,
    /// log colour of f_r), one panel per material (.png or .svg).
    #[arg(long, value_name = "OUT")]
    pub plot_halfdiff: Option<PathBuf>,
    /// The difference azimuth φ_d [°] of --plot-halfdiff's image (BRDF
    /// Explorer's default, 90°, when not given).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub phi_d: Option<f64>,
    /// What the plots draw of RGB: mean (default), luminance, r, g, b.
    #[arg(long, value_name = "C", default_value = "mean")]
    pub channel: Channel,
    /// Which term of a layered gltf-pbr material the values, albedo,
    /// gloss and plots show: all (the whole f_r, default), base, sheen,
    /// clearcoat (each layer's lobe times what the layers above let
    /// through: the terms sum to the whole), or each (the whole and every
    /// term the material has, overlaid; --albedo then prints the terms'
    /// sum too).
    #[arg(long, value_name = "L", default_value = "all")]
    pub layer: LayerChoice,
    /// Print the Markdown albedo table of docs/brdf-models.md (all models).
    #[arg(long)]
    pub albedo_table: bool,
}

/// `--model`'s help: every model of the table.
fn model_help() -> String {
    let names: Vec<&str> = ReflectanceModel::ALL.iter().map(|m| m.name()).collect();
    format!(
        "Reflectance model (repeat to overlay several): {}",
        names.join(", ")
    )
}

/// `--set`'s help: every key a material takes.
fn set_help() -> String {
    let keys: Vec<&str> = crate::material::entry::keys()
        .iter()
        .copied()
        .filter(|k| *k != "model")
        .collect();
    format!(
        "A material key for every material, as in a scene file: {}. Values are TOML: \
`k_d=[0.8,0.2,0.1]`, `k_e=80`, `fresnel=schlick`",
        keys.join(", ")
    )
}

/// Runs `gonio brdf`.
pub fn run(args: &BrdfArgs) -> Result<()> {
    if args.albedo_table {
        print!("{}", table::markdown(&table::compute()?));
        if args.models.is_empty() && args.compare.is_empty() {
            return Ok(());
        }
    }
    let materials = materials(args)?;
    check_layer(args.layer, &materials)?;
    let parts = parts(&materials, args.layer);
    let angles = Angles::from_args(args)?;
    // Claim the outputs first: a bad path fails before any work.
    let slice_file = args
        .plot_slice
        .as_deref()
        .map(PlotFile::prepare)
        .transpose()?;
    let albedo_file = args
        .plot_albedo
        .as_deref()
        .map(PlotFile::prepare)
        .transpose()?;
    let halfdiff_file = args
        .plot_halfdiff
        .as_deref()
        .map(PlotFile::prepare)
        .transpose()?;
    if let Some(phi_d) = args.phi_d {
        if args.plot_halfdiff.is_none() {
            return Err(Error::argument(
                format!("--phi-d {phi_d}"),
                "φ_d is the azimuth of the θ_h × θ_d image: add --plot-halfdiff OUT.png",
            ));
        }
        if !phi_d.is_finite() {
            return Err(Error::argument(
                format!("--phi-d {phi_d}"),
                "the difference azimuth must be a number of degrees",
            ));
        }
    }
    if let Some(max) = args.slice_max
        && !(max.is_finite() && max > 0.0)
    {
        return Err(Error::argument(
            format!("--slice-max {max}"),
            "the outer radius must be a positive number",
        ));
    }

    print_values(&parts, &angles);
    if args.albedo {
        print_albedo(&materials, args.layer, &angles);
    }
    if args.gloss {
        print_gloss(&parts, angles.phi_i);
    }
    let note = shared_note(&args.set);
    let mut written = Vec::new();
    if let Some(file) = slice_file {
        if angles.theta_i >= 90.0 {
            return Err(Error::argument(
                format!("--theta-i {}", angles.theta_i),
                "the slice needs light above the surface: θ_i < 90°",
            ));
        }
        let theta_i = angles.theta_i.to_radians();
        let phi_i = angles.phi_i.to_radians();
        let plot = SlicePlot {
            theta_i,
            phi_i,
            quantity: args.quantity,
            channel: args.channel,
            series: parts
                .iter()
                .map(|(label, part)| {
                    let s = slice(*part, theta_i, phi_i, args.quantity, args.channel);
                    (label.clone(), s)
                })
                .collect(),
            max: args.slice_max,
            note: note.clone(),
        };
        let bytes = file.encode(&plot)?;
        written.push((file.into_file(), bytes));
    }
    if let Some(file) = halfdiff_file {
        let phi_d = args.phi_d.unwrap_or(90.0);
        let bytes = super::halfdiff_plot::encode(&file, &parts, args.channel, phi_d, note.clone())?;
        written.push((file.into_file(), bytes));
    }
    if let Some(file) = albedo_file {
        let phi_i = angles.phi_i.to_radians();
        let thetas_deg: Vec<f64> = (0..=89).map(f64::from).collect();
        let thetas: Vec<f64> = thetas_deg.iter().map(|d| d.to_radians()).collect();
        // A bar on a terminal, lines in a log: a measured material's
        // curve takes a minute (it once ran silent for 40–82 s).
        // The others take a second at most and stay quiet.
        let long = materials
            .iter()
            .any(|m| m.material.model == crate::material::ReflectanceModel::Measured);
        let progress = long.then(|| {
            std::sync::Mutex::new(crate::output::progress::Progress::new(
                "albedo",
                (parts.len() * thetas.len()) as u64,
            ))
        });
        let with_progress = |f: &dyn Fn(&mut crate::output::progress::Progress)| {
            if let Some(Ok(mut p)) = progress.as_ref().map(|p| p.lock()) {
                f(&mut p);
            }
        };
        let step = || with_progress(&|p| p.inc(1));
        let series = parts
            .iter()
            .map(|(label, part)| {
                with_progress(&|p| p.set_message(label.clone()));
                let curve = albedo_curve_with(*part, &thetas, phi_i, &step);
                (label.clone(), curve)
            })
            .collect();
        with_progress(&|p| p.finish());
        let plot = AlbedoPlot {
            phi_i,
            series,
            thetas_deg,
            channel: args.channel,
            note,
        };
        let bytes = file.encode(&plot)?;
        written.push((file.into_file(), bytes));
    }
    // The plots appear together or not at all.
    let paths: Vec<_> = written
        .iter()
        .map(|(f, _)| f.path().to_path_buf())
        .collect();
    crate::output::commit_all(written)?;
    for path in paths {
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The materials of `--model` and `--compare`, in that order.
fn materials(args: &BrdfArgs) -> Result<Vec<Labelled>> {
    if args.models.is_empty() && args.compare.is_empty() {
        return Err(Error::argument(
            "gonio brdf",
            "name at least one material: --model MODEL (e.g. --model phong-normalized) or --compare SPEC (e.g. --compare cook-torrance,preset=gold)",
        ));
    }
    let mut out = Vec::new();
    for model in &args.models {
        out.push(spec::material(
            &format!("--model {model}"),
            model,
            &args.set,
            &[],
        )?);
    }
    for s in &args.compare {
        out.push(spec::compare_spec(s, &args.set)?);
    }
    Ok(out)
}

/// The directions of the printout, in degrees.
struct Angles {
    theta_i: f64,
    phi_i: f64,
    theta_o: f64,
    phi_o: f64,
    mirror: bool,
}

impl Angles {
    fn from_args(args: &BrdfArgs) -> Result<Self> {
        let check = |flag: &str, v: f64, polar: bool| {
            let ok = v.is_finite() && (!polar || (0.0..=180.0).contains(&v));
            if ok {
                Ok(v)
            } else {
                Err(Error::argument(
                    format!("--{flag} {v}"),
                    if polar {
                        "a polar angle is in degrees from the normal, within [0, 180]"
                    } else {
                        "an azimuth must be a finite number of degrees"
                    },
                ))
            }
        };
        let theta_i = check("theta-i", args.theta_i, true)?;
        let phi_i = check("phi-i", args.phi_i, false)?;
        let theta_o = args
            .theta_o
            .map(|t| check("theta-o", t, true))
            .transpose()?;
        let phi_o = args.phi_o.map(|p| check("phi-o", p, false)).transpose()?;
        let phi_mirror = phi_i + 180.0;
        Ok(Angles {
            theta_i,
            phi_i,
            theta_o: theta_o.unwrap_or(theta_i),
            phi_o: phi_o.unwrap_or(phi_mirror),
            mirror: theta_o.is_none_or(|t| t == theta_i)
                && phi_o.is_none_or(|p| (p - phi_mirror).rem_euclid(360.0) == 0.0),
        })
    }
}

/// `--layer` names a term no material has: an error (nothing would be
/// shown but zeros); a material without the term: a note.
fn check_layer(choice: LayerChoice, materials: &[Labelled]) -> Result<()> {
    let LayerChoice::One(term @ (LayerTerm::Sheen | LayerTerm::Clearcoat | LayerTerm::Base)) =
        choice
    else {
        return Ok(());
    };
    let has = |m: &Labelled| {
        let l = &m.material.layers;
        m.material.model == ReflectanceModel::GltfPbr
            && match term {
                LayerTerm::Sheen => l.has_sheen(),
                LayerTerm::Clearcoat => l.has_clearcoat(),
                _ => true,
            }
    };
    if !materials.iter().any(has) {
        let key = match term {
            LayerTerm::Sheen => {
                "a gltf-pbr material with sheen_color ≠ 0, e.g. `--model gltf-pbr --set sheen_color=[0.5,0.5,0.5]`"
            }
            LayerTerm::Clearcoat => {
                "a gltf-pbr material with clearcoat > 0, e.g. `--model gltf-pbr --set clearcoat=1`"
            }
            _ => "a gltf-pbr material (`--model gltf-pbr`)",
        };
        return Err(Error::argument(
            format!("--layer {term}"),
            format!("no material has that layer: it needs {key}"),
        ));
    }
    for m in materials.iter().filter(|m| !has(m)) {
        eprintln!(
            "gonio: note: --layer {term}: {} has no {term} layer; its term is 0",
            m.label
        );
    }
    Ok(())
}

/// Every material's terms `choice` shows, each with its label.
fn parts(materials: &[Labelled], choice: LayerChoice) -> Vec<(String, MaterialPart<'_>)> {
    materials
        .iter()
        .flat_map(|m| {
            choice.terms(&m.material).into_iter().map(|term| {
                let part = MaterialPart::new(&m.material, term);
                (term_label(&m.label, term), part)
            })
        })
        .collect()
}

fn print_values(parts: &[(String, MaterialPart)], a: &Angles) {
    let wi = direction(a.theta_i.to_radians(), a.phi_i.to_radians());
    let wo = direction(a.theta_o.to_radians(), a.phi_o.to_radians());
    println!(
        "θ_i = {}°, φ_i = {}°, θ_o = {}°, φ_o = {}°{} (n = +Z, t = +X)",
        a.theta_i,
        a.phi_i,
        a.theta_o,
        a.phi_o,
        if a.mirror { " (mirror direction)" } else { "" }
    );
    if wi.z <= 0.0 || wo.z <= 0.0 {
        println!("a direction is at or below the horizon: f_r = 0 (every model is one-sided)");
    }
    for (label, part) in parts {
        let f = part.f_r(wi, wo, &frame());
        println!("{label}: f_r = [{}, {}, {}] 1/sr", f.x, f.y, f.z);
        if part.is_dirac() {
            let rho = part.dirac(wi.z);
            println!(
                "  plus a Dirac δ lobe in the mirror direction of reflectance k_s·F(cos θ_i) = [{}, {}, {}]",
                rho.x, rho.y, rho.z
            );
        }
    }
}

/// The albedo of each material at θ_i, of the terms `--layer` chooses;
/// with `each`, of the whole and of each term, then the terms' sum (equal
/// to the whole's within the error bounds: the terms are additive). For
/// a material that lets light through, also the transmitted albedo
/// `τ = ∫ f_t |cos θ_o| dω_o` over the far side and `ρ + τ`, at most 1
/// (`Side::Transmitted`).
fn print_albedo(materials: &[Labelled], choice: LayerChoice, a: &Angles) {
    let wi = direction(a.theta_i.to_radians(), a.phi_i.to_radians());
    for m in materials {
        let terms = choice.terms(&m.material);
        let mut sum = None;
        for &term in &terms {
            let part = MaterialPart::new(&m.material, term);
            let e = super::albedo::albedo_towards(part, wi, &frame());
            println!(
                "{}: albedo ρ(θ_i = {}°) = {}",
                term_label(&m.label, term),
                a.theta_i,
                with_bound(e.value, e.error_bound)
            );
            if part.transmits() {
                let t = super::albedo::albedo_towards(part.transmitted(), wi, &frame());
                let label = term_label(&m.label, term);
                println!(
                    "{label}: transmitted τ(θ_i = {}°) = {}",
                    a.theta_i,
                    with_bound(t.value, t.error_bound)
                );
                println!(
                    "{label}: reflected + transmitted ρ + τ = {}",
                    with_bound(e.value + t.value, e.error_bound + t.error_bound)
                );
            }
            if term != LayerTerm::All {
                let (v, b) = sum.unwrap_or_default();
                sum = Some((v + e.value, b + e.error_bound));
            }
        }
        if let Some((v, b)) = sum.filter(|_| terms.len() > 2) {
            println!("{}: sum of the terms = {}", m.label, with_bound(v, b));
        }
    }
}

/// `[r, g, b] ± [r, g, b]`.
fn with_bound(v: crate::scene::Rgb, b: crate::scene::Rgb) -> String {
    format!(
        "[{}, {}, {}] ± [{}, {}, {}]",
        number(v.x),
        number(v.y),
        number(v.z),
        number(b.x),
        number(b.y),
        number(b.z)
    )
}

fn print_gloss(parts: &[(String, MaterialPart)], phi_i: f64) {
    println!(
        "specular gloss (ISO 2813 / ASTM D523) at φ_i = {phi_i}°: 100 · Y(∫_aperture f_r cos θ_o dω_o) / F(black glass, η = {})",
        super::gloss::STANDARD_ETA
    );
    for (label, part) in parts {
        let readings: Vec<String> = GEOMETRIES
            .iter()
            .map(|&g| {
                let r = gloss_at(*part, g, phi_i.to_radians());
                format!("{}°: {} GU", g.angle_deg, number(r.gloss_units))
            })
            .collect();
        println!("{label}: {}", readings.join(", "));
    }
}

/// The `--set` assignments, for the plots' footers.
fn shared_note(set: &[String]) -> String {
    if set.is_empty() {
        String::new()
    } else {
        let kv: Vec<String> = set
            .iter()
            .map(|s| s.chars().filter(|c| !c.is_whitespace()).collect())
            .collect();
        format!("all: {}", kv.join(", "))
    }
}
