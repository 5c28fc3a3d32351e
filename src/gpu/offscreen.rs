//! The one-shot offscreen render: a [`Scene`] in, a [`Frame`] of
//! radiance out (`gonio render`, the image tests).
//!
//! The colour target is `Rgba32Float`: linear radiance in RGB and coverage
//! in alpha (cleared to 0, written as 1), read back exactly (or, where the
//! adapter cannot render into it, `Rgba32Uint` holding the same bits:
//! [`GpuContext::radiance_format`]). Without
//! multisampling each pixel is the surface seen at its centre, as in the
//! CPU reference; with `image.msaa` the pass resolves the samples' mean.
//!
//! When a light casts shadows, depth-only passes fill its shadow maps
//! first (one pass per array layer, [`super::shadows`]), and the scene
//! pipeline gets a second bind group with the maps; otherwise neither the
//! passes nor the bind group nor any shadow code exist.

use super::context::GpuContext;
use super::draw::FrameTarget;
use super::formats::DEPTH_FORMAT;
use super::pipelines::PipelineCache;
use super::prepared::PreparedScene;
use super::readback::{PassTimestamps, Readback};
use super::scene_parts::{self, PartBreak};
use super::texture_pool::TextureRequest;
use super::timing::{Clock, Timings};
use crate::frame::Frame;
use crate::scene::Scene;
use crate::{Error, Result};
use std::time::Instant;

/// The targets' labels and their roles in the device's texture pool.
const COLOR_ROLE: &str = "radiance";
const DEPTH_ROLE: &str = "depth";
const MULTISAMPLED_ROLE: &str = "radiance (multisampled)";

/// Renders `scene` offscreen, returning the frame and the time of each
/// step: a [`PreparedScene`] into an `Rgba32Float` target, one
/// [`PreparedScene::encode`], and a readback.
pub fn render(
    ctx: &GpuContext,
    cache: &mut PipelineCache,
    vertex_shadow_coords: bool,
    cull_shadow_casters: bool,
    scene: &Scene,
) -> Result<(Frame, Timings)> {
    draw_once(ctx, Size::of(scene), |format, samples| {
        let mut p = PreparedScene::new(ctx, cache, vertex_shadow_coords, scene, format, samples)?;
        p.cull_shadow_casters = cull_shadow_casters;
        Ok(p)
    })
}

/// [`render`] for a GPU-only run, freeing `scene`'s meshes as they are
/// uploaded ([`PreparedScene::new_releasing_meshes`]): afterwards the
/// meshes have their material and name, their arrays empty.
pub fn render_releasing_meshes(
    ctx: &GpuContext,
    cache: &mut PipelineCache,
    vertex_shadow_coords: bool,
    cull_shadow_casters: bool,
    scene: &mut Scene,
) -> Result<(Frame, Timings)> {
    draw_once(ctx, Size::of(scene), |format, samples| {
        let mut p = PreparedScene::new_releasing_meshes(
            ctx,
            cache,
            vertex_shadow_coords,
            scene,
            format,
            samples,
        )?;
        p.cull_shadow_casters = cull_shadow_casters;
        Ok(p)
    })
}

/// A scene's image size and samples per pixel.
#[derive(Clone, Copy)]
struct Size {
    width: u32,
    height: u32,
    msaa: u32,
}

impl Size {
    fn of(scene: &Scene) -> Self {
        Size {
            width: scene.width,
            height: scene.height,
            msaa: scene.msaa,
        }
    }
}

/// Both renders: a target of `size`, the scene `prepare`d for its format
/// and samples, one frame.
fn draw_once(
    ctx: &GpuContext,
    size: Size,
    prepare: impl FnOnce(wgpu::TextureFormat, u32) -> Result<PreparedScene>,
) -> Result<(Frame, Timings)> {
    let mut timings = Timings::default();
    let pass_triangles = scene_parts::pass_triangles()?;
    let (width, height) = (size.width, size.height);
    check_target_size(ctx, width, height)?;
    let format = ctx
        .radiance_format()
        .ok_or_else(|| Error::Gpu("the adapter has no renderable radiance format".into()))?;
    let samples = size.msaa.max(1);
    if samples > 1 {
        check_msaa(ctx, format, samples)?;
    }
    let start = Instant::now();
    let mut prepared = prepare(format, samples)?;
    timings.push(
        "build vertex data + pipeline + upload",
        start.elapsed(),
        Clock::Wall,
    );

    let start = Instant::now();
    let device = &ctx.device;
    // From the device's pool: the last one-shot render's targets when
    // they have this shape (the scene pass clears both; texture_pool.rs).
    let target = |role, format, usage, sample_count| {
        ctx.textures.take(
            device,
            &TextureRequest {
                role,
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                format,
                usage,
                sample_count,
                view_formats: &[],
            },
        )
    };
    let color = target(
        COLOR_ROLE,
        format,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        1,
    );
    let depth = target(
        DEPTH_ROLE,
        DEPTH_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
        samples,
    );
    // With MSAA the pass draws into a multisampled target and resolves
    // (averages the samples) into `color`: radiance is the pixel's
    // mean, coverage the covered fraction.
    let multisampled = (samples > 1).then(|| {
        target(
            MULTISAMPLED_ROLE,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            samples,
        )
    });
    // What this render did not take (a multisampled target, shadow maps,
    // a target of another size) it does not need: dropped before its
    // passes, so the pool never adds to a render's peak memory.
    ctx.textures.clear();
    let readback = Readback::new(device, width, height);
    let queries = ctx.timestamps.then(|| PassTimestamps::new(device));
    timings.push("create targets", start.elapsed(), Clock::Wall);

    let start = Instant::now();
    let color_view = color.create_view(&Default::default());
    let depth_view = depth.create_view(&Default::default());
    let multisampled_view = multisampled
        .as_ref()
        .map(|t| t.create_view(&Default::default()));
    let frame_target = FrameTarget {
        color: multisampled_view.as_ref().unwrap_or(&color_view),
        resolve: multisampled_view.as_ref().map(|_| &color_view),
        depth: &depth_view,
        viewport: None,
        clip: None,
        timestamps: queries.as_ref().map(|q| &q.set),
    };
    // A huge mesh's passes in parts, each submitted and finished before
    // the next is recorded, the shadow passes' too: lavapipe's binned
    // scenes stay small (src/gpu/scene_parts.rs).
    let mut submit_and_wait = |encoder: &mut wgpu::CommandEncoder| {
        let done = std::mem::replace(encoder, device.create_command_encoder(&Default::default()));
        ctx.queue.submit([done.finish()]);
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
    };
    let mut encoder = device.create_command_encoder(&Default::default());
    let shadow_parts = PartBreak {
        max_triangles: pass_triangles,
        submit_and_wait: &mut submit_and_wait,
    };
    let drawn = prepared.encode_shadows(&mut encoder, frame_target.timestamps, Some(shadow_parts));
    // The images transmissive surfaces read, before the scene pass.
    prepared.encode_transmission(&mut encoder);
    let parts = prepared.scene_parts(pass_triangles);
    if parts.len() > 1 && drawn.shadow_layers > 0 {
        submit_and_wait(&mut encoder);
    }
    for part in parts {
        prepared.encode_scene_part(&mut encoder, &frame_target, part.position, part.draws);
        if !part.position.last {
            submit_and_wait(&mut encoder);
        }
    }
    readback.copy_from(&mut encoder, &color);
    if let Some(q) = &queries {
        q.resolve(&mut encoder);
    }
    ctx.queue.submit([encoder.finish()]);
    let frame_bytes = readback.read_bytes(device)?;
    timings.push("render pass + readback", start.elapsed(), Clock::Wall);
    // Done with the textures (the readback waited for the last
    // submission): the next one-shot render on this device reuses them.
    drop((color_view, depth_view, multisampled_view));
    prepared.release(ctx);
    ctx.textures.give(COLOR_ROLE, color);
    ctx.textures.give(DEPTH_ROLE, depth);
    if let Some(t) = multisampled {
        ctx.textures.give(MULTISAMPLED_ROLE, t);
    }
    if let Some(q) = &queries {
        let (scene_pass, shadow_passes) = q.read(ctx)?;
        if drawn.shadow_layers > 0 {
            timings.push(
                format!(
                    "shadow passes ({} layers, {} of {} caster draws culled)",
                    drawn.shadow_layers, drawn.shadow_draws_culled, drawn.shadow_draws_total
                ),
                shadow_passes,
                Clock::GpuTimestamp,
            );
        }
        timings.push("render pass", scene_pass, Clock::GpuTimestamp);
    }

    let frame = timings.wall("unpack frame", || readback.unpack(&frame_bytes));
    Ok((frame, timings))
}

/// Refuses a sample count the device cannot draw offscreen radiance
/// with, naming `image.msaa`.
pub fn check_msaa(ctx: &GpuContext, format: wgpu::TextureFormat, samples: u32) -> Result<()> {
    let specific = ctx
        .device
        .features()
        .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES);
    let flags = ctx.adapter.get_texture_format_features(format).flags;
    if specific
        && flags.sample_count_supported(samples)
        && flags.contains(wgpu::TextureFormatFeatureFlags::MULTISAMPLE_RESOLVE)
    {
        Ok(())
    } else {
        Err(Error::argument(
            format!("image.msaa = {samples}"),
            format!(
                "the GPU adapter `{}` cannot multisample and resolve {format:?} targets; use image.msaa = 1",
                ctx.adapter_info.name
            ),
        ))
    }
}

/// Refuses a target the device cannot hold: a side over
/// `max_texture_dimension_2d`, or a readback buffer (16 bytes a pixel,
/// rows padded to 256 bytes) over `max_buffer_size` (16384 × 8192 is
/// 2 GiB). The message says what size would fit.
pub fn check_target_size(ctx: &GpuContext, width: u32, height: u32) -> Result<()> {
    let limits = ctx.device.limits();
    let max_side = limits.max_texture_dimension_2d;
    let argument = || format!("--width {width} --height {height} (image.width, image.height)");
    if width > max_side || height > max_side {
        return Err(Error::argument(
            argument(),
            format!("the image is larger than the GPU's maximum texture side of {max_side} pixels"),
        ));
    }
    let row = Readback::padded_row(width);
    let bytes = u64::from(row) * u64::from(height);
    if bytes > limits.max_buffer_size {
        let rows = limits.max_buffer_size / u64::from(row);
        return Err(Error::argument(
            argument(),
            format!(
                "reading the image back takes a buffer of {bytes} bytes (16 a pixel), over the GPU's maximum buffer size of {} bytes; at this width at most {rows} rows fit (e.g. --width {width} --height {rows})",
                limits.max_buffer_size,
            ),
        ));
    }
    Ok(())
}

/// A 2D texture of `size` pixels to render into (the colour or depth
/// target of an offscreen pass); the bench's passes use the same.
pub fn render_target(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    sample_count: u32,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}
