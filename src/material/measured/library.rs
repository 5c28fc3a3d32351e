//! The built-in library: the 100 materials of the MERL BRDF database
//! (Matusik, Pfister, Brand, McMillan, "A Data-Driven Reflectance Model",
//! ACM TOG 22(3), 2003) as their Neural-BRDF networks, by MERL's names
//! (`gold-metallic-paint`, `chrome`, ...). The weights file is embedded in
//! the binary; it and its license (CC-BY-SA-4.0) and attribution are in
//! `data/measured/`. It is parsed once, on first use.

use super::network::{HIDDEN, INPUTS, Network, OUTPUTS};
use super::{MeasuredBrdf, Source};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::sync::LazyLock;

/// The weights file as shipped (`data/measured/README.md`).
const WEIGHTS_JSON: &str = include_str!("../../../data/measured/merl100_nbrdf_weights.json");

/// Materials in the weights file (checked when it is parsed).
pub const MATERIAL_COUNT: usize = 100;

#[derive(Deserialize)]
struct WeightsFile {
    materials: BTreeMap<String, Weights>,
}

#[allow(non_snake_case)]
#[derive(Deserialize)]
struct Weights {
    W1: Vec<Vec<f64>>,
    b1: Vec<f64>,
    W2: Vec<Vec<f64>>,
    b2: Vec<f64>,
    W3: Vec<Vec<f64>>,
    b3: Vec<f64>,
}

/// Every built-in material, in name order.
static LIBRARY: LazyLock<Vec<MeasuredBrdf>> = LazyLock::new(|| {
    let file: WeightsFile =
        serde_json::from_str(WEIGHTS_JSON).expect("the embedded weights file parses (tests)");
    assert_eq!(file.materials.len(), MATERIAL_COUNT);
    file.materials
        .into_iter()
        .map(|(name, w)| MeasuredBrdf {
            source: Source::Network(Box::new(network(&name, &w))),
            name,
        })
        .collect()
});

fn network(name: &str, w: &Weights) -> Network {
    fn matrix<const I: usize, const O: usize>(name: &str, m: &[Vec<f64>]) -> [[f64; O]; I] {
        assert_eq!(m.len(), I, "{name}");
        std::array::from_fn(|i| vector(name, &m[i]))
    }
    fn vector<const N: usize>(name: &str, v: &[f64]) -> [f64; N] {
        assert_eq!(v.len(), N, "{name}");
        std::array::from_fn(|i| v[i])
    }
    Network {
        w1: matrix::<INPUTS, HIDDEN>(name, &w.W1),
        b1: vector(name, &w.b1),
        w2: matrix::<HIDDEN, HIDDEN>(name, &w.W2),
        b2: vector(name, &w.b2),
        w3: matrix::<HIDDEN, OUTPUTS>(name, &w.W3),
        b3: vector(name, &w.b3),
    }
}

/// Every built-in material, in name order.
pub fn all() -> &'static [MeasuredBrdf] {
    &LIBRARY
}

/// The built-in material `name`, or a message listing the names.
pub fn builtin(name: &str) -> Result<&'static MeasuredBrdf, String> {
    all().iter().find(|m| m.name == name).ok_or_else(|| {
        // The suggestion first: the list of names is long, and messages
        // are cut for display.
        let names = all().iter().map(|m| m.name.as_str());
        format!(
            "`{name}` is not a built-in measured material nor a path to a MERL `.binary` file{}; the built-in ones are the 100 MERL names: {}",
            crate::base::did_you_mean(name, names.clone()),
            names.collect::<Vec<_>>().join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_library_has_the_100_merl_materials() {
        assert_eq!(all().len(), MATERIAL_COUNT);
        for name in [
            "gold-metallic-paint",
            "chrome",
            "blue-fabric",
            "alum-bronze",
        ] {
            assert_eq!(builtin(name).unwrap().name, name);
        }
        let e = builtin("gold").unwrap_err();
        assert!(e.contains("gold-metallic-paint"), "{e}");
        let e = builtin("chromee").unwrap_err();
        assert!(e.contains("file; did you mean `chrome`?"), "{e}");
    }
}
