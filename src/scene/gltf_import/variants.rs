//! `KHR_materials_variants`: a file names variants (`extensions.
//! KHR_materials_variants.variants`, each with a `name`) and a primitive
//! maps variants to materials (`mappings`, each a `material` and the
//! `variants` that use it). Every material loads (they are all glTF
//! materials of the file); a primitive draws its own `material` (the
//! file's default look) until a variant is chosen
//! ([`GltfScene::choose_variant`], the scene file's `[gltf] variant`);
//! a primitive no mapping of the chosen variant names keeps its own.

use super::GltfScene;
use serde::Deserialize;

pub(super) const NAME: &str = "KHR_materials_variants";

#[derive(Deserialize)]
struct Variants {
    variants: Vec<Variant>,
}

#[derive(Deserialize)]
struct Variant {
    name: String,
}

#[derive(Deserialize)]
struct Mappings {
    mappings: Vec<Mapping>,
}

#[derive(Deserialize)]
struct Mapping {
    material: usize,
    variants: Vec<usize>,
}

/// The variants' names, in the file's order (none without the extension).
pub(super) fn names(document: &gltf::Document) -> Result<Vec<String>, String> {
    let Some(value) = document.extension_value(NAME) else {
        return Ok(Vec::new());
    };
    let v = Variants::deserialize(value).map_err(|e| format!("extensions.{NAME}: {e}"))?;
    Ok(v.variants.into_iter().map(|v| v.name).collect())
}

/// `primitive`'s mappings as `(variant, material)` pairs, each index
/// checked against the file's `variants` and `materials` counts.
pub(super) fn mappings(
    primitive: &gltf::Primitive,
    variants: usize,
    materials: usize,
) -> Result<Vec<(usize, usize)>, String> {
    let Some(value) = primitive.extension_value(NAME) else {
        return Ok(Vec::new());
    };
    let m = Mappings::deserialize(value).map_err(|e| format!("{NAME}: {e}"))?;
    let mut pairs = Vec::new();
    for mapping in m.mappings {
        if mapping.material >= materials {
            return Err(format!(
                "{NAME}: a mapping names material {}; the file has {materials}",
                mapping.material
            ));
        }
        for variant in mapping.variants {
            if variant >= variants {
                return Err(format!(
                    "{NAME}: a mapping names variant {variant}; the file has {variants}"
                ));
            }
            pairs.push((variant, mapping.material));
        }
    }
    Ok(pairs)
}

impl GltfScene {
    /// Draws every primitive with its material of variant `name`
    /// (primitives without one keep theirs); an error listing the file's
    /// variants if it has none of that name.
    pub fn choose_variant(&mut self, name: &str) -> Result<(), String> {
        let Some(chosen) = self.variants.iter().position(|v| v == name) else {
            return Err(if self.variants.is_empty() {
                format!("there is no material variant \"{name}\": the file has none ({NAME})")
            } else {
                let listed: Vec<String> =
                    self.variants.iter().map(|v| format!("\"{v}\"")).collect();
                format!(
                    "there is no material variant \"{name}\"; the file's variants are {}",
                    listed.join(", ")
                )
            });
        };
        for (mesh, mappings) in self.meshes.iter_mut().zip(&self.variant_materials) {
            if let Some(&(_, material)) = mappings.iter().find(|(v, _)| *v == chosen) {
                mesh.material = material;
            }
        }
        Ok(())
    }
}
