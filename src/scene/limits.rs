//! Caps on what one input may make gonio hold or draw (the bounded read
//! of input files is [`crate::base::input`]).
//!
//! A glTF file declares sizes and counts; a hostile one declares whatever
//! exhausts the machine. [`Limits`] says how much an input may take, with
//! defaults that fit a desktop, and the loaders check every declared size
//! against it *before* allocating for it. `gonio render --limit KEY=VALUE`
//! raises (or lowers) one cap; see [`Limits::set`].

pub use crate::base::input::{ReadError, read_regular_file};

/// How much one scene's inputs may take. Every count is a total over the
/// scene, so a mesh instanced by many nodes counts once per instance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Bytes of input held while a glTF file loads: the file itself, its
    /// buffers, and an estimate of its parsed JSON (which can be a hundred
    /// times larger than its text). Default 1 GiB.
    pub bytes: u64,
    /// Vertices of the imported meshes. Default 50 million.
    pub vertices: u64,
    /// Triangles of the imported meshes. Default 50 million.
    pub triangles: u64,
    /// Nodes of one glTF file. Default 1 million.
    pub nodes: u64,
    /// Images plus textures declared by one glTF file (gonio does not
    /// decode them, but a file is still refused past this). Default 4096.
    pub textures: u64,
    /// Lights (each is evaluated at every pixel, so they bound render
    /// time). Default 1024.
    pub lights: u64,
    /// Bytes the renderer may allocate beyond the loaded scene, estimated
    /// before it starts: the CPU reference's ray-casting hierarchy, the
    /// GPU path's vertex stream and its staging window. Default 8 GiB.
    pub memory: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            bytes: 1 << 30,
            vertices: 50_000_000,
            triangles: 50_000_000,
            nodes: 1_000_000,
            textures: 4096,
            lights: 1024,
            memory: 8 << 30,
        }
    }
}

/// The keys [`Limits::set`] accepts, in the order the docs list them.
pub const LIMIT_KEYS: [&str; 7] = [
    "bytes",
    "vertices",
    "triangles",
    "nodes",
    "textures",
    "lights",
    "memory",
];

impl Limits {
    /// Sets one limit from `KEY=VALUE`, e.g. `triangles=200M` or
    /// `bytes=4Gi`. VALUE is a whole number with an optional suffix `k`,
    /// `M`, `G` (powers of 1000) or `Ki`, `Mi`, `Gi` (powers of 1024).
    pub fn set(&mut self, assignment: &str) -> Result<(), String> {
        let (key, value) = assignment
            .split_once('=')
            .ok_or("expected KEY=VALUE, e.g. triangles=200M")?;
        let value = parse_amount(value.trim())?;
        let slot = match key.trim() {
            "bytes" => &mut self.bytes,
            "vertices" => &mut self.vertices,
            "triangles" => &mut self.triangles,
            "nodes" => &mut self.nodes,
            "textures" => &mut self.textures,
            "lights" => &mut self.lights,
            "memory" => &mut self.memory,
            other => {
                return Err(format!(
                    "unknown limit `{other}`; the limits are {}",
                    LIMIT_KEYS.join(", ")
                ));
            }
        };
        *slot = value;
        Ok(())
    }

    /// Limits with every `KEY=VALUE` of `assignments` applied in order.
    pub fn from_assignments(assignments: &[String]) -> Result<Self, (String, String)> {
        let mut limits = Limits::default();
        for a in assignments {
            limits.set(a).map_err(|problem| (a.clone(), problem))?;
        }
        Ok(limits)
    }
}

pub use crate::base::input::exceeded;

/// Parses `123`, `5k`, `200M`, `4Gi`, ...
fn parse_amount(text: &str) -> Result<u64, String> {
    let split = text
        .find(|c: char| !c.is_ascii_digit() && c != '_')
        .unwrap_or(text.len());
    let (digits, suffix) = text.split_at(split);
    let multiplier: u64 = match suffix {
        "" => 1,
        "k" | "K" => 1_000,
        "M" => 1_000_000,
        "G" => 1_000_000_000,
        "Ki" => 1 << 10,
        "Mi" => 1 << 20,
        "Gi" => 1 << 30,
        _ => {
            return Err(format!(
                "`{text}` is not a whole number with an optional k, M, G, Ki, Mi or Gi suffix"
            ));
        }
    };
    let number: u64 = digits
        .replace('_', "")
        .parse()
        .map_err(|_| format!("`{text}` is not a whole number"))?;
    number
        .checked_mul(multiplier)
        .ok_or_else(|| format!("`{text}` is too large"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn amounts_parse_with_suffixes() {
        assert_eq!(parse_amount("12").unwrap(), 12);
        assert_eq!(parse_amount("1_000").unwrap(), 1000);
        assert_eq!(parse_amount("5k").unwrap(), 5000);
        assert_eq!(parse_amount("200M").unwrap(), 200_000_000);
        assert_eq!(parse_amount("4Gi").unwrap(), 4 << 30);
        assert!(parse_amount("").is_err());
        assert!(parse_amount("-1").is_err());
        assert!(parse_amount("3x").is_err());
        assert!(parse_amount("99999999999999999999").is_err());
        assert!(parse_amount("99999999999Gi").is_err());
    }

    #[test]
    fn limits_are_set_by_key() {
        let mut limits = Limits::default();
        limits.set("triangles=200M").unwrap();
        limits.set(" bytes = 4Gi ").unwrap();
        assert_eq!(limits.triangles, 200_000_000);
        assert_eq!(limits.bytes, 4 << 30);
        let err = limits.set("triangels=1").unwrap_err();
        assert!(
            err.contains("triangels") && err.contains("triangles"),
            "{err}"
        );
        assert!(limits.set("nodes").is_err());
    }
}
