//! One background computation per plotted quantity: the albedo and gloss
//! integrals take milliseconds to a second (narrow lobes, measured
//! networks), so they run on a background thread (`ui::background`: lower priority,
//! a thread pool of their own) while the panel shows the
//! last finished result, marked stale until the new one arrives. The frame
//! rate never waits for them, and the (otherwise idle) window is woken by
//! egui's repaint request when a result is ready.

use std::sync::mpsc::{Receiver, channel};

/// The last result for a key and the job under way, if any.
pub struct Slot<K, V> {
    done: Option<(K, V)>,
    pending: Option<(K, Receiver<V>)>,
}

impl<K, V> Default for Slot<K, V> {
    fn default() -> Self {
        Slot {
            done: None,
            pending: None,
        }
    }
}

impl<K: PartialEq + Clone + Send + 'static, V: Send + 'static> Slot<K, V> {
    /// Collects a finished job; starts `compute(key)` on a thread unless
    /// `key`'s result is there or under way. One job at a time: while an
    /// older one runs, the newest key waits for it (a slider drag does not
    /// pile up threads).
    pub fn request(
        &mut self,
        key: &K,
        ctx: &egui::Context,
        compute: impl FnOnce(K) -> V + Send + 'static,
    ) {
        if let Some((_, rx)) = &self.pending
            && let Ok(value) = rx.try_recv()
        {
            let (k, _) = self.pending.take().expect("checked");
            self.done = Some((k, value));
        }
        let have = self.done.as_ref().is_some_and(|(k, _)| k == key);
        if have || self.pending.is_some() {
            return;
        }
        let (tx, rx) = channel();
        let ctx = ctx.clone();
        let k = key.clone();
        // Off the UI thread and below its priority (`ui::background`).
        crate::ui::background::spawn(move || {
            let _ = tx.send(compute(k));
            ctx.request_repaint();
        });
        self.pending = Some((key.clone(), rx));
    }

    /// The last finished result and whether it is for `key` (else it is
    /// stale: shown until the new one arrives).
    pub fn latest(&self, key: &K) -> Option<(&V, bool)> {
        self.done.as_ref().map(|(k, v)| (v, k == key))
    }

    /// Whether a job is under way (or finished and not yet collected).
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};

    #[test]
    fn a_slot_computes_once_per_key_and_keeps_the_last_result() {
        let ctx = egui::Context::default();
        let mut slot: Slot<u32, u32> = Slot::default();
        slot.request(&3, &ctx, |k| k * 10);
        assert!(slot.busy());
        let start = Instant::now();
        while slot.latest(&3).is_none() {
            assert!(start.elapsed() < Duration::from_secs(10));
            std::thread::sleep(Duration::from_millis(1));
            slot.request(&3, &ctx, |_| unreachable!("computed once"));
        }
        assert_eq!(slot.latest(&3), Some((&30, true)));
        assert!(!slot.busy());
        // Another key: the old result stays, marked stale, until the new one.
        slot.request(&4, &ctx, |k| k * 10);
        assert_eq!(slot.latest(&4), Some((&30, false)));
    }
}
