//! A scene's vertex stream and parameter buffers on the GPU, and the
//! scene pass that draws them material batch by material batch.
//!
//! The renderer's [`super::PreparedScene`] draws through one, with a
//! pipeline per BRDF variant and the shadow maps; the bench draws through
//! one with a pipeline of its own (an unlit floor, a hand-written shader):
//! the same buffers, the same bind group and the same pass, so that two
//! measurements differ only by the shader.

use super::bind_groups::{self, SceneLayouts};
use super::bindings::{self, UniformArrays};
use super::geometry::{Batch, ObjectRange, VertexLayout};
use super::layout::{GpuGlobals, GpuLight, GpuMaterial};
use super::measured_tables::MeasuredTables;
use super::scene_parts::PassPosition;
use super::shader_gen::ShaderKey;
use super::upload::GpuGeometry;
use crate::scene::Scene;
use wgpu::util::DeviceExt;

/// Where a scene pass draws.
pub struct FrameTarget<'a> {
    /// Colour attachment of the prepared scene's `format` and samples.
    pub color: &'a wgpu::TextureView,
    /// Where a multisampled `color` is resolved to.
    pub resolve: Option<&'a wgpu::TextureView>,
    /// Depth attachment ([`super::formats::DEPTH_FORMAT`]) of the same
    /// size.
    pub depth: &'a wgpu::TextureView,
    /// `[x, y, width, height]` in pixels of the 3D area; `None`: all of it.
    /// The scene's camera aspect should be `width / height` of this area.
    pub viewport: Option<[f32; 4]>,
    /// `[x, y, width, height]` in pixels: draw only inside this rectangle
    /// and keep the colour target's other pixels (loaded, not cleared).
    /// The viewer's split view draws two scenes side by side this way.
    /// `None`: the whole target, cleared first.
    pub clip: Option<[u32; 4]>,
    /// Timestamps written around the scene pass (indices 0, 1) and around
    /// all shadow passes (2, 3), if given.
    pub timestamps: Option<&'a wgpu::QuerySet>,
}

/// Begins the scene pass into `target`: clears the whole colour target to
/// transparent black (coverage 0) unless it is clipped, and the depth to
/// the far plane, writes timestamps 0 and 1 around the pass if asked, and
/// sets the viewport (and the clip's scissor rectangle).
pub fn begin_scene_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &FrameTarget,
) -> wgpu::RenderPass<'e> {
    begin_scene_pass_part(encoder, target, PassPosition::WHOLE)
}

/// [`begin_scene_pass`] for one part of a split scene pass
/// (src/gpu/scene_parts.rs): only the first part clears and writes
/// timestamp 0; a later part loads the colour and the depth the earlier
/// one stored; only the last resolves, discards the depth and writes
/// timestamp 1.
pub fn begin_scene_pass_part<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &FrameTarget,
    position: PassPosition,
) -> wgpu::RenderPass<'e> {
    let timestamp_writes = target.timestamps.and_then(|set| {
        (position.first || position.last).then_some(wgpu::RenderPassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: position.first.then_some(0),
            end_of_pass_write_index: position.last.then_some(1),
        })
    });
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target.color,
            depth_slice: None,
            resolve_target: if position.last { target.resolve } else { None },
            ops: wgpu::Operations {
                load: if target.clip.is_some() || !position.first {
                    wgpu::LoadOp::Load
                } else {
                    wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                },
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: target.depth,
            depth_ops: Some(wgpu::Operations {
                load: if position.first {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                },
                store: if position.last {
                    wgpu::StoreOp::Discard
                } else {
                    wgpu::StoreOp::Store
                },
            }),
            stencil_ops: None,
        }),
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    if let Some([x, y, w, h]) = target.viewport {
        pass.set_viewport(x, y, w, h, 0.0, 1.0);
    }
    if let Some([x, y, w, h]) = target.clip {
        pass.set_scissor_rect(x, y, w, h);
    }
    pass
}

/// The GPU materials of `scene`, with the variant indices of `key`.
pub fn gpu_materials(scene: &Scene, key: &ShaderKey) -> Vec<GpuMaterial> {
    let tables = measured_tables(scene);
    scene
        .effective_materials()
        .iter()
        .map(|m| {
            let mut g = GpuMaterial::new(m, key.variant_code(&m.variant()));
            if let Some(brdf) = m.measured_brdf() {
                g.lobe = tables.lobe(brdf);
            }
            g
        })
        .collect()
}

/// What the GPU reads of a scene's materials: one record per material
/// and the measured tables (empty without a measured material).
#[derive(Clone, Copy)]
pub struct MaterialData<'a> {
    pub records: &'a [GpuMaterial],
    pub measured_tables: &'a [f32],
}

/// The measured tables of `scene` (built once per material and
/// resolution, then cached: src/gpu/measured_tables.rs), or its networks'
/// weights (`shading.measured_mode = "network"`).
pub fn measured_tables(scene: &Scene) -> MeasuredTables {
    if scene.measured_network {
        MeasuredTables::networks(&scene.materials)
    } else {
        MeasuredTables::new(&scene.materials, scene.measured_table)
    }
}

/// A vertex stream, its material batches, and the scene bind group
/// (globals, materials, lights) that draws them.
pub struct SceneDraw {
    /// The stream's attributes.
    pub layout: VertexLayout,
    /// Bytes of vertex and index data on the GPU.
    pub geometry_bytes: u64,
    vertex_buffer: wgpu::Buffer,
    index_buffer: Option<wgpu::Buffer>,
    draw_count: u32,
    /// The stream's material runs, in order.
    batches: Vec<Batch>,
    /// The stream's meshes, in order.
    objects: Vec<ObjectRange>,
    /// Bytes between materials in the materials buffer (dynamic-offset
    /// alignment; src/gpu/bindings.rs).
    material_stride: u64,
    arrays: UniformArrays,
    globals_buffer: wgpu::Buffer,
    materials_buffer: wgpu::Buffer,
    lights_buffer: wgpu::Buffer,
    /// The measured tables (binding 3), when the scene has any.
    measured_buffer: Option<wgpu::Buffer>,
    /// The sheen's albedo table (binding 4), when a material has a sheen.
    sheen_buffer: Option<wgpu::Buffer>,
    bind_group: wgpu::BindGroup,
}

impl SceneDraw {
    /// Draws `geometry` (uploaded by [`GpuGeometry::upload`]) and uploads
    /// the parameters, bound as `arrays` says with `layouts` (those of
    /// `arrays`).
    pub fn new(
        device: &wgpu::Device,
        layouts: &SceneLayouts,
        geometry: GpuGeometry,
        arrays: UniformArrays,
        globals: &GpuGlobals,
        materials: MaterialData<'_>,
        lights: &[GpuLight],
    ) -> Self {
        let MaterialData {
            records: materials,
            measured_tables: measured,
        } = materials;
        let init = |label, contents: &[u8], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let dynamic = wgpu::BufferUsages::COPY_DST;
        let globals_buffer = init(
            "globals",
            bytemuck::bytes_of(globals),
            wgpu::BufferUsages::UNIFORM | dynamic,
        );
        let material_stride = bind_groups::material_stride(device);
        let materials_buffer = init(
            "materials",
            &bind_groups::material_bytes(materials, material_stride),
            wgpu::BufferUsages::UNIFORM | dynamic,
        );
        let lights_buffer = init(
            "lights",
            &bind_groups::light_bytes(lights, arrays.lights),
            bindings::usage(arrays.lights) | dynamic,
        );
        let measured_buffer = measured_buffer(device, arrays, measured);
        let sheen_buffer = sheen_buffer(device, arrays);
        let bind_group = scene_bind_group(
            device,
            layouts,
            &globals_buffer,
            &materials_buffer,
            &lights_buffer,
            measured_buffer.as_ref(),
            sheen_buffer.as_ref(),
        );
        SceneDraw {
            layout: geometry.layout,
            geometry_bytes: geometry.bytes,
            vertex_buffer: geometry.vertex_buffer,
            index_buffer: geometry.index_buffer,
            draw_count: geometry.draw_count,
            batches: geometry.batches,
            objects: geometry.objects,
            material_stride,
            arrays,
            globals_buffer,
            materials_buffer,
            lights_buffer,
            measured_buffer,
            sheen_buffer,
            bind_group,
        }
    }

    /// The stream's material batches, in drawing order.
    pub fn batches(&self) -> &[Batch] {
        &self.batches
    }

    /// The stream's meshes, in drawing order.
    pub fn objects(&self) -> &[ObjectRange] {
        &self.objects
    }

    /// Indices (or vertices) of the whole stream.
    pub fn draw_count(&self) -> u32 {
        self.draw_count
    }

    /// Which arrays the bind group has in uniform buffers.
    pub fn arrays(&self) -> UniformArrays {
        self.arrays
    }

    /// Writes material `index`'s record in place (its slot of the
    /// materials buffer): what an edit of one material's values changes.
    /// Returns the bytes written.
    pub fn write_material(&self, queue: &wgpu::Queue, index: usize, record: &GpuMaterial) -> u64 {
        let offset = bind_groups::material_offset(index as u32, self.material_stride);
        let bytes = bytemuck::bytes_of(record);
        queue.write_buffer(&self.materials_buffer, u64::from(offset), bytes);
        bytes.len() as u64
    }

    /// Writes the lights in place, as many as the buffer was made for
    /// (the same light count and binding). Returns the bytes written.
    pub fn write_lights(&self, queue: &wgpu::Queue, lights: &[GpuLight]) -> u64 {
        let bytes = bind_groups::light_bytes(lights, self.arrays.lights);
        debug_assert_eq!(bytes.len() as u64, self.lights_buffer.size());
        queue.write_buffer(&self.lights_buffer, 0, &bytes);
        bytes.len() as u64
    }

    /// The globals' buffer (the back-face pass of the traced
    /// transmission exit binds its camera: src/gpu/transmission_back_faces.rs).
    pub fn globals_buffer(&self) -> &wgpu::Buffer {
        &self.globals_buffer
    }

    /// Writes the per-view values.
    pub fn write_globals(&self, queue: &wgpu::Queue, globals: &GpuGlobals) {
        queue.write_buffer(&self.globals_buffer, 0, bytemuck::bytes_of(globals));
    }

    /// Writes new materials and lights, bound as `arrays` says: in place
    /// when they fit the buffers and the bindings are the same, else into
    /// new buffers and a new bind group (made with `layouts`, those of
    /// `arrays`).
    pub fn write_parameters(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &SceneLayouts,
        arrays: UniformArrays,
        materials: MaterialData<'_>,
        lights: &[GpuLight],
    ) {
        let MaterialData {
            records: materials,
            measured_tables: measured,
        } = materials;
        let measured_bytes: &[u8] = bytemuck::cast_slice(measured);
        let measured_changed = match &self.measured_buffer {
            None => arrays.measured,
            Some(b) => !arrays.measured || b.size() != measured_bytes.len().max(4) as u64,
        };
        if measured_changed {
            self.measured_buffer = measured_buffer(device, arrays, measured);
        } else if let Some(b) = &self.measured_buffer
            && !measured_bytes.is_empty()
        {
            queue.write_buffer(b, 0, measured_bytes);
        }
        let materials_bytes = bind_groups::material_bytes(materials, self.material_stride);
        let lights_bytes = bind_groups::light_bytes(lights, arrays.lights);
        let rebind = arrays != self.arrays
            || measured_changed
            || materials_bytes.len() as u64 != self.materials_buffer.size()
            || lights_bytes.len() as u64 != self.lights_buffer.size();
        if rebind {
            let init = |label, contents: &[u8], usage| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: usage | wgpu::BufferUsages::COPY_DST,
                })
            };
            self.materials_buffer =
                init("materials", &materials_bytes, wgpu::BufferUsages::UNIFORM);
            self.lights_buffer = init("lights", &lights_bytes, bindings::usage(arrays.lights));
            if arrays.sheen != self.sheen_buffer.is_some() {
                self.sheen_buffer = sheen_buffer(device, arrays);
            }
            self.bind_group = scene_bind_group(
                device,
                layouts,
                &self.globals_buffer,
                &self.materials_buffer,
                &self.lights_buffer,
                self.measured_buffer.as_ref(),
                self.sheen_buffer.as_ref(),
            );
            self.arrays = arrays;
        } else {
            queue.write_buffer(&self.materials_buffer, 0, &materials_bytes);
            queue.write_buffer(&self.lights_buffer, 0, &lights_bytes);
        }
    }

    /// Binds the vertex stream (and index buffer) for [`Self::draw_range`].
    pub fn bind_geometry(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        if let Some(indices) = &self.index_buffer {
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        }
    }

    /// Draws `range` of the bound stream (indices or vertices).
    pub fn draw_range(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        range: std::ops::Range<u32>,
        instances: std::ops::Range<u32>,
    ) {
        match self.index_buffer {
            Some(_) => pass.draw_indexed(range, 0, instances),
            None => pass.draw(range, instances),
        }
    }

    /// The whole stream in one draw call (the shadow passes: no material).
    pub fn draw_all(&self, pass: &mut wgpu::RenderPass<'_>, instances: std::ops::Range<u32>) {
        self.bind_geometry(pass);
        self.draw_range(pass, 0..self.draw_count, instances);
    }

    /// Draws `batch` of the bound stream with its material bound (group
    /// 0 at the material's slot, src/gpu/bindings.rs).
    pub fn draw_batch(&self, pass: &mut wgpu::RenderPass<'_>, batch: &Batch) {
        self.draw_batch_part(pass, batch, batch.range.clone());
    }

    /// [`Self::draw_batch`] of `range`, a part of `batch`'s range (a
    /// split scene pass: src/gpu/scene_parts.rs).
    pub fn draw_batch_part(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        batch: &Batch,
        range: std::ops::Range<u32>,
    ) {
        let offset = bind_groups::material_offset(batch.material, self.material_stride);
        pass.set_bind_group(0, &self.bind_group, &[offset]);
        self.draw_range(pass, range, batch.instance..batch.instance + 1);
    }

    /// Binds group 0 at material `material`'s slot (for a pass that reads
    /// only the globals, as the environment's background).
    pub fn bind_scene_group(&self, pass: &mut wgpu::RenderPass<'_>, material: u32) {
        let offset = bind_groups::material_offset(material, self.material_stride);
        pass.set_bind_group(0, &self.bind_group, &[offset]);
    }

    /// Draws every batch with `pipeline` (a pipeline for all the scene's
    /// materials, as the bench's).
    pub fn draw_with(&self, pass: &mut wgpu::RenderPass<'_>, pipeline: &wgpu::RenderPipeline) {
        pass.set_pipeline(pipeline);
        self.bind_geometry(pass);
        for batch in &self.batches {
            self.draw_batch(pass, batch);
        }
    }
}

/// Group 0 of a scene pipeline over these buffers.
fn scene_bind_group(
    device: &wgpu::Device,
    layouts: &SceneLayouts,
    globals: &wgpu::Buffer,
    materials: &wgpu::Buffer,
    lights: &wgpu::Buffer,
    measured: Option<&wgpu::Buffer>,
    sheen: Option<&wgpu::Buffer>,
) -> wgpu::BindGroup {
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: globals.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: bind_groups::material_binding(materials),
        },
        wgpu::BindGroupEntry {
            binding: 2,
            resource: lights.as_entire_binding(),
        },
    ];
    if let Some(m) = measured {
        entries.push(wgpu::BindGroupEntry {
            binding: 3,
            resource: m.as_entire_binding(),
        });
    }
    if let Some(t) = sheen {
        entries.push(wgpu::BindGroupEntry {
            binding: 4,
            resource: t.as_entire_binding(),
        });
    }
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("gonio scene"),
        layout: &layouts.scene_group,
        entries: &entries,
    })
}

/// The measured tables' storage buffer, if `arrays` binds one (at least
/// one word: a binding cannot be empty).
fn measured_buffer(
    device: &wgpu::Device,
    arrays: UniformArrays,
    measured: &[f32],
) -> Option<wgpu::Buffer> {
    arrays.measured.then(|| {
        let mut bytes = bytemuck::cast_slice::<f32, u8>(measured).to_vec();
        bytes.resize(bytes.len().max(4), 0);
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("measured tables"),
            contents: &bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        })
    })
}

/// The sheen's albedo table as a uniform buffer, if `arrays` binds one
/// (the stored nodes, `gltf_layers::sheen_albedo_nodes`).
fn sheen_buffer(device: &wgpu::Device, arrays: UniformArrays) -> Option<wgpu::Buffer> {
    use crate::material::brdf::gltf_layers::sheen_albedo_nodes::SHEEN_ALBEDO_NODES;
    arrays.sheen.then(|| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sheen albedo table"),
            contents: bytemuck::cast_slice(&SHEEN_ALBEDO_NODES),
            usage: wgpu::BufferUsages::UNIFORM,
        })
    })
}
