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

/// Textures a material can read, counted as glTF counts them: an image
/// with its sampler (bindings 1–6 textures, 7–12 samplers). Several
/// slots may read one binding (a metallic-roughness texture feeds two
/// parameters from two channels; an ORM texture three).
pub const MAX_TEXTURE_BINDINGS: usize = 6;

/// Texture reads (slots) a material can have: one per parameter a
/// texture scales, each with its UV set, transform and channel, and each
/// naming the binding it samples. A uniform array of 64-byte entries, so
/// room for the layered-material extensions' textures costs 1 KiB.
pub const MAX_TEXTURE_SLOTS: usize = 16;

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
    /// `1 + MAX_TEXTURE_BINDINGS + texture`).
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

/// Group 2's layout: the slots' uniform, the textures, the samplers.
pub fn group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
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
    for s in 0..MAX_TEXTURE_BINDINGS as u32 {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 1 + s,
            visibility: stage,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        });
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 1 + MAX_TEXTURE_BINDINGS as u32 + s,
            visibility: stage,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        });
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio material textures"),
        entries: &entries,
    })
}

/// The slots of one material: what the GPU multiplies, from the material
/// as rendered (roughness floor applied). An error when a texture names
/// a parameter the GPU cannot vary ([`texture_fields::gpu_field_mask`]) or a
/// material has more textures than slots.
pub fn material_slots(m: &crate::material::Material) -> Result<Vec<GpuTextureSlot>> {
    let bindings = material_bindings(m);
    if bindings.len() > MAX_TEXTURE_BINDINGS {
        return Err(Error::Scene(format!(
            "material `{}` reads {} distinct textures (image and sampler pairs); the GPU renderer binds at most {MAX_TEXTURE_BINDINGS} per material",
            m.name,
            bindings.len()
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
    /// Bytes of texels on the GPU (all levels).
    pub bytes: u64,
}

impl SceneTextures {
    /// Uploads `scene`'s images and makes every material's bind group
    /// with `layout` ([`group_layout`]).
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
        let materials = scene.effective_materials();
        let mut groups = Vec::with_capacity(materials.len());
        let mut slot_buffers = Vec::with_capacity(materials.len());
        let mut alpha_textures = Vec::with_capacity(materials.len());
        for m in &materials {
            let slots = material_slots(m)?;
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
            for s in 0..MAX_TEXTURE_BINDINGS {
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
                    binding: 1 + s as u32,
                    resource: wgpu::BindingResource::TextureView(view),
                });
                entries.push(wgpu::BindGroupEntry {
                    binding: 1 + (MAX_TEXTURE_BINDINGS + s) as u32,
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
        let slots = material_slots(material)?;
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
}
