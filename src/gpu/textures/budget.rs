//! How many textures a material can bind on a device: its per-stage
//! limits less what the scene's other bind groups take.

/// Texture reads (slots) a material can have: one per parameter a
/// texture scales, each naming the read whose texel it takes. The core
/// material names 6 (base colour, metallic, roughness, normal, occlusion,
/// emission) and the layer extensions 14 more (coat 3, sheen 2, specular
/// 2, transmission, thickness, iridescence 2, anisotropy, diffuse
/// transmission 2): 24 holds all 20 with room. Also the most reads
/// (the uniform's two arrays are this long).
pub const MAX_TEXTURE_SLOTS: usize = 24;

/// Sampled textures and samplers that the other groups of a scene
/// pipeline bind in each stage, which a material's textures share the
/// device's per-stage limits with: shadows (group 1: the map array and its
/// comparison sampler), the environment (group 3: the map, the prefiltered
/// stack, the DFG table and the sheen stack) and transmission (group 4:
/// the image and its sampler). The test below holds these against the
/// groups' layouts.
pub const OTHER_GROUPS: StageBindings = StageBindings {
    textures: 6,
    samplers: 2,
};

/// Sampled textures and samplers bound in one shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StageBindings {
    pub textures: u32,
    pub samplers: u32,
}

/// Textures a material can bind on one device, counted as glTF counts
/// them: an image with its sampler (group 2: [`super::texture_binding`],
/// [`super::sampler_binding`]). Several slots may read one binding (a
/// metallic-roughness texture feeds two parameters from two channels; an
/// ORM texture three). Bounded by the device's real per-stage limits
/// (gonio requests the adapter's own, `GpuContext`) less what the other
/// groups take ([`OTHER_GROUPS`]), and by the slots: WebGPU's guaranteed
/// 16 and 16 leave 10, lavapipe and desktop Vulkan drivers all 24.
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

#[cfg(test)]
mod tests {
    use super::*;

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
        // WebGPU's guaranteed limits: 16 and 16, less 6 and 2.
        let webgpu = TextureBudget::for_limits(&wgpu::Limits::default());
        assert_eq!(webgpu.bindings, 10);
        assert!(
            webgpu.explained().contains("at most 10"),
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
}
