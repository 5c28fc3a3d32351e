//! The GPU renderer: wgpu on Vulkan (Mesa lavapipe on machines without a
//! GPU). One render path for the CLI, the tests, the viewer and the bench.
//!
//! One concern per file, each with one owner:
//!
//! * [`context`] finds the device; [`formats`] names the render targets'
//!   texture formats;
//! * [`shader_gen`] writes a scene's WGSL, [`layout`] mirrors its structs,
//!   [`bindings`] says which arrays live in uniform buffers (and why),
//!   [`bind_groups`] packs the buffers' bytes and makes the bind group
//!   layouts, [`geometry`] lays the meshes out for the shading mode,
//!   [`upload`] writes that stream into GPU buffers in small chunks,
//!   [`shadows`] plans the shadow maps ([`shadow_fit`] fits their sides
//!   to the screen when asked), [`shadow_culling`] picks each layer's
//!   casters;
//! * [`textures`] holds the material textures and their samplers,
//!   [`measured_tables`] the tables measured materials are rendered
//!   from, [`environment`] the environment map's texture, uniform and
//!   background pass;
//! * [`pipelines`] (the pipeline cache) owns every compiled module,
//!   pipeline and layout (and `GONIO_DUMP_WGSL`);
//! * [`draw`] holds a vertex stream and its bind group and records the
//!   scene pass ([`scene_parts`] splits a one-shot pass into parts of
//!   bounded size); [`shadow_maps`] holds a shadow plan's maps and records
//!   their passes, [`shadow_masks`] the pass of alpha MASK casters;
//!   [`prepared`] is a scene uploaded once and drawn many
//!   times (update by what changed, encode a frame), counting what it
//!   sends by kind in an [`upload_tally`]; [`transmission`] holds the
//!   images transmissive surfaces read what lies behind them from, and
//!   records their mip chains, [`transmission_back_faces`] the volumes'
//!   back faces and the opaque scene's depth a traced exit marches
//!   against;
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
//! the top, each file uses only files listed after it; every file of
//! `gpu/` appears; `tests/import_graph.rs` checks that there is no circle,
//! and `IMPORT_GRAPH_SHOW=gpu cargo test --test import_graph --
//! --nocapture` prints the edges):
//!
//! ```text
//! renderer    -> offscreen prepared pipelines draw readback timing
//!                upload geometry layout shader_gen context formats
//! offscreen   -> prepared pipelines draw scene_parts readback timing
//!                context texture_pool formats
//! prepared    -> shadow_maps shadow_culling shadow_masks pipelines
//!                environment draw scene_parts upload upload_tally
//!                geometry bind_groups bindings layout textures
//!                shader_gen shadows transmission transmission_back_faces
//!                context formats
//! shadow_maps -> shadow_culling shadow_masks pipelines draw scene_parts
//!                bind_groups bindings layout shadows context texture_pool
//! shadow_masks -> pipelines textures geometry shader_gen
//! shadow_culling -> geometry shadows
//! pipelines   -> environment bind_groups bindings geometry shader_gen
//!                shadows transmission formats
//! transmission -> transmission_back_faces shader_gen formats
//! transmission_back_faces -> geometry shader_gen formats
//! environment -> bind_groups shader_gen formats
//! draw        -> bind_groups bindings layout geometry measured_tables
//!                scene_parts upload shader_gen
//! scene_parts -> geometry
//! upload      -> geometry
//! geometry    -> textures
//! bind_groups -> bindings layout shadows textures
//! shader_gen  -> bindings shadows textures formats
//! shadows     -> shadow_fit layout (GpuLight, GpuShadowView)
//! readback    -> context
//! textures    -> context
//! context     -> formats texture_pool
//! layout, bindings, measured_tables, timing, texture_pool, shadow_fit,
//! upload_tally, formats -> nothing in gpu/
//! ```
//!
//! Every edge points down, so there is no circle (`GpuMaterial::new`
//! takes the variant's code, not the `ShaderKey`, so `layout` imports
//! nothing of `gpu/`; `shadow_fit` queries the scene's BVH,
//! `crate::scene::bvh`, not the reference's).

pub mod bind_groups;
pub mod bindings;
pub mod context;
pub mod draw;
pub mod environment;
pub mod formats;
pub mod geometry;
pub mod layout;
pub mod layout_entries;
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
pub mod transmission;
pub mod transmission_back_faces;
pub mod upload;
pub mod upload_tally;

pub use context::{AdapterChoice, GpuContext};
pub use draw::FrameTarget;
pub use formats::DEPTH_FORMAT;
pub use prepared::PreparedScene;
pub use renderer::GpuRenderer;
pub use upload_tally::UploadTally;
