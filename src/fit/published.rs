//! The published ABC fits of the 100 MERL materials (Löw, Kronander,
//! Ynnerman, Unger, "BRDF Models for Accurate and Efficient Rendering of
//! Glossy Surfaces", ACM TOG 31(1) 2012; the table of J. Dupuy's
//! `dj_brdf.h`, `data/measured/merl100_abc_fits.csv`) as gonio materials
//! of the model `abc`, so that `gonio fit` scores them under the same
//! metric on the same samples as its own fits (`--model abc-published`).
//!
//! Each row `kD_rgb, A_rgb, B, C, ior` is the material `k_d = kD`,
//! `k_s = 1`, `abc_a = A`, `abc_b = B`, `abc_c = C`, `η_i = 1`,
//! `η_t = ior` (the model's definition: `crate::material::brdf::abc`).

use crate::base::Rgb;
use crate::material::{Material, ReflectanceModel};

/// The table, embedded (its license and source: `data/measured/README.md`).
const CSV: &str = include_str!("../../data/measured/merl100_abc_fits.csv");

/// The published ABC material of the MERL material `name`, or `None` if
/// the table has no row of that name.
pub fn abc(name: &str) -> Option<Material> {
    CSV.lines()
        .skip(1)
        .find(|l| l.split(',').next() == Some(name))
        .map(|l| parse_row(l).expect("the embedded table parses (test: every_row_parses)"))
}

/// One row as a material named after it.
fn parse_row(line: &str) -> Result<Material, String> {
    let f: Vec<&str> = line.split(',').collect();
    if f.len() != 10 {
        return Err(format!("{} fields, expected 10: `{line}`", f.len()));
    }
    let v: Vec<f64> = f[1..]
        .iter()
        .map(|s| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    let mut m = Material::new(f[0], ReflectanceModel::Abc);
    m.k_d = Rgb::new(v[0], v[1], v[2]);
    m.k_s = Rgb::ONE;
    m.abc_a = Rgb::new(v[3], v[4], v[5]);
    (m.abc_b, m.abc_c) = (v[6], v[7]);
    (m.eta_i, m.eta_t) = (1.0, v[8]);
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::measured::library;

    #[test]
    fn every_row_parses_and_names_a_builtin_material() {
        let rows: Vec<&str> = CSV.lines().skip(1).filter(|l| !l.is_empty()).collect();
        assert_eq!(rows.len(), 100);
        for l in rows {
            let m = parse_row(l).unwrap();
            m.validate().unwrap();
            assert!(library::builtin(&m.name).is_ok(), "{}", m.name);
        }
        let chrome = abc("chrome").unwrap();
        assert_eq!(chrome.abc_b, 64661.257812);
        assert_eq!(chrome.eta_t, 99.999413);
        assert!(abc("unobtainium").is_none());
    }
}
