//! The MERL BRDF table format (Matusik et al. 2003), read and written from
//! its description in `data/measured/README.md` (not from MERL's code):
//!
//! * a 12-byte header, three little-endian `i32`: the sample counts
//!   `(n_h, n_d, n_φ)` of `(θ_h, θ_d, φ_d)`, `(90, 90, 180)` for MERL's files;
//! * `3 · n_h · n_d · n_φ` little-endian `f64`, all red, then all green,
//!   then all blue, at index `i_φ + n_φ · (i_d + n_d · i_h)`;
//! * channel scales `1/1500`, `1.15/1500`, `1.66/1500` make them `f_r` in
//!   1/sr; a negative value marks a sample below the horizon (missing).
//!
//! Sample `k` of each axis lies at `θ_h = (k/n_h)² · π/2` (the θ_h axis in
//! square-root spacing, fine near the specular peak), `θ_d = k/n_d · π/2`,
//! `φ_d = k/n_φ · π` (reciprocity folds `φ_d` by π). [`MerlTable::f_r`]
//! interpolates trilinearly between them in the continuous indices
//! `u_h = sqrt(θ_h/(π/2)) · n_h`, `u_d`, `u_φ` (the contract's rule),
//! `φ_d` wrapping around, the θ axes clamped at their last sample, missing
//! samples as 0. The same rule looks up the GPU's tables
//! (`shaders/brdf/measured.wgsl`), which are MERL-format tables of another
//! resolution.

use crate::base::Rgb;
use crate::base::input::read_regular_file;
use crate::base::range;
use sha2::{Digest, Sha256};
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// The channel scales: stored value × scale = `f_r` [1/sr].
pub const CHANNEL_SCALE: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// MERL's sample counts `(θ_h, θ_d, φ_d)`.
pub const MERL_DIMS: [usize; 3] = [90, 90, 180];

/// Largest sample count of one axis gonio reads (MERL's is 180): a header
/// asking for more is an error, not an allocation.
pub const MAX_SAMPLES_PER_AXIS: usize = 4096;

/// Largest MERL file gonio reads (1 GiB, 30 times MERL's 33.6 MB): a
/// bigger file, or a FIFO or device named as one, is refused before it is
/// read.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// sha256 and size of the 100 original MERL files (`data/measured/`).
const KNOWN_FILES: &str = include_str!("../../../data/measured/merl-lfs-sha256.txt");

/// A MERL-format table of `f_r`, scaled to 1/sr, missing samples as 0.
#[derive(Clone, Debug, PartialEq)]
pub struct MerlTable {
    /// Sample counts `(n_h, n_d, n_φ)`.
    pub dims: [usize; 3],
    /// `f_r` [1/sr] per channel, at index `i_φ + n_φ · (i_d + n_d · i_h)`.
    pub channels: [Vec<f64>; 3],
    /// Samples marked missing (negative) in the file, per channel.
    pub missing: usize,
    /// The file's sha256 (hex).
    pub sha256: String,
    /// The MERL material this file is, if its sha256 is one of the 100.
    pub known_as: Option<String>,
    /// The period of the φ_d axis: π for MERL's files (reciprocity folds
    /// φ_d by π), 2π for gonio's tables of a network (which is not exactly
    /// symmetric under φ_d → φ_d + π, and is the truth as it is).
    pub phi_period: f64,
}

impl MerlTable {
    /// Reads and validates the file `path`; the message names the file.
    pub fn read(path: &Path) -> Result<MerlTable, String> {
        let bytes = read_regular_file(path, MAX_FILE_BYTES)
            .map_err(|e| format!("MERL table {}: {e}", path.display()))?;
        MerlTable::parse(&bytes).map_err(|p| format!("MERL table {}: {p}", path.display()))
    }

    /// Validates and decodes a table held in memory.
    pub fn parse(bytes: &[u8]) -> Result<MerlTable, String> {
        let header = bytes.get(..12).ok_or_else(|| {
            format!(
                "truncated: {} bytes, shorter than the 12-byte header (three little-endian i32 sample counts)",
                bytes.len()
            )
        })?;
        let dim = |k: usize| i32::from_le_bytes(header[4 * k..4 * k + 4].try_into().unwrap());
        let raw = [dim(0), dim(1), dim(2)];
        let valid = |n: i32| n >= 1 && n as usize <= MAX_SAMPLES_PER_AXIS;
        if !raw.iter().all(|&n| valid(n)) {
            return Err(format!(
                "wrong header: sample counts ({}, {}, {}) for (θ_h, θ_d, φ_d), expected each in 1..={MAX_SAMPLES_PER_AXIS} (MERL's are (90, 90, 180)); is this a MERL .binary file?",
                raw[0], raw[1], raw[2]
            ));
        }
        let dims = raw.map(|n| n as usize);
        let count = dims.iter().product::<usize>();
        let expected = 12 + 3 * 8 * count as u64;
        if bytes.len() as u64 != expected {
            let what = if (bytes.len() as u64) < expected {
                "truncated"
            } else {
                "wrong size"
            };
            return Err(format!(
                "{what}: {} bytes, but its header ({}, {}, {}) needs 12 + 3·8·{count} = {expected} bytes",
                bytes.len(),
                dims[0],
                dims[1],
                dims[2]
            ));
        }
        let mut missing = 0;
        let mut channels: [Vec<f64>; 3] = Default::default();
        for (c, channel) in channels.iter_mut().enumerate() {
            let start = 12 + c * count * 8;
            *channel = bytes[start..start + count * 8]
                .chunks_exact(8)
                .enumerate()
                .map(|(i, b)| {
                    let v = f64::from_le_bytes(b.try_into().unwrap());
                    // Negative marks a missing sample; the rest is held to
                    // the range rule of every reflectance source.
                    if v.is_finite() && v < 0.0 {
                        missing += 1;
                        return Ok(0.0);
                    }
                    let f_r = v * CHANNEL_SCALE[c];
                    if !range::is_reflectance(f_r) {
                        let (ih, id, ip) = (i / (dims[1] * dims[2]), i / dims[2] % dims[1], i % dims[2]);
                        return Err(format!(
                            "value {v} in the {} channel at (θ_h, θ_d, φ_d) index ({ih}, {id}, {ip}); values must be finite (negative marks a missing sample) and scale to at most f_r = {:e} 1/sr (the GPU computes in f32, largest 3.4e38)",
                            ["red", "green", "blue"][c],
                            range::MAX_REFLECTANCE
                        ));
                    }
                    Ok(f_r)
                })
                .collect::<Result<_, _>>()?;
        }
        let sha256 = hex(&Sha256::digest(bytes));
        let known_as = known_material(&sha256).map(str::to_string);
        Ok(MerlTable {
            dims,
            channels,
            missing,
            sha256,
            known_as,
            phi_period: PI,
        })
    }

    /// A table of `dims` samples of `f`, a function of `(θ_h, θ_d, φ_d)`
    /// (the samples' angles in the module doc).
    pub fn sample(dims: [usize; 3], f: impl Fn(f64, f64, f64) -> Rgb) -> MerlTable {
        MerlTable::sample_over(dims, PI, f)
    }

    /// [`MerlTable::sample`] with the φ_d axis over `[0, phi_period)`.
    pub fn sample_over(
        dims: [usize; 3],
        phi_period: f64,
        f: impl Fn(f64, f64, f64) -> Rgb,
    ) -> MerlTable {
        let count = dims.iter().product::<usize>();
        let mut channels: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(count));
        for ih in 0..dims[0] {
            for id in 0..dims[1] {
                for ip in 0..dims[2] {
                    let (th, td, pd) = sample_angles_over(dims, phi_period, ih, id, ip);
                    let v = f(th, td, pd);
                    for (c, ch) in channels.iter_mut().enumerate() {
                        ch.push(v[c]);
                    }
                }
            }
        }
        MerlTable {
            dims,
            channels,
            missing: 0,
            sha256: String::new(),
            known_as: None,
            phi_period,
        }
    }

    /// The file's bytes (values divided by the channel scales).
    pub fn encode(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(12 + 24 * self.channels[0].len());
        for n in self.dims {
            out.extend((n as i32).to_le_bytes());
        }
        for (c, ch) in self.channels.iter().enumerate() {
            for v in ch {
                out.extend((v / CHANNEL_SCALE[c]).to_le_bytes());
            }
        }
        out
    }

    /// `f_r` [1/sr] at `(θ_h, θ_d, φ_d)` by trilinear interpolation (see
    /// the module doc).
    pub fn f_r(&self, theta_h: f64, theta_d: f64, phi_d: f64) -> Rgb {
        let [nh, nd, np] = self.dims;
        let (h0, h1, th) = clamped(theta_h_index(theta_h, nh), nh);
        let (d0, d1, td) = clamped(theta_d.max(0.0) / FRAC_PI_2 * nd as f64, nd);
        let (p0, p1, tp) = wrapped(phi_index(phi_d, np, self.phi_period), np);
        let mut out = [0.0; 3];
        for (c, ch) in self.channels.iter().enumerate() {
            let at = |ih: usize, id: usize, ip: usize| ch[ip + np * (id + nd * ih)];
            let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
            let along_phi = |ih, id| lerp(at(ih, id, p0), at(ih, id, p1), tp);
            let along_d = |ih| lerp(along_phi(ih, d0), along_phi(ih, d1), td);
            out[c] = lerp(along_d(h0), along_d(h1), th);
        }
        Rgb::from_array(out)
    }
}

impl MerlTable {
    /// The trilinear filter's error estimate at `(θ_h, θ_d, φ_d)`, per
    /// channel: linear interpolation over a step of 1 (index units) errs
    /// by at most `⅛ max|f''|`, and the axes add; `f''` along each axis is
    /// estimated by the largest second difference of the samples at the
    /// cell's corners and their neighbours (4 × 4 × 4 samples; an axis'
    /// end has none): curvature varies within a cell, and the
    /// neighbouring cells' second differences see where it grows.
    pub fn second_difference_bound(&self, theta_h: f64, theta_d: f64, phi_d: f64) -> Rgb {
        let [nh, nd, np] = self.dims;
        let u_h = theta_h_index(theta_h, nh);
        let u_d = theta_d.max(0.0) / FRAC_PI_2 * nd as f64;
        let (h0, h1, _) = clamped(u_h, nh);
        let (d0, d1, _) = clamped(u_d, nd);
        let (p0, p1, _) = wrapped(phi_index(phi_d, np, self.phi_period), np);
        let mut out = [0.0; 3];
        for (c, ch) in self.channels.iter().enumerate() {
            let at = |ih: usize, id: usize, ip: usize| ch[ip + np * (id + nd * ih)];
            let mut sum = 0.0;
            for axis in 0..3 {
                let mut worst: f64 = 0.0;
                for ih in h0.saturating_sub(1)..=(h1 + 1).min(nh - 1) {
                    for id in d0.saturating_sub(1)..=(d1 + 1).min(nd - 1) {
                        for ip in [(p0 + np - 1) % np, p0, p1, (p1 + 1) % np] {
                            let second = match axis {
                                0 if ih >= 1 && ih + 1 < nh => {
                                    at(ih - 1, id, ip) - 2.0 * at(ih, id, ip) + at(ih + 1, id, ip)
                                }
                                1 if id >= 1 && id + 1 < nd => {
                                    at(ih, id - 1, ip) - 2.0 * at(ih, id, ip) + at(ih, id + 1, ip)
                                }
                                2 => {
                                    at(ih, id, (ip + np - 1) % np) - 2.0 * at(ih, id, ip)
                                        + at(ih, id, (ip + 1) % np)
                                }
                                _ => 0.0,
                            };
                            worst = worst.max(second.abs());
                        }
                    }
                }
                sum += worst / 8.0;
            }
            // Past an axis' last sample the look-up is clamped (constant):
            // there it errs by the slope times the distance, the slope
            // estimated by the last step (times 2, as the curvature above).
            let beyond = |u: f64, n: usize| (u - (n - 1) as f64).max(0.0);
            let (bh, bd) = (beyond(u_h, nh), beyond(u_d, nd));
            if nh >= 2 && bh > 0.0 {
                let step = (at(nh - 1, d0, p0) - at(nh - 2, d0, p0)).abs();
                sum += 2.0 * bh * step;
            }
            if nd >= 2 && bd > 0.0 {
                let step = (at(h0, nd - 1, p0) - at(h0, nd - 2, p0)).abs();
                sum += 2.0 * bd * step;
            }
            out[c] = sum;
        }
        Rgb::from_array(out)
    }
}

/// The angles of sample `(i_h, i_d, i_φ)` of a table of `dims` samples.
pub fn sample_angles(dims: [usize; 3], ih: usize, id: usize, ip: usize) -> (f64, f64, f64) {
    sample_angles_over(dims, PI, ih, id, ip)
}

/// [`sample_angles`] with the φ_d axis over `[0, phi_period)`.
pub fn sample_angles_over(
    dims: [usize; 3],
    phi_period: f64,
    ih: usize,
    id: usize,
    ip: usize,
) -> (f64, f64, f64) {
    let s = ih as f64 / dims[0] as f64;
    (
        s * s * FRAC_PI_2,
        id as f64 / dims[1] as f64 * FRAC_PI_2,
        ip as f64 / dims[2] as f64 * phi_period,
    )
}

/// The continuous θ_h index `sqrt(θ_h/(π/2)) · n_h`.
pub fn theta_h_index(theta_h: f64, nh: usize) -> f64 {
    (theta_h.max(0.0) / FRAC_PI_2).sqrt() * nh as f64
}

/// The continuous φ_d index in [0, n_φ): `φ_d` folded into
/// `[0, phi_period)`.
pub fn phi_index(phi_d: f64, np: usize, phi_period: f64) -> f64 {
    phi_d.rem_euclid(phi_period) / phi_period * np as f64
}

/// The two samples around index `u` and the weight of the second, the
/// axis clamped at its ends.
fn clamped(u: f64, n: usize) -> (usize, usize, f64) {
    let u = u.clamp(0.0, (n - 1) as f64);
    let i0 = (u.floor() as usize).min(n - 1);
    (i0, (i0 + 1).min(n - 1), u - i0 as f64)
}

/// The two samples around index `u` on a periodic axis of `n` samples.
fn wrapped(u: f64, n: usize) -> (usize, usize, f64) {
    let i0 = u.floor();
    let t = u - i0;
    let i0 = (i0 as usize) % n;
    (i0, (i0 + 1) % n, t)
}

/// The MERL material whose original file has this sha256 (hex), if any.
pub fn known_material(sha256: &str) -> Option<&'static str> {
    KNOWN_FILES
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            Some((w.next()?, w.next()?))
        })
        .find(|(_, sha)| sha.eq_ignore_ascii_case(sha256))
        .map(|(name, _)| name)
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_100_known_files_are_listed() {
        let listed = KNOWN_FILES.lines().filter(|l| !l.starts_with('#')).count();
        assert_eq!(listed, 100);
        assert_eq!(
            known_material("d6506c69e44430bfe8ea676f3950599ca3a6bfb1f46b9906da336d13991bd37d"),
            Some("alum-bronze")
        );
        assert_eq!(known_material("00"), None);
    }

    #[test]
    fn a_written_table_reads_back_at_its_samples() {
        let f = |th: f64, td: f64, pd: f64| Rgb::new(th + 1.0, td * 2.0, pd.cos() + 2.0);
        let table = MerlTable::sample([8, 6, 12], f);
        let back = MerlTable::parse(&table.encode()).unwrap();
        for (ih, id, ip) in [(0, 0, 0), (3, 2, 5), (7, 5, 11), (5, 1, 0)] {
            let (th, td, pd) = sample_angles(back.dims, ih, id, ip);
            let got = back.f_r(th, td, pd);
            assert!((got - f(th, td, pd)).abs().max_element() < 1e-12, "{got}");
        }
    }

    #[test]
    fn bad_tables_are_refused() {
        let good = MerlTable::sample([2, 2, 4], |_, _, _| Rgb::ONE).encode();
        let e = MerlTable::parse(&good[..7]).unwrap_err();
        assert!(e.starts_with("truncated"), "{e}");
        let e = MerlTable::parse(&good[..good.len() - 8]).unwrap_err();
        assert!(e.starts_with("truncated"), "{e}");
        let mut long = good.clone();
        long.push(0);
        assert!(
            MerlTable::parse(&long)
                .unwrap_err()
                .starts_with("wrong size")
        );
        let mut header = good.clone();
        header[..4].copy_from_slice(&(-5i32).to_le_bytes());
        assert!(
            MerlTable::parse(&header)
                .unwrap_err()
                .starts_with("wrong header")
        );
        let mut nan = good.clone();
        nan[12 + 8 * 17..12 + 8 * 18].copy_from_slice(&f64::NAN.to_le_bytes());
        let e = MerlTable::parse(&nan).unwrap_err();
        assert!(
            e.contains("NaN in the green channel at (θ_h, θ_d, φ_d) index (0, 0, 1)"),
            "{e}"
        );
        let mut missing = good.clone();
        missing[12..20].copy_from_slice(&(-1.0f64).to_le_bytes());
        let t = MerlTable::parse(&missing).unwrap();
        assert_eq!((t.missing, t.channels[0][0]), (1, 0.0));
    }
}
