//! Material textures on the GPU (bind group 2, `shaders/textures.wgsl`):
//! the scene's images uploaded once as `rgba16float` with their mip
//! chains (the half floats the CPU reference reads,
//! `scene::texture::Image`), one `wgpu::Sampler` per distinct glTF
//! sampler, and one bind group per material: its slots and reads in a
//! small uniform buffer (`slots.rs`), then a texture view and a sampler per
//! read (`wgsl.rs`; unused ones: a 1×1 white texel).
//!
//! Why `rgba16float`: colour textures must be filtered after the sRGB
//! decode (glTF 2.0 §3.9.6), which an 8-bit linear format would quantize
//! in the darks, and `rgba8unorm-srgb` decodes with the GPU's own
//! approximation; f16 holds the exactly decoded values to 2⁻¹¹ relative,
//! and the CPU reference reads the very same halves. 8 bytes per texel,
//! × 4/3 for the mips.

mod budget;
mod slots;
mod wgsl;

pub use budget::{MAX_TEXTURE_SLOTS, OTHER_GROUPS, StageBindings, TextureBudget};

pub use slots::{
    ANISOTROPY_MAP_CHANNEL, CLEARCOAT_NORMAL_MAP_CHANNEL, GpuTextureRead, GpuTextureSlot,
    MaterialTextureUniform, NORMAL_MAP_CHANNEL, TextureRead, UNIFORM_BYTES, material_reads,
    material_slots, read_bindings,
};
pub use wgsl::{group_layout, sampler_binding, texture_binding, wgsl_bindings};

use super::context::GpuContext;
use crate::material::texture::{Filter, Sampler, Wrap};
use crate::scene::Scene;
use crate::scene::texture::Image;
use crate::{Error, Result};
use std::collections::HashMap;
use wgpu::util::DeviceExt;

/// The format of every texture.
pub const TEXTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

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
        .map(|m| material_reads(&scene.materials[m.material]).len())
        .max()
        .map(|n| n.min(MAX_TEXTURE_SLOTS) as u32)
        .unwrap_or(0)
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

/// An image's texture with every level written, each straight from its
/// level's texels (no flattened copy of the whole chain first: for
/// DamagedHelmet's five 2048² images that copy was 225 MB more to
/// allocate and write before the upload).
fn upload(ctx: &GpuContext, image: &Image) -> wgpu::Texture {
    let base = &image.levels[0];
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
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
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let texel_bytes = std::mem::size_of::<[u16; 4]>() as u32;
    for (mip_level, level) in image.levels.iter().enumerate() {
        ctx.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: mip_level as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(&level.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(level.width * texel_bytes),
                rows_per_image: Some(level.height),
            },
            wgpu::Extent3d {
                width: level.width,
                height: level.height,
                depth_or_array_layers: 1,
            },
        );
    }
    texture
}

/// One material's slots on the GPU, what they hold, and the bindings its
/// group was made with.
struct MaterialSlots {
    buffer: wgpu::Buffer,
    held: MaterialTextureUniform,
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
                contents: &slots.bytes(),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }];
            let bindings = read_bindings(m);
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
        if read_bindings(material) != *bindings {
            return Ok(None);
        }
        let slots = material_slots(material, &self.budget)?;
        if slots == *held {
            return Ok(Some(0));
        }
        let bytes = slots.bytes();
        queue.write_buffer(buffer, 0, &bytes);
        *held = slots;
        Ok(Some(bytes.len() as u64))
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
