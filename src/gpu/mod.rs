//! The GPU renderer: wgpu on Vulkan (Mesa lavapipe on machines without a
//! GPU). One render path for the CLI, the tests, the viewer and the bench.
//!
//! One concern per file, each with one owner:
//!
//! * [`context`] finds the device;
//! * [`shader_gen`] writes a scene's WGSL, [`layout`] mirrors its structs,
//!   [`bindings`] says where the arrays live and makes the bind group
//!   layouts, [`geometry`] lays the meshes out for the shading mode,
//!   [`shadows`] plans the shadow maps;
//! * [`pipelines`] (the pipeline cache) owns every compiled module,
//!   pipeline and layout;
//! * [`draw`] holds a vertex stream and its bind group and records the
//!   scene pass; [`prepared`] is a scene uploaded once and drawn many
//!   times (update by what changed, encode a frame, shadow maps);
//! * [`readback`] copies a radiance target into a [`crate::frame::Frame`]
//!   and reads the timestamp queries; [`timing`] names the durations;
//! * [`offscreen`] is the one-shot render (`scene -> Frame`);
//! * [`renderer`]'s [`GpuRenderer`] owns the device and the cache and
//!   hands them to the others (and gives the bench its pipeline with
//!   another shader and its [`draw::SceneDraw`]).
//!
//! Who imports whom (an arrow: "uses"); no file imports one above it in
//! a cycle:
//!
//! ```text
//! renderer ──> offscreen ──> prepared ──> draw ──> bindings
//!    │            │             │  │        │
//!    │            │             │  │        └─> geometry, layout, shader_gen
//!    │            │             │  └─> pipelines ──> bindings, geometry,
//!    │            │             │                    shader_gen, shadows
//!    │            │             └─> shadows, layout, context
//!    │            └─> readback ──> context
//!    │            └─> timing
//!    └─> (all of the above)
//!
//! shader_gen ──> bindings, shadows      shadows ──> layout
//! layout ──> shader_gen                 bindings ──> (nothing in gpu/)
//! geometry, timing, context ──> (nothing in gpu/)
//! ```

pub mod bindings;
pub mod context;
pub mod draw;
pub mod geometry;
pub mod layout;
pub mod offscreen;
pub mod pipelines;
pub mod prepared;
pub mod readback;
pub mod renderer;
pub mod shader_gen;
pub mod shadows;
pub mod timing;

pub use context::{AdapterChoice, GpuContext};
pub use draw::FrameTarget;
pub use pipelines::DEPTH_FORMAT;
pub use prepared::PreparedScene;
pub use renderer::GpuRenderer;
