//! `gonio render --max-error E`: the cheapest measured configuration
//! whose error is within E.
//!
//! It reads the `results.csv` that `gonio bench` wrote (by default
//! `gonio-bench/results.csv`, or `--bench-results PATH`), keeps the rows
//! measured on the scene being rendered, and returns the `--set`
//! overrides of the cheapest one whose error is at most E: a point of the
//! Pareto front ([`super::pareto::cheapest_within`]).

use super::pareto::{self, Point};
use super::report::{RESULTS_HEADER, parse_csv_line};
use crate::{Error, Result};
use std::path::Path;

/// One row of `results.csv` as `--max-error` needs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    pub scene: String,
    pub label: String,
    pub overrides: Vec<String>,
    pub time_ms: f64,
    pub error: f64,
}

/// What `--max-error` chose.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    pub label: String,
    pub overrides: Vec<String>,
    pub time_ms: f64,
    pub error: f64,
}

/// Parses `results.csv`; `path` names the file in errors.
pub fn parse_results(text: &str, path: &Path) -> Result<Vec<Measured>> {
    let bad = |line: usize, problem: String| {
        Error::input(
            path,
            format!(
                "line {line}: {problem}; this file should be the results.csv that `gonio bench` writes"
            ),
        )
    };
    let mut lines = text.lines().enumerate();
    let header = lines
        .next()
        .map(|(_, l)| parse_csv_line(l))
        .unwrap_or_default();
    if header != RESULTS_HEADER {
        return Err(bad(
            1,
            format!("the header is not `{}`", RESULTS_HEADER.join(",")),
        ));
    }
    let column = |name: &str| RESULTS_HEADER.iter().position(|h| *h == name).unwrap_or(0);
    let mut rows = Vec::new();
    for (k, line) in lines.filter(|(_, l)| !l.trim().is_empty()) {
        let f = parse_csv_line(line);
        if f.len() != RESULTS_HEADER.len() {
            return Err(bad(
                k + 1,
                format!("{} fields, expected {}", f.len(), RESULTS_HEADER.len()),
            ));
        }
        let number = |name: &str| -> Result<f64> {
            let text = &f[column(name)];
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
                _ => Err(bad(
                    k + 1,
                    format!("{name} = `{text}` is not a finite number ≥ 0"),
                )),
            }
        };
        let knob = &f[column("knob")];
        rows.push(Measured {
            scene: f[column("scene")].clone(),
            label: if knob == "base" {
                "base".into()
            } else {
                format!("{knob}={}", f[column("value")])
            },
            overrides: f[column("overrides")]
                .split(';')
                .filter(|s| !s.trim().is_empty())
                .map(str::to_string)
                .collect(),
            time_ms: number("time_ms")?,
            error: number("rel_rms_error")?,
        });
    }
    Ok(rows)
}

/// The cheapest row of `rows` measured on `scene` with error ≤ `max_error`.
pub fn choose(rows: &[Measured], scene: &str, max_error: f64, path: &Path) -> Result<Choice> {
    let arg = format!("--max-error {max_error}");
    if !max_error.is_finite() || max_error < 0.0 {
        return Err(Error::argument(
            arg,
            "the error budget must be a finite number ≥ 0 (a relative RMS error, e.g. 0.05 for 5%)",
        ));
    }
    // The layer knobs draw another material (their error is against
    // their own reference, `Config::own_truth`): never a pick.
    let here: Vec<&Measured> = rows
        .iter()
        .filter(|r| r.scene == scene && !r.label.starts_with(super::configs::LAYER_KNOB))
        .collect();
    if here.is_empty() {
        let measured: std::collections::BTreeSet<&str> =
            rows.iter().map(|r| r.scene.as_str()).collect();
        return Err(Error::input(
            path,
            format!(
                "no configuration of scene `{scene}` was measured here (the file has {}); run `gonio bench` on this scene first",
                if measured.is_empty() {
                    "none".to_string()
                } else {
                    measured.into_iter().collect::<Vec<_>>().join(", ")
                }
            ),
        ));
    }
    let points: Vec<Point> = here
        .iter()
        .map(|r| Point {
            time: r.time_ms,
            error: r.error,
        })
        .collect();
    match pareto::cheapest_within(&points, max_error) {
        Some(i) => Ok(Choice {
            label: here[i].label.clone(),
            overrides: here[i].overrides.clone(),
            time_ms: here[i].time_ms,
            error: here[i].error,
        }),
        None => {
            let best = points.iter().map(|p| p.error).fold(f64::INFINITY, f64::min);
            Err(Error::argument(
                arg,
                format!(
                    "no measured configuration is that accurate: the most accurate one in {} has a relative RMS error of {best:.3e}; allow a larger error or measure more exact settings with `gonio bench`",
                    path.display()
                ),
            ))
        }
    }
}

/// The cheapest configuration measured on `scene` (the label
/// [`super::run::scene_label`] gives) in `results` whose error is at most
/// `max_error`: what `--max-error` resolves to (`crate::cli::MaxErrorArgs`).
pub fn cheapest_within(max_error: f64, results: &Path, scene: Option<&Path>) -> Result<Choice> {
    if !max_error.is_finite() || max_error < 0.0 {
        return choose(&[], "", max_error, results);
    }
    // A bench's results are a few hundred rows; 64 MiB bounds a wrong file.
    let text = crate::base::input::read_regular_text(results, 64 << 20).map_err(|e| {
        Error::input(
            results,
            format!("cannot read the bench results for --max-error ({e}); run `gonio bench` first (it writes gonio-bench/results.csv) or name the file with --bench-results"),
        )
    })?;
    let rows = parse_results(&text, results)?;
    choose(&rows, &super::run::scene_label(scene), max_error, results)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv() -> String {
        let mut s = RESULTS_HEADER.join(",");
        s.push('\n');
        for (knob, value, overrides, time, error) in [
            ("base", "as loaded", "a=1", 10.0, 0.01),
            ("shading", "flat", "a=1;shading.mode=flat", 5.0, 0.2),
            ("shading", "gouraud", "a=1;shading.mode=gouraud", 6.0, 0.05),
            ("area_samples", "256", "a=1;lights.1.samples=256", 40.0, 0.0),
        ] {
            s += &format!(
                "built-in,{knob},{value},{overrides},{time},{time},{time},1.0,{error},0.1,false,gpu-timestamp\n"
            );
        }
        s
    }

    #[test]
    fn picks_the_cheapest_within_the_budget() {
        let p = Path::new("results.csv");
        let rows = parse_results(&csv(), p).unwrap();
        assert_eq!(rows.len(), 4);
        let pick = |e| choose(&rows, "built-in", e, p);
        assert_eq!(pick(1.0).unwrap().label, "shading=flat");
        assert_eq!(pick(0.1).unwrap().label, "shading=gouraud");
        assert_eq!(
            pick(0.1).unwrap().overrides,
            vec!["a=1".to_string(), "shading.mode=gouraud".into()]
        );
        assert_eq!(pick(0.02).unwrap().label, "base");
        assert_eq!(pick(0.0).unwrap().label, "area_samples=256");
        assert!(pick(-1.0).is_err());
        assert!(pick(f64::NAN).is_err());
        assert!(choose(&rows, "other.toml", 1.0, p).is_err());
    }

    #[test]
    fn malformed_files_are_input_errors() {
        let p = Path::new("r.csv");
        assert!(parse_results("not,a,header\n", p).is_err());
        let short = format!("{}\nbuilt-in,base\n", RESULTS_HEADER.join(","));
        assert!(parse_results(&short, p).is_err());
        let nan = csv().replace("0.2", "NaN");
        let e = parse_results(&nan, p).unwrap_err().to_string();
        assert!(e.contains("rel_rms_error"), "{e}");
    }
}
