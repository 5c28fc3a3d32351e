//! One material's textures as the shader reads them (group 2's uniform,
//! `TextureSlots` of `shaders/textures.wgsl`): its reads (an image with
//! its sampler, UV set and transform: one texture as glTF counts it,
//! sampled once per pixel) and its slots (a read's texel applied to the
//! fields of one parameter, from one channel).

use super::budget::{MAX_TEXTURE_SLOTS, TextureBudget};
use crate::material::texture::{MaterialTexture, Sampler, TextureTarget, UvTransform};
use crate::material::texture_fields;
use crate::{Error, Result};
use bytemuck::{Pod, Zeroable};

/// `TextureSlot` of `shaders/textures.wgsl` (32 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTextureSlot {
    pub fields: u32,
    pub channel: u32,
    /// The factor's strength (`TextureTarget::with_strength`): 1 for a
    /// parameter, glTF's `strength` for occlusion, `scale` for a normal
    /// map.
    pub strength: f32,
    /// 1: the texel's A multiplies the material's alpha
    /// (`MaterialTexture::carries_alpha`).
    pub alpha: u32,
    /// The read whose texel this slot takes ([`material_reads`]; texture
    /// [`super::texture_binding`] of it).
    pub texture: u32,
    pub _pad: u32,
    /// `(cos r, sin r)` of the read's transform's rotation (a normal map's
    /// normal turns with it: `material::texture::rotated_normal`).
    pub rotation: [f32; 2],
}

/// `TextureRead` of `shaders/textures.wgsl` (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTextureRead {
    /// The transform's rows: `u' = row_u · (u, v, 1)`.
    pub row_u: [f32; 4],
    pub row_v: [f32; 4],
    pub tex_coord: u32,
    pub _pad: [u32; 3],
}

/// The uniform of one material's group 2: every slot, then every read
/// (unused ones zero).
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTextureUniform {
    pub slots: [GpuTextureSlot; MAX_TEXTURE_SLOTS],
    pub reads: [GpuTextureRead; MAX_TEXTURE_SLOTS],
}

/// Bytes of [`MaterialTextureUniform`] on the GPU.
pub const UNIFORM_BYTES: usize =
    MAX_TEXTURE_SLOTS * (size_of::<GpuTextureSlot>() + size_of::<GpuTextureRead>());

impl MaterialTextureUniform {
    /// The uniform buffer's bytes.
    pub fn bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(UNIFORM_BYTES);
        out.extend_from_slice(bytemuck::cast_slice(&self.slots));
        out.extend_from_slice(bytemuck::cast_slice(&self.reads));
        out
    }
}

/// `channel` of a normal-map slot (0–3: a scalar's channel, 4: RGB).
pub const NORMAL_MAP_CHANNEL: u32 = 5;
/// `channel` of the coat's normal map (`TextureTarget::ClearcoatNormal`).
pub const CLEARCOAT_NORMAL_MAP_CHANNEL: u32 = 6;
/// `channel` of the anisotropy map (`TextureTarget::Anisotropy`).
pub const ANISOTROPY_MAP_CHANNEL: u32 = 7;

/// One texture as glTF counts it: an image read through a sampler at a
/// UV set and transform. The textures of a material that agree on all
/// four are one read (DamagedHelmet's metallic-roughness texture feeds
/// two parameters; an ORM texture three).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRead {
    pub image: usize,
    pub sampler: Sampler,
    pub tex_coord: usize,
    pub transform: UvTransform,
}

impl TextureRead {
    fn of(t: &MaterialTexture) -> Self {
        TextureRead {
            image: t.image,
            sampler: t.sampler,
            tex_coord: t.tex_coord,
            transform: t.transform,
        }
    }

    /// What its binding holds: the image and sampler.
    pub fn binding(&self) -> (usize, Sampler) {
        (self.image, self.sampler)
    }

    fn gpu(&self) -> GpuTextureRead {
        let matrix = self.transform.matrix();
        let row = |r: usize| {
            [
                matrix.x_axis[r] as f32,
                matrix.y_axis[r] as f32,
                matrix.z_axis[r] as f32,
                0.0,
            ]
        };
        GpuTextureRead {
            row_u: row(0),
            row_v: row(1),
            tex_coord: self.tex_coord as u32,
            _pad: [0; 3],
        }
    }
}

/// The reads of material `m`: each distinct image, sampler, UV set and
/// transform its textures name, in the order of first use (DamagedHelmet's
/// five images are five reads for six textured parameters).
pub fn material_reads(m: &crate::material::Material) -> Vec<TextureRead> {
    let mut reads: Vec<TextureRead> = Vec::new();
    for t in &m.textures {
        let read = TextureRead::of(t);
        if !reads.contains(&read) {
            reads.push(read);
        }
    }
    reads
}

/// What the bind group of material `m` holds, read by read: each read's
/// image and sampler (a read's UV set and transform are in the uniform).
pub fn read_bindings(m: &crate::material::Material) -> Vec<(usize, Sampler)> {
    material_reads(m).iter().map(TextureRead::binding).collect()
}

/// The slots and reads of one material: what the GPU multiplies, from the
/// material as rendered (roughness floor applied). An error when a
/// texture names a parameter the GPU cannot vary
/// ([`texture_fields::gpu_field_mask`]) or a material has more reads than
/// the device binds or more textures than slots.
pub fn material_slots(
    m: &crate::material::Material,
    budget: &TextureBudget,
) -> Result<MaterialTextureUniform> {
    let reads = material_reads(m);
    if reads.len() > budget.bindings {
        return Err(Error::Scene(format!(
            "material `{}` reads {} distinct textures (image, sampler, UV set and transform); {} (`--reference` renders it)",
            m.name,
            reads.len(),
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
    let mut uniform = MaterialTextureUniform {
        slots: [GpuTextureSlot::default(); MAX_TEXTURE_SLOTS],
        reads: [GpuTextureRead::default(); MAX_TEXTURE_SLOTS],
    };
    for (gpu, read) in uniform.reads.iter_mut().zip(&reads) {
        *gpu = read.gpu();
    }
    for (slot, t) in uniform.slots.iter_mut().zip(&m.textures) {
        let texture = reads
            .iter()
            .position(|r| *r == TextureRead::of(t))
            .expect("every texture's read is listed") as u32;
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
            fields,
            channel,
            strength,
            alpha: u32::from(t.carries_alpha()),
            texture,
            _pad: 0,
            rotation: if t.transform.rotation == 0.0 {
                [1.0, 0.0]
            } else {
                let (s, c) = t.transform.rotation.sin_cos();
                [c as f32, s as f32]
            },
        };
    }
    Ok(uniform)
}

#[cfg(test)]
mod tests {
    use super::super::budget::StageBindings;
    use super::*;

    /// The WGSL struct named `name`'s size in the module of a textured
    /// scene.
    fn wgsl_size(name: &str) -> u32 {
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
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap()
            .1;
        ty.inner.size(module.to_ctx())
    }

    #[test]
    fn the_uniform_mirrors_the_wgsl_layout() {
        assert_eq!(size_of::<GpuTextureSlot>(), 32);
        assert_eq!(wgsl_size("TextureSlot"), 32);
        assert_eq!(size_of::<GpuTextureRead>(), 48);
        assert_eq!(wgsl_size("TextureRead"), 48);
        assert_eq!(wgsl_size("TextureSlots") as usize, UNIFORM_BYTES);
    }

    fn texture(image: usize, target: TextureTarget, channel: usize) -> MaterialTexture {
        MaterialTexture {
            target,
            image,
            channel,
            tex_coord: 0,
            transform: Default::default(),
            sampler: Sampler::default(),
        }
    }

    #[test]
    fn textures_agreeing_on_image_sampler_uv_set_and_transform_are_one_read() {
        let mut m =
            crate::material::Material::new("orm", crate::material::ReflectanceModel::GltfPbr);
        m.textures
            .push(texture(0, TextureTarget::Param("base_color"), 0));
        // An ORM image: occlusion from R, roughness from G, metallic from B.
        m.textures
            .push(texture(1, TextureTarget::Occlusion { strength: 1.0 }, 0));
        m.textures
            .push(texture(1, TextureTarget::Param("roughness"), 1));
        m.textures
            .push(texture(1, TextureTarget::Param("metallic"), 2));
        // The same image on another UV set is a read of its own.
        let mut second = texture(1, TextureTarget::Param("metallic"), 2);
        second.tex_coord = 1;
        m.textures.push(second);
        let reads = material_reads(&m);
        assert_eq!(reads.len(), 3);
        let budget = TextureBudget {
            bindings: 3,
            limits: StageBindings {
                textures: 8,
                samplers: 16,
            },
        };
        let u = material_slots(&m, &budget).unwrap();
        let taken: Vec<u32> = u.slots[..5].iter().map(|s| s.texture).collect();
        assert_eq!(taken, [0, 1, 1, 1, 2]);
        assert_eq!(u.reads[2].tex_coord, 1);
        assert_eq!(u.bytes().len(), UNIFORM_BYTES);
    }

    #[test]
    fn a_material_past_the_budget_is_refused_with_what_fits() {
        let mut m =
            crate::material::Material::new("many", crate::material::ReflectanceModel::GltfPbr);
        for image in 0..3 {
            m.textures
                .push(texture(image, TextureTarget::Param("base_color"), 0));
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
}
