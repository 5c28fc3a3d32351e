//! The GPU renderer: wgpu on Vulkan (Mesa lavapipe on machines without a
//! GPU). One render path for the CLI, the tests, the viewer and the bench.
//!
//! One concern per file, each with one owner:
//!
//! * [`context`] finds the device;
//! * [`shader_gen`] writes a scene's WGSL, [`layout`] mirrors its structs,
//!   [`bindings`] says which arrays live in uniform buffers (and why),
//!   [`bind_groups`] packs the buffers' bytes and makes the bind group
//!   layouts, [`geometry`] lays the meshes out for the shading mode,
//!   [`upload`] writes that stream into GPU buffers in small chunks,
//!   [`shadows`] plans the shadow maps ([`shadow_fit`] fits their sides
//!   to the screen when asked), [`shadow_culling`] picks each layer's
//!   casters;
//! * [`pipelines`] (the pipeline cache) owns every compiled module,
//!   pipeline and layout (and `GONIO_DUMP_WGSL`);
//! * [`draw`] holds a vertex stream and its bind group and records the
//!   scene pass; [`shadow_maps`] holds a shadow plan's maps and records
//!   their passes, [`shadow_masks`] the pass of alpha MASK casters;
//!   [`prepared`] is a scene uploaded once and drawn many
//!   times (update by what changed, encode a frame);
//! * [`readback`] copies a radiance target into a [`crate::frame::Frame`]
//!   and reads the timestamp queries; [`timing`] names the durations;
//! * [`offscreen`] is the one-shot render (`scene -> Frame`);
//!   [`texture_pool`] keeps its targets and shadow maps for the next one
//!   on the same device (fresh memory costs a CPU device its first
//!   touch);
//! * [`renderer`]'s [`GpuRenderer`] owns the device and the cache and
//!   hands them to the others, and gives the bench the renderer's
//!   pipeline with another shader over a [`draw::SceneDraw`].
//!
//! Who imports whom inside `gpu/` (`a -> b`: `a` uses `b`; listed from
//! the top, each file uses only files listed after it):
//!
//! ```text
//! renderer    -> offscreen prepared pipelines draw readback timing
//!                upload geometry layout shader_gen context
//! offscreen   -> prepared pipelines draw readback timing context
//!                texture_pool
//! prepared    -> shadow_maps shadow_culling shadow_masks pipelines draw
//!                upload geometry layout shader_gen shadows context
//! shadow_maps -> shadow_culling shadow_masks pipelines draw bind_groups
//!                bindings shadows context texture_pool
//! shadow_culling -> geometry shadows
//! shadow_masks -> textures pipelines geometry shader_gen
//! draw        -> bind_groups bindings upload geometry layout shader_gen
//! pipelines   -> bind_groups bindings geometry shader_gen shadows
//! bind_groups -> bindings layout shadows
//! readback    -> context
//! context     -> texture_pool
//! upload      -> geometry
//! layout      -> nothing in gpu/ (the material's BRDF value, the scene)
//! shader_gen  -> bindings shadows
//! shadows     -> shadow_fit layout (GpuLight, GpuShadowView)
//! bindings, geometry, timing, texture_pool, shadow_fit -> nothing in
//!                gpu/
//! ```
//!
//! Every edge points down: a DAG (`GpuMaterial::new` takes the variant's
//! code, not the `ShaderKey`, so `layout` imports nothing of `gpu/`).

pub mod bind_groups;
pub mod bindings;
pub mod context;
pub mod draw;
pub mod environment;
pub mod geometry;
pub mod layout;
pub mod measured_tables;
pub mod offscreen;
pub mod pipelines;
pub mod prepared;
pub mod readback;
pub mod renderer;
pub mod scene_parts;
pub mod shader_gen;
pub mod shadow_culling;
pub mod shadow_fit;
pub mod shadow_maps;
pub mod shadow_masks;
pub mod shadows;
pub mod texture_pool;
pub mod textures;
pub mod timing;
pub mod upload;

pub use context::{AdapterChoice, GpuContext};
pub use draw::FrameTarget;
pub use pipelines::DEPTH_FORMAT;
pub use prepared::PreparedScene;
pub use renderer::GpuRenderer;
