//! The θ_h × θ_d image slice: f_r over the half/difference angles of
//! Rusinkiewicz ("A New Change of Variables for Efficient BRDF
//! Representation", EGWR 1998), as BRDF Explorer's "Image Slice" shows it
//! (and the natural view of measured tables such as MERL's, binned the same
//! way). For an isotropic material f_r depends on θ_h, θ_d and φ_d only;
//! `gonio brdf --plot-halfdiff` fixes φ_d = 90° (BRDF Explorer's default),
//! the viewer takes any φ_d (`src/ui/plots/halfdiff.rs`); both φ_h = 0.
//!
//! Directions: the half vector `h = (sin θ_h, 0, cos θ_h)` (φ_h = 0); the
//! difference vector `d = (θ_d, φ_d)` is given in the frame in which h is
//! the pole, obtained from the surface frame by rotating by θ_h about the
//! bitangent (Rusinkiewicz §3.1); `ω_i = R_y(θ_h) d` and `ω_o` is ω_i
//! reflected about h. At φ_d = 90°, `d = (0, sin θ_d, cos θ_d)`, so
//! `ω_i = (cos θ_d sin θ_h, sin θ_d, cos θ_d cos θ_h)`: above the surface for
//! every θ_h, θ_d < 90°. Specular peaks sit at θ_h = 0 (the left column);
//! Fresnel's rise at θ_d → 90° (the top rows).

use super::part::MaterialPart;
use super::{Channel, frame};
use crate::scene::Rgb;
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// Cells per axis: 1° each over [0°, 90°], the resolution of MERL's θ_d axis.
pub const CELLS: usize = 90;

/// The sampled image: `values[j][i]` is f_r (reduced by `channel`) at the
/// centre of cell i along θ_h and row j along θ_d.
#[derive(Clone, Debug)]
pub struct HalfDiffImage {
    pub values: Vec<Vec<f64>>,
}

/// The centre of cell `k` of [`CELLS`] over [0, π/2], radians.
pub fn cell_centre(k: usize) -> f64 {
    (k as f64 + 0.5) * FRAC_PI_2 / CELLS as f64
}

/// `(ω_i, ω_o)` for half angle `theta_h`, difference angles `theta_d`,
/// `phi_d` (radians), φ_h = 0.
pub fn directions(theta_h: f64, theta_d: f64, phi_d: f64) -> (DVec3, DVec3) {
    let (sd, cd) = theta_d.sin_cos();
    let (sp, cp) = phi_d.sin_cos();
    let d = DVec3::new(sd * cp, sd * sp, cd);
    let (sh, ch) = theta_h.sin_cos();
    // R_y(θ_h): the pole (0, 0, 1) goes to h = (sin θ_h, 0, cos θ_h).
    let rotate = |v: DVec3| DVec3::new(ch * v.x + sh * v.z, v.y, -sh * v.x + ch * v.z);
    let wi = rotate(d);
    let wo = rotate(DVec3::new(-d.x, -d.y, d.z));
    (wi, wo)
}

/// f_r of `m` at half angle `theta_h` and difference angles `theta_d`,
/// `phi_d` (radians, φ_h = 0): the one evaluation behind every cell of
/// the image, in `gonio brdf` and in the viewer.
pub fn f_r_at<'a>(m: impl Into<MaterialPart<'a>>, theta_h: f64, theta_d: f64, phi_d: f64) -> Rgb {
    let m = m.into();
    let (wi, wo) = directions(theta_h, theta_d, phi_d);
    m.f_r(wi, wo, &frame())
}

/// f_r (RGB) of `m` at the centre of every cell for the difference
/// azimuth `phi_d` (radians): `rows[j][i]`, i along θ_h, j along θ_d.
pub fn half_diff_rgb<'a>(m: impl Into<MaterialPart<'a>>, phi_d: f64) -> Vec<Vec<Rgb>> {
    let m = m.into();
    (0..CELLS)
        .map(|j| {
            (0..CELLS)
                .map(|i| f_r_at(m, cell_centre(i), cell_centre(j), phi_d))
                .collect()
        })
        .collect()
}

/// The image of `m` at φ_d = 90°.
pub fn half_diff_image<'a>(m: impl Into<MaterialPart<'a>>, channel: Channel) -> HalfDiffImage {
    half_diff_image_at(m, channel, FRAC_PI_2)
}

/// [`half_diff_image`] at the difference azimuth `phi_d` (radians):
/// `gonio brdf --plot-halfdiff --phi-d`.
pub fn half_diff_image_at<'a>(
    m: impl Into<MaterialPart<'a>>,
    channel: Channel,
    phi_d: f64,
) -> HalfDiffImage {
    let values = half_diff_rgb(m, phi_d)
        .into_iter()
        .map(|row| row.into_iter().map(|c| channel.of(c)).collect())
        .collect();
    HalfDiffImage { values }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::explore::spec::compare_spec;
    use crate::material::Material;

    fn material(spec: &str) -> Material {
        compare_spec(spec, &[]).unwrap().material
    }

    /// The directions are Rusinkiewicz's: h bisects ω_i and ω_o at θ_h
    /// from the normal, and ω_i is θ_d from h, for arbitrary angles.
    #[test]
    fn directions_have_the_half_and_difference_angles() {
        for (th, td, pd) in [(0.3, 0.7, 1.2), (1.2, 0.2, 2.5), (0.0, 1.5, 0.4)] {
            let (wi, wo) = directions(th, td, pd);
            let h = (wi + wo).normalize();
            assert!((h.z.acos() - th).abs() < 1e-12);
            assert!(h.y.abs() < 1e-12, "φ_h = 0");
            assert!((wi.dot(h).acos() - td).abs() < 1e-12);
            assert!((wi.length() - 1.0).abs() < 1e-12 && (wo.length() - 1.0).abs() < 1e-12);
        }
    }

    /// A glossy lobe peaks at θ_h = 0: in every row below 80°, the largest
    /// value is in the first column; and the first column's value is f_r at
    /// the mirror pair built independently (ω_i = h cos θ_d + b sin θ_d,
    /// ω_o its reflection about h).
    #[test]
    fn a_glossy_lobe_peaks_in_the_first_column() {
        let m = material("cook-torrance,k_d=0,k_s=1,roughness=0.1,preset=gold-rgb");
        let img = half_diff_image(&m, Channel::Mean);
        for (j, row) in img.values.iter().enumerate().take(80) {
            let (argmax, _) =
                row.iter().enumerate().fold(
                    (0, f64::MIN),
                    |b, (i, v)| if *v > b.1 { (i, *v) } else { b },
                );
            assert_eq!(argmax, 0, "row {j}");
        }
        let (th, td) = (cell_centre(0), cell_centre(45));
        let h = DVec3::new(th.sin(), 0.0, th.cos());
        let wi = h * td.cos() + DVec3::Y * td.sin();
        let wo = 2.0 * wi.dot(h) * h - wi;
        let want = Channel::Mean.of(m.f_r(wi, wo, &frame()));
        assert!((img.values[45][0] - want).abs() <= 1e-12 * want, "{want}");
        assert!(want > 10.0, "a sharp lobe: f_r {want}");
    }

    /// Lambert is flat: k_d/π in every cell.
    #[test]
    fn lambert_is_constant() {
        let img = half_diff_image(&material("lambert,k_d=0.5"), Channel::Mean);
        for v in img.values.iter().flatten() {
            assert!((v - 0.5 / std::f64::consts::PI).abs() < 1e-12);
        }
    }
}
