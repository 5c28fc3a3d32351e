//! What a scene's shader must contain: the [`ShaderKey`].

use super::features::Feature;
use super::specialization::VariantCode;
use crate::gpu::bindings::UniformArrays;
use crate::gpu::shadows::{Projection, ShadowFeatures, ShadowPlan};
use crate::material::{BrdfVariant, ReflectanceModel};
use crate::scene::{LightKind, Scene, ShadingMode};
use std::collections::BTreeSet;

/// What a scene's shader must contain. Equal keys share a pipeline.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    pub shading: ShadingMode,
    /// The BRDF variants (a model with its chosen terms) of the materials
    /// some mesh uses.
    pub variants: BTreeSet<BrdfVariant>,
    pub light_kinds: BTreeSet<LightKind>,
    /// Shadow-map projections and filtering in use (empty: no shadow code).
    pub shadows: ShadowFeatures,
    /// Loop counts compiled in as constants.
    pub counts: LoopCounts,
    /// Which arrays are bound as uniform buffers (src/gpu/bindings.rs).
    pub arrays: UniformArrays,
    /// Some light has a glTF range: the range window of the
    /// inverse-square law is compiled (feature `light_range`); without,
    /// every light's window is 1 and the code is left out.
    pub light_range: bool,
    /// Some light may coincide with a shaded point (`key::light_guard`): the
    /// inverse-square law's zero-distance guard is compiled (feature
    /// `light_guard`); without, no shaded point is at a light, `d² > 0`
    /// and the guard could never fire.
    pub light_guard: bool,
    /// Compute the shadow-map coordinates per vertex where the key allows
    /// it ([`ShaderKey::shadow_coords_per_vertex`]); `false`: always per
    /// pixel (for tests and measurements of the difference).
    pub vertex_shadow_coords: bool,
    /// `shading.shadow_coords = "vertex"`: also per vertex where that is
    /// an approximation (one perspective map; see
    /// [`ShaderKey::shadow_coords_per_vertex`]).
    pub approximate_shadow_coords: bool,
    /// The scene has an environment map (`Feature::Environment`).
    pub environment: bool,
    /// It lights through the whole BRDF, sampled
    /// (`Feature::EnvironmentSampled`).
    pub environment_sampled: bool,
    /// Its glossy part by the split-sum approximation
    /// (`Feature::EnvironmentPrefiltered`).
    pub environment_prefiltered: bool,
    /// Its Phong lobes by SH convolution (`Feature::EnvironmentSh`).
    pub environment_sh: bool,
    /// Texture slots read per pixel: the most textures of one material the
    /// scene draws (0: no texture code; `crate::gpu::textures`).
    pub texture_slots: u32,
    /// Some material has a normal map (feature `normal_map`; tangents and
    /// bitangent signs in the vertex stream).
    pub normal_maps: bool,
    /// Some material the scene draws is double-sided (feature
    /// `two_sided`: vertex shading computes both sides).
    pub two_sided: bool,
    /// Some material the scene draws is single-sided (feature `culling`).
    pub culling: bool,
    /// Some mesh has vertex colours (feature `vertex_colors`; location 9).
    pub vertex_colors: bool,
    /// Some material the scene draws reads its alpha (glTF `alphaMode`
    /// MASK or BLEND; feature `alpha`).
    pub alpha: bool,
    /// Some material the scene draws is alpha BLEND: its batches are drawn
    /// last, back to front, by pipelines that blend and keep the depth
    /// (`PipelineCache::compile_scene`); no shader feature of its own.
    pub alpha_blend: bool,
    /// Measured materials evaluate their network in WGSL (feature
    /// `measured_network`, `shading.measured_mode = "network"`; only with
    /// a measured variant).
    pub measured_network: bool,
    /// Some material the scene draws has energy compensation (feature
    /// `energy_compensation`).
    pub energy_compensation: bool,
    /// Some material the scene draws emits (`emission` ≠ 0; feature
    /// `emission`): without, the emission add is left out of
    /// `reflected_radiance` (adding 0 changes no pixel).
    pub emission: bool,
    /// Some material the scene draws has an ambient occlusion other than
    /// 1 (a constant or an occlusion texture; feature `occlusion`):
    /// without, the occlusion multiplies are left out (multiplying by 1
    /// changes no pixel). The two cost about 6 % of the bench's
    /// specialized Lambert frame on lavapipe (docs/bench/report.md).
    pub occlusion: bool,
    /// Smith-Beckmann's G1 and Λ by Walter's rational approximation
    /// (feature `smith_beckmann_rational`, `shading.smith_beckmann =
    /// "rational"`; only with a variant that uses them); else the exact
    /// erf form.
    pub smith_beckmann_rational: bool,
    /// `image.tone_map`, compiled into display modules as the constant
    /// `TONE_MAP` so a window pays for its own operator only (computing
    /// all four and selecting by a uniform cost 9–13 % of the viewer's CPU
    /// time on lavapipe, docs/viewer.md). Offscreen modules ignore it.
    pub tone_map: crate::output::tone_map::ToneMap,
}

/// Whether some light of `scene` with a position (point, spot, area
/// sample) may coincide with a point the GPU shades, so that its
/// inverse-square law needs the zero-distance guard (`d² = 0`: no light
/// instead of 0/0). A shaded point is interpolated between a triangle's
/// corners, so it lies in the triangle's mesh's bounding box up to f32
/// rounding (a few units in the last place of the coordinates, about
/// 10⁻⁷ relative); a light outside every mesh's box grown by a margin
/// far above that (10⁻⁴ of the box's size plus its largest coordinate)
/// is at a distance of at least the margin from every shaded point, so
/// its `d²` is positive and the guard would never fire. The guard stays
/// for a light inside or on some box (an area light lying on a wall, a
/// light inside a room): the per-mesh boxes are a cheap test, not the
/// exact distance to the triangles. The left-out guard changes no
/// pixel.
pub fn light_guard(scene: &Scene) -> bool {
    let boxes: Vec<_> = scene
        .meshes
        .iter()
        .filter_map(|m| crate::scene::mesh::bounds(m.positions.iter().copied()))
        .map(|(lo, hi)| {
            let margin = 1e-4 * ((hi - lo).max_element() + lo.abs().max(hi.abs()).max_element());
            (lo - margin, hi + margin)
        })
        .collect();
    scene.lights.iter().filter_map(|l| l.position()).any(|p| {
        !p.is_finite()
            || boxes
                .iter()
                .any(|(lo, hi)| p.cmpge(*lo).all() && p.cmple(*hi).all())
    })
}

/// The counts of the shader's loops, compiled in as WGSL constants so the
/// compiler can unroll them. A software rasterizer pays for every dynamic
/// loop and every private array per pixel: with the light count read from
/// a uniform and a 64-entry visibility array, lavapipe's scene pass took
/// about twice as long as with constants (measured on the viewer's 1080p
/// benchmark scene). Changing a count selects another pipeline; changing
/// a value never does.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct LoopCounts {
    /// Punctual lights (area-light samples included); 0: read from the
    /// globals at run time (an uber shader for any light count).
    pub lights: u32,
    /// Shadow maps looked up per pixel (one per shadowed light; the
    /// samples of an area light share one). 0 without shadows.
    pub shadow_maps: u32,
    /// The PCF kernel radius, `(k − 1) / 2`, when every shadowed light
    /// uses the same one; `None`: read per light.
    pub pcf_radius: Option<u32>,
}

impl ShaderKey {
    /// The features `scene` uses with the shadow maps of `plan` (its
    /// [`ShadowPlan::new`]): the variants of materials that some mesh
    /// references, the kinds of lights present, the projections of the
    /// maps. An empty plan (no light casts shadows, or nothing to cast a
    /// shadow on) compiles no shadow code.
    pub fn new(scene: &Scene, plan: &ShadowPlan) -> ShaderKey {
        let shadows = if plan.is_empty() {
            ShadowFeatures::default()
        } else {
            ShadowFeatures::for_scene(scene)
        };
        let pcf_radius = shadows
            .any()
            .then(|| ShadowFeatures::uniform_pcf_radius(scene))
            .flatten();
        let mut key = ShaderKey {
            shading: scene.shading,
            variants: scene
                .meshes
                .iter()
                .map(|m| scene.materials[m.material].variant())
                .collect(),
            light_kinds: scene.lights.iter().map(|l| l.kind()).collect(),
            counts: LoopCounts {
                lights: scene.lights.len() as u32,
                shadow_maps: if shadows.any() {
                    plan.casters.len() as u32
                } else {
                    0
                },
                pcf_radius,
            },
            shadows,
            arrays: UniformArrays::for_counts(scene.lights.len(), plan.layers.len()),
            light_range: scene.lights.iter().any(|l| {
                matches!(
                    l,
                    crate::scene::Light::Point { range: Some(_), .. }
                        | crate::scene::Light::Spot { range: Some(_), .. }
                )
            }),
            light_guard: light_guard(scene),
            vertex_shadow_coords: true,
            approximate_shadow_coords: scene.shadow_coords == crate::scene::ShadowCoords::Vertex,
            environment: scene.environment.map.is_some(),
            environment_sampled: scene
                .environment
                .map
                .as_ref()
                .is_some_and(|m| m.settings.specular == crate::environment::map::Specular::Sampled),
            environment_prefiltered: scene.environment.map.as_ref().is_some_and(|m| {
                m.settings.specular == crate::environment::map::Specular::Prefiltered
            }),
            environment_sh: scene
                .environment
                .map
                .as_ref()
                .is_some_and(|m| m.settings.specular == crate::environment::map::Specular::Sh),
            texture_slots: crate::gpu::textures::slot_count(scene),
            normal_maps: crate::gpu::textures::has_normal_maps(scene),
            two_sided: scene
                .meshes
                .iter()
                .any(|m| scene.materials[m.material].sides == crate::material::Sides::Both),
            culling: scene
                .meshes
                .iter()
                .any(|m| scene.materials[m.material].sides == crate::material::Sides::Front),
            vertex_colors: scene.meshes.iter().any(|m| !m.colors.is_empty()),
            alpha: scene.meshes.iter().any(|m| {
                scene.materials[m.material].alpha_mode != crate::material::AlphaMode::Opaque
            }),
            alpha_blend: scene.meshes.iter().any(|m| {
                scene.materials[m.material].alpha_mode == crate::material::AlphaMode::Blend
            }),
            measured_network: scene.measured_network,
            energy_compensation: scene
                .meshes
                .iter()
                .any(|m| scene.materials[m.material].energy_compensation),
            emission: scene
                .meshes
                .iter()
                .any(|m| scene.materials[m.material].emits()),
            occlusion: scene
                .meshes
                .iter()
                .any(|m| scene.materials[m.material].has_occlusion()),
            smith_beckmann_rational: scene.smith_beckmann
                == crate::material::SmithBeckmann::Rational,
            tone_map: scene.tone_map,
        };
        key.arrays.measured = key.has_measured();
        key.measured_network &= key.has_measured();
        key.smith_beckmann_rational &= key.uses_beckmann_g1();
        key
    }

    /// `GpuMaterial.variant` of a material of `variant`: its packed codes
    /// (the same in every key; see [`VariantCode::packed`]).
    pub fn variant_code(&self, variant: &BrdfVariant) -> u32 {
        VariantCode::of(variant).packed()
    }

    /// The packed variants `key`'s pipelines are specialized to: each of
    /// its BRDF variants when it has several (each material's batch is
    /// drawn by the pipeline of its variant), else `None` (one pipeline,
    /// specialized by the module's defaults).
    pub fn specializations(&self) -> Vec<Option<u32>> {
        match self.variants.len() {
            0 | 1 => vec![None],
            _ => self
                .variants
                .iter()
                .map(|v| Some(self.variant_code(v)))
                .collect(),
        }
    }

    /// Whether any variant needs a tangent frame in the vertex stream
    /// (an anisotropic model, or a normal map).
    pub fn needs_tangents(&self) -> bool {
        self.normal_maps || self.variants.iter().any(|v| v.model.needs_tangents())
    }

    /// Whether the vertex shader computes the shadow-map coordinates
    /// (feature `shadow_vertex`, else `shadow_pixel`): per-pixel (Phong)
    /// shading whose one shadow map is orthographic. The lookup point is
    /// then `x` plus an offset that depends only on the light and the
    /// triangle's geometric normal, so its map coordinates are an affine
    /// function of `x` over each triangle and interpolating them from the
    /// corners (perspective-correct, as `x` itself) gives what the
    /// fragment shader would compute, without a matrix, the offset and the
    /// position derivatives per pixel: on lavapipe, the 1080p viewer
    /// benchmark's scene pass went from about 28 to about 25 ms
    /// (tests/shadows.rs (e) checks that the images are the same). The
    /// vertex stream is then de-indexed, each corner with its triangle's
    /// normal (`VertexLayout::face_normal`).
    ///
    /// With `shading.shadow_coords = "vertex"`
    /// ([`ShaderKey::approximate_shadow_coords`]) also when the one map is
    /// perspective (a spot light): the corners' homogeneous map
    /// coordinates are interpolated and divided per pixel, exact for the
    /// projection of `x` but not for the lookup point's offsets, which
    /// scale with the distance to the light and turn with the direction
    /// to it; docs/shadows.md bounds the displacement over a triangle.
    /// Cube maps stay per pixel (the face is chosen per lookup point).
    pub fn shadow_coords_per_vertex(&self) -> bool {
        let projection = |p: Projection| {
            self.shadows.projections.len() == 1 && self.shadows.projections.contains(&p)
        };
        self.vertex_shadow_coords
            && self.shading == ShadingMode::Phong
            && self.counts.shadow_maps == 1
            && (projection(Projection::Ortho)
                || (self.approximate_shadow_coords && projection(Projection::Perspective)))
    }

    /// Whether any variant is measured: group 0 then binds the measured
    /// tables ([`UniformArrays::measured`]).
    pub fn has_measured(&self) -> bool {
        self.variants
            .iter()
            .any(|v| v.model == ReflectanceModel::Measured)
    }

    /// Whether any variant evaluates Smith's G1 or Λ for Beckmann:
    /// Cook-Torrance with `smith` or `smith-correlated` geometry and a
    /// distribution other than GGX (which has its own).
    pub fn uses_beckmann_g1(&self) -> bool {
        use crate::material::{Distribution, Geometry};
        self.variants
            .iter()
            .map(super::specialization::resolved)
            .any(|v| {
                v.model == ReflectanceModel::CookTorrance
                    && matches!(
                        v.geometry,
                        Some(Geometry::Smith | Geometry::SmithCorrelated)
                    )
                    && v.distribution != Some(Distribution::Ggx)
            })
    }

    /// Whether any variant is a mirror (environment reflection code).
    pub fn has_mirror(&self) -> bool {
        self.variants
            .iter()
            .any(|v| v.model == ReflectanceModel::Mirror)
    }

    /// The models of the variants, each once.
    pub fn models(&self) -> BTreeSet<ReflectanceModel> {
        self.variants.iter().map(|v| v.model).collect()
    }

    /// The `#if` features on for this key.
    pub fn features(&self) -> Vec<Feature> {
        let mut f = Vec::new();
        if self.shading == ShadingMode::Flat {
            f.push(Feature::Flat);
        }
        if self.needs_tangents() {
            f.push(Feature::Tangents);
        }
        f.extend(super::specialization::brdf_features(&self.variants));
        f.extend(Feature::of_shadows(&self.shadows));
        if self.shadow_coords_per_vertex() {
            f.push(Feature::ShadowVertex);
        } else if self.shadows.any() {
            f.push(Feature::ShadowPixel);
        }
        if self.counts.lights > 0 {
            f.push(Feature::LightCount);
        }
        if self.light_range {
            f.push(Feature::LightRange);
        }
        if self.light_guard {
            f.push(Feature::LightGuard);
        }
        if self.shadows.pcf && self.counts.pcf_radius.is_some() {
            f.push(Feature::PcfUniform);
        }
        if self.arrays.lights {
            f.push(Feature::UniformLights);
        }
        if self.arrays.shadow_views {
            f.push(Feature::UniformShadowViews);
        }
        if self.environment {
            f.push(Feature::Environment);
            if self.environment_sampled {
                f.push(Feature::EnvironmentSampled);
            }
            if self.environment_prefiltered {
                f.push(Feature::EnvironmentPrefiltered);
            }
            if self.environment_sh {
                f.push(Feature::EnvironmentSh);
            }
        }
        if self.texture_slots > 0 {
            f.push(Feature::Textures);
            if self.normal_maps {
                f.push(Feature::NormalMap);
            }
        }
        if self.two_sided {
            f.push(Feature::TwoSided);
        }
        if self.culling {
            f.push(Feature::Culling);
        }
        if self.vertex_colors {
            f.push(Feature::VertexColors);
        }
        if self.alpha {
            f.push(Feature::Alpha);
        }
        if self.measured_network {
            f.push(Feature::MeasuredNetwork);
        }
        if self.energy_compensation {
            f.push(Feature::EnergyCompensation);
        }
        if self.smith_beckmann_rational {
            f.push(Feature::SmithBeckmannRational);
        }
        if self.emission {
            f.push(Feature::Emission);
        }
        if self.occlusion {
            f.push(Feature::Occlusion);
        }
        f
    }

    /// A one-line description for logs.
    pub fn describe(&self) -> String {
        let variants: Vec<_> = self.variants.iter().map(|v| v.describe()).collect();
        let lights: Vec<_> = self.light_kinds.iter().map(|k| k.name()).collect();
        format!(
            "shading {}, models [{}], lights [{}], {}{}",
            self.shading,
            variants.join(", "),
            lights.join(", "),
            self.shadows.describe(),
            if self.environment {
                ", environment map"
            } else {
                ""
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_file::{self, SceneSource};

    fn key_with_light(light: &str) -> ShaderKey {
        let scene =
            scene_file::load(&SceneSource::BuiltIn, &[format!("lights=[{light}]")]).unwrap();
        ShaderKey::new(&scene, &ShadowPlan::new(&scene))
    }

    /// The guard and the range window are compiled exactly when a light
    /// needs them: a light inside a mesh's box (the sphere's centre) or
    /// on its boundary (the floor's plane) keeps the guard, one above
    /// the scene does not; a range turns the window on.
    #[test]
    fn guard_and_range_window_only_where_a_light_has_them() {
        let above = key_with_light(
            r#"{kind="point", position=[3.0, 5.0, 3.0], intensity=[1.0, 1.0, 1.0]}"#,
        );
        assert!(!above.light_guard && !above.light_range);
        let inside = key_with_light(
            r#"{kind="point", position=[0.0, 1.0, 0.0], intensity=[1.0, 1.0, 1.0]}"#,
        );
        assert!(inside.light_guard);
        let on_floor = key_with_light(
            r#"{kind="spot", position=[0.5, 0.0, 2.0], direction=[0.0, 1.0, 0.0], intensity=[1.0, 1.0, 1.0], range=4.0}"#,
        );
        assert!(on_floor.light_guard && on_floor.light_range);
        assert!(on_floor.features().contains(&Feature::LightGuard));
        assert!(on_floor.features().contains(&Feature::LightRange));
        let sun = key_with_light(
            r#"{kind="directional", direction=[0.0, -1.0, 0.0], irradiance=[1.0, 1.0, 1.0]}"#,
        );
        assert!(!sun.light_guard && !sun.light_range);
    }
}
