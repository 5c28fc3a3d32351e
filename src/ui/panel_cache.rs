//! Draws the egui side panel once per change instead of once per frame.
//!
//! On lavapipe the egui pass over a full-height panel costs about as much
//! as a third of the 1080p scene pass (measured: 25 ms of a 75 ms frame),
//! although the panel rarely changes while the camera moves. So the panel's
//! paint jobs are drawn into a texture of their own when their tessellated
//! geometry changes (a hash of vertices, indices, clip rectangles and
//! textures), and every frame copies the panel's rectangle from it into
//! the swapchain image: a memory copy. What is drawn over the 3D area (the
//! overlay, dialogs) is drawn every frame by a second egui renderer, since
//! each renderer's buffers hold one job list.

use egui::epaint::{ClippedPrimitive, Primitive};
use std::hash::{Hash, Hasher};

/// The cached panel and its renderer.
pub struct PanelCache {
    renderer: egui_wgpu::Renderer,
    texture: Option<wgpu::Texture>,
    hash: Option<u64>,
    /// Times the panel was drawn (tests and the frame report).
    pub redraws: u64,
}

impl PanelCache {
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> PanelCache {
        PanelCache {
            renderer: egui_wgpu::Renderer::new(
                device,
                format,
                egui_wgpu::RendererOptions {
                    dithering: false,
                    ..Default::default()
                },
            ),
            texture: None,
            hash: None,
            redraws: 0,
        }
    }

    /// Applies egui's texture changes (the font atlas) to this renderer too.
    pub fn update_texture(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        id: egui::TextureId,
        delta: &egui::epaint::ImageDelta,
    ) {
        self.renderer.update_texture(device, queue, id, delta);
        // A changed texture changes what the same geometry looks like.
        self.hash = None;
    }

    pub fn free_texture(&mut self, id: &egui::TextureId) {
        self.renderer.free_texture(id);
        self.hash = None;
    }

    /// Records (if the panel changed) drawing `jobs` into the cache, then
    /// the copy of `rect` (`[x, y, w, h]`, pixels) from the cache into
    /// `target`. Returns the command buffers egui-wgpu asks to submit first.
    pub fn draw(
        &mut self,
        ctx: &crate::gpu::GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        jobs: &[ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
        target: &wgpu::Texture,
        rect: [u32; 4],
    ) -> Vec<wgpu::CommandBuffer> {
        let (device, queue) = (&ctx.device, &ctx.queue);
        let [w, h] = screen.size_in_pixels;
        let hash = hash_jobs(jobs, screen);
        let resized = !matches!(&self.texture, Some(t) if t.width() == w && t.height() == h);
        if resized {
            self.texture = Some(device.create_texture(&wgpu::TextureDescriptor {
                label: Some("panel cache"),
                size: wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: target.format(),
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            }));
        }
        let texture = self.texture.as_ref().expect("created above");
        let mut extra = Vec::new();
        if resized || self.hash != Some(hash) {
            extra = self
                .renderer
                .update_buffers(device, queue, encoder, jobs, screen);
            let view = texture.create_view(&Default::default());
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui panel"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            let mut pass = pass.forget_lifetime();
            self.renderer.render(&mut pass, jobs, screen);
            self.hash = Some(hash);
            self.redraws += 1;
        }
        let [x, y, rw, rh] = rect;
        let (rw, rh) = (rw.min(w.saturating_sub(x)), rh.min(h.saturating_sub(y)));
        if rw > 0 && rh > 0 {
            let origin = wgpu::Origin3d { x, y, z: 0 };
            encoder.copy_texture_to_texture(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: 0,
                    origin,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyTextureInfo {
                    texture: target,
                    mip_level: 0,
                    origin,
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::Extent3d {
                    width: rw,
                    height: rh,
                    depth_or_array_layers: 1,
                },
            );
        }
        extra
    }
}

/// Splits egui's jobs into those inside the panel (whose clip rectangle
/// lies right of `panel_left`, in points) and the rest.
pub fn split_jobs(
    jobs: Vec<ClippedPrimitive>,
    panel_left: f32,
) -> (Vec<ClippedPrimitive>, Vec<ClippedPrimitive>) {
    jobs.into_iter()
        .partition(|j| j.clip_rect.min.x >= panel_left - 0.5)
}

fn hash_jobs(jobs: &[ClippedPrimitive], screen: &egui_wgpu::ScreenDescriptor) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    screen.size_in_pixels.hash(&mut h);
    screen.pixels_per_point.to_bits().hash(&mut h);
    for job in jobs {
        for v in [
            job.clip_rect.min.x,
            job.clip_rect.min.y,
            job.clip_rect.max.x,
            job.clip_rect.max.y,
        ] {
            v.to_bits().hash(&mut h);
        }
        match &job.primitive {
            Primitive::Mesh(mesh) => {
                mesh.texture_id.hash(&mut h);
                bytemuck::cast_slice::<_, u8>(&mesh.vertices).hash(&mut h);
                mesh.indices.hash(&mut h);
            }
            // Paint callbacks are not cached: a fresh hash each time.
            Primitive::Callback(_) => std::time::Instant::now().hash(&mut h),
        }
    }
    h.finish()
}
