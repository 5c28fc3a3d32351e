//! The pipeline cache: every shader module, render pipeline and bind
//! group layout the renderer draws with, made on first use and kept for
//! the device's lifetime, so that re-rendering with new parameter values
//! (or a setting the viewer toggles back) never recompiles.
//!
//! Three kinds of pipelines, one description of the scene pass:
//!
//! * **scene pipelines**, keyed by [`PipelineKey`] (features, target
//!   format, samples per pixel, BRDF variant), from one generated module
//!   per [`ShaderKey`] and [`Output`]; a pipeline specialized to a variant
//!   differs from its siblings only by a pipeline-overridable constant;
//! * the **shadow pass** pipeline, one per vertex stride: vertex shader
//!   only, reversed depth;
//! * a scene pipeline with **another shader** ([`PipelineCache::with_shader`],
//!   not cached), for the bench: the same vertex stream, bind groups,
//!   rasterizer and depth state as the renderer's, so that two bench
//!   measurements differ only by the shader.
//!
//! `GONIO_DUMP_WGSL=DIR` writes every generated module to `DIR`, for
//! reading what a scene compiles.

use super::bind_groups::SceneLayouts;
use super::bindings::UniformArrays;
use super::environment::{EnvironmentLayouts, background_pipeline};
use super::formats::DEPTH_FORMAT;
use super::geometry::VertexLayout;
use super::shader_gen::{self, Output, ShaderKey};
use super::shadows;
use crate::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

/// The environment variable naming a directory to write every generated
/// WGSL module to.
pub const DUMP_WGSL_ENV: &str = "GONIO_DUMP_WGSL";

/// What tells scene pipelines apart: features, colour format, samples
/// per pixel, the BRDF variant a pipeline draws (`None`: any of the
/// key's, chosen per material at run time), and whether it blends (alpha
/// BLEND materials: "over" blending, depth tested but not written).
pub type PipelineKey = (ShaderKey, wgpu::TextureFormat, u32, Option<u32>, bool);

/// Shader modules, pipelines and layouts of one device, made on first
/// use. The only owner of compiled GPU code.
pub struct PipelineCache {
    device: wgpu::Device,
    /// One module per key and output; its pipelines differ by constants.
    modules: HashMap<(ShaderKey, Output), wgpu::ShaderModule>,
    /// Scene bind group and pipeline layouts, one set per choice of
    /// uniform or storage arrays.
    scene_layouts: HashMap<UniformArrays, SceneLayouts>,
    scene_pipelines: HashMap<PipelineKey, wgpu::RenderPipeline>,
    /// The depth-only passes: layers in group 0.
    pass_group_layout: wgpu::BindGroupLayout,
    pass_pipeline_layout: wgpu::PipelineLayout,
    /// One per vertex stride.
    pass_pipelines: HashMap<u64, wgpu::RenderPipeline>,
    /// The comparison sampler every shadow-map bind group uses.
    shadow_sampler: wgpu::Sampler,
    /// Group 2's layouts by their number of material textures.
    texture_groups: HashMap<u32, wgpu::BindGroupLayout>,
    /// Layouts with the environment's group 3, per [`UniformArrays`].
    environment_layouts: HashMap<UniformArrays, EnvironmentLayouts>,
    /// Background pipelines by arrays, colour format and samples.
    backgrounds: HashMap<
        (
            UniformArrays,
            wgpu::TextureFormat,
            u32,
            crate::output::tone_map::ToneMap,
        ),
        wgpu::RenderPipeline,
    >,
    /// Group 4 of pipelines that draw transmission (src/gpu/transmission.rs):
    /// the image alone, and with the traced exit's images.
    transmission_group_layout: wgpu::BindGroupLayout,
    traced_transmission_group_layout: wgpu::BindGroupLayout,
    /// Whether a scene of several BRDF variants is drawn by one pipeline
    /// that switches per material at run time instead of one specialized
    /// pipeline per variant ([`Self::specializations`]).
    pub one_pipeline: bool,
}

impl PipelineCache {
    /// An empty cache on `device` (only the shadow pass's layouts and the
    /// shadow sampler are made now).
    pub fn new(device: &wgpu::Device) -> Self {
        let storage = wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        // Nearest texel, hardware depth comparison: 1 where the receiver's
        // depth is ≤ the stored occluder depth (lit).
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("gonio shadow compare"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            address_mode_w: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Nearest,
            min_filter: wgpu::FilterMode::Nearest,
            // Reversed depth: lit where the receiver is at least as near
            // the light as the stored occluder.
            compare: Some(wgpu::CompareFunction::GreaterEqual),
            ..Default::default()
        });
        let pass_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("gonio shadow pass"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: storage,
                count: None,
            }],
        });
        let pass_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("gonio shadow pass"),
            bind_group_layouts: &[Some(&pass_group_layout)],
            immediate_size: 0,
        });
        PipelineCache {
            device: device.clone(),
            modules: HashMap::new(),
            scene_layouts: HashMap::new(),
            scene_pipelines: HashMap::new(),
            pass_group_layout,
            pass_pipeline_layout,
            pass_pipelines: HashMap::new(),
            shadow_sampler,
            texture_groups: HashMap::new(),
            environment_layouts: HashMap::new(),
            backgrounds: HashMap::new(),
            transmission_group_layout: super::transmission::group_layout(device, false),
            traced_transmission_group_layout: super::transmission::group_layout(device, true),
            one_pipeline: false,
        }
    }

    /// The variants `key`'s pipelines are specialized to: each of its BRDF
    /// variants when it has several (each material's batch is drawn by the
    /// pipeline of its variant), else `None` (one pipeline, no switch).
    /// With [`Self::one_pipeline`], always `None`: the pipeline whose
    /// variant comes from the material (the switch). Why both: on a
    /// software rasterizer the switch runs every arm for every pixel, so
    /// frames are faster specialized (the viewer), but each pipeline costs
    /// a compilation, which a one-frame render pays once per variant
    /// (the cold `gonio render`).
    pub fn specializations(&self, key: &ShaderKey) -> Vec<Option<u32>> {
        if self.one_pipeline {
            vec![None]
        } else {
            key.specializations()
        }
    }

    /// Compiles (once) every pipeline `key` draws with into `format` (one
    /// per [`Self::specializations`]) and the layouts of its bindings.
    pub fn compile_scene(
        &mut self,
        key: &ShaderKey,
        layout: VertexLayout,
        format: wgpu::TextureFormat,
        samples: u32,
    ) -> Result<()> {
        for variant in self.specializations(key) {
            self.compile_scene_pipeline(key, layout, format, samples, (variant, false))?;
            if key.materials.alpha_blend {
                self.compile_scene_pipeline(key, layout, format, samples, (variant, true))?;
            }
        }
        Ok(())
    }

    /// A scene pipeline made by [`Self::compile_scene`].
    ///
    /// # Panics
    /// If it was not compiled.
    pub fn scene_pipeline(&self, key: &PipelineKey) -> &wgpu::RenderPipeline {
        &self.scene_pipelines[key]
    }

    /// The bind group and pipeline layouts of scenes whose arrays are
    /// bound as `arrays` says, made on first use.
    pub fn scene_layouts(&mut self, arrays: UniformArrays) -> &SceneLayouts {
        let device = &self.device;
        self.scene_layouts
            .entry(arrays)
            .or_insert_with(|| SceneLayouts::new(device, arrays))
    }

    /// Group 2's layout with `bindings` material textures
    /// ([`super::textures::group_layout`]), made on first use: sized per
    /// scene, as its shader declares them (every binding of a layout
    /// referenced by the shader: lavapipe 22.3 aborted, "stack smashing
    /// detected", drawing with a layout of 24 pairs and a shader reading 1).
    pub fn texture_group(&mut self, bindings: u32) -> &wgpu::BindGroupLayout {
        let device = &self.device;
        self.texture_groups
            .entry(bindings)
            .or_insert_with(|| super::textures::group_layout(device, bindings))
    }

    /// The layouts with the environment's group 3 for `arrays`, made on
    /// first use.
    pub fn environment_layouts(&mut self, arrays: UniformArrays) -> &EnvironmentLayouts {
        self.scene_layouts(arrays);
        let scene = &self.scene_layouts[&arrays];
        let device = &self.device;
        self.environment_layouts
            .entry(arrays)
            .or_insert_with(|| EnvironmentLayouts::new(device, scene))
    }

    /// The background pass's pipeline for scenes bound as `arrays`
    /// drawing into `format` with `samples`, compiled on first use.
    pub fn background(
        &mut self,
        arrays: UniformArrays,
        format: wgpu::TextureFormat,
        samples: u32,
        tone_map: crate::output::tone_map::ToneMap,
    ) -> Result<wgpu::RenderPipeline> {
        let cache_key = (arrays, format, samples, tone_map);
        if let Some(p) = self.backgrounds.get(&cache_key) {
            return Ok(p.clone());
        }
        self.environment_layouts(arrays);
        let layouts = &self.environment_layouts[&arrays];
        let pipeline = background_pipeline(&self.device, layouts, format, samples, tone_map)?;
        self.backgrounds.insert(cache_key, pipeline.clone());
        Ok(pipeline)
    }

    /// The comparison sampler of shadow-map bind groups.
    pub fn shadow_sampler(&self) -> &wgpu::Sampler {
        &self.shadow_sampler
    }

    /// The layout of group 4, the transmission image, with the traced
    /// exit's images when `traced` (the key's `transmission_exit_traced`).
    pub fn transmission_group_layout(&self, traced: bool) -> &wgpu::BindGroupLayout {
        if traced {
            &self.traced_transmission_group_layout
        } else {
            &self.transmission_group_layout
        }
    }

    /// The layout of the shadow passes' bind group (the layer views).
    pub fn shadow_pass_group_layout(&self) -> &wgpu::BindGroupLayout {
        &self.pass_group_layout
    }

    /// The WGSL module of `key` writing `output`, generated and checked on
    /// first use.
    fn module(&mut self, key: &ShaderKey, output: Output) -> Result<&wgpu::ShaderModule> {
        let module_key = (key.clone(), output);
        if !self.modules.contains_key(&module_key) {
            let wgsl = shader_gen::compose_for(key, output);
            if let Some(dir) = std::env::var_os(DUMP_WGSL_ENV) {
                dump_wgsl(Path::new(&dir), &module_key, &wgsl);
            }
            // naga validation first: a failure here is a bug in gonio, and
            // this way it is an error message, not a device panic.
            shader_gen::validate(&wgsl).map_err(|e| {
                Error::Gpu(format!(
                    "generated shader for {} is invalid: {e}",
                    key.describe()
                ))
            })?;
            let module = self
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("gonio scene shader"),
                    source: wgpu::ShaderSource::Wgsl(wgsl.into()),
                });
            self.modules.insert(module_key.clone(), module);
        }
        Ok(&self.modules[&module_key])
    }

    /// The pipeline for `key` drawing into `format`, specialized to
    /// `variant` (see [`Self::specializations`]), compiled on first use.
    fn compile_scene_pipeline(
        &mut self,
        key: &ShaderKey,
        layout: VertexLayout,
        format: wgpu::TextureFormat,
        samples: u32,
        (variant, blend): (Option<u32>, bool),
    ) -> Result<()> {
        let cache_key = (key.clone(), format, samples, variant, blend);
        if self.scene_pipelines.contains_key(&cache_key) {
            return Ok(());
        }
        let module = self.module(key, Output::for_format(format))?.clone();
        let constants = shader_gen::pipeline_constants(variant);
        self.scene_layouts(key.arrays);
        if key.environment.map {
            self.environment_layouts(key.arrays);
        }
        let textures = key.materials.texture_slots > 0;
        if textures {
            self.texture_group(key.materials.texture_bindings);
        }
        // Groups 0 to 4 as the key uses them, unused ones in between
        // empty, none after the last used.
        let layouts = &self.scene_layouts[&key.arrays];
        let mut groups = vec![
            Some(&layouts.scene_group),
            key.shadows.any().then_some(&layouts.shadow_group),
            textures.then(|| &self.texture_groups[&key.materials.texture_bindings]),
            key.environment
                .map
                .then(|| &self.environment_layouts[&key.arrays].group),
            key.materials
                .layer_transmission
                .then(|| self.transmission_group_layout(key.materials.transmission_exit_traced)),
        ];
        while groups.last() == Some(&None) {
            groups.pop();
        }
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("gonio scene"),
                bind_group_layouts: &groups,
                immediate_size: 0,
            });
        let pipeline = scene_pipeline(
            &self.device,
            &ScenePipeline {
                label: "gonio scene",
                module: &module,
                pipeline_layout: &pipeline_layout,
                stride: layout.stride(),
                attributes: &layout.attributes(),
                constants: &constants,
                format,
                samples,
                blend,
            },
        );
        self.scene_pipelines.insert(cache_key, pipeline);
        Ok(())
    }

    /// The renderer's scene pipeline (no shadows, `samples` 1) with the
    /// WGSL of `wgsl` instead of a generated module: `vs_main` / `fs_main`
    /// over the bindings of `shaders/common.wgsl` for `arrays`, reading
    /// the attributes of `stream` at locations below `locations` (all:
    /// `None`). Not cached: the bench times its compilation. `wgsl` must
    /// have passed [`shader_gen::validate`].
    pub fn with_shader(
        &mut self,
        label: &str,
        wgsl: &str,
        arrays: UniformArrays,
        stream: VertexLayout,
        locations: Option<u32>,
        format: wgpu::TextureFormat,
    ) -> wgpu::RenderPipeline {
        let attributes: Vec<wgpu::VertexAttribute> = stream
            .attributes()
            .into_iter()
            .filter(|a| locations.is_none_or(|n| a.shader_location < n))
            .collect();
        // The layouts first, so that what the caller may time is the
        // module and the pipeline.
        self.scene_layouts(arrays);
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            });
        scene_pipeline(
            &self.device,
            &ScenePipeline {
                label,
                module: &module,
                pipeline_layout: &self.scene_layouts[&arrays].plain,
                stride: stream.stride(),
                attributes: &attributes,
                constants: &[],
                format,
                samples: 1,
                blend: false,
            },
        )
    }

    /// Compiles (once) the depth-only pipeline of the shadow passes for a
    /// vertex stream of `stride` bytes.
    pub fn compile_shadow_pass(&mut self, stride: u64) {
        let device = &self.device;
        let layout = &self.pass_pipeline_layout;
        self.pass_pipelines
            .entry(stride)
            .or_insert_with(|| shadow_pass_pipeline(device, layout, stride));
    }

    /// A shadow pass pipeline made by [`Self::compile_shadow_pass`].
    ///
    /// # Panics
    /// If it was not compiled.
    pub fn shadow_pass(&self, stride: u64) -> &wgpu::RenderPipeline {
        &self.pass_pipelines[&stride]
    }
}

/// Writes a generated module to `dir` (named by the hash of its key);
/// says so on stderr when it cannot.
fn dump_wgsl(dir: &Path, module_key: &(ShaderKey, Output), wgsl: &str) {
    let name = format!("gonio-{:016x}.wgsl", {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        module_key.hash(&mut h);
        h.finish()
    });
    if let Err(e) = std::fs::write(dir.join(&name), wgsl) {
        eprintln!("{}", dump_warning(dir, &name, &e));
    }
}

/// The one line that says a module could not be dumped: the variable,
/// the file, the directory and the OS error.
fn dump_warning(dir: &Path, name: &str, error: &std::io::Error) -> String {
    format!(
        "warning: {DUMP_WGSL_ENV}: cannot write {name} into {}: {error}",
        dir.display()
    )
}

/// Everything a scene pipeline is made of that is not common to all.
struct ScenePipeline<'a> {
    label: &'a str,
    module: &'a wgpu::ShaderModule,
    pipeline_layout: &'a wgpu::PipelineLayout,
    stride: u64,
    attributes: &'a [wgpu::VertexAttribute],
    constants: &'a [(&'a str, f64)],
    format: wgpu::TextureFormat,
    samples: u32,
    /// Alpha BLEND: `L = a·L_s + (1 − a)·L_dst` (straight alpha, glTF's
    /// "over", as the Khronos sample viewer: SRC_ALPHA,
    /// ONE_MINUS_SRC_ALPHA), coverage `a + (1 − a)·a_dst`; the depth is
    /// tested, not written, so what lies behind stays drawable.
    blend: bool,
}

/// The scene pass's pipeline: `vs_main` / `fs_main`, both faces, depth
/// test; depth writes and no blending, or blending without depth writes
/// (`blend`).
fn scene_pipeline(device: &wgpu::Device, p: &ScenePipeline) -> wgpu::RenderPipeline {
    let compilation_options = wgpu::PipelineCompilationOptions {
        constants: p.constants,
        ..Default::default()
    };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(p.label),
        layout: Some(p.pipeline_layout),
        vertex: wgpu::VertexState {
            module: p.module,
            entry_point: Some("vs_main"),
            compilation_options: compilation_options.clone(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: p.stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: p.attributes,
            })],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            // Both faces are drawn, as the reference's rays hit both;
            // the one-sided BRDF leaves back faces to the ambient term.
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(!p.blend),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: wgpu::MultisampleState {
            count: p.samples,
            ..Default::default()
        },
        fragment: Some(wgpu::FragmentState {
            module: p.module,
            entry_point: Some("fs_main"),
            compilation_options,
            targets: &[Some(wgpu::ColorTargetState {
                format: p.format,
                blend: p.blend.then_some(wgpu::BlendState {
                    color: wgpu::BlendComponent {
                        src_factor: wgpu::BlendFactor::SrcAlpha,
                        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                        operation: wgpu::BlendOperation::Add,
                    },
                    alpha: wgpu::BlendComponent {
                        src_factor: wgpu::BlendFactor::One,
                        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                        operation: wgpu::BlendOperation::Add,
                    },
                }),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The depth-only pipeline of the shadow passes for a vertex stream of
/// `stride` bytes (position at offset 0): vertex shader only, reversed
/// depth (the nearest surface has the largest depth).
fn shadow_pass_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    stride: u64,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gonio shadow pass"),
        source: wgpu::ShaderSource::Wgsl(shader_gen::sources::get("shadow_pass.wgsl").into()),
    });
    let attributes = [wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x3,
        offset: 0,
        shader_location: 0,
    }];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("gonio shadow pass"),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_shadow"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attributes,
            })],
        },
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            front_face: wgpu::FrontFace::Ccw,
            // Every face occludes, as for the reference's rays.
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(shadow_depth_state()),
        multisample: Default::default(),
        fragment: None,
        multiview_mask: None,
        cache: None,
    })
}

/// The depth state of every shadow pass: reversed depth (the nearest
/// occluder, the largest value, wins), written.
pub fn shadow_depth_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: shadows::SHADOW_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Greater),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_dump_names_the_directory_and_the_os_error() {
        let dir = Path::new("/nonexistent/gonio-dump");
        let error = std::fs::write(dir.join("x.wgsl"), "").unwrap_err();
        let line = dump_warning(dir, "gonio-0.wgsl", &error);
        assert!(line.starts_with("warning: GONIO_DUMP_WGSL: "), "{line}");
        assert!(line.contains("/nonexistent/gonio-dump"), "{line}");
        assert!(line.contains(&error.to_string()), "{line}");
        assert!(!line.contains('\n'));
    }
}
