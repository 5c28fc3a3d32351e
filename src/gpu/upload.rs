//! Filling the vertex and index buffers through a small staging window.
//!
//! `create_buffer_init` maps a staging copy of the whole buffer: with the
//! `f32` stream built in a `Vec` first, a mesh was in host memory three
//! times over during its upload (the `Vec`, the staging copy, and the
//! buffer itself, which is host memory on lavapipe). Here the stream is
//! written straight from the meshes ([`StreamPlan::write`]) into
//! [`CHUNK_BYTES`] chunks, each handed to `Queue::write_buffer` (wgpu's
//! own staging belt), and every [`IN_FLIGHT_BYTES`] the queue is
//! submitted and waited for, so that the staging memory already copied is
//! recycled: the upload holds at most a few MiB besides the buffers.

use super::geometry::{Batch, Meshes, ObjectRange, StreamPlan, VertexLayout, Words};

/// Words gathered before one `write_buffer` (a multiple of 4 bytes).
pub const CHUNK_BYTES: usize = 1 << 20;

/// Bytes written between two waits for the queue: the staging memory
/// wgpu holds at most (4 chunks).
pub const IN_FLIGHT_BYTES: u64 = 4 << 20;

/// A new buffer of known size, filled front to back.
pub struct BufferWriter<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    buffer: wgpu::Buffer,
    /// Bytes handed to the queue so far.
    written: u64,
    /// Bytes handed to the queue since the last wait.
    in_flight: u64,
    chunk: Vec<u32>,
}

impl<'a> BufferWriter<'a> {
    /// A buffer of `size` bytes (a multiple of 4) for `usage`.
    pub fn new(
        device: &'a wgpu::Device,
        queue: &'a wgpu::Queue,
        label: &str,
        size: u64,
        usage: wgpu::BufferUsages,
    ) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        BufferWriter {
            device,
            queue,
            buffer,
            written: 0,
            in_flight: 0,
            chunk: Vec::with_capacity(CHUNK_BYTES / 4),
        }
    }

    fn flush(&mut self) {
        if self.chunk.is_empty() {
            return;
        }
        let bytes: &[u8] = bytemuck::cast_slice(&self.chunk);
        self.queue.write_buffer(&self.buffer, self.written, bytes);
        self.written += bytes.len() as u64;
        self.in_flight += bytes.len() as u64;
        self.chunk.clear();
        if self.in_flight >= IN_FLIGHT_BYTES {
            self.wait();
        }
    }

    /// Submits the writes so far and waits for them, which frees their
    /// staging memory.
    fn wait(&mut self) {
        self.queue.submit([]);
        // A lost device shows at the frame's own submit and readback.
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
        self.in_flight = 0;
    }

    /// The filled buffer (its writes submitted). Panics if fewer or more
    /// bytes were written than its size: the plan and the writer
    /// disagree, a bug.
    pub fn finish(mut self) -> wgpu::Buffer {
        self.flush();
        if self.in_flight > 0 {
            self.wait();
        }
        assert_eq!(self.written, self.buffer.size(), "stream size");
        self.buffer
    }
}

impl Words for BufferWriter<'_> {
    fn put(&mut self, mut words: &[u32]) {
        while !words.is_empty() {
            let room = CHUNK_BYTES / 4 - self.chunk.len();
            let (now, rest) = words.split_at(room.min(words.len()));
            self.chunk.extend_from_slice(now);
            words = rest;
            if self.chunk.len() * 4 == CHUNK_BYTES {
                self.flush();
            }
        }
    }
}

/// A scene's vertex stream (and index buffer) on the GPU.
pub struct GpuGeometry {
    pub layout: VertexLayout,
    pub vertex_buffer: wgpu::Buffer,
    pub index_buffer: Option<wgpu::Buffer>,
    /// Vertices to draw (non-indexed) or indices to draw (indexed).
    pub draw_count: u32,
    /// The stream's material runs, in order.
    pub batches: Vec<Batch>,
    /// The stream's meshes with their bounds, in order (shadow culling).
    pub objects: Vec<ObjectRange>,
    /// Bytes of vertex and index data.
    pub bytes: u64,
}

impl GpuGeometry {
    /// Writes the stream `plan` lays out for `meshes` (those of the scene
    /// it was made for; released ones are freed as they are written)
    /// straight into new GPU buffers.
    pub fn upload(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        plan: StreamPlan,
        meshes: Meshes,
    ) -> Self {
        let mut vertices = BufferWriter::new(
            device,
            queue,
            "vertices",
            plan.vertex_bytes,
            wgpu::BufferUsages::VERTEX,
        );
        let index_buffer = if plan.indexed {
            let mut indices = BufferWriter::new(
                device,
                queue,
                "indices",
                plan.index_bytes,
                wgpu::BufferUsages::INDEX,
            );
            plan.write(meshes, &mut vertices, &mut indices);
            Some(indices.finish())
        } else {
            plan.write(meshes, &mut vertices, &mut Vec::<u32>::new());
            None
        };
        GpuGeometry {
            layout: plan.layout,
            vertex_buffer: vertices.finish(),
            index_buffer,
            draw_count: plan.draw_count,
            bytes: plan.vertex_bytes + plan.index_bytes,
            batches: plan.batches,
            objects: plan.objects,
        }
    }
}
