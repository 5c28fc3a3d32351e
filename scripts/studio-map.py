#!/usr/bin/env python3
"""Writes gonio's built-in neutral studio (`[environment] map = "studio"`)
as a lat-long float EXR, for renderers that need it as a file (the Bevy
peer of scripts/texture-frame-time.sh) and for `gonio --set
environment.map=PATH`.

    scripts/studio-map.py OUT.exr

The same generator as src/environment/studio.rs (panels, room gradient,
raised-cosine edges) on the same 256 x 128 grid, each texel the mean of
4 x 4 point samples (src/environment/latlong.rs: supersampled_texels),
in the contract's direction convention: u = atan2(d.x, -d.z)/(2 pi),
v = acos(d.y)/pi, row 0 at +Y. Written as 32-bit float RGB, uncompressed
scanlines, so gonio reads back the same values it generates (to f32
rounding). Keep it in step with studio.rs: a change there is a change
here.
"""

import struct
import sys

import numpy as np

WIDTH = 256
# elevation, azimuth (from +Z towards +X), radius, edge [deg], radiance
PANELS = [
    (40.0, -45.0, 14.0, 6.0, 3.5),  # key: above the front left
    (15.0, 70.0, 18.0, 8.0, 1.6),  # fill: the right, lower and larger
    (30.0, 170.0, 12.0, 6.0, 2.5),  # rim: behind
]


def unit(elevation_deg, azimuth_deg):
    e, a = np.radians(elevation_deg), np.radians(azimuth_deg)
    return np.array([np.cos(e) * np.sin(a), np.sin(e), np.cos(e) * np.cos(a)])


def radiance(d):
    """Radiance of unit directions d[..., 3] (point-sampled)."""
    y = d[..., 1]
    room = np.where(
        y >= 0.0,
        0.45 + (0.6 - 0.45) * y,
        0.45 + (0.25 - 0.45) * np.sqrt(np.maximum(-y, 0.0)),
    )
    l = room
    for elev, azim, radius, edge, rad in PANELS:
        cosang = np.clip(d @ unit(elev, azim), -1.0, 1.0)
        angle = np.degrees(np.arccos(cosang))
        t = np.clip((angle - radius) / edge, 0.0, 1.0)
        l = l + rad * 0.5 * (1.0 + np.cos(np.pi * t))
    return l


def direction(u, v):
    phi, cos_t = 2.0 * np.pi * u, np.cos(np.pi * v)
    sin_t = np.sqrt(np.maximum(1.0 - cos_t * cos_t, 0.0))
    return np.stack([sin_t * np.sin(phi), cos_t, -sin_t * np.cos(phi)], axis=-1)


def texels():
    w, h, n = WIDTH, WIDTH // 2, 4
    col = np.arange(w)[None, :]
    row = np.arange(h)[:, None]
    acc = np.zeros((h, w))
    for a in range(n):
        for b in range(n):
            u = (col + (b + 0.5) / n) / w
            v = (row + (a + 0.5) / n) / h
            acc += radiance(direction(u + 0 * v, v + 0 * u))
    return (acc / (n * n)).astype(np.float32)


def write_exr(path, grey):
    h, w = grey.shape

    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (
        struct.pack("<ii", 20000630, 2)
        + attr("channels", "chlist", chlist)
        + attr("compression", "compression", b"\0")
        + attr("dataWindow", "box2i", box)
        + attr("displayWindow", "box2i", box)
        + attr("lineOrder", "lineOrder", b"\0")
        + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
        + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
        + attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
        + b"\0"
    )
    line_bytes = 3 * w * 4
    first = len(header) + 8 * h
    offsets = struct.pack(f"<{h}Q", *[first + y * (8 + line_bytes) for y in range(h)])
    with open(path, "wb") as f:
        f.write(header + offsets)
        for y in range(h):
            row = grey[y].astype("<f4").tobytes()
            f.write(struct.pack("<ii", y, line_bytes) + row * 3)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scripts/studio-map.py OUT.exr")
    write_exr(sys.argv[1], texels())
