//! Compare mode: materials compared with the selected one. Every plot
//! overlays them (with their albedo and gloss in the table), and the 3D
//! view can be split: its left half shows the scene as it is, its right
//! half the same scene, camera and lights with the selected material
//! replaced by one of the compared materials. One object cut down the
//! middle, lit alike on both sides, so the two materials meet at the seam.
//!
//! The compared materials are the viewer's, not the scene file's: Save
//! scene does not write them. They come from `gonio view --compare SPEC`
//! (the syntax of `gonio brdf --compare`), `--compare-fit MODEL` (a
//! measured material's fit, [`super::fitted`]), or the panel; scripted
//! edits address them as `compare.N.KEY=VALUE` (N from 0),
//! `compare.split=BOOL` and `compare.shown=N`.

use crate::material::Material;

/// The compared materials and the split view.
#[derive(Clone, Debug, Default)]
pub struct Compare {
    /// Each with its name (the plots' table shows it).
    pub materials: Vec<Material>,
    /// Whether the 3D view is split.
    pub split: bool,
    /// Which compared material the right half shows.
    pub shown: usize,
}

impl Compare {
    /// Adds `m`; the first one added splits the view.
    pub fn add(&mut self, m: Material) {
        if self.materials.is_empty() {
            self.split = true;
            self.shown = 0;
        }
        self.materials.push(m);
    }

    /// Removes compared material `i`.
    pub fn remove(&mut self, i: usize) {
        if i < self.materials.len() {
            self.materials.remove(i);
        }
        if self.shown >= self.materials.len() {
            self.shown = self.materials.len().saturating_sub(1);
        }
        if self.materials.is_empty() {
            self.split = false;
        }
    }

    /// The material the right half of a split view shows, if split.
    pub fn right_half(&self) -> Option<&Material> {
        self.split.then(|| self.materials.get(self.shown)).flatten()
    }

    /// Applies `compare.…` edit `parts` (after `compare`) `= value`.
    pub fn edit(&mut self, parts: &[&str], value: &str) -> Result<(), String> {
        match parts {
            ["split"] => {
                let on: bool = crate::ui::edit_values::toml_value(value)?;
                if on && self.materials.is_empty() {
                    return Err("there is no compared material to split the view with (gonio view --compare SPEC adds one)".into());
                }
                self.split = on;
                Ok(())
            }
            ["shown"] => {
                let i: usize = crate::ui::edit_values::toml_value(value)?;
                if i >= self.materials.len() {
                    return Err(self.no_such(i));
                }
                self.shown = i;
                Ok(())
            }
            [index, field] => {
                let i: usize = index
                    .parse()
                    .map_err(|_| format!("`{index}` is not the index of a compared material"))?;
                let m = self.materials.get(i).ok_or_else(|| self.no_such(i))?;
                let edited = crate::ui::edit_values::edit_material(m, field, value)?;
                edited.validate()?;
                self.materials[i] = edited;
                Ok(())
            }
            _ => Err(
                "compare mode takes compare.N.KEY (N from 0), compare.split and compare.shown"
                    .into(),
            ),
        }
    }

    fn no_such(&self, i: usize) -> String {
        match self.materials.len() {
            0 => format!(
                "there is no compared material {i}: none is compared (gonio view --compare SPEC adds one)"
            ),
            n => format!(
                "there is no compared material {i}: they are numbered 0 to {}",
                n - 1
            ),
        }
    }
}

/// Runs `f` on `scene` with material `index` replaced by `other` (keeping
/// the replaced material's name), then puts it back: the right half of a
/// split view is the same scene with one material swapped, and cloning a
/// scene would copy its meshes.
pub fn with_material<R>(
    scene: &mut crate::scene::Scene,
    index: usize,
    other: &Material,
    f: impl FnOnce(&crate::scene::Scene) -> R,
) -> R {
    let mut swapped = other.clone();
    swapped.name = scene.materials[index].name.clone();
    std::mem::swap(&mut scene.materials[index], &mut swapped);
    let result = f(scene);
    std::mem::swap(&mut scene.materials[index], &mut swapped);
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::ReflectanceModel;

    #[test]
    fn compare_edits_change_only_the_compared_material() {
        let mut c = Compare::default();
        assert!(
            c.edit(&["0", "k_e"], "5")
                .unwrap_err()
                .contains("none is compared")
        );
        assert!(c.edit(&["split"], "true").is_err());
        c.add(Material::new("B", ReflectanceModel::Phong));
        assert!(c.split && c.right_half().is_some());
        c.edit(&["0", "k_d"], "[0.0, 0.0, 1.0]").unwrap();
        assert_eq!(c.materials[0].k_d, crate::scene::Rgb::new(0.0, 0.0, 1.0));
        assert!(c.edit(&["0", "k_e"], "-3").is_err());
        assert!(c.edit(&["1", "k_e"], "3").unwrap_err().contains("0 to 0"));
        assert!(c.edit(&["shown"], "2").is_err());
        c.edit(&["split"], "false").unwrap();
        assert!(c.right_half().is_none());
        c.remove(0);
        assert!(c.materials.is_empty() && !c.split);
    }

    #[test]
    fn the_swap_is_undone() {
        let mut doc = crate::ui::document::Document::load(
            crate::scene::scene_file::SceneSource::BuiltIn,
            vec![],
            crate::scene::limits::Limits::default(),
        )
        .unwrap();
        let scene = &mut doc.scene;
        let before = scene.materials.clone();
        let other = Material::new("B", ReflectanceModel::Phong);
        let seen = with_material(scene, 0, &other, |s| {
            (s.materials[0].model, s.materials[0].name.clone())
        });
        assert_eq!(seen, (ReflectanceModel::Phong, before[0].name.clone()));
        assert_eq!(scene.materials, before);
    }
}
