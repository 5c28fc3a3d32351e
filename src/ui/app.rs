//! The viewer's window loop (winit 0.30 `ApplicationHandler`).
//!
//! One frame (`App::frame`) runs these phases in order: scripted input
//! (`apply_scripted_resize`, `apply_scripted_edits`), the egui panel
//! (`run_panel`, which may edit the document; `report_message`,
//! `take_new_document`), fitting the scene's image size and camera to the
//! 3D area left of the panel (`fit_view`), bringing the [`PreparedScene`]
//! up to date (`update_gpu_scene`: one buffer write for most edits), then
//! drawing: the scene into the swapchain image through the same renderer
//! as `gonio render` (`draw_scene`), egui over it (`draw_panel`),
//! `present`, and afterwards `read_gpu_times` and `save_screenshot`.
//!
//! Frames are drawn only when something changed ([`super::pacing`]);
//! between them the loop sleeps in `ControlFlow::WaitUntil`.

use super::cli::ViewArgs;
use super::document::Document;
use super::orbit::Orbit;
use super::pacing::{Pacing, Wake};
use super::state::ViewerState;
use super::surface::{PendingScreenshot, WindowSurface};
use crate::gpu::{AdapterChoice, FrameTarget, GpuContext, GpuRenderer, PreparedScene};
use crate::scene::change::Change;
use crate::{Error, Result};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoopProxy};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

/// Width of the side panel in points.
const PANEL_WIDTH: f32 = 380.0;
/// How often the scene file is checked for changes.
const RELOAD_CHECK: Duration = Duration::from_millis(500);
/// When a frame could not be drawn (surface not ready), the next try.
const SURFACE_RETRY: Duration = Duration::from_millis(16);

/// The GPU side of the window.
struct Gfx {
    renderer: GpuRenderer,
    surface: WindowSurface,
    prepared: Option<PreparedScene>,
    /// The right half of a split view (compare mode): the scene with the
    /// selected material replaced by a compared one.
    prepared_right: Option<PreparedScene>,
    egui_renderer: egui_wgpu::Renderer,
    egui_state: egui_winit::State,
    timestamps: Option<crate::gpu::renderer::PassTimestamps>,
    /// The side panel drawn once per change (None: the surface cannot be
    /// copied into, so egui draws everything every frame).
    panel_cache: Option<super::panel_cache::PanelCache>,
    /// Timestamps around the egui pass (its slots 0 and 1).
    panel_timestamps: Option<crate::gpu::renderer::PassTimestamps>,
}

impl Gfx {
    /// egui's new and changed textures, to its renderer and the panel
    /// cache.
    fn upload_textures(&mut self, textures: &egui::TexturesDelta) {
        let ctx = self.renderer.context();
        for (id, deltas) in &textures.set {
            for delta in deltas {
                self.egui_renderer
                    .update_texture(&ctx.device, &ctx.queue, *id, delta);
                if let Some(cache) = &mut self.panel_cache {
                    cache.update_texture(&ctx.device, &ctx.queue, *id, delta);
                }
            }
        }
    }

    /// Frees the textures egui no longer uses (after the frame drew).
    fn free_textures(&mut self, textures: &egui::TexturesDelta) {
        for id in &textures.free {
            self.egui_renderer.free_texture(id);
            if let Some(cache) = &mut self.panel_cache {
                cache.free_texture(id);
            }
        }
    }
}

/// What laying out the panel left for drawing it.
struct PanelFrame {
    ctx: egui::Context,
    output: egui::FullOutput,
    /// The 3D area (what the panel leaves), in points.
    central: egui::Rect,
    /// CPU time of the layout.
    layout_time: Duration,
}

/// The egui render pass over the frame (loading what is there), with
/// `timestamps` around it (slots 0 and 1) when given.
fn encode_egui_pass(
    renderer: &egui_wgpu::Renderer,
    encoder: &mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    paint_jobs: &[egui::ClippedPrimitive],
    screen: &egui_wgpu::ScreenDescriptor,
    timestamps: Option<&crate::gpu::renderer::PassTimestamps>,
) {
    let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("egui"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: timestamps.map(|t| wgpu::RenderPassTimestampWrites {
            query_set: &t.set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }),
        occlusion_query_set: None,
        multiview_mask: None,
    });
    let mut pass = pass.forget_lifetime();
    renderer.render(&mut pass, paint_jobs, screen);
    drop(pass);
    if let Some(t) = timestamps {
        t.resolve(encoder);
    }
}

/// The application: window, GPU, state, and the scripted run's progress.
pub struct App {
    args: ViewArgs,
    state: ViewerState,
    window: Option<Arc<Window>>,
    gfx: Option<Gfx>,
    /// The first error that ends the run (exit status 2).
    pub result: Result<()>,
    frames: u32,
    frame_times: Vec<Duration>,
    /// GPU scene-pass times (timestamp queries, every 10th frame).
    gpu_times: Vec<f64>,
    /// CPU time of the panel per frame: egui layout and tessellation, ms.
    ui_times: Vec<f64>,
    /// GPU time of the egui pass (sampled like `gpu_times`), ms.
    panel_gpu_times: Vec<f64>,
    last_frame: Option<Instant>,
    /// When the window was created, and how long after it the first
    /// frame was presented: the window is blank until then (the scene's
    /// preparation, pipeline compilation, anything the first frame waits
    /// for), which the frame-to-frame times do not include.
    window_opened: Option<Instant>,
    first_frame: Option<Duration>,
    last_reload_check: Instant,
    drag: Option<(MouseButton, f64, f64)>,
    cursor: (f64, f64),
    last_message: Option<String>,
    /// The 3D area in physical pixels: x, y, width, height.
    view_rect: [u32; 4],
    /// When to draw (only on a change, unless scripted or animated).
    pacing: Pacing,
    /// The document a newly opened one replaced, with its view and
    /// selection, until the new one is on the GPU: a file the GPU cannot
    /// take (a limit of the device) brings it back instead of ending the
    /// viewer.
    previous: Option<(Document, Orbit, usize)>,
    /// Wakes the loop from egui's repaint callback (any thread).
    proxy: EventLoopProxy<Wake>,
    /// What the first frame sent to the GPU (the scene's preparation),
    /// and what every later frame sent (edits, camera moves, shadow maps
    /// drawn again): `--frame-times` prints both.
    first_uploads: Option<crate::gpu::UploadTally>,
    uploads: crate::gpu::UploadTally,
}

impl App {
    pub fn new(args: ViewArgs, doc: Document, proxy: EventLoopProxy<Wake>) -> App {
        let continuous = args.frames.is_some() || args.spin != 0.0 || args.spin_lights != 0.0;
        let idle_exit = args.exit_when_idle.map(Duration::from_secs_f64);
        App {
            pacing: Pacing::new(continuous, idle_exit),
            previous: None,
            proxy,
            state: ViewerState::new(doc, &args),
            args,
            window: None,
            gfx: None,
            result: Ok(()),
            frames: 0,
            frame_times: Vec::new(),
            gpu_times: Vec::new(),
            ui_times: Vec::new(),
            panel_gpu_times: Vec::new(),
            last_frame: None,
            window_opened: None,
            first_frame: None,
            last_reload_check: Instant::now(),
            drag: None,
            cursor: (0.0, 0.0),
            last_message: None,
            view_rect: [0, 0, 1, 1],
            first_uploads: None,
            uploads: Default::default(),
        }
    }

    /// What was sent to the GPU after the first frame, by kind
    /// ([`crate::gpu::UploadTally`]): a scripted edit's cost.
    pub fn upload_report(&self) -> String {
        let first = self.first_uploads.unwrap_or_default();
        format!(
            "uploads: first frame {} calls, {} bytes; later frames {} calls, {} bytes: {}",
            first.calls(),
            first.bytes(),
            self.uploads.calls(),
            self.uploads.bytes(),
            self.uploads
        )
    }

    /// Adds what the prepared scenes sent since the last frame to the
    /// first frame's count or to the later frames'.
    fn count_uploads(&mut self) {
        let Some(gfx) = self.gfx.as_mut() else {
            return;
        };
        let mut sent = crate::gpu::UploadTally::default();
        for p in [&mut gfx.prepared, &mut gfx.prepared_right]
            .into_iter()
            .flatten()
        {
            sent += p.take_uploads();
        }
        match &mut self.first_uploads {
            None => self.first_uploads = Some(sent),
            Some(_) => self.uploads += sent,
        }
    }

    /// Frame-time statistics for `--frame-times`, after the warm-up.
    pub fn frame_time_report(&self) -> String {
        let warm: Vec<f64> = self
            .frame_times
            .iter()
            .skip(self.args.warmup as usize)
            .map(|d| d.as_secs_f64() * 1e3)
            .collect();
        let (w, h) = self
            .gfx
            .as_ref()
            .map(|g| (g.surface.config.width, g.surface.config.height))
            .unwrap_or((0, 0));
        if warm.is_empty() {
            return format!(
                "frame times: no frames after the {} warm-up frames",
                self.args.warmup
            );
        }
        let mut sorted = warm.clone();
        sorted.sort_by(f64::total_cmp);
        let q = |p: f64| sorted[((sorted.len() - 1) as f64 * p).round() as usize];
        let mut ui = self.ui_times.clone();
        ui.sort_by(f64::total_cmp);
        let ui = match ui.len() {
            0 => String::new(),
            n => format!(
                "; panel CPU (egui layout + tessellation) median {:.2} ms",
                ui[n / 2]
            ),
        };
        let mut panel_gpu = self.panel_gpu_times.clone();
        panel_gpu.sort_by(f64::total_cmp);
        let panel_gpu = match panel_gpu.len() {
            0 => String::new(),
            n => format!("; egui pass (GPU) median {:.2} ms", panel_gpu[n / 2]),
        };
        let mut gpu = self.gpu_times.clone();
        gpu.sort_by(f64::total_cmp);
        let gpu = match gpu.len() {
            0 => String::new(),
            n => format!(
                "; GPU scene pass median {:.2} ms over {n} sampled frames",
                gpu[n / 2]
            ),
        };
        let first = match self.first_frame {
            Some(d) => format!(
                "; first frame {:.2} ms after the window opened",
                d.as_secs_f64() * 1e3
            ),
            None => String::new(),
        };
        format!(
            "frame times over {} frames after {} warm-up, window {}x{}, 3D area {}x{}, vsync {}: median {:.2} ms, p10 {:.2} ms, p90 {:.2} ms, min {:.2} ms, max {:.2} ms{first}{gpu}{panel_gpu}{ui}",
            sorted.len(),
            self.args.warmup,
            w,
            h,
            self.view_rect[2],
            self.view_rect[3],
            if self.state.view.vsync { "on" } else { "off" },
            q(0.5),
            q(0.1),
            q(0.9),
            sorted[0],
            sorted[sorted.len() - 1]
        )
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        if self.result.is_ok() {
            self.result = Err(e);
        }
        event_loop.exit();
    }

    fn init(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let (w, h) = self.args.size;
        let attributes = Window::default_attributes()
            .with_title(format!("gonio view: {}", self.state.doc.title()))
            .with_inner_size(winit::dpi::PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| Error::NoDisplay(format!("cannot open a window: {e}")))?,
        );
        self.window_opened = Some(Instant::now());
        let choice = AdapterChoice::from_flag_or_env(self.args.adapter.as_deref());
        let (ctx, surface) = GpuContext::with_window(&choice, window.clone())?;
        let caps = surface.get_capabilities(&ctx.adapter);
        let size = window.inner_size();
        let surface = WindowSurface::new(
            &ctx,
            caps,
            surface,
            (size.width, size.height),
            self.state.view.vsync,
        )?;
        self.state.adapter = ctx.adapter_info.name.clone();
        if self.args.verbose {
            eprintln!("adapter: {}", ctx.describe());
            eprintln!(
                "surface: {:?}, {:?}",
                surface.config.format, surface.config.present_mode
            );
        }
        let egui_ctx = egui::Context::default();
        // egui's repaint requests from outside a pass (a finished
        // background plot) wake the loop; those made during a pass are in
        // that pass's `repaint_delay` (Self::frame).
        let proxy = self.proxy.clone();
        egui_ctx.set_request_repaint_callback(move |info| {
            let _ = proxy.send_event(Wake::Repaint {
                delay: info.delay,
                pass: info.current_cumulative_pass_nr,
            });
        });
        let egui_state = egui_winit::State::new(
            egui_ctx,
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(ctx.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer = egui_wgpu::Renderer::new(
            &ctx.device,
            surface.config.format,
            egui_wgpu::RendererOptions {
                dithering: false,
                ..Default::default()
            },
        );
        let timestamps = ctx
            .timestamps
            .then(|| crate::gpu::renderer::PassTimestamps::new(&ctx.device));
        let panel_cache = surface
            .writable
            .then(|| super::panel_cache::PanelCache::new(&ctx.device, surface.config.format));
        let panel_timestamps = ctx
            .timestamps
            .then(|| crate::gpu::renderer::PassTimestamps::new(&ctx.device));
        self.gfx = Some(Gfx {
            renderer: GpuRenderer::new(ctx),
            surface,
            prepared: None,
            prepared_right: None,
            egui_renderer,
            egui_state,
            timestamps,
            panel_cache,
            panel_timestamps,
        });
        self.window = Some(window);
        Ok(())
    }

    /// One frame, phase by phase; `Err` ends the run.
    fn frame(&mut self, event_loop: &ActiveEventLoop) -> Result<()> {
        let Some(window) = self.window.clone() else {
            return Ok(());
        };
        if self.gfx.is_none() {
            return Ok(());
        }
        if !self.apply_scripted_resize(&window) {
            // Minimized: nothing to draw, but a scripted run still counts
            // the frame so it ends.
            self.frames += 1;
            if self.args.frames == Some(self.frames) {
                event_loop.exit();
            }
            return Ok(());
        }
        let start = Instant::now();
        if self.pacing.continuous() {
            self.record_frame_time();
        }
        self.apply_scripted_edits()?;
        let panel = self.run_panel(&window);
        let repaint_delay = panel
            .output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        self.report_message();
        self.take_new_document(&window);
        self.fit_view(panel.central, panel.output.pixels_per_point);
        if let Err(e) = self.update_gpu_scene() {
            let Some((doc, orbit, selected)) = self.previous.take() else {
                return Err(e);
            };
            self.state.message = Some(format!(
                "cannot show {}: {e}; the previous scene stays",
                self.state.doc.title()
            ));
            window.set_title(&format!("gonio view: {}", doc.title()));
            self.state.doc = doc;
            self.state.orbit = orbit;
            self.state.selected_material = selected;
            self.state.changes.mark(Change::Scene);
            if let Some(gfx) = &mut self.gfx {
                gfx.prepared = None;
                gfx.prepared_right = None;
            }
            self.report_message();
            self.fit_view(panel.central, panel.output.pixels_per_point);
            self.update_gpu_scene()?;
        }
        self.previous = None;
        let Some(frame) = self.acquire_surface_texture()? else {
            // Not drawn: try again shortly (an occluded window keeps
            // failing; do not spin on it).
            self.pacing.request(Instant::now(), SURFACE_RETRY);
            return Ok(());
        };
        let gfx = self.gfx.as_mut().expect("checked above");
        let mut encoder = gfx
            .renderer
            .context()
            .device
            .create_command_encoder(&Default::default());
        let measure_gpu = gfx.timestamps.is_some() && self.frames % 10 == 5;
        let view = frame.texture.create_view(&Default::default());
        self.draw_scene(&view, &mut encoder, measure_gpu);
        self.count_uploads();
        let extra = self.draw_panel(panel, &frame.texture, &view, &mut encoder, measure_gpu);
        self.frames += 1;
        let scripted_last = self.args.frames == Some(self.frames);
        let screenshot = self.present(&window, frame, encoder, extra, scripted_last);
        let now = Instant::now();
        self.pacing.drawn(now);
        self.pacing.request(now, repaint_delay);
        if !self.pacing.continuous() {
            // The time between frames means nothing when idle: the
            // overlay shows the frame's own CPU time.
            self.state.frame_ms = (now - start).as_secs_f64() * 1e3;
        }
        self.read_gpu_times(measure_gpu)?;
        if let Some(pending) = screenshot {
            self.save_screenshot(pending, scripted_last)?;
        }
        if scripted_last {
            event_loop.exit();
        }
        Ok(())
    }

    /// A scripted `--resize` due at this frame; returns whether the window
    /// has an area to draw into (not minimized).
    fn apply_scripted_resize(&mut self, window: &Window) -> bool {
        if let Some(&(_, (w, h))) = self.args.resizes.iter().find(|(at, _)| *at == self.frames) {
            if w == 0 || h == 0 {
                window.set_minimized(true);
            } else {
                window.set_minimized(false);
                let _ = window.request_inner_size(winit::dpi::PhysicalSize::new(w, h));
            }
        }
        let size = window.inner_size();
        size.width != 0 && size.height != 0
    }

    /// The time since the last frame, and the overlay's median of the
    /// last 30.
    fn record_frame_time(&mut self) {
        let now = Instant::now();
        if let Some(last) = self.last_frame {
            self.frame_times.push(now - last);
            let recent = &self.frame_times[self.frame_times.len().saturating_sub(30)..];
            let mut ms: Vec<f64> = recent.iter().map(|d| d.as_secs_f64() * 1e3).collect();
            ms.sort_by(f64::total_cmp);
            self.state.frame_ms = ms[ms.len() / 2];
        } else if let Some(opened) = self.window_opened {
            self.first_frame = Some(now - opened);
        }
        self.last_frame = Some(now);
    }

    /// Scripted `--edit`s (through the panel's path: typed values applied
    /// to the document) and `--drop`s due at this frame.
    fn apply_scripted_edits(&mut self) -> Result<()> {
        let frame = self.frames;
        for (_, kv) in self.args.edits.iter().filter(|(at, _)| *at == frame) {
            // The plots' settings are the viewer's, not the document's.
            if let Some((key, value)) = kv
                .strip_prefix("plots.")
                .and_then(|rest| rest.split_once('='))
            {
                self.state
                    .plots
                    .plots
                    .edit(key.trim(), value)
                    .map_err(|p| Error::argument(format!("--edit {kv}"), p))?;
                continue;
            }
            // A variant reloads the scene (its meshes draw other
            // materials): a new document, as the panel's combo makes.
            if let Some((key, value)) = kv.split_once('=')
                && key.trim() == super::document::VARIANT_KEY
            {
                let name: String = super::edit_values::toml_value(value)
                    .map_err(|p| Error::argument(format!("--edit {kv}"), p))?;
                self.state.choose_variant(&name)?;
                continue;
            }
            if let Some((key, value)) = kv
                .strip_prefix("panel.")
                .and_then(|rest| rest.split_once('='))
            {
                let request = super::view::section_request(key.trim(), value)
                    .map_err(|p| Error::argument(format!("--edit {kv}"), p))?;
                self.state.section_requests.push(request);
                continue;
            }
            let change = self.state.doc.edit(kv)?;
            self.state.changes.mark(change);
        }
        let drops: Vec<PathBuf> = self
            .args
            .drops
            .iter()
            .filter(|(at, _)| *at == frame)
            .map(|(_, p)| p.clone())
            .collect();
        for path in drops {
            self.state.drop_file(path);
        }
        Ok(())
    }

    /// Lays out the panel (which may edit the state).
    fn run_panel(&mut self, window: &Window) -> PanelFrame {
        let gfx = self.gfx.as_mut().expect("initialized");
        let start = Instant::now();
        let raw_input = gfx.egui_state.take_egui_input(window);
        let ctx = gfx.egui_state.egui_ctx().clone();
        let state = &mut self.state;
        let mut central = egui::Rect::NOTHING;
        let mut output = ctx.run_ui(raw_input, |ui| {
            central = super::view::ui(ui, state, PANEL_WIDTH);
        });
        let platform_output = std::mem::take(&mut output.platform_output);
        gfx.egui_state
            .handle_platform_output(window, platform_output);
        PanelFrame {
            ctx,
            output,
            central,
            layout_time: start.elapsed(),
        }
    }

    /// A new message also goes to stderr (scripted runs, logs).
    fn report_message(&mut self) {
        if self.state.message != self.last_message {
            if let Some(m) = &self.state.message {
                eprintln!("gonio view: {m}");
            }
            self.last_message = self.state.message.clone();
        }
    }

    /// A new document (opened, dropped, reloaded) replaces the old one
    /// (and its GPU resources, unless the meshes are the same).
    fn take_new_document(&mut self, window: &Window) {
        let Some(doc) = self.state.replace.take() else {
            return;
        };
        window.set_title(&format!("gonio view: {}", doc.title()));
        let (previous_orbit, previous_selection) =
            (self.state.orbit.clone(), self.state.selected_material);
        let keep_view = doc.path() == self.state.doc.path()
            && doc.loaded_camera == self.state.doc.loaded_camera;
        if !keep_view {
            self.state.orbit = Orbit::from_camera(&doc.loaded_camera);
            self.state.selected_material = 0;
        }
        // A reload with the same meshes (the file changed a light or a
        // material): the GPU keeps them and updates the rest.
        if doc.scene.meshes != self.state.doc.scene.meshes
            && let Some(gfx) = &mut self.gfx
        {
            gfx.prepared = None;
            gfx.prepared_right = None;
        }
        // The compared materials are the viewer's: they stay.
        let mut doc = doc;
        doc.compare = self.state.doc.compare.clone();
        let old = std::mem::replace(&mut self.state.doc, doc);
        self.previous = Some((old, previous_orbit, previous_selection));
        self.state.changes.mark(Change::Scene);
    }

    /// Fits the scene's image size and camera to the 3D area the panel
    /// left (`central`, in points), in physical pixels.
    fn fit_view(&mut self, central: egui::Rect, ppp: f32) {
        let gfx = self.gfx.as_ref().expect("initialized");
        let (sw, sh) = (gfx.surface.config.width, gfx.surface.config.height);
        let x0 = (central.min.x * ppp).round().clamp(0.0, sw as f32) as u32;
        let y0 = (central.min.y * ppp).round().clamp(0.0, sh as f32) as u32;
        let x1 = (central.max.x * ppp).round().clamp(0.0, sw as f32) as u32;
        let y1 = (central.max.y * ppp).round().clamp(0.0, sh as f32) as u32;
        let rect = [
            x0,
            y0,
            x1.saturating_sub(x0).max(1),
            y1.saturating_sub(y0).max(1),
        ];
        if rect != self.view_rect {
            self.view_rect = rect;
            // The roughness floor depends on the image height, the
            // shadow maps' fit on the image: compared in full.
            self.state.changes.mark(Change::Scene);
        }
        if self.args.spin != 0.0 {
            self.state.orbit.rotate_degrees(self.args.spin, 0.0);
        }
        if self.args.spin_lights != 0.0 {
            let target = self.state.orbit.camera().target;
            match super::lights::spin::spin_lights(
                &mut self.state.doc,
                target,
                self.args.spin_lights,
            ) {
                Ok(()) => self.state.changes.mark(Change::Lights),
                Err(e) => self.state.message = Some(e),
            }
        }
        let scene = &mut self.state.doc.scene;
        let camera = self.state.orbit.camera();
        if scene.camera != camera {
            scene.camera = camera;
            self.state.changes.mark(Change::View);
        }
        scene.width = self.view_rect[2];
        scene.height = self.view_rect[3];
    }

    /// Brings the [`PreparedScene`] up to date: prepared anew after a new
    /// document, updated after an edit, only its view after a camera move.
    fn update_gpu_scene(&mut self) -> Result<()> {
        let changes = self.state.changes.take();
        let display_scale = self.state.view.exposure.exp2() as f32;
        let gfx = self.gfx.as_mut().expect("initialized");
        let format = gfx.surface.config.format;
        let verbose = self.args.verbose;
        let scene = &mut self.state.doc.scene;
        let message = bring_up_to_date(
            &mut gfx.renderer,
            &mut gfx.prepared,
            scene,
            format,
            display_scale,
            &changes,
            verbose,
        )?;
        // The split view's right half: the same scene with the selected
        // material replaced (src/ui/compare/materials.rs).
        let right = self.state.doc.compare.right_half().cloned();
        let selected = self.state.selected_material;
        // Its changes: the scene's, and the compared material in place
        // of the selected one.
        let mut right_changes = changes.clone();
        if right_changes.compared {
            right_changes.mark(Change::Material(selected));
        }
        let right_message = match right {
            Some(other) if selected < scene.materials.len() => {
                super::compare::materials::with_material(scene, selected, &other, |scene| {
                    bring_up_to_date(
                        &mut gfx.renderer,
                        &mut gfx.prepared_right,
                        scene,
                        format,
                        display_scale,
                        &right_changes,
                        false,
                    )
                })?
            }
            _ => {
                gfx.prepared_right = None;
                None
            }
        };
        if let Some(m) = message.or(right_message) {
            self.state.message = Some(m);
        }
        Ok(())
    }

    /// The swapchain image to draw into; `None` skips the frame (the
    /// surface was reconfigured, timed out or is occluded).
    fn acquire_surface_texture(&mut self) -> Result<Option<wgpu::SurfaceTexture>> {
        let gfx = self.gfx.as_mut().expect("initialized");
        match gfx.surface.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => Ok(Some(f)),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                gfx.surface.reconfigure(gfx.renderer.context());
                Ok(None)
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                Ok(None)
            }
            other => Err(Error::Gpu(format!(
                "the window surface failed: {}",
                match other {
                    wgpu::CurrentSurfaceTexture::Validation => "validation error",
                    _ => "unknown",
                }
            ))),
        }
    }

    /// The scene into the 3D area, through the same renderer as
    /// `gonio render`.
    fn draw_scene(
        &mut self,
        view: &wgpu::TextureView,
        encoder: &mut wgpu::CommandEncoder,
        measure_gpu: bool,
    ) {
        let gfx = self.gfx.as_mut().expect("initialized");
        let [x, y, w, h] = self.view_rect;
        // image.msaa: the scene pass draws into a multisampled target and
        // resolves into the swapchain image (bring_up_to_date compiled the
        // pipelines for the same count).
        let samples = gfx.prepared.as_ref().map_or(1, |p| p.samples);
        let ctx = gfx.renderer.context();
        let depth = gfx.surface.depth_view(ctx, samples).clone();
        let multisampled = gfx.surface.multisampled_view(ctx, samples).cloned();
        let (color, resolve) = match &multisampled {
            Some(m) => (m, Some(view)),
            None => (view, None),
        };
        let timestamps = gfx.timestamps.as_ref().filter(|_| measure_gpu);
        let viewport = Some([x as f32, y as f32, w as f32, h as f32]);
        // Split (compare mode): the same camera and viewport for both
        // scenes, each clipped to its half, so one object is cut down the
        // middle.
        let half = w / 2;
        let (left, right) = match gfx.prepared_right {
            Some(_) => (Some([x, y, half, h]), Some([x + half, y, w - half, h])),
            None => (None, None),
        };
        let prepared = gfx.prepared.as_mut().expect("prepared by update_gpu_scene");
        gfx.renderer.encode(
            prepared,
            encoder,
            &FrameTarget {
                color,
                resolve,
                depth: &depth,
                viewport,
                clip: left,
                timestamps: timestamps.map(|t| &t.set),
            },
        );
        if let (Some(p), Some(clip)) = (gfx.prepared_right.as_mut(), right) {
            gfx.renderer.encode(
                p,
                encoder,
                &FrameTarget {
                    color,
                    resolve,
                    depth: &depth,
                    viewport,
                    clip: Some(clip),
                    timestamps: None,
                },
            );
        }
        if let Some(t) = timestamps {
            t.resolve(encoder);
        }
    }

    /// egui over the scene: the side panel from its cache (drawn again
    /// only when it changed), the rest (overlay, dialogs) now. Returns
    /// command buffers egui needs submitted first.
    fn draw_panel(
        &mut self,
        panel: PanelFrame,
        texture: &wgpu::Texture,
        view: &wgpu::TextureView,
        encoder: &mut wgpu::CommandEncoder,
        measure_gpu: bool,
    ) -> Vec<wgpu::CommandBuffer> {
        let gfx = self.gfx.as_mut().expect("initialized");
        let tessellate_start = Instant::now();
        let ppp = panel.output.pixels_per_point;
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [gfx.surface.config.width, gfx.surface.config.height],
            pixels_per_point: ppp,
        };
        let paint_jobs = panel.ctx.tessellate(panel.output.shapes, ppp);
        if self.frames >= self.args.warmup {
            let tessellation = tessellate_start.elapsed();
            self.ui_times
                .push((panel.layout_time + tessellation).as_secs_f64() * 1e3);
        }
        let textures = &panel.output.textures_delta;
        gfx.upload_textures(textures);
        let ctx = gfx.renderer.context();
        let (paint_jobs, mut extra) = match &mut gfx.panel_cache {
            Some(cache) if self.state.show_panel && !self.state.file.open_dialog => {
                let (panel_jobs, rest) =
                    super::panel_cache::split_jobs(paint_jobs, panel.central.max.x);
                let x = self.view_rect[0] + self.view_rect[2];
                let [sw, sh] = screen.size_in_pixels;
                let rect = [x, 0, sw.saturating_sub(x), sh];
                let extra = cache.draw(ctx, encoder, &panel_jobs, &screen, texture, rect);
                (rest, extra)
            }
            _ => (paint_jobs, Vec::new()),
        };
        extra.extend(gfx.egui_renderer.update_buffers(
            &ctx.device,
            &ctx.queue,
            encoder,
            &paint_jobs,
            &screen,
        ));
        let timestamps = gfx.panel_timestamps.as_ref().filter(|_| measure_gpu);
        encode_egui_pass(
            &gfx.egui_renderer,
            encoder,
            view,
            &paint_jobs,
            &screen,
            timestamps,
        );
        gfx.free_textures(textures);
        extra
    }

    /// Submits the frame and presents it; records the screenshot copy
    /// first when one is due (`Some(None)`: due, but the surface cannot be
    /// copied).
    fn present(
        &mut self,
        window: &Window,
        frame: wgpu::SurfaceTexture,
        mut encoder: wgpu::CommandEncoder,
        extra: Vec<wgpu::CommandBuffer>,
        scripted_last: bool,
    ) -> Option<Option<PendingScreenshot>> {
        let gfx = self.gfx.as_mut().expect("initialized");
        let ctx = gfx.renderer.context();
        let screenshot = (self.state.screenshot_requested
            || (scripted_last && self.args.screenshot.is_some()))
        .then(|| {
            gfx.surface
                .copyable
                .then(|| PendingScreenshot::record(&ctx.device, &mut encoder, &frame.texture))
        });
        ctx.queue
            .submit(extra.into_iter().chain([encoder.finish()]));
        window.pre_present_notify();
        ctx.queue.present(frame);
        screenshot
    }

    /// The GPU times of the scene and egui passes, on the frames that
    /// measured them.
    fn read_gpu_times(&mut self, measured: bool) -> Result<()> {
        let gfx = self.gfx.as_mut().expect("initialized");
        let ctx = gfx.renderer.context();
        let warm = self.frames > self.args.warmup;
        if measured && let Some(t) = &gfx.panel_timestamps {
            let (panel_pass, _) = t.read(ctx)?;
            if warm {
                self.panel_gpu_times.push(panel_pass.as_secs_f64() * 1e3);
            }
        }
        if measured && let Some(t) = &gfx.timestamps {
            let (scene_pass, _) = t.read(ctx)?;
            self.state.gpu_ms = Some(scene_pass.as_secs_f64() * 1e3);
            if warm {
                self.gpu_times.push(scene_pass.as_secs_f64() * 1e3);
            }
        }
        Ok(())
    }

    /// Writes a due screenshot; a failure ends a scripted run and is a
    /// message otherwise.
    fn save_screenshot(
        &mut self,
        pending: Option<PendingScreenshot>,
        scripted_last: bool,
    ) -> Result<()> {
        let gfx = self.gfx.as_ref().expect("initialized");
        self.state.screenshot_requested = false;
        let path = self.state.screenshot_path.clone();
        let result = match pending {
            Some(p) => p.save(&gfx.renderer.context().device, &path),
            None => Err(Error::Gpu(
                "this window surface cannot be copied, so no screenshot".into(),
            )),
        };
        match result {
            Ok(()) => {
                let [x, y, w, h] = self.view_rect;
                println!(
                    "screenshot {}: window {}x{}, 3D area x={x} y={y} {w}x{h}",
                    path.display(),
                    gfx.surface.config.width,
                    gfx.surface.config.height
                );
                self.state.message = Some(format!("saved {}", path.display()));
            }
            Err(e) if scripted_last => return Err(e),
            Err(e) => self.state.message = Some(e.to_string()),
        }
        Ok(())
    }

    /// Every [`RELOAD_CHECK`]: a changed scene file is reloaded (and a
    /// frame requested to show it).
    fn check_reload(&mut self) {
        if self.last_reload_check.elapsed() < RELOAD_CHECK {
            return;
        }
        self.last_reload_check = Instant::now();
        if self.state.doc.changed_on_disk() {
            match self.state.doc.reload() {
                Ok(doc) => {
                    self.state.replace = Some(doc);
                    self.state.message = Some("reloaded: the file changed on disk".into());
                }
                Err(e) => {
                    // Keep the current scene; do not retry the same
                    // broken file every half second.
                    self.state.message = Some(format!("not reloaded: {e}"));
                    self.state.doc.mark_seen();
                }
            }
        }
    }

    /// The 3D view's mouse and keys; returns whether the event may have
    /// changed what is drawn.
    fn on_view_input(&mut self, event: &WindowEvent) -> bool {
        // The light handles take the mouse first (super::lights::drag).
        let ppp = self.window.as_ref().map_or(1.0, |w| w.scale_factor());
        let state = &mut self.state;
        let pointer = super::lights::input::Pointer {
            view_rect: self.view_rect,
            cursor: self.cursor,
            pixels_per_point: ppp,
            overlay_shown: state.view.show_overlay,
        };
        let mut shared = super::shared::Shared {
            doc: &mut state.doc,
            changes: &mut state.changes,
            message: &mut state.message,
        };
        let camera = state.orbit.camera();
        let lights = state.lights.on_input(&mut shared, &camera, pointer, event);
        if let Some(acted) = lights {
            if let WindowEvent::CursorMoved { position, .. } = event {
                self.cursor = (position.x, position.y);
            }
            return acted;
        }
        let [x, y, w, h] = self.view_rect;
        let inside = |(cx, cy): (f64, f64)| {
            cx >= x as f64 && cy >= y as f64 && cx < (x + w) as f64 && cy < (y + h) as f64
        };
        match event {
            WindowEvent::MouseInput { state, button, .. } => match state {
                ElementState::Pressed if inside(self.cursor) => {
                    self.drag = Some((*button, self.cursor.0, self.cursor.1));
                }
                ElementState::Released => self.drag = None,
                _ => {}
            },
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x, position.y);
                if let Some((button, px, py)) = self.drag {
                    let (dx, dy) = (position.x - px, position.y - py);
                    match button {
                        MouseButton::Left => self.state.orbit.rotate(dx, dy),
                        MouseButton::Right | MouseButton::Middle => {
                            self.state.orbit.pan(dx, dy, h as f64)
                        }
                        _ => {}
                    }
                    self.drag = Some((button, position.x, position.y));
                    return true;
                }
                return false;
            }
            WindowEvent::MouseWheel { delta, .. } if inside(self.cursor) => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y as f64,
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.state.orbit.zoom(steps);
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                match &event.logical_key {
                    Key::Named(NamedKey::ArrowLeft) => self.state.orbit.rotate(-20.0, 0.0),
                    Key::Named(NamedKey::ArrowRight) => self.state.orbit.rotate(20.0, 0.0),
                    Key::Named(NamedKey::ArrowUp) => self.state.orbit.rotate(0.0, -20.0),
                    Key::Named(NamedKey::ArrowDown) => self.state.orbit.rotate(0.0, 20.0),
                    Key::Named(NamedKey::F12) => self.state.screenshot_requested = true,
                    Key::Character(c) => match c.as_str() {
                        "r" | "R" => self.state.orbit.reset(),
                        "+" | "=" => self.state.orbit.zoom(1.0),
                        "-" => self.state.orbit.zoom(-1.0),
                        "p" | "P" => self.state.show_panel = !self.state.show_panel,
                        "l" | "L" => self.state.lights.visible ^= true,
                        _ => {}
                    },
                    _ => {}
                }
            }
            _ => return false,
        }
        true
    }
}

/// Brings `prepared` up to date with `scene`: prepared anew when there is
/// none, else given `changes` (each kind writes only what it reaches:
/// [`GpuRenderer::apply`]), only its view after a camera move or a new
/// exposure. Returns a message for an edit the GPU refused (the scene
/// stays as it was drawn).
fn bring_up_to_date(
    renderer: &mut GpuRenderer,
    prepared: &mut Option<PreparedScene>,
    scene: &crate::scene::Scene,
    format: wgpu::TextureFormat,
    display_scale: f32,
    changes: &crate::scene::change::Changes,
    verbose: bool,
) -> Result<Option<String>> {
    // image.msaa, as `gonio render` draws it, or one sample with a word
    // when the adapter cannot multisample the window's format.
    let (samples, mut refused) = match scene.msaa {
        0 | 1 => (1, None),
        n => match crate::gpu::offscreen::check_msaa(renderer.context(), format, n) {
            Ok(()) => (n, None),
            Err(e) => (
                1,
                Some(format!("{e}; the viewer draws one sample per pixel")),
            ),
        },
    };
    if prepared.as_ref().is_some_and(|p| p.samples != samples) {
        *prepared = None;
    }
    match prepared {
        None => {
            let mut p = renderer.prepare_with_samples(scene, format, samples)?;
            // Prepared with the scene's own values: only the exposure is
            // the viewer's.
            p.display_scale = display_scale;
            renderer.update_view(&mut p, scene);
            if verbose {
                eprintln!("shader: {}", p.key.describe());
            }
            *prepared = Some(p);
        }
        Some(p) if !changes.is_empty() && !changes.view_only() => {
            p.display_scale = display_scale;
            if let Err(e) = renderer.apply(p, scene, changes) {
                return Ok(Some(e.to_string()));
            }
        }
        Some(p) if changes.view || p.display_scale != display_scale => {
            p.display_scale = display_scale;
            renderer.update_view(p, scene);
        }
        Some(_) => refused = None,
    }
    Ok(refused)
}

impl ApplicationHandler<Wake> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none()
            && let Err(e) = self.init(event_loop)
        {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let (Some(window), Some(gfx)) = (self.window.clone(), self.gfx.as_mut()) else {
            return;
        };
        let response = gfx.egui_state.on_window_event(&window, &event);
        match &event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                let ctx = gfx.renderer.context();
                gfx.surface.resize(ctx, size.width, size.height);
                self.state.changes.mark(Change::View);
            }
            WindowEvent::DroppedFile(path) => self.state.drop_file(path.clone()),
            WindowEvent::RedrawRequested => {
                // Drawn now whatever asked (the schedule, or the system:
                // an exposed window).
                if let Some(gfx) = self.gfx.as_mut() {
                    let ctx = gfx.renderer.context();
                    let vsync = matches!(
                        gfx.surface.config.present_mode,
                        wgpu::PresentMode::AutoVsync
                    );
                    if vsync != self.state.view.vsync {
                        gfx.surface.set_vsync(ctx, self.state.view.vsync);
                    }
                }
                if let Err(e) = self.frame(event_loop) {
                    self.fail(event_loop, e);
                }
                return;
            }
            _ => {}
        }
        let acted = !response.consumed && self.on_view_input(&event);
        let changed = matches!(
            event,
            WindowEvent::Resized(_)
                | WindowEvent::DroppedFile(_)
                | WindowEvent::ScaleFactorChanged { .. }
        );
        if response.repaint || acted || changed {
            self.pacing.request(Instant::now(), Duration::ZERO);
        }
    }

    fn user_event(&mut self, _event_loop: &ActiveEventLoop, wake: Wake) {
        let Wake::Repaint { delay, pass } = wake;
        let Some(gfx) = &self.gfx else {
            return;
        };
        // A request made during a pass that has ended was in that pass's
        // `repaint_delay` already.
        if pass >= gfx.egui_state.egui_ctx().cumulative_pass_nr() {
            self.pacing.request(Instant::now(), delay);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(window) = self.window.clone() else {
            return;
        };
        let now = Instant::now();
        if !self.pacing.continuous()
            && let Some(outcome) = self.pacing.idle_exit(now, self.state.busy())
        {
            match outcome {
                Ok(report) => {
                    println!("{report}");
                    event_loop.exit();
                }
                Err(problem) => self.fail(event_loop, Error::Gpu(problem)),
            }
            return;
        }
        self.check_reload();
        if self.state.replace.is_some() {
            self.pacing.request(now, Duration::ZERO);
        }
        if self.pacing.due(now) {
            window.request_redraw();
            event_loop.set_control_flow(ControlFlow::Wait);
        } else {
            let check_at = self.last_reload_check + RELOAD_CHECK;
            event_loop.set_control_flow(ControlFlow::WaitUntil(self.pacing.wake_at(check_at)));
        }
    }
}
