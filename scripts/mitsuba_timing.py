#!/usr/bin/env python3
"""Times `gonio render --reference` against Mitsuba 3 on the same scene,
interleaved, and prints the ratio. Not a test: shared
machines are noisy; compare the two within one run.

The scene is gonio's built-in one with both materials Lambert (Mitsuba has
no Blinn-Phong), no ambient term and the point light's shadow ray on: a UV sphere of 64
slices × 32 stacks (radius 1 at (0, 1, 0)) on an 8 × 8 plane of 16 × 16
quads, one point light of 60 W/sr at (3, 5, 3), 640 × 480, the camera of
the built-in scene. Both trace one camera ray and one shadow ray per pixel
through a triangle-mesh hierarchy:
- gonio: `render --reference --timings`, its "reference render" line (the
  hierarchy's build, the rays and the shading; all cores, rayon);
- Mitsuba: variant `scalar_rgb`, the same meshes as OBJ files, integrator
  `direct` with one emitter sample and no BSDF sample, one sample per pixel,
  box filter; `mi.render` timed after `mi.load_dict` (the hierarchy is built
  at load, so its build time is reported too).

Usage: scripts/mitsuba_timing.py [ROUNDS] (needs `pip install mitsuba numpy`;
the gonio binary is target/release/gonio).
"""

import math
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GONIO = ROOT / "target/release/gonio"


def uv_sphere_obj(path, slices=64, stacks=32, centre=(0.0, 1.0, 0.0), r=1.0):
    lines = []
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            x, y, z = math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)
            lines.append(f"v {centre[0] + r * x} {centre[1] + r * y} {centre[2] + r * z}")
            lines.append(f"vn {x} {y} {z}")
    row = slices + 1
    for j in range(stacks):
        for i in range(slices):
            a, b, c, d = j * row + i + 1, j * row + i + 2, (j + 1) * row + i + 1, (j + 1) * row + i + 2
            if j != 0:
                lines.append(f"f {a}//{a} {c}//{c} {b}//{b}")
            if j != stacks - 1:
                lines.append(f"f {b}//{b} {c}//{c} {d}//{d}")
    path.write_text("\n".join(lines) + "\n")


def plane_obj(path, size=8.0, n=16):
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            lines.append(f"v {-size / 2 + size * i / n} 0 {-size / 2 + size * j / n}")
    lines.append("vn 0 1 0")
    row = n + 1
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * row + i + 1, j * row + i + 2, (j + 1) * row + i + 1, (j + 1) * row + i + 2
            lines.append(f"f {a}//1 {c}//1 {b}//1")
            lines.append(f"f {b}//1 {c}//1 {d}//1")
    path.write_text("\n".join(lines) + "\n")


def mitsuba_scene(mi, dir):
    diffuse = lambda rgb: {"type": "diffuse", "reflectance": {"type": "rgb", "value": rgb}}
    return {
        "type": "scene",
        "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0},
        "sensor": {
            "type": "perspective",
            "fov": 40.0,
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[0.0, 2.0, 5.5], target=[0.0, 0.8, 0.0], up=[0.0, 1.0, 0.0]
            ),
            "film": {"type": "hdrfilm", "width": 640, "height": 480, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": 1},
        },
        "ball": {"type": "obj", "filename": str(dir / "sphere.obj"), "bsdf": diffuse([0.8, 0.15, 0.1])},
        "floor": {"type": "obj", "filename": str(dir / "plane.obj"), "bsdf": diffuse([0.6, 0.6, 0.6])},
        "light": {"type": "point", "position": [3.0, 5.0, 3.0], "intensity": {"type": "rgb", "value": [60.0] * 3}},
    }


def gonio_ms(out):
    result = subprocess.run(
        [str(GONIO), "render", "--reference", "--timings", "-o", str(out),
         "--set", 'materials.ball.model="lambert"', "--set", "materials.ball.k_s=0",
         "--set", "lights.0.shadows=true", "--set", "ambient.radiance=[0.0, 0.0, 0.0]"],
        capture_output=True, text=True, check=True,
    )
    line = next(l for l in result.stdout.splitlines() if l.startswith("reference render"))
    return float(line.split()[2])


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        uv_sphere_obj(d / "sphere.obj")
        plane_obj(d / "plane.obj")
        gonio_times, mitsuba_times, mitsuba_loads = [], [], []
        for _ in range(rounds):
            gonio_times.append(gonio_ms(d / "gonio.exr"))
            start = time.perf_counter()
            scene = mi.load_dict(mitsuba_scene(mi, d))
            loaded = time.perf_counter()
            image = mi.render(scene, spp=1)
            done = time.perf_counter()
            mitsuba_loads.append(1e3 * (loaded - start))
            mitsuba_times.append(1e3 * (done - loaded))
            # The two images, to show the scenes are the same: mean
            # radiance over the frame (Mitsuba jitters its rays within
            # the pixel, so edges differ; the means agree closely).
            mean_mitsuba = float(mi.TensorXf(image).numpy().mean())
            mean_gonio = float(mi.TensorXf(mi.Bitmap(str(d / "gonio.exr"))).numpy()[..., :3].mean())
    print(f"mean radiance: gonio {mean_gonio:.5f}, Mitsuba {mean_mitsuba:.5f}")
    g, m, l = (statistics.median(x) for x in (gonio_times, mitsuba_times, mitsuba_loads))
    print(f"rounds: {rounds} (interleaved), load {open('/proc/loadavg').read().split()[:3]}")
    print(f"gonio --reference (BVH build + render): median {g:.1f} ms, all {sorted(round(x, 1) for x in gonio_times)}")
    print(f"Mitsuba 3 scalar_rgb render: median {m:.1f} ms, all {sorted(round(x, 1) for x in mitsuba_times)}")
    print(f"Mitsuba 3 load_dict (OBJ parse + BVH build): median {l:.1f} ms")
    print(f"ratio gonio / Mitsuba (render): {g / m:.2f}; gonio / Mitsuba (load + render): {g / (m + l):.2f}")


if __name__ == "__main__":
    main()
