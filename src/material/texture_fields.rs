//! Which fields of the GPU's material a texture scales: a texture on a
//! parameter multiplies the WGSL `Material` fields the parameter sets,
//! found by probing the model's row (the textures themselves, their
//! targets and samplers, are in `texture.rs`, below the material).

use super::param::Value;
use super::{Material, table};
use crate::base::Rgb;

/// The GPU material's fields, in the order of their bits in a texture
/// slot's field mask (`shaders/textures.wgsl` reads the same order), with
/// their component counts: the values the WGSL `Material` holds for a
/// material (`k_a` from the material, the rest from
/// [`super::brdf::ShaderParams`]).
pub fn gpu_field_values(m: &Material) -> Vec<(&'static str, Vec<f64>)> {
    let p = m.brdf().shader_params();
    let rgb = |c: Rgb| c.to_array().to_vec();
    vec![
        ("k_a", rgb(m.k_a)),
        ("k_d", rgb(p.k_d)),
        ("k_s", rgb(p.k_s)),
        ("k_e", vec![p.k_e]),
        ("roughness", vec![p.roughness]),
        ("sigma_x", vec![p.sigma_x]),
        ("sigma_y", vec![p.sigma_y]),
        ("eta", rgb(p.eta)),
        ("kappa", rgb(p.kappa)),
        ("eta_i", vec![p.eta_i]),
        ("eta_t", vec![p.eta_t]),
        ("d_norm", vec![p.d_norm]),
        ("blinn_e", vec![p.blinn_e]),
        ("lobe", p.lobe.to_vec()),
        ("base_color", rgb(p.base_color)),
        ("metallic", vec![p.metallic]),
        ("emission", rgb(m.emission)),
        ("occlusion", vec![m.occlusion]),
        ("ior", vec![p.layers.ior]),
        ("specular", vec![p.layers.specular]),
        ("specular_color", rgb(p.layers.specular_color)),
        ("clearcoat", vec![p.layers.clearcoat]),
        ("clearcoat_roughness", vec![p.layers.clearcoat_roughness]),
        ("sheen_color", rgb(p.layers.sheen_color)),
        ("sheen_roughness", vec![p.layers.sheen_roughness]),
        ("iridescence", vec![p.layers.iridescence]),
        ("iridescence_ior", vec![p.layers.iridescence_ior]),
        (
            "iridescence_thickness",
            vec![p.layers.iridescence_thickness],
        ),
        ("anisotropy_strength", vec![p.layers.anisotropy_strength]),
        // (cos ρ, sin ρ): not linear in ρ, so a texture on
        // `anisotropy_rotation` is refused (`anisotropy_texture` turns the
        // direction instead).
        (
            "anisotropy_direction",
            p.layers.anisotropy_direction().to_array().to_vec(),
        ),
        ("transmission", vec![p.layers.transmission]),
        ("thickness", vec![p.layers.thickness]),
        // Past the 32 bits: each shares the bit of a field of Ward's
        // ([`field_bit`]).
        ("diffuse_transmission", vec![p.layers.diffuse_transmission]),
        (
            "diffuse_transmission_color",
            rgb(p.layers.diffuse_transmission_color),
        ),
    ]
}

/// The fields past the mask's 32 bits and the bits they share: the
/// diffuse transmission's share and colour (gltf-pbr's layers) take
/// Ward's `sigma_x` and `sigma_y` (bits 5 and 6). No model has a
/// parameter on both fields of a pair (the test below), and a bit scales
/// both fields (`scale_fields` in shaders/textures.wgsl), which is
/// harmless: Ward's shader reads no layer (its layers are 0, and 0 times
/// a texel is 0), gltf-pbr's no `sigma` (the footprint floor
/// `textured_widths_floored` widens it unread).
pub const SHARED_BITS: [(usize, u32); 2] = [(32, 5), (33, 6)];

/// The mask bit of field `index` of [`gpu_field_values`]: its index, or
/// for the fields past 32 the bit it shares ([`SHARED_BITS`]).
pub fn field_bit(index: usize) -> u32 {
    SHARED_BITS
        .iter()
        .find(|(i, _)| *i == index)
        .map_or(index as u32, |&(_, bit)| bit)
}

/// The bit of the `occlusion` field in a texture slot's field mask (the
/// occlusion texture's slot sets it; no parameter maps to it).
pub const OCCLUSION_FIELD: u32 = 1 << 17;

/// Which GPU material fields a texture on parameter `key` scales, as a
/// bit mask over [`gpu_field_values`]: found by scaling the parameter in a
/// copy of `m` and seeing which fields change. Each must change by
/// exactly the same factor (channel by channel for a colour), so that
/// multiplying the GPU's field by the texel is the same as multiplying
/// the parameter: an error names the field when a model derives it from
/// the parameter some other way (e.g. Blinn's exponent from the
/// roughness), which the GPU could not follow per pixel.
pub fn gpu_field_mask(m: &Material, key: &str) -> Result<u32, String> {
    let p = table::param_for(m.model, key)
        .ok_or_else(|| format!("{} has no parameter `{key}`", m.model.name()))?;
    let scale = [0.5, 0.25, 0.125];
    let mut probe = m.clone();
    let scaled = match p.read(m) {
        Value::Color(c) => Value::Color(c * Rgb::from_array(scale)),
        Value::Scalar(v) => Value::Scalar(0.5 * v),
    };
    p.write(&mut probe, scaled);
    let colour = matches!(scaled, Value::Color(_));
    let mut mask = 0;
    for (index, ((name, before), (_, after))) in gpu_field_values(m)
        .into_iter()
        .zip(gpu_field_values(&probe))
        .enumerate()
    {
        if before == after {
            continue;
        }
        let linear = before.iter().zip(&after).enumerate().all(|(c, (b, a))| {
            let s = if colour && before.len() == 3 {
                scale[c]
            } else {
                scale[0]
            };
            (a - s * b).abs() <= 1e-12 * b.abs()
        });
        if !linear || (colour && before.len() != 3) {
            return Err(format!(
                "{key}_texture: {} derives `{name}` from {key} on the CPU, so it cannot vary over the surface",
                m.model.name()
            ));
        }
        mask |= 1 << field_bit(index);
    }
    Ok(mask)
}

/// The fields of [`gpu_field_values`]: the 32 bits of a `u32` mask
/// (`TextureSlot.fields` in shaders/textures.wgsl) and those sharing one
/// ([`SHARED_BITS`]).
pub const FIELD_COUNT: usize = 32 + SHARED_BITS.len();

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_field_has_a_bit_of_the_mask() {
        let m = crate::material::Material::new("m", crate::material::ReflectanceModel::GltfPbr);
        assert_eq!(gpu_field_values(&m).len(), FIELD_COUNT);
    }

    /// No model has parameters on both fields of a shared bit, so a
    /// texture on one never scales a field its model reads through the
    /// other: for every model, every parameter's fields (probed on its
    /// default material) meet at most one field of each pair.
    #[test]
    fn no_model_reaches_both_fields_of_a_shared_bit() {
        use crate::material::table;
        let mut anywhere = std::collections::HashSet::new();
        for model in crate::material::ReflectanceModel::ALL {
            let m = crate::material::Material::new("m", model);
            let names: Vec<&str> = gpu_field_values(&m).iter().map(|(n, _)| *n).collect();
            let mut reached = std::collections::HashSet::new();
            for p in table::COMMON.iter().chain(model.row().params) {
                let mut probe = m.clone();
                let scaled = match p.read(&m) {
                    Value::Color(c) => Value::Color(c * 0.5 + Rgb::splat(0.25)),
                    Value::Scalar(v) => Value::Scalar(0.5 * v + 0.25),
                };
                p.write(&mut probe, scaled);
                for (k, ((_, a), (_, b))) in gpu_field_values(&m)
                    .into_iter()
                    .zip(gpu_field_values(&probe))
                    .enumerate()
                {
                    if a != b {
                        reached.insert(k);
                    }
                }
            }
            anywhere.extend(reached.iter().copied());
            for &(index, bit) in &SHARED_BITS {
                assert!(
                    !(reached.contains(&index) && reached.contains(&(bit as usize))),
                    "{}: parameters on both `{}` and `{}`",
                    model.name(),
                    names[index],
                    names[bit as usize]
                );
            }
        }
        // Both fields of every pair are reached by some model (the probe
        // sees them).
        for &(index, bit) in &SHARED_BITS {
            assert!(anywhere.contains(&index) && anywhere.contains(&(bit as usize)));
        }
    }

    #[test]
    fn occlusion_field_bit_is_its_place_in_the_field_order() {
        let m = crate::material::Material::new("m", crate::material::ReflectanceModel::Lambert);
        let at = gpu_field_values(&m)
            .iter()
            .position(|(name, _)| *name == "occlusion")
            .unwrap();
        assert_eq!(OCCLUSION_FIELD, 1 << at);
    }
}
