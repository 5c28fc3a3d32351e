#!/usr/bin/env python3
"""Builds assets/gltf/MetalRoughSpheresTextured: Khronos's MetalRoughSpheres
textures on Khronos's MetalRoughSpheresNoTextures geometry.

Why: the factor-vs-texture pair MetalRoughSpheres / MetalRoughSpheresNoTextures
is a glTF conformance check, but MetalRoughSpheres' buffer (its geometry) was
not obtainable here; its two PNGs and its .gltf were. So this script keeps
NoTextures' spheres and gives each of its 98 materials the two textures of
MetalRoughSpheres (`Spheres_BaseColor.png`, `Spheres_MetalRough.png`, with
that model's sampler) instead of factors, each looking up the texture cell
of its own metallic, roughness and colour: one shared TEXCOORD_0 of zeros
and a `KHR_texture_transform` with `scale = [0, 0]` and `offset` at the
centre of the cell, so every fragment reads that cell's texel.

It writes two files sharing one buffer:
- `MetalRoughSpheresTextured.gltf`: the textured materials;
- `MetalRoughSpheresTexelFactors.gltf`: the same spheres with factor-only
  materials whose values are the texels' (base colour sRGB-decoded, as the
  glTF specification decodes the texture; metallic = B/255, roughness =
  G/255). A renderer that samples and decodes textures right draws both
  alike; tests/conformance.rs asserts it. NoTextures' own factors are k/6;
  the 8-bit texels differ from them by at most 0.5/255.

Usage: scripts/make_metal_rough_spheres_textured.py DIR_WITH_KHRONOS_PNGS
(the directory holding Spheres_BaseColor.png, Spheres_MetalRough.png from
KhronosGroup/glTF-Sample-Assets Models/MetalRoughSpheres/glTF). Needs Pillow.
"""

import json
import shutil
import struct
import sys
from pathlib import Path

from PIL import Image

ROOT = Path(__file__).resolve().parent.parent
SOURCE = ROOT / "assets/gltf/MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb"
OUT = ROOT / "assets/gltf/MetalRoughSpheresTextured"
BASE = "Spheres_BaseColor.png"
METAL_ROUGH = "Spheres_MetalRough.png"


def read_glb(path):
    data = path.read_bytes()
    magic, _version, _length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67, "not a GLB"
    json_len, json_type = struct.unpack_from("<II", data, 12)
    assert json_type == 0x4E4F534A
    doc = json.loads(data[20 : 20 + json_len])
    bin_at = 20 + json_len
    bin_len, bin_type = struct.unpack_from("<II", data, bin_at)
    assert bin_type == 0x004E4942
    return doc, data[bin_at + 8 : bin_at + 8 + bin_len]


def runs(values):
    """(start, end, value) of equal runs in a sequence."""
    out, start = [], 0
    for i in range(1, len(values) + 1):
        if i == len(values) or values[i] != values[start]:
            out.append((start, i, values[start]))
            start = i
    return out


def srgb_to_linear(c):
    c = c / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def cells(base, metal_rough):
    """Texel centre (x, y) of each (metal step, rough step, yellow) cell.

    Cells are found from the textures themselves: along a row of the
    metallic-roughness texture, runs of one G value are the roughness
    columns; along a column, runs of one B value the metallic rows
    (B = 255 at the top); inside a column, the base colour texture's grey
    and yellow stripes. The centre of a run is far (tens of texels) from
    its edges, so bilinear filtering and the mip chain's first levels read
    the run's own value."""
    w, h = metal_rough.size
    border = metal_rough.getpixel((0, 0))[:3]
    y_mid = h // 2
    columns = [r for r in runs([metal_rough.getpixel((x, y_mid))[:3] for x in range(w)])
               if r[2] != border and r[1] - r[0] > 40]
    x_mid = (columns[0][0] + columns[0][1]) // 2
    rows = [r for r in runs([metal_rough.getpixel((x_mid, y))[:3] for y in range(h)])
            if r[2] != border and r[1] - r[0] > 40]
    assert len(columns) == 7 and len(rows) == 7, (len(columns), len(rows))
    out = {}
    for m, (y0, y1, _) in enumerate(reversed(rows)):  # metal 0 is the bottom row
        y = (y0 + y1) // 2
        for r, (x0, x1, _) in enumerate(columns):
            stripes = [s for s in runs([base.getpixel((x, y))[:3] for x in range(x0, x1)])
                       if s[1] - s[0] > 12]
            for s0, s1, rgb in stripes:
                yellow = rgb[2] < 128
                out[(m, r, yellow)] = (x0 + (s0 + s1) // 2, y)
    assert len(out) == 98, len(out)
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    pngs = Path(sys.argv[1])
    base = Image.open(pngs / BASE).convert("RGB")
    metal_rough = Image.open(pngs / METAL_ROUGH).convert("RGB")
    size = base.size
    centres = cells(base, metal_rough)

    doc, binary = read_glb(SOURCE)
    binary = bytearray(binary)
    binary += b"\0" * (-len(binary) % 4)

    # One TEXCOORD_0 of zeros, as long as the longest POSITION accessor
    # a textured primitive uses; accessors of shorter primitives share it.
    uv_offset = len(binary)
    counts = set()
    for mesh in doc["meshes"]:
        for p in mesh["primitives"]:
            if "material" in p:
                counts.add(doc["accessors"][p["attributes"]["POSITION"]]["count"])
    longest = max(counts)
    binary += b"\0" * (8 * longest)
    doc["bufferViews"].append(
        {"buffer": 0, "byteOffset": uv_offset, "byteLength": 8 * longest, "target": 34962}
    )
    uv_view = len(doc["bufferViews"]) - 1
    uv_accessor = {}
    for count in sorted(counts):
        doc["accessors"].append({
            "bufferView": uv_view, "componentType": 5126, "count": count, "type": "VEC2",
            "min": [0.0, 0.0], "max": [0.0, 0.0],
        })
        uv_accessor[count] = len(doc["accessors"]) - 1
    for mesh in doc["meshes"]:
        for p in mesh["primitives"]:
            if "material" in p:
                count = doc["accessors"][p["attributes"]["POSITION"]]["count"]
                p["attributes"]["TEXCOORD_0"] = uv_accessor[count]

    doc["buffers"] = [{"byteLength": len(binary), "uri": "MetalRoughSpheresTextured.bin"}]
    doc["asset"] = {
        "version": "2.0",
        "generator": "gonio scripts/make_metal_rough_spheres_textured.py",
        "copyright": "Geometry: MetalRoughSpheresNoTextures (2019, Public, CC0 1.0). "
        "Textures: MetalRoughSpheres (2017, Analytical Graphics, Inc., CC BY 4.0).",
    }

    factors = []
    for m in doc["materials"]:
        pbr = m["pbrMetallicRoughness"]
        metal = round(pbr["metallicFactor"] * 6)
        rough = round(pbr["roughnessFactor"] * 6)
        yellow = pbr["baseColorFactor"][2] < 0.5
        factors.append((m.get("name"), centres[(metal, rough, yellow)]))

    textured = json.loads(json.dumps(doc))
    textured["images"] = [{"uri": BASE}, {"uri": METAL_ROUGH}]
    # MetalRoughSpheres' own sampler: LINEAR, LINEAR_MIPMAP_LINEAR, clamp.
    textured["samplers"] = [
        {"magFilter": 9729, "minFilter": 9986, "wrapS": 33071, "wrapT": 33071}
    ]
    textured["textures"] = [{"sampler": 0, "source": 0}, {"sampler": 0, "source": 1}]
    textured["extensionsUsed"] = ["KHR_texture_transform"]

    def lookup(index, texel):
        x, y = texel
        offset = [(x + 0.5) / size[0], (y + 0.5) / size[1]]
        return {
            "index": index,
            "extensions": {"KHR_texture_transform": {"offset": offset, "scale": [0.0, 0.0]}},
        }

    textured["materials"] = [
        {"name": name, "pbrMetallicRoughness": {
            "baseColorTexture": lookup(0, texel),
            "metallicRoughnessTexture": lookup(1, texel),
        }}
        for name, texel in factors
    ]

    texel_factors = json.loads(json.dumps(doc))
    texel_factors["materials"] = []
    for name, texel in factors:
        r, g, b = base.getpixel(texel)
        _, rough, metal = metal_rough.getpixel(texel)
        texel_factors["materials"].append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b), 1.0],
            "metallicFactor": metal / 255.0,
            "roughnessFactor": rough / 255.0,
        }})

    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "MetalRoughSpheresTextured.bin").write_bytes(bytes(binary))
    for name, d in [("MetalRoughSpheresTextured.gltf", textured),
                    ("MetalRoughSpheresTexelFactors.gltf", texel_factors)]:
        (OUT / name).write_text(json.dumps(d, indent=1) + "\n")
    for png in (BASE, METAL_ROUGH):
        shutil.copyfile(pngs / png, OUT / png)
    print(f"wrote {OUT} ({len(binary)} bytes of buffer, {len(factors)} materials)")


if __name__ == "__main__":
    main()
