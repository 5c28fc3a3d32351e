//! Which piece of a batch this process runs: `--shard I/N` (1-based), or
//! `--shard auto` / `--shard auto/N`, read from the variables a cluster
//! scheduler sets in each task of an array job.
//!
//! Every sharded command takes the same rule, "item k belongs to shard
//! `k mod N + 1`" (interleaved, so that neighbouring rows or consecutive
//! configurations, which cost about the same, spread over all shards).
//!
//! The schedulers (first match wins):
//! - Slurm job arrays (`sbatch --array=A-B`): `SLURM_ARRAY_TASK_ID` in
//!   `SLURM_ARRAY_TASK_MIN..=SLURM_ARRAY_TASK_MAX`, `SLURM_ARRAY_TASK_COUNT`
//!   tasks (<https://slurm.schedmd.com/job_array.html>); the array must be
//!   a contiguous range, as `--array=1-8`.
//! - Kubernetes Indexed Jobs: `JOB_COMPLETION_INDEX`, 0-based
//!   (<https://kubernetes.io/docs/concepts/workloads/controllers/job/#completion-mode>);
//!   the pod sees no count, so the job gives it: `--shard auto/N`.
//! - HyperQueue task arrays (`hq submit --array=1-N`): `HQ_TASK_ID`,
//!   1-based as submitted; no count either: `--shard auto/N`.
//!
//! There is deliberately no `GONIO_SHARD` variable: a shard changes what
//! the command writes (a partial file in place of an image), and a
//! variable left in an environment would do that to commands that never
//! asked for it. The job script says `--shard auto`.

use crate::{Error, Result};

/// Shard `index` of `count`, 1 ≤ index ≤ count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// The variables `--shard auto` reads, in the order it tries them.
pub const SCHEDULER_VARIABLES: [&str; 3] =
    ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "HQ_TASK_ID"];

impl Shard {
    /// The whole batch in one piece.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// `--shard TEXT` with the process's environment.
    pub fn from_arg(text: &str) -> Result<(Shard, Option<String>)> {
        Self::parse(text, |name| std::env::var(name).ok())
    }

    /// `TEXT` is `I/N`, `auto` or `auto/N`; `env` looks a variable up.
    /// Returns the shard and, for `auto`, where it came from (e.g.
    /// `SLURM_ARRAY_TASK_ID=3 of 1-8`), for the log.
    pub fn parse(
        text: &str,
        env: impl Fn(&str) -> Option<String>,
    ) -> Result<(Shard, Option<String>)> {
        let argument = || format!("--shard {text}");
        let bad = || {
            Error::argument(
                argument(),
                "expected I/N with 1 ≤ I ≤ N (e.g. --shard 2/8), or `auto` (or `auto/N`) to read the shard from a cluster scheduler's variables",
            )
        };
        let (head, tail) = match text.split_once('/') {
            Some((h, t)) => (h.trim(), Some(t.trim())),
            None => (text.trim(), None),
        };
        let count: Option<usize> = match tail {
            Some(t) => match t.parse() {
                Ok(n) if n >= 1 => Some(n),
                _ => return Err(bad()),
            },
            None => None,
        };
        if head != "auto" {
            let (Ok(index), Some(count)) = (head.parse::<usize>(), count) else {
                return Err(bad());
            };
            if index == 0 || index > count {
                return Err(bad());
            }
            return Ok((Shard { index, count }, None));
        }
        let number = |name: &str| -> Result<Option<i64>> {
            match env(name) {
                None => Ok(None),
                Some(v) => v.trim().parse().map(Some).map_err(|_| {
                    Error::argument(argument(), format!("{name}={v} is not a whole number"))
                }),
            }
        };
        let (shard, source) = if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let need = |name: &str| -> Result<i64> {
                number(name)?.ok_or_else(|| {
                    Error::argument(
                        argument(),
                        format!("SLURM_ARRAY_TASK_ID is set but not {name}: is this a Slurm job array (sbatch --array=1-N)?"),
                    )
                })
            };
            let (min, max) = (need("SLURM_ARRAY_TASK_MIN")?, need("SLURM_ARRAY_TASK_MAX")?);
            let range = max - min + 1;
            let tasks = number("SLURM_ARRAY_TASK_COUNT")?.unwrap_or(range);
            if tasks != range || id < min || id > max {
                return Err(Error::argument(
                    argument(),
                    format!(
                        "the Slurm array is not one contiguous range (SLURM_ARRAY_TASK_ID={id}, MIN={min}, MAX={max}, COUNT={tasks}): submit it as --array=1-N, without a step or a list (a `%` limit is fine)"
                    ),
                ));
            }
            let shard = Shard {
                index: (id - min + 1) as usize,
                count: range as usize,
            };
            if let Some(n) = count
                && n != shard.count
            {
                return Err(Error::argument(
                    argument(),
                    format!(
                        "the Slurm array has {} tasks ({min}-{max}), not {n}",
                        shard.count
                    ),
                ));
            }
            (shard, format!("SLURM_ARRAY_TASK_ID={id} of {min}-{max}"))
        } else if let Some(k) = number("JOB_COMPLETION_INDEX")? {
            let n = count.ok_or_else(|| {
                Error::argument(
                    argument(),
                    format!("JOB_COMPLETION_INDEX={k} (a Kubernetes Indexed Job) gives no count: give it, --shard auto/N with N the job's `completions`"),
                )
            })?;
            if k < 0 || k as usize >= n {
                return Err(Error::argument(
                    argument(),
                    format!(
                        "JOB_COMPLETION_INDEX={k} is outside 0..{n}: the job's `completions` must be {n}"
                    ),
                ));
            }
            (
                Shard {
                    index: k as usize + 1,
                    count: n,
                },
                format!("JOB_COMPLETION_INDEX={k} of 0-{}", n - 1),
            )
        } else if let Some(id) = number("HQ_TASK_ID")? {
            let n = count.ok_or_else(|| {
                Error::argument(
                    argument(),
                    format!("HQ_TASK_ID={id} (HyperQueue) gives no count: give it, --shard auto/N with `hq submit --array=1-N`"),
                )
            })?;
            if id < 1 || id as usize > n {
                return Err(Error::argument(
                    argument(),
                    format!(
                        "HQ_TASK_ID={id} is outside 1..={n}: submit with `hq submit --array=1-{n}`"
                    ),
                ));
            }
            (
                Shard {
                    index: id as usize,
                    count: n,
                },
                format!("HQ_TASK_ID={id} of 1-{n}"),
            )
        } else {
            return Err(Error::argument(
                argument(),
                format!(
                    "none of the schedulers' variables is set ({}: Slurm job arrays, Kubernetes Indexed Jobs, HyperQueue arrays); outside a scheduler give the shard as I/N",
                    SCHEDULER_VARIABLES.join(", ")
                ),
            ));
        };
        Ok((shard, Some(source)))
    }

    /// Whether item `k` (0-based) of the batch is this shard's.
    pub fn takes(&self, k: usize) -> bool {
        k % self.count == self.index - 1
    }

    /// This shard's items of `0..total`: `I−1, I−1+N, …`.
    pub fn items(&self, total: usize) -> impl Iterator<Item = usize> + use<> {
        (self.index - 1..total).step_by(self.count)
    }

    /// `path` with `{shard}` replaced by the index, zero-padded to the
    /// width of the count (so that `part-*.exr` lists in order).
    pub fn expand(&self, path: &std::path::Path) -> std::path::PathBuf {
        let text = path.to_string_lossy();
        if !text.contains("{shard}") {
            return path.to_path_buf();
        }
        let width = self.count.to_string().len();
        text.replace("{shard}", &format!("{:0width$}", self.index))
            .into()
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn with(vars: &[(&str, &str)], text: &str) -> Result<(Shard, Option<String>)> {
        let map: HashMap<String, String> = vars
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        Shard::parse(text, |k| map.get(k).cloned())
    }

    fn shard(index: usize, count: usize) -> Shard {
        Shard { index, count }
    }

    #[test]
    fn explicit_shards_parse_and_bad_ones_are_refused() {
        assert_eq!(with(&[], "3/8").unwrap().0, shard(3, 8));
        assert_eq!(with(&[], " 1 / 1 ").unwrap().0, shard(1, 1));
        for bad in ["0/8", "9/8", "3", "3/0", "a/b", "-1/2", "", "auto/0"] {
            let e = with(&[], bad).unwrap_err().to_string();
            assert!(e.contains("expected I/N"), "{bad}: {e}");
        }
    }

    #[test]
    fn slurm_arrays_give_the_shard_whatever_their_first_index() {
        let one_based = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        let (s, source) = with(&one_based, "auto").unwrap();
        assert_eq!(s, shard(3, 4));
        assert_eq!(source.unwrap(), "SLURM_ARRAY_TASK_ID=3 of 1-4");
        assert_eq!(with(&one_based, "auto/4").unwrap().0, shard(3, 4));
        let e = with(&one_based, "auto/5").unwrap_err().to_string();
        assert!(e.contains("4 tasks") && e.contains("not 5"), "{e}");
        let zero_based = [
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_MAX", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        assert_eq!(with(&zero_based, "auto").unwrap().0, shard(1, 8));
        // --array=1-7:2 has 4 tasks over a range of 7.
        let stepped = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        let e = with(&stepped, "auto").unwrap_err().to_string();
        assert!(e.contains("contiguous"), "{e}");
        let e = with(&[("SLURM_ARRAY_TASK_ID", "3")], "auto")
            .unwrap_err()
            .to_string();
        assert!(e.contains("SLURM_ARRAY_TASK_MIN"), "{e}");
    }

    #[test]
    fn kubernetes_and_hyperqueue_need_the_count() {
        let k8s = [("JOB_COMPLETION_INDEX", "0")];
        assert_eq!(with(&k8s, "auto/5").unwrap().0, shard(1, 5));
        let e = with(&k8s, "auto").unwrap_err().to_string();
        assert!(e.contains("auto/N"), "{e}");
        let e = with(&[("JOB_COMPLETION_INDEX", "5")], "auto/5")
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside 0..5"), "{e}");
        let hq = [("HQ_TASK_ID", "5")];
        assert_eq!(with(&hq, "auto/5").unwrap().0, shard(5, 5));
        let e = with(&[("HQ_TASK_ID", "0")], "auto/5")
            .unwrap_err()
            .to_string();
        assert!(e.contains("--array=1-5"), "{e}");
        let e = with(&[("HQ_TASK_ID", "x")], "auto/5")
            .unwrap_err()
            .to_string();
        assert!(e.contains("HQ_TASK_ID=x"), "{e}");
    }

    #[test]
    fn auto_without_a_scheduler_names_the_variables() {
        let e = with(&[], "auto").unwrap_err().to_string();
        for name in SCHEDULER_VARIABLES {
            assert!(e.contains(name), "{e}");
        }
    }

    #[test]
    fn the_shards_items_cover_the_batch_once() {
        for total in [0, 1, 5, 60, 61] {
            for count in 1..=7 {
                let mut seen = vec![0; total];
                for index in 1..=count {
                    let s = shard(index, count);
                    for k in s.items(total) {
                        assert!(s.takes(k));
                        seen[k] += 1;
                    }
                }
                assert!(
                    seen.iter().all(|&n| n == 1),
                    "{total} items, {count} shards"
                );
            }
        }
    }

    #[test]
    fn the_output_path_takes_the_padded_index() {
        let p = std::path::Path::new("out/part-{shard}.exr");
        assert_eq!(
            shard(3, 12).expand(p),
            std::path::Path::new("out/part-03.exr")
        );
        assert_eq!(
            shard(3, 9).expand(p),
            std::path::Path::new("out/part-3.exr")
        );
        let plain = std::path::Path::new("part.exr");
        assert_eq!(shard(3, 9).expand(plain), plain);
    }
}
