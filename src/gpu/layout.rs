//! CPU mirrors of the GPU structs in `shaders/common.wgsl`, with explicit
//! padding so `bytemuck` can upload them as they are. Field order and sizes
//! follow WGSL's layout rules (vec3 aligned to 16 bytes).

use crate::material::Material;
use crate::scene::{Light, Scene};
use bytemuck::{Pod, Zeroable};

/// `Globals` (uniform buffer, 4240 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGlobals {
    pub clip_from_world: [[f32; 4]; 4],
    pub eye: [f32; 3],
    pub light_count: u32,
    pub ambient: [f32; 3],
    /// `2^exposure` for display targets (`target_output` in common.wgsl).
    pub display_scale: f32,
    pub env_zenith: [f32; 3],
    /// `ToneMap::code` of `image.tone_map`, read by display targets only.
    pub tone_map: u32,
    pub env_horizon: [f32; 3],
    /// `Scene::roughness_floor`, applied on the GPU to lobe widths a
    /// texture multiplies (`textured_widths_floored` in textures.wgsl).
    pub roughness_floor: f32,
    pub env_ground: [f32; 3],
    pub _pad3: f32,
    /// Energy compensation's albedo table (`DfgTable::albedo_uniform`),
    /// read by shaders/brdf/energy.wgsl: filled only when some material
    /// of the scene has `energy_compensation` (the table is computed on
    /// first use, about 0.1 s; a scene without it never pays for it), else
    /// zeros. In the globals rather than a binding of its own: they are
    /// bound in every scene pipeline (with or without an environment map)
    /// and 4 KiB is well inside a uniform buffer's 64 KiB.
    pub albedo: [[f32; 4]; 256],
}

/// `Material` (uniform buffer record, 304 bytes: 176 without the layers,
/// which the WGSL declares only with feature `gltf_layers`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    pub k_a: [f32; 3],
    /// The model and terms, packed (`ShaderKey::variant_code`).
    pub variant: u32,
    pub k_d: [f32; 3],
    pub k_e: f32,
    pub k_s: [f32; 3],
    pub roughness: f32,
    pub eta: [f32; 3],
    pub sigma_x: f32,
    pub kappa: [f32; 3],
    pub sigma_y: f32,
    pub eta_i: f32,
    pub eta_t: f32,
    pub d_norm: f32,
    pub blinn_e: f32,
    /// A model's own derived constants (`ShaderParams::lobe`).
    pub lobe: [f32; 4],
    /// gltf-pbr's base colour and metallic (`ShaderParams::base_color`).
    pub base_color: [f32; 3],
    pub metallic: f32,
    /// Emitted radiance, added to `L_o` (`Material::emission`).
    pub emission: [f32; 3],
    /// `Sides::code` of the material (glTF `doubleSided`).
    pub sides: u32,
    /// The base colour's alpha (`Material::alpha`).
    pub alpha: f32,
    /// `AlphaMode::cutoff`: a fragment of lower alpha is discarded.
    pub alpha_cutoff: f32,
    /// `AlphaMode::code` (0 opaque, 1 mask, 2 blend).
    pub alpha_mode: u32,
    /// The ambient occlusion (`Material::occlusion`; an occlusion
    /// texture's slot multiplies it per pixel).
    pub occlusion: f32,
    /// 1: the shading normal turns toward the viewer where it faces away
    /// (`Material::facing_normals`, `facing_frame` in surface.wgsl).
    pub facing_normals: u32,
    pub _pad0: [u32; 3],
    /// gltf-pbr's layers (`ShaderParams::layers`); the WGSL `Material`
    /// declares them only where a drawn material uses a layer (feature
    /// `gltf_layers`), the bytes are always there.
    pub layers: GpuGltfLayers,
}

/// `GltfLayers` of shaders/brdf/gltf_layers/mod.wgsl (128 bytes, same
/// order): the layer parameters of `material::layers::GltfLayers` in
/// `f32`, the anisotropy rotation as its direction `(cos ρ, sin ρ)`
/// computed in `f64`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGltfLayers {
    pub specular_color: [f32; 3],
    pub ior: f32,
    pub sheen_color: [f32; 3],
    pub specular: f32,
    pub clearcoat_normal: [f32; 3],
    pub clearcoat: f32,
    pub anisotropy_direction: [f32; 2],
    pub clearcoat_roughness: f32,
    pub sheen_roughness: f32,
    pub iridescence: f32,
    pub iridescence_ior: f32,
    pub iridescence_thickness: f32,
    pub anisotropy_strength: f32,
    /// `KHR_materials_volume`: the colour kept after
    /// `attenuation_distance`.
    pub attenuation_color: [f32; 3],
    /// `KHR_materials_transmission`'s `T`.
    pub transmission: f32,
    /// The volume's thickness (0: thin-walled).
    pub thickness: f32,
    /// `1 / attenuation_distance` (0 for the default `inf`: no
    /// attenuation), so the shader never divides by infinity.
    pub attenuation_rate: f32,
    /// `KHR_materials_dispersion`: `20 / V_d` (0: none).
    pub dispersion: f32,
    /// `KHR_materials_diffuse_transmission`'s share `D` and colour.
    pub diffuse_transmission: f32,
    pub diffuse_transmission_color: [f32; 3],
    pub _pad0: f32,
}

impl From<&crate::material::layers::GltfLayers> for GpuGltfLayers {
    fn from(l: &crate::material::layers::GltfLayers) -> Self {
        GpuGltfLayers {
            specular_color: f32x3(l.specular_color),
            ior: l.ior as f32,
            sheen_color: f32x3(l.sheen_color),
            specular: l.specular as f32,
            clearcoat_normal: f32x3(l.clearcoat_normal),
            clearcoat: l.clearcoat as f32,
            anisotropy_direction: l.anisotropy_direction().as_vec2().to_array(),
            clearcoat_roughness: l.clearcoat_roughness as f32,
            sheen_roughness: l.sheen_roughness as f32,
            iridescence: l.iridescence as f32,
            iridescence_ior: l.iridescence_ior as f32,
            iridescence_thickness: l.iridescence_thickness as f32,
            anisotropy_strength: l.anisotropy_strength as f32,
            attenuation_color: f32x3(l.attenuation_color),
            transmission: l.transmission as f32,
            thickness: l.thickness as f32,
            attenuation_rate: (1.0 / l.attenuation_distance) as f32,
            dispersion: l.dispersion as f32,
            diffuse_transmission: l.diffuse_transmission as f32,
            diffuse_transmission_color: f32x3(l.diffuse_transmission_color),
            _pad0: 0.0,
        }
    }
}

/// `Light` (storage buffer element, 128 bytes). The `shadow_*` fields are
/// filled by [`super::shadows::ShadowPlan::apply`]; `shadow_layer` is −1
/// for a light without a shadow map.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLight {
    pub position: [f32; 3],
    pub kind: u32,
    pub direction: [f32; 3],
    pub range: f32,
    pub intensity: [f32; 3],
    pub cos_inner: f32,
    pub shadow_origin: [f32; 3],
    pub cos_outer: f32,
    pub shadow_layer: i32,
    pub shadow_projection: u32,
    pub shadow_texel: f32,
    pub shadow_bias: f32,
    pub shadow_slope_bias: f32,
    pub shadow_normal_offset: f32,
    pub shadow_pcf_radius: u32,
    pub shadow_uv_scale: f32,
    pub shadow_map: u32,
    pub shadow_array_texel: f32,
    pub _pad: [u32; 2],
    /// Cube maps: `s` times the f64 origin, rounded once to f32 (not `s`
    /// times the f32 `shadow_origin`), the
    /// faces' clip x and y offsets up to sign; see `shadow_cube_clip`
    /// in shaders/shadows.wgsl.
    pub shadow_cube_offset: [f32; 3],
    /// Cube maps: `s`, the faces' clip x and y scale (the projection's
    /// `1 / tan(fov / 2)`).
    pub shadow_cube_scale: f32,
}

/// `ShadowView` (storage buffer element, 64 bytes): one layer of the
/// shadow-map array.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuShadowView {
    pub clip_from_world: [[f32; 4]; 4],
}

fn f32x3(v: glam::DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

impl GpuGlobals {
    pub fn new(scene: &Scene) -> Self {
        let aspect = scene.width as f64 / scene.height as f64;
        GpuGlobals {
            clip_from_world: scene
                .camera
                .clip_from_world(aspect)
                .as_mat4()
                .to_cols_array_2d(),
            eye: f32x3(scene.camera.position),
            light_count: scene.lights.len() as u32,
            ambient: f32x3(scene.ambient),
            display_scale: 1.0,
            env_zenith: f32x3(scene.environment.zenith),
            tone_map: scene.tone_map.code(),
            env_horizon: f32x3(scene.environment.horizon),
            roughness_floor: scene.roughness_floor() as f32,
            env_ground: f32x3(scene.environment.ground),
            _pad3: 0.0,
            albedo: if scene.materials.iter().any(|m| m.energy_compensation) {
                crate::material::brdf::dfg::table().albedo_uniform()
            } else {
                [[0.0; 4]; 256]
            },
        }
    }
}

impl GpuMaterial {
    /// The size of WGSL's `Material` in a shader with or without the
    /// feature `gltf_layers`: without it the struct ends before `layers`
    /// (a uniform binding of the whole record reads the same fields; a
    /// storage array of records needs this stride).
    pub fn wgsl_size(layers: bool) -> usize {
        if layers {
            std::mem::size_of::<Self>()
        } else {
            std::mem::offset_of!(GpuMaterial, layers)
        }
    }

    /// `m` as the GPU sees it: `m` must be an effective material (roughness
    /// floor applied), `variant` its code in the scene's shader
    /// (`ShaderKey::variant_code`).
    /// The BRDF's values come from [`Material::brdf`]: what the model's
    /// WGSL twin reads, its derived constants computed in `f64`; fields the
    /// model does not read are 0.
    pub fn new(m: &Material, variant: u32) -> Self {
        let p = m.brdf().shader_params();
        GpuMaterial {
            k_a: f32x3(m.k_a),
            variant,
            k_d: f32x3(p.k_d),
            k_e: p.k_e as f32,
            k_s: f32x3(p.k_s),
            roughness: p.roughness as f32,
            eta: f32x3(p.eta),
            sigma_x: p.sigma_x as f32,
            kappa: f32x3(p.kappa),
            sigma_y: p.sigma_y as f32,
            eta_i: p.eta_i as f32,
            eta_t: p.eta_t as f32,
            d_norm: p.d_norm as f32,
            blinn_e: p.blinn_e as f32,
            lobe: p.lobe.map(|v| v as f32),
            base_color: f32x3(p.base_color),
            metallic: p.metallic as f32,
            emission: f32x3(m.emission),
            sides: m.sides.code(),
            alpha: m.alpha as f32,
            alpha_cutoff: m.alpha_mode.cutoff() as f32,
            alpha_mode: m.alpha_mode.code(),
            occlusion: m.occlusion as f32,
            facing_normals: u32::from(m.facing_normals),
            _pad0: [0; 3],
            layers: GpuGltfLayers::from(&p.layers),
        }
    }
}

impl From<&Light> for GpuLight {
    fn from(light: &Light) -> Self {
        let mut g = GpuLight::zeroed();
        g.kind = light.kind().id();
        g.range = -1.0;
        g.shadow_layer = -1;
        match *light {
            Light::Point {
                position,
                intensity,
                range,
                ..
            } => {
                g.position = f32x3(position);
                g.intensity = f32x3(intensity);
                g.range = range.unwrap_or(-1.0) as f32;
            }
            Light::Directional {
                direction,
                irradiance,
                ..
            } => {
                g.direction = f32x3(direction);
                g.intensity = f32x3(irradiance);
            }
            Light::Spot {
                position,
                direction,
                intensity,
                inner_cone_deg,
                outer_cone_deg,
                range,
                ..
            } => {
                g.position = f32x3(position);
                g.direction = f32x3(direction);
                g.intensity = f32x3(intensity);
                g.cos_inner = inner_cone_deg.to_radians().cos() as f32;
                g.cos_outer = outer_cone_deg.to_radians().cos() as f32;
                g.range = range.unwrap_or(-1.0) as f32;
            }
            Light::AreaSample {
                position,
                normal,
                intensity,
                ..
            } => {
                g.position = f32x3(position);
                g.direction = f32x3(normal);
                g.intensity = f32x3(intensity);
            }
        }
        g
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The values the WGSL reads are the material's, rounded once, and the
    /// derived constants are computed in f64 (Blinn's exponent, the
    /// Gaussian's normalization) whichever way the BRDF value is built.
    #[test]
    fn uploaded_values_are_the_materials() {
        use crate::material::brdf::microfacet::{blinn_exponent, gaussian_normalization};
        use crate::material::{Distribution, Fresnel, ReflectanceModel};
        let mut ct = Material::new("ct", ReflectanceModel::CookTorrance);
        (ct.roughness, ct.k_s) = (0.37, glam::DVec3::new(0.1, 0.2, 0.3));
        ct.distribution = Distribution::Blinn;
        let g = GpuMaterial::new(&ct, 0);
        assert_eq!(g.blinn_e, blinn_exponent(0.37) as f32);
        assert_eq!((g.eta, g.kappa), (f32x3(ct.eta), f32x3(ct.kappa)));
        assert_eq!((g.k_d, g.k_s), (f32x3(ct.k_d), f32x3(ct.k_s)));
        ct.distribution = Distribution::GaussianNormalized;
        let g = GpuMaterial::new(&ct, 0);
        assert_eq!(g.d_norm, gaussian_normalization(0.37) as f32);
        assert_eq!(g.roughness, 0.37f32);
        let mut ward = Material::new("w", ReflectanceModel::WardAnisotropic);
        (ward.sigma_x, ward.sigma_y) = (0.05, 0.3);
        let g = GpuMaterial::new(&ward, 0);
        assert_eq!((g.sigma_x, g.sigma_y), (0.05, 0.3));
        let mut glass = Material::new("m", ReflectanceModel::Mirror);
        (glass.fresnel, glass.eta_t) = (Fresnel::Dielectric, 1.33);
        let g = GpuMaterial::new(&glass, 0);
        assert_eq!((g.eta_i, g.eta_t, g.k_s), (1.0, 1.33, [1.0; 3]));
        let mut phong = Material::new("p", ReflectanceModel::Phong);
        phong.k_e = 77.0;
        assert_eq!(GpuMaterial::new(&phong, 0).k_e, 77.0);
    }

    /// `(field, byte offset)` of a Rust mirror, in declaration order.
    macro_rules! offsets {
        ($ty:ty { $($field:ident),+ $(,)? }) => {
            vec![$((stringify!($field), std::mem::offset_of!($ty, $field))),+]
        };
    }

    /// The WGSL struct `name` in `module`: its size and `(member, offset)`
    /// in declaration order.
    fn wgsl_layout(module: &naga::Module, name: &str) -> (usize, Vec<(String, usize)>) {
        let (_, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no struct {name} in the WGSL"));
        let naga::TypeInner::Struct { members, .. } = &ty.inner else {
            panic!("{name} is not a struct");
        };
        let fields = members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
            .collect();
        (ty.inner.size(module.to_ctx()) as usize, fields)
    }

    /// Each Rust mirror has the WGSL struct's size and, field by field,
    /// its names in its order at its offsets (padding fields, `_…`, are
    /// named freely): a swapped or misplaced field fails here even when the
    /// sizes agree.
    fn assert_mirrors(module: &naga::Module, name: &str, size: usize, rust: Vec<(&str, usize)>) {
        let (wgsl_size, wgsl) = wgsl_layout(module, name);
        assert_eq!(wgsl_size, size, "size of {name}");
        let named = |fields: Vec<(String, usize)>| -> Vec<(String, usize)> {
            fields
                .into_iter()
                .filter(|(f, _)| !f.starts_with('_'))
                .collect()
        };
        let rust = named(rust.into_iter().map(|(f, o)| (f.to_string(), o)).collect());
        assert_eq!(named(wgsl), rust, "fields and offsets of {name}");
    }

    #[test]
    fn rust_mirrors_match_the_wgsl_structs_field_by_field() {
        use crate::gpu::shader_gen::{Feature, common, preprocess, sources};
        // With the layers declared (feature `gltf_layers`), as the
        // buffer always holds them.
        let common = common(&[Feature::UniformLights, Feature::GltfLayers]);
        let module = naga::front::wgsl::parse_str(&common).unwrap();
        assert_mirrors(
            &module,
            "Globals",
            std::mem::size_of::<GpuGlobals>(),
            offsets!(GpuGlobals {
                clip_from_world,
                eye,
                light_count,
                ambient,
                display_scale,
                env_zenith,
                tone_map,
                env_horizon,
                roughness_floor,
                env_ground,
                _pad3,
                albedo
            }),
        );
        assert_mirrors(
            &module,
            "Material",
            std::mem::size_of::<GpuMaterial>(),
            offsets!(GpuMaterial {
                k_a,
                variant,
                k_d,
                k_e,
                k_s,
                roughness,
                eta,
                sigma_x,
                kappa,
                sigma_y,
                eta_i,
                eta_t,
                d_norm,
                blinn_e,
                lobe,
                base_color,
                metallic,
                emission,
                sides,
                alpha,
                alpha_cutoff,
                alpha_mode,
                occlusion,
                facing_normals,
                layers
            }),
        );
        assert_mirrors(
            &module,
            "GltfLayers",
            std::mem::size_of::<GpuGltfLayers>(),
            offsets!(GpuGltfLayers {
                specular_color,
                ior,
                sheen_color,
                specular,
                clearcoat_normal,
                clearcoat,
                anisotropy_direction,
                clearcoat_roughness,
                sheen_roughness,
                iridescence,
                iridescence_ior,
                iridescence_thickness,
                anisotropy_strength,
                attenuation_color,
                transmission,
                thickness,
                attenuation_rate,
                dispersion,
                diffuse_transmission,
                diffuse_transmission_color,
                _pad0
            }),
        );
        assert_mirrors(
            &module,
            "Light",
            std::mem::size_of::<GpuLight>(),
            offsets!(GpuLight {
                position,
                kind,
                direction,
                range,
                intensity,
                cos_inner,
                shadow_origin,
                cos_outer,
                shadow_layer,
                shadow_projection,
                shadow_texel,
                shadow_bias,
                shadow_slope_bias,
                shadow_normal_offset,
                shadow_pcf_radius,
                shadow_uv_scale,
                shadow_map,
                shadow_array_texel,
                _pad,
                shadow_cube_offset,
                shadow_cube_scale
            }),
        );
        let shadows = naga::front::wgsl::parse_str(&format!(
            "{common}{}",
            preprocess(
                "shadows.wgsl",
                sources::get("shadows.wgsl"),
                &[Feature::Shadows, Feature::ShadowPcf]
            )
            .unwrap()
        ))
        .unwrap();
        assert_mirrors(
            &shadows,
            "ShadowView",
            std::mem::size_of::<GpuShadowView>(),
            offsets!(GpuShadowView { clip_from_world }),
        );
    }
}
