//! What an edit of a loaded [`super::Scene`] reached, so that whoever
//! holds a copy of it elsewhere (the viewer's scene on the GPU) rewrites
//! that and nothing else: a roughness slider on a textured glTF should
//! write one material record, not the vertex stream, the textures and the
//! shadow maps.
//!
//! Every edit names its [`Change`]; the edits between two frames gather
//! in one [`Changes`], which the renderer applies at once
//! (`gpu::PreparedScene::apply`).

use std::collections::BTreeSet;

/// What one edit changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// The parameters of material `index` of `Scene::materials` (not
    /// which meshes use it).
    Material(usize),
    /// Every material's values as drawn: the roughness floor follows the
    /// image height (`Scene::roughness_floor`).
    Materials,
    /// The lights: one moved, recoloured, added, removed or retyped.
    Lights,
    /// The camera, the image size, the exposure or the ambient radiance.
    View,
    /// The environment map or its settings.
    Environment,
    /// A material drawn in place of one of the scene's (the viewer's
    /// split view): the scene itself is as it was.
    Compared,
    /// Anything else (the shading mode, the tone map, a new document):
    /// everything is compared with what was drawn.
    Scene,
}

/// The changes gathered since the scene was last drawn.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Changes {
    /// Materials edited one by one (indices).
    pub materials: BTreeSet<usize>,
    /// Every material ([`Change::Materials`]).
    pub all_materials: bool,
    pub lights: bool,
    pub view: bool,
    pub environment: bool,
    pub compared: bool,
    pub scene: bool,
}

impl Changes {
    /// Everything, as for a scene never drawn.
    pub fn everything() -> Changes {
        Changes {
            scene: true,
            ..Changes::default()
        }
    }

    /// Adds `change`.
    pub fn mark(&mut self, change: Change) {
        match change {
            Change::Material(i) => {
                self.materials.insert(i);
            }
            Change::Materials => self.all_materials = true,
            Change::Lights => self.lights = true,
            Change::View => self.view = true,
            Change::Environment => self.environment = true,
            Change::Compared => self.compared = true,
            Change::Scene => self.scene = true,
        }
    }

    /// Nothing changed.
    pub fn is_empty(&self) -> bool {
        *self == Changes::default()
    }

    /// The changes so far, leaving none.
    pub fn take(&mut self) -> Changes {
        std::mem::take(self)
    }

    /// Whether material `index` may have changed.
    pub fn material(&self, index: usize) -> bool {
        self.scene || self.all_materials || self.materials.contains(&index)
    }

    /// Whether only the view changed (the camera, the exposure): what a
    /// renderer writes is the per-view values.
    pub fn view_only(&self) -> bool {
        *self
            == Changes {
                view: true,
                ..Changes::default()
            }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn changes_gather_by_kind() {
        let mut c = Changes::default();
        assert!(c.is_empty());
        c.mark(Change::View);
        assert!(c.view_only());
        c.mark(Change::Material(3));
        c.mark(Change::Material(1));
        c.mark(Change::Material(3));
        assert!(!c.view_only() && !c.is_empty());
        assert_eq!(c.materials.iter().copied().collect::<Vec<_>>(), [1, 3]);
        assert!(c.material(3) && !c.material(2));
        let taken = c.take();
        assert!(c.is_empty());
        assert!(taken.material(1));
        let all = Changes::everything();
        assert!(all.material(7) && all.scene);
        let mut floor = Changes::default();
        floor.mark(Change::Materials);
        assert!(floor.material(0) && !floor.scene);
    }
}
