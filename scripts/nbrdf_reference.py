#!/usr/bin/env python3
"""Independent reference values of the built-in measured materials, for
tests/measured.rs (`the_network_matches_independent_values`).

Reads data/measured/merl100_nbrdf_weights.json and evaluates the Neural-BRDF
network (Sztrajman et al. 2021) as the JSON's `forward`/`input` keys define
it, in plain Python floats (IEEE f64), from directions (w_i, w_o) in the
surface frame (n = +z): Rusinkiewicz's half/difference vectors computed
here with rotation matrices, not with gonio's code.

Run: python3 scripts/nbrdf_reference.py
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
WEIGHTS = os.path.join(HERE, "..", "data", "measured", "merl100_nbrdf_weights.json")


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def matvec(m, v):
    return [sum(m[r][c] * v[c] for c in range(3)) for r in range(3)]


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]


def network_input(wi, wo):
    h = normalize([a + b for a, b in zip(wi, wo)])
    theta_h = math.acos(max(-1.0, min(1.0, h[2])))
    sin_h = math.sqrt(h[0] ** 2 + h[1] ** 2)
    phi_h = 0.0 if sin_h < 1e-9 else math.atan2(h[1], h[0])
    d = matvec(rot_y(-theta_h), matvec(rot_z(-phi_h), wi))
    return [math.sin(theta_h), 0.0, math.cos(theta_h)] + d


def forward(w, x):
    def dense(x, W, b):
        return [b[j] + sum(x[i] * W[i][j] for i in range(len(x))) for j in range(len(b))]

    a1 = [max(0.0, v) for v in dense(x, w["W1"], w["b1"])]
    a2 = [max(0.0, v) for v in dense(a1, w["W2"], w["b2"])]
    return [max(0.0, math.exp(v) - 1.0) for v in dense(a2, w["W3"], w["b3"])]


def direction(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]


# (material, (θ_i, φ_i), (θ_o, φ_o)) in degrees.
CASES = [
    ("gold-metallic-paint", (30, 0), (30, 180)),
    ("gold-metallic-paint", (60, 10), (20, 200)),
    ("chrome", (45, 0), (45, 180)),
    ("chrome", (45, 0), (40, 170)),
    ("blue-fabric", (10, 0), (70, 90)),
    ("blue-fabric", (0, 0), (0, 0)),
    ("alum-bronze", (80, 30), (75, 250)),
]

if __name__ == "__main__":
    materials = json.load(open(WEIGHTS))["materials"]
    for name, (ti, pi), (to, po) in CASES:
        f = forward(materials[name], network_input(direction(ti, pi), direction(to, po)))
        print(f'    ("{name}", ({ti}.0, {pi}.0), ({to}.0, {po}.0), [{f[0]!r}, {f[1]!r}, {f[2]!r}]),')
