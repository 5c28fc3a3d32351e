//! A scene uploaded once and drawn many times.
//!
//! `gonio render` draws a scene once; the viewer and the bench draw it
//! every frame. Both go through [`PreparedScene`]: the vertex stream,
//! the parameter buffers and the shadow maps live on the GPU between
//! frames, and [`PreparedScene::update`] rewrites only what a change
//! touches (a camera move writes 144 bytes of globals; a new roughness
//! writes the material buffer; a light change re-plans and re-renders the
//! shadow maps once). The shadow maps are drawn only when they are stale,
//! so orbiting the camera costs one scene pass per frame.
//!
//! The scene's compiled code comes from the [`PipelineCache`] it is
//! given; the stream and the bind group are a [`SceneDraw`].

use super::context::GpuContext;
use super::draw::{self, FrameTarget, SceneDraw};
use super::environment::GpuEnvironment;
use super::formats::TRANSMISSION_FORMAT;
use super::geometry::{Batch, GeometryData, Meshes, StreamPlan};
use super::layout::{GpuGlobals, GpuLight};
use super::pipelines::PipelineCache;
use super::scene_parts::{self, PartBreak, PassPosition, ScenePart};
use super::shader_gen::ShaderKey;
use super::shadow_culling::{self, LayerCasters};
use super::shadow_maps::{self, ShadowMaps};
use super::shadow_masks::ShadowMasks;
use super::shadows::ShadowPlan;
use super::transmission::{self, TransmissionImages};
use super::transmission_back_faces::BackFacePass;
use super::upload::GpuGeometry;
use super::upload_tally::UploadTally;
use crate::scene::Scene;
use crate::{Error, Result};

mod targeted;

/// A scene's GPU resources, ready to draw into a colour target of
/// `format`.
pub struct PreparedScene {
    /// The features compiled for this scene.
    pub key: ShaderKey,
    /// The colour target format the pipeline writes (decides
    /// [`super::shader_gen::Output`]).
    pub format: wgpu::TextureFormat,
    /// `2^exposure`, applied by display targets only.
    pub display_scale: f32,
    /// Samples per pixel of the targets it draws into.
    pub samples: u32,
    /// Triangles drawn per scene pass.
    pub triangles: u64,
    /// Bytes of vertex and index data on the GPU.
    pub geometry_bytes: u64,
    /// The stream, its batches and the scene bind group.
    draw: SceneDraw,
    /// For each batch, the variant it is drawn with, whether it blends,
    /// and that pipeline (resolved when the scene changes, so a frame
    /// looks nothing up).
    batch_pipelines: Vec<BatchPipeline>,
    /// Alpha BLEND batches (index into the batches) with the centre of
    /// their mesh's bounding box, which orders them.
    blend_centers: Vec<(usize, glam::DVec3)>,
    /// Transmissive batches drawn by the transmission pass, with their
    /// centres (empty unless the key draws transmission).
    transmissive_centers: Vec<(usize, glam::DVec3)>,
    /// The order batches are drawn in: the others in stream order, then
    /// the transmissive ones, then the BLEND ones, each back to front from
    /// the camera ([`draw_order`]).
    order: Vec<usize>,
    /// For each batch, the transmission layer it reads (transmissive
    /// batches only; [`crate::scene::TransmissionSettings::layer_of`]).
    batch_layers: Vec<Option<usize>>,
    /// The transmission images and the pipelines that draw them (`None`
    /// unless the key draws transmission).
    transmission: Option<TransmissionDraw>,
    plan: ShadowPlan,
    shadows: Option<ShadowMaps>,
    /// The masked shadow pass of alpha MASK casters (none without them).
    shadow_masks: Option<ShadowMasks>,
    /// The world bounding box of each object of the stream (for culling
    /// the casters per shadow-map layer).
    caster_bounds: Vec<(glam::DVec3, glam::DVec3)>,
    /// Each shadow-map layer draws only the casters whose boxes reach its
    /// frustum (src/gpu/shadow_culling.rs); default true. Off draws every
    /// caster into every layer: the same maps, for tests and A/B timing.
    pub cull_shadow_casters: bool,
    /// Per shadow-map layer, the objects it leaves out as markers of its
    /// light (`shadow_culling::markers`); empty for none.
    shadow_markers: Vec<Vec<u32>>,
    /// The shadow maps must be drawn before the next scene pass.
    shadows_stale: bool,
    /// The environment map, its uniform and the background pipeline.
    environment: Option<GpuEnvironment>,
    /// The materials' textures (group 2), when the scene has any.
    textures: Option<super::textures::SceneTextures>,
    /// What was sent to the GPU since the last [`Self::take_uploads`].
    uploads: UploadTally,
}

/// The scene a [`PreparedScene`] is built from, and whether its meshes
/// may be freed as they are uploaded.
enum Source<'a> {
    Keep(&'a Scene),
    Release(&'a mut Scene),
}

impl Source<'_> {
    fn scene(&self) -> &Scene {
        match self {
            Source::Keep(s) => s,
            Source::Release(s) => s,
        }
    }
}

/// A per-object batch (index into the batches) and the centre of its
/// mesh's bounding box, which orders it.
type ObjectCenter = (usize, glam::DVec3);

/// A batch's pipeline: the variant it is specialized to (`None`: the
/// key's one or all), whether it blends, the pipeline.
type BatchPipeline = (Option<u32>, bool, wgpu::RenderPipeline);

/// What draws the transmission images (src/gpu/transmission.rs): the
/// images, each batch's pipeline into their format, the background's.
struct TransmissionDraw {
    images: TransmissionImages,
    pipelines: Vec<BatchPipeline>,
    background: Option<wgpu::RenderPipeline>,
    settings: crate::scene::TransmissionSettings,
    /// Group 4's layout, for new images at a new size.
    group_layout: wgpu::BindGroupLayout,
    /// With the traced exit: the back-face pass and the batches it draws
    /// (the transmissive volumes', `thickness > 0`).
    back_faces: Option<(BackFacePass, Vec<usize>)>,
}

/// The colour target a [`PreparedScene`] draws into.
struct Target {
    format: wgpu::TextureFormat,
    samples: u32,
}

/// What one [`PreparedScene::encode`] drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Drawn {
    /// Shadow-map layers rendered (0 when the maps were current).
    pub shadow_layers: usize,
    /// Object draws the caster culling removed from those layers.
    pub shadow_draws_culled: usize,
    /// Object draws those layers would make without culling (objects ×
    /// layers).
    pub shadow_draws_total: usize,
}

impl PreparedScene {
    /// Uploads `scene` for drawing into targets of `format` (`Rgba32Float`:
    /// linear radiance; an 8-bit format: display) with `samples` samples
    /// per pixel, compiling what it needs into `cache`.
    /// `vertex_shadow_coords`: see [`ShaderKey::shadow_coords_per_vertex`].
    pub fn new(
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &Scene,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<Self> {
        let target = Target { format, samples };
        Self::build(
            ctx,
            cache,
            vertex_shadow_coords,
            Source::Keep(scene),
            target,
        )
    }

    /// [`PreparedScene::new`] for a GPU-only render: `scene`'s meshes are
    /// freed as their stream is uploaded ([`Meshes::Release`]), so the
    /// `f64` meshes and the buffers are not in memory whole at once. The
    /// meshes stay in `scene` with their material and name, their arrays
    /// empty: the CPU reference cannot render it afterwards, and
    /// [`PreparedScene::update`] needs the meshes back.
    pub fn new_releasing_meshes(
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &mut Scene,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<Self> {
        let target = Target { format, samples };
        Self::build(
            ctx,
            cache,
            vertex_shadow_coords,
            Source::Release(scene),
            target,
        )
    }

    /// What both constructors do: everything that reads the meshes'
    /// arrays first, then the upload (which may free them), then what
    /// reads only materials, lights and the camera.
    fn build(
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        mut source: Source<'_>,
        Target { format, samples }: Target,
    ) -> Result<Self> {
        let scene = source.scene();
        check_drawable(scene)?;
        let (key, plan) = plan(&ctx.device, vertex_shadow_coords, scene)?;
        check_geometry_size(&ctx.device, scene, &key)?;
        if key.materials.alpha_blend && !ctx.blendable(format) {
            return Err(Error::Gpu(format!(
                "the scene has alpha BLEND materials, and the GPU adapter `{}` cannot blend into {format:?} targets; use another backend (unset WGPU_BACKEND for Vulkan)",
                ctx.adapter_info.name
            )));
        }
        let stream = StreamPlan::new(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
        cache.compile_scene(&key, stream.layout, format, samples)?;
        if key.materials.layer_transmission {
            transmission::check_limits(&ctx.device)?;
            cache.compile_scene(&key, stream.layout, TRANSMISSION_FORMAT, 1)?;
        }
        let arrays = key.arrays;
        let materials = draw::gpu_materials(scene, &key);
        let measured = draw::measured_tables(scene);
        check_measured_size(&ctx.device, &measured.data)?;
        let lights = gpu_lights(scene, &plan);
        let globals = GpuGlobals::new(scene);
        let blend_centers = object_centers(&stream.batches, scene, |m| {
            m.alpha_mode == crate::material::AlphaMode::Blend
        });
        let transmissive_centers = if key.materials.layer_transmission {
            object_centers(&stream.batches, scene, |m| {
                m.transmits_specularly() && m.alpha_mode != crate::material::AlphaMode::Blend
            })
        } else {
            Vec::new()
        };
        let volume_batches: Vec<usize> = if key.materials.transmission_exit_traced {
            object_centers(&stream.batches, scene, |m| {
                m.transmits_specularly()
                    && m.layers.thickness > 0.0
                    && m.alpha_mode != crate::material::AlphaMode::Blend
            })
            .into_iter()
            .map(|(b, _)| b)
            .collect()
        } else {
            Vec::new()
        };
        let triangles = scene.triangle_count() as u64;
        let geometry = match &mut source {
            Source::Keep(scene) => {
                GpuGeometry::upload(&ctx.device, &ctx.queue, stream, Meshes::Keep(&scene.meshes))
            }
            Source::Release(scene) => GpuGeometry::upload(
                &ctx.device,
                &ctx.queue,
                stream,
                Meshes::Release(&mut scene.meshes),
            ),
        };
        let scene = source.scene();
        let draw = SceneDraw::new(
            &ctx.device,
            cache.scene_layouts(arrays),
            geometry,
            arrays,
            &globals,
            draw::MaterialData {
                records: &materials,
                measured_tables: &measured.data,
            },
            &lights,
        );
        let shadows = ShadowMaps::new(ctx, cache, &plan, arrays, draw.layout.stride());
        let batch_pipelines = batch_pipelines(cache, &key, format, samples, &materials, &draw);
        let caster_bounds = if shadows.is_some() {
            shadow_culling::object_bounds(draw.objects())
        } else {
            Vec::new()
        };
        let shadow_markers = shadow_culling::markers(&plan, scene, draw.objects());
        let (order, batch_layers) = draw_order(
            draw.batches().len(),
            (&transmissive_centers, &blend_centers),
            scene,
        );
        let environment = prepare_environment(ctx, cache, &key, scene, format, samples)?;
        let transmission = if key.materials.layer_transmission {
            let background = match &environment {
                Some(_) => Some(cache.background(arrays, TRANSMISSION_FORMAT, 1, key.tone_map)?),
                None => None,
            };
            let traced = key.materials.transmission_exit_traced;
            let group_layout = cache.transmission_group_layout(traced).clone();
            Some(TransmissionDraw {
                images: TransmissionImages::new(
                    &ctx.device,
                    &ctx.queue,
                    &group_layout,
                    (scene.width, scene.height),
                    (scene.transmission.layers, traced),
                ),
                pipelines: self::batch_pipelines(
                    cache,
                    &key,
                    TRANSMISSION_FORMAT,
                    1,
                    &materials,
                    &draw,
                ),
                background,
                settings: scene.transmission,
                group_layout,
                back_faces: traced.then(|| {
                    let pass = BackFacePass::new(&ctx.device, draw.layout, draw.globals_buffer());
                    (pass, volume_batches)
                }),
            })
        } else {
            None
        };
        let textures = if key.materials.texture_slots > 0 {
            let layout = cache.texture_group(key.materials.texture_bindings);
            Some(super::textures::SceneTextures::new(ctx, layout, scene)?)
        } else {
            None
        };
        let shadow_masks = shadows.as_ref().and_then(|_| {
            ShadowMasks::new(
                &ctx.device,
                &ctx.queue,
                cache.shadow_pass_group_layout(),
                draw.layout,
                scene,
                textures.as_ref(),
            )
        });
        let mut uploads = UploadTally::default();
        uploads.geometry.add(draw.geometry_bytes);
        uploads.globals.add(size_of::<GpuGlobals>() as u64);
        count_parameters(
            &mut uploads,
            ctx,
            arrays,
            &materials,
            &measured.data,
            &lights,
        );
        if let Some(t) = &textures {
            uploads.textures.add(t.bytes);
            count_slots(&mut uploads, scene);
        }
        if environment.is_some() {
            count_environment(&mut uploads, scene);
        }
        Ok(PreparedScene {
            key,
            format,
            display_scale: 1.0,
            samples,
            triangles,
            geometry_bytes: draw.geometry_bytes,
            draw,
            batch_pipelines,
            blend_centers,
            transmissive_centers,
            order,
            batch_layers,
            transmission,
            shadows_stale: shadows.is_some(),
            plan,
            shadows,
            shadow_masks,
            caster_bounds,
            cull_shadow_casters: true,
            shadow_markers,
            environment,
            textures,
            uploads,
        })
    }

    /// Brings this scene up to date with `scene`, which must have the same
    /// meshes as the scene it was prepared from (reload the file: prepare
    /// anew). Writes only what changed; a change of the shader features
    /// selects (or compiles, once) another cached pipeline; a change of
    /// the vertex stream (shading mode, tangents) rebuilds it.
    pub fn update(
        &mut self,
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &Scene,
    ) -> Result<()> {
        check_drawable(scene)?;
        let (key, plan) = plan(&ctx.device, vertex_shadow_coords, scene)?;
        let layout = self.draw.layout;
        // Textures: their bind groups hold each material's slots, made
        // with the materials, so a textured scene is prepared anew.
        if key.shading != self.key.shading
            || key.needs_tangents() != layout.tangents
            || key.shadow_coords_per_vertex() != layout.face_normal
            || key.materials.texture_slots > 0
            || self.key.materials.texture_slots > 0
            || key.materials.alpha_blend
            || self.key.materials.alpha_blend
            || key.materials.layer_transmission
            || self.key.materials.layer_transmission
        {
            let (display_scale, cull) = (self.display_scale, self.cull_shadow_casters);
            let uploads = self.uploads;
            *self = Self::new(
                ctx,
                cache,
                vertex_shadow_coords,
                scene,
                self.format,
                self.samples,
            )?;
            self.display_scale = display_scale;
            self.cull_shadow_casters = cull;
            self.uploads += uploads;
            return Ok(());
        }
        cache.compile_scene(&key, layout, self.format, self.samples)?;
        // The background's module has the tone map compiled in.
        if !self.environment.as_ref().is_some_and(|e| e.holds(scene))
            || key.tone_map != self.key.tone_map
        {
            self.environment =
                prepare_environment(ctx, cache, &key, scene, self.format, self.samples)?;
            if self.environment.is_some() {
                count_environment(&mut self.uploads, scene);
            }
        }
        self.update_view(ctx, scene);

        let arrays = key.arrays;
        let materials = draw::gpu_materials(scene, &key);
        let measured = draw::measured_tables(scene);
        let lights = gpu_lights(scene, &plan);
        self.draw.write_parameters(
            &ctx.device,
            &ctx.queue,
            cache.scene_layouts(arrays),
            arrays,
            draw::MaterialData {
                records: &materials,
                measured_tables: &measured.data,
            },
            &lights,
        );
        count_parameters(
            &mut self.uploads,
            ctx,
            arrays,
            &materials,
            &measured.data,
            &lights,
        );
        let masks_changed = self.shadow_masks.as_ref().is_some_and(|m| {
            m.records() != super::shadow_masks::records(&scene.effective_materials())
        }) || (self.shadows.is_some()
            && self.shadow_masks.is_none()
            && scene.meshes.iter().any(|mesh| {
                matches!(
                    scene.materials[mesh.material].alpha_mode,
                    crate::material::AlphaMode::Mask { .. }
                )
            }));
        self.refresh_shadows(ctx, cache, scene, plan, arrays, masks_changed);
        self.refresh_markers(scene);
        self.batch_pipelines = batch_pipelines(
            cache,
            &key,
            self.format,
            self.samples,
            &materials,
            &self.draw,
        );
        self.key = key;
        Ok(())
    }

    /// Brings the shadow maps up to `plan` (bound as `arrays`): a moved
    /// light with maps of the same shape rewrites their views (a light
    /// dragged or spinning in the viewer); anything else that changes the
    /// plan, or the alpha MASK casters (`masks_changed`), makes new maps.
    /// Either way they are drawn again; a change that leaves the plan as
    /// it was (a light's colour) does not touch them.
    fn refresh_shadows(
        &mut self,
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        scene: &Scene,
        plan: ShadowPlan,
        arrays: super::bindings::UniformArrays,
        masks_changed: bool,
    ) {
        let layout = self.draw.layout;
        let reusable = self
            .shadows
            .as_ref()
            .filter(|s| !masks_changed && s.holds(&plan, arrays, layout.stride()));
        if let Some(shadows) = reusable {
            if plan != self.plan {
                shadows.write_plan(&ctx.queue, &plan);
                count_shadow_views(&mut self.uploads, &plan, arrays);
                self.shadows_stale = true;
                self.plan = plan;
            }
        } else if plan != self.plan || masks_changed || arrays != self.key.arrays {
            self.shadows = ShadowMaps::new(ctx, cache, &plan, arrays, layout.stride());
            self.shadow_masks = self.shadows.as_ref().and_then(|_| {
                ShadowMasks::new(
                    &ctx.device,
                    &ctx.queue,
                    cache.shadow_pass_group_layout(),
                    layout,
                    scene,
                    self.textures.as_ref(),
                )
            });
            self.shadows_stale = self.shadows.is_some();
            if self.shadows.is_some() && self.caster_bounds.is_empty() {
                self.caster_bounds = shadow_culling::object_bounds(self.draw.objects());
            }
            self.plan = plan;
        }
    }

    /// An edit can make or unmake a marker (a light moved into a lamp, a
    /// material's emission): its light's layers are drawn again.
    fn refresh_markers(&mut self, scene: &Scene) {
        let markers = shadow_culling::markers(&self.plan, scene, self.draw.objects());
        if markers != self.shadow_markers {
            self.shadow_markers = markers;
            self.shadows_stale = self.shadows.is_some();
        }
    }

    /// Gives this scene's shadow-map array back to `ctx`'s texture pool
    /// for the next one-shot render (src/gpu/texture_pool.rs); call it
    /// after the last submission that draws this scene.
    pub fn release(self, ctx: &GpuContext) {
        if let Some(shadows) = self.shadows {
            shadows.release(ctx);
        }
    }

    /// Writes only the per-view values of `scene` (camera, image size,
    /// ambient, environment, exposure): what a camera move changes. The
    /// shadow maps do not depend on the camera, so they stay.
    pub fn update_view(&mut self, ctx: &GpuContext, scene: &Scene) {
        (self.order, self.batch_layers) = draw_order(
            self.draw.batches().len(),
            (&self.transmissive_centers, &self.blend_centers),
            scene,
        );
        if let Some(t) = &mut self.transmission
            && t.images.size != (scene.width.max(1), scene.height.max(1))
        {
            t.images = TransmissionImages::new(
                &ctx.device,
                &ctx.queue,
                &t.group_layout,
                (scene.width, scene.height),
                (t.settings.layers, t.back_faces.is_some()),
            );
        }
        let mut globals = GpuGlobals::new(scene);
        globals.display_scale = self.display_scale;
        self.draw.write_globals(&ctx.queue, &globals);
        self.uploads.globals.add(size_of::<GpuGlobals>() as u64);
        if let Some(environment) = &self.environment {
            environment.write(&ctx.queue, scene);
            self.uploads
                .globals
                .add(size_of::<super::environment::GpuEnvironmentUniform>() as u64);
        }
    }

    /// What was sent to the GPU since the last call (or since it was
    /// prepared), by kind; the count starts again at zero.
    pub fn take_uploads(&mut self) -> UploadTally {
        std::mem::take(&mut self.uploads)
    }

    /// Records the shadow passes (if the maps are stale) and the scene
    /// pass into `encoder`. The scene pass clears the whole target to
    /// transparent black (coverage 0) and draws into the viewport.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, target: &FrameTarget) -> Drawn {
        let drawn = self.encode_shadows(encoder, target.timestamps, None);
        self.encode_transmission(encoder);
        let batches = self.draw.batches();
        let whole = self.order.iter().map(|&b| (b, batches[b].range.clone()));
        self.encode_scene_part(encoder, target, PassPosition::WHOLE, whole);
        drawn
    }

    /// The scene pass split into parts of at most `max_triangles`
    /// triangles (src/gpu/scene_parts.rs), for
    /// [`Self::encode_shadows`] and [`Self::encode_scene_part`] to record
    /// one submission each; one part when the scene has no more.
    pub fn scene_parts(&self, max_triangles: u64) -> Vec<ScenePart> {
        scene_parts::split(&self.order, self.draw.batches(), max_triangles)
    }

    /// Records the shadow passes into `encoder` if the maps are stale
    /// (timestamps 2 and 3 around them when `timestamps` is given), split
    /// into submitted parts by `parts` (src/gpu/scene_parts.rs).
    pub fn encode_shadows(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<&wgpu::QuerySet>,
        parts: Option<PartBreak<'_>>,
    ) -> Drawn {
        let mut drawn = Drawn::default();
        if let (Some(shadows), true) = (&self.shadows, self.shadows_stale) {
            let casters =
                (self.cull_shadow_casters || !self.shadow_markers.is_empty()).then(|| {
                    LayerCasters::new(
                        &self.plan,
                        &self.caster_bounds,
                        self.cull_shadow_casters,
                        &self.shadow_markers,
                    )
                });
            drawn.shadow_layers = shadows.encode(
                encoder,
                &self.plan,
                &self.draw,
                (casters.as_ref(), self.shadow_masks.as_ref()),
                timestamps,
                parts,
            );
            drawn.shadow_draws_total = self.plan.layers.len() * self.draw.objects().len();
            drawn.shadow_draws_culled = casters.map_or(0, |c| c.culled);
            self.shadows_stale = false;
            self.uploads.shadow_layers.calls += drawn.shadow_layers as u64;
        }
        drawn
    }

    /// Records the scene pass, or the part of it at `position` drawing
    /// `draws` (batch, range of it; in drawing order), into `encoder`.
    pub fn encode_scene_part(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &FrameTarget,
        position: PassPosition,
        draws: impl IntoIterator<Item = (usize, std::ops::Range<u32>)>,
    ) {
        let mut pass = draw::begin_scene_pass_part(encoder, target, position);
        self.bind_pass_groups(&mut pass);
        self.draw.bind_geometry(&mut pass);
        // Each material's batch with its material bound (src/gpu/bindings.rs)
        // and the pipeline of its BRDF variant (consecutive batches of one
        // variant share the bind).
        // Alpha BLEND batches last, back to front (`order`), each with its
        // blending pipeline.
        // A transmissive batch binds the transmission image of its layer.
        let mut bound = None;
        let background_before = self.background_before();
        for (b, range) in draws {
            let (batch, (variant, blend, pipeline)) =
                (&self.draw.batches()[b], &self.batch_pipelines[b]);
            if background_before == Some((b, range.start)) {
                self.encode_background(&mut pass);
                self.bind_pass_groups(&mut pass);
                bound = None;
            }
            let which = (*variant, *blend);
            if bound != Some(which) {
                pass.set_pipeline(pipeline);
                bound = Some(which);
            }
            if let Some(textures) = &self.textures {
                pass.set_bind_group(2, textures.group(batch.material), &[]);
            }
            if let (Some(t), Some(layer)) = (&self.transmission, self.batch_layers[b]) {
                pass.set_bind_group(transmission::GROUP, t.images.group(layer), &[]);
            }
            self.draw.draw_batch_part(&mut pass, batch, range);
        }
        if position.last && background_before.is_none() {
            self.encode_background(&mut pass);
        }
    }

    /// Binds the groups every draw of the scene pass shares: the shadow
    /// maps, the environment's map (its background is drawn after the
    /// opaque batches) and the first transmission image.
    fn bind_pass_groups(&self, pass: &mut wgpu::RenderPass<'_>) {
        if let Some(shadows) = &self.shadows {
            pass.set_bind_group(1, shadows.scene_group(), &[]);
        }
        if let Some(environment) = &self.environment {
            environment.bind(pass);
        }
        if let Some(t) = &self.transmission {
            pass.set_bind_group(transmission::GROUP, t.images.group(0), &[]);
        }
    }

    /// Where the background goes in the scene pass: before the draw
    /// (batch, first index) of the first alpha-BLEND batch, which blends
    /// over it; `None` without one (then after every batch, in the last
    /// part). Drawn after the opaque batches at the far plane with a
    /// depth test (environment::background_pipeline), it shades only the
    /// pixels they leave (drawn first, it would shade every pixel, the
    /// covered ones in vain: 90 % of DamagedHelmet's 1080p frame is
    /// background).
    fn background_before(&self) -> Option<(usize, u32)> {
        let batches = self.draw.batches();
        self.order
            .iter()
            .find(|&&b| self.batch_pipelines[b].1)
            .map(|&b| (b, batches[b].range.start))
    }

    /// Draws the environment's background, if the scene has a map
    /// (group 0 bound for it; the caller binds its pipeline again).
    fn encode_background(&self, pass: &mut wgpu::RenderPass<'_>) {
        if let Some(environment) = &self.environment {
            self.draw.bind_scene_group(pass, 0);
            environment.encode_background(pass);
        }
    }

    /// Records the transmission images (src/gpu/transmission.rs) if the
    /// scene draws transmission: layer 0 the background and every batch
    /// that neither transmits nor blends, layer `k` the transmissive
    /// batches that read layer `k − 1` over a copy of it; each followed by
    /// its mip chain. With the traced exit, the volumes' back faces
    /// first and the opaque scene's depth kept after layer 0
    /// (src/gpu/transmission_back_faces.rs). Call after the shadow
    /// passes, before the scene pass.
    pub fn encode_transmission(&self, encoder: &mut wgpu::CommandEncoder) {
        let Some(t) = &self.transmission else {
            return;
        };
        let batches = self.draw.batches();
        if let (Some((back_faces, volumes)), Some(exit)) = (&t.back_faces, t.images.exit()) {
            let mut pass = exit.begin(encoder);
            back_faces.bind(&mut pass);
            self.draw.bind_geometry(&mut pass);
            for &b in volumes {
                self.draw
                    .draw_range(&mut pass, batches[b].range.clone(), 0..1);
            }
        }
        for layer in 0..t.images.layer_count() {
            {
                let mut pass = t.images.begin_layer(encoder, layer);
                if let Some(shadows) = &self.shadows {
                    pass.set_bind_group(1, shadows.scene_group(), &[]);
                }
                let reads = match layer {
                    0 => t.images.black_group(),
                    _ => t.images.group(layer - 1),
                };
                pass.set_bind_group(transmission::GROUP, reads, &[]);
                if let Some(environment) = &self.environment {
                    match (&t.background, layer) {
                        (Some(background), 0) => {
                            self.draw.bind_scene_group(&mut pass, 0);
                            environment.encode_background_with(&mut pass, background);
                        }
                        _ => environment.bind(&mut pass),
                    }
                }
                self.draw.bind_geometry(&mut pass);
                for &b in &self.order {
                    let drawn = match layer {
                        0 => self.batch_layers[b].is_none() && !self.batch_pipelines[b].1,
                        _ => self.batch_layers[b] == Some(layer - 1),
                    };
                    if !drawn {
                        continue;
                    }
                    pass.set_pipeline(&t.pipelines[b].2);
                    if let Some(textures) = &self.textures {
                        pass.set_bind_group(2, textures.group(batches[b].material), &[]);
                    }
                    self.draw.draw_batch(&mut pass, &batches[b]);
                }
            }
            if layer == 0 {
                t.images.copy_scene_depth(encoder);
            }
            t.images.encode_mips(encoder, layer);
        }
    }

    /// Shadow-map layers this scene renders when its maps are stale.
    pub fn shadow_layers(&self) -> usize {
        self.plan.layers.len()
    }

    /// Marks the shadow maps stale (the bench re-renders them each frame
    /// to measure their cost).
    pub fn invalidate_shadows(&mut self) {
        self.shadows_stale = self.shadows.is_some();
    }
}

/// A scene without a material, or without a light or an environment map,
/// cannot be drawn.
fn check_drawable(scene: &Scene) -> Result<()> {
    if scene.materials.is_empty() || (scene.lights.is_empty() && scene.environment.map.is_none()) {
        return Err(Error::Scene(
            "it needs at least one material and one light (or an environment map)".into(),
        ));
    }
    Ok(())
}

/// `scene`'s environment map on the GPU (`None` without one) with the
/// background pipeline of `format` and `samples`.
fn prepare_environment(
    ctx: &GpuContext,
    cache: &mut PipelineCache,
    key: &ShaderKey,
    scene: &Scene,
    format: wgpu::TextureFormat,
    samples: u32,
) -> Result<Option<GpuEnvironment>> {
    if scene.environment.map.is_none() {
        return Ok(None);
    }
    let background = cache.background(key.arrays, format, samples, key.tone_map)?;
    let layouts = cache.environment_layouts(key.arrays);
    GpuEnvironment::new(&ctx.device, &ctx.queue, layouts, background, scene)
}

/// Host bytes the GPU path allocates for `scene`'s geometry beyond the
/// scene itself, an upper bound checked against `--limit memory` before a
/// device is opened: the f32 vertex stream and index buffer (host memory
/// on lavapipe) and the upload's staging window (`gpu::upload`: the
/// stream is written straight into chunks, never whole on the CPU). The
/// larger layout is assumed where the device decides later (per-vertex
/// shadow coordinates, which store three vertices per triangle).
pub fn host_memory_estimate(scene: &Scene) -> u64 {
    let mut key = ShaderKey::new(scene, &ShadowPlan::new(scene));
    key.shadows.vertex_coords = true;
    let (vertex_bytes, index_bytes) =
        GeometryData::byte_sizes(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
    let staging = super::upload::IN_FLIGHT_BYTES + 2 * super::upload::CHUNK_BYTES as u64;
    vertex_bytes + index_bytes + staging
}

/// Refuses a vertex stream or index buffer larger than the device's
/// `max_buffer_size` before building it (a flat-shaded 3200-segment plane
/// is a 2.2 GB stream), naming the settings that make it
/// and how many triangles would fit.
fn check_geometry_size(device: &wgpu::Device, scene: &Scene, key: &ShaderKey) -> Result<()> {
    let (vertex_bytes, index_bytes) =
        GeometryData::byte_sizes(scene, key.needs_tangents(), key.shadow_coords_per_vertex());
    let max = device.limits().max_buffer_size;
    let (what, bytes) = if vertex_bytes >= index_bytes {
        ("vertex buffer", vertex_bytes)
    } else {
        ("index buffer", index_bytes)
    };
    if bytes <= max {
        return Ok(());
    }
    let triangles = scene.triangle_count() as u64;
    let per_triangle = bytes.div_ceil(triangles.max(1));
    Err(Error::argument(
        "objects.*.segments / the model's meshes",
        format!(
            "the {what} of {triangles} triangles with shading `{}` would take {bytes} bytes, over the GPU's maximum buffer size of {max} bytes: at most about {} triangles fit; use fewer `segments` (a sphere of n segments has about n²/2 triangles, a plane 2n²) or a smaller model{}",
            scene.shading.name(),
            max / per_triangle,
            if scene.shading == crate::scene::ShadingMode::Flat {
                " (flat shading stores three vertices per triangle; gouraud or phong shares them)"
            } else {
                ""
            }
        ),
    ))
}

/// Refuses measured tables whose storage buffer (every measured material
/// of the scene, one table each at `shading.measured_table` samples) is
/// over the device's binding limit: each table alone is checked at load
/// against the guaranteed 128 MiB, their sum only here.
fn check_measured_size(device: &wgpu::Device, data: &[f32]) -> Result<()> {
    let bytes = 4 * data.len() as u64;
    let limits = device.limits();
    let max = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    if bytes <= max {
        return Ok(());
    }
    Err(Error::argument(
        "shading.measured_table",
        format!(
            "the scene's measured tables take {} MiB together, over the {} MiB the GPU binds in one storage buffer; lower shading.measured_table, use fewer measured materials, or set shading.measured_mode = \"network\"",
            bytes >> 20,
            max >> 20
        ),
    ))
}

/// The shader key and shadow plan of `scene`, checked against the
/// device's limits.
fn plan(
    device: &wgpu::Device,
    vertex_shadow_coords: bool,
    scene: &Scene,
) -> Result<(ShaderKey, ShadowPlan)> {
    let plan = ShadowPlan::new(scene);
    let mut key = ShaderKey::new(scene, &plan);
    key.shadows.vertex_coords = vertex_shadow_coords;
    debug_assert_eq!(key.counts.shadow_maps as usize, plan.casters.len());
    shadow_maps::check_limits(device, &plan)?;
    Ok((key, plan))
}

/// The pipeline each batch of `draw` is drawn with, compiled by
/// [`PipelineCache::compile_scene`]: specialized to its material's
/// variant when `key` has several ([`PipelineCache::specializations`]).
fn batch_pipelines(
    cache: &PipelineCache,
    key: &ShaderKey,
    format: wgpu::TextureFormat,
    samples: u32,
    materials: &[super::layout::GpuMaterial],
    draw: &SceneDraw,
) -> Vec<BatchPipeline> {
    let specialized = cache.specializations(key).len() > 1;
    draw.batches()
        .iter()
        .map(|b| {
            let material = &materials[b.material as usize];
            let variant = specialized.then_some(material.variant);
            let blend = material.alpha_mode == crate::material::AlphaMode::Blend.code();
            let pipeline = cache.scene_pipeline(&(key.clone(), format, samples, variant, blend));
            (variant, blend, pipeline.clone())
        })
        .collect()
}

/// The lights of `scene` with their shadow maps as `plan` assigns them.
pub fn gpu_lights(scene: &Scene, plan: &ShadowPlan) -> Vec<GpuLight> {
    scene
        .lights
        .iter()
        .enumerate()
        .map(|(l, light)| {
            let mut g = GpuLight::from(light);
            plan.apply(l, &mut g);
            g
        })
        .collect()
}

/// The per-object batches of `batches` whose material passes `test`
/// (index, the centre of the bounding box of the mesh each draws, in
/// world space).
fn object_centers(
    batches: &[Batch],
    scene: &Scene,
    test: impl Fn(&crate::material::Material) -> bool,
) -> Vec<(usize, glam::DVec3)> {
    batches
        .iter()
        .enumerate()
        .filter_map(|(i, b)| {
            let mesh = &scene.meshes[b.object? as usize];
            if !test(&scene.materials[mesh.material]) {
                return None;
            }
            let (lo, hi) = mesh.positions.iter().fold(
                (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
                |(lo, hi), &p| (lo.min(p), hi.max(p)),
            );
            Some((i, 0.5 * (lo + hi)))
        })
        .collect()
}

/// The drawing order of `batches` batches and the transmission layer of
/// each: every batch that neither transmits nor blends, in stream order,
/// then the transmissive ones (`transmissive`), then the BLEND ones
/// (`blend`), each back to front, farthest centre from `scene`'s camera
/// first ("sorted per object": the triangles within one are drawn in
/// index order; the reference composites in exact depth order, see
/// `reference::renderer`). The transmissive batch of rank `k` in that
/// order reads layer `scene.transmission.layer_of(k)`.
fn draw_order(
    batches: usize,
    (transmissive, blend): (&[ObjectCenter], &[ObjectCenter]),
    scene: &Scene,
) -> (Vec<usize>, Vec<Option<usize>>) {
    let eye = scene.camera.position;
    let listed = |i: &usize| transmissive.iter().chain(blend).any(|(b, _)| b == i);
    let mut order: Vec<usize> = (0..batches).filter(|i| !listed(i)).collect();
    let back_to_front = |centers: &[ObjectCenter]| {
        let mut sorted = centers.to_vec();
        sorted
            .sort_by(|(_, a), (_, b)| b.distance_squared(eye).total_cmp(&a.distance_squared(eye)));
        sorted.into_iter().map(|(i, _)| i).collect::<Vec<_>>()
    };
    let mut layers = vec![None; batches];
    for (rank, i) in back_to_front(transmissive).into_iter().enumerate() {
        layers[i] = Some(scene.transmission.layer_of(rank));
        order.push(i);
    }
    order.extend(back_to_front(blend));
    (order, layers)
}

/// Counts the parameter buffers written whole: every material record (at
/// the device's stride), the lights, the measured tables if bound.
fn count_parameters(
    uploads: &mut UploadTally,
    ctx: &GpuContext,
    arrays: super::bindings::UniformArrays,
    materials: &[super::layout::GpuMaterial],
    measured: &[f32],
    lights: &[GpuLight],
) {
    let stride = super::bind_groups::material_stride(&ctx.device);
    uploads.materials.add(materials.len() as u64 * stride);
    let light_bytes = super::bind_groups::light_bytes(lights, arrays.lights);
    uploads.lights.add(light_bytes.len() as u64);
    if arrays.measured && !measured.is_empty() {
        uploads.measured.add(4 * measured.len() as u64);
    }
}

/// Counts every material's texture slots (one uniform buffer each).
fn count_slots(uploads: &mut UploadTally, scene: &Scene) {
    let slots = super::textures::UNIFORM_BYTES;
    for _ in &scene.materials {
        uploads.texture_slots.add(slots as u64);
    }
}

/// Counts the environment map's texels (RGBA `f32`) uploaded anew.
fn count_environment(uploads: &mut UploadTally, scene: &Scene) {
    if let Some(map) = &scene.environment.map {
        uploads
            .environment
            .add(16 * u64::from(map.data.width) * u64::from(map.data.height));
    }
}

/// Counts the layer views and casters of `plan` written in place.
fn count_shadow_views(
    uploads: &mut UploadTally,
    plan: &ShadowPlan,
    arrays: super::bindings::UniformArrays,
) {
    let views = super::bind_groups::shadow_view_bytes(&plan.gpu_views(), arrays.shadow_views);
    let casters = super::bind_groups::caster_bytes(&plan.casters);
    uploads
        .shadow_views
        .add((views.len() + casters.len()) as u64);
}
