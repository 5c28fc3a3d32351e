//! Published optical constants `n(λ) + i k(λ)` of the metals behind the
//! coloured conductor presets ([`crate::material::conductors`]), the
//! visible rows (0.35–0.83 µm) of the refractiveindex.info database files
//! (CC0), copied from `scripts/conductor_presets.py`, which reduced them to
//! the presets' three channels. Between samples `n` and `k` are
//! interpolated linearly in wavelength, as the script does.

use crate::material::conductors::Metal;

/// One metal: the preset it was reduced to, its source, and rows of
/// (wavelength \[µm\], n, k) in increasing wavelength.
pub struct SpectralMetal {
    pub preset: &'static str,
    pub source: &'static str,
    pub rows: &'static [[f64; 3]],
}

impl SpectralMetal {
    /// `(n, k)` at `nm` nanometres, linear between the two rows around it.
    /// Panics outside the rows (the tables span 380–780 nm and more).
    pub fn index_at(&self, nm: f64) -> (f64, f64) {
        let um = nm / 1000.0;
        let i = self
            .rows
            .windows(2)
            .position(|w| w[0][0] <= um && um <= w[1][0])
            .unwrap_or_else(|| panic!("{} nm outside the {} rows", nm, self.preset));
        let ([l0, n0, k0], [l1, n1, k1]) = (self.rows[i], self.rows[i + 1]);
        let t = (um - l0) / (l1 - l0);
        (n0 + t * (n1 - n0), k0 + t * (k1 - k0))
    }
}

/// Au: P. B. Johnson, R. W. Christy, "Optical constants of the noble metals", Phys. Rev. B 6, 4370 (1972).
pub const GOLD: SpectralMetal = SpectralMetal {
    preset: "gold-rgb",
    source: "Au, Johnson & Christy 1972",
    rows: &[
        [0.3542, 1.50, 1.866],
        [0.3679, 1.48, 1.895],
        [0.3815, 1.46, 1.933],
        [0.3974, 1.47, 1.952],
        [0.4133, 1.46, 1.958],
        [0.4305, 1.45, 1.948],
        [0.4509, 1.38, 1.914],
        [0.4714, 1.31, 1.849],
        [0.4959, 1.04, 1.833],
        [0.5209, 0.62, 2.081],
        [0.5486, 0.43, 2.455],
        [0.5821, 0.29, 2.863],
        [0.6168, 0.21, 3.272],
        [0.6595, 0.14, 3.697],
        [0.7045, 0.13, 4.103],
        [0.7560, 0.14, 4.542],
        [0.8211, 0.16, 5.083],
    ],
};

/// Ag: Johnson & Christy (1972), as gold.
pub const SILVER: SpectralMetal = SpectralMetal {
    preset: "silver-rgb",
    source: "Ag, Johnson & Christy 1972",
    rows: &[
        [0.3542, 0.10, 1.419],
        [0.3679, 0.07, 1.657],
        [0.3815, 0.05, 1.864],
        [0.3974, 0.05, 2.070],
        [0.4133, 0.05, 2.275],
        [0.4305, 0.04, 2.462],
        [0.4509, 0.04, 2.657],
        [0.4714, 0.05, 2.869],
        [0.4959, 0.05, 3.093],
        [0.5209, 0.05, 3.324],
        [0.5486, 0.06, 3.586],
        [0.5821, 0.05, 3.858],
        [0.6168, 0.06, 4.152],
        [0.6595, 0.05, 4.483],
        [0.7045, 0.04, 4.838],
        [0.7560, 0.03, 5.242],
        [0.8211, 0.04, 5.727],
    ],
};

/// Cu: Johnson & Christy (1972), as gold.
pub const COPPER: SpectralMetal = SpectralMetal {
    preset: "copper-rgb",
    source: "Cu, Johnson & Christy 1972",
    rows: &[
        [0.3542, 1.37, 1.916],
        [0.3679, 1.36, 1.975],
        [0.3815, 1.33, 2.045],
        [0.3974, 1.32, 2.116],
        [0.4133, 1.28, 2.207],
        [0.4305, 1.25, 2.305],
        [0.4509, 1.24, 2.397],
        [0.4714, 1.25, 2.483],
        [0.4959, 1.22, 2.564],
        [0.5209, 1.18, 2.608],
        [0.5486, 1.02, 2.577],
        [0.5821, 0.70, 2.704],
        [0.6168, 0.30, 3.205],
        [0.6595, 0.22, 3.747],
        [0.7045, 0.21, 4.205],
        [0.7560, 0.24, 4.665],
        [0.8211, 0.26, 5.180],
    ],
};

/// Al: A. D. Rakić, "Algorithm for the determination of intrinsic optical constants of metal films: application to aluminum", Appl. Opt. 34, 4755 (1995).
pub const ALUMINIUM: SpectralMetal = SpectralMetal {
    preset: "aluminium-rgb",
    source: "Al, Rakic 1995",
    rows: &[
        [0.32628, 0.31474, 3.9165],
        [0.36466, 0.39877, 4.3957],
        [0.41328, 0.52135, 5.0008],
        [0.44280, 0.60790, 5.3676],
        [0.47687, 0.72780, 5.7781],
        [0.51660, 0.87340, 6.2418],
        [0.56357, 1.0728, 6.7839],
        [0.61993, 1.3660, 7.4052],
        [0.65225, 1.5724, 7.7354],
        [0.68881, 1.8301, 8.0601],
        [0.72932, 2.1606, 8.3565],
        [0.77491, 2.6154, 8.4914],
        [0.79478, 2.7675, 8.3866],
    ],
};

/// Fe: P. B. Johnson, R. W. Christy, "Optical constants of transition metals", Phys. Rev. B 9, 5056 (1974).
pub const IRON: SpectralMetal = SpectralMetal {
    preset: "iron-rgb",
    source: "Fe, Johnson & Christy 1974",
    rows: &[
        [0.354, 1.93, 2.35],
        [0.368, 2.02, 2.43],
        [0.381, 2.12, 2.50],
        [0.397, 2.24, 2.58],
        [0.413, 2.35, 2.65],
        [0.431, 2.48, 2.71],
        [0.451, 2.59, 2.77],
        [0.471, 2.67, 2.82],
        [0.496, 2.74, 2.88],
        [0.521, 2.86, 2.91],
        [0.549, 2.95, 2.93],
        [0.582, 2.94, 2.99],
        [0.617, 2.88, 3.05],
        [0.659, 2.92, 3.10],
        [0.704, 2.86, 3.19],
        [0.756, 2.87, 3.28],
        [0.821, 2.94, 3.39],
    ],
};

/// Every metal, in the presets' order.
pub const METALS: [&SpectralMetal; 5] = [&GOLD, &SILVER, &COPPER, &ALUMINIUM, &IRON];

/// The table of the metal a material names (`spectral_metal`).
pub fn of(metal: Metal) -> &'static SpectralMetal {
    match metal {
        Metal::Gold => &GOLD,
        Metal::Silver => &SILVER,
        Metal::Copper => &COPPER,
        Metal::Aluminium => &ALUMINIUM,
        Metal::Iron => &IRON,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each material name finds the table reduced to its preset.
    #[test]
    fn every_name_finds_its_table() {
        for metal in Metal::ALL {
            assert_eq!(of(metal).preset, metal.preset_name());
        }
    }

    /// Every table covers 380–780 nm in increasing wavelength, and
    /// interpolation returns the inner rows at their wavelengths.
    #[test]
    fn tables_cover_the_visible_and_interpolate_through_their_rows() {
        for m in METALS {
            assert!(m.rows.windows(2).all(|w| w[0][0] < w[1][0]), "{}", m.preset);
            assert!(m.rows[0][0] <= 0.380 && m.rows[m.rows.len() - 1][0] >= 0.780);
            // Inner rows: at the ends `l · 1000 / 1000` may round outside.
            for [l, n, k] in m.rows[1..m.rows.len() - 1].iter().copied() {
                let (ni, ki) = m.index_at(l * 1000.0);
                assert!((ni - n).abs() < 1e-12 && (ki - k).abs() < 1e-12);
            }
        }
    }
}
