//! One timed render pass with a shader of the bench's choosing, on the
//! renderer's device and over the renderer's vertex stream.
//!
//! The floors (an unlit pass, a hand-written Lambert shader) and the
//! uber-shader comparison need pipelines the renderer does not build. The
//! harness asks the renderer for them: its scene pipeline with another
//! shader ([`GpuRenderer::pipeline_with_shader`]), over its own vertex
//! stream and bind group ([`GpuRenderer::scene_draw`]), drawn by its scene
//! pass and read back by its readback, and timed with the same GPU
//! timestamp queries around the pass, so that the only difference between
//! two measurements is the shader. Shadows are not drawn here: the
//! harness measures the scene pass alone.

use crate::frame::Frame;
use crate::gpu::draw::{self, SceneDraw};
use crate::gpu::formats::COLOR_FORMAT;
use crate::gpu::offscreen::render_target;
use crate::gpu::readback::{PassTimestamps, Readback};
use crate::gpu::shader_gen::{self, ShaderKey};
use crate::gpu::timing::Clock;
use crate::gpu::{DEPTH_FORMAT, FrameTarget, GpuContext, GpuRenderer};
use crate::scene::Scene;
use crate::{Error, Result};
use std::time::Instant;

/// Which vertex attributes a harness shader reads (the stream always has
/// the scene's full layout; unread attributes are skipped by the stride).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Inputs {
    /// `@location(0)` position only.
    Position,
    /// Position and normal (locations 0–1).
    PositionNormal,
    /// Everything the scene's layout has (a generated shader).
    All,
}

impl Inputs {
    /// The shader locations read: those below this (`None`: all).
    fn locations(self) -> Option<u32> {
        match self {
            Inputs::Position => Some(1),
            Inputs::PositionNormal => Some(2),
            Inputs::All => None,
        }
    }
}

/// A shader for the harness: WGSL with `vs_main` / `fs_main` over the
/// bindings of `shaders/common.wgsl`, and the key whose variant indices
/// the material buffer uses.
pub struct HarnessShader {
    pub label: String,
    pub wgsl: String,
    pub inputs: Inputs,
    pub key: ShaderKey,
}

impl HarnessShader {
    /// The scene-specialized shader the renderer would build for `scene`
    /// (without shadows), or any other key's shader (the uber shader).
    pub fn generated(label: &str, key: ShaderKey) -> Self {
        HarnessShader {
            label: label.into(),
            wgsl: shader_gen::compose(&key),
            inputs: Inputs::All,
            key,
        }
    }
}

/// A pass ready to draw and time repeatedly on the device it was built
/// on (passed to each call, so the renderer that owns the device can
/// render in between).
pub struct Harness {
    pipeline: wgpu::RenderPipeline,
    draw: SceneDraw,
    color: wgpu::Texture,
    depth: wgpu::Texture,
    width: u32,
    height: u32,
    /// Wall time of shader module + pipeline creation (compilation).
    pub compile_ms: f64,
}

impl Harness {
    /// Uploads `scene` and compiles `shader` for it.
    pub fn new(renderer: &mut GpuRenderer, scene: &Scene, shader: &HarnessShader) -> Result<Self> {
        shader_gen::validate(&shader.wgsl)
            .map_err(|e| Error::Gpu(format!("bench shader `{}` is invalid: {e}", shader.label)))?;
        let draw = renderer.scene_draw(scene, &shader.key);
        let start = Instant::now();
        let pipeline = renderer.pipeline_with_shader(
            &shader.label,
            &shader.wgsl,
            &draw,
            shader.inputs.locations(),
        );
        // Pipeline creation is lazy on some drivers: one draw makes sure the
        // compile is inside `compile_ms`.
        let device = &renderer.context().device;
        let target = |label, format, usage| {
            render_target(device, label, (scene.width, scene.height), format, usage, 1)
        };
        let color = target(
            "bench radiance",
            COLOR_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = target(
            "bench depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let mut harness = Harness {
            pipeline,
            draw,
            color,
            depth,
            width: scene.width,
            height: scene.height,
            compile_ms: 0.0,
        };
        harness.time_once(renderer.context())?;
        harness.compile_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(harness)
    }

    /// Records the scene pass into `encoder`, with timestamps 0 and 1
    /// around it when `queries` is given.
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, queries: Option<&wgpu::QuerySet>) {
        let color_view = self.color.create_view(&Default::default());
        let depth_view = self.depth.create_view(&Default::default());
        let mut pass = draw::begin_scene_pass(
            encoder,
            &FrameTarget {
                color: &color_view,
                resolve: None,
                depth: &depth_view,
                viewport: None,
                clip: None,
                timestamps: queries,
            },
        );
        self.draw.draw_with(&mut pass, &self.pipeline);
    }

    /// Draws once and returns the pass time in milliseconds: GPU
    /// timestamps where the adapter has them, else the wall time of
    /// submit-and-wait.
    pub fn time_once(&self, ctx: &GpuContext) -> Result<(f64, Clock)> {
        let device = &ctx.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        if !ctx.timestamps {
            self.encode(&mut encoder, None);
            let start = Instant::now();
            ctx.queue.submit([encoder.finish()]);
            device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|e| Error::Gpu(format!("waiting for the GPU failed: {e}")))?;
            return Ok((start.elapsed().as_secs_f64() * 1e3, Clock::Wall));
        }
        let queries = PassTimestamps::scene_pass(device);
        self.encode(&mut encoder, Some(&queries.set));
        queries.resolve(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        let ns = queries.read_nanos(ctx)?[0];
        Ok((ns * 1e-6, Clock::GpuTimestamp))
    }

    /// Draws once more and reads the radiance back (to check that a floor
    /// shader draws the image it claims to).
    pub fn frame(&self, ctx: &GpuContext) -> Result<Frame> {
        let readback = Readback::new(&ctx.device, self.width, self.height);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode(&mut encoder, None);
        readback.copy_from(&mut encoder, &self.color);
        ctx.queue.submit([encoder.finish()]);
        readback.read(&ctx.device)
    }
}
