//! A census of the JSON, taken before it is parsed.
//!
//! Parsing builds a struct for every JSON object, and a struct can be a
//! hundred times larger than the text it came from: three bytes `{}` in
//! `nodes` become a 224-byte `Node`. So the JSON is first walked without
//! building anything (serde with a visitor that only counts), and the
//! counts are checked against the [`Limits`] before the real parse.

use crate::scene::limits::{Limits, exceeded};
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// Upper bounds of what parsing costs, per JSON object and per other JSON
/// value. An empty object `{}` in `nodes` becomes a 224-byte `Node`, and
/// `Vec` growth can double that; a number inside `min`/`max` becomes a
/// 32-byte `serde_json::Value`. Three bytes of text can so become half a
/// kilobyte, which is why the census runs before the parse.
const PARSED_BYTES_PER_OBJECT: u64 = 512;
const PARSED_BYTES_PER_VALUE: u64 = 64;

/// Counts of the JSON, taken without building it.
#[derive(Debug, Default)]
pub(super) struct Census {
    /// Every value: objects, arrays, strings, numbers, booleans, nulls.
    values: u64,
    objects: u64,
    nodes: u64,
    images: u64,
    textures: u64,
}

impl Census {
    pub(super) fn take(json: &[u8]) -> Result<Census, String> {
        gltf::json::deserialize::from_slice::<TopLevel>(json)
            .map(|top| top.0)
            .map_err(|e| format!("invalid glTF: the JSON is malformed: {e}"))
    }

    pub(super) fn check(&self, used_bytes: &mut u64, limits: &Limits) -> Result<(), String> {
        if self.nodes > limits.nodes {
            return Err(exceeded(
                "the number of nodes",
                self.nodes,
                "nodes",
                limits.nodes,
            ));
        }
        let textures = self.images.saturating_add(self.textures);
        if textures > limits.textures {
            return Err(exceeded(
                "the number of images and textures",
                textures,
                "textures",
                limits.textures,
            ));
        }
        let parsed = self
            .objects
            .saturating_mul(PARSED_BYTES_PER_OBJECT)
            .saturating_add(self.values.saturating_mul(PARSED_BYTES_PER_VALUE));
        *used_bytes = used_bytes.saturating_add(parsed);
        if *used_bytes > limits.bytes {
            return Err(exceeded(
                &format!(
                    "the file plus its parsed JSON ({} objects, {} values, up to {parsed} bytes)",
                    self.objects, self.values
                ),
                format!("{used_bytes} bytes"),
                "bytes",
                limits.bytes,
            ));
        }
        Ok(())
    }
}

/// The top-level object: counts as a [`Tally`] does, and also the entries
/// of the arrays that limits cap.
struct TopLevel(Census);

impl<'de> de::Deserialize<'de> for TopLevel {
    fn deserialize<D: Deserializer<'de>>(de: D) -> Result<TopLevel, D::Error> {
        de.deserialize_map(TopLevelVisitor)
    }
}

struct TopLevelVisitor;

impl<'de> Visitor<'de> for TopLevelVisitor {
    type Value = TopLevel;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a glTF JSON object")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TopLevel, A::Error> {
        let mut census = Census {
            values: 1,
            objects: 1,
            ..Census::default()
        };
        while let Some(key) = map.next_key::<std::borrow::Cow<'de, str>>()? {
            let entries = map.next_value_seed(Tally {
                census: &mut census,
            })?;
            match key.as_ref() {
                "nodes" => census.nodes = entries,
                "images" => census.images = entries,
                "textures" => census.textures = entries,
                _ => {}
            }
        }
        Ok(TopLevel(census))
    }
}

/// Counts one value and everything inside it; yields the number of
/// elements if the value is an array (0 otherwise). Recursion depth is
/// bounded by serde_json's nesting limit (128), so this cannot overflow
/// the stack.
struct Tally<'c> {
    census: &'c mut Census,
}

impl<'de> DeserializeSeed<'de> for Tally<'_> {
    type Value = u64;
    fn deserialize<D: Deserializer<'de>>(self, de: D) -> Result<u64, D::Error> {
        de.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Tally<'_> {
    type Value = u64;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<u64, A::Error> {
        self.census.values += 1;
        let mut elements = 0;
        while seq
            .next_element_seed(Tally {
                census: &mut *self.census,
            })?
            .is_some()
        {
            elements += 1;
        }
        Ok(elements)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<u64, A::Error> {
        self.census.values += 1;
        self.census.objects += 1;
        while map.next_key::<IgnoredAny>()?.is_some() {
            map.next_value_seed(Tally {
                census: &mut *self.census,
            })?;
        }
        Ok(0)
    }
    fn visit_bool<E: de::Error>(self, _: bool) -> Result<u64, E> {
        self.scalar()
    }
    fn visit_i64<E: de::Error>(self, _: i64) -> Result<u64, E> {
        self.scalar()
    }
    fn visit_u64<E: de::Error>(self, _: u64) -> Result<u64, E> {
        self.scalar()
    }
    fn visit_f64<E: de::Error>(self, _: f64) -> Result<u64, E> {
        self.scalar()
    }
    fn visit_str<E: de::Error>(self, _: &str) -> Result<u64, E> {
        self.scalar()
    }
    fn visit_unit<E: de::Error>(self) -> Result<u64, E> {
        self.scalar()
    }
}

impl Tally<'_> {
    fn scalar<E>(self) -> Result<u64, E> {
        self.census.values += 1;
        Ok(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn census_counts_without_building() {
        let census =
            Census::take(br#"{"nodes": [{}, {"children": [0, 1]}], "images": [{}], "x": null}"#)
                .unwrap();
        assert_eq!(census.nodes, 2);
        assert_eq!(census.images, 1);
        assert_eq!(census.objects, 4);
        // root, nodes array, 2 nodes, children array, 2 numbers, images
        // array, 1 image, null.
        assert_eq!(census.values, 10);
        assert!(Census::take(b"[1]").is_err());
        assert!(Census::take(b"{} trailing").is_err());
        let deep = format!("{{\"a\": {}{}}}", "[".repeat(100_000), "]".repeat(100_000));
        assert!(Census::take(deep.as_bytes()).is_err());
    }
}
