//! Applying named changes ([`Changes`]) to a [`PreparedScene`]: each kind
//! writes only what it reaches, where [`PreparedScene::update`] compares
//! everything (and makes a textured scene anew, its textures included).
//!
//! - a material edit writes that material's record in place (one
//!   `write_buffer` at its offset) and, on a textured material, its
//!   slots if they changed; the vertex stream, the textures and the
//!   shadow maps stay;
//! - a light edit writes the lights buffer and brings the shadow maps up
//!   to the new plan (views rewritten in place when the maps keep their
//!   shape; the maps are then drawn again);
//! - an environment edit uploads a new map only when the texels changed;
//! - a view change writes the per-view globals.
//!
//! What a targeted write cannot express falls back to `update`: a change
//! of the shader key (a model switch that needs other code, a new light
//! count, energy compensation switched on), a measured material (its
//! tables), a material whose alpha MASK changes the shadow casters or
//! whose BLEND changes its pipelines and the drawing order, any material
//! of a scene with transmission (its own pipelines and drawing order per
//! layer), a texture edit that changes which images a material binds. The viewer's
//! `--frame-times` prints what each path sent (`upload_tally`).

use super::{PreparedScene, gpu_lights, plan, prepare_environment};
use crate::Result;
use crate::gpu::context::GpuContext;
use crate::gpu::layout::GpuMaterial;
use crate::gpu::pipelines::PipelineCache;
use crate::gpu::shader_gen::ShaderKey;
use crate::gpu::shadow_masks;
use crate::scene::Scene;
use crate::scene::change::Changes;

/// Why a material could not be written in place.
struct Fallback;

impl PreparedScene {
    /// Brings this scene up to date with `scene` after `changes` (which
    /// must name everything that changed since it was last brought up to
    /// date), writing only what they reach; see the module's notes for
    /// what goes through [`Self::update`] instead.
    pub fn apply(
        &mut self,
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        vertex_shadow_coords: bool,
        scene: &Scene,
        changes: &Changes,
    ) -> Result<()> {
        if changes.scene {
            return self.update(ctx, cache, vertex_shadow_coords, scene);
        }
        super::check_drawable(scene)?;
        let (key, plan) = plan(&ctx.device, vertex_shadow_coords, scene)?;
        if key != self.key {
            return self.update(ctx, cache, vertex_shadow_coords, scene);
        }
        if changes.environment && !self.environment.as_ref().is_some_and(|e| e.holds(scene)) {
            self.environment =
                prepare_environment(ctx, cache, &key, scene, self.format, self.samples)?;
            if self.environment.is_some() {
                super::count_environment(&mut self.uploads, scene);
            }
        }
        let edited: Vec<usize> = (0..scene.materials.len())
            .filter(|&m| changes.material(m))
            .collect();
        if self
            .write_materials(ctx, cache, scene, &key, &edited)?
            .is_err()
        {
            return self.update(ctx, cache, vertex_shadow_coords, scene);
        }
        if changes.lights {
            let lights = gpu_lights(scene, &plan);
            let bytes = self.draw.write_lights(&ctx.queue, &lights);
            self.uploads.lights.add(bytes);
            self.refresh_shadows(ctx, cache, scene, plan, key.arrays, false);
        }
        // A moved light or a material's emission can make or unmake a
        // marker of a light (its layers are then drawn again).
        if changes.lights || !edited.is_empty() {
            self.refresh_markers(scene);
        }
        // The globals hold the light count and the ambient radiance, the
        // environment's uniform its settings.
        if changes.view || changes.lights || changes.environment {
            self.update_view(ctx, scene);
        }
        Ok(())
    }

    /// Writes the records (and texture slots) of materials `edited` in
    /// place; `Err(Fallback)` when one needs more than that (nothing is
    /// left half written that `update` would not write again).
    fn write_materials(
        &mut self,
        ctx: &GpuContext,
        cache: &PipelineCache,
        scene: &Scene,
        key: &ShaderKey,
        edited: &[usize],
    ) -> Result<std::result::Result<(), Fallback>> {
        let floor = scene.roughness_floor();
        for &index in edited {
            let m = scene.materials[index].with_roughness_floor(floor);
            if m.measured_brdf().is_some()
                || self.masks_differ(index, &m)
                || self.blend_differs(index, &m)
                || self.transmission.is_some()
            {
                return Ok(Err(Fallback));
            }
            let record = GpuMaterial::new(&m, key.variant_code(&m.variant()));
            if let Some(textures) = &mut self.textures {
                match textures.write_slots(&ctx.queue, index, &m)? {
                    None => return Ok(Err(Fallback)),
                    Some(0) => {}
                    Some(bytes) => self.uploads.texture_slots.add(bytes),
                }
            }
            let bytes = self.draw.write_material(&ctx.queue, index, &record);
            self.uploads.materials.add(bytes);
            self.repipeline(cache, key, index, record.variant);
        }
        Ok(Ok(()))
    }

    /// Whether material `index`, now `m`, would change what the masked
    /// shadow pass draws (alpha MASK and its cutoff).
    fn masks_differ(&self, index: usize, m: &crate::material::Material) -> bool {
        if self.shadows.is_none() {
            return false;
        }
        let now = shadow_masks::records(std::slice::from_ref(m))[0];
        let held = self
            .shadow_masks
            .as_ref()
            .and_then(|s| s.records().get(index).copied().flatten());
        now != held
    }

    /// Whether material `index`, now `m`, blends where its batches did not
    /// or the other way round (their pipelines and the drawing order,
    /// BLEND batches last and sorted, are then made anew).
    fn blend_differs(&self, index: usize, m: &crate::material::Material) -> bool {
        let blends = m.alpha_mode == crate::material::AlphaMode::Blend;
        self.draw
            .batches()
            .iter()
            .zip(&self.batch_pipelines)
            .any(|(batch, (_, held, _))| batch.material as usize == index && *held != blends)
    }

    /// Points material `index`'s batches at the pipeline of its variant
    /// `variant` where pipelines are specialized per variant (a model
    /// switch between variants the key already has: no compilation).
    fn repipeline(&mut self, cache: &PipelineCache, key: &ShaderKey, index: usize, variant: u32) {
        for (batch, (held, blend, pipeline)) in
            self.draw.batches().iter().zip(&mut self.batch_pipelines)
        {
            if batch.material as usize != index || held.is_none_or(|v| v == variant) {
                continue;
            }
            let cached = (
                key.clone(),
                self.format,
                self.samples,
                Some(variant),
                *blend,
            );
            *held = Some(variant);
            *pipeline = cache.scene_pipeline(&cached).clone();
        }
    }
}
