//! Time per pass, for `--timings` and the speed/accuracy work.

use std::time::{Duration, Instant};

/// How a duration was measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// GPU timestamp queries around the pass.
    GpuTimestamp,
    /// Wall time on the CPU (around submit-and-wait for GPU work).
    Wall,
}

/// Named durations in the order they happened.
#[derive(Clone, Debug, Default)]
pub struct Timings {
    pub entries: Vec<(String, Duration, Clock)>,
}

impl Timings {
    /// Records `duration` under `name`.
    pub fn push(&mut self, name: impl Into<String>, duration: Duration, clock: Clock) {
        self.entries.push((name.into(), duration, clock));
    }

    /// Runs `f`, recording its wall time under `name`.
    pub fn wall<T>(&mut self, name: &str, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let value = f();
        self.push(name, start.elapsed(), Clock::Wall);
        value
    }

    /// Appends another set of timings.
    pub fn extend(&mut self, other: Timings) {
        self.entries.extend(other.entries);
    }

    /// A small table, one line per entry.
    pub fn report(&self) -> String {
        let width = self
            .entries
            .iter()
            .map(|(n, ..)| n.len())
            .max()
            .unwrap_or(0);
        self.entries
            .iter()
            .map(|(name, d, clock)| {
                let how = match clock {
                    Clock::GpuTimestamp => "GPU timestamps",
                    Clock::Wall => "wall",
                };
                format!(
                    "{name:<width$}  {:>10.3} ms  ({how})",
                    d.as_secs_f64() * 1e3
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    }
}
