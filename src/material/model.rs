//! The closed set of reflectance models and their contract names. What
//! each model needs (files, tangents, terms, parameters) is its row in
//! [`super::table`] (which also gives the model its `row()`).

use crate::base::named_enum;

named_enum!(
    /// Every reflectance model gonio knows, by the contract's names. A material
    /// picks one; the GPU compiles only the models (and terms) a scene uses.
    ReflectanceModel, "reflectance model" {
        /// `f_r = k_d / π` (lecture: "Diffuse Reflection Model").
        Lambert = "lambert",
        /// The lecture's Phong: `k_d/π + k_s (R(I)·V)^k_e / (I·N)`, as written
        /// (not normalized, not reciprocal).
        Phong = "phong",
        /// Normalized Phong: `k_d/π + k_s (k_e+2)/(2π) (R(I)·V)^k_e`
        /// (reciprocal, energy conserving).
        PhongNormalized = "phong-normalized",
        /// The lecture's Blinn-Phong: `k_d/π + k_s (H·N)^k_e / (I·N)`, as
        /// written (not normalized, not reciprocal).
        BlinnPhong = "blinn-phong",
        /// Normalized Blinn-Phong (reciprocal, energy conserving).
        BlinnPhongNormalized = "blinn-phong-normalized",
        /// Ward's isotropic model as the lecture writes it (σ = `sigma`).
        Ward = "ward",
        /// Ward's anisotropic model (σ_x along the tangent, σ_y along the bitangent).
        WardAnisotropic = "ward-anisotropic",
        /// Cook-Torrance: `k_d/π + k_s · D·G·F / (denominator (N·V)(N·I))`
        /// with selectable D, G, F and denominator.
        CookTorrance = "cook-torrance",
        /// An ideal mirror: a Dirac lobe of reflectance `k_s · F(cos θ)`; it
        /// reflects the environment and the discs of lights of finite size.
        Mirror = "mirror",
        /// Oren-Nayar's qualitative model of rough diffuse surfaces (Oren &
        /// Nayar 1994, eq. 30): `k_d/π (A + B max(0, cos Δφ) sin α tan β)`.
        OrenNayar = "oren-nayar",
        /// Oren-Nayar's full model (Oren & Nayar 1994, eqs. 27–29): the
        /// direct term with C1, C2, C3 and one interreflection.
        OrenNayarFull = "oren-nayar-full",
        /// A measured BRDF (`measured = NAME|PATH`): a built-in MERL
        /// material's Neural-BRDF network or a MERL-format table
        /// (`src/material/measured/`); `f_r` in 1/sr, no `k_d`, `k_s`.
        Measured = "measured",
        /// glTF 2.0's metallic-roughness BRDF (Appendix B, its `mix` form as
        /// the Khronos sample renderer evaluates it): base colour, metallic,
        /// and glTF's *perceptual* roughness r (GGX α = r², unlike
        /// Cook-Torrance's `roughness`, which is α itself).
        GltfPbr = "gltf-pbr",
        /// The ABC microfacet model of Löw, Kronander, Ynnerman, Unger 2012:
        /// `k_d/π + k_s · F·D·G / (π (N·V)(N·I))` with the ABC distribution
        /// `D = A / (1 + B(1 − cos θ_h))^C`, the V-groove G and the exact
        /// dielectric F, the form of the published fits of the MERL materials.
        Abc = "abc",
        /// No reflection: the surface shows its base colour (× texture ×
        /// `COLOR_0`) as radiance, whatever lights it (glTF
        /// `KHR_materials_unlit`; contract "Other glTF material
        /// extensions"). `f_r = 0`.
        Unlit = "unlit",
    }
);
