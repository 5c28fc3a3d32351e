//! `gonio merge`: the partial images of one sharded render joined into
//! the image a single `gonio render --reference` writes, bit for bit.
//!
//! The set is checked from the headers before any pixel is read: every
//! file a partial image, all of one render (same key, size and shard
//! count), each shard exactly once. A file that does not belong, a shard
//! given twice or a shard missing is named, and nothing is written.

use super::partial::{self, Header};
use crate::frame::Frame;
use crate::output::{OutputFile, OutputFormat};
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// The partial files `parts`, checked to be one complete render, in
/// shard order.
pub fn check_set(parts: &[PathBuf]) -> Result<Vec<(PathBuf, Header)>> {
    if parts.is_empty() {
        return Err(Error::argument(
            "gonio merge",
            "no partial images given: e.g. `gonio merge -o out.exr part-*.exr`",
        ));
    }
    let headers: Vec<(PathBuf, Header)> = parts
        .iter()
        .map(|p| Ok((p.clone(), partial::read_header(p)?)))
        .collect::<Result<_>>()?;
    // The render the set is of: the one most files belong to (the first
    // file's on a tie), so that the message names the odd file out.
    let render = |h: &Header| (h.key.clone(), h.width, h.height, h.shard.count);
    let votes = |h: &Header| {
        headers
            .iter()
            .filter(|(_, o)| render(o) == render(h))
            .count()
    };
    let (_, majority) = headers
        .iter()
        .rev()
        .max_by_key(|(_, h)| votes(h))
        .expect("not empty");
    for (path, h) in &headers {
        if render(h) != render(majority) {
            return Err(Error::input(
                path,
                format!(
                    "belongs to another render: it holds {}, while {} of the {} files hold parts of {}; merge the parts of one render",
                    h.describe(),
                    votes(majority),
                    headers.len(),
                    majority.describe_render()
                ),
            ));
        }
    }
    let count = majority.shard.count;
    let mut by_shard: Vec<Option<&(PathBuf, Header)>> = vec![None; count];
    for entry in &headers {
        let slot = &mut by_shard[entry.1.shard.index - 1];
        if let Some(first) = slot {
            return Err(Error::input(
                &entry.0,
                format!(
                    "holds shard {} as {} does: a shard given twice (the same file, or a copy)",
                    entry.1.shard,
                    first.0.display()
                ),
            ));
        }
        *slot = Some(entry);
    }
    let missing: Vec<String> = by_shard
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(k, _)| format!("{}/{count}", k + 1))
        .collect();
    if !missing.is_empty() {
        return Err(Error::argument(
            "gonio merge",
            format!(
                "the set is incomplete: {} {} {} missing ({} of {count} given); render {} with `gonio render --reference --shard I/{count}` and merge again",
                if missing.len() == 1 {
                    "shard"
                } else {
                    "shards"
                },
                missing.join(", "),
                if missing.len() == 1 { "is" } else { "are" },
                headers.len(),
                if missing.len() == 1 { "it" } else { "them" },
            ),
        ));
    }
    Ok(by_shard.into_iter().flatten().cloned().collect())
}

/// Joins the checked set into the whole image (coverage is not carried
/// by partial files and stays unset: no output format stores it).
pub fn assemble(set: &[(PathBuf, Header)]) -> Result<Frame> {
    let first = &set[0].1;
    let (width, height) = (first.width as usize, first.height as usize);
    let mut frame = Frame::new(first.width, first.height);
    for (path, header) in set {
        let pixels = partial::read_rows(path, header)?;
        for (k, row) in header.shard.items(height).enumerate() {
            frame.radiance[row * width..(row + 1) * width]
                .copy_from_slice(&pixels[k * width..(k + 1) * width]);
        }
    }
    Ok(frame)
}

/// `gonio merge -o OUT [--exposure E] PARTS…`.
pub fn run(output: &Path, exposure: f64, parts: &[PathBuf]) -> Result<()> {
    if !exposure.is_finite() {
        return Err(Error::argument(
            format!("--exposure {exposure}"),
            "the exposure must be a finite number of stops",
        ));
    }
    let format = OutputFormat::from_path(output)?;
    if exposure != 0.0 && format == OutputFormat::Exr {
        return Err(Error::argument(
            format!("--exposure {exposure}"),
            format!(
                "{} is an EXR, which holds linear radiance without exposure or tone mapping; drop --exposure, or write a .png",
                output.display()
            ),
        ));
    }
    if let Some(p) = parts.iter().find(|p| same_file(p, output)) {
        return Err(Error::argument(
            format!("-o {}", output.display()),
            format!(
                "{} is also one of the parts to merge: write the image elsewhere",
                p.display()
            ),
        ));
    }
    let file = OutputFile::prepare(output)?;
    let set = check_set(parts)?;
    let tone_map = set[0].1.tone_map;
    if tone_map != Default::default() && format == OutputFormat::Exr {
        eprintln!(
            "gonio: warning: image.tone_map = \"{tone_map}\" does not apply to {}: an EXR holds linear radiance; write a .png to see it tone-mapped",
            output.display()
        );
    }
    let frame = assemble(&set)?;
    file.write_tone_mapped(&frame, exposure, tone_map)
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
