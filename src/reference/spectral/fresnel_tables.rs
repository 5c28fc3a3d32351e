//! The spectral Fresnel of each metal tabulated over `cos θ`, for
//! rendering: [`spectral_conductor_rgb`] integrates 81 wavelengths (the
//! exact conductor Fresnel of the published `n(λ) + i k(λ)`: Johnson &
//! Christy 1972 for Au, Ag, Cu, 1974 for Fe, Rakić 1995 for Al, against
//! the CIE 1931 observer under D65) per value, too costly at every light
//! sample of every pixel; but it depends on the angle alone, so it is
//! computed once per metal at [`NODES`] values of `cos θ` and
//! interpolated ([`FresnelTable`], Catmull-Rom).
//!
//! Interpolation error, measured against the direct integral at the
//! midpoints between nodes and at 1000 further angles in the test below:
//! below [`TABLE_ERROR`] in every channel for every metal (largest 5.1·10⁻⁸,
//! aluminium, in the interval next to grazing, where the end node is
//! extrapolated; 7·10⁻¹⁰–4·10⁻⁸ for the others), four orders of magnitude
//! under the smallest effect the tables are for (the presets' errors,
//! 10⁻³–6·10⁻², docs/spectral.md).

use super::conductors::spectral_conductor_rgb;
use super::metals;
use crate::material::brdf::fresnel_table::FresnelTable;
use crate::material::conductors::Metal;
use std::sync::LazyLock;

/// Nodes per table: `cos θ = i / 1024`.
pub const NODES: usize = 1025;

/// The bound the test holds every table to (its measured error is printed
/// by `cargo test --release --lib fresnel_tables -- --nocapture` and
/// stated in docs/spectral.md).
pub const TABLE_ERROR: f64 = 1e-7;

static TABLES: LazyLock<Vec<FresnelTable>> = LazyLock::new(|| {
    Metal::ALL
        .iter()
        .map(|&m| {
            let metal = metals::of(m);
            FresnelTable::from_fn(metal.source, NODES, |cos| {
                spectral_conductor_rgb(metal, cos)
            })
        })
        .collect()
});

/// The table of `metal`, built on first use (5 × 1025 × 81 Fresnel
/// evaluations for all five: milliseconds).
pub fn table(metal: Metal) -> &'static FresnelTable {
    let i = Metal::ALL
        .iter()
        .position(|&m| m == metal)
        .expect("every metal is listed");
    &TABLES[i]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::Rgb;

    /// The table against the direct integral: at every node (exact), at
    /// the midpoint of every interval (where a cubic's error peaks) and
    /// at 1000 angles evenly spaced in θ (dense towards grazing, where
    /// `F` bends most). The largest error is printed and held to
    /// [`TABLE_ERROR`].
    #[test]
    fn tables_match_the_spectral_integral() {
        let last = (NODES - 1) as f64;
        for metal in Metal::ALL {
            let (t, m) = (table(metal), metals::of(metal));
            let mut worst = (0.0, 0.0);
            let mut check = |cos: f64| {
                let e = (t.eval(cos) - spectral_conductor_rgb(m, cos))
                    .abs()
                    .max_element();
                if e > worst.0 {
                    worst = (e, cos);
                }
            };
            for i in 0..NODES - 1 {
                check(i as f64 / last);
                check((i as f64 + 0.5) / last);
            }
            check(1.0);
            for k in 0..1000 {
                check((k as f64 * 0.09f64).to_radians().cos());
            }
            println!(
                "{}: largest |table − integral| {:.2e} at cos θ = {:.5}",
                m.source, worst.0, worst.1
            );
            assert!(worst.0 < TABLE_ERROR, "{}: {:e}", m.source, worst.0);
            assert_eq!(t.eval(1.0), spectral_conductor_rgb(m, 1.0));
            assert!((t.eval(0.0) - Rgb::ONE).abs().max_element() < 1e-14);
        }
    }
}
