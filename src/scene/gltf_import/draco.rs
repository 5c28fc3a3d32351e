//! `KHR_draco_mesh_compression`: primitives whose indices and attributes
//! are one Draco stream in a buffer view. Each stream is decoded here
//! (draco-oxide's decoder, a Rust port of Google's reference decoder,
//! which dequantizes positions and texture coordinates and undoes the
//! octahedral normal encoding), and every accessor the extension names is
//! given a buffer of its own with the decoded values in the accessor's
//! declared type, so the accessors are then checked and read like any
//! other (`accessors`).
//!
//! The extension's rules (KHR_draco_mesh_compression, "Conformance"): the
//! extension's `attributes` map a primitive attribute's semantic to the
//! Draco attribute's unique id; the accessors keep their `count`,
//! `componentType` and `type`, which the decoded data must match; the
//! decoded connectivity is the primitive's `indices`; only triangles are
//! compressed.

use draco_oxide_core::attribute::ComponentDataType;
use gltf::json::accessor::{ComponentType, Type};
use gltf::json::validation::Checked;
use serde_json::Value;
use std::borrow::Cow;

const EXTENSION: &str = "KHR_draco_mesh_compression";

/// The accessors Draco-compressed primitives fill: their data comes from
/// the stream, so they may have no `bufferView` (which gltf-json's
/// validation would report as missing).
pub(super) fn filled_accessors(root: &gltf::json::Root) -> std::collections::HashSet<usize> {
    let mut filled = std::collections::HashSet::new();
    for primitive in root.meshes.iter().flat_map(|m| &m.primitives) {
        let compressed = primitive
            .extensions
            .as_ref()
            .is_some_and(|e| e.others.contains_key(EXTENSION));
        if compressed {
            filled.extend(primitive.indices.map(|i| i.value()));
            filled.extend(primitive.attributes.values().map(|a| a.value()));
        }
    }
    filled
}

/// One accessor's decoded bytes.
struct Decoded {
    accessor: usize,
    bytes: Vec<u8>,
}

/// Decodes every Draco-compressed primitive of `root`, appends a buffer
/// and a buffer view per decoded accessor, and points the accessors at
/// them. The decoded bytes are added to `used_bytes` and held to `limit`.
pub(super) fn decode_primitives(
    root: &mut gltf::json::Root,
    buffers: &mut Vec<Cow<'_, [u8]>>,
    used_bytes: &mut u64,
    limits: &crate::scene::limits::Limits,
) -> Result<(), String> {
    let limit = limits.bytes;
    let mut decoded = Vec::new();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let Some(value) = primitive
                .extensions
                .as_ref()
                .and_then(|e| e.others.get(EXTENSION))
            else {
                continue;
            };
            let at = |problem: String| format!("mesh {m} primitive {p}: {EXTENSION}: {problem}");
            decoded.extend(decode_primitive(root, primitive, value, buffers, limits).map_err(at)?);
        }
    }
    for Decoded { accessor, bytes } in decoded {
        *used_bytes = used_bytes.saturating_add(bytes.len() as u64);
        if *used_bytes > limit {
            return Err(format!(
                "accessor {accessor}: {}",
                crate::scene::limits::exceeded(
                    "the file plus its decoded Draco data",
                    format!("{used_bytes} bytes"),
                    "bytes",
                    limit,
                )
            ));
        }
        let length = bytes.len() as u64;
        let buffer = buffers.len() as u32;
        buffers.push(Cow::Owned(bytes));
        root.buffers.push(gltf::json::Buffer {
            byte_length: length.into(),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let view = root.buffer_views.len() as u32;
        root.buffer_views.push(gltf::json::buffer::View {
            buffer: gltf::json::Index::new(buffer),
            byte_length: length.into(),
            byte_offset: None,
            byte_stride: None,
            name: None,
            target: None,
            extensions: None,
            extras: Default::default(),
        });
        let accessor = &mut root.accessors[accessor];
        accessor.buffer_view = Some(gltf::json::Index::new(view));
        accessor.byte_offset = None;
        accessor.sparse = None;
    }
    Ok(())
}

/// Decodes one primitive's stream into the bytes of its indices and of
/// each attribute the extension names.
fn decode_primitive(
    root: &gltf::json::Root,
    primitive: &gltf::json::mesh::Primitive,
    value: &Value,
    buffers: &[Cow<'_, [u8]>],
    limits: &crate::scene::limits::Limits,
) -> Result<Vec<Decoded>, String> {
    if !matches!(
        primitive.mode,
        Checked::Valid(gltf::json::mesh::Mode::Triangles)
    ) {
        return Err("the primitive's mode is not TRIANGLES, the only one Draco compresses".into());
    }
    let view_index = value
        .get("bufferView")
        .and_then(Value::as_u64)
        .ok_or("`bufferView` is missing or not an index")?;
    let stream = view_bytes(root, buffers, view_index)?;
    let indices = primitive
        .indices
        .ok_or("the primitive has no `indices`, which must receive Draco's triangles")?
        .value();
    let count = |a: usize| root.accessors.get(a).map_or(0, |a| a.count.0);
    let declared = super::draco_counts::Declared {
        indices: count(indices),
        points: primitive
            .attributes
            .values()
            .map(|a| count(a.value()))
            .max()
            .unwrap_or(0),
    };
    super::draco_counts::check(stream, &declared, limits)?;
    let mesh = decode_stream(stream)?;

    let mut decoded = Vec::new();
    decoded.push(Decoded {
        accessor: indices,
        bytes: index_bytes(root, indices, &mesh.faces)?,
    });

    let names = value
        .get("attributes")
        .and_then(Value::as_object)
        .ok_or("`attributes` is missing or not an object")?;
    for (semantic, id) in names {
        let shown = super::hostile::abbreviate(semantic);
        let id = id
            .as_u64()
            .ok_or_else(|| format!("attribute {shown}: the id is not an integer"))?;
        let accessor = primitive
            .attributes
            .iter()
            .find(|(s, _)| matches!(s, Checked::Valid(s) if s.to_string() == *semantic))
            .map(|(_, a)| a.value())
            .ok_or_else(|| {
                format!("attribute {shown}: the primitive has no attribute of that name")
            })?;
        let attribute = mesh
            .attributes
            .iter()
            .find(|a| a.get_id().as_usize() as u64 == id)
            .ok_or_else(|| format!("attribute {shown}: the Draco stream has no attribute {id}"))?;
        let bytes = attribute_bytes(root, accessor, attribute).map_err(|e| {
            format!("attribute {shown} (Draco attribute {id}, accessor {accessor}): {e}")
        })?;
        decoded.push(Decoded { accessor, bytes });
    }
    Ok(decoded)
}

/// The Draco mesh of `stream`; a panic in the decoder (a malformed stream
/// it did not anticipate, e.g. an edgebreaker count past any capacity,
/// found by fuzzing) is reported as corrupt data, its own text kept off
/// stderr ([`super::hostile::guarded`]).
fn decode_stream(stream: &[u8]) -> Result<draco_oxide_core::mesh::Mesh, String> {
    let result = super::hostile::guarded(|| draco_oxide_decoder::decode_mesh(stream));
    match result {
        Ok(Ok(mesh)) => Ok(mesh),
        Ok(Err(e)) => Err(format!("the Draco stream is corrupt or unsupported ({e})")),
        Err(_) => Err("the Draco stream is corrupt (the decoder failed on it)".into()),
    }
}

/// The bytes of buffer view `index`, checked against its buffer.
fn view_bytes<'b>(
    root: &gltf::json::Root,
    buffers: &'b [Cow<'_, [u8]>],
    index: u64,
) -> Result<&'b [u8], String> {
    let view = usize::try_from(index)
        .ok()
        .and_then(|i| root.buffer_views.get(i))
        .ok_or_else(|| format!("buffer view {index} does not exist"))?;
    let offset = view.byte_offset.map_or(0, |o| o.0);
    let end = offset.checked_add(view.byte_length.0);
    buffers
        .get(view.buffer.value())
        .and_then(|b| b.get(usize::try_from(offset).ok()?..usize::try_from(end?).ok()?))
        .ok_or_else(|| format!("buffer view {index} is not inside its buffer"))
}

/// The accessor `index` (its existence was validated).
fn accessor(root: &gltf::json::Root, index: usize) -> Result<&gltf::json::Accessor, String> {
    root.accessors
        .get(index)
        .ok_or_else(|| format!("accessor {index} does not exist"))
}

/// Draco's triangles as the indices accessor's declared type.
fn index_bytes(
    root: &gltf::json::Root,
    index: usize,
    faces: &[[draco_oxide_core::types::PointIdx; 3]],
) -> Result<Vec<u8>, String> {
    let a = accessor(root, index)?;
    let fail = |p: String| format!("indices (accessor {index}): {p}");
    let declared = a.count.0;
    if faces.len() as u64 * 3 != declared {
        return Err(fail(format!(
            "Draco decoded {} triangles, but the accessor declares {declared} indices",
            faces.len()
        )));
    }
    let size = match a.component_type {
        Checked::Valid(t) => t.0.size(),
        Checked::Invalid => return Err(fail("its componentType is invalid".into())),
    };
    let max = if size >= 4 {
        u64::from(u32::MAX)
    } else {
        (1u64 << (8 * size)) - 1
    };
    let mut bytes = Vec::with_capacity(faces.len() * 3 * size);
    for &corner in faces.iter().flatten() {
        let i = usize::from(corner) as u64;
        if i > max {
            return Err(fail(format!("index {i} does not fit in {size} bytes")));
        }
        bytes.extend_from_slice(&(i as u32).to_le_bytes()[..size]);
    }
    Ok(bytes)
}

/// A Draco attribute's values, point by point, as the accessor declares
/// them (same component type and count, as the extension requires).
fn attribute_bytes(
    root: &gltf::json::Root,
    index: usize,
    attribute: &draco_oxide_core::attribute::Attribute,
) -> Result<Vec<u8>, String> {
    let a = accessor(root, index)?;
    let (Checked::Valid(component), Checked::Valid(kind)) = (a.component_type, a.type_) else {
        return Err("the accessor's componentType or type is invalid".into());
    };
    let expected = match component.0 {
        ComponentType::I8 => ComponentDataType::I8,
        ComponentType::U8 => ComponentDataType::U8,
        ComponentType::I16 => ComponentDataType::I16,
        ComponentType::U16 => ComponentDataType::U16,
        ComponentType::U32 => ComponentDataType::U32,
        ComponentType::F32 => ComponentDataType::F32,
    };
    let found = attribute.get_component_type();
    if found != expected {
        return Err(format!(
            "Draco decoded {found:?} components, but the accessor declares {:?}",
            component.0
        ));
    }
    let components = match kind {
        Type::Scalar => 1,
        Type::Vec2 => 2,
        Type::Vec3 => 3,
        Type::Vec4 => 4,
        Type::Mat2 => 4,
        Type::Mat3 => 9,
        Type::Mat4 => 16,
    };
    if attribute.get_num_components() != components {
        return Err(format!(
            "Draco decoded {} components per value, but the accessor's type {kind:?} has {components}",
            attribute.get_num_components()
        ));
    }
    let points = attribute.len();
    if points as u64 != a.count.0 {
        return Err(format!(
            "Draco decoded {points} values, but the accessor declares {}",
            a.count.0
        ));
    }
    let size = components * found.size();
    let data = attribute.get_data_as_bytes();
    let map = attribute.point_map_as_slice();
    let mut bytes = Vec::with_capacity(points * size);
    for point in 0..points {
        let value = map.map_or(point, |m| usize::from(m[point]));
        let chunk = data
            .get(value * size..(value + 1) * size)
            .ok_or("the Draco stream maps a point to a value it does not have")?;
        bytes.extend_from_slice(chunk);
    }
    Ok(bytes)
}
