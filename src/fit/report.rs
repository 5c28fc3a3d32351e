//! `gonio fit --all`'s files: one CSV (errors) and one TOML (the fitted
//! materials) per shard, and the merge of all shards into the ranking
//! (`ranking.csv`, `ranking.md`) and `fits.toml`.
//!
//! A shard is self-contained (its rows name material and model), so shards
//! can run anywhere (a job array) and be merged in any order; the merge
//! checks that every (material, model) pair is there exactly once.

use crate::base::input::read_regular_text;
use crate::output::{AtomicFile, commit_all};
use crate::{Error, Result};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One fit's row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub material: String,
    /// The model's label (`ct-ggx-conductor`).
    pub model: String,
    pub metric: String,
    pub error: f64,
    pub relative: f64,
    pub evaluations: usize,
    /// Time of this fit on one core.
    pub seconds: f64,
}

/// The shard file names of shard `i` of `n` (1-based).
pub fn shard_paths(dir: &Path, i: usize, n: usize) -> (PathBuf, PathBuf) {
    let shards = dir.join("shards");
    (
        shards.join(format!("shard-{i}-of-{n}.csv")),
        shards.join(format!("shard-{i}-of-{n}.toml")),
    )
}

const HEADER: &str = "material,model,metric,error,relative,evaluations,seconds";

/// The CSV text of `rows`.
pub fn csv(rows: &[Row]) -> String {
    let mut s = format!("{HEADER}\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{:.6e},{:.6e},{},{:.3}",
            r.material, r.model, r.metric, r.error, r.relative, r.evaluations, r.seconds
        );
    }
    s
}

/// Rows from a shard CSV (`path` names it in errors).
pub fn parse_csv(path: &Path, text: &str) -> Result<Vec<Row>> {
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        return Err(Error::input(
            path,
            format!("not a gonio fit shard: the first line is not `{HEADER}`"),
        ));
    }
    lines
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, line)| {
            let bad = |what: &str| Error::input(path, format!("line {}: {what}: `{line}`", i + 2));
            let f: Vec<&str> = line.split(',').collect();
            if f.len() != 7 {
                return Err(bad("expected 7 fields"));
            }
            let num = |s: &str| s.parse::<f64>().map_err(|_| bad("not a number"));
            // An error is a sum of squares or its root: finite and ≥ 0.
            let error = |s: &str| {
                let v = num(s)?;
                if v.is_finite() && v >= 0.0 {
                    Ok(v)
                } else {
                    Err(bad(&format!("error {v} is not a finite number ≥ 0")))
                }
            };
            Ok(Row {
                material: f[0].into(),
                model: f[1].into(),
                metric: f[2].into(),
                error: error(f[3])?,
                relative: error(f[4])?,
                evaluations: f[5].parse().map_err(|_| bad("not a count"))?,
                seconds: num(f[6])?,
            })
        })
        .collect()
}

/// Writes `text` to `path` whole or not at all ([`crate::output::atomic`]).
pub fn write_atomic(path: &Path, text: &str) -> Result<()> {
    write_set(&[(path, text)])
}

/// Writes every `(path, text)` so that the files appear together or not at
/// all ([`crate::output::commit_all`]).
pub fn write_set(files: &[(&Path, &str)]) -> Result<()> {
    let claimed = files
        .iter()
        .map(|(path, text)| Ok((AtomicFile::create(path)?, text.as_bytes())))
        .collect::<Result<Vec<_>>>()?;
    commit_all(claimed)
}

/// Largest shard file `--merge` reads (a shard of all 100 materials and
/// a dozen models is about 100 kB).
const MAX_SHARD_BYTES: u64 = 64 << 20;

/// `shard-I-of-N.csv` as (I, N).
fn shard_number(path: &Path) -> Option<(usize, usize)> {
    let name = path.file_name()?.to_str()?;
    let (i, n) = name
        .strip_prefix("shard-")?
        .strip_suffix(".csv")?
        .split_once("-of-")?;
    let (i, n) = (i.parse().ok()?, n.parse().ok()?);
    (1..=n).contains(&i).then_some((i, n))
}

/// Reads a shard file (a regular file, bounded).
fn read_shard_file(path: &Path) -> Result<String> {
    read_regular_text(path, MAX_SHARD_BYTES).map_err(|e| Error::input(path, e.to_string()))
}

/// Every row of every shard in `dir/shards`, and the fitted tables. The
/// set must be whole: shards 1 to N of one N, each with its `.toml`, every
/// row's errors finite and ≥ 0, every `.toml` valid TOML.
fn read_shards(dir: &Path) -> Result<(Vec<Row>, String)> {
    let shards = dir.join("shards");
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&shards)
        .map_err(|e| Error::input(&shards, format!("cannot read the shards' folder: {e}")))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    entries.sort();
    if entries.is_empty() {
        return Err(Error::input(
            &shards,
            "no shard-*.csv: run `gonio fit --all [--shard I/N]` first",
        ));
    }
    let mut numbered = Vec::new();
    for p in &entries {
        let Some(number) = shard_number(p) else {
            return Err(Error::input(
                p,
                "is not named like a shard (shard-I-of-N.csv, 1 ≤ I ≤ N): move it out of the shards' folder",
            ));
        };
        numbered.push((number, p));
    }
    let of = numbered[0].0.1;
    if let Some(((_, n), p)) = numbered.iter().find(|((_, n), _)| *n != of) {
        return Err(Error::input(
            p,
            format!(
                "is a shard of {n}, where {} is a shard of {of}: the folder mixes runs; merge the shards of one run",
                numbered[0].1.display()
            ),
        ));
    }
    for i in 1..=of {
        if !numbered.iter().any(|((k, _), _)| *k == i) {
            let (missing, _) = shard_paths(dir, i, of);
            return Err(Error::input(
                missing,
                format!(
                    "shard {i} of {of} is missing: run `gonio fit --all --shard {i}/{of}` (with the run's other flags) before merging"
                ),
            ));
        }
    }
    let (mut rows, mut fits) = (Vec::new(), String::new());
    for (_, p) in numbered {
        let text = read_shard_file(p)?;
        rows.extend(parse_csv(p, &text)?);
        let toml_path = p.with_extension("toml");
        if !toml_path.exists() {
            return Err(Error::input(
                &toml_path,
                format!(
                    "is missing, while its shard {} is there: the shard was not written whole; run it again",
                    p.display()
                ),
            ));
        }
        let t = read_shard_file(&toml_path)?;
        if let Err(e) = t.parse::<toml::Table>() {
            let line = e
                .span()
                .map(|s| t[..s.start.min(t.len())].matches('\n').count() + 1)
                .unwrap_or(1);
            return Err(Error::input(
                &toml_path,
                format!("line {line}: not valid TOML: {}", e.message()),
            ));
        }
        fits.push_str(&t);
    }
    if rows.is_empty() {
        return Err(Error::input(
            &shards,
            "the shards hold no fits: nothing to rank",
        ));
    }
    Ok((rows, fits))
}

/// The ranks of `errors` (1 = smallest; ties share their mean rank).
pub fn ranks(errors: &[f64]) -> Vec<f64> {
    errors
        .iter()
        .map(|&e| {
            let below = errors.iter().filter(|&&o| o < e).count() as f64;
            let equal = errors.iter().filter(|&&o| o == e).count() as f64;
            below + (equal + 1.0) / 2.0
        })
        .collect()
}

/// Merges the shards in `dir` into `ranking.csv`, `ranking.md` and
/// `fits.toml`; `wall` is the whole run's time when one process ran it.
pub fn merge(dir: &Path, wall: Option<(f64, usize)>) -> Result<String> {
    let (rows, fits) = read_shards(dir)?;
    let mut by_material: BTreeMap<&str, Vec<&Row>> = BTreeMap::new();
    let mut models: Vec<&str> = Vec::new();
    for r in &rows {
        by_material.entry(&r.material).or_default().push(r);
        if !models.contains(&r.model.as_str()) {
            models.push(&r.model);
        }
    }
    let metric = rows.first().map(|r| r.metric.clone()).unwrap_or_default();
    if rows.iter().any(|r| r.metric != metric) {
        return Err(Error::input(
            dir,
            "the shards mix metrics: merge the shards of one run",
        ));
    }
    for (m, rs) in &by_material {
        let mut names: Vec<&str> = rs.iter().map(|r| r.model.as_str()).collect();
        names.sort();
        let n = names.len();
        names.dedup();
        if n != models.len() || names.len() != models.len() {
            return Err(Error::input(
                dir,
                format!(
                    "material `{m}` has {n} fits of {} models (a shard missing or run twice?)",
                    models.len()
                ),
            ));
        }
    }
    // Ranks per material, in the models' order.
    let mut csv_out = String::from("material,model,metric,error,relative,rank\n");
    let mut rank_sum = vec![0.0; models.len()];
    let mut wins = vec![0usize; models.len()];
    let mut relative: Vec<Vec<f64>> = vec![Vec::new(); models.len()];
    let mut table = String::new();
    for (m, rs) in &by_material {
        let errs: Vec<f64> = models
            .iter()
            .map(|name| rs.iter().find(|r| r.model == *name).expect("checked").error)
            .collect();
        let rk = ranks(&errs);
        let _ = write!(table, "| {m} |");
        for (k, name) in models.iter().enumerate() {
            let r = rs.iter().find(|r| r.model == *name).expect("checked");
            let _ = writeln!(
                csv_out,
                "{m},{name},{metric},{:.6e},{:.6e},{}",
                r.error, r.relative, rk[k]
            );
            rank_sum[k] += rk[k];
            if rk[k] < 1.5 {
                wins[k] += 1;
            }
            relative[k].push(r.relative);
            let cell = format!("{:.3}", r.relative);
            let _ = write!(
                table,
                " {} |",
                if rk[k] < 1.5 {
                    format!("**{cell}**")
                } else {
                    cell
                }
            );
        }
        table.push('\n');
    }
    let n_mat = by_material.len() as f64;
    let mut order: Vec<usize> = (0..models.len()).collect();
    order.sort_by(|&a, &b| rank_sum[a].total_cmp(&rank_sum[b]));
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Model ranking on the MERL materials (`gonio fit --all`)\n"
    );
    let _ = writeln!(
        md,
        "Generated by `gonio fit --all --metric {metric}` (merge of the shards in `shards/`); \
see docs/measured.md for the method (samples, metric, optimizer, bounds) and how the ranking \
compares with Ngan et al. 2005. {} materials × {} models.\n",
        by_material.len(),
        models.len()
    );
    let total: f64 = rows.iter().map(|r| r.seconds).sum();
    let _ = write!(
        md,
        "Run time: the fits took {total:.0} s of one core in total"
    );
    if let Some((w, threads)) = wall {
        let _ = write!(md, "; the run took {w:.0} s wall time on {threads} threads");
    }
    let _ = writeln!(md, ".\n");
    let _ = writeln!(md, "## Mean rank\n");
    let _ = writeln!(
        md,
        "Rank 1 is the smallest error on a material; ties share their mean rank. Relative error is `E/E₀` (`E₀`: the error of `f_r = 0`).\n"
    );
    let _ = writeln!(
        md,
        "| model | mean rank | best on | median relative error | mean relative error |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    for &k in &order {
        let mut v = relative[k].clone();
        v.sort_by(f64::total_cmp);
        let median = v[v.len() / 2];
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let _ = writeln!(
            md,
            "| {} | {:.2} | {} | {median:.3} | {mean:.3} |",
            models[k],
            rank_sum[k] / n_mat,
            wins[k]
        );
    }
    let _ = writeln!(md, "\n## Relative error per material (best in bold)\n");
    let _ = writeln!(md, "| material | {} |", models.join(" | "));
    let _ = writeln!(md, "|---|{}", "---|".repeat(models.len()));
    md.push_str(&table);
    let mut abc = None;
    if let Some((abc_md, abc_csv)) = abc_comparison(&by_material, &metric) {
        let _ = writeln!(
            md,
            "\n## ABC: the published parameters against gonio's fit\n\nSee `abc.md` (and `abc.csv`)."
        );
        abc = Some((abc_md, abc_csv));
    }
    let (ranking_csv, ranking_md, fits_toml) = (
        dir.join("ranking.csv"),
        dir.join("ranking.md"),
        dir.join("fits.toml"),
    );
    let (abc_md, abc_csv) = (dir.join("abc.md"), dir.join("abc.csv"));
    let mut set: Vec<(&Path, &str)> = vec![
        (ranking_csv.as_path(), csv_out.as_str()),
        (ranking_md.as_path(), md.as_str()),
        (fits_toml.as_path(), fits.as_str()),
    ];
    if let Some((m, c)) = &abc {
        set.push((abc_md.as_path(), m.as_str()));
        set.push((abc_csv.as_path(), c.as_str()));
    }
    write_set(&set)?;
    let summary: Vec<String> = order
        .iter()
        .take(5)
        .map(|&k| format!("{} ({:.2})", models[k], rank_sum[k] / n_mat))
        .collect();
    Ok(format!("mean rank: {}", summary.join(", ")))
}

/// The published ABC parameters (`abc-published`) against gonio's own ABC
/// fits per material, when the run has them: `abc` (gonio's own starts)
/// and `abc-from-published` (those starts and the published parameters),
/// Markdown and CSV. All are scored by the same metric on the same
/// samples, so a fit, which minimizes it, should not be worse; the table
/// says where it is.
fn abc_comparison(
    by_material: &BTreeMap<&str, Vec<&Row>>,
    metric: &str,
) -> Option<(String, String)> {
    let pick = |rs: &[&Row], name: &str| rs.iter().find(|r| r.model == name).map(|r| (*r).clone());
    let rows: Vec<(&str, Row, Option<Row>, Option<Row>)> = by_material
        .iter()
        .filter_map(|(m, rs)| {
            Some((
                *m,
                pick(rs, super::models::ABC_PUBLISHED)?,
                pick(rs, "abc"),
                pick(rs, "abc-from-published"),
            ))
        })
        .filter(|(_, _, own, warm)| own.is_some() || warm.is_some())
        .collect();
    if rows.is_empty() {
        return None;
    }
    let mut csv = String::from(
        "material,metric,published_error,published_relative,gonio_error,gonio_relative,gonio_from_published_error,gonio_from_published_relative\n",
    );
    let mut table = String::new();
    // [better, worse] of the own fit and of the fit also started from the
    // published parameters. Equal within 1e-6 relative: the stopping rule's
    // cost spread (1e-9 of E₀²) is far below it.
    let mut counts = [[0usize; 2]; 2];
    let mut ratios: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    let cell = |p: &Row,
                g: &Option<Row>,
                k: usize,
                counts: &mut [[usize; 2]; 2],
                ratios: &mut [Vec<f64>; 2]|
     -> String {
        let Some(g) = g else {
            return "| – | – ".into();
        };
        let ratio = g.error / p.error;
        ratios[k].push(ratio);
        let mark = if ratio < 1.0 - 1e-6 {
            counts[k][0] += 1;
            format!("{ratio:.3}")
        } else if ratio > 1.0 + 1e-6 {
            counts[k][1] += 1;
            format!("**{ratio:.3} worse**")
        } else {
            format!("{ratio:.3}")
        };
        format!("| {:.4} | {mark} ", g.relative)
    };
    let field = |g: &Option<Row>| {
        g.as_ref().map_or(",".to_string(), |g| {
            format!("{:.6e},{:.6e}", g.error, g.relative)
        })
    };
    for (m, p, own, warm) in &rows {
        let _ = writeln!(
            csv,
            "{m},{metric},{:.6e},{:.6e},{},{}",
            p.error,
            p.relative,
            field(own),
            field(warm)
        );
        let _ = writeln!(
            table,
            "| {m} | {:.4e} | {:.4} {}{}|",
            p.error,
            p.relative,
            cell(p, own, 0, &mut counts, &mut ratios),
            cell(p, warm, 1, &mut counts, &mut ratios)
        );
    }
    let summary = |k: usize, what: &str| -> String {
        let mut r = ratios[k].clone();
        if r.is_empty() {
            return String::new();
        }
        r.sort_by(f64::total_cmp);
        format!(
            "{what}: better than the published parameters on {} of {}, worse on {}, median ratio {:.3}.",
            counts[k][0],
            r.len(),
            counts[k][1],
            r[r.len() / 2]
        )
    };
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# ABC (Löw et al. 2012): published parameters against gonio's fit\n\n\
Generated by `gonio fit --merge` from the rows of `abc-published` (the published \
parameters of `data/measured/merl100_abc_fits.csv`, rendered as gonio's `abc` model and \
scored, not fitted), `abc` (gonio's fit of the same model from its own starts) and \
`abc-from-published` (the same fit with the published parameters as one more start), \
under the metric `{metric}` on the same samples of the same materials (the Neural-BRDF \
networks; see docs/measured.md). Errors `E` in 1/sr, relative `E/E₀`; the ratios are \
gonio's `E` over the published `E` (below 1: gonio's fit is better).\n"
    );
    let _ = writeln!(md, "{}\n", summary(0, "gonio's own starts"));
    let _ = writeln!(md, "{}\n", summary(1, "with the published start"));
    let _ = writeln!(
        md,
        "| material | published E | published E/E₀ | gonio E/E₀ | ratio | gonio from published E/E₀ | ratio |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    md.push_str(&table);
    Some((md, csv))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_share_their_mean_rank() {
        assert_eq!(ranks(&[0.3, 0.1, 0.3, 0.2]), vec![3.5, 1.0, 3.5, 2.0]);
    }

    #[test]
    fn rows_read_back() {
        let r = Row {
            material: "chrome".into(),
            model: "ct-ggx-conductor".into(),
            metric: "ngan".into(),
            error: 1.5,
            relative: 0.25,
            evaluations: 10,
            seconds: 0.5,
        };
        let text = csv(std::slice::from_ref(&r));
        assert_eq!(parse_csv(Path::new("x.csv"), &text).unwrap(), vec![r]);
        assert!(parse_csv(Path::new("x.csv"), "a,b\n").is_err());
    }
}
