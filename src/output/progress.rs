//! A long job's progress (`gonio bench`, `gonio fit --all`): a bar with an
//! ETA on a terminal, plain lines without one (CI logs, `2>log`), so a
//! long run is never silent.
//!
//! indicatif draws nothing when stderr is not a terminal (a
//! 111 s run once printed nothing in CI). Without a terminal each line says
//! what is measured, step n of m, the time so far and the estimated time
//! left, when the step's subject changes or at most every
//! [`PLAIN_EVERY`], so a log gets a few dozen lines, not one per frame.
//! The estimate assumes the remaining steps take as long as the ones so
//! far did on average; steps differ (a ratio step renders more than one
//! configuration in one round), so it is a rough guide.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// Shortest interval between two plain lines about the same subject.
pub const PLAIN_EVERY: Duration = Duration::from_secs(5);

/// Progress over `len` steps, drawn as fits stderr.
pub enum Progress {
    Bar(ProgressBar),
    Plain(PlainProgress),
}

impl Progress {
    /// Progress of the job named `job` (the plain lines' prefix).
    pub fn new(job: &'static str, len: u64) -> Progress {
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} ETA {eta} {msg}",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            Progress::Bar(bar)
        } else {
            Progress::Plain(PlainProgress::new(job, len, Box::new(std::io::stderr())))
        }
    }

    pub fn set_message(&mut self, message: impl Into<String>) {
        match self {
            Progress::Bar(b) => b.set_message(message.into()),
            Progress::Plain(p) => p.set_message(message.into()),
        }
    }

    pub fn inc(&mut self, n: u64) {
        match self {
            Progress::Bar(b) => b.inc(n),
            Progress::Plain(p) => p.inc(n),
        }
    }

    pub fn finish(&mut self) {
        match self {
            Progress::Bar(b) => b.finish_and_clear(),
            Progress::Plain(p) => p.finish(),
        }
    }
}

/// Plain progress lines to a writer.
pub struct PlainProgress {
    job: &'static str,
    len: u64,
    pos: u64,
    message: String,
    start: Instant,
    last_line: Option<(Instant, String)>,
    out: Box<dyn Write + Send>,
}

impl PlainProgress {
    pub fn new(job: &'static str, len: u64, out: Box<dyn Write + Send>) -> PlainProgress {
        PlainProgress {
            job,
            len,
            pos: 0,
            message: String::new(),
            start: Instant::now(),
            last_line: None,
            out,
        }
    }

    /// The subject of a message: the text before its first `:` ("round
    /// 3/12: ..." is about the round).
    fn subject(message: &str) -> &str {
        message.split(':').next().unwrap_or(message)
    }

    pub fn set_message(&mut self, message: String) {
        self.message = message;
        self.maybe_print(Instant::now());
    }

    pub fn inc(&mut self, n: u64) {
        self.pos = (self.pos + n).min(self.len);
        self.maybe_print(Instant::now());
    }

    fn maybe_print(&mut self, now: Instant) {
        let due = match &self.last_line {
            None => true,
            Some((at, subject)) => {
                subject != Self::subject(&self.message) || now - *at >= PLAIN_EVERY
            }
        };
        if due {
            let line = self.line(now - self.start);
            let _ = writeln!(self.out, "{line}");
            self.last_line = Some((now, Self::subject(&self.message).to_string()));
        }
    }

    /// `JOB: step n/m, elapsed, ETA: what`.
    pub fn line(&self, elapsed: Duration) -> String {
        let eta = if self.pos == 0 {
            "ETA unknown".to_string()
        } else {
            let left = elapsed.as_secs_f64() / self.pos as f64 * (self.len - self.pos) as f64;
            format!("ETA {}", clock(left))
        };
        format!(
            "{}: step {}/{} ({:.0} %), elapsed {}, {eta}: {}",
            self.job,
            self.pos,
            self.len,
            100.0 * self.pos as f64 / self.len.max(1) as f64,
            clock(elapsed.as_secs_f64()),
            self.message
        )
    }

    pub fn finish(&mut self) {
        let _ = writeln!(
            self.out,
            "{}: done, {} steps in {}",
            self.job,
            self.pos,
            clock(self.start.elapsed().as_secs_f64())
        );
    }
}

/// Seconds as `1 min 05 s` or `42 s`.
fn clock(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 60 {
        format!("{} min {:02} s", s / 60, s % 60)
    } else {
        format!("{s} s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::{Arc, Mutex};

    #[derive(Clone, Default)]
    struct Sink(Arc<Mutex<Vec<u8>>>);
    impl Write for Sink {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn plain_lines_name_the_step_the_time_and_the_eta() {
        let sink = Sink::default();
        let mut p = PlainProgress::new("bench", 10, Box::new(sink.clone()));
        p.set_message("truth image".into());
        p.pos = 4;
        let line = p.line(Duration::from_secs(20));
        assert_eq!(
            line,
            "bench: step 4/10 (40 %), elapsed 20 s, ETA 30 s: truth image"
        );
        p.pos = 1;
        assert!(p.line(Duration::from_secs(100)).contains("ETA 15 min 00 s"));
    }

    #[test]
    fn plain_lines_come_per_subject_not_per_step() {
        let sink = Sink::default();
        let mut p = PlainProgress::new("bench", 100, Box::new(sink.clone()));
        for round in 1..=3 {
            for config in ["a", "b", "c"] {
                p.set_message(format!("round {round}/3: {config}"));
                p.inc(1);
            }
        }
        p.set_message("unlit floor".into());
        p.finish();
        let text = String::from_utf8(sink.0.lock().unwrap().clone()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        // One line per round (the subject changes), one for the floor,
        // one at the end: not one per configuration.
        assert_eq!(lines.len(), 5, "{text}");
        assert!(lines[1].starts_with("bench: step 3/100"), "{text}");
        assert!(lines[3].ends_with(": unlit floor"), "{text}");
        assert!(lines[4].starts_with("bench: done, 9 steps"), "{text}");
    }
}
