#!/usr/bin/env python3
"""Measures gonio's renders against three.js, Babylon.js and Filament (scripts/peer-compare.sh
makes the renders) and writes the side-by-side pictures and the table of docs/peers.md.

For each file NAME, RENDERS/NAME/{gonio,three,babylon,filament}.png (8-bit sRGB, same camera,
map and tone map) and RENDERS/NAME/camera.json. Differences are in 8-bit sRGB codes, averaged
over the three channels and over the *object pixels*: those where gonio's or three.js's image
differs from the bare map seen through the camera (computed here: gonio's lat-long convention,
bilinear, PBR Neutral, sRGB) by more than BACKGROUND_CODES in some channel (three.js's mask
opened, the union closed, each by a 3 x 3 square). The background
itself is left out because it only measures the map's filtering (Filament's is a 256^2 cube).

Per file:
  d(a, b)      mean |a - b| over the object pixels, for every pair of renderers;
  odd(X)       mean |X - per-pixel median of the other three renderers|, for each of the four
               (for gonio: the median of the three peers);
  gonio-odd    odd(gonio); peer-odd the largest odd(peer) of the three peers;
  inside       gonio-odd <= peer-odd: gonio is not the odd one out of the four (some established
               renderer lies at least as far from the rest); margin = gonio-odd - peer-odd;
  sampled-odd  odd() of gonio with specular = "sampled", 1024 directions ("gonio-sampled.png",
               measured against the same median of the peers, not pictured), and its inside;
  in-range     the share of object pixel-channels where gonio lies within [min, max] of the
               three peers widened by 2 codes (Filament's dithering and LUT: web-peers README).

Writes DOCS/NAME.png (labelled gonio | three.js | Babylon.js | Filament, palettised PNG) and
replaces the rows of the files given in DOCS/results.csv; prints the whole table as Markdown.
"""

import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
from PIL import Image

RENDERERS = ["gonio", "three", "babylon", "filament"]
PEERS = RENDERERS[1:]
LABELS = {"gonio": "gonio", "three": "three.js r187", "babylon": "Babylon.js 9.28", "filament": "Filament 1.53.4"}
BACKGROUND_CODES = 6  # above the bilinear/rounding noise of a sharp background, measured on Box (max 3)
DITHER_CODES = 2
COLUMNS = ["file", "object_px", "gonio_three", "gonio_babylon", "gonio_filament", "three_babylon",
           "three_filament", "babylon_filament", "gonio_odd", "peer_odd", "margin", "inside", "in_range_pct", "sampled_odd", "sampled_inside",
           "missing"]


def read_hdr(path):
    """Radiance RGBE (flat or new-style RLE), rows top to bottom -> float32 (H, W, 3)."""
    data = open(path, "rb").read()
    off = 0

    def line():
        nonlocal off
        end = data.index(b"\n", off)
        text = data[off:end].decode("latin1")
        off = end + 1
        return text

    if not line().startswith("#?"):
        raise ValueError(f"{path}: not a Radiance .hdr file")
    while line() != "":
        pass
    res = line().split()
    if res[0] != "-Y" or res[2] != "+X":
        raise ValueError(f"{path}: orientation {' '.join(res)} not supported")
    h, w = int(res[1]), int(res[3])
    rgbe = np.zeros((h, w, 4), np.uint8)
    buf = np.frombuffer(data, np.uint8)
    for y in range(h):
        if 8 <= w < 32768 and buf[off] == 2 and buf[off + 1] == 2 and (int(buf[off + 2]) << 8 | int(buf[off + 3])) == w:
            off += 4
            for c in range(4):
                x = 0
                while x < w:
                    n = int(buf[off])
                    off += 1
                    if n > 128:
                        rgbe[y, x:x + n - 128, c] = buf[off]
                        off += 1
                        x += n - 128
                    else:
                        rgbe[y, x:x + n, c] = buf[off:off + n]
                        off += n
                        x += n
        else:
            rgbe[y] = buf[off:off + 4 * w].reshape(w, 4)
            off += 4 * w
    e = rgbe[..., 3].astype(np.int32)
    scale = np.where(e > 0, np.ldexp(1.0, e - 136), 0.0)
    return (rgbe[..., :3] * scale[..., None]).astype(np.float32)


def pbr_neutral(c):
    """Khronos PBR Neutral (https://github.com/KhronosGroup/ToneMapping, PBR_Neutral)."""
    start, desat = 0.8 - 0.04, 0.15
    x = np.min(c, axis=-1, keepdims=True)
    offset = np.where(x < 0.08, x - 6.25 * x * x, 0.04)
    c = c - offset
    peak = np.max(c, axis=-1, keepdims=True)
    d = 1.0 - start
    new_peak = 1.0 - d * d / (peak + d - start)
    mapped = c * (new_peak / np.maximum(peak, 1e-30))
    g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0)
    mapped = mapped * (1.0 - g) + new_peak * g
    return np.where(peak < start, c, mapped)


def srgb8(lin):
    lin = np.clip(lin, 0.0, 1.0)
    s = np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * np.power(lin, 1 / 2.4) - 0.055)
    return np.floor(s * 255.0 + 0.5)


def background(cam, env):
    """The bare map through the camera: gonio's convention u = atan2(d.x, -d.z) / 2pi,
    v = acos(d.y) / pi, texel centres at (k + 1/2) / size, bilinear, u wrapping."""
    w, h = cam["width"], cam["height"]
    pos, tgt = np.array(cam["position"], float), np.array(cam["target"], float)
    fwd = (tgt - pos) / np.linalg.norm(tgt - pos)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(cam["fov_y_deg"]) / 2)
    xs = ((np.arange(w) + 0.5) / w * 2 - 1) * t * w / h
    ys = (1 - (np.arange(h) + 0.5) / h * 2) * t
    d = fwd + xs[None, :, None] * right + ys[:, None, None] * up
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    eh, ew = env.shape[:2]
    u = (np.arctan2(d[..., 0], -d[..., 2]) / (2 * math.pi)) % 1.0
    v = np.arccos(np.clip(d[..., 1], -1, 1)) / math.pi
    fx, fy = u * ew - 0.5, np.clip(v * eh - 0.5, 0, eh - 1)
    x0, y0 = np.floor(fx).astype(int), np.floor(fy).astype(int)
    ax, ay = (fx - x0)[..., None], (fy - y0)[..., None]
    x0 %= ew
    x1, y1 = (x0 + 1) % ew, np.minimum(y0 + 1, eh - 1)
    lin = ((1 - ax) * (1 - ay) * env[y0, x0] + ax * (1 - ay) * env[y0, x1]
           + (1 - ax) * ay * env[y1, x0] + ax * ay * env[y1, x1])
    return srgb8(pbr_neutral(lin))


def dilate(m):
    """3 x 3 binary dilation."""
    p = np.pad(m, 1)
    out = np.zeros_like(m)
    for dy in range(3):
        for dx in range(3):
            out |= p[dy:dy + m.shape[0], dx:dx + m.shape[1]]
    return out


def erode(m):
    return ~dilate(~m)


def measure(name, images, bg):
    """The row of the table for one file (images: renderer -> float (H, W, 3) codes)."""
    row = {"file": name, "missing": " ".join(r for r in RENDERERS if r not in images)}
    mask = np.zeros(bg.shape[:2], bool)
    for r in ("gonio", "three"):
        if r in images:
            m = np.max(np.abs(images[r] - bg), axis=-1) > BACKGROUND_CODES
            # three.js's background (a half-float cube) strays above the threshold in scattered
            # single pixels: an opening removes them, a closing fills the object's holes.
            mask |= dilate(erode(m)) if r == "three" else m
    mask = erode(dilate(mask))
    row["object_px"] = int(mask.sum())
    if not mask.any():
        return row, mask
    pix = {r: images[r][mask] for r in RENDERERS if r in images}
    for i, a in enumerate(RENDERERS):
        for b in RENDERERS[i + 1:]:
            if a in pix and b in pix:
                row[f"{a}_{b}"] = float(np.mean(np.abs(pix[a] - pix[b])))
    if len(pix) == 4:
        odd = {}
        for r in RENDERERS:
            med = np.median(np.stack([pix[o] for o in RENDERERS if o != r]), axis=0)
            odd[r] = float(np.mean(np.abs(pix[r] - med)))
        row["gonio_odd"] = odd["gonio"]
        row["peer_odd"] = max(odd[p] for p in PEERS)
        row["margin"] = row["gonio_odd"] - row["peer_odd"]
        row["inside"] = "yes" if row["margin"] <= 0 else "no"
        if "gonio-sampled" in images:
            s_pix = images["gonio-sampled"][mask]
            med = np.median(np.stack([pix[p] for p in PEERS]), axis=0)
            row["sampled_odd"] = float(np.mean(np.abs(s_pix - med)))
            row["sampled_inside"] = "yes" if row["sampled_odd"] <= row["peer_odd"] else "no"
        stack = np.stack([pix[p] for p in PEERS])
        lo, hi = stack.min(axis=0) - DITHER_CODES, stack.max(axis=0) + DITHER_CODES
        g = pix["gonio"]
        row["in_range_pct"] = float(100 * np.mean((g >= lo) & (g <= hi)))
    return row, mask


def why_missing(log_path):
    """A short reason for a render that did not happen, from its log."""
    try:
        log = open(log_path, errors="replace").read()
    except OSError:
        return "not rendered"
    m = re.search(r"requires the glTF extension (\S+)", log)
    if m:
        return "refuses " + m.group(1).rstrip(",")
    if "timed out" in log:
        return "timed out"
    return "failed"


def montage(name, paths, out, logs):
    """gonio | three.js | Babylon.js | Filament, labelled, 128 colours (no dithering) to keep the PNG near 120 kB."""
    args = ["convert"]
    for r in RENDERERS:
        p = paths.get(r)
        src = p if p else "xc:gray20[480x360]"
        text = LABELS[r] if p else f"{LABELS[r]}: {why_missing(logs[r])}"
        args += ["(", src, "-resize", "480x360!", "-gravity", "north", "-background", "black", "-fill", "white",
                 "-font", "DejaVu-Sans", "-pointsize", "15", "-splice", "0x22", "-annotate", "+0+3", text, ")"]
    args += ["+append", "-gravity", "south", "-background", "black", "-splice", "0x0",
             "-dither", "None", "-colors", "128", "PNG8:" + out]
    subprocess.run(args, check=True)


def fmt(v):
    if isinstance(v, float):
        return f"{v:.1f}"
    return str(v) if v is not None else ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--renders", required=True)
    ap.add_argument("--map", required=True)
    ap.add_argument("--docs", required=True)
    ap.add_argument("names", nargs="+")
    a = ap.parse_args()
    env = read_hdr(a.map)
    csv_path = os.path.join(a.docs, "results.csv")
    rows = {}
    if os.path.exists(csv_path):
        with open(csv_path, newline="") as f:
            for r in csv.DictReader(f):
                rows[r["file"]] = r
    order = list(rows)
    for name in a.names:
        d = os.path.join(a.renders, name)
        cam = json.load(open(os.path.join(d, "camera.json")))
        paths = {r: os.path.join(d, r + ".png") for r in RENDERERS if os.path.exists(os.path.join(d, r + ".png"))}
        images = {r: np.asarray(Image.open(p).convert("RGB"), dtype=np.float64) for r, p in paths.items()}
        sampled = os.path.join(d, "gonio-sampled.png")
        if os.path.exists(sampled):
            images["gonio-sampled"] = np.asarray(Image.open(sampled).convert("RGB"), dtype=np.float64)
        bg = background(cam, env)
        row, mask = measure(name, images, bg)
        Image.fromarray((mask * 255).astype(np.uint8)).save(os.path.join(d, "mask.png"))
        Image.fromarray(bg.astype(np.uint8)).save(os.path.join(d, "background.png"))
        montage(name, paths, os.path.join(a.docs, name + ".png"), {r: os.path.join(d, r + ".log") for r in RENDERERS})
        rows[name] = {k: fmt(row.get(k)) for k in COLUMNS}
        if name not in order:
            order.append(name)
    with open(csv_path, "w", newline="") as f:
        wr = csv.DictWriter(f, COLUMNS)
        wr.writeheader()
        for n in order:
            wr.writerow({k: rows[n].get(k, "") for k in COLUMNS})
    head = ["file", "object px", "g–three", "g–babylon", "g–filament", "three–babylon", "three–filament",
            "babylon–filament", "gonio odd", "peer odd", "margin", "inside", "in range %", "sampled odd", "sampled inside"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for n in order:
        r = rows[n]
        cells = [r.get(k, "") for k in COLUMNS[:-1]]
        if r.get("missing"):
            cells[0] += f" (no {r['missing']})"
        print("| " + " | ".join(cells) + " |")
    full = [rows[n] for n in order if rows[n].get("inside")]
    if full:
        num = lambda k: np.array([float(r[k]) for r in full])
        nearest = np.minimum(np.minimum(num("gonio_three"), num("gonio_babylon")), num("gonio_filament"))
        pairs = np.minimum(np.minimum(num("three_babylon"), num("three_filament")), num("babylon_filament"))
        print(f"\ninside on {sum(r['inside'] == 'yes' for r in full)} of {len(full)} files rendered by all four "
              f"(sampled: {sum(r.get('sampled_inside') == 'yes' for r in full)}); "
              f"medians over the files: gonio-odd {np.median(num('gonio_odd')):.1f}, "
              f"peer-odd {np.median(num('peer_odd')):.1f}, gonio to its nearest peer {np.median(nearest):.1f}, "
              f"closest pair of peers {np.median(pairs):.1f} codes")


if __name__ == "__main__":
    sys.exit(main())
