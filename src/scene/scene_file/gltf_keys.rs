//! `[gltf]`: how glTF files are shown. `energy_compensation` (default
//! true: glTF materials are rendered as three.js, Filament and Babylon.js
//! render them, with multiple scattering compensated; false gives the
//! specification's BRDF exactly, the contract's measured-reflectance
//! section), `facing_normals` (default true: a shading normal that faces
//! away from the viewer is turned toward it, `SurfaceFrame::facing`),
//! `default_light` (the light of a glTF scene that has
//! none) and `variant` (the `KHR_materials_variants` variant the files are
//! drawn in). Errors name the key.

use super::schema::GltfSection;
use crate::material::{Material, ReflectanceModel};
use crate::scene::gltf_import::GltfScene;
use std::path::Path;

/// The light of a scene whose glTF files bring none, with no
/// `[[lights]]` and no `[environment] map` (`[gltf] default_light`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DefaultLight {
    /// The built-in neutral studio environment (`"studio"`), lighting
    /// the whole BRDF from every side, as model-viewer's neutral
    /// environment and the Khronos sample viewer do.
    #[default]
    Studio,
    /// The scene files' default light, directional from the upper front
    /// left (`"directional"`).
    Directional,
}

impl DefaultLight {
    pub const NAMES: [&str; 2] = ["studio", "directional"];

    fn parse(s: &str) -> Option<Self> {
        match s {
            "studio" => Some(DefaultLight::Studio),
            "directional" => Some(DefaultLight::Directional),
            _ => None,
        }
    }
}

/// `gltf.variant`: the material variant each glTF file of the scene is
/// drawn in. A file that has variants must have one of that name (an
/// error lists the file's); files without variants are drawn as they
/// are, but at least one file of the scene must have variants.
#[derive(Clone, Debug, Default)]
pub struct VariantChoice {
    name: Option<String>,
    found: bool,
    /// Every variant name of the files seen, in file order, each once
    /// (the viewer's variant choice).
    pub names: Vec<String>,
}

impl VariantChoice {
    pub fn new(section: &GltfSection) -> Self {
        VariantChoice {
            name: section.variant.clone(),
            found: false,
            names: Vec::new(),
        }
    }

    /// Draws `imported` (read from `path`) in the chosen variant.
    pub fn apply(&mut self, path: &Path, imported: &mut GltfScene) -> crate::Result<()> {
        for v in &imported.variants {
            if !self.names.contains(v) {
                self.names.push(v.clone());
            }
        }
        let Some(name) = &self.name else {
            return Ok(());
        };
        if imported.variants.is_empty() {
            return Ok(());
        }
        imported
            .choose_variant(name)
            .map_err(|p| crate::Error::input(path, format!("gltf.variant = \"{name}\": {p}")))?;
        self.found = true;
        Ok(())
    }

    /// After every file: an error if a variant was asked for and no file
    /// has variants.
    pub fn finish(&self) -> Result<(), String> {
        match &self.name {
            Some(name) if !self.found => Err(format!(
                "gltf.variant = \"{name}\": no glTF file of the scene has material variants (KHR_materials_variants)"
            )),
            _ => Ok(()),
        }
    }
}

/// `[gltf]`, validated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GltfKeys {
    /// `None`: each glTF material as imported (compensated).
    pub energy_compensation: Option<bool>,
    /// `None`: each glTF material as imported (facing normals on).
    pub facing_normals: Option<bool>,
    pub default_light: DefaultLight,
}

impl GltfKeys {
    pub fn read(section: &GltfSection) -> Result<GltfKeys, String> {
        let default_light = match &section.default_light {
            None => DefaultLight::default(),
            Some(s) => DefaultLight::parse(s).ok_or_else(|| {
                format!(
                    "gltf.default_light = \"{s}\" is neither \"{}\" nor \"{}\"",
                    DefaultLight::NAMES[0],
                    DefaultLight::NAMES[1]
                )
            })?,
        };
        Ok(GltfKeys {
            energy_compensation: section.energy_compensation,
            facing_normals: section.facing_normals,
            default_light,
        })
    }

    /// Sets `gltf.energy_compensation`, when given, on every glTF
    /// material of `imported` (models without compensation are left as
    /// they are), and `gltf.facing_normals`, when given, on all of them.
    pub fn apply(&self, imported: &mut [Material]) {
        if let Some(on) = self.energy_compensation {
            for m in imported
                .iter_mut()
                .filter(|m| m.model == ReflectanceModel::GltfPbr)
            {
                m.energy_compensation = on;
            }
        }
        if let Some(on) = self.facing_normals {
            for m in imported.iter_mut() {
                m.facing_normals = on;
            }
        }
    }
}
