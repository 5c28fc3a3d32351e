//! `gonio render --reference --shard I/N -o part-{shard}.exr`: the rows
//! of one shard, into a partial file, skipped when that file is already
//! there (a restarted array job redoes only what is missing).

use super::partial::{self, Header};
use super::shard::Shard;
use crate::output::{AtomicFile, OutputFormat};
use crate::scene::Scene;
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// A shard's output, claimed before the scene is loaded (a bad path fails
/// before any work, as for every render).
pub struct ShardOutput {
    shard: Shard,
    file: AtomicFile,
}

impl ShardOutput {
    /// Parses `--shard TEXT` (a reference render only), expands `{shard}`
    /// in `output`, and claims the file. `verbose` says where `auto`
    /// found the shard.
    pub fn prepare(text: &str, output: &Path, reference: bool, verbose: bool) -> Result<Self> {
        if !reference {
            return Err(Error::argument(
                format!("--shard {text}"),
                "a shard is a part of a CPU reference render: add --reference (a GPU frame renders in one piece)",
            ));
        }
        let (shard, source) = Shard::from_arg(text)?;
        if verbose && let Some(source) = source {
            eprintln!("gonio: --shard {text}: shard {shard} ({source})");
        }
        let path: PathBuf = shard.expand(output);
        if OutputFormat::from_path(&path)? != OutputFormat::Exr {
            return Err(Error::argument(
                format!("-o {}", output.display()),
                "a shard writes a partial image for `gonio merge`, which is an .exr (exact float radiance); merge the parts into a .png",
            ));
        }
        Ok(ShardOutput {
            shard,
            file: AtomicFile::create(&path)?,
        })
    }

    /// The shard.
    pub fn shard(&self) -> Shard {
        self.shard
    }

    /// Renders the shard's rows of `scene` and writes them, unless the
    /// file already holds them. Returns whether it rendered.
    pub fn render(self, scene: &Scene) -> Result<bool> {
        let header = Header::new(scene, self.shard);
        let path = self.file.path().to_path_buf();
        if self.shard.count > scene.height as usize {
            return Err(Error::argument(
                format!("--shard {}", self.shard),
                format!(
                    "the image has {} rows, and a shard is at least one row: use at most {} shards",
                    scene.height, scene.height
                ),
            ));
        }
        match partial::is_done(&path, &header) {
            Ok(true) => {
                eprintln!(
                    "gonio: {} already holds {}: skipped",
                    path.display(),
                    header.describe()
                );
                return Ok(false);
            }
            Ok(false) => {}
            Err(why) => eprintln!("gonio: note: replacing {} ({why})", path.display()),
        }
        let rows: Vec<u32> = self
            .shard
            .items(scene.height as usize)
            .map(|r| r as u32)
            .collect();
        let frame = crate::reference::render_rows(scene, &rows);
        partial::write(self.file, &header, &frame)?;
        Ok(true)
    }
}
