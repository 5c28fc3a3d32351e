//! What a prepared scene sent to the GPU, by kind: the count that shows
//! whether an edit rewrote only what it changed (a material slider should
//! write one material record, not the vertex stream, the textures and
//! the shadow maps). The viewer prints it with `--frame-times` and its
//! tests assert it.
//!
//! A *call* is one buffer or texture written or created with data (the
//! vertex stream counts once however many chunks `upload.rs` splits it
//! into); *bytes* are those handed to the queue. Shadow-map layers are
//! drawn, not uploaded, but they are the other cost an edit can bring
//! back, so they are counted too (bytes: none).

use std::fmt;
use std::ops::AddAssign;

/// Calls and bytes of one kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub calls: u64,
    pub bytes: u64,
}

impl Tally {
    /// Counts one call of `bytes`.
    pub fn add(&mut self, bytes: u64) {
        self.calls += 1;
        self.bytes += bytes;
    }
}

impl AddAssign for Tally {
    fn add_assign(&mut self, other: Tally) {
        self.calls += other.calls;
        self.bytes += other.bytes;
    }
}

/// Uploads by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UploadTally {
    /// The vertex stream and index buffer.
    pub geometry: Tally,
    /// Material textures (all mip levels) and the white placeholder.
    pub textures: Tally,
    /// Per-material texture slots (transforms, channels, field masks).
    pub texture_slots: Tally,
    /// Material records (the whole buffer, or one record in place).
    pub materials: Tally,
    /// Measured materials' tables.
    pub measured: Tally,
    /// The lights buffer.
    pub lights: Tally,
    /// Per-view globals (camera, exposure, ambient) and the environment's
    /// per-view uniform.
    pub globals: Tally,
    /// The environment map's texels (a new map or stack).
    pub environment: Tally,
    /// Shadow-map views and casters written in place.
    pub shadow_views: Tally,
    /// Shadow-map layers drawn (calls: layers; bytes: none).
    pub shadow_layers: Tally,
}

impl UploadTally {
    /// The kinds with their names, in the order they are printed.
    pub fn kinds(&self) -> [(&'static str, Tally); 10] {
        [
            ("geometry", self.geometry),
            ("textures", self.textures),
            ("texture slots", self.texture_slots),
            ("materials", self.materials),
            ("measured tables", self.measured),
            ("lights", self.lights),
            ("globals", self.globals),
            ("environment", self.environment),
            ("shadow views", self.shadow_views),
            ("shadow layers drawn", self.shadow_layers),
        ]
    }

    /// Bytes of every kind together.
    pub fn bytes(&self) -> u64 {
        self.kinds().iter().map(|(_, t)| t.bytes).sum()
    }

    /// Calls of every kind together.
    pub fn calls(&self) -> u64 {
        self.kinds().iter().map(|(_, t)| t.calls).sum()
    }
}

impl AddAssign for UploadTally {
    fn add_assign(&mut self, other: UploadTally) {
        self.geometry += other.geometry;
        self.textures += other.textures;
        self.texture_slots += other.texture_slots;
        self.materials += other.materials;
        self.measured += other.measured;
        self.lights += other.lights;
        self.globals += other.globals;
        self.environment += other.environment;
        self.shadow_views += other.shadow_views;
        self.shadow_layers += other.shadow_layers;
    }
}

/// `geometry 0, textures 0, …, materials 1 (224 B), …`: every kind, so
/// that a reader (or a test) sees the zeros too.
impl fmt::Display for UploadTally {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (name, t)) in self.kinds().iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} {} ({} B)", t.calls, t.bytes)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tallies_add_by_kind_and_print_every_kind() {
        let mut a = UploadTally::default();
        a.materials.add(224);
        a.geometry.add(1 << 20);
        let mut b = UploadTally::default();
        b.materials.add(224);
        b.shadow_layers.add(0);
        a += b;
        assert_eq!(
            a.materials,
            Tally {
                calls: 2,
                bytes: 448
            }
        );
        assert_eq!(a.calls(), 4);
        assert_eq!(a.bytes(), 448 + (1 << 20));
        let text = a.to_string();
        assert!(text.contains("materials 2 (448 B)"), "{text}");
        assert!(text.contains("textures 0 (0 B)"), "{text}");
        assert!(text.contains("shadow layers drawn 1 (0 B)"), "{text}");
    }
}
