//! The GPU side of a [`ShadowPlan`]: the shadow-map array, the bind
//! groups that fill it (the depth-only passes) and read it (the scene
//! pass), the passes themselves, and the check that the device can hold
//! the maps.

use super::bind_groups;
use super::bindings::{self, UniformArrays};
use super::context::GpuContext;
use super::draw::SceneDraw;
use super::pipelines::PipelineCache;
use super::scene_parts::{self, PartBreak};
use super::shadow_culling::LayerCasters;
use super::shadow_masks::ShadowMasks;
use super::shadows::{self, ShadowPlan};
use super::texture_pool::TextureRequest;
use crate::{Error, Result};
use std::ops::Range;
use wgpu::util::DeviceExt;

/// The shadow-map array and the bind groups that read and fill it, and
/// the depth-only pipeline that fills it.
///
/// The layer views live in two buffers: the depth passes read `views`,
/// the plan's matrices as they are; the scene pass reads `scene_views`,
/// a copy made when the maps are drawn in which every skipped layer
/// (a cube face or spot map no caster reaches, see [`ShadowMaps::encode`])
/// has an all-zero matrix. Its clip `w` is then 0, and the perspective
/// lookup returns "lit" for `w ≤ 0` (shaders/shadows.wgsl `shadow_read`;
/// the cube lookup `shadow_cube` for its face's `near` entry 0)
/// before it reads a texel: what every tap of the cleared layer would
/// have returned (a cleared texel holds 0, "nothing here", and the
/// comparison `d ≥ 0` passes). So a skipped layer costs neither its clear
/// nor its pass, and the image is the one every layer drawn gives.
pub struct ShadowMaps {
    /// The array itself, kept to give back to the device's
    /// [`TexturePool`](super::texture_pool::TexturePool) after a one-shot render ([`ShadowMaps::release`]).
    texture: wgpu::Texture,
    layer_views: Vec<wgpu::TextureView>,
    scene_group: wgpu::BindGroup,
    pass_group: wgpu::BindGroup,
    pass_pipeline: wgpu::RenderPipeline,
    views: wgpu::Buffer,
    scene_views: wgpu::Buffer,
    casters: wgpu::Buffer,
    /// What the texture and the buffers were made for:
    /// [`ShadowMaps::holds`].
    shape: Shape,
}

/// The sizes a [`ShadowMaps`] was made for: a plan of the same shape
/// reuses it ([`ShadowMaps::write_plan`]) instead of allocating anew.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shape {
    side: u32,
    layers: usize,
    arrays: UniformArrays,
    stride: u64,
}

/// The shadow-map array's label and its role in the [`TexturePool`](super::texture_pool::TexturePool).
const SHADOW_MAPS_ROLE: &str = "shadow maps";

/// Layers of the shadow-map texture for `plan`'s maps: one per map, and
/// on the GL backend one more where the count would make wgpu's GL
/// backend create another kind of texture than the 2D array the scene
/// pass binds. GL fixes a texture's target when it is created, and
/// wgpu-hal guesses it from the size alone (`Texture::get_info_from_desc`):
/// one layer makes a `TEXTURE_2D`, six square layers a `TEXTURE_CUBE_MAP`
/// (a multiple of six a cube array). Sampling a 2D-array view of those
/// compared every texel as in shadow: a sun's or spot's single map, or one
/// point light's cube, were the GL backend's wrong shadows.
/// The extra layer is never drawn or read.
pub fn texture_layers(plan: &ShadowPlan, backend: wgpu::Backend) -> u32 {
    let maps = plan.layers.len() as u32;
    if backend == wgpu::Backend::Gl && (maps == 1 || maps.is_multiple_of(6)) {
        maps + 1
    } else {
        maps
    }
}

impl ShadowMaps {
    /// The shadow-map array of `plan` with one view per layer to render
    /// into, the bind groups that read and fill it and the depth-only
    /// pipeline for a stream of `stride` bytes; `None` without shadowed
    /// lights. The array is the one the last one-shot render on `ctx`
    /// left in its [`TexturePool`](super::texture_pool::TexturePool) when it has this shape (its layers'
    /// old depths are never read: [`ShadowMaps::encode`] clears every
    /// layer it draws and zeroes the view of every layer it skips).
    pub fn new(
        ctx: &GpuContext,
        cache: &mut PipelineCache,
        plan: &ShadowPlan,
        arrays: UniformArrays,
        stride: u64,
    ) -> Option<Self> {
        if plan.is_empty() {
            return None;
        }
        cache.compile_shadow_pass(stride);
        let device = &ctx.device;
        let texture = ctx.textures.take(
            device,
            &TextureRequest {
                role: SHADOW_MAPS_ROLE,
                size: wgpu::Extent3d {
                    width: plan.side,
                    height: plan.side,
                    depth_or_array_layers: texture_layers(plan, ctx.adapter_info.backend),
                },
                format: shadows::SHADOW_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                sample_count: 1,
                view_formats: &[],
            },
        );
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        // The depth passes read `views` (storage), the scene pass its copy
        // `scene_views` (uniform or storage, as `arrays` says).
        let view_bytes = view_bytes(plan, arrays);
        let copy = wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC;
        let views_buffer = init(
            "shadow views",
            &view_bytes,
            wgpu::BufferUsages::STORAGE | copy,
        );
        let scene_views = init(
            "shadow views (scene pass)",
            &view_bytes,
            bindings::usage(arrays.shadow_views) | copy,
        );
        let casters_buffer = init(
            "shadow casters",
            &bind_groups::caster_bytes(&plan.casters),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let layer_views = (0..plan.layers.len() as u32)
            .map(|layer| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("shadow layer"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: layer,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("shadow maps"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let sampler = cache.shadow_sampler().clone();
        let scene_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio shadow maps"),
            layout: &cache.scene_layouts(arrays).shadow_group,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&array_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: scene_views.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: casters_buffer.as_entire_binding(),
                },
            ],
        });
        let pass_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gonio shadow pass"),
            layout: cache.shadow_pass_group_layout(),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: views_buffer.as_entire_binding(),
            }],
        });
        Some(ShadowMaps {
            texture,
            layer_views,
            scene_group,
            pass_group,
            pass_pipeline: cache.shadow_pass(stride).clone(),
            views: views_buffer,
            scene_views,
            casters: casters_buffer,
            shape: Shape {
                side: plan.side,
                layers: plan.layers.len(),
                arrays,
                stride,
            },
        })
    }

    /// Gives the array back to `ctx`'s [`TexturePool`](super::texture_pool::TexturePool) for the next
    /// one-shot render (after this one's last submission).
    pub fn release(self, ctx: &GpuContext) {
        ctx.textures.give(SHADOW_MAPS_ROLE, self.texture);
    }

    /// Whether `plan` fits these maps as they are: the same side and
    /// layers, bound the same way, filled from a stream of `stride`
    /// bytes. Then [`ShadowMaps::write_plan`] takes it, and a moving light
    /// costs no new 2D array (24 MiB for a cube of 1024² per light, which
    /// lavapipe allocates and zeroes in host memory) every frame.
    pub fn holds(&self, plan: &ShadowPlan, arrays: UniformArrays, stride: u64) -> bool {
        self.shape
            == Shape {
                side: plan.side,
                layers: plan.layers.len(),
                arrays,
                stride,
            }
    }

    /// Writes `plan`'s layer views and casters, for a plan these maps
    /// [`hold`](ShadowMaps::holds); the maps must then be drawn again.
    pub fn write_plan(&self, queue: &wgpu::Queue, plan: &ShadowPlan) {
        queue.write_buffer(&self.views, 0, &view_bytes(plan, self.shape.arrays));
        queue.write_buffer(&self.casters, 0, &bind_groups::caster_bytes(&plan.casters));
    }

    /// Group 1 of the scene pass: the maps, the comparison sampler, the
    /// layer views and the casters.
    pub fn scene_group(&self) -> &wgpu::BindGroup {
        &self.scene_group
    }

    /// Records the depth-only passes of `plan`'s layers (the stream of
    /// `draw`), with timestamps 2 and 3 around them all when `timestamps`
    /// is given; returns the layers drawn. With `casters`, each layer
    /// draws only the objects it lists (src/gpu/shadow_culling.rs), and a
    /// perspective layer (cube face, spot) that lists none is skipped,
    /// clear included: the scene pass reads it as lit through its zeroed
    /// view (see [`ShadowMaps`]). An orthographic layer is always drawn
    /// (its lookup has no `w` to test; a sun's map is fitted to the scene,
    /// so it is never empty). Without `casters`, every layer draws the
    /// whole stream. With `masks`, the draws of alpha MASK materials go
    /// through its pipeline, which discards what MASK cuts out
    /// (src/gpu/shadow_masks.rs). With `parts` (a one-shot render of a
    /// huge mesh), the passes are split so that at most its
    /// `max_triangles` are drawn between two submissions
    /// (src/gpu/scene_parts.rs): lavapipe's binned scene stays small.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        plan: &ShadowPlan,
        draw: &SceneDraw,
        (casters, masks): (Option<&LayerCasters>, Option<&ShadowMasks>),
        timestamps: Option<&wgpu::QuerySet>,
        mut parts: Option<PartBreak<'_>>,
    ) -> usize {
        let skippable = plan.layers_read_lit_when_zeroed();
        let layer_runs: Vec<_> = (0..plan.layers.len())
            .map(|i| runs(draw, casters.map(|c| c.layers[i].as_slice()), masks))
            .collect();
        let skipped: Vec<bool> = (0..plan.layers.len())
            .map(|i| skippable[i] && layer_runs[i].is_empty())
            .collect();
        // The scene pass's views: the plan's, the skipped layers zeroed.
        let view_size = size_of::<super::layout::GpuShadowView>() as u64;
        encoder.copy_buffer_to_buffer(&self.views, 0, &self.scene_views, 0, self.views.size());
        for i in (0..plan.layers.len()).filter(|&i| skipped[i]) {
            encoder.clear_buffer(&self.scene_views, i as u64 * view_size, Some(view_size));
        }
        let mut drawn: Vec<(usize, Vec<Run>)> = layer_runs
            .into_iter()
            .enumerate()
            .filter(|&(i, _)| !skipped[i])
            .collect();
        // The timestamps need a pass: with every layer skipped, layer 0's
        // clear carries them (its view stays zeroed).
        let clear_only = drawn.is_empty() && timestamps.is_some();
        if clear_only {
            drawn.push((0, Vec::new()));
        }
        let max_triangles = parts.as_ref().map_or(u64::MAX, |p| p.max_triangles);
        let passes = scene_parts::split_layers(&drawn, max_triangles);
        let last = passes.len().saturating_sub(1);
        for (k, part) in passes.iter().enumerate() {
            if let (true, Some(parts)) = (part.break_before, parts.as_mut()) {
                (parts.submit_and_wait)(encoder);
            }
            let timestamp_writes = timestamps.and_then(|set| {
                (k == 0 || k == last).then_some(wgpu::RenderPassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: (k == 0).then_some(2),
                    end_of_pass_write_index: (k == last).then_some(3),
                })
            });
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.layer_views[part.layer],
                    depth_ops: Some(wgpu::Operations {
                        // Reversed depth: 0 is "nothing here".
                        load: match part.clears {
                            true => wgpu::LoadOp::Clear(0.0),
                            false => wgpu::LoadOp::Load,
                        },
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            let size = plan.layers[part.layer].map_size as f32;
            pass.set_viewport(0.0, 0.0, size, size, 0.0, 1.0);
            if part.draws.is_empty() {
                continue;
            }
            pass.set_pipeline(&self.pass_pipeline);
            pass.set_bind_group(0, &self.pass_group, &[]);
            draw.bind_geometry(&mut pass);
            // MASK runs with the masked pipeline and their group 1, the
            // others depth-only (both layouts share group 0).
            let mut masked = false;
            let layer = part.layer as u32..part.layer as u32 + 1;
            for (range, material) in &part.draws {
                match material.and_then(|m| masks?.group(m)) {
                    Some(group) => {
                        if !masked {
                            pass.set_pipeline(masks.expect("a group").pipeline());
                            masked = true;
                        }
                        pass.set_bind_group(1, group, &[]);
                    }
                    None if masked => {
                        pass.set_pipeline(&self.pass_pipeline);
                        masked = false;
                    }
                    None => {}
                }
                draw.draw_range(&mut pass, range.clone(), layer.clone());
            }
        }
        if clear_only { 0 } else { drawn.len() }
    }
}

/// One draw of a shadow pass: a range of the stream, with the material
/// whose masked pipeline draws it (`None`: depth-only).
type Run = (Range<u32>, Option<u32>);

/// `plan`'s layer views as the buffers hold them (`arrays` says how).
fn view_bytes(plan: &ShadowPlan, arrays: UniformArrays) -> Vec<u8> {
    bind_groups::shadow_view_bytes(&plan.gpu_views(), arrays.shadow_views)
}

/// The draws of one layer: `objects` of `draw`'s stream (all of it when
/// `None`), consecutive ones merged into one range where they are
/// contiguous and draw alike; each with its material where `masks` draws
/// that material with the masked pipeline, `None` for the depth-only
/// pipeline. A depth-only pass keeps the nearest depth whatever the draw
/// order, so merging changes no texel.
fn runs(draw: &SceneDraw, objects: Option<&[u32]>, masks: Option<&ShadowMasks>) -> Vec<Run> {
    let masked = |m: u32| masks.and_then(|k| k.group(m)).map(|_| m);
    let items: Vec<(Range<u32>, Option<u32>)> = match objects {
        Some(list) => list
            .iter()
            .map(|&o| {
                let object = &draw.objects()[o as usize];
                (object.range.clone(), masked(object.material))
            })
            .collect(),
        None if masks.is_none() => vec![(0..draw.draw_count(), None)],
        None => draw
            .batches()
            .iter()
            .map(|b| (b.range.clone(), masked(b.material)))
            .collect(),
    };
    let mut runs: Vec<(Range<u32>, Option<u32>)> = Vec::with_capacity(items.len());
    for (range, material) in items {
        match runs.last_mut() {
            Some((last, m)) if last.end == range.start && *m == material => last.end = range.end,
            _ => runs.push((range, material)),
        }
    }
    runs
}

/// Refuses shadow maps the device cannot hold, naming the setting to
/// lower.
pub fn check_limits(device: &wgpu::Device, plan: &ShadowPlan) -> Result<()> {
    if plan.is_empty() {
        return Ok(());
    }
    let limits = device.limits();
    let problem = if plan.casters.len() > shadows::MAX_SHADOW_MAPS {
        Some(format!(
            "{} lights cast shadows through their own maps (an area light with shadow_per_sample counts each sample); at most {} can",
            plan.casters.len(),
            shadows::MAX_SHADOW_MAPS
        ))
    } else if plan.side > limits.max_texture_dimension_2d {
        Some(format!(
            "a shadow map of {0}x{0} texels is larger than the GPU's maximum texture side of {1}",
            plan.side, limits.max_texture_dimension_2d
        ))
    } else if plan.layers.len() as u32 > limits.max_texture_array_layers {
        Some(format!(
            "the shadow maps need {} layers (6 per point or area light, 1 per directional or spot light); the GPU allows {}",
            plan.layers.len(),
            limits.max_texture_array_layers
        ))
    } else if plan.bytes() > shadows::MAX_SHADOW_BYTES {
        Some(format!(
            "the shadow maps need {} MiB ({} layers of {}x{} texels, every layer as large as the largest map; a point or area light has 6); at most {} MiB, which holds these {} layers at a side of at most {} texels",
            plan.bytes() >> 20,
            plan.layers.len(),
            plan.side,
            plan.side,
            shadows::MAX_SHADOW_BYTES >> 20,
            plan.layers.len(),
            largest_side(plan.layers.len() as u64, plan.bytes(), plan.side)
        ))
    } else {
        None
    };
    // The light whose map sets the layers' side (the first of the
    // largest), by its place in the scene's light list.
    let largest = plan
        .lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| l.as_ref().map(|l| (i, l.settings.map_size)))
        .fold(None, |best: Option<(usize, u32)>, (i, size)| match best {
            Some((_, s)) if s >= size => best,
            _ => Some((i, size)),
        });
    let largest = largest
        .map(|(i, size)| {
            format!(" (the largest map, {size}x{size}, is light {i}'s, counting the scene's lights in order)")
        })
        .unwrap_or_default();
    match problem {
        Some(p) => Err(Error::argument(
            SHADOW_SIZE_KEY,
            format!("{p}{largest}; lower shadow_map_size or turn shadows off for some lights"),
        )),
        None => Ok(()),
    }
}

/// The key [`check_limits`] names.
const SHADOW_SIZE_KEY: &str =
    "shadow_map_size (lights.N.shadow_map_size or [shadows] map_size in the scene file, or --set)";

/// `error` with the scene file named, when it is [`check_limits`]'s (the
/// GPU path does not know which file the scene came from).
pub fn name_scene_file(error: Error, scene: &str) -> Error {
    match error {
        Error::Argument { argument, problem } if argument == SHADOW_SIZE_KEY => {
            Error::argument(format!("{scene}: {argument}"), problem)
        }
        other => other,
    }
}

/// The largest power-of-two side at which `layers` layers fit
/// [`shadows::MAX_SHADOW_BYTES`], from the `bytes` they take at `side`.
fn largest_side(layers: u64, bytes: u64, side: u32) -> u32 {
    let per_texel = bytes / (layers.max(1) * u64::from(side).pow(2)).max(1);
    let mut fit = side;
    while fit > 16 && layers * u64::from(fit).pow(2) * per_texel.max(1) > shadows::MAX_SHADOW_BYTES
    {
        fit /= 2;
    }
    fit
}
