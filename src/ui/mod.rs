//! The interactive viewer, `gonio view`: a winit window with an egui side
//! panel, drawn by the same [`crate::gpu::GpuRenderer`] as `gonio render`
//! (through a [`crate::gpu::PreparedScene`] that lives across frames).
//!
//! Arranged by feature. [`app`] runs the window loop, [`view`] lays out
//! the panel, [`state`] holds what the viewer keeps between frames (the
//! document, the camera's [`orbit`], the sections), [`shared`] is what
//! every section edits besides its own state. [`document`] holds the
//! scene as loaded and its edits, [`edit`] applies one `KEY=VALUE` edit
//! and keeps the edits across a reload ([`edit_values`] reads a value,
//! [`save`] writes the scene file). Each panel section is a state struct
//! with its own `ui`: [`view_section`] and [`material_section`] (whose
//! widgets are in [`panels`]), and each feature's folder with its
//! section: [`file`](mod@file) (the section, the open dialog),
//! [`lights`] (the section, kinds, overlay, handles, spin, the
//! document's list edits),
//! [`environment`] (the map's section and edits), [`compare`] (compared
//! materials, the split view, fits), [`plots`] (the section, the plots).
//! [`surface`] owns the swapchain and screenshots.

pub mod app;
pub mod background;
pub mod cli;
pub mod compare;
pub mod document;
pub mod edit;
pub mod edit_values;
pub mod environment;
pub mod file;
pub mod lights;
pub mod material_section;
pub mod memory;
pub mod orbit;
pub mod pacing;
pub mod panel_cache;
pub mod panels;
pub mod plots;
pub mod save;
pub mod shared;
pub mod state;
pub mod surface;
pub mod view;
pub mod view_section;

use crate::scene::limits::Limits;
use crate::scene::scene_file::SceneSource;
use crate::{Error, Result};
pub use cli::ViewArgs;

/// `gonio view`: loads the scene (a bad one fails before any window
/// opens), opens the window, runs until it is closed or the scripted
/// frames are done. `chosen` are the overrides `--max-error` resolved to
/// (by the command line, `gonio view --max-error`); the `--set`s apply
/// after them.
pub fn run(args: ViewArgs, chosen: Vec<String>) -> Result<()> {
    memory::return_large_blocks_to_the_system();
    if !args.exposure.is_finite() {
        return Err(Error::argument(
            format!("--exposure {}", args.exposure),
            "the exposure must be a finite number of stops",
        ));
    }
    if args.screenshot.is_some() && args.frames.is_none() {
        return Err(Error::argument(
            "--screenshot",
            "needs --frames N (the scripted mode); in the window press F12 or use the panel's button",
        ));
    }
    if let Some(s) = args.exit_when_idle
        && !(s.is_finite() && s > 0.0)
    {
        return Err(Error::argument(
            format!("--exit-when-idle {s}"),
            "give a positive number of seconds",
        ));
    }
    if args.exit_when_idle.is_some()
        && (args.frames.is_some() || args.spin != 0.0 || args.spin_lights != 0.0)
    {
        return Err(Error::argument(
            "--exit-when-idle",
            "the scripted mode (--frames), --spin and --spin-lights draw continuously and are never idle; use it without them",
        ));
    }
    if args.frames == Some(0) {
        return Err(Error::argument("--frames 0", "render at least one frame"));
    }
    let limits = Limits::from_assignments(&args.limits)
        .map_err(|(arg, problem)| Error::argument(format!("--limit {arg}"), problem))?;
    let source = match &args.scene {
        Some(path) => SceneSource::File(path.clone()),
        None => SceneSource::BuiltIn,
    };
    let mut overrides = chosen;
    overrides.extend(args.set.iter().cloned());
    let mut doc = document::Document::load(source, overrides, limits)?;
    add_compared(&mut doc, &args)?;
    if args.spin_lights != 0.0 && doc.lights.entries.is_empty() {
        return Err(Error::argument(
            format!("--spin-lights {}", args.spin_lights),
            "the scene has no [[lights]] entries to move (a glTF's own lights and the built-in headlight are not moved); add [[lights]] to the scene file or drop the flag",
        ));
    }
    if !args.spin_lights.is_finite() || !args.spin.is_finite() {
        return Err(Error::argument(
            "--spin / --spin-lights",
            "give a finite number of degrees per frame",
        ));
    }
    if let Some(path) = &args.screenshot {
        // Fail on an unwritable destination before opening the window.
        crate::output::write::AtomicFile::create(path)?;
    }
    let event_loop = winit::event_loop::EventLoop::<pacing::Wake>::with_user_event()
        .build()
        .map_err(|e| {
        Error::NoDisplay(format!(
            "gonio view needs a display and none could be opened ({e}); on a desktop run it in the graphical session, on a headless machine run it under Xvfb: `xvfb-run -a gonio view` (./setup.sh installs xvfb)"
        ))
    })?;
    let report = args.frame_times;
    let proxy = event_loop.create_proxy();
    let mut app = app::App::new(args, doc, proxy);
    event_loop
        .run_app(&mut app)
        .map_err(|e| Error::NoDisplay(format!("the window loop failed: {e}")))?;
    if report {
        println!("{}", app.frame_time_report());
        println!("{}", app.upload_report());
    }
    app.result
}

/// `--compare SPEC`s and `--compare-fit MODEL` into the document's compare
/// list (a bad one fails before any window opens).
fn add_compared(doc: &mut document::Document, args: &ViewArgs) -> Result<()> {
    for spec in &args.compare {
        let labelled = crate::explore::spec::compare_spec(spec, &[])?;
        let mut m = labelled.material;
        m.name = labelled.label;
        doc.compare.add(m);
    }
    if let Some(text) = &args.compare_fit {
        let flag = format!("--compare-fit {text}");
        let model = compare::fitted::model(text).map_err(|p| Error::argument(&flag, p))?;
        let Some(first) = doc.scene.materials.first() else {
            return Err(Error::argument(flag, "the scene has no material"));
        };
        let brdf = match (first.model, first.measured_brdf()) {
            (crate::material::ReflectanceModel::Measured, Some(b)) => b,
            _ => {
                return Err(Error::argument(
                    flag,
                    format!(
                        "the fit is of the scene's first material, and `{0}` is not measured; make it one, e.g. --set materials.{0}.model=measured --set materials.{0}.measured=gold-metallic-paint",
                        first.name
                    ),
                ));
            }
        };
        let start = std::time::Instant::now();
        let stored = compare::fitted::stored(&brdf.name, &model).is_some();
        let m = compare::fitted::fit(brdf, &model).map_err(|p| Error::argument(&flag, p))?;
        if !stored {
            eprintln!(
                "gonio view: {} is not in docs/fit/fits.toml; fitted now in {:.1} s",
                m.name,
                start.elapsed().as_secs_f64()
            );
        }
        doc.compare.add(m);
    }
    Ok(())
}
