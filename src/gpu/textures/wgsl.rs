//! Group 2's bindings as WGSL and as a layout: the slots' uniform, then
//! one image and sampler pair per read, and the generated functions that
//! sample each pair once (`shaders/textures.wgsl` documents them).

use std::fmt::Write;

/// Group 2's binding of read `i`'s texture: the pairs follow the slots'
/// uniform (binding 0), texture then sampler, so a layout of `n` pairs
/// has bindings 0 to `2n`.
pub fn texture_binding(i: u32) -> u32 {
    1 + 2 * i
}

/// Group 2's binding of read `i`'s sampler.
pub fn sampler_binding(i: u32) -> u32 {
    2 + 2 * i
}

/// The WGSL of group 2's first `n` textures and samplers, the struct
/// `ReadTexels` holding one texel per read, and the functions that fill it
/// (`read_texels` with the pixel's UV derivatives, `read_texels_level0`
/// for the vertex stage: each binding sampled once, at its read's UV) and
/// take read `i`'s texel from it (`read_texel`, by selects). Generated
/// because WGSL cannot index separate bindings and the count is the
/// scene's ([`super::binding_count`]).
pub fn wgsl_bindings(n: u32) -> String {
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
    let _ = writeln!(out, "struct ReadTexels {{");
    for i in 0..n {
        let _ = writeln!(out, "    t{i}: vec4<f32>,");
    }
    let _ = writeln!(out, "}}");
    for (name, parameters, prelude, call) in [
        (
            "read_texels",
            "s: SurfaceUv, zero: u32",
            "let f{i} = read_footprint(texture_slots.reads[{i}u + zero], s);",
            "textureSampleGrad(slot_texture_{i}, slot_sampler_{i}, f{i}.uv, f{i}.ddx, f{i}.ddy)",
        ),
        (
            "read_texels_level0",
            "uv0: vec2<f32>, uv1: vec2<f32>, zero: u32",
            "let f{i} = read_uv_level0(texture_slots.reads[{i}u + zero], uv0, uv1);",
            "textureSampleLevel(slot_texture_{i}, slot_sampler_{i}, f{i}, 0.0)",
        ),
    ] {
        let _ = writeln!(out, "fn {name}({parameters}) -> ReadTexels {{");
        let _ = writeln!(out, "    var out: ReadTexels;");
        for i in 0..n {
            let i = i.to_string();
            let _ = writeln!(out, "    {}", prelude.replace("{i}", &i));
            let _ = writeln!(out, "    out.t{i} = {};", call.replace("{i}", &i));
        }
        let _ = writeln!(out, "    return out;\n}}");
    }
    let _ = writeln!(out, "fn read_texel(t: ReadTexels, i: u32) -> vec4<f32> {{");
    let _ = writeln!(out, "    var texel = t.t0;");
    for i in 1..n {
        let _ = writeln!(out, "    texel = select(texel, t.t{i}, i == {i}u);");
    }
    let _ = writeln!(out, "    return texel;\n}}");
    out
}

/// Group 2's layout: the slots' uniform, then `bindings` textures and
/// samplers (the scene's [`super::binding_count`], which its shader
/// declares).
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
        entries.push(crate::gpu::layout_entries::filterable_texture_2d(
            texture_binding(s),
            stage,
        ));
        entries.push(crate::gpu::layout_entries::filtering_sampler(
            sampler_binding(s),
            stage,
        ));
    }
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("gonio material textures"),
        entries: &entries,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_bindings_declare_and_sample_each_pair_once() {
        let wgsl = wgsl_bindings(3);
        for i in 0..3 {
            assert!(wgsl.contains(&format!("@binding({}) var slot_texture_{i}:", 1 + 2 * i)));
            assert!(wgsl.contains(&format!("@binding({}) var slot_sampler_{i}:", 2 + 2 * i)));
            assert_eq!(
                wgsl.matches(&format!("(slot_texture_{i}, slot_sampler_{i},"))
                    .count(),
                2,
                "once per pixel, once per vertex"
            );
        }
        assert!(!wgsl.contains("slot_texture_3"));
        assert!(!wgsl.contains("switch"));
        assert_eq!(wgsl.matches("select(texel").count(), 2);
    }
}
