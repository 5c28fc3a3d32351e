//! `EXT_meshopt_compression` and `KHR_meshopt_compression`: buffer views
//! whose bytes are meshoptimizer-encoded. Each such view is decoded here,
//! into a buffer of its own, and the view is pointed at it, so every
//! accessor reading it is then checked and read like any other
//! (`accessors`). The decoder is meshoptimizer's own
//! (`meshopt_decodeVertexBuffer`, `…IndexBuffer`, `…IndexSequence` and the
//! filters), which is written to be safe on untrusted input; what it
//! asserts instead of checking (vertex sizes, index counts, filter
//! strides) is checked here first.
//!
//! The extensions' JSON (EXT_meshopt_compression, "Specifying compressed
//! views"): `buffer`, `byteOffset`, `byteLength` locate the compressed
//! bytes; `byteStride` and `count` give the decoded size; `mode` is
//! `ATTRIBUTES`, `TRIANGLES` or `INDICES`; `filter` is `NONE`,
//! `OCTAHEDRAL`, `QUATERNION`, `EXPONENTIAL` (and, in the KHR version,
//! `COLOR`). A buffer marked `fallback: true` without a `uri` holds no
//! data of its own (`is_placeholder`).

use serde_json::Value;
use std::borrow::Cow;

/// The two names of the extension, with whether the `COLOR` filter (added
/// by the KHR version) is allowed.
const EXTENSIONS: [(&str, bool); 2] = [
    ("KHR_meshopt_compression", true),
    ("EXT_meshopt_compression", false),
];

/// Whether a buffer is a meshopt fallback buffer without data: its views
/// are all compressed ones, decoded from other buffers, so it is not read.
pub(super) fn is_placeholder(buffer: &gltf::Buffer) -> bool {
    let fallback = |name: &str| {
        buffer
            .extension_value(name)
            .and_then(|v| v.get("fallback"))
            .and_then(Value::as_bool)
            == Some(true)
    };
    matches!(buffer.source(), gltf::buffer::Source::Bin)
        && EXTENSIONS.iter().any(|(name, _)| fallback(name))
}

/// What to do with one compressed view.
struct Compressed {
    buffer: usize,
    offset: usize,
    length: usize,
    stride: usize,
    count: usize,
    mode: Mode,
    filter: Filter,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mode {
    Attributes,
    Triangles,
    Indices,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Filter {
    None,
    Octahedral,
    Quaternion,
    Exponential,
    Color,
}

/// Decodes every compressed buffer view of `root` into a new buffer
/// appended to `buffers`, and points the view at it. The decoded bytes are
/// added to `used_bytes` and held to `limit` before anything is allocated.
pub(super) fn decode_views(
    root: &mut gltf::json::Root,
    buffers: &mut Vec<Cow<'_, [u8]>>,
    used_bytes: &mut u64,
    limit: u64,
) -> Result<(), String> {
    for index in 0..root.buffer_views.len() {
        let view = &root.buffer_views[index];
        let Some(others) = view.extensions.as_ref().map(|e| &e.others) else {
            continue;
        };
        let Some((name, value, color_allowed)) = EXTENSIONS
            .iter()
            .find_map(|&(name, color)| others.get(name).map(|v| (name, v, color)))
        else {
            continue;
        };
        let at = |problem: String| format!("buffer view {index}: {name}: {problem}");
        let compressed = parse(value, color_allowed).map_err(at)?;
        let declared = view.byte_length.0;
        let decoded_len = compressed
            .count
            .checked_mul(compressed.stride)
            .filter(|&n| n as u64 <= declared)
            .ok_or_else(|| {
                at(format!(
                    "{} elements of {} bytes do not fit in the view's byteLength {declared}",
                    compressed.count, compressed.stride
                ))
            })?;
        *used_bytes = used_bytes.saturating_add(declared);
        if *used_bytes > limit {
            return Err(at(crate::scene::limits::exceeded(
                "the file plus its decoded buffers",
                format!("{used_bytes} bytes"),
                "bytes",
                limit,
            )));
        }
        let source = buffers
            .get(compressed.buffer)
            .and_then(|b| {
                b.get(compressed.offset..compressed.offset.checked_add(compressed.length)?)
            })
            .ok_or_else(|| {
                at(format!(
                    "bytes {}.. +{} are not inside buffer {}",
                    compressed.offset, compressed.length, compressed.buffer
                ))
            })?;
        let mut bytes = decode(source, &compressed).map_err(at)?;
        debug_assert_eq!(bytes.len(), decoded_len);
        // The rest of the view (if it declares more than it decodes) reads
        // as zeros.
        bytes.resize(declared as usize, 0);
        let new_buffer = buffers.len();
        buffers.push(Cow::Owned(bytes));
        root.buffers.push(gltf::json::Buffer {
            byte_length: declared.into(),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let view = &mut root.buffer_views[index];
        view.buffer = gltf::json::Index::new(new_buffer as u32);
        view.byte_offset = None;
    }
    Ok(())
}

/// The extension object of one view.
fn parse(value: &Value, color_allowed: bool) -> Result<Compressed, String> {
    let number = |key: &str, default: Option<u64>| -> Result<usize, String> {
        match value.get(key) {
            None => default
                .map(|d| d as usize)
                .ok_or(format!("`{key}` is missing")),
            Some(v) => v
                .as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or(format!("`{key}` is not a non-negative integer")),
        }
    };
    let text = |key: &str, default: Option<&'static str>| -> Result<String, String> {
        match value.get(key) {
            None => default
                .map(str::to_string)
                .ok_or(format!("`{key}` is missing")),
            Some(v) => v
                .as_str()
                .map(|s| super::hostile::abbreviate(s).into_owned())
                .ok_or(format!("`{key}` is not a string")),
        }
    };
    let mode = match text("mode", None)?.as_str() {
        "ATTRIBUTES" => Mode::Attributes,
        "TRIANGLES" => Mode::Triangles,
        "INDICES" => Mode::Indices,
        other => return Err(format!("unknown mode \"{other}\"")),
    };
    let filter = match text("filter", Some("NONE"))?.as_str() {
        "NONE" => Filter::None,
        "OCTAHEDRAL" => Filter::Octahedral,
        "QUATERNION" => Filter::Quaternion,
        "EXPONENTIAL" => Filter::Exponential,
        "COLOR" if color_allowed => Filter::Color,
        other => return Err(format!("unknown filter \"{other}\"")),
    };
    let compressed = Compressed {
        buffer: number("buffer", None)?,
        offset: number("byteOffset", Some(0))?,
        length: number("byteLength", None)?,
        stride: number("byteStride", None)?,
        count: number("count", None)?,
        mode,
        filter,
    };
    check_shape(&compressed)?;
    Ok(compressed)
}

/// What meshoptimizer asserts rather than checks: the vertex size (a
/// multiple of 4 up to 256), index sizes of 2 or 4 bytes, whole triangles,
/// and the strides each filter is defined for (the extension's "Filters").
fn check_shape(c: &Compressed) -> Result<(), String> {
    let stride = c.stride;
    match c.mode {
        Mode::Attributes if stride == 0 || stride > 256 || !stride.is_multiple_of(4) => {
            return Err(format!(
                "byteStride {stride}: ATTRIBUTES need a multiple of 4 from 4 to 256"
            ));
        }
        Mode::Triangles | Mode::Indices if stride != 2 && stride != 4 => {
            return Err(format!(
                "byteStride {stride}: {:?} need 2 or 4 bytes per index",
                c.mode
            ));
        }
        Mode::Triangles if !c.count.is_multiple_of(3) => {
            return Err(format!(
                "count {} is not a whole number of triangles",
                c.count
            ));
        }
        _ => {}
    }
    let filter_fits = match c.filter {
        Filter::None => true,
        Filter::Octahedral | Filter::Color => stride == 4 || stride == 8,
        Filter::Quaternion => stride == 8,
        Filter::Exponential => stride.is_multiple_of(4),
    };
    if c.filter != Filter::None && c.mode != Mode::Attributes {
        return Err(format!("filter {:?} on {:?} data", c.filter, c.mode));
    }
    if !filter_fits {
        return Err(format!(
            "filter {:?} is not defined for byteStride {stride}",
            c.filter
        ));
    }
    Ok(())
}

/// Decodes one view's bytes (shape already checked) to `count · stride`
/// bytes.
fn decode(source: &[u8], c: &Compressed) -> Result<Vec<u8>, String> {
    let failed = |e: meshopt::Error| format!("the compressed data is corrupt ({e})");
    let mut bytes = match (c.mode, c.stride) {
        (Mode::Attributes, stride) => decode_vertices(source, c.count, stride).map_err(failed)?,
        (Mode::Triangles, 2) => to_bytes(
            meshopt::encoding::decode_index_buffer::<u16>(source, c.count).map_err(failed)?,
        ),
        (Mode::Triangles, _) => to_bytes(
            meshopt::encoding::decode_index_buffer::<u32>(source, c.count).map_err(failed)?,
        ),
        (Mode::Indices, 2) => to_bytes(
            meshopt::encoding::decode_index_sequence::<u16>(source, c.count).map_err(failed)?,
        ),
        (Mode::Indices, _) => to_bytes(
            meshopt::encoding::decode_index_sequence::<u32>(source, c.count).map_err(failed)?,
        ),
    };
    apply_filter(&mut bytes, c.filter, c.stride);
    Ok(bytes)
}

/// Little-endian bytes of decoded indices.
fn to_bytes<T: IndexBytes>(values: Vec<T>) -> Vec<u8> {
    values.into_iter().flat_map(IndexBytes::le_bytes).collect()
}

trait IndexBytes {
    fn le_bytes(self) -> Vec<u8>;
}

impl IndexBytes for u16 {
    fn le_bytes(self) -> Vec<u8> {
        self.to_le_bytes().to_vec()
    }
}

impl IndexBytes for u32 {
    fn le_bytes(self) -> Vec<u8> {
        self.to_le_bytes().to_vec()
    }
}

/// One vertex of `N` bytes: meshoptimizer's vertex size is the element
/// type's size, so each allowed stride is its own type.
#[derive(Clone, Copy)]
struct Vertex<const N: usize>([u8; N]);

impl<const N: usize> Default for Vertex<N> {
    fn default() -> Self {
        Vertex([0; N])
    }
}

fn decode_sized<const N: usize>(source: &[u8], count: usize) -> meshopt::Result<Vec<u8>> {
    let vertices = meshopt::encoding::decode_vertex_buffer::<Vertex<N>>(source, count)?;
    Ok(vertices.into_iter().flat_map(|v| v.0).collect())
}

/// `meshopt_decodeVertexBuffer` with a vertex size known only at run time
/// (a multiple of 4 from 4 to 256, checked before).
fn decode_vertices(source: &[u8], count: usize, stride: usize) -> meshopt::Result<Vec<u8>> {
    macro_rules! sizes {
        ($($n:literal)*) => {
            match stride {
                $($n => decode_sized::<$n>(source, count),)*
                _ => unreachable!("vertex size {stride} was checked"),
            }
        };
    }
    sizes!(4 8 12 16 20 24 28 32 36 40 44 48 52 56 60 64 68 72 76 80 84 88 92 96
        100 104 108 112 116 120 124 128 132 136 140 144 148 152 156 160 164 168 172
        176 180 184 188 192 196 200 204 208 212 216 220 224 228 232 236 240 244 248
        252 256)
}

/// The filter's inverse, in place, on decoded elements of `stride` bytes
/// (strides checked before).
fn apply_filter(bytes: &mut [u8], filter: Filter, stride: usize) {
    match (filter, stride) {
        (Filter::None, _) => {}
        (Filter::Octahedral, 4) => with_quads::<i8>(bytes, meshopt::encoding::decode_filter_oct),
        (Filter::Octahedral, _) => with_quads::<i16>(bytes, meshopt::encoding::decode_filter_oct),
        (Filter::Color, 4) => with_quads::<u8>(bytes, meshopt::encoding::decode_filter_color),
        (Filter::Color, _) => with_quads::<u16>(bytes, meshopt::encoding::decode_filter_color),
        (Filter::Quaternion, _) => with_quads::<i16>(bytes, meshopt::encoding::decode_filter_quat),
        (Filter::Exponential, _) => {
            // Each 32-bit component is decoded on its own, whatever the
            // stride, so the view is filtered as single components.
            let mut words: Vec<[u32; 1]> = bytes
                .chunks_exact(4)
                .map(|c| [u32::from_le_bytes([c[0], c[1], c[2], c[3]])])
                .collect();
            meshopt::encoding::decode_filter_exp(&mut words);
            for (chunk, [w]) in bytes.chunks_exact_mut(4).zip(words) {
                chunk.copy_from_slice(&w.to_le_bytes());
            }
        }
    }
}

/// Runs `filter` over the bytes read as 4-component elements of `C`
/// (little-endian), and writes the result back.
fn with_quads<C: Component>(bytes: &mut [u8], filter: fn(&mut [[C; 4]])) {
    let size = std::mem::size_of::<C>();
    let mut quads: Vec<[C; 4]> = bytes
        .chunks_exact(4 * size)
        .map(|q| std::array::from_fn(|i| C::read(&q[i * size..(i + 1) * size])))
        .collect();
    filter(&mut quads);
    for (chunk, quad) in bytes.chunks_exact_mut(4 * size).zip(quads) {
        for (i, c) in quad.into_iter().enumerate() {
            c.write(&mut chunk[i * size..(i + 1) * size]);
        }
    }
}

/// A filter component and its little-endian bytes.
trait Component: Copy {
    fn read(bytes: &[u8]) -> Self;
    fn write(self, bytes: &mut [u8]);
}

macro_rules! component {
    ($($t:ty)*) => {$(
        impl Component for $t {
            fn read(bytes: &[u8]) -> Self {
                <$t>::from_le_bytes(bytes.try_into().unwrap_or_default())
            }
            fn write(self, bytes: &mut [u8]) {
                bytes.copy_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
component!(i8 u8 i16 u16);

#[cfg(test)]
mod tests {
    use super::*;

    fn compressed(mode: Mode, filter: Filter, stride: usize, count: usize) -> Compressed {
        Compressed {
            buffer: 0,
            offset: 0,
            length: 0,
            stride,
            count,
            mode,
            filter,
        }
    }

    /// Round trip through meshoptimizer's encoder: every mode decodes to
    /// the bytes that were encoded.
    #[test]
    fn encoded_views_decode_to_their_bytes() {
        let vertices: Vec<[u8; 12]> = (0..50u8).map(|i| [i; 12]).collect();
        let encoded = meshopt::encoding::encode_vertex_buffer(&vertices).unwrap();
        let c = compressed(Mode::Attributes, Filter::None, 12, 50);
        assert_eq!(decode(&encoded, &c).unwrap(), vertices.concat());
        let triangles: Vec<u32> = (0..30).map(|i| (i * 7) % 20).collect();
        let encoded = meshopt::encoding::encode_index_buffer(&triangles, 20).unwrap();
        let c = compressed(Mode::Triangles, Filter::None, 4, 30);
        assert_eq!(decode(&encoded, &c).unwrap(), to_bytes(triangles.clone()));
        let encoded = meshopt::encoding::encode_index_sequence(&triangles, 20).unwrap();
        let c = compressed(Mode::Indices, Filter::None, 2, 30);
        let as_u16: Vec<u16> = triangles.iter().map(|&i| i as u16).collect();
        assert_eq!(decode(&encoded, &c).unwrap(), to_bytes(as_u16));
    }

    #[test]
    fn shapes_meshoptimizer_asserts_on_are_refused() {
        for (c, expect) in [
            (
                compressed(Mode::Attributes, Filter::None, 6, 3),
                "multiple of 4",
            ),
            (
                compressed(Mode::Attributes, Filter::None, 260, 3),
                "multiple of 4",
            ),
            (
                compressed(Mode::Triangles, Filter::None, 2, 4),
                "whole number",
            ),
            (compressed(Mode::Indices, Filter::None, 3, 4), "2 or 4"),
            (
                compressed(Mode::Attributes, Filter::Quaternion, 4, 1),
                "not defined",
            ),
            (
                compressed(Mode::Indices, Filter::Octahedral, 2, 1),
                "filter",
            ),
        ] {
            let e = check_shape(&c).unwrap_err();
            assert!(e.contains(expect), "{e}");
        }
    }

    #[test]
    fn garbage_is_an_error() {
        let c = compressed(Mode::Attributes, Filter::None, 16, 100);
        assert!(
            decode(&[0xa0, 1, 2, 3, 4], &c)
                .unwrap_err()
                .contains("corrupt")
        );
        let c = compressed(Mode::Triangles, Filter::None, 4, 99);
        assert!(decode(&[0xe1, 9, 9], &c).unwrap_err().contains("corrupt"));
    }
}
