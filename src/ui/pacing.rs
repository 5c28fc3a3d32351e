//! When the viewer draws: only when something changed. An idle window
//! costs no CPU, and the panel's background integrals (albedo, gloss:
//! [`super::plots`]) get the cores instead of a render loop.
//!
//! A frame is drawn on: window input (egui's `EventResponse::repaint`, or
//! any input the 3D view acts on), egui's own repaint requests (its
//! `repaint_delay` after a frame, e.g. a tooltip's delay, and requests
//! from other threads through its repaint callback, which is how a
//! finished background plot wakes the window), a changed scene file, a
//! skipped frame (the surface was not ready), and animation. Between them
//! winit waits (`ControlFlow::WaitUntil` the next deadline: egui's, the
//! next scene-file check).
//!
//! Scripted runs (`--frames N`) and `--spin` draw continuously, as they
//! did: they measure frame times, and a script counts frames.

use std::time::{Duration, Instant};

/// A wake-up sent to the window loop from any thread.
#[derive(Debug, Clone, Copy)]
pub enum Wake {
    /// egui asked for a frame after `delay`, during or after pass `pass`
    /// (its `cumulative_pass_nr`).
    Repaint { delay: Duration, pass: u64 },
}

/// The viewer's frame schedule and its frame counter.
#[derive(Debug)]
pub struct Pacing {
    continuous: bool,
    /// The next frame egui (or a worker, or the loop) asked for.
    repaint_at: Option<Instant>,
    /// Frames drawn (presented) so far.
    pub frames: u64,
    last_frame: Instant,
    started: Instant,
    /// `--exit-when-idle`: end the run after this long without a frame.
    idle_exit: Option<Duration>,
}

/// `--exit-when-idle` gives up after this long without an idle spell.
pub const IDLE_EXIT_CAP: Duration = Duration::from_secs(60);

impl Pacing {
    pub fn new(continuous: bool, idle_exit: Option<Duration>) -> Pacing {
        let now = Instant::now();
        Pacing {
            continuous,
            repaint_at: Some(now),
            frames: 0,
            last_frame: now,
            started: now,
            idle_exit,
        }
    }

    /// Whether every frame is followed by the next (scripted, animated).
    pub fn continuous(&self) -> bool {
        self.continuous
    }

    /// A frame is wanted `delay` from `now` (`Duration::MAX`: never).
    pub fn request(&mut self, now: Instant, delay: Duration) {
        if let Some(at) = now.checked_add(delay) {
            self.repaint_at = Some(self.repaint_at.map_or(at, |t| t.min(at)));
        }
    }

    /// A frame was drawn at `now`: the requests it answered are done.
    pub fn drawn(&mut self, now: Instant) {
        self.frames += 1;
        self.last_frame = now;
        self.repaint_at = None;
    }

    /// Whether a frame is due at `now`.
    pub fn due(&self, now: Instant) -> bool {
        self.continuous || self.repaint_at.is_some_and(|t| t <= now)
    }

    /// When the loop must wake next without an event: the next requested
    /// frame, the next scene-file check `check_at`, or the idle exit.
    pub fn wake_at(&self, check_at: Instant) -> Instant {
        let mut at = check_at;
        if let Some(t) = self.repaint_at {
            at = at.min(t);
        }
        if let Some(idle) = self.idle_exit {
            at = at.min(self.last_frame + idle);
        }
        at
    }

    /// `--exit-when-idle`: `Some(Ok(report))` once the idle spell was
    /// reached with no background work under way (`busy`: a result not
    /// yet shown counts, so a worker that fails to wake the window keeps
    /// the run going), `Some(Err(..))` when none came within
    /// [`IDLE_EXIT_CAP`].
    pub fn idle_exit(&self, now: Instant, busy: bool) -> Option<Result<String, String>> {
        let idle = self.idle_exit?;
        let quiet = now.saturating_duration_since(self.last_frame);
        if quiet >= idle && !busy {
            return Some(Ok(format!(
                "idle: {} frames drawn in {:.2} s, then none for {:.2} s",
                self.frames,
                (self.last_frame - self.started).as_secs_f64(),
                quiet.as_secs_f64()
            )));
        }
        if now - self.started >= IDLE_EXIT_CAP {
            return Some(Err(format!(
                "the viewer never stayed {:.1} s without drawing, its background plots done, in {} s ({} frames drawn)",
                idle.as_secs_f64(),
                IDLE_EXIT_CAP.as_secs(),
                self.frames
            )));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_idle_schedule_waits_for_the_next_check_only() {
        let mut p = Pacing::new(false, None);
        let t0 = Instant::now();
        assert!(p.due(t0), "the first frame is due at once");
        p.drawn(t0);
        assert!(!p.due(t0 + Duration::from_secs(5)));
        let check = t0 + Duration::from_millis(500);
        assert_eq!(p.wake_at(check), check);
        // egui's "no repaint needed" is Duration::MAX: still idle.
        p.request(t0, Duration::MAX);
        assert!(!p.due(t0 + Duration::from_secs(3600)));
    }

    #[test]
    fn requests_keep_the_earliest_deadline() {
        let mut p = Pacing::new(false, None);
        let t0 = Instant::now();
        p.drawn(t0);
        p.request(t0, Duration::from_millis(300));
        p.request(t0, Duration::from_millis(100));
        p.request(t0, Duration::from_millis(200));
        assert!(!p.due(t0 + Duration::from_millis(99)));
        assert!(p.due(t0 + Duration::from_millis(100)));
        let later = t0 + Duration::from_secs(1);
        assert_eq!(p.wake_at(later), t0 + Duration::from_millis(100));
    }

    #[test]
    fn a_continuous_schedule_is_always_due() {
        let mut p = Pacing::new(true, None);
        let t0 = Instant::now();
        p.drawn(t0);
        assert!(p.due(t0));
    }

    #[test]
    fn the_idle_exit_reports_the_quiet_spell() {
        let mut p = Pacing::new(false, Some(Duration::from_secs(1)));
        let t0 = Instant::now();
        p.drawn(t0);
        assert!(
            p.idle_exit(t0 + Duration::from_millis(999), false)
                .is_none()
        );
        assert!(p.idle_exit(t0 + Duration::from_secs(2), true).is_none());
        let report = p
            .idle_exit(t0 + Duration::from_secs(1), false)
            .unwrap()
            .unwrap();
        assert!(report.contains("1 frames drawn"), "{report}");
        assert_eq!(
            p.wake_at(t0 + Duration::from_secs(5)),
            t0 + Duration::from_secs(1)
        );
    }
}
