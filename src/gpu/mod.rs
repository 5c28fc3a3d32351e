//! The GPU renderer: wgpu on Vulkan (Mesa lavapipe on machines without a
//! GPU). One render path for the CLI, the tests and later the viewer:
//! [`context`] finds the device, [`shader_gen`] writes the scene's WGSL,
//! [`geometry`] lays the meshes out for the shading mode, [`shadows`]
//! plans the shadow maps, [`renderer`] draws them and the scene and reads
//! back a [`crate::frame::Frame`].

pub mod bindings;
pub mod context;
pub mod geometry;
pub mod layout;
pub mod prepared;
pub mod renderer;
pub mod shader_gen;
pub mod shadows;
pub mod timing;

pub use context::{AdapterChoice, GpuContext};
pub use prepared::{FrameTarget, PreparedScene};
pub use renderer::GpuRenderer;
