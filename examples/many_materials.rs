//! Writes a glTF the size of Crytek Sponza in materials and textures, made
//! entirely by this program (so it can be shipped and regenerated): a grid
//! of `MATERIALS` spheres, each with its own material and three images of
//! `SIDE`² texels (base colour, metallic-roughness, normal map), about
//! 16 000 triangles each. Sponza has 25 materials, 69 textures (mostly
//! 1024²) and 262 000 triangles; the defaults give 25, 75 and 410 000.
//!
//! ```text
//! cargo run --release --example many_materials -- OUT_DIR [MATERIALS] [SIDE]
//! gonio render OUT_DIR/many-materials.gltf --timings -o many.png
//! ```
//!
//! Used to measure the texture path on a many-material scene: texture
//! memory, the time from opening the file to the first frame, and the
//! viewer's frame time.

use std::f32::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;

/// Sphere segments around and from pole to pole.
const AROUND: u32 = 128;
const POLES: u32 = 64;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(out) = args.first() else {
        eprintln!("usage: many_materials OUT_DIR [MATERIALS] [SIDE]");
        std::process::exit(2);
    };
    let parse = |i: usize, default: u32| {
        args.get(i).map_or(default, |a| {
            a.parse().unwrap_or_else(|_| {
                eprintln!("many_materials: `{a}` is not a whole number");
                std::process::exit(2);
            })
        })
    };
    let materials = parse(1, 25).max(1);
    let side = parse(2, 1024).clamp(4, 8192);
    let out = Path::new(out);
    if let Err(e) = write(out, materials, side) {
        eprintln!("many_materials: cannot write into {}: {e}", out.display());
        std::process::exit(2);
    }
    println!(
        "wrote {} ({materials} materials, {} images of {side}², {} triangles)",
        out.join("many-materials.gltf").display(),
        3 * materials,
        materials * AROUND * POLES * 2
    );
}

/// One unit sphere's interleaved-free arrays: positions, normals, UVs and
/// triangle indices.
struct Sphere {
    positions: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

fn sphere() -> Sphere {
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for j in 0..=POLES {
        let v = j as f32 / POLES as f32;
        let theta = v * PI;
        for i in 0..=AROUND {
            let u = i as f32 / AROUND as f32;
            let phi = u * TAU;
            positions.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ]);
            uvs.push([u, v]);
        }
    }
    let mut indices = Vec::new();
    let row = AROUND + 1;
    for j in 0..POLES {
        for i in 0..AROUND {
            let a = j * row + i;
            let b = a + row;
            indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    Sphere {
        positions,
        uvs,
        indices,
    }
}

/// Material `m`'s three images: a checker in a hue of its own (sRGB), a
/// metallic-roughness map (roughness rising along u in G, metal bands
/// in B) and a normal map of round bumps.
fn images(m: u32, side: u32) -> [image::RgbImage; 3] {
    let hue = m as f32 * 0.618_034 % 1.0;
    let colour = |t: f32| {
        let c = |o: f32| (0.5 + 0.5 * (TAU * (hue + o)).cos()) * t;
        [c(0.0), c(1.0 / 3.0), c(2.0 / 3.0)].map(|x| (x * 255.0) as u8)
    };
    let cells = 4 + m % 5;
    let base = image::RgbImage::from_fn(side, side, |x, y| {
        let cx = x * cells / side;
        let cy = y * cells / side;
        image::Rgb(colour(if (cx + cy).is_multiple_of(2) {
            0.9
        } else {
            0.45
        }))
    });
    let bands = 2 + m % 4;
    let metal_rough = image::RgbImage::from_fn(side, side, |x, y| {
        let roughness = 40 + 200 * x / side;
        let metal = if (y * bands / side).is_multiple_of(2) {
            255
        } else {
            0
        };
        image::Rgb([0, roughness as u8, metal])
    });
    let bumps = 3 + m % 6;
    let normal = image::RgbImage::from_fn(side, side, |x, y| {
        let cell = side as f32 / bumps as f32;
        let fx = (x as f32 % cell) / cell * 2.0 - 1.0;
        let fy = (y as f32 % cell) / cell * 2.0 - 1.0;
        let r2 = fx * fx + fy * fy;
        let (nx, ny) = if r2 < 0.8 {
            (0.5 * fx, -0.5 * fy)
        } else {
            (0.0, 0.0)
        };
        let nz = (1.0 - nx * nx - ny * ny).sqrt();
        let enc = |c: f32| ((c * 0.5 + 0.5) * 255.0).round() as u8;
        image::Rgb([enc(nx), enc(ny), enc(nz)])
    });
    [base, metal_rough, normal]
}

fn write(out: &Path, materials: u32, side: u32) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(out)?;
    let s = sphere();
    // One buffer: positions (as normals too: a unit sphere), UVs, indices.
    let mut bin: Vec<u8> = Vec::new();
    for p in &s.positions {
        bin.extend(p.iter().flat_map(|c| c.to_le_bytes()));
    }
    let uv_offset = bin.len();
    for uv in &s.uvs {
        bin.extend(uv.iter().flat_map(|c| c.to_le_bytes()));
    }
    let index_offset = bin.len();
    for i in &s.indices {
        bin.extend(i.to_le_bytes());
    }
    std::fs::write(out.join("many-materials.bin"), &bin)?;

    let columns = (materials as f32).sqrt().ceil() as u32;
    let mut images_json = String::new();
    let mut textures_json = String::new();
    let mut materials_json = String::new();
    let mut meshes_json = String::new();
    let mut nodes_json = String::new();
    for m in 0..materials {
        for (k, (image, name)) in images(m, side)
            .into_iter()
            .zip(["base", "metal-rough", "normal"])
            .enumerate()
        {
            let file = format!("m{m:03}-{name}.png");
            image.save(out.join(&file))?;
            let sep = if m == 0 && k == 0 { "" } else { "," };
            write!(images_json, "{sep}{{\"uri\":\"{file}\"}}")?;
            write!(
                textures_json,
                "{sep}{{\"sampler\":0,\"source\":{}}}",
                3 * m + k as u32
            )?;
        }
        let sep = if m == 0 { "" } else { "," };
        write!(
            materials_json,
            "{sep}{{\"name\":\"material {m}\",\"pbrMetallicRoughness\":{{\"baseColorTexture\":{{\"index\":{}}},\"metallicRoughnessTexture\":{{\"index\":{}}}}},\"normalTexture\":{{\"index\":{}}}}}",
            3 * m,
            3 * m + 1,
            3 * m + 2
        )?;
        write!(
            meshes_json,
            "{sep}{{\"primitives\":[{{\"attributes\":{{\"POSITION\":0,\"NORMAL\":0,\"TEXCOORD_0\":1}},\"indices\":2,\"material\":{m}}}]}}"
        )?;
        let (x, z) = ((m % columns) as f32, (m / columns) as f32);
        let half = (columns as f32 - 1.0) / 2.0;
        write!(
            nodes_json,
            "{sep}{{\"mesh\":{m},\"translation\":[{},0,{}]}}",
            2.5 * (x - half),
            2.5 * (z - half)
        )?;
    }
    let vertices = s.positions.len();
    let node_list: Vec<String> = (0..materials).map(|m| m.to_string()).collect();
    let gltf = format!(
        r#"{{
"asset":{{"version":"2.0","generator":"gonio examples/many_materials.rs"}},
"scene":0,
"scenes":[{{"nodes":[{nodes}]}}],
"nodes":[{nodes_json}],
"meshes":[{meshes_json}],
"materials":[{materials_json}],
"textures":[{textures_json}],
"images":[{images_json}],
"samplers":[{{"magFilter":9729,"minFilter":9987,"wrapS":10497,"wrapT":10497}}],
"buffers":[{{"uri":"many-materials.bin","byteLength":{len}}}],
"bufferViews":[
{{"buffer":0,"byteOffset":0,"byteLength":{pos_len},"target":34962}},
{{"buffer":0,"byteOffset":{uv_offset},"byteLength":{uv_len},"target":34962}},
{{"buffer":0,"byteOffset":{index_offset},"byteLength":{index_len},"target":34963}}
],
"accessors":[
{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]}},
{{"bufferView":1,"componentType":5126,"count":{vertices},"type":"VEC2"}},
{{"bufferView":2,"componentType":5125,"count":{indices},"type":"SCALAR"}}
]
}}
"#,
        nodes = node_list.join(","),
        len = bin.len(),
        pos_len = uv_offset,
        uv_len = index_offset - uv_offset,
        index_len = bin.len() - index_offset,
        indices = s.indices.len(),
    );
    std::fs::write(out.join("many-materials.gltf"), gltf)?;
    Ok(())
}
