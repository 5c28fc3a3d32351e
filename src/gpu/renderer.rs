//! [`GpuRenderer`]: the device and its [`PipelineCache`], and the one
//! place that hands them to each concern: [`PreparedScene`] (upload,
//! update, encode a frame), [`super::offscreen`] (the one-shot render),
//! and, for the bench, a [`SceneDraw`] and a pipeline with another shader.

use super::context::GpuContext;
use super::draw::{self, FrameTarget, SceneDraw};
use super::formats::COLOR_FORMAT;
use super::geometry::{Meshes, StreamPlan};
use super::layout::{GpuGlobals, GpuLight};
use super::offscreen;
use super::pipelines::PipelineCache;
use super::prepared::{Drawn, PreparedScene};
use super::shader_gen::ShaderKey;
use super::timing::Timings;
use super::upload::GpuGeometry;
use crate::Result;
use crate::frame::Frame;
use crate::scene::Scene;

/// The timestamp queries of a frame, where the viewer finds them.
pub use super::readback::PassTimestamps;

/// A renderer bound to one device, caching every pipeline it compiles so
/// re-rendering with new parameter values never recompiles.
pub struct GpuRenderer {
    ctx: GpuContext,
    pipelines: PipelineCache,
    /// Whether shadow-map coordinates may be computed per vertex
    /// ([`ShaderKey::shadow_coords_per_vertex`]); default true.
    pub vertex_shadow_coords: bool,
    /// Whether each shadow-map layer draws only the casters that reach
    /// it ([`PreparedScene::cull_shadow_casters`]); default true.
    pub cull_shadow_casters: bool,
}

impl GpuRenderer {
    /// A renderer on `ctx`.
    pub fn new(ctx: GpuContext) -> Self {
        GpuRenderer {
            pipelines: PipelineCache::new(&ctx.device),
            ctx,
            vertex_shadow_coords: true,
            cull_shadow_casters: true,
        }
    }

    /// Draws scenes of several BRDF variants with one pipeline that
    /// switches per material (`true`, one compilation: a one-frame render)
    /// or one specialized pipeline per variant (`false`, the default:
    /// faster frames). See [`PipelineCache::specializations`].
    pub fn set_one_pipeline(&mut self, on: bool) {
        self.pipelines.one_pipeline = on;
    }

    /// The device this renderer draws with.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// Renders `scene` offscreen, returning the frame and the time of each
    /// step ([`offscreen::render`]).
    pub fn render(&mut self, scene: &Scene) -> Result<(Frame, Timings)> {
        offscreen::render(
            &self.ctx,
            &mut self.pipelines,
            self.vertex_shadow_coords,
            self.cull_shadow_casters,
            scene,
        )
    }

    /// [`GpuRenderer::render`] for a GPU-only run: `scene`'s meshes are
    /// freed as they are uploaded
    /// ([`offscreen::render_releasing_meshes`]), so the `f64` meshes and
    /// the GPU buffers are not whole in memory at once.
    pub fn render_releasing_meshes(&mut self, scene: &mut Scene) -> Result<(Frame, Timings)> {
        offscreen::render_releasing_meshes(
            &self.ctx,
            &mut self.pipelines,
            self.vertex_shadow_coords,
            self.cull_shadow_casters,
            scene,
        )
    }

    /// Refuses a target the device cannot hold.
    pub fn check_target_size(&self, width: u32, height: u32) -> Result<()> {
        offscreen::check_target_size(&self.ctx, width, height)
    }

    /// Uploads `scene` for drawing into targets of `format`
    /// (`Rgba32Float`: linear radiance; an 8-bit format: display).
    pub fn prepare(&mut self, scene: &Scene, format: wgpu::TextureFormat) -> Result<PreparedScene> {
        self.prepare_with_samples(scene, format, 1)
    }

    /// [`GpuRenderer::prepare`] for targets of `samples` samples per pixel.
    pub fn prepare_with_samples(
        &mut self,
        scene: &Scene,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<PreparedScene> {
        let mut prepared = PreparedScene::new(
            &self.ctx,
            &mut self.pipelines,
            self.vertex_shadow_coords,
            scene,
            format,
            samples,
        )?;
        prepared.cull_shadow_casters = self.cull_shadow_casters;
        Ok(prepared)
    }

    /// Brings `prepared` up to date with `scene` ([`PreparedScene::update`]).
    pub fn update(&mut self, prepared: &mut PreparedScene, scene: &Scene) -> Result<()> {
        prepared.update(
            &self.ctx,
            &mut self.pipelines,
            self.vertex_shadow_coords,
            scene,
        )
    }

    /// Brings `prepared` up to date with `scene` after `changes`, writing
    /// only what they reach ([`PreparedScene::apply`]).
    pub fn apply(
        &mut self,
        prepared: &mut PreparedScene,
        scene: &Scene,
        changes: &crate::scene::change::Changes,
    ) -> Result<()> {
        prepared.apply(
            &self.ctx,
            &mut self.pipelines,
            self.vertex_shadow_coords,
            scene,
            changes,
        )
    }

    /// Writes only the per-view values of `scene`
    /// ([`PreparedScene::update_view`]).
    pub fn update_view(&self, prepared: &mut PreparedScene, scene: &Scene) {
        prepared.update_view(&self.ctx, scene);
    }

    /// Records the shadow passes (if stale) and the scene pass of
    /// `prepared` into `encoder` ([`PreparedScene::encode`]).
    pub fn encode(
        &mut self,
        prepared: &mut PreparedScene,
        encoder: &mut wgpu::CommandEncoder,
        target: &FrameTarget,
    ) -> Drawn {
        prepared.encode(encoder, target)
    }

    /// For the bench: `scene`'s vertex stream and scene bind group laid
    /// out for `key` (its attributes, its variant indices, its arrays),
    /// without shadows, as the renderer uploads them.
    pub fn scene_draw(&mut self, scene: &Scene, key: &ShaderKey) -> SceneDraw {
        let stream = StreamPlan::new(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
        let geometry = GpuGeometry::upload(
            &self.ctx.device,
            &self.ctx.queue,
            stream,
            Meshes::Keep(&scene.meshes),
        );
        let lights: Vec<GpuLight> = scene.lights.iter().map(GpuLight::from).collect();
        SceneDraw::new(
            &self.ctx.device,
            self.pipelines.scene_layouts(key.arrays),
            geometry,
            key.arrays,
            &GpuGlobals::new(scene),
            draw::MaterialData {
                records: &draw::gpu_materials(scene, key),
                measured_tables: &draw::measured_tables(scene).data,
            },
            &lights,
        )
    }

    /// For the bench: the renderer's pipeline for `draw` into its radiance
    /// target (`Rgba32Float`, one sample, no shadows) with the shader
    /// `wgsl` (validated by the caller) reading the attributes at
    /// locations below `locations` (`None`: all). Compiled anew on each
    /// call ([`PipelineCache::with_shader`]).
    pub fn pipeline_with_shader(
        &mut self,
        label: &str,
        wgsl: &str,
        draw: &SceneDraw,
        locations: Option<u32>,
    ) -> wgpu::RenderPipeline {
        self.pipelines.with_shader(
            label,
            wgsl,
            draw.arrays(),
            draw.layout,
            locations,
            COLOR_FORMAT,
        )
    }
}
