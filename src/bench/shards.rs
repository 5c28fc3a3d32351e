//! `gonio bench --shard I/N` and `gonio bench --merge`: the
//! configurations measured in pieces (configuration k by shard
//! `k mod N + 1`, as every gonio shard deals its items), each piece on
//! whatever machine runs it, and joined into `results.csv` and a report.
//!
//! A shard measures its configurations as the whole run does (round
//! robin, warm-up, two passes, error against the truth image, which each
//! shard computes) and the unlit floor of its own machine; it leaves out
//! the target ratios and the scale sweeps, which compare measurements
//! that must come from one machine and one run. Times of different
//! machines are not comparable, their ratios to the same machine's floor
//! are: the merge finds the Pareto front on `time_over_unlit`.
//!
//! A shard file is `DIR/shards/bench-shard-I-of-N.csv`: a first line
//! `# gonio bench shard I/N key=… configs=M unlit_ms=… adapter=…`, then
//! `results.csv`'s header and rows. The key (a SHA-256 of the base scene,
//! the budget and the configuration list) keeps shards of different runs
//! apart; a shard whose file exists with the same key is skipped.

use super::Row;
use super::pareto::{self, Point};
use super::report::{RESULTS_HEADER, csv_field, parse_csv_line};
use crate::cluster::Shard;
use crate::gpu::timing::Clock;
use crate::output::AtomicFile;
use crate::{Error, Result};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The shard file of shard `shard` in `dir`.
pub fn shard_path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join("shards").join(format!(
        "bench-shard-{}-of-{}.csv",
        shard.index, shard.count
    ))
}

/// A SHA-256 (hex) of what decides the set of measurements: `what`'s
/// `Debug` form (the base scene, the budget, the configurations).
pub fn key(what: &dyn std::fmt::Debug) -> String {
    struct Hasher(Sha256);
    impl std::fmt::Write for Hasher {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            self.0.update(s.as_bytes());
            Ok(())
        }
    }
    let mut h = Hasher(Sha256::new());
    let _ = write!(h, "gonio {} bench\n{what:?}", env!("CARGO_PKG_VERSION"));
    h.0.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A claimed shard file.
pub struct ShardFile {
    pub shard: Shard,
    file: AtomicFile,
}

/// What a shard file's first line says.
#[derive(Clone, Debug, PartialEq)]
struct Meta {
    shard: Shard,
    key: String,
    configs: usize,
    unlit_ms: f64,
}

fn meta_line(m: &Meta, adapter: &str) -> String {
    format!(
        "# gonio bench shard {} key={} configs={} unlit_ms={:.6} adapter={}",
        m.shard,
        m.key,
        m.configs,
        m.unlit_ms,
        adapter.replace('\n', " ")
    )
}

fn parse_meta(line: &str, path: &Path) -> Result<Meta> {
    let bad = || {
        Error::input(
            path,
            "not a shard of `gonio bench --shard`: the first line is not `# gonio bench shard I/N key=… configs=… unlit_ms=…`",
        )
    };
    let rest = line.strip_prefix("# gonio bench shard ").ok_or_else(bad)?;
    let mut words = rest.split(' ');
    let (shard, _) = Shard::parse(words.next().unwrap_or(""), |_| None).map_err(|_| bad())?;
    let mut field = |name: &str| -> Result<String> {
        words
            .next()
            .and_then(|w| w.strip_prefix(name))
            .and_then(|w| w.strip_prefix('='))
            .map(str::to_string)
            .ok_or_else(bad)
    };
    let key = field("key")?;
    let configs = field("configs")?.parse().map_err(|_| bad())?;
    let unlit_ms = field("unlit_ms")?.parse().map_err(|_| bad())?;
    Ok(Meta {
        shard,
        key,
        configs,
        unlit_ms,
    })
}

impl ShardFile {
    /// Parses `--shard TEXT` and claims the shard's file in `dir`.
    pub fn claim(dir: &Path, text: &str) -> Result<Self> {
        let (shard, source) = Shard::from_arg(text)?;
        if let Some(source) = source {
            eprintln!("gonio bench: --shard {text}: shard {shard} ({source})");
        }
        let path = shard_path(dir, shard);
        let folder = path.parent().expect("has a parent");
        std::fs::create_dir_all(folder)
            .map_err(|e| Error::output(folder, format!("cannot create the folder: {e}")))?;
        Ok(ShardFile {
            shard,
            file: AtomicFile::create(&path)?,
        })
    }

    /// Whether the file already holds this shard of the run `key`.
    pub fn is_done(&self, key: &str) -> bool {
        let path = self.file.path();
        std::fs::read_to_string(path)
            .ok()
            .and_then(|t| parse_meta(t.lines().next()?, path).ok())
            .is_some_and(|m| m.shard == self.shard && m.key == key)
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Writes the shard's rows (overrides with the base's first).
    #[allow(clippy::too_many_arguments)]
    pub fn write(
        self,
        key: &str,
        configs: usize,
        scene: &str,
        base_overrides: &[String],
        rows: &[Row],
        unlit_ms: f64,
        adapter: &str,
        clock: Clock,
    ) -> Result<()> {
        let meta = Meta {
            shard: self.shard,
            key: key.to_string(),
            configs,
            unlit_ms,
        };
        let mut out = meta_line(&meta, adapter);
        out.push('\n');
        out.push_str(&RESULTS_HEADER.join(","));
        out.push('\n');
        let clock = match clock {
            Clock::GpuTimestamp => "gpu-timestamp",
            Clock::Wall => "wall",
        };
        for row in rows {
            let overrides: Vec<String> = base_overrides
                .iter()
                .chain(&row.config.overrides)
                .cloned()
                .collect();
            let _ = writeln!(
                out,
                "{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6e},{:.6e},false,{clock}",
                csv_field(scene),
                csv_field(&row.config.knob),
                csv_field(&row.config.value),
                csv_field(&overrides.join(";")),
                row.time.median,
                row.time.q1,
                row.time.q3,
                row.time.median / unlit_ms,
                row.error,
                row.max_rel,
            );
        }
        self.file.commit(out.as_bytes())
    }
}

/// `gonio bench --merge -o DIR`: the shards in `DIR/shards` joined into
/// `DIR/results.csv` (what `gonio render --max-error` reads) and
/// `DIR/report.md`.
pub fn merge(dir: &Path) -> Result<()> {
    let folder = dir.join("shards");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .map_err(|e| Error::input(&folder, format!("cannot read the shards' folder: {e}")))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("bench-shard-") && n.ends_with(".csv"))
        })
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(Error::input(
            &folder,
            "no bench-shard-*.csv: run `gonio bench --shard I/N -o DIR` first",
        ));
    }
    let results = AtomicFile::create(&dir.join("results.csv"))?;
    let report = AtomicFile::create(&dir.join("report.md"))?;
    // (meta, data lines, adapter)
    let mut shards: Vec<(PathBuf, Meta, Vec<Vec<String>>, String)> = Vec::new();
    for path in &paths {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::input(path, format!("cannot read it: {e}")))?;
        let mut lines = text.lines();
        let first = lines.next().unwrap_or_default();
        let meta = parse_meta(first, path)?;
        let adapter = first
            .split_once(" adapter=")
            .map(|(_, a)| a.to_string())
            .unwrap_or_default();
        if lines.next().map(parse_csv_line) != Some(RESULTS_HEADER.map(String::from).to_vec()) {
            return Err(Error::input(
                path,
                format!("the second line is not `{}`", RESULTS_HEADER.join(",")),
            ));
        }
        let rows: Vec<Vec<String>> = lines
            .filter(|l| !l.trim().is_empty())
            .map(parse_csv_line)
            .collect();
        if let Some(r) = rows.iter().find(|r| r.len() != RESULTS_HEADER.len()) {
            return Err(Error::input(
                path,
                format!(
                    "a row has {} fields, expected {}",
                    r.len(),
                    RESULTS_HEADER.len()
                ),
            ));
        }
        shards.push((path.clone(), meta, rows, adapter));
    }
    let first = &shards[0].1;
    if let Some((path, m, ..)) = shards
        .iter()
        .find(|(_, m, ..)| (&m.key, m.shard.count) != (&first.key, first.shard.count))
    {
        return Err(Error::input(
            path,
            format!(
                "belongs to another bench run (shard {}, key {}…) than {} (shard {}, key {}…): merge the shards of one run (remove the other's files from {})",
                m.shard,
                &m.key[..12],
                shards[0].0.display(),
                first.shard,
                &first.key[..12],
                folder.display()
            ),
        ));
    }
    let count = first.shard.count;
    let configs = first.configs;
    let mut by_shard: Vec<Option<usize>> = vec![None; count];
    for (k, (path, m, rows, _)) in shards.iter().enumerate() {
        if let Some(other) = by_shard[m.shard.index - 1].replace(k) {
            return Err(Error::input(
                path,
                format!(
                    "holds shard {} as {} does",
                    m.shard,
                    shards[other].0.display()
                ),
            ));
        }
        let want = m.shard.items(configs).count();
        if rows.len() != want {
            return Err(Error::input(
                path,
                format!(
                    "holds {} rows; shard {} of {configs} configurations has {want}",
                    rows.len(),
                    m.shard
                ),
            ));
        }
    }
    let missing: Vec<String> = (1..=count)
        .filter(|i| by_shard[i - 1].is_none())
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(Error::input(
            &folder,
            format!(
                "the set is incomplete: shard(s) {} missing; run `gonio bench --shard I/{count}` for them and merge again",
                missing.join(", ")
            ),
        ));
    }
    // Configuration k is row k / N of shard k mod N + 1.
    let mut rows: Vec<Vec<String>> = (0..configs)
        .map(|k| shards[by_shard[k % count].expect("complete")].2[k / count].clone())
        .collect();
    let column = |name: &str| {
        RESULTS_HEADER
            .iter()
            .position(|h| *h == name)
            .expect("a column")
    };
    let (relative, error, front) = (
        column("time_over_unlit"),
        column("rel_rms_error"),
        column("on_front"),
    );
    let points: Vec<Point> = rows
        .iter()
        .map(|r| Point {
            time: r[relative].parse().unwrap_or(f64::INFINITY),
            error: r[error].parse().unwrap_or(f64::INFINITY),
        })
        .collect();
    for i in pareto::front(&points) {
        rows[i][front] = "true".into();
    }
    let mut csv = RESULTS_HEADER.join(",");
    csv.push('\n');
    for r in &rows {
        let fields: Vec<String> = r.iter().map(|f| csv_field(f)).collect();
        csv.push_str(&fields.join(","));
        csv.push('\n');
    }
    let mut md = String::from("# gonio bench: the speed/accuracy trade, measured in shards\n\n");
    let _ = writeln!(
        md,
        "Merged by `gonio bench --merge` from {count} shards of `gonio bench --shard I/{count}` ({configs} configurations). Each shard measured its configurations against the truth image and the unlit floor of its own machine; `× unlit` (the time over that floor) is what compares across shards, and the Pareto front (★) is found on it. The target ratios and the scale sweeps are measured by an unsharded `gonio bench` only.\n"
    );
    let _ = writeln!(
        md,
        "| shard | machine (adapter) | unlit floor (ms) |\n| --- | --- | --- |"
    );
    for (_, m, _, adapter) in by_shard.iter().map(|k| &shards[k.expect("complete")]) {
        let _ = writeln!(md, "| {} | {adapter} | {:.3} |", m.shard, m.unlit_ms);
    }
    let _ = writeln!(
        md,
        "\n| configuration | × unlit | time (ms) [q1–q3] | rel. RMS error | max rel. error | front |\n| --- | --- | --- | --- | --- | --- |"
    );
    let (knob, value) = (column("knob"), column("value"));
    let (t, q1, q3, max_rel) = (
        column("time_ms"),
        column("time_q1_ms"),
        column("time_q3_ms"),
        column("max_rel_error"),
    );
    for r in &rows {
        let label = if r[knob] == "base" {
            "base".to_string()
        } else {
            format!("{}={}", r[knob], r[value])
        };
        let _ = writeln!(
            md,
            "| `{label}` | {} | {} [{}–{}] | {} | {} | {} |",
            r[relative],
            r[t],
            r[q1],
            r[q3],
            r[error],
            r[max_rel],
            if r[front] == "true" { "★" } else { "" }
        );
    }
    results.commit(csv.as_bytes())?;
    report.commit(md.as_bytes())?;
    eprintln!(
        "gonio bench --merge: wrote {} and {} ({configs} configurations from {count} shards)",
        dir.join("results.csv").display(),
        dir.join("report.md").display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_meta_line_round_trips() {
        let m = Meta {
            shard: Shard { index: 2, count: 3 },
            key: "ab".repeat(32),
            configs: 17,
            unlit_ms: 1.25,
        };
        let line = meta_line(&m, "llvmpipe (LLVM 15)");
        assert_eq!(parse_meta(&line, Path::new("x")).unwrap(), m);
        assert!(parse_meta("scene,knob", Path::new("x")).is_err());
    }
}
