//! What surfaces do: validated material parameters and the reflectance
//! models of the lecture, as an `f64` reference ([`brdf`]).
//!
//! A [`Material`] holds parameters only (its struct: `definition.rs`);
//! the maths lives in [`brdf`], one file per family, mirrored function by
//! function in `shaders/brdf/*.wgsl`. Every model's needs (keys, defaults,
//! tolerances) are its row in [`table`]. The methods of `Material` that
//! read that row or evaluate the BRDF are written here, above the table
//! and the BRDFs they join; nothing else in `material/` uses this file.

pub mod brdf;
pub mod conductors;
mod definition;
pub mod entry;
pub mod layers;
pub mod measured;
mod model;
pub mod param;
pub mod presets;
pub mod spectral_metal;
pub mod table;
pub mod terms;
pub mod texture;
pub mod texture_fields;
pub mod weights;

pub use definition::{AlphaMode, BrdfVariant, Material, ROUGHNESS_FLOOR, Sides};
pub use entry::{MaterialEntry, material_from_entry, material_from_entry_in, material_table};
pub use model::ReflectanceModel;
pub use terms::{Denominator, Distribution, Fresnel, Geometry, SmithBeckmann};

use crate::base::Rgb;
use brdf::{Brdf, SurfaceFrame};
use glam::DVec3;

impl Material {
    /// A material with the given model and neutral parameters: `k_a = 0`,
    /// `k_e = 32`, roughness 0.3, σ = 0.2, gold's η/κ from the lecture's
    /// table, glass (1 → 1.5) for the dielectric, Beckmann with Smith G and
    /// the exact conductor Fresnel over the 4(N·V)(N·I) denominator; then
    /// the model's own defaults from its row (a mirror: Fresnel `none`, so
    /// its reflectance is `k_s`), and last its default `k_d`, `k_s` for
    /// those ([`weights`]: `k_d = 0.8`, `k_s = 0` for the diffuse models,
    /// `k_d = k_s = 0.5` for Phong, Blinn-Phong and Ward, a bare metal
    /// `k_d = 0`, `k_s = 1` for this Cook-Torrance gold).
    pub fn new(name: impl Into<String>, model: ReflectanceModel) -> Self {
        let mut m = Material {
            name: name.into(),
            model,
            k_a: Rgb::ZERO,
            // Placeholders: the row's `weights` set both below.
            k_d: Rgb::ZERO,
            k_s: Rgb::ZERO,
            k_e: 32.0,
            roughness: 0.3,
            sigma_x: 0.2,
            sigma_y: 0.2,
            facet_sigma: 0.5,
            eta: Rgb::splat(0.370),
            kappa: Rgb::splat(2.820),
            eta_i: 1.0,
            eta_t: 1.5,
            distribution: Distribution::Beckmann,
            geometry: Geometry::Smith,
            fresnel: Fresnel::Conductor,
            denominator: Denominator::Microfacet,
            spectral_metal: None,
            measured: None,
            base_color: Rgb::splat(0.8),
            metallic: 0.0,
            layers: layers::GltfLayers::default(),
            abc_a: Rgb::splat(10.0),
            abc_b: 1000.0,
            abc_c: 1.0,
            emission: Rgb::ZERO,
            textures: Vec::new(),
            sides: Sides::Unculled,
            alpha: 1.0,
            alpha_mode: AlphaMode::Opaque,
            occlusion: 1.0,
            energy_compensation: false,
            facing_normals: false,
        };
        (model.row().defaults)(&mut m);
        (m.k_d, m.k_s) = (model.row().weights)(&m);
        m
    }

    /// After an edit (the viewer's panel, `--edit`, `compare.N.KEY`): a
    /// weight `k_d` or `k_s` still at its default for the material as it
    /// was (`before`, its row's [`weights`]) takes its default for the
    /// material as it is now, as a scene file that does not give it would:
    /// a Lambert floor switched to `phong` gets Phong's `k_s = 0.5` and
    /// keeps its own `k_d`; a bare Cook-Torrance gold given `preset =
    /// "glass"` becomes the glass plastic. A weight set to another value
    /// stays (one equal to the default follows it: the viewer does not
    /// know which keys a file gave).
    pub fn follow_default_weights(&mut self, before: weights::Weights) {
        let now = (self.model.row().weights)(self);
        if self.k_d == before.0 {
            self.k_d = now.0;
        }
        if self.k_s == before.1 {
            self.k_s = now.1;
        }
    }

    /// Checks every parameter against the contract's ranges (the table's,
    /// [`table::stored_params`]); the message names the parameter and the
    /// offending value.
    pub fn validate(&self) -> Result<(), String> {
        table::stored_params()
            .into_iter()
            .try_for_each(|p| p.check(self))?;
        if !spectral_metal::still_holds(self) {
            return Err(format!(
                "material `{}`: `spectral_metal` needs the metal's own η, κ (its preset) and fresnel = \"conductor\", without η or κ textures",
                self.name
            ));
        }
        if self.energy_compensation && !self.model.row().energy_compensation {
            return Err(format!(
                "material `{}`: energy_compensation = true, but model `{}` has no energy compensation (it applies to the microfacet models {}); remove the key or set it to false",
                self.name,
                self.model.name(),
                table::ROWS
                    .iter()
                    .filter(|r| r.energy_compensation)
                    .map(|r| format!("`{}`", r.model.name()))
                    .collect::<Vec<_>>()
                    .join(" and ")
            ));
        }
        Ok(())
    }

    /// The BRDF of this material: its model's typed value, with the
    /// derived constants computed (see [`brdf::Brdf`]).
    pub fn brdf(&self) -> Brdf {
        Brdf {
            k_d: self.k_d,
            k_s: self.k_s,
            specular: (self.model.row().specular)(self),
            energy_compensation: self.energy_compensation,
        }
    }

    /// The BRDF `f_r(ω_i, ω_o)` [1/sr] in the shading frame `frame`; `wi`
    /// points to the light, `wo` to the viewer (both unit).
    ///
    /// One-sided, as the contract says: zero where `N·I ≤ 0` or `N·V ≤ 0`.
    /// It builds the material's [`Brdf`] on every call: a loop over
    /// directions builds it once ([`Self::brdf`]) and calls [`Brdf::f_r`].
    pub fn f_r(&self, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        self.brdf().f_r(wi, wo, frame)
    }

    /// One term of `f_r` ([`layers::LayerTerm`]: a `gltf-pbr` layer's
    /// contribution apart, [`brdf::eval_term`]); one-sided as [`Self::f_r`].
    pub fn f_r_term(
        &self,
        term: layers::LayerTerm,
        wi: DVec3,
        wo: DVec3,
        frame: &SurfaceFrame,
    ) -> Rgb {
        self.brdf().f_r_term(term, wi, wo, frame)
    }

    /// The part of the material that decides which shader code runs: the
    /// model and, where the model has them, its terms.
    pub fn variant(&self) -> BrdfVariant {
        let terms = self.model.row().terms;
        let (distribution, geometry, fresnel, denominator) = (
            terms.distribution.then_some(self.distribution),
            terms.geometry.then_some(self.geometry),
            terms.fresnel.then_some(self.fresnel),
            terms.denominator.then_some(self.denominator),
        );
        BrdfVariant {
            model: self.model,
            distribution,
            geometry,
            fresnel,
            denominator,
        }
    }
}
