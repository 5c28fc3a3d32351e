//! What a scene's shader must contain: the [`ShaderKey`], its groups
//! ([`super::key_groups`]: lights, shadow maps, environment, materials)
//! and the features it turns on.

use super::features::Feature;
use super::key_groups::{EnvironmentKey, LightsKey, MaterialsKey, ShadowKey};
use super::specialization::VariantCode;
use crate::gpu::bindings::UniformArrays;
use crate::gpu::shadows::{Projection, ShadowFeatures, ShadowPlan};
use crate::material::{BrdfVariant, ReflectanceModel};
use crate::scene::{Scene, ShadingMode};
use std::collections::BTreeSet;

/// What a scene's shader must contain. Equal keys share a pipeline.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    pub shading: ShadingMode,
    /// The BRDF variants (a model with its chosen terms) of the materials
    /// some mesh uses.
    pub variants: BTreeSet<BrdfVariant>,
    pub lights: LightsKey,
    pub shadows: ShadowKey,
    /// Loop counts compiled in as constants.
    pub counts: LoopCounts,
    /// Which arrays are bound as uniform buffers (src/gpu/bindings.rs).
    pub arrays: UniformArrays,
    pub environment: EnvironmentKey,
    pub materials: MaterialsKey,
    /// `image.tone_map`, compiled into display modules as the constant
    /// `TONE_MAP` so a window pays for its own operator only (computing
    /// all four and selecting by a uniform cost 9–13 % of the viewer's CPU
    /// time on lavapipe, docs/notes/viewer-frame-times.md). Offscreen modules ignore it.
    pub tone_map: crate::output::tone_map::ToneMap,
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
        let maps = if plan.is_empty() {
            ShadowFeatures::default()
        } else {
            ShadowFeatures::for_scene(scene)
        };
        let pcf_radius = maps
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
            lights: LightsKey::for_scene(scene),
            counts: LoopCounts {
                lights: scene.lights.len() as u32,
                shadow_maps: if maps.any() {
                    plan.casters.len() as u32
                } else {
                    0
                },
                pcf_radius,
            },
            shadows: ShadowKey {
                maps,
                vertex_coords: true,
                approximate_coords: scene.shadow_coords == crate::scene::ShadowCoords::Vertex,
            },
            arrays: UniformArrays::for_counts(scene.lights.len(), plan.layers.len()),
            environment: EnvironmentKey::for_scene(scene),
            materials: MaterialsKey::for_scene(scene),
            tone_map: scene.tone_map,
        };
        key.arrays.measured = key.has_measured();
        key.materials.measured_network &= key.has_measured();
        key.materials.smith_beckmann_rational &= key.uses_beckmann_g1();
        key.arrays.sheen = key.materials.layer_sheen;
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
    /// (an anisotropic model or glTF layer, or a normal map).
    pub fn needs_tangents(&self) -> bool {
        self.materials.normal_maps
            || self.materials.layer_anisotropy
            || self.variants.iter().any(|v| v.model.needs_tangents())
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
    /// ([`ShadowKey::approximate_coords`]) also when the one map is
    /// perspective (a spot light): the corners' homogeneous map
    /// coordinates are interpolated and divided per pixel, exact for the
    /// projection of `x` but not for the lookup point's offsets, which
    /// scale with the distance to the light and turn with the direction
    /// to it; docs/shadows.md bounds the displacement over a triangle.
    /// Cube maps stay per pixel (the face is chosen per lookup point).
    pub fn shadow_coords_per_vertex(&self) -> bool {
        let projection = |p: Projection| {
            self.shadows.maps.projections.len() == 1 && self.shadows.maps.projections.contains(&p)
        };
        self.shadows.vertex_coords
            && self.shading == ShadingMode::Phong
            && self.counts.shadow_maps == 1
            && (projection(Projection::Ortho)
                || (self.shadows.approximate_coords && projection(Projection::Perspective)))
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

    /// The `#if` features on for this key: the one place they are derived
    /// from it (each group's flags from its declaration).
    pub fn features(&self) -> Vec<Feature> {
        let mut f = Vec::new();
        if self.shading == ShadingMode::Flat {
            f.push(Feature::Flat);
        }
        if self.needs_tangents() {
            f.push(Feature::Tangents);
        }
        f.extend(super::specialization::brdf_features(&self.variants));
        f.extend(self.shadows.map_features());
        if self.shadow_coords_per_vertex() {
            f.push(Feature::ShadowVertex);
        } else if self.shadows.any() {
            f.push(Feature::ShadowPixel);
        }
        if self.counts.lights > 0 {
            f.push(Feature::LightCount);
        }
        f.extend(self.lights.features());
        if self.shadows.maps.pcf && self.counts.pcf_radius.is_some() {
            f.push(Feature::PcfUniform);
        }
        if self.arrays.lights {
            f.push(Feature::UniformLights);
        }
        if self.arrays.shadow_views {
            f.push(Feature::UniformShadowViews);
        }
        f.extend(self.environment.features());
        f.extend(self.materials.features());
        f
    }

    /// A one-line description for logs.
    pub fn describe(&self) -> String {
        let variants: Vec<_> = self.variants.iter().map(|v| v.describe()).collect();
        let lights: Vec<_> = self.lights.kinds.iter().map(|k| k.name()).collect();
        format!(
            "shading {}, models [{}], lights [{}], {}{}",
            self.shading,
            variants.join(", "),
            lights.join(", "),
            self.shadows.maps.describe(),
            if self.environment.map {
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
        assert!(!above.lights.guard && !above.lights.range);
        let inside = key_with_light(
            r#"{kind="point", position=[0.0, 1.0, 0.0], intensity=[1.0, 1.0, 1.0]}"#,
        );
        assert!(inside.lights.guard);
        let on_floor = key_with_light(
            r#"{kind="spot", position=[0.5, 0.0, 2.0], direction=[0.0, 1.0, 0.0], intensity=[1.0, 1.0, 1.0], range=4.0}"#,
        );
        assert!(on_floor.lights.guard && on_floor.lights.range);
        assert!(on_floor.features().contains(&Feature::LightGuard));
        assert!(on_floor.features().contains(&Feature::LightRange));
        let sun = key_with_light(
            r#"{kind="directional", direction=[0.0, -1.0, 0.0], irradiance=[1.0, 1.0, 1.0]}"#,
        );
        assert!(!sun.lights.guard && !sun.lights.range);
    }
}
