//! Material textures on the GPU (bind group 2, `shaders/textures.wgsl`):
//! the scene's images uploaded once as `rgba16float` with their mip
//! chains (the half floats the CPU reference reads,
//! `scene::texture::Image`), one `wgpu::Sampler` per distinct glTF
//! sampler, and one bind group per material: its slots' transforms,
//! UV sets and field masks in a small uniform buffer, then a texture view
//! and a sampler per slot (unused slots: a 1×1 white texel).
//!
//! Why `rgba16float`: colour textures must be filtered after the sRGB
//! decode (glTF 2.0 §3.9.6), which an 8-bit linear format would quantize
//! in the darks, and `rgba8unorm-srgb` decodes with the GPU's own
//! approximation; f16 holds the exactly decoded values to 2⁻¹¹ relative,
//! and the CPU reference reads the very same halves. 8 bytes per texel,
//! × 4/3 for the mips.

use super::context::GpuContext;
use crate::material::texture::{Filter, Sampler, TextureTarget, Wrap};
use crate::material::texture_fields;
use crate::scene::Scene;
use crate::scene::texture::Image;
use crate::{Error, Result};
use bytemuck::{Pod, Zeroable};
use std::collections::HashMap;
use wgpu::util::DeviceExt;

/// Texture reads (slots) a material can have: one per parameter a
/// texture scales, each with its UV set, transform and channel, and each
/// naming the binding it samples. The core material names 6 (base colour,
/// metallic, roughness, normal, occlusion, emission) and the layer
/// extensions 14 more (coat 3, sheen 2, specular 2, transmission,
/// thickness, iridescence 2, anisotropy, diffuse transmission 2): 24 holds
/// all 20 with room. A uniform array of 64-byte entries (1.5 KiB).
pub const MAX_TEXTURE_SLOTS: usize = 24;

/// Sampled textures and samplers that the other groups of a scene
/// pipeline bind in each stage, which a material's textures share the
/// device's per-stage limits with: shadows (group 1: the map array and its
/// comparison sampler), the environment (group 3: the map, the prefiltered
/// stack and the DFG table) and transmission (group 4: the image and its
/// sampler). The test below holds these against the groups' layouts.
pub const OTHER_GROUPS: StageBindings = StageBindings {
    textures: 5,
    samplers: 2,
};

/// Sampled textures and samplers bound in one shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StageBindings {
    pub textures: u32,
    pub samplers: u32,
}

/// Textures a material can bind on one device, counted as glTF counts
/// them: an image with its sampler (group 2: [`texture_binding`],
/// [`sampler_binding`]). Several slots may read one binding (a
/// metallic-roughness texture feeds two parameters from two channels; an
/// ORM texture three). Bounded by the device's real per-stage limits
/// (gonio requests the adapter's own, `GpuContext`) less what the other
/// groups take ([`OTHER_GROUPS`]), and by the slots: WebGPU's guaranteed
/// 16 and 16 leave 11, lavapipe and desktop Vulkan drivers all 24.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureBudget {
    /// Image and sampler pairs one material binds.
    pub bindings: usize,
    /// The device's limits this was derived from.
    pub limits: StageBindings,
}

impl TextureBudget {
    /// The budget under a device's `limits`.
    pub fn for_limits(limits: &wgpu::Limits) -> Self {
        let limits = StageBindings {
            textures: limits.max_sampled_textures_per_shader_stage,
            samplers: limits.max_samplers_per_shader_stage,
        };
        let free = limits
            .textures
            .saturating_sub(OTHER_GROUPS.textures)
            .min(limits.samplers.saturating_sub(OTHER_GROUPS.samplers));
        TextureBudget {
            bindings: (free as usize).min(MAX_TEXTURE_SLOTS),
            limits,
        }
    }

    /// Why the budget is what it is, for a refusal.
    pub fn explained(&self) -> String {
        if self.bindings == MAX_TEXTURE_SLOTS {
            return format!("gonio binds at most {MAX_TEXTURE_SLOTS} per material");
        }
        format!(
            "this GPU binds at most {} per material ({} sampled textures and {} samplers per shader stage, of which shadows, the environment and transmission take {} and {})",
            self.bindings,
            self.limits.textures,
            self.limits.samplers,
            OTHER_GROUPS.textures,
            OTHER_GROUPS.samplers
        )
    }
}

/// The format of every texture.
pub const TEXTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// `TextureSlot` of `shaders/textures.wgsl` (64 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuTextureSlot {
    pub row_u: [f32; 4],
    pub row_v: [f32; 4],
    pub fields: u32,
    pub channel: u32,
    pub tex_coord: u32,
    /// The factor's strength (`TextureTarget::with_strength`): 1 for a
    /// parameter, glTF's `strength` for occlusion, `scale` for a normal
    /// map.
    pub strength: f32,
    /// 1: the texel's A multiplies the material's alpha
    /// (`MaterialTexture::carries_alpha`).
    pub alpha: u32,
    /// The material's binding this slot samples
    /// ([`material_bindings`]: texture `1 + texture`, sampler
    /// [`sampler_binding`] of it).
    pub texture: u32,
    /// `(cos r, sin r)` of the transform's rotation (a normal map's
    /// normal turns with it: `material::texture::rotated_normal`).
    pub rotation: [f32; 2],
}

/// `channel` of a normal-map slot (0–3: a scalar's channel, 4: RGB).
pub const NORMAL_MAP_CHANNEL: u32 = 5;
/// `channel` of the coat's normal map (`TextureTarget::ClearcoatNormal`).
pub const CLEARCOAT_NORMAL_MAP_CHANNEL: u32 = 6;
/// `channel` of the anisotropy map (`TextureTarget::Anisotropy`).
pub const ANISOTROPY_MAP_CHANNEL: u32 = 7;

/// Whether a material the scene draws has a normal map (feature
/// `normal_map`: tangents and their signs in the vertex stream).
pub fn has_normal_maps(scene: &Scene) -> bool {
    scene
        .meshes
        .iter()
        .any(|m| crate::scene::tangents::normal_map_set(&scene.materials[m.material]).is_some())
}

/// The most textures one material the scene draws has (the shader's
/// `TEXTURE_SLOTS`).
pub fn slot_count(scene: &Scene) -> u32 {
    scene
        .meshes
        .iter()
        .map(|m| scene.materials[m.material].textures.len())
        .max()
        .unwrap_or(0)
        .min(MAX_TEXTURE_SLOTS) as u32
}

/// The most image and sampler pairs one material the scene draws binds
/// (the shader's `TEXTURE_BINDINGS`: it declares and reads that many of
/// group 2's bindings, [`wgsl_bindings`]).
pub fn binding_count(scene: &Scene) -> u32 {
    scene
        .meshes
        .iter()
        .map(|m| material_bindings(&scene.materials[m.material]).len())
        .max()
        .filter(|&n| n > 0)
        .map(|n| n.clamp(MIN_TEXTURE_BINDINGS, MAX_TEXTURE_SLOTS) as u32)
        .unwrap_or(0)
}

/// The fewest pairs a textured scene's group 2 has: with one, lavapipe
/// (Mesa 22.3.6) aborts ("stack smashing detected", in its queue thread)
/// drawing the coat-normal-map scene of tests/layers_gpu.rs
/// (`layer_maps_and_textures_render_like_the_reference`); with two or more
/// it draws it as the reference does. A second pair costs one bind of the
/// white texel.
pub const MIN_TEXTURE_BINDINGS: usize = 2;

/// Group 2's binding of material texture `i`: the pairs follow the slots'
/// uniform (binding 0), texture then sampler, so a layout of `n` pairs
/// has bindings 0 to `2n`.
pub fn texture_binding(i: u32) -> u32 {
    1 + 2 * i
}

/// Group 2's binding of material texture `i`'s sampler.
pub fn sampler_binding(i: u32) -> u32 {
    2 + 2 * i
}

/// The WGSL of group 2's first `n` textures and samplers and the two
/// functions that sample binding `i` (`slot_texel`, with the pixel's UV
/// derivatives, and `slot_texel_level0`, for the vertex stage). WGSL
/// cannot index separate bindings, hence one `switch` case per binding;
/// generated because the count is the scene's ([`binding_count`]).
/// Used by `shaders/textures.wgsl`, which documents the functions.
pub fn wgsl_bindings(n: u32) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    for i in 0..n {
        let _ = writeln!(
            out,
            "@group(2) @binding({}) var slot_texture_{i}: texture_2d<f32>;",
            texture_binding(i)
        );
        let _ = writeln!(
            out,
            "@group(2) @binding({}) var slot_sampler_{i}: sampler;",
            sampler_binding(i)
        );
    }
    for (name, parameters, call) in [
        (
            "slot_texel",
            "uv: vec2<f32>, ddx: vec2<f32>, ddy: vec2<f32>",
            "textureSampleGrad(slot_texture_{i}, slot_sampler_{i}, uv, ddx, ddy)",
        ),
        (
            "slot_texel_level0",
            "uv: vec2<f32>",
            "textureSampleLevel(slot_texture_{i}, slot_sampler_{i}, uv, 0.0)",
        ),
    ] {
        let _ = writeln!(out, "fn {name}(i: u32, {parameters}) -> vec4<f32> {{");
        let _ = writeln!(out, "    switch i {{");
        for i in 0..n {
            let call = call.replace("{i}", &i.to_string());
            let _ = writeln!(out, "        case {i}u: {{ return {call}; }}");
        }
        let _ = writeln!(
            out,
            "        default: {{ return vec4<f32>(1.0); }}\n    }}\n}}"
        );
    }
    out
}

/// Group 2's layout: the slots' uniform, then `bindings` textures and
/// samplers (the scene's [`binding_count`], which its shader declares).
pub fn group_layout(device: &wgpu::Device, bindings: u32) -> wgpu::BindGroupLayout {
    let stage = wgpu::ShaderStages::VERTEX_FRAGMENT;
    let mut entries = vec![wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: stage,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }];
    for s in 0..bindings {
        entries.push(super::layout_entries::filterable_texture_2d(
            texture_binding(s),
            stage,
        ));
        entries.push(super::layout_entries::filtering_sampler(
            sampler_binding(s),
            stage,
        ));
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio material textures"),
        entries: &entries,
    })
}

/// The slots of one material: what the GPU multiplies, from the material
/// as rendered (roughness floor applied). An error when a texture names
/// a parameter the GPU cannot vary ([`texture_fields::gpu_field_mask`]) or a
/// material has more textures than the device binds or than slots.
pub fn material_slots(
    m: &crate::material::Material,
    budget: &TextureBudget,
) -> Result<Vec<GpuTextureSlot>> {
    let bindings = material_bindings(m);
    if bindings.len() > budget.bindings {
        return Err(Error::Scene(format!(
            "material `{}` reads {} distinct textures (image and sampler pairs); {} (`--reference` renders it)",
            m.name,
            bindings.len(),
            budget.explained()
        )));
    }
    if m.textures.len() > MAX_TEXTURE_SLOTS {
        return Err(Error::Scene(format!(
            "material `{}` has {} textured parameters; the GPU renderer reads at most {MAX_TEXTURE_SLOTS} per material",
            m.name,
            m.textures.len()
        )));
    }
    let mut slots = vec![GpuTextureSlot::default(); MAX_TEXTURE_SLOTS];
    for (slot, t) in slots.iter_mut().zip(&m.textures) {
        let texture = bindings
            .iter()
            .position(|b| *b == (t.image, t.sampler))
            .expect("every texture's binding is listed") as u32;
        let matrix = t.transform.matrix();
        let row = |r: usize| {
            [
                matrix.x_axis[r] as f32,
                matrix.y_axis[r] as f32,
                matrix.z_axis[r] as f32,
                0.0,
            ]
        };
        // A texture on a zero constant changes nothing: 0 fields is
        // an unused slot, which is the same.
        let (fields, channel, strength) = match t.target {
            TextureTarget::Param(key) => {
                let fields = texture_fields::gpu_field_mask(m, key)
                    .map_err(|e| Error::Scene(format!("material `{}`: {e}", m.name)))?;
                let colour = matches!(
                    crate::material::table::param_for(m.model, key).map(|p| p.kind),
                    Some(crate::material::param::Kind::Color)
                );
                (fields, if colour { 4 } else { t.channel as u32 }, 1.0)
            }
            // Material.occlusion (gpu_field_values' order), from R.
            TextureTarget::Occlusion { strength } => {
                (texture_fields::OCCLUSION_FIELD, 0, strength as f32)
            }
            TextureTarget::Normal { scale } => (0, NORMAL_MAP_CHANNEL, scale as f32),
            TextureTarget::ClearcoatNormal { scale } => {
                (0, CLEARCOAT_NORMAL_MAP_CHANNEL, scale as f32)
            }
            TextureTarget::Anisotropy => (0, ANISOTROPY_MAP_CHANNEL, 1.0),
        };
        *slot = GpuTextureSlot {
            row_u: row(0),
            row_v: row(1),
            fields,
            channel,
            tex_coord: t.tex_coord as u32,
            strength,
            alpha: u32::from(t.carries_alpha()),
            texture,
            rotation: if t.transform.rotation == 0.0 {
                [1.0, 0.0]
            } else {
                let (s, c) = t.transform.rotation.sin_cos();
                [c as f32, s as f32]
            },
        };
    }
    Ok(slots)
}

/// The textures material `m` binds: each distinct image and sampler
/// pair its slots read, in the order of first use (what glTF counts as
/// its textures: DamagedHelmet's five images are five bindings for six
/// textured parameters).
pub fn material_bindings(m: &crate::material::Material) -> Vec<(usize, Sampler)> {
    let mut bindings: Vec<(usize, Sampler)> = Vec::new();
    for t in &m.textures {
        if !bindings.contains(&(t.image, t.sampler)) {
            bindings.push((t.image, t.sampler));
        }
    }
    bindings
}

/// The sampler descriptor of a glTF sampler. Without mipmaps the view is
/// one level (see [`SceneTextures`]), so the mipmap filter is moot.
fn sampler_descriptor(s: &Sampler) -> wgpu::SamplerDescriptor<'static> {
    let address = |w: Wrap| match w {
        Wrap::Repeat => wgpu::AddressMode::Repeat,
        Wrap::ClampToEdge => wgpu::AddressMode::ClampToEdge,
        Wrap::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
    };
    let filter = |f: Filter| match f {
        Filter::Nearest => wgpu::FilterMode::Nearest,
        Filter::Linear => wgpu::FilterMode::Linear,
    };
    let mipmap = match s.mipmap {
        Some(Filter::Linear) => wgpu::MipmapFilterMode::Linear,
        _ => wgpu::MipmapFilterMode::Nearest,
    };
    wgpu::SamplerDescriptor {
        label: Some("gonio material texture"),
        address_mode_u: address(s.wrap_u),
        address_mode_v: address(s.wrap_v),
        mag_filter: filter(s.mag),
        min_filter: filter(s.min),
        mipmap_filter: mipmap,
        ..Default::default()
    }
}

/// An image's texture with every level written.
fn upload(ctx: &GpuContext, image: &Image) -> wgpu::Texture {
    let base = &image.levels[0];
    let texels: Vec<u16> = image
        .levels
        .iter()
        .flat_map(|l| l.texels.iter().flatten().copied())
        .collect();
    ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some(&image.name),
            size: wgpu::Extent3d {
                width: base.width,
                height: base.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: image.levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: TEXTURE_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&texels),
    )
}

/// One material's slots on the GPU, what they hold, and the bindings its
/// group was made with.
struct MaterialSlots {
    buffer: wgpu::Buffer,
    held: Vec<GpuTextureSlot>,
    bindings: Vec<(usize, Sampler)>,
}

/// A scene's textures on the GPU and each material's group 2.
pub struct SceneTextures {
    /// One bind group per scene material (index for index).
    groups: Vec<wgpu::BindGroup>,
    /// Per scene material, its slots' uniform buffer and what it holds,
    /// and the bindings its group was made with: an edit of the material
    /// rewrites the slots in place ([`Self::write_slots`]) while the
    /// bindings stay.
    slots: Vec<MaterialSlots>,
    /// Per scene material, the view and sampler of its texture that
    /// carries alpha (the base colour's), for the masked shadow pass
    /// (src/gpu/shadow_masks.rs).
    alpha_textures: Vec<Option<(wgpu::TextureView, wgpu::Sampler)>>,
    /// The device's budget the groups were made under.
    budget: TextureBudget,
    /// Bytes of texels on the GPU (all levels).
    pub bytes: u64,
}

impl SceneTextures {
    /// Uploads `scene`'s images and makes every material's bind group
    /// with `layout` ([`group_layout`] of the scene's [`binding_count`]
    /// pairs).
    pub fn new(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, scene: &Scene) -> Result<Self> {
        let device = &ctx.device;
        // Decoding caps a side at MAX_TEXTURE_SIDE (8192); an adapter may
        // allow less (WebGPU's guaranteed minimum is 8192, downlevel GL
        // adapters 2048): checked before creating any texture.
        let max = device.limits().max_texture_dimension_2d;
        if let Some(image) = scene.images.iter().find(|i| {
            let base = &i.levels[0];
            base.width > max || base.height > max
        }) {
            let base = &image.levels[0];
            return Err(crate::Error::Scene(format!(
                "the texture {} is {}×{} texels; the GPU adapter `{}` allows at most {max} per side: scale the image down",
                image.name, base.width, base.height, ctx.adapter_info.name
            )));
        }
        let textures: Vec<wgpu::Texture> = scene.images.iter().map(|i| upload(ctx, i)).collect();
        let full: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        // Level 0 alone, for samplers without mipmaps (glTF minFilter
        // NEAREST or LINEAR): the view clamps the level, the sampler still
        // chooses the mag or min filter from the true footprint.
        let base: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| {
                t.create_view(&wgpu::TextureViewDescriptor {
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let white = upload(
            ctx,
            &Image::new(
                "white",
                crate::scene::texture::Encoding::Linear,
                crate::scene::texture::decode::Decoded {
                    width: 1,
                    height: 1,
                    rgba: vec![[1.0; 4]],
                },
            ),
        )
        .create_view(&Default::default());
        let mut samplers: HashMap<Sampler, wgpu::Sampler> = HashMap::new();
        let default_sampler = device.create_sampler(&sampler_descriptor(&Sampler::default()));
        let budget = TextureBudget::for_limits(&device.limits());
        // The layout's pairs: as many as the most textured material drawn
        // reads (a material not drawn may read more; its group is made
        // but never bound).
        let bound = binding_count(scene) as usize;
        if bound > budget.bindings {
            return Err(Error::Scene(format!(
                "the scene's textured materials need {bound} texture bindings; {}",
                budget.explained()
            )));
        }
        let materials = scene.effective_materials();
        let mut groups = Vec::with_capacity(materials.len());
        let mut slot_buffers = Vec::with_capacity(materials.len());
        let mut alpha_textures = Vec::with_capacity(materials.len());
        for m in &materials {
            let slots = material_slots(m, &budget)?;
            for t in &m.textures {
                samplers
                    .entry(t.sampler)
                    .or_insert_with(|| device.create_sampler(&sampler_descriptor(&t.sampler)));
            }
            alpha_textures.push(
                m.textures
                    .iter()
                    .find(|t| t.carries_alpha())
                    .map(|t| (full[t.image].clone(), samplers[&t.sampler].clone())),
            );
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("gonio texture slots"),
                contents: bytemuck::cast_slice(&slots),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }];
            let bindings = material_bindings(m);
            for s in 0..bound {
                let (view, sampler) = match bindings.get(s) {
                    Some((image, sampler)) => (
                        if sampler.mipmap.is_some() {
                            &full[*image]
                        } else {
                            &base[*image]
                        },
                        &samplers[sampler],
                    ),
                    None => (&white, &default_sampler),
                };
                entries.push(wgpu::BindGroupEntry {
                    binding: texture_binding(s as u32),
                    resource: wgpu::BindingResource::TextureView(view),
                });
                entries.push(wgpu::BindGroupEntry {
                    binding: sampler_binding(s as u32),
                    resource: wgpu::BindingResource::Sampler(sampler),
                });
            }
            groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("gonio material textures"),
                layout,
                entries: &entries,
            }));
            slot_buffers.push(MaterialSlots {
                buffer,
                held: slots,
                bindings,
            });
        }
        Ok(SceneTextures {
            groups,
            slots: slot_buffers,
            alpha_textures,
            budget,
            bytes: scene.images.iter().map(|i| i.gpu_bytes()).sum(),
        })
    }

    /// Rewrites the slots of material `m` (as rendered: roughness floor
    /// applied) after an edit, if they changed: returns the bytes written
    /// (0 when they are as they were), or `None` when the edit changed
    /// which images or samplers the material reads, which its bind group
    /// holds (the textures are then made anew).
    pub fn write_slots(
        &mut self,
        queue: &wgpu::Queue,
        m: usize,
        material: &crate::material::Material,
    ) -> Result<Option<u64>> {
        let Some(MaterialSlots {
            buffer,
            held,
            bindings,
        }) = self.slots.get_mut(m)
        else {
            return Ok(None);
        };
        if material_bindings(material) != *bindings {
            return Ok(None);
        }
        let slots = material_slots(material, &self.budget)?;
        if bytemuck::cast_slice::<_, u8>(&slots) == bytemuck::cast_slice::<_, u8>(held) {
            return Ok(Some(0));
        }
        queue.write_buffer(buffer, 0, bytemuck::cast_slice(&slots));
        *held = slots;
        Ok(Some(size_of_val(held.as_slice()) as u64))
    }

    /// Group 2 of material `m`.
    pub fn group(&self, m: u32) -> &wgpu::BindGroup {
        &self.groups[m as usize]
    }

    /// The view (all levels) and sampler of material `m`'s texture that
    /// carries alpha, if it has one.
    pub fn alpha_texture(&self, m: usize) -> Option<(&wgpu::TextureView, &wgpu::Sampler)> {
        self.alpha_textures
            .get(m)
            .and_then(Option::as_ref)
            .map(|(v, s)| (v, s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slot_mirrors_the_wgsl_size() {
        assert_eq!(size_of::<GpuTextureSlot>(), 64);
        let key = crate::gpu::shader_gen::ShaderKey {
            variants: [crate::material::Material::new(
                "m",
                crate::material::ReflectanceModel::Lambert,
            )
            .variant()]
            .into(),
            materials: crate::gpu::shader_gen::MaterialsKey {
                texture_slots: 1,
                texture_bindings: 1,
                ..Default::default()
            },
            ..Default::default()
        };
        let wgsl = crate::gpu::shader_gen::compose(&key);
        let module = naga::front::wgsl::parse_str(&wgsl).unwrap();
        let ty = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("TextureSlot"))
            .unwrap()
            .1;
        assert_eq!(ty.inner.size(module.to_ctx()), 64);
    }

    /// Sampled textures and samplers among a group's entries.
    fn stage_bindings(entries: &[wgpu::BindGroupLayoutEntry]) -> StageBindings {
        let count = |test: fn(&wgpu::BindingType) -> bool| {
            entries.iter().filter(|e| test(&e.ty)).count() as u32
        };
        StageBindings {
            textures: count(|t| matches!(t, wgpu::BindingType::Texture { .. })),
            samplers: count(|t| matches!(t, wgpu::BindingType::Sampler(_))),
        }
    }

    #[test]
    fn the_other_groups_take_what_their_layouts_bind() {
        let arrays = crate::gpu::bindings::UniformArrays {
            lights: true,
            shadow_views: true,
            measured: false,
            sheen: false,
        };
        let groups = [
            stage_bindings(&crate::gpu::bind_groups::shadow_group_entries(arrays)),
            stage_bindings(&crate::gpu::environment::group_entries()),
            stage_bindings(&crate::gpu::transmission::group_entries()),
        ];
        let sum = StageBindings {
            textures: groups.iter().map(|g| g.textures).sum(),
            samplers: groups.iter().map(|g| g.samplers).sum(),
        };
        assert_eq!(sum, OTHER_GROUPS);
    }

    #[test]
    fn the_budget_is_the_devices_limits_less_the_other_groups() {
        // WebGPU's guaranteed limits: 16 and 16, less 5 and 2.
        let webgpu = TextureBudget::for_limits(&wgpu::Limits::default());
        assert_eq!(webgpu.bindings, 11);
        assert!(
            webgpu.explained().contains("at most 11"),
            "{}",
            webgpu.explained()
        );
        // Samplers scarcer than textures bound it.
        let few_samplers = wgpu::Limits {
            max_samplers_per_shader_stage: 8,
            ..wgpu::Limits::default()
        };
        assert_eq!(TextureBudget::for_limits(&few_samplers).bindings, 6);
        // A generous driver is bounded by the slots.
        let generous = wgpu::Limits {
            max_sampled_textures_per_shader_stage: 1 << 20,
            max_samplers_per_shader_stage: 1 << 20,
            ..wgpu::Limits::default()
        };
        assert_eq!(
            TextureBudget::for_limits(&generous).bindings,
            MAX_TEXTURE_SLOTS
        );
        // A device below the other groups' needs binds none, without
        // wrapping around.
        let starved = wgpu::Limits {
            max_sampled_textures_per_shader_stage: 4,
            ..wgpu::Limits::default()
        };
        assert_eq!(TextureBudget::for_limits(&starved).bindings, 0);
    }

    #[test]
    fn a_material_past_the_budget_is_refused_with_what_fits() {
        let mut m =
            crate::material::Material::new("many", crate::material::ReflectanceModel::GltfPbr);
        for image in 0..3 {
            m.textures.push(crate::material::texture::MaterialTexture {
                target: TextureTarget::Param("base_color"),
                image,
                channel: 0,
                tex_coord: 0,
                transform: Default::default(),
                sampler: Sampler::default(),
            });
        }
        let two = TextureBudget {
            bindings: 2,
            limits: StageBindings {
                textures: 7,
                samplers: 16,
            },
        };
        let e = material_slots(&m, &two).unwrap_err().to_string();
        assert!(e.contains("`many` reads 3 distinct textures"), "{e}");
        assert!(e.contains("binds at most 2 per material"), "{e}");
        assert!(e.contains("7 sampled textures"), "{e}");
        assert!(material_slots(&m, &TextureBudget { bindings: 3, ..two }).is_ok());
    }

    #[test]
    fn generated_bindings_declare_and_read_each_pair() {
        let wgsl = wgsl_bindings(3);
        for i in 0..3 {
            assert!(wgsl.contains(&format!("@binding({}) var slot_texture_{i}:", 1 + 2 * i)));
            assert!(wgsl.contains(&format!("@binding({}) var slot_sampler_{i}:", 2 + 2 * i)));
        }
        assert!(!wgsl.contains("slot_texture_3"));
        assert_eq!(wgsl.matches("case 2u").count(), 2);
    }
}
