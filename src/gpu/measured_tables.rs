//! The tables the GPU renders measured materials from (the lecture:
//! "Rendering from measured BRDF: look-up of BRDF values during
//! rendering; sampled BRDF must be filtered"). Each distinct measured BRDF
//! of a scene becomes a MERL-format table of the scene's resolution
//! ([`crate::scene::Scene::measured_table`], scene key
//! `shading.measured_table`), sampled on the CPU from its source (the
//! network in `f64`, or the file's own interpolation), rounded to `f32`
//! and concatenated into one storage buffer (group 0, binding 3, bound
//! only when the scene has a measured material). A material's `lobe`
//! holds its table's first index (as bits) and its sample counts;
//! `shaders/brdf/measured.wgsl` interpolates trilinearly, the rule of
//! [`MerlTable::f_r`].
//!
//! Tables are built once per (BRDF, resolution) and kept: a viewer edit or
//! a second render of the same material reuses them.

use crate::material::Material;
use crate::material::measured::merl::MerlTable;
use crate::material::measured::{MeasuredBrdf, Source, coords};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};
use std::sync::{Arc, LazyLock, Mutex};

pub use crate::material::measured::DEFAULT_TABLE_RESOLUTION;

/// The scene's tables, concatenated, and where each BRDF's starts.
#[derive(Clone, Debug, Default)]
pub struct MeasuredTables {
    /// RGB `f_r` [1/sr] per sample, `3 · (i_φ + n_φ · (i_d + n_d · i_h))`
    /// from a table's first index.
    pub data: Vec<f32>,
    /// (the BRDF, its first index in `data`).
    placements: Vec<(&'static MeasuredBrdf, u32)>,
    pub resolution: [u32; 3],
    /// Each BRDF is its network's 675 weights (`Network::flat`), not a
    /// table (`shading.measured_mode = "network"`).
    pub network: bool,
}

impl MeasuredTables {
    /// The tables of the measured materials among `materials`.
    pub fn new(materials: &[Material], resolution: [u32; 3]) -> Self {
        let mut out = MeasuredTables {
            resolution,
            ..Default::default()
        };
        for m in materials {
            let Some(brdf) = m.measured_brdf() else {
                continue;
            };
            if out.placements.iter().any(|(b, _)| std::ptr::eq(*b, brdf)) {
                continue;
            }
            out.placements.push((brdf, out.data.len() as u32));
            out.data.extend(table(brdf, resolution).iter());
        }
        out
    }

    /// The networks' weights of the measured materials among `materials`
    /// (`shading.measured_mode = "network"`): per BRDF its 675 weights in
    /// `Network::flat`'s order, rounded to `f32`, read by the network arm
    /// of `shaders/brdf/measured.wgsl`. A MERL file has no network: the
    /// scene loader refuses one in this mode; here it gets zeros.
    pub fn networks(materials: &[Material]) -> Self {
        use crate::material::measured::network::WEIGHT_COUNT;
        let mut out = MeasuredTables {
            network: true,
            ..Default::default()
        };
        for m in materials {
            let Some(brdf) = m.measured_brdf() else {
                continue;
            };
            if out.placements.iter().any(|(b, _)| std::ptr::eq(*b, brdf)) {
                continue;
            }
            out.placements.push((brdf, out.data.len() as u32));
            match &brdf.source {
                Source::Network(n) => out.data.extend(n.flat().iter().map(|&w| w as f32)),
                Source::Table(_) => out.data.extend(std::iter::repeat_n(0.0, WEIGHT_COUNT)),
            }
        }
        out
    }

    /// `GpuMaterial.lobe` of a material of `brdf`: its first index (bits)
    /// and the sample counts (zero for a network), `n_φ` negative for a φ_d axis over 2π (a
    /// network's table, [`phi_period`]).
    pub fn lobe(&self, brdf: &MeasuredBrdf) -> [f32; 4] {
        let first = self
            .placements
            .iter()
            .find(|(b, _)| std::ptr::eq(*b, brdf))
            .map_or(0, |(_, first)| *first);
        if self.network {
            return [f32::from_bits(first), 0.0, 0.0, 0.0];
        }
        let [nh, nd, np] = self.resolution;
        let np = if phi_period(brdf) > PI {
            -(np as f32)
        } else {
            np as f32
        };
        [f32::from_bits(first), nh as f32, nd as f32, np]
    }
}

type Cache = HashMap<(usize, [u32; 3]), Arc<Vec<f32>>>;
static CACHE: LazyLock<Mutex<Cache>> = LazyLock::new(Default::default);

/// The `f32` table of `brdf` at `resolution`, built once.
pub fn table(brdf: &'static MeasuredBrdf, resolution: [u32; 3]) -> Arc<Vec<f32>> {
    let key = (std::ptr::from_ref(brdf) as usize, resolution);
    if let Some(t) = CACHE.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return t.clone();
    }
    let built = Arc::new(build(brdf, resolution.map(|n| n as usize)));
    CACHE
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, built.clone());
    built
}

/// The φ_d period of `brdf`'s tables: π for a file (MERL's fold), 2π for a
/// network, whose value at φ_d + π differs slightly from that at φ_d (up
/// to a few per cent: folding made a table render 1–3 % off the network
/// at every resolution).
pub fn phi_period(brdf: &MeasuredBrdf) -> f64 {
    match &brdf.source {
        Source::Network(_) => TAU,
        Source::Table(t) => t.phi_period,
    }
}

/// Samples `brdf` at the sample angles of a table of `dims` (in parallel
/// over θ_h), RGB interleaved. A file at its own resolution is copied.
pub fn build(brdf: &MeasuredBrdf, dims: [usize; 3]) -> Vec<f32> {
    if let Source::Table(t) = &brdf.source
        && t.dims == dims
    {
        return (0..t.channels[0].len())
            .flat_map(|i| t.channels.iter().map(move |c| c[i] as f32))
            .collect();
    }
    let [nh, nd, np] = dims;
    let period = phi_period(brdf);
    (0..nh)
        .into_par_iter()
        .flat_map_iter(|ih| {
            (0..nd * np).flat_map(move |k| {
                let (th, td, pd) = crate::material::measured::merl::sample_angles_over(
                    dims,
                    period,
                    ih,
                    k / np,
                    k % np,
                );
                let f = f_r_at(brdf, th, td, pd);
                [f.x as f32, f.y as f32, f.z as f32]
            })
        })
        .collect()
}

/// `brdf`'s `f_r` at half/difference angles (`φ_h = 0`).
fn f_r_at(brdf: &MeasuredBrdf, theta_h: f64, theta_d: f64, phi_d: f64) -> DVec3 {
    brdf.f_r_half_diff(&coords::half_diff_of_angles(theta_h, theta_d, phi_d))
}

/// The table `build` makes, in `f64`, as a [`MerlTable`]: the CPU twin of
/// the GPU's look-up (tests).
pub fn as_merl_table(brdf: &MeasuredBrdf, dims: [usize; 3]) -> MerlTable {
    MerlTable::sample_over(dims, phi_period(brdf), |th, td, pd| {
        f_r_at(brdf, th, td, pd)
    })
}
