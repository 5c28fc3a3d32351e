//! What the explorer evaluates of a material: its whole `f_r`, or one
//! additive term of a layered `gltf-pbr` material apart ([`LayerTerm`]:
//! the base, the sheen, the clearcoat, each weighted by what the layers
//! above let through, so the terms sum to the whole), on the side of the
//! surface the light is on or, for a material that lets light through,
//! on the far side ([`Side`]). Every quantity of the explorer (values,
//! slices, the 3D lobe, the θ_h × θ_d image, albedo, gloss) takes a
//! [`MaterialPart`]; a `&Material` is its whole, reflected.

use crate::material::brdf::gltf_layers::sheen::sheen_alpha;
use crate::material::brdf::gltf_layers::sheen_curve::sheen_albedo_of;
use crate::material::brdf::gltf_layers::transmission::gltf_transmitted;
use crate::material::brdf::{Brdf, SurfaceFrame, mirror_reflectance};
use crate::material::layers::LayerTerm;
use crate::material::{Material, ReflectanceModel};
use crate::scene::Rgb;
use glam::DVec3;
use std::fmt;
use std::str::FromStr;

/// A material and the term of its `f_r` evaluated, with the material's
/// [`Brdf`] built once: every quantity evaluates `f_r` thousands of times,
/// and building the value is not free (a normalized Gaussian sums a
/// 1000-term series).
#[derive(Clone, Copy, Debug)]
pub struct MaterialPart<'a> {
    pub material: &'a Material,
    pub term: LayerTerm,
    pub side: Side,
    brdf: Brdf,
}

/// Which side of the surface the outgoing direction is on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Side {
    /// The light's side: `f_r`.
    #[default]
    Reflected,
    /// The far side: the BTDF `f_t` of a `gltf-pbr` material with
    /// `transmission` or `diffuse_transmission`, as the renderers evaluate
    /// it for a light on the other side of the surface from the viewer
    /// (`gltf_transmitted`, the specification's thin-walled
    /// `specular_btdf` and `diffuse_btdf`, with the normal turned towards
    /// the viewer). Evaluated at the outgoing direction mirrored through
    /// the surface, `ω_o = (x, y, z) ↦ (x, y, −z)`: so the transmitted
    /// lobe, centred on the straight line `−ω_i`, lands on the mirror
    /// direction `R(ω_i)`, and every quantity that integrates or plots
    /// the upper hemisphere about the mirror direction (albedo, slices)
    /// takes the far side unchanged. A volume's boundary refracts by
    /// Walter et al.'s BTDF instead (`volume_btdf`), not shown.
    Transmitted,
}

impl<'a> From<&'a Material> for MaterialPart<'a> {
    /// The whole material.
    fn from(material: &'a Material) -> Self {
        MaterialPart::new(material, LayerTerm::All)
    }
}

impl<'a> MaterialPart<'a> {
    /// Term `term` of `material`.
    pub fn new(material: &'a Material, term: LayerTerm) -> Self {
        MaterialPart {
            material,
            term,
            side: Side::Reflected,
            brdf: material.brdf(),
        }
    }

    /// The same term on the far side ([`Side::Transmitted`]).
    pub fn transmitted(self) -> Self {
        MaterialPart {
            side: Side::Transmitted,
            ..self
        }
    }
}

impl MaterialPart<'_> {
    /// The term's `f_r` (one-sided, as `Material::f_r`); on the far side
    /// its `f_t` at `wo` mirrored through the surface ([`Side`]).
    pub fn f_r(&self, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        match (self.side, self.term) {
            (Side::Transmitted, _) => self.f_t_mirrored(wi, wo, frame),
            (Side::Reflected, LayerTerm::All) => self.brdf.f_r(wi, wo, frame),
            (Side::Reflected, term) => self.brdf.f_r_term(term, wi, wo, frame),
        }
    }

    /// `f_t(ω_i, ω_o')` for `ω_o'` the mirror image of `wo` through the
    /// surface, `wi` and `wo` on the normal's side (0 elsewhere): the
    /// transmission belongs to the base, so the whole and the base term
    /// have it, the sheen and the clearcoat none (their scaling of the
    /// base is in it). No sheen albedo scaling, as the reference's thin
    /// wall evaluates it (`reference::transmission::thin`).
    fn f_t_mirrored(&self, wi: DVec3, wo: DVec3, frame: &SurfaceFrame) -> Rgb {
        let n = frame.n;
        if !self.transmits() || n.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
            return Rgb::ZERO;
        }
        let below = wo - 2.0 * n.dot(wo) * n;
        let m = self.material;
        gltf_transmitted(
            m.base_color,
            m.metallic,
            m.roughness,
            &m.layers,
            0.0,
            0.0,
            -n,
            wi,
            below,
        )
    }

    /// Whether the term lets light through: a `gltf-pbr` material with
    /// `transmission` or `diffuse_transmission`, its whole or its base.
    pub fn transmits(&self) -> bool {
        let m = self.material;
        m.model == ReflectanceModel::GltfPbr
            && m.layers.transmits()
            && matches!(self.term, LayerTerm::All | LayerTerm::Base)
    }

    /// The reflectance of a Dirac lobe in the mirror direction (the
    /// mirror model's, [`mirror_reflectance`]): a base's, so in the
    /// whole and the base term, 0 in the others and on the far side.
    pub fn dirac(&self, cos_theta: f64) -> Rgb {
        match (self.side, self.term) {
            (Side::Reflected, LayerTerm::All | LayerTerm::Base) => {
                mirror_reflectance(self.material, cos_theta)
            }
            _ => Rgb::ZERO,
        }
    }

    /// What reading the sheen's `E(μ)` from its curve
    /// (`brdf::gltf_layers::sheen_curve`) may add to an integral of this
    /// part (albedo, gloss): `max(max₃(C), 2)` times the curve's error
    /// `ε` (measured as `|ΔE| / max(1, E)`, which changes the scaling
    /// `σ = max(0, min(1 − max₃(C) E_o, 1 − max₃(C) E_i))` by at most
    /// that), since `σ` multiplies the base, whose albedo is at most 1
    /// (the layers' white furnace, tests/layer_properties.rs).
    /// Zero for a term that does not read `E` or while `E` is exact.
    pub fn sheen_curve_error(&self) -> Rgb {
        let m = self.material;
        let reads_sheen = m.model == ReflectanceModel::GltfPbr
            && m.layers.has_sheen()
            && self.side == Side::Reflected
            && matches!(self.term, LayerTerm::All | LayerTerm::Base);
        if !reads_sheen {
            return Rgb::ZERO;
        }
        let error = sheen_albedo_of(sheen_alpha(m.layers.sheen_roughness)).error();
        Rgb::splat(m.layers.sheen_color.max_element().max(2.0) * error)
    }

    /// Whether the part has a Dirac lobe beside its function value.
    pub fn is_dirac(&self) -> bool {
        self.side == Side::Reflected
            && matches!(self.term, LayerTerm::All | LayerTerm::Base)
            && self.brdf.is_dirac()
    }
}

/// Which terms the explorer shows: one, or the whole and each term apart
/// (`each`), overlaid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LayerChoice {
    One(LayerTerm),
    Each,
}

impl Default for LayerChoice {
    /// The whole `f_r`.
    fn default() -> Self {
        LayerChoice::One(LayerTerm::All)
    }
}

impl LayerChoice {
    /// Every choice, in the order `--layer` lists them.
    pub const ALL: [LayerChoice; 5] = [
        LayerChoice::One(LayerTerm::All),
        LayerChoice::One(LayerTerm::Base),
        LayerChoice::One(LayerTerm::Sheen),
        LayerChoice::One(LayerTerm::Clearcoat),
        LayerChoice::Each,
    ];

    /// The name `--layer` and `plots.layer` take.
    pub fn name(self) -> &'static str {
        match self {
            LayerChoice::One(t) => t.name(),
            LayerChoice::Each => "each",
        }
    }

    /// The terms of `m` shown: the chosen one; or, for `each`, the whole
    /// and then every term `m` has (the base, and the sheen and the
    /// clearcoat where they are on): only the whole for a material
    /// without layers on.
    pub fn terms(self, m: &Material) -> Vec<LayerTerm> {
        match self {
            LayerChoice::One(t) => vec![t],
            LayerChoice::Each => {
                let mut terms = vec![LayerTerm::All];
                let layered = m.model == crate::material::ReflectanceModel::GltfPbr
                    && (m.layers.has_sheen() || m.layers.has_clearcoat());
                if layered {
                    terms.push(LayerTerm::Base);
                    terms.extend(m.layers.has_sheen().then_some(LayerTerm::Sheen));
                    terms.extend(m.layers.has_clearcoat().then_some(LayerTerm::Clearcoat));
                }
                terms
            }
        }
    }
}

impl fmt::Display for LayerChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for LayerChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|c| c.name()).collect();
                format!(
                    "unknown layer `{s}`{}; expected one of {}",
                    crate::base::did_you_mean(s, names.iter().copied()),
                    names.join(", ")
                )
            })
    }
}

/// The label of `term` of a material labelled `label`: the label itself
/// for the whole, else `label [term]`.
pub fn term_label(label: &str, term: LayerTerm) -> String {
    match term {
        LayerTerm::All => label.to_string(),
        t => format!("{label} [{t}]"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::explore::{direction, frame};
    use crate::material::ReflectanceModel;

    fn layered() -> Material {
        let mut m = Material::new("m", ReflectanceModel::GltfPbr);
        m.base_color = Rgb::new(0.8, 0.1, 0.1);
        m.roughness = 0.5;
        m.layers.clearcoat = 0.7;
        m.layers.clearcoat_roughness = 0.2;
        m.layers.sheen_color = Rgb::new(0.3, 0.5, 0.9);
        m.layers.sheen_roughness = 0.4;
        m.layers.iridescence = 0.5;
        m.layers.anisotropy_strength = 0.3;
        m
    }

    #[test]
    fn the_terms_sum_to_the_whole() {
        let m = layered();
        let f = frame();
        let mut checked = 0;
        let mut nonzero = [false; 3];
        for (ti, pi, to, po) in [
            (30.0, 0.0, 30.0, 180.0),
            (60.0, 20.0, 10.0, 250.0),
            (5.0, 0.0, 80.0, 90.0),
            (85.0, 10.0, 85.0, 190.0),
        ] {
            let rad = |d: f64| f64::to_radians(d);
            let (wi, wo) = (direction(rad(ti), rad(pi)), direction(rad(to), rad(po)));
            let whole = m.f_r(wi, wo, &f);
            let terms: Vec<Rgb> = [LayerTerm::Base, LayerTerm::Sheen, LayerTerm::Clearcoat]
                .into_iter()
                .map(|t| m.f_r_term(t, wi, wo, &f))
                .collect();
            for (seen, t) in nonzero.iter_mut().zip(&terms) {
                *seen |= t.min_element() > 0.0;
            }
            let sum = terms[0] + terms[1] + terms[2];
            // Rounding only: three products in another order, ~4 ulps.
            assert!(
                (sum - whole).abs().max_element() <= 1e-14 * whole.max_element(),
                "{sum:?} vs {whole:?}"
            );
            assert_eq!(m.f_r_term(LayerTerm::All, wi, wo, &f), whole);
            checked += 1;
        }
        assert_eq!(checked, 4);
        assert_eq!(nonzero, [true; 3], "every term drawn somewhere");
    }

    #[test]
    fn a_model_without_layers_is_all_base() {
        let m = Material::new("p", ReflectanceModel::PhongNormalized);
        let f = frame();
        let (wi, wo) = (direction(0.5, 0.0), direction(0.6, 3.0));
        assert_eq!(m.f_r_term(LayerTerm::Base, wi, wo, &f), m.f_r(wi, wo, &f));
        assert_eq!(m.f_r_term(LayerTerm::Clearcoat, wi, wo, &f), Rgb::ZERO);
        assert_eq!(LayerChoice::Each.terms(&m), vec![LayerTerm::All]);
        let l = layered();
        assert_eq!(
            LayerChoice::Each.terms(&l),
            vec![
                LayerTerm::All,
                LayerTerm::Base,
                LayerTerm::Sheen,
                LayerTerm::Clearcoat
            ]
        );
    }

    /// The clearcoat term's directional albedo is the albedo of the coat
    /// alone computed as a whole material (a black base without its
    /// specular lobe: `f_r = (1 − k F_c)·0 + k F_c G`, the same numbers),
    /// and with the base's term it sums to the whole's within the
    /// quadrature's error bounds.
    #[test]
    fn the_clearcoat_terms_albedo_is_the_coats_own() {
        use crate::explore::albedo::albedo_towards;
        let mut m = layered();
        m.layers.sheen_color = Rgb::ZERO;
        let mut alone = m.clone();
        // No base lobe: black, no specular lobe, no thin film (whose
        // Fresnel is not 0 over a black base).
        (alone.base_color, alone.layers.specular) = (Rgb::ZERO, 0.0);
        alone.layers.iridescence = 0.0;
        let f = frame();
        for theta in [0.0, 40.0, 75.0_f64] {
            let wi = direction(theta.to_radians(), 0.3);
            let part = |term| MaterialPart::new(&m, term);
            let coat = albedo_towards(part(LayerTerm::Clearcoat), wi, &f);
            let direct = albedo_towards(&alone, wi, &f);
            assert_eq!(coat.value, direct.value, "θ_i = {theta}°");
            // At least k·F_c(1) = 0.7 · 0.04 (more towards grazing).
            assert!(coat.value.x >= 0.7 * 0.04 * 0.99, "{coat:?}");
            let base = albedo_towards(part(LayerTerm::Base), wi, &f);
            let whole = albedo_towards(&m, wi, &f);
            let bound = base.error_bound + coat.error_bound + whole.error_bound;
            let gap = (base.value + coat.value - whole.value).abs();
            assert!(
                gap.cmple(bound + Rgb::splat(1e-14)).all(),
                "θ_i = {theta}°: {gap:?} > {bound:?}"
            );
        }
    }

    /// The far side's white furnace: a white, non-absorbing thin wall
    /// (`transmission = 1`, no compensation) reflects `F·D·Vis` and
    /// transmits `(1 − F)·D·Vis` about the mirror image of the same half
    /// vector, so `ρ + τ` is the GGX lobe's single-scattering albedo: the
    /// albedo of a white metal of the same roughness (`F = 1`), computed
    /// by the same quadrature, within the three error bounds; at most 1.
    /// With diffuse transmission and colours, `ρ + τ ≤ 1` in every
    /// channel (the glTF mix never creates light).
    #[test]
    fn reflected_and_transmitted_albedo_sum_to_at_most_one() {
        use crate::explore::albedo::albedo_towards;
        let f = frame();
        for r in [0.05, 0.3, 0.7] {
            let mut glass = Material::new("g", ReflectanceModel::GltfPbr);
            (glass.base_color, glass.metallic, glass.roughness) = (Rgb::ONE, 0.0, r);
            glass.energy_compensation = false;
            glass.layers.transmission = 1.0;
            let mut metal = glass.clone();
            metal.metallic = 1.0;
            metal.layers.transmission = 0.0;
            for theta in [0.0, 30.0, 60.0, 85.0_f64] {
                let wi = direction(theta.to_radians(), 0.2);
                let part = MaterialPart::from(&glass);
                assert!(part.transmits());
                let rho = albedo_towards(part, wi, &f);
                let tau = albedo_towards(part.transmitted(), wi, &f);
                let lobe = albedo_towards(&metal, wi, &f);
                let bound = rho.error_bound + tau.error_bound + lobe.error_bound;
                let gap = (rho.value + tau.value - lobe.value).abs();
                assert!(
                    gap.cmple(bound + Rgb::splat(1e-13)).all(),
                    "r {r}, θ_i {theta}°: ρ {:?} + τ {:?} vs E {:?}",
                    rho.value,
                    tau.value,
                    lobe.value
                );
                assert!(lobe.value.x <= 1.0 + lobe.error_bound.x);
                if theta <= 60.0 {
                    assert!(tau.value.x > rho.value.x, "a dielectric transmits most");
                }
            }
        }
        let mut leaf = Material::new("l", ReflectanceModel::GltfPbr);
        (leaf.base_color, leaf.roughness) = (Rgb::new(0.9, 0.95, 0.2), 0.5);
        leaf.layers.transmission = 0.4;
        leaf.layers.diffuse_transmission = 0.8;
        leaf.layers.diffuse_transmission_color = Rgb::new(1.0, 0.7, 0.9);
        for theta in [0.0, 45.0, 80.0_f64] {
            let wi = direction(theta.to_radians(), 0.0);
            let part = MaterialPart::from(&leaf);
            let rho = albedo_towards(part, wi, &f);
            let tau = albedo_towards(part.transmitted(), wi, &f);
            let sum = rho.value + tau.value;
            let bound = rho.error_bound + tau.error_bound;
            assert!(sum.cmple(Rgb::ONE + bound).all(), "θ_i {theta}°: {sum:?}");
            assert!(tau.value.min_element() > 0.1, "{:?}", tau.value);
        }
        // The sheen and the clearcoat terms, and opaque models, have no far side.
        assert!(!MaterialPart::new(&leaf, LayerTerm::Clearcoat).transmits());
        let lambert = Material::new("d", ReflectanceModel::Lambert);
        assert!(!MaterialPart::from(&lambert).transmits());
        let wi = direction(0.3, 0.0);
        let tau = albedo_towards(MaterialPart::from(&lambert).transmitted(), wi, &f);
        assert_eq!(tau.value, Rgb::ZERO);
    }

    /// The transmitted slice lies below the surface and its `f_t` peaks on
    /// the light's straight line `θ_i − 180°` (where `D` peaks; `Vis` and
    /// `1 − F` move the peak by 0.065° at r = 0.2, θ_i = 35°: within 1°);
    /// an opaque material has none.
    #[test]
    fn the_transmitted_slice_peaks_straight_through() {
        use crate::explore::Channel;
        use crate::explore::slice::{Quantity, slice};
        let mut glass = Material::new("g", ReflectanceModel::GltfPbr);
        (glass.base_color, glass.roughness) = (Rgb::ONE, 0.2);
        glass.layers.transmission = 1.0;
        let theta_i = 35f64.to_radians();
        let s = slice(&glass, theta_i, 0.0, Quantity::Fr, Channel::Mean);
        assert!(!s.transmitted.is_empty());
        assert!(
            s.transmitted
                .iter()
                .all(|&(t, _)| t.abs() >= std::f64::consts::FRAC_PI_2)
        );
        let peak = s
            .transmitted
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        let straight = theta_i - std::f64::consts::PI;
        assert!(
            (peak.0 - straight).abs() < 1f64.to_radians(),
            "{peak:?} vs {straight}"
        );
        let lambert = Material::new("d", ReflectanceModel::Lambert);
        assert!(
            slice(&lambert, theta_i, 0.0, Quantity::Fr, Channel::Mean)
                .transmitted
                .is_empty()
        );
    }

    #[test]
    fn choices_parse_by_name() {
        for c in LayerChoice::ALL {
            assert_eq!(c.name().parse::<LayerChoice>(), Ok(c));
        }
        let err = "clearcot".parse::<LayerChoice>().unwrap_err();
        assert!(err.contains("clearcoat"), "{err}");
    }
}
