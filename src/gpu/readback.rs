//! Getting results off the GPU: a radiance target copied into a buffer
//! and unpacked into a [`Frame`], and the timestamp queries around the
//! passes of a frame.
//!
//! A texture-to-buffer copy pads every row to
//! [`wgpu::COPY_BYTES_PER_ROW_ALIGNMENT`] (256 bytes), so the bytes are
//! unpacked row by row, skipping the padding.

use super::context::GpuContext;
use crate::frame::Frame;
use crate::{Error, Result};
use std::time::Duration;

/// Bytes of one [`COLOR_FORMAT`](super::formats::COLOR_FORMAT) (or
/// [`COLOR_BITS_FORMAT`](super::formats::COLOR_BITS_FORMAT)) texel.
const BYTES_PER_PIXEL: u32 = 16;

/// Maps `buffer` for reading, waits, and copies its bytes out.
pub fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| Error::Gpu(format!("waiting for the GPU failed: {e}")))?;
    rx.recv()
        .map_err(|e| Error::Gpu(format!("readback was dropped: {e}")))?
        .map_err(|e| Error::Gpu(format!("readback failed: {e}")))?;
    let bytes = slice
        .get_mapped_range()
        .map_err(|e| Error::Gpu(format!("readback mapping failed: {e}")))?
        .to_vec();
    buffer.unmap();
    Ok(bytes)
}

/// A buffer that receives one [`COLOR_FORMAT`](super::formats::COLOR_FORMAT) target of `width` ×
/// `height` texels, row by padded row.
pub struct Readback {
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    /// Bytes per row in the buffer: a row of texels rounded up to the copy
    /// alignment.
    padded_row: u32,
}

impl Readback {
    /// A readback buffer for a `width` × `height` radiance target.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Self {
        let padded_row = Self::padded_row(width);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Readback {
            buffer,
            width,
            height,
            padded_row,
        }
    }

    /// Bytes per buffer row of a `width`-texel row: rounded up to the copy
    /// alignment.
    pub fn padded_row(width: u32) -> u32 {
        (width * BYTES_PER_PIXEL).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
    }

    /// Records the copy of `texture` (of this size and [`COLOR_FORMAT`](super::formats::COLOR_FORMAT))
    /// into the buffer.
    pub fn copy_from(&self, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture) {
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// Waits for the submitted copy and returns the padded bytes (see
    /// [`Self::unpack`]).
    pub fn read_bytes(&self, device: &wgpu::Device) -> Result<Vec<u8>> {
        map_read(device, &self.buffer)
    }

    /// Rows of RGBA f32 (padded to the copy alignment) into a [`Frame`]:
    /// radiance from RGB, coverage where alpha is written (> 0.5).
    pub fn unpack(&self, bytes: &[u8]) -> Frame {
        let mut frame = Frame::new(self.width, self.height);
        for i in 0..self.height {
            let row =
                &bytes[(i * self.padded_row) as usize..][..(self.width * BYTES_PER_PIXEL) as usize];
            let texels: &[[f32; 4]] = bytemuck::cast_slice(row);
            for (j, t) in texels.iter().enumerate() {
                let k = frame.index(i, j as u32);
                frame.radiance[k] = [t[0], t[1], t[2]];
                frame.coverage[k] = t[3] > 0.5;
            }
        }
        frame
    }

    /// Waits for the submitted copy and unpacks it.
    pub fn read(&self, device: &wgpu::Device) -> Result<Frame> {
        Ok(self.unpack(&self.read_bytes(device)?))
    }
}

/// Timestamp queries around the scene pass (0, 1) and, when there are
/// four, around all shadow passes (2, 3) of one frame, and the buffers to
/// read them.
pub struct PassTimestamps {
    pub set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    count: u32,
}

impl PassTimestamps {
    /// Queries around the scene pass and the shadow passes.
    pub fn new(device: &wgpu::Device) -> Self {
        Self::with_count(device, 4)
    }

    /// Queries around the scene pass only (indices 0 and 1).
    pub fn scene_pass(device: &wgpu::Device) -> Self {
        Self::with_count(device, 2)
    }

    fn with_count(device: &wgpu::Device, count: u32) -> Self {
        let bytes = 8 * u64::from(count);
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count,
        });
        let resolve = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps"),
            size: bytes,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps read"),
            size: bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        PassTimestamps {
            set,
            resolve,
            read,
            count,
        }
    }

    /// Records the resolve and the copy to the readable buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..self.count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, 8 * u64::from(self.count));
    }

    /// Waits for the submitted frame and returns the span of each pair of
    /// queries ((0, 1), then (2, 3)) in nanoseconds.
    pub fn read_nanos(&self, ctx: &GpuContext) -> Result<Vec<f64>> {
        let bytes = map_read(&ctx.device, &self.read)?;
        let stamps: &[u64] = bytemuck::cast_slice(&bytes);
        let period = ctx.queue.get_timestamp_period() as f64;
        Ok(stamps
            .chunks_exact(2)
            .map(|pair| pair[1].saturating_sub(pair[0]) as f64 * period)
            .collect())
    }

    /// Waits for the submitted frame and returns (scene pass, shadow
    /// passes) durations (needs the four queries of [`Self::new`]).
    pub fn read(&self, ctx: &GpuContext) -> Result<(Duration, Duration)> {
        let spans = self.read_nanos(ctx)?;
        let span = |ns: f64| Duration::from_nanos(ns as u64);
        Ok((span(spans[0]), span(spans[1])))
    }
}
