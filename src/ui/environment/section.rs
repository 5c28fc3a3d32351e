//! The side panel's Environment section: the map's path field and the
//! editor of its keys ([`super::editor`]), whose edits go through
//! `Document::edit` as `--edit environment.KEY=VALUE` does.
//!
//! An edit that needs a prefiltered stack not made yet (the prefiltered
//! mode, or a new `prefilter_size`) is held while the stack is made on a
//! background thread ([`crate::ui::background`]), with a progress bar;
//! the scene keeps its current look until the stack is ready, then the
//! edit is applied and the upload finds the stack made.

use crate::environment::map::{MapData, Specular};
use crate::environment::prefiltered;
use crate::ui::shared::Shared;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

/// The Environment section's state: the map path being typed.
#[derive(Debug, Default)]
pub struct EnvironmentSection {
    /// The path field (the map's name until one is typed; a dropped file
    /// fills it too).
    pub path: String,
    /// Edits held until their prefiltered stack is made.
    pending: Option<PendingStack>,
}

/// A prefiltered stack being made in the background, and the edits that
/// wait for it.
#[derive(Debug)]
struct PendingStack {
    edits: Vec<String>,
    size: u32,
    /// Texels computed so far, of `prefiltered::texels_to_compute(size)`.
    done: Arc<AtomicU64>,
    finished: Arc<AtomicBool>,
    started: Instant,
}

impl EnvironmentSection {
    /// Lays out the section and applies what it asks for.
    pub fn ui(&mut self, ui: &mut egui::Ui, shared: &mut Shared) {
        if !self.poll(shared) {
            if let Some(p) = &self.pending {
                let total = prefiltered::texels_to_compute(p.size) as f32;
                let fraction = p.done.load(Ordering::Relaxed) as f32 / total;
                ui.add(egui::ProgressBar::new(fraction.min(1.0)).text(format!(
                    "prefiltering the map at {} ({:.0} s)",
                    p.size,
                    p.started.elapsed().as_secs_f64()
                )));
            }
            ui.ctx().request_repaint();
            return;
        }
        let doc = &*shared.doc;
        let off = super::document::is_off(doc);
        let settings = doc.scene.environment.map.as_ref().map(|m| m.settings);
        if let Some(m) = &doc.scene.environment.map
            && self.path.is_empty()
        {
            self.path = m.data.name.clone();
        }
        let edits = super::editor::environment_editor(ui, settings, off, &mut self.path);
        if self.submit(edits, shared) {
            ui.ctx().request_repaint();
        }
    }

    /// Applies `edits`, or holds them while the prefiltered stack they
    /// need is made in the background: whether they are held.
    fn submit(&mut self, edits: Vec<String>, shared: &mut Shared) -> bool {
        if let Some(map) = &shared.doc.scene.environment.map
            && let Some(size) =
                stack_needed(&edits, map.settings.specular, map.settings.prefilter_size)
            && map.data.cached_prefiltered(size).is_none()
        {
            self.pending = Some(PendingStack::start(map.data.clone(), size, edits));
            return true;
        }
        for edit in edits {
            shared.edit(&edit);
        }
        false
    }

    /// Applies the held edits once their stack is made: whether nothing
    /// is held any more.
    fn poll(&mut self, shared: &mut Shared) -> bool {
        match &self.pending {
            None => true,
            Some(p) if p.finished.load(Ordering::Acquire) => {
                let p = self.pending.take().expect("checked");
                for edit in &p.edits {
                    shared.edit(edit);
                }
                true
            }
            Some(_) => false,
        }
    }
}

impl PendingStack {
    /// Starts making `data`'s stack `size` wide in the background.
    fn start(data: Arc<MapData>, size: u32, edits: Vec<String>) -> PendingStack {
        let done = Arc::new(AtomicU64::new(0));
        let finished = Arc::new(AtomicBool::new(false));
        let (d, f) = (done.clone(), finished.clone());
        crate::ui::background::spawn(move || {
            data.prefiltered_stack(size, &d);
            f.store(true, Ordering::Release);
        });
        PendingStack {
            edits,
            size,
            done,
            finished,
            started: Instant::now(),
        }
    }
}

/// The prefilter size whose stack `edits` need, if they leave the map in
/// the prefiltered mode with a size or mode they change (from the
/// current `specular` and `size`).
fn stack_needed(edits: &[String], specular: Specular, size: u32) -> Option<u32> {
    let (mut mode, mut new_size, mut changed) = (specular, size, false);
    for edit in edits {
        if let Some(v) = edit.strip_prefix("environment.specular=") {
            mode = Specular::parse(v.trim_matches('"')).unwrap_or(mode);
            changed = true;
        } else if let Some(v) = edit.strip_prefix("environment.prefilter_size=") {
            new_size = v.parse().unwrap_or(new_size);
            changed = true;
        }
    }
    (changed && mode == Specular::Prefiltered).then_some(new_size)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::change::Changes;
    use crate::scene::scene_file::SceneSource;
    use crate::ui::document::Document;

    /// A new prefilter size is held, its stack made in the background
    /// while the document keeps the old size, then applied; the stack is
    /// then cached, so the upload does not make it again.
    #[test]
    fn a_new_stack_is_made_in_the_background_before_the_edit_applies() {
        let mut doc = Document::load(
            SceneSource::BuiltIn,
            vec![
                "environment.map=\"sky\"".into(),
                "environment.specular=\"prefiltered\"".into(),
            ],
            Default::default(),
        )
        .unwrap();
        let (mut changes, mut message) = (Changes::default(), None);
        let mut shared = Shared {
            doc: &mut doc,
            changes: &mut changes,
            message: &mut message,
        };
        let mut section = EnvironmentSection::default();
        assert!(section.submit(vec!["environment.prefilter_size=128".into()], &mut shared));
        let size = |s: &Shared| {
            s.doc
                .scene
                .environment
                .map
                .as_ref()
                .unwrap()
                .settings
                .prefilter_size
        };
        assert_eq!(size(&shared), 64, "applied before its stack was made");
        let start = Instant::now();
        while !section.poll(&mut shared) {
            assert!(start.elapsed().as_secs() < 120, "the stack was not made");
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        assert_eq!(size(&shared), 128);
        let map = shared.doc.scene.environment.map.as_ref().unwrap();
        assert!(map.data.cached_prefiltered(128).is_some());
        assert!(message.is_none(), "{message:?}");
        // A size whose stack is made applies at once (64's was never
        // made here: no upload ran; 128's now is).
        let mut shared = Shared {
            doc: &mut doc,
            changes: &mut changes,
            message: &mut message,
        };
        shared.edit("environment.prefilter_size=32");
        assert!(section.submit(vec!["environment.prefilter_size=64".into()], &mut shared));
        section.pending = None;
        assert!(!section.submit(vec!["environment.prefilter_size=128".into()], &mut shared));
        assert_eq!(size(&shared), 128);
    }

    #[test]
    fn a_new_size_or_the_prefiltered_mode_needs_a_stack() {
        let e = |s: &[&str]| s.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            stack_needed(
                &e(&["environment.prefilter_size=2048"]),
                Specular::Prefiltered,
                64
            ),
            Some(2048)
        );
        assert_eq!(
            stack_needed(
                &e(&["environment.specular=\"prefiltered\""]),
                Specular::Sampled,
                256
            ),
            Some(256)
        );
        assert_eq!(
            stack_needed(&e(&["environment.scale=2"]), Specular::Prefiltered, 64),
            None
        );
        assert_eq!(
            stack_needed(
                &e(&["environment.specular=\"sampled\""]),
                Specular::Prefiltered,
                64
            ),
            None
        );
    }
}
