//! Which BRDF a pipeline draws: the codes of models and terms shared by
//! `GpuMaterial.variant` (packed) and the pipeline-overridable constants of
//! `shaders/brdf/variant.wgsl` (one per field). The codes are the indices
//! of the Rust enums' `ALL` lists, written into every module as WGSL
//! constants (`MODEL_COOK_TORRANCE`, `DISTRIBUTION_GGX`, ...), so the WGSL
//! `switch`es name them and no number is kept in sync by hand.

use super::features::Feature;
use crate::material::{
    BrdfVariant, Denominator, Distribution, Fresnel, Geometry, ReflectanceModel,
};
use std::collections::BTreeSet;
use std::fmt::Write;

/// The value of a constant that leaves the choice to the material's
/// packed code at run time (`FROM_MATERIAL` in WGSL).
pub const FROM_MATERIAL: u32 = u32::MAX;

/// A BRDF variant as codes: the model and the terms it uses (0 for the
/// terms it does not).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VariantCode {
    pub model: u32,
    pub distribution: u32,
    pub geometry: u32,
    pub fresnel: u32,
    pub denominator: u32,
}

/// `v` with the terms its model uses filled in where it left them open
/// (Cook-Torrance: Beckmann, Smith, conductor, microfacet, as the CPU's
/// `Material` defaults; the mirror: no Fresnel, `k_s` unchanged) and the
/// others cleared.
pub fn resolved(v: &BrdfVariant) -> BrdfVariant {
    let ct = v.model == ReflectanceModel::CookTorrance;
    let fresnel_default = match v.model {
        ReflectanceModel::CookTorrance => Some(Fresnel::Conductor),
        ReflectanceModel::Mirror => Some(Fresnel::None),
        _ => None,
    };
    BrdfVariant {
        model: v.model,
        distribution: ct.then(|| v.distribution.unwrap_or(Distribution::Beckmann)),
        geometry: ct.then(|| v.geometry.unwrap_or(Geometry::Smith)),
        fresnel: fresnel_default.map(|f| v.fresnel.unwrap_or(f)),
        denominator: ct.then(|| v.denominator.unwrap_or(Denominator::Microfacet)),
    }
}

/// The `#if` features of `variants`: their models and the Cook-Torrance
/// and mirror terms they use (so a module holds the `switch` arms of
/// those terms only, and the compiler reads no unused term function).
pub fn brdf_features(variants: &BTreeSet<BrdfVariant>) -> Vec<Feature> {
    let mut features = BTreeSet::new();
    for v in variants.iter().map(resolved) {
        features.insert(Feature::Model(v.model));
        features.extend(v.distribution.map(Feature::Distribution));
        features.extend(v.geometry.map(Feature::Geometry));
        features.extend(v.fresnel.map(Feature::Fresnel));
    }
    features.into_iter().collect()
}

/// The index of `x` in `all` (the enums' `ALL`, which list every value).
fn index<T: PartialEq>(all: &[T], x: T) -> u32 {
    all.iter()
        .position(|a| *a == x)
        .expect("ALL lists every value") as u32
}

impl VariantCode {
    /// The codes of `v`. Cook-Torrance's terms default as the CPU's do
    /// (Beckmann, Smith, conductor, microfacet); the mirror without a
    /// Fresnel choice reflects `k_s` unchanged.
    pub fn of(v: &BrdfVariant) -> Self {
        let v = resolved(v);
        VariantCode {
            model: index(&ReflectanceModel::ALL, v.model),
            distribution: v.distribution.map_or(0, |d| index(&Distribution::ALL, d)),
            geometry: v.geometry.map_or(0, |g| index(&Geometry::ALL, g)),
            fresnel: v.fresnel.map_or(0, |f| index(&Fresnel::ALL, f)),
            denominator: v.denominator.map_or(0, |c| index(&Denominator::ALL, c)),
        }
    }

    /// `GpuMaterial.variant`: model in bits 0-7, distribution 8-11,
    /// geometry 12-15, Fresnel 16-19, denominator 20-23 (decoded by
    /// `shaders/brdf/variant.wgsl`).
    pub fn packed(self) -> u32 {
        debug_assert!(self.model < 0x100);
        debug_assert!(
            [
                self.distribution,
                self.geometry,
                self.fresnel,
                self.denominator
            ]
            .iter()
            .all(|&c| c < 0x10)
        );
        self.model
            | self.distribution << 8
            | self.geometry << 12
            | self.fresnel << 16
            | self.denominator << 20
    }

    /// The codes of a packed `variant`.
    pub fn unpack(packed: u32) -> Self {
        VariantCode {
            model: packed & 0xff,
            distribution: (packed >> 8) & 0xf,
            geometry: (packed >> 12) & 0xf,
            fresnel: (packed >> 16) & 0xf,
            denominator: (packed >> 20) & 0xf,
        }
    }

    /// The pipeline constants (WGSL `override`s) that specialize a module
    /// to this variant.
    pub fn pipeline_constants(self) -> Vec<(&'static str, f64)> {
        self.fields()
            .into_iter()
            .map(|(name, code)| (name, f64::from(code)))
            .collect()
    }

    /// `(WGSL override name, code)` per field.
    fn fields(self) -> [(&'static str, u32); 5] {
        let codes = [
            self.model,
            self.distribution,
            self.geometry,
            self.fresnel,
            self.denominator,
        ];
        std::array::from_fn(|i| (OVERRIDES[i], codes[i]))
    }
}

/// The overrides of `shaders/brdf/variant.wgsl`, in [`VariantCode`]'s
/// field order.
const OVERRIDES: [&str; 5] = [
    "BRDF_MODEL",
    "BRDF_DISTRIBUTION",
    "BRDF_GEOMETRY",
    "BRDF_FRESNEL",
    "BRDF_DENOMINATOR",
];

/// The pipeline constants of a pipeline specialized to the packed
/// `variant` (`None`: none set, the module's defaults apply).
pub fn pipeline_constants(variant: Option<u32>) -> Vec<(&'static str, f64)> {
    variant
        .map(|v| VariantCode::unpack(v).pipeline_constants())
        .unwrap_or_default()
}

/// `"cook-torrance"` → `"COOK_TORRANCE"`.
pub(super) fn constant_name(name: &str) -> String {
    name.to_uppercase().replace('-', "_")
}

/// The WGSL constants naming every code: `MODEL_*`, `DISTRIBUTION_*`,
/// `GEOMETRY_*`, `FRESNEL_*`, `DENOMINATOR_*`.
pub fn wgsl_codes() -> String {
    let mut out = String::from(
        "// Codes of the models and terms (their order in the Rust enums; src/gpu/shader_gen/specialization.rs).\n",
    );
    let mut group = |prefix: &str, names: Vec<&str>| {
        for (code, name) in names.into_iter().enumerate() {
            let _ = writeln!(
                out,
                "const {prefix}_{}: u32 = {code}u;",
                constant_name(name)
            );
        }
    };
    group(
        "MODEL",
        ReflectanceModel::ALL.iter().map(|m| m.name()).collect(),
    );
    group(
        "DISTRIBUTION",
        Distribution::ALL.iter().map(|d| d.name()).collect(),
    );
    group("GEOMETRY", Geometry::ALL.iter().map(|g| g.name()).collect());
    group("FRESNEL", Fresnel::ALL.iter().map(|f| f.name()).collect());
    group(
        "DENOMINATOR",
        Denominator::ALL.iter().map(|c| c.name()).collect(),
    );
    out
}

/// The defaults of the pipeline constants for a module of `variants`
/// (`BRDF_*_DEFAULT`): the one variant's codes when there is one (the
/// module is then specialized with no constant set), else `FROM_MATERIAL`
/// (each material's batch gets a pipeline that sets them, or, without,
/// the material decides: the uber shader).
pub fn wgsl_defaults(variants: &BTreeSet<BrdfVariant>) -> String {
    let code = match variants.iter().collect::<Vec<_>>().as_slice() {
        [only] => Some(VariantCode::of(only)),
        _ => None,
    };
    let mut out =
        String::from("// The variant this module draws unless a pipeline overrides it.\n");
    for (i, name) in OVERRIDES.iter().enumerate() {
        let value = match code {
            Some(code) => format!("{}u", code.fields()[i].1),
            None => "FROM_MATERIAL".into(),
        };
        let _ = writeln!(out, "const {name}_DEFAULT: u32 = {value};");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::shader_gen::all_variants;

    #[test]
    fn codes_pack_and_unpack_and_tell_variants_apart() {
        let variants = all_variants();
        let mut packed: Vec<u32> = variants
            .iter()
            .map(|v| {
                let code = VariantCode::of(v);
                assert_eq!(VariantCode::unpack(code.packed()), code);
                assert_ne!(code.packed(), FROM_MATERIAL);
                code.packed()
            })
            .collect();
        packed.sort();
        packed.dedup();
        assert_eq!(packed.len(), variants.len(), "two variants share a code");
    }
}
