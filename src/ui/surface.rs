//! The window's swapchain, its depth buffer, and screenshots of it.
//!
//! The scene is drawn straight into the swapchain image (display output:
//! exposure and sRGB encoding in the scene shader, see
//! `shader_gen::Output::Display`), so a frame is one scene pass, one egui
//! pass and a present, with no intermediate copy.

use crate::gpu::DEPTH_FORMAT;
use crate::gpu::GpuContext;
use crate::output::write::AtomicFile;
use crate::{Error, Result};
use std::path::Path;

/// A configured window surface.
pub struct WindowSurface {
    pub surface: wgpu::Surface<'static>,
    pub config: wgpu::SurfaceConfiguration,
    /// Whether the swapchain images can be copied (screenshots).
    pub copyable: bool,
    /// Whether the swapchain images can be copied into (the panel cache).
    pub writable: bool,
    depth: Option<(u32, u32, u32, wgpu::TextureView)>,
    /// The multisampled colour target the scene pass draws into and
    /// resolves to the swapchain image (`image.msaa` > 1).
    multisampled: Option<(u32, u32, u32, wgpu::TextureView)>,
}

impl WindowSurface {
    /// Configures `surface` for `ctx` at `width`×`height` with an 8-bit
    /// non-sRGB format (egui-wgpu expects one; the scene shader encodes
    /// sRGB itself).
    pub fn new(
        ctx: &GpuContext,
        adapter_surface_caps: wgpu::SurfaceCapabilities,
        surface: wgpu::Surface<'static>,
        (width, height): (u32, u32),
        vsync: bool,
    ) -> Result<WindowSurface> {
        let caps = adapter_surface_caps;
        let format = [
            wgpu::TextureFormat::Bgra8Unorm,
            wgpu::TextureFormat::Rgba8Unorm,
        ]
        .into_iter()
        .find(|f| caps.formats.contains(f))
        .ok_or_else(|| {
            Error::NoAdapter(format!(
                "the window surface offers no 8-bit RGBA/BGRA format (it offers {:?})",
                caps.formats
            ))
        })?;
        let copyable = caps.usages.contains(wgpu::TextureUsages::COPY_SRC);
        let writable = caps.usages.contains(wgpu::TextureUsages::COPY_DST);
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if copyable {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        if writable {
            usage |= wgpu::TextureUsages::COPY_DST;
        }
        let present_mode = if vsync {
            wgpu::PresentMode::AutoVsync
        } else {
            wgpu::PresentMode::AutoNoVsync
        };
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: width.max(1),
            height: height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&ctx.device, &config);
        Ok(WindowSurface {
            surface,
            config,
            copyable,
            writable,
            depth: None,
            multisampled: None,
        })
    }

    /// Follows a window resize. A minimized window (0×0) keeps the old
    /// configuration: nothing is drawn until it has an area again.
    pub fn resize(&mut self, ctx: &GpuContext, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        let max = ctx.device.limits().max_texture_dimension_2d;
        self.config.width = width.min(max);
        self.config.height = height.min(max);
        self.surface.configure(&ctx.device, &self.config);
    }

    /// Switches vsync.
    pub fn set_vsync(&mut self, ctx: &GpuContext, vsync: bool) {
        self.config.present_mode = if vsync {
            wgpu::PresentMode::AutoVsync
        } else {
            wgpu::PresentMode::AutoNoVsync
        };
        self.surface.configure(&ctx.device, &self.config);
    }

    /// Reconfigures after the surface was lost or outdated.
    pub fn reconfigure(&self, ctx: &GpuContext) {
        self.surface.configure(&ctx.device, &self.config);
    }

    /// The depth buffer for the current size and `samples` per pixel.
    pub fn depth_view(&mut self, ctx: &GpuContext, samples: u32) -> &wgpu::TextureView {
        let size = (self.config.width, self.config.height);
        cached_target(
            &mut self.depth,
            ctx,
            size,
            samples,
            DEPTH_FORMAT,
            "viewer depth",
        )
    }

    /// The multisampled colour target for `samples` > 1 per pixel (in the
    /// swapchain's format, resolved into its image), `None` for 1.
    pub fn multisampled_view(
        &mut self,
        ctx: &GpuContext,
        samples: u32,
    ) -> Option<&wgpu::TextureView> {
        if samples <= 1 {
            self.multisampled = None;
            return None;
        }
        let size = (self.config.width, self.config.height);
        let format = self.config.format;
        Some(cached_target(
            &mut self.multisampled,
            ctx,
            size,
            samples,
            format,
            "viewer colour (multisampled)",
        ))
    }
}

/// A render attachment of `size`, `samples` and `format`, made again only
/// when one of them changed.
fn cached_target<'a>(
    slot: &'a mut Option<(u32, u32, u32, wgpu::TextureView)>,
    ctx: &GpuContext,
    (w, h): (u32, u32),
    samples: u32,
    format: wgpu::TextureFormat,
    label: &str,
) -> &'a wgpu::TextureView {
    if !matches!(slot, Some((dw, dh, ds, _)) if (*dw, *dh, *ds) == (w, h, samples)) {
        let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        *slot = Some((w, h, samples, texture.create_view(&Default::default())));
    }
    &slot.as_ref().expect("just created").3
}

/// A copy of a swapchain image on its way to the CPU.
pub struct PendingScreenshot {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    padded_row: u32,
    bgra: bool,
}

impl PendingScreenshot {
    /// Records a copy of `texture` (a swapchain image) into a readable
    /// buffer; submit the encoder, then [`PendingScreenshot::save`].
    pub fn record(
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        texture: &wgpu::Texture,
    ) -> PendingScreenshot {
        let (width, height) = (texture.width(), texture.height());
        let padded_row = (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("screenshot"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded_row),
                    rows_per_image: Some(height),
                },
            },
            texture.size(),
        );
        PendingScreenshot {
            buffer,
            width,
            height,
            padded_row,
            bgra: texture.format() == wgpu::TextureFormat::Bgra8Unorm,
        }
    }

    /// Waits for the copy and writes an RGB PNG to `path` (atomically).
    pub fn save(self, device: &wgpu::Device, path: &Path) -> Result<()> {
        let file = AtomicFile::create(path)?;
        let slice = self.buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| Error::Gpu(format!("waiting for the screenshot failed: {e}")))?;
        rx.recv()
            .map_err(|e| Error::Gpu(format!("screenshot readback dropped: {e}")))?
            .map_err(|e| Error::Gpu(format!("screenshot readback failed: {e}")))?;
        let mut rgb = Vec::with_capacity((self.width * self.height * 3) as usize);
        {
            let bytes = slice
                .get_mapped_range()
                .map_err(|e| Error::Gpu(format!("screenshot mapping failed: {e}")))?;
            for row in bytes.chunks(self.padded_row as usize) {
                for px in row[..(self.width * 4) as usize].chunks_exact(4) {
                    if self.bgra {
                        rgb.extend_from_slice(&[px[2], px[1], px[0]]);
                    } else {
                        rgb.extend_from_slice(&px[..3]);
                    }
                }
            }
        }
        self.buffer.unmap();
        let image = image::RgbImage::from_raw(self.width, self.height, rgb)
            .ok_or_else(|| Error::Gpu("screenshot size mismatch".into()))?;
        let mut png = std::io::Cursor::new(Vec::new());
        image
            .write_to(&mut png, image::ImageFormat::Png)
            .map_err(|e| Error::output(path, format!("PNG encoding failed: {e}")))?;
        file.commit(png.get_ref())
    }
}
