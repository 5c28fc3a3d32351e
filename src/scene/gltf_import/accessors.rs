//! Accessors and primitives: every accessor is checked against its buffer
//! view and buffer (types, counts, offsets and strides, with
//! overflow-checked arithmetic) before the `gltf` crate's reader touches
//! it, because that reader slices and indexes without checking. Only then
//! is anything allocated from its count.
//!
//! Vertex attributes are decoded here ([`read_attribute`]), not by the
//! reader's `read_positions` (which takes every component for an `f32`):
//! with `KHR_mesh_quantization` a position may be a (normalized) integer,
//! a normal or tangent a normalized one, decoded as the extension says
//! (signed: `max(c / (2ⁿ⁻¹ − 1), −1)`, unsigned: `c / (2ⁿ − 1)`).

use glam::{DVec2, DVec3, DVec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::{Mode, Semantic};
use std::borrow::Cow;

/// What an accessor is read as, and therefore which types it may have.
#[derive(Clone, Copy)]
pub(super) enum Usage {
    Position,
    Normal,
    Tangent,
    Index,
    /// `TEXCOORD_n`: VEC2 of FLOAT, or of normalized UNSIGNED_BYTE /
    /// UNSIGNED_SHORT (glTF 2.0 §3.7.2.1).
    TexCoord,
    /// `COLOR_0`: VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE /
    /// UNSIGNED_SHORT (glTF 2.0 §3.7.2.1).
    Color,
}

impl Usage {
    fn name(self) -> &'static str {
        match self {
            Usage::Position => "POSITION",
            Usage::Normal => "NORMAL",
            Usage::Tangent => "TANGENT",
            Usage::Index => "indices",
            Usage::TexCoord => "TEXCOORD",
            Usage::Color => "COLOR_0",
        }
    }

    /// The types the reader can decode for this usage; the `gltf` reader
    /// misreads or panics (`unreachable!`) on anything else. With
    /// `quantized` (the file uses `KHR_mesh_quantization`) also the
    /// extension's integer types: any 8- or 16-bit integer for POSITION
    /// (normalized or not), normalized signed ones for NORMAL and TANGENT.
    fn accepts(
        self,
        data_type: DataType,
        dimensions: Dimensions,
        normalized: bool,
        quantized: bool,
    ) -> bool {
        let signed_normalized = normalized && matches!(data_type, DataType::I8 | DataType::I16);
        let small_integer = matches!(
            data_type,
            DataType::I8 | DataType::U8 | DataType::I16 | DataType::U16
        );
        match self {
            Usage::Position => {
                dimensions == Dimensions::Vec3
                    && (data_type == DataType::F32 || (quantized && small_integer))
            }
            Usage::Normal => {
                dimensions == Dimensions::Vec3
                    && (data_type == DataType::F32 || (quantized && signed_normalized))
            }
            Usage::Tangent => {
                dimensions == Dimensions::Vec4
                    && (data_type == DataType::F32 || (quantized && signed_normalized))
            }
            Usage::Index => {
                matches!(data_type, DataType::U8 | DataType::U16 | DataType::U32)
                    && dimensions == Dimensions::Scalar
            }
            Usage::Color => {
                matches!(dimensions, Dimensions::Vec3 | Dimensions::Vec4)
                    && (data_type == DataType::F32
                        || (normalized && matches!(data_type, DataType::U8 | DataType::U16)))
            }
            Usage::TexCoord => {
                dimensions == Dimensions::Vec2
                    && (data_type == DataType::F32
                        || (normalized && matches!(data_type, DataType::U8 | DataType::U16)))
            }
        }
    }

    fn expected(self, quantized: bool) -> &'static str {
        match (self, quantized) {
            (Usage::Position, false) | (Usage::Normal, false) => {
                "VEC3 of FLOAT (integer types need KHR_mesh_quantization)"
            }
            (Usage::Position, true) => {
                "VEC3 of FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (KHR_mesh_quantization)"
            }
            (Usage::Normal, true) => {
                "VEC3 of FLOAT, or normalized BYTE or SHORT (KHR_mesh_quantization)"
            }
            (Usage::Tangent, false) => "VEC4 of FLOAT (integer types need KHR_mesh_quantization)",
            (Usage::Tangent, true) => {
                "VEC4 of FLOAT, or normalized BYTE or SHORT (KHR_mesh_quantization)"
            }
            (Usage::Index, _) => "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
            (Usage::TexCoord, _) => "VEC2 of FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT",
            (Usage::Color, _) => {
                "VEC3 or VEC4 of FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT"
            }
        }
    }
}

/// Checks that the `gltf` reader can read `accessor` for `usage` without
/// going out of bounds: right types, 1 to `max_count` elements, and every
/// byte it will touch inside its buffer view and buffer (sparse parts
/// included). Errors name the accessor.
///
/// `max_count` bounds accessors whose elements are not all backed by data
/// (sparse accessors without a buffer view are materialized from zeros);
/// callers pass what the limits or a sibling accessor allow.
pub(super) fn check_accessor(
    accessor: &gltf::Accessor,
    usage: Usage,
    max_count: usize,
    buffers: &[Cow<[u8]>],
    quantized: bool,
) -> Result<(), String> {
    let fail = |problem: String| {
        format!(
            "accessor {} ({}): {problem}",
            accessor.index(),
            usage.name()
        )
    };
    let (data_type, dimensions) = (accessor.data_type(), accessor.dimensions());
    if !usage.accepts(data_type, dimensions, accessor.normalized(), quantized) {
        let normalized = if accessor.normalized() {
            "normalized "
        } else {
            ""
        };
        return Err(fail(format!(
            "has type {dimensions:?} of {normalized}{data_type:?}, expected {}",
            usage.expected(quantized)
        )));
    }
    let element = accessor.size();
    let count = accessor.count();
    if count == 0 {
        return Err(fail("has count 0".into()));
    }
    // The reader counts elements in a u32.
    if count > max_count || u32::try_from(count).is_err() {
        return Err(fail(format!(
            "has count {count}, more than the {max_count} it may have here"
        )));
    }
    if let Some(view) = accessor.view() {
        check_range(&view, accessor.offset(), count, element, buffers).map_err(fail)?;
    }
    match accessor.sparse() {
        Some(sparse) => check_sparse(&sparse, count, element, buffers).map_err(fail),
        None if accessor.view().is_none() => {
            Err(fail("has neither a buffer view nor sparse data".into()))
        }
        None => Ok(()),
    }
}

fn check_sparse(
    sparse: &gltf::accessor::sparse::Sparse,
    count: usize,
    element: usize,
    buffers: &[Cow<[u8]>],
) -> Result<(), String> {
    let sparse_count = sparse.count();
    if sparse_count == 0 || sparse_count > count {
        return Err(format!(
            "has sparse count {sparse_count}, expected 1 to {count}"
        ));
    }
    let indices = sparse.indices();
    check_range(
        &indices.view(),
        indices.offset(),
        sparse_count,
        indices.index_type().size(),
        buffers,
    )
    .map_err(|p| format!("sparse indices: {p}"))?;
    check_sparse_indices(&indices, sparse_count, count, buffers)?;
    let values = sparse.values();
    check_range(
        &values.view(),
        values.offset(),
        sparse_count,
        element,
        buffers,
    )
    .map_err(|p| format!("sparse values: {p}"))
}

/// The sparse indices (tightly packed, in range: checked before) must
/// each name an element of the accessor and strictly increase (glTF 2.0,
/// "Sparse Accessors"); an index past `count` would otherwise be dropped
/// without a word.
fn check_sparse_indices(
    indices: &gltf::accessor::sparse::Indices,
    sparse_count: usize,
    count: usize,
    buffers: &[Cow<[u8]>],
) -> Result<(), String> {
    let view = indices.view();
    let size = indices.index_type().size();
    let start = view.offset() + indices.offset();
    let bytes = &buffers[view.buffer().index()][start..start + sparse_count * size];
    let mut previous: Option<usize> = None;
    for (k, chunk) in bytes.chunks_exact(size).enumerate() {
        let index = match size {
            1 => chunk[0] as usize,
            2 => u16::from_le_bytes([chunk[0], chunk[1]]) as usize,
            _ => u32::from_le_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]) as usize,
        };
        if index >= count {
            return Err(format!(
                "sparse index {k} is {index}, past the accessor's {count} elements"
            ));
        }
        if previous.is_some_and(|p| index <= p) {
            return Err(format!(
                "sparse indices must strictly increase, but index {k} is {index} after {}",
                previous.unwrap_or(0)
            ));
        }
        previous = Some(index);
    }
    Ok(())
}

/// Checks `count ≥ 1` elements of `element` bytes, `offset` bytes into
/// `view`, at the view's stride, against the view and its buffer.
fn check_range(
    view: &gltf::buffer::View,
    offset: usize,
    count: usize,
    element: usize,
    buffers: &[Cow<[u8]>],
) -> Result<(), String> {
    let buffer = view.buffer().index();
    let buffer_len = buffers.get(buffer).map_or(0, |b| b.len());
    let view_fits = view
        .offset()
        .checked_add(view.length())
        .is_some_and(|end| end <= buffer_len);
    if !view_fits {
        return Err(format!(
            "buffer view {} (offset {}, length {}) does not fit in buffer {buffer} of {buffer_len} bytes",
            view.index(),
            view.offset(),
            view.length()
        ));
    }
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "buffer view {} has byteStride {stride}, smaller than the {element}-byte element",
            view.index()
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(element));
    match end {
        Some(end) if end <= view.length() => Ok(()),
        _ => Err(format!(
            "{count} elements of {element} bytes at offset {offset} with stride {stride} do not fit in buffer view {} of {} bytes",
            view.index(),
            view.length()
        )),
    }
}

/// A primitive's data in object space, before it becomes a mesh.
pub(super) struct RawPrimitive {
    pub positions: Vec<DVec3>,
    /// Unit normals, or zero where the file's normal had no length;
    /// `None` when the primitive has no `NORMAL`.
    pub normals: Option<Vec<DVec3>>,
    /// Unit tangents (the xyz of `TANGENT`), `None` when the primitive
    /// has none.
    pub tangents: Option<Vec<DVec3>>,
    /// `TANGENT`'s w, the bitangent's sign (±1; a normal map's frame is
    /// `B = w · N × T`), with `tangents`.
    pub bitangent_signs: Option<Vec<f64>>,
    /// `COLOR_0` as linear RGBA (VEC3: alpha 1), `None` without it.
    pub colors: Option<Vec<DVec4>>,
    pub indices: Vec<[u32; 3]>,
    /// `TEXCOORD_0` and `TEXCOORD_1` where present (empty sets stop the
    /// list: a missing set 0 with a set 1 keeps an empty set 0).
    pub tex_coords: Vec<Vec<DVec2>>,
}

/// Reads a primitive, or `None` if it draws points or lines. The vertex
/// and triangle budget was checked from the declared counts beforehand
/// (see `graph::check_cost`); `max_vertices` and `max_corners` are those
/// limits, which bound accessors without data behind every element.
/// `quantized`: the file uses `KHR_mesh_quantization` (integer attributes).
pub(super) fn read_primitive(
    primitive: &gltf::Primitive,
    buffers: &[Cow<[u8]>],
    max_vertices: usize,
    max_corners: usize,
    quantized: bool,
) -> Result<Option<RawPrimitive>, String> {
    let mode = primitive.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        return Ok(None);
    }
    let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(|b| &b[..]));

    let position_accessor = primitive
        .get(&Semantic::Positions)
        .ok_or("has no POSITION attribute")?;
    check_accessor(
        &position_accessor,
        Usage::Position,
        max_vertices,
        buffers,
        quantized,
    )?;
    let positions: Vec<DVec3> = read_attribute::<3>(&position_accessor, buffers)
        .ok_or_else(|| unreadable(&position_accessor, Usage::Position))?
        .into_iter()
        .map(DVec3::from)
        .collect();
    if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!(
            "accessor {} (POSITION): vertex {k} is not finite ({})",
            position_accessor.index(),
            positions[k]
        ));
    }
    let vertex_count = positions.len();
    // check_accessor bounded the count by u32::MAX.
    let vertex_limit = vertex_count as u32;

    let normals = match primitive.get(&Semantic::Normals) {
        None => None,
        Some(accessor) => Some(read_directions(
            &accessor,
            Usage::Normal,
            vertex_count,
            buffers,
            quantized,
            |a| read_attribute::<3>(a, buffers),
        )?),
    };

    let tangents = match primitive.get(&Semantic::Tangents) {
        None => None,
        Some(accessor) => Some(read_directions(
            &accessor,
            Usage::Tangent,
            vertex_count,
            buffers,
            quantized,
            |a| {
                read_attribute::<4>(a, buffers)
                    .map(|v| v.into_iter().map(|[x, y, z, _w]| [x, y, z]).collect())
            },
        )?),
    };

    // w after the xyz were checked and read: ±1 by glTF; its sign is all
    // that is used (a zero counts as +1).
    let bitangent_signs = match (&tangents, primitive.get(&Semantic::Tangents)) {
        (Some(_), Some(accessor)) => Some(
            read_attribute::<4>(&accessor, buffers)
                .ok_or_else(|| unreadable(&accessor, Usage::Tangent))?
                .into_iter()
                .map(|[.., w]| if w < 0.0 { -1.0 } else { 1.0 })
                .collect(),
        ),
        _ => None,
    };

    let mut tex_coords = Vec::new();
    for set in 0..2u32 {
        let Some(accessor) = primitive.get(&Semantic::TexCoords(set)) else {
            continue;
        };
        check_accessor(&accessor, Usage::TexCoord, max_vertices, buffers, quantized)?;
        if accessor.count() != vertex_count {
            return Err(format!(
                "accessor {} (TEXCOORD_{set}) has {} elements but POSITION has {vertex_count}",
                accessor.index(),
                accessor.count()
            ));
        }
        let uvs: Vec<DVec2> = reader
            .read_tex_coords(set)
            .map(|t| {
                t.into_f32()
                    .map(|[u, v]| DVec2::new(u.into(), v.into()))
                    .collect()
            })
            .unwrap_or_default();
        if uvs.len() != vertex_count || uvs.iter().any(|uv| !uv.is_finite()) {
            return Err(format!(
                "accessor {} (TEXCOORD_{set}): not {vertex_count} finite UVs",
                accessor.index()
            ));
        }
        tex_coords.resize(set as usize, Vec::new());
        tex_coords.push(uvs);
    }

    let colors = match primitive.get(&Semantic::Colors(0)) {
        None => None,
        Some(accessor) => {
            check_accessor(&accessor, Usage::Color, max_vertices, buffers, quantized)?;
            let colors: Vec<DVec4> = reader
                .read_colors(0)
                .map(|c| {
                    c.into_rgba_f32()
                        .map(|c| DVec4::from(c.map(f64::from)))
                        .collect()
                })
                .unwrap_or_default();
            if colors.len() != vertex_count || colors.iter().any(|c| !c.is_finite()) {
                return Err(format!(
                    "accessor {} (COLOR_0): not {vertex_count} finite colours",
                    accessor.index()
                ));
            }
            Some(colors)
        }
    };

    let vertices: Vec<u32> = match primitive.indices() {
        None => (0..vertex_limit).collect(),
        Some(accessor) => read_indices(&reader, &accessor, vertex_limit, max_corners, buffers)?,
    };
    let indices = triangulate(mode, &vertices).map_err(|p| match primitive.indices() {
        Some(accessor) => format!("accessor {} (indices): {p}", accessor.index()),
        None => format!("accessor {} (POSITION): {p}", position_accessor.index()),
    })?;

    Ok(Some(RawPrimitive {
        positions,
        normals,
        tangents,
        bitangent_signs,
        colors,
        indices,
        tex_coords,
    }))
}

/// The elements of a vertex attribute accessor (checked by
/// [`check_accessor`]: in bounds, of a type its usage accepts), each
/// component decoded to `f64`: floats as they are, normalized integers as
/// glTF and `KHR_mesh_quantization` say (signed `max(c / (2ⁿ⁻¹ − 1), −1)`,
/// unsigned `c / (2ⁿ − 1)`), other integers as their value. Sparse
/// accessors are applied by the `gltf` crate's iterator. `None` if the
/// accessor has a type no usage accepts or the reader fails.
pub(super) fn read_attribute<const N: usize>(
    accessor: &gltf::Accessor,
    buffers: &[Cow<[u8]>],
) -> Option<Vec<[f64; N]>>
where
    [f32; N]: gltf::accessor::Item,
    [i8; N]: gltf::accessor::Item,
    [u8; N]: gltf::accessor::Item,
    [i16; N]: gltf::accessor::Item,
    [u16; N]: gltf::accessor::Item,
{
    let normalized = accessor.normalized();
    let values = match accessor.data_type() {
        DataType::F32 => decode::<f32, N>(accessor, buffers, |c| c),
        DataType::I8 if normalized => decode::<i8, N>(accessor, buffers, |c| (c / 127.0).max(-1.0)),
        DataType::U8 if normalized => decode::<u8, N>(accessor, buffers, |c| c / 255.0),
        DataType::I16 if normalized => {
            decode::<i16, N>(accessor, buffers, |c| (c / 32767.0).max(-1.0))
        }
        DataType::U16 if normalized => decode::<u16, N>(accessor, buffers, |c| c / 65535.0),
        DataType::I8 => decode::<i8, N>(accessor, buffers, |c| c),
        DataType::U8 => decode::<u8, N>(accessor, buffers, |c| c),
        DataType::I16 => decode::<i16, N>(accessor, buffers, |c| c),
        DataType::U16 => decode::<u16, N>(accessor, buffers, |c| c),
        DataType::U32 => None,
    }?;
    (values.len() == accessor.count()).then_some(values)
}

/// The accessor's elements as `[T; N]`, each component mapped by `f`.
fn decode<T, const N: usize>(
    accessor: &gltf::Accessor,
    buffers: &[Cow<[u8]>],
    f: impl Fn(f64) -> f64,
) -> Option<Vec<[f64; N]>>
where
    T: Copy + Into<f64>,
    [T; N]: gltf::accessor::Item,
{
    let iter = gltf::accessor::Iter::<[T; N]>::new(accessor.clone(), |buffer: gltf::Buffer| {
        buffers.get(buffer.index()).map(|b| &b[..])
    })?;
    Some(iter.map(|v| v.map(|c| f(c.into()))).collect())
}

/// A per-vertex direction attribute: one element per position, types
/// checked before `read` decodes it, all finite, normalized (zero where
/// the file's vector has no length).
fn read_directions(
    accessor: &gltf::Accessor,
    usage: Usage,
    vertex_count: usize,
    buffers: &[Cow<[u8]>],
    quantized: bool,
    read: impl FnOnce(&gltf::Accessor) -> Option<Vec<[f64; 3]>>,
) -> Result<Vec<DVec3>, String> {
    let name = usage.name();
    if accessor.count() != vertex_count {
        return Err(format!(
            "accessor {} ({name}) has {} elements but POSITION has {vertex_count}",
            accessor.index(),
            accessor.count()
        ));
    }
    check_accessor(accessor, usage, vertex_count, buffers, quantized)?;
    let values: Vec<DVec3> = read(accessor)
        .ok_or_else(|| unreadable(accessor, usage))?
        .into_iter()
        .map(DVec3::from)
        .collect();
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(format!(
            "accessor {} ({name}): {} {k} is not finite ({})",
            accessor.index(),
            name.to_lowercase(),
            values[k]
        ));
    }
    Ok(values.into_iter().map(DVec3::normalize_or_zero).collect())
}

/// Vertex indices, each checked to address one of `vertex_limit` vertices.
fn read_indices<'a, 's, F>(
    reader: &gltf::mesh::Reader<'a, 's, F>,
    accessor: &gltf::Accessor,
    vertex_limit: u32,
    max_corners: usize,
    buffers: &[Cow<[u8]>],
) -> Result<Vec<u32>, String>
where
    F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
{
    check_accessor(accessor, Usage::Index, max_corners, buffers, false)?;
    let indices: Vec<u32> = reader
        .read_indices()
        .ok_or_else(|| unreadable(accessor, Usage::Index))?
        .into_u32()
        .collect();
    if indices.len() != accessor.count() {
        return Err(unreadable(accessor, Usage::Index));
    }
    if let Some(k) = indices.iter().position(|&i| i >= vertex_limit) {
        return Err(format!(
            "accessor {} (indices): index {} at position {k} is out of range for {vertex_limit} vertices",
            accessor.index(),
            indices[k]
        ));
    }
    Ok(indices)
}

/// Reported if the reader still fails after [`check_accessor`] passed.
fn unreadable(accessor: &gltf::Accessor, usage: Usage) -> String {
    format!(
        "accessor {} ({}) could not be read",
        accessor.index(),
        usage.name()
    )
}

/// Turns a vertex sequence into triangles, per glTF's definition of each
/// mode (strips alternate the winding back to counter-clockwise; fans turn
/// around the first vertex).
pub(super) fn triangulate(mode: Mode, v: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let n = v.len();
    Ok(match mode {
        Mode::Triangles => {
            if !n.is_multiple_of(3) {
                return Err(format!(
                    "a triangle list needs a multiple of 3 vertices, got {n}"
                ));
            }
            v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect()
        }
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [v[i], v[i + 1], v[i + 2]]
                } else {
                    [v[i], v[i + 2], v[i + 1]]
                }
            })
            .collect(),
        Mode::TriangleFan => (0..n.saturating_sub(2))
            .map(|i| [v[i + 1], v[i + 2], v[0]])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => Vec::new(),
    })
}
