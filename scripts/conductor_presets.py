#!/usr/bin/env python3
"""Reduces published spectral optical constants of metals to the per-channel
(linear Rec.709 R, G, B) eta, kappa of gonio's coloured conductor presets
(src/material/presets.rs, `COLOURED_CONDUCTORS`). Standard library only.

Reduction, per metal:
 1. F0(l) = ((n-1)^2 + k^2) / ((n+1)^2 + k^2): the exact Fresnel reflectance at
    normal incidence of n + ik, at every 5 nm from 380 to 780 nm (n, k
    linearly interpolated in wavelength between the published samples).
 2. XYZ = sum F0 S xbar / sum S ybar with S = CIE standard illuminant D65 and
    xbar, ybar, zbar the CIE 1931 2-degree observer (CIE 15.2-1986 Tables 1.1,
    2.1, 5 nm, as abridged to 4 digits).
 3. Linear Rec.709 RGB = M XYZ (IEC 61966-2-1 matrix), divided channel-wise by
    the RGB of a perfect reflector (F0 = 1) under the same tables, so that
    white maps to exactly (1, 1, 1) despite the 4-digit rounding.
    A channel above the metal's largest spectral F0 in 380-780 nm (gold's red
    is 1.038: its yellow lies outside the Rec.709 gamut) is clipped to that
    largest F0, since no Fresnel reflectance reaches 1; G and B stay exact.
 4. Per channel c: eta_c = n(l_c) at l_c = 630 / 532 / 465 nm (R / G / B),
    and kappa_c solved in closed form so that F0(eta_c, kappa_c) equals the
    colour's channel exactly:
        kappa^2 = (F0 (eta+1)^2 - (eta-1)^2) / (1 - F0).
    So the normal-incidence colour is the measured one; eta (which shapes the
    angular fall-off) is the measurement at the channel's wavelength.

Data (refractiveindex.info database, CC0; visible rows copied below):
  Au, Ag, Cu: P. B. Johnson, R. W. Christy, Phys. Rev. B 6, 4370 (1972).
  Fe:         P. B. Johnson, R. W. Christy, Phys. Rev. B 9, 5056 (1974).
  Al:         A. D. Rakic, Appl. Opt. 34, 4755 (1995).
Run: python3 scripts/conductor_presets.py  (prints the Rust table rows).
"""
import math

# wavelength (um), n, k: the rows of the database files that span 0.36-0.83 um.
METALS = {
    "gold-rgb": ("Au, Johnson & Christy 1972", """
0.3542 1.50 1.866
0.3679 1.48 1.895
0.3815 1.46 1.933
0.3974 1.47 1.952
0.4133 1.46 1.958
0.4305 1.45 1.948
0.4509 1.38 1.914
0.4714 1.31 1.849
0.4959 1.04 1.833
0.5209 0.62 2.081
0.5486 0.43 2.455
0.5821 0.29 2.863
0.6168 0.21 3.272
0.6595 0.14 3.697
0.7045 0.13 4.103
0.7560 0.14 4.542
0.8211 0.16 5.083
"""),
    "silver-rgb": ("Ag, Johnson & Christy 1972", """
0.3542 0.10 1.419
0.3679 0.07 1.657
0.3815 0.05 1.864
0.3974 0.05 2.070
0.4133 0.05 2.275
0.4305 0.04 2.462
0.4509 0.04 2.657
0.4714 0.05 2.869
0.4959 0.05 3.093
0.5209 0.05 3.324
0.5486 0.06 3.586
0.5821 0.05 3.858
0.6168 0.06 4.152
0.6595 0.05 4.483
0.7045 0.04 4.838
0.7560 0.03 5.242
0.8211 0.04 5.727
"""),
    "copper-rgb": ("Cu, Johnson & Christy 1972", """
0.3542 1.37 1.916
0.3679 1.36 1.975
0.3815 1.33 2.045
0.3974 1.32 2.116
0.4133 1.28 2.207
0.4305 1.25 2.305
0.4509 1.24 2.397
0.4714 1.25 2.483
0.4959 1.22 2.564
0.5209 1.18 2.608
0.5486 1.02 2.577
0.5821 0.70 2.704
0.6168 0.30 3.205
0.6595 0.22 3.747
0.7045 0.21 4.205
0.7560 0.24 4.665
0.8211 0.26 5.180
"""),
    "aluminium-rgb": ("Al, Rakic 1995", """
0.32628 0.31474 3.9165
0.36466 0.39877 4.3957
0.41328 0.52135 5.0008
0.44280 0.60790 5.3676
0.47687 0.72780 5.7781
0.51660 0.87340 6.2418
0.56357 1.0728 6.7839
0.61993 1.3660 7.4052
0.65225 1.5724 7.7354
0.68881 1.8301 8.0601
0.72932 2.1606 8.3565
0.77491 2.6154 8.4914
0.79478 2.7675 8.3866
"""),
    "iron-rgb": ("Fe, Johnson & Christy 1974", """
0.354 1.93 2.35
0.368 2.02 2.43
0.381 2.12 2.50
0.397 2.24 2.58
0.413 2.35 2.65
0.431 2.48 2.71
0.451 2.59 2.77
0.471 2.67 2.82
0.496 2.74 2.88
0.521 2.86 2.91
0.549 2.95 2.93
0.582 2.94 2.99
0.617 2.88 3.05
0.659 2.92 3.10
0.704 2.86 3.19
0.756 2.87 3.28
0.821 2.94 3.39
"""),
}

# CIE 15.2-1986, 380..780 nm every 5 nm.
D65 = [49.9755, 52.3118, 54.6482, 68.7015, 82.7549, 87.1204, 91.486, 92.4589,
       93.4318, 90.057, 86.6823, 95.7736, 104.865, 110.936, 117.008, 117.41,
       117.812, 116.336, 114.861, 115.392, 115.923, 112.367, 108.811, 109.082,
       109.354, 108.578, 107.802, 106.296, 104.79, 106.239, 107.689, 106.047,
       104.405, 104.225, 104.046, 102.023, 100.0, 98.1671, 96.3342, 96.0611,
       95.788, 92.2368, 88.6856, 89.3459, 90.0062, 89.8026, 89.5991, 88.6489,
       87.6987, 85.4936, 83.2886, 83.4939, 83.6992, 81.863, 80.0268, 80.1207,
       80.2146, 81.2462, 82.2778, 80.281, 78.2842, 74.0027, 69.7213, 70.6652,
       71.6091, 72.979, 74.349, 67.9765, 61.604, 65.7448, 69.8856, 72.4863,
       75.087, 69.3398, 63.5927, 55.0054, 46.4182, 56.6118, 66.8054, 65.0941,
       63.3828]
XBAR = [0.0014, 0.0022, 0.0042, 0.0076, 0.0143, 0.0232, 0.0435, 0.0776, 0.1344,
        0.2148, 0.2839, 0.3285, 0.3483, 0.3481, 0.3362, 0.3187, 0.2908, 0.2511,
        0.1954, 0.1421, 0.0956, 0.0580, 0.0320, 0.0147, 0.0049, 0.0024, 0.0093,
        0.0291, 0.0633, 0.1096, 0.1655, 0.2257, 0.2904, 0.3597, 0.4334, 0.5121,
        0.5945, 0.6784, 0.7621, 0.8425, 0.9163, 0.9786, 1.0263, 1.0567, 1.0622,
        1.0456, 1.0026, 0.9384, 0.8544, 0.7514, 0.6424, 0.5419, 0.4479, 0.3608,
        0.2835, 0.2187, 0.1649, 0.1212, 0.0874, 0.0636, 0.0468, 0.0329, 0.0227,
        0.0158, 0.0114, 0.0081, 0.0058, 0.0041, 0.0029, 0.0020, 0.0014, 0.0010,
        0.0007, 0.0005, 0.0003, 0.0002, 0.0002, 0.0001, 0.0001, 0.0001, 0.0000]
YBAR = [0, 0.0001, 0.0001, 0.0002, 0.0004, 0.0006, 0.0012, 0.0022, 0.004, 0.0073,
        0.0116, 0.0168, 0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.091, 0.1126,
        0.139, 0.1693, 0.208, 0.2586, 0.323, 0.4073, 0.503, 0.6082, 0.71, 0.7932,
        0.862, 0.9149, 0.954, 0.9803, 0.995, 1, 0.995, 0.9786, 0.952, 0.9154, 0.87,
        0.8163, 0.757, 0.6949, 0.631, 0.5668, 0.503, 0.4412, 0.381, 0.321, 0.265,
        0.217, 0.175, 0.1382, 0.107, 0.0816, 0.061, 0.0446, 0.032, 0.0232, 0.017,
        0.0119, 0.0082, 0.0057, 0.0041, 0.0029, 0.0021, 0.0015, 0.001, 0.0007,
        0.0005, 0.0004, 0.0002, 0.0002, 0.0001, 0.0001, 0.0001, 0, 0, 0, 0]
# zbar is tabulated to 630 nm; zero beyond.
ZBAR = [0.0065, 0.0105, 0.0201, 0.0362, 0.0679, 0.1102, 0.2074, 0.3713, 0.6456,
        1.0391, 1.3856, 1.623, 1.7471, 1.7826, 1.7721, 1.7441, 1.6692, 1.5281,
        1.2876, 1.0419, 0.813, 0.6162, 0.4652, 0.3533, 0.272, 0.2123, 0.1582,
        0.1117, 0.0782, 0.0573, 0.0422, 0.0298, 0.0203, 0.0134, 0.0087, 0.0057,
        0.0039, 0.0027, 0.0021, 0.0018, 0.0017, 0.0014, 0.0011, 0.001, 0.0008,
        0.0006, 0.0003, 0.0002, 0.0002, 0.0001, 0]
ZBAR += [0.0] * (len(XBAR) - len(ZBAR))
WAVELENGTHS = [380 + 5 * i for i in range(len(XBAR))]
XYZ_TO_709 = [[3.2404542, -1.5371385, -0.4985314],
              [-0.9692660, 1.8760108, 0.0415560],
              [0.0556434, -0.2040259, 1.0572252]]
CHANNEL_NM = (630.0, 532.0, 465.0)


def parse(text):
    return [tuple(float(v) for v in line.split()) for line in text.strip().splitlines()]


def interp(rows, nm):
    um = nm / 1000.0
    for (l0, n0, k0), (l1, n1, k1) in zip(rows, rows[1:]):
        if l0 <= um <= l1:
            t = (um - l0) / (l1 - l0)
            return n0 + t * (n1 - n0), k0 + t * (k1 - k0)
    raise ValueError(f"{nm} nm outside the data")


def f0(n, k):
    return ((n - 1) ** 2 + k * k) / ((n + 1) ** 2 + k * k)


def rgb_of(reflectance):
    norm = sum(s * y for s, y in zip(D65, YBAR))
    xyz = [sum(r * s * c for r, s, c in zip(reflectance, D65, cmf)) / norm
           for cmf in (XBAR, YBAR, ZBAR)]
    return [sum(m * v for m, v in zip(row, xyz)) for row in XYZ_TO_709]


def reduce(rows):
    white = rgb_of([1.0] * len(WAVELENGTHS))
    spectral = [f0(*interp(rows, nm)) for nm in WAVELENGTHS]
    rgb = [min(c / w, max(spectral)) for c, w in zip(rgb_of(spectral), white)]
    eta, kappa = [], []
    for c, nm in zip(rgb, CHANNEL_NM):
        n, k_sampled = interp(rows, nm)
        k2 = (c * (n + 1) ** 2 - (n - 1) ** 2) / (1 - c)
        assert k2 > 0, (nm, c, n)
        eta.append(n)
        kappa.append(math.sqrt(k2))
    return rgb, eta, kappa


def main():
    for name, (source, text) in METALS.items():
        rows = parse(text)
        rgb, eta, kappa = reduce(rows)
        white = rgb_of([1.0] * len(WAVELENGTHS))
        spectral = [f0(*interp(rows, nm)) for nm in WAVELENGTHS]
        unclipped = [c / w for c, w in zip(rgb_of(spectral), white)]
        sampled = [interp(rows, nm) for nm in CHANNEL_NM]
        f = lambda v: ", ".join(f"{x:.4f}" for x in v)
        print(f"// {name}: {source}; F0 = [{f(rgb)}]; kappa sampled at the "
              f"channel wavelengths [{f(k for _, k in sampled)}]; before clipping "
              f"[{f(unclipped)}], largest spectral F0 {max(spectral):.4f}")
        print(f'("{name}", [{f(eta)}], [{f(kappa)}], [{f(rgb)}]),')


if __name__ == "__main__":
    main()
