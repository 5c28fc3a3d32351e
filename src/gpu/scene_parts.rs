//! A one-shot scene pass split into parts of a bounded number of
//! triangles, each submitted and finished before the next is recorded.
//!
//! Why: lavapipe rasterizes with llvmpipe, which bins a render pass's
//! triangles into a "scene" (per-tile command lists and the triangles'
//! setup data) before its threads rasterize it, and flushes a scene when
//! its data reach a cap (`LP_SCENE_MAX_SIZE`, 36 MiB in Mesa 22,
//! `src/gallium/drivers/llvmpipe/lp_scene.h`); while the threads
//! rasterize one scene the submitting thread bins the next, so one huge
//! draw holds two or more full scenes at once. That is most of what a
//! 10⁶-triangle render adds to the process's peak beyond its own buffers
//! (docs/bench/memory.md). A submission ends the scene (the queue flushes
//! it with a fence); waiting for it before recording the next part keeps
//! one small scene in memory at a time.
//!
//! The parts draw the same triangles in the same order with the same
//! pipelines and bindings; the depth buffer is stored after a part and
//! loaded by the next (instead of cleared), the colour target loaded, so
//! the image is the same bytes (a rasterizer's result does not depend on
//! where a pass boundary falls: each triangle is tested against the depth
//! the earlier ones left, as in one pass).
//!
//! Only [`super::offscreen`]'s one-shot render splits, and only above
//! [`PASS_TRIANGLES`]: below it a scene is small anyway, and each part
//! costs a submission and a wait that serialises the binning and the
//! rasterization (docs/bench/memory.md gives the measured cost).

use super::geometry::Batch;
use std::ops::Range;

/// Triangles per part of a split scene pass: a scene pass with more is
/// split. Derived from the measured scene data per triangle
/// (docs/bench/memory.md): parts of this size keep llvmpipe's binned
/// scene within a few MiB.
pub const PASS_TRIANGLES: u64 = 20_000;

/// The environment variable that overrides [`PASS_TRIANGLES`] (`0`: never
/// split), for measuring what the split costs and saves.
pub const PASS_TRIANGLES_ENV: &str = "GONIO_PASS_TRIANGLES";

/// Triangles per part: `GONIO_PASS_TRIANGLES` if set (`0` for no split),
/// else [`PASS_TRIANGLES`]; a value that is not a count is an error
/// naming it.
pub fn pass_triangles() -> crate::Result<u64> {
    match std::env::var(PASS_TRIANGLES_ENV) {
        Ok(text) if !text.trim().is_empty() => match text.trim().parse::<u64>() {
            Ok(0) => Ok(u64::MAX),
            Ok(n) => Ok(n),
            Err(_) => Err(crate::Error::argument(
                format!("{PASS_TRIANGLES_ENV}={text}"),
                "expected a triangle count per part of a scene or shadow pass (0: draw the passes whole)",
            )),
        },
        _ => Ok(PASS_TRIANGLES),
    }
}

/// Where a part falls in the split pass: the first clears the targets,
/// the last resolves and discards the depth; a pass that is both is the
/// unsplit pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PassPosition {
    pub first: bool,
    pub last: bool,
}

impl PassPosition {
    /// The whole scene pass in one.
    pub const WHOLE: PassPosition = PassPosition {
        first: true,
        last: true,
    };
}

/// One part: the batches it draws (index into the batches) with the
/// range of each it draws.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScenePart {
    pub position: PassPosition,
    pub draws: Vec<(usize, Range<u32>)>,
}

/// Splits the batches, drawn in `order`, into parts of at most
/// `max_triangles` triangles each (a batch's range is split on triangle
/// boundaries: three indices, or vertices, a triangle). One part, the
/// whole pass, when everything fits (or there is nothing to draw).
pub fn split(order: &[usize], batches: &[Batch], max_triangles: u64) -> Vec<ScenePart> {
    // The scene pass is one layer's drawing: the same split as the
    // shadow maps' (its first part clears, every later one follows a
    // break), each draw tagged with its batch.
    let draws = order
        .iter()
        .map(|&b| (batches[b].range.clone(), b))
        .collect();
    let parts = split_layers(&[(0, draws)], max_triangles);
    let n = parts.len();
    parts
        .into_iter()
        .enumerate()
        .map(|(i, part)| ScenePart {
            position: PassPosition {
                first: i == 0,
                last: i + 1 == n,
            },
            draws: part
                .draws
                .into_iter()
                .map(|(range, b)| (b, range))
                .collect(),
        })
        .collect()
}

/// What ends a part of a split pass in a one-shot render: the triangles
/// drawn since the last submission may reach `max_triangles`, then
/// `submit_and_wait` submits what the encoder holds, waits for it, and
/// leaves a fresh encoder in its place.
pub struct PartBreak<'a> {
    pub max_triangles: u64,
    pub submit_and_wait: &'a mut dyn FnMut(&mut wgpu::CommandEncoder),
}

/// A layer and its draws (stream range, tag) in order.
pub type LayerDraws<T> = (usize, Vec<(Range<u32>, T)>);

/// One pass of a layered depth-only drawing (the shadow maps) split into
/// parts: the layer it draws into, whether it is the layer's first pass
/// (which clears the layer; later ones load it), whether the encoder
/// must be submitted before it, and its draws.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LayerPart<T> {
    pub layer: usize,
    pub clears: bool,
    pub break_before: bool,
    pub draws: Vec<(Range<u32>, T)>,
}

/// Splits the draws of `layers` (layer index, its draws in order; a layer
/// without draws is only cleared) into passes, so that at most
/// `max_triangles` triangles are drawn between two breaks (a draw's
/// range is split on triangle boundaries). Layers share a part's room:
/// small layers need no break between them. A layer's first pass clears
/// it, the next ones load what it drew (a depth pass keeps the nearest
/// depth whatever the order, so the texels are the ones a whole pass
/// gives).
pub fn split_layers<T: Clone>(layers: &[LayerDraws<T>], max_triangles: u64) -> Vec<LayerPart<T>> {
    let max = (max_triangles.clamp(1, (u32::MAX / 3) as u64) * 3) as u32;
    let mut parts = Vec::new();
    let mut room = max;
    for (layer, draws) in layers {
        let mut part = LayerPart {
            layer: *layer,
            clears: true,
            break_before: false,
            draws: Vec::new(),
        };
        for (range, tag) in draws {
            let mut range = range.clone();
            while !range.is_empty() {
                if room == 0 {
                    // A layer's pass that has drawn ends here; one that
                    // has not (the room ran out with the layer before)
                    // just starts after the break.
                    if !part.draws.is_empty() {
                        parts.push(std::mem::replace(
                            &mut part,
                            LayerPart {
                                layer: *layer,
                                clears: false,
                                break_before: false,
                                draws: Vec::new(),
                            },
                        ));
                    }
                    part.break_before = true;
                    room = max;
                }
                let take = room.min(range.end - range.start);
                part.draws
                    .push((range.start..range.start + take, tag.clone()));
                range.start += take;
                room -= take;
            }
        }
        parts.push(part);
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;

    fn batch(range: Range<u32>) -> Batch {
        Batch {
            material: 0,
            range,
            object: None,
            instance: 0,
        }
    }

    /// Every part within the bound, the draws in order and covering each
    /// batch exactly once, only the first part first and only the last
    /// last.
    #[test]
    fn parts_cover_the_order_within_the_bound() {
        let batches = vec![batch(0..30), batch(30..33), batch(33..93), batch(93..93)];
        let order = [2, 0, 3, 1];
        for max in [1u64, 2, 7, 10, 31, 1000] {
            let parts = split(&order, &batches, max);
            let mut flat: Vec<(usize, Range<u32>)> = Vec::new();
            for (i, p) in parts.iter().enumerate() {
                let tris: u32 = p.draws.iter().map(|(_, r)| r.len() as u32 / 3).sum();
                assert!(tris as u64 <= max, "max {max}: part {i} has {tris}");
                assert!(
                    p.draws
                        .iter()
                        .all(|(_, r)| r.len() % 3 == 0 && !r.is_empty())
                );
                assert_eq!(p.position.first, i == 0);
                assert_eq!(p.position.last, i + 1 == parts.len());
                flat.extend(p.draws.iter().cloned());
            }
            // Consecutive pieces of one batch join up again.
            let mut joined: Vec<(usize, Range<u32>)> = Vec::new();
            for (b, r) in flat {
                match joined.last_mut() {
                    Some((lb, lr)) if *lb == b && lr.end == r.start => lr.end = r.end,
                    _ => joined.push((b, r)),
                }
            }
            let expected: Vec<_> = order
                .iter()
                .filter(|&&b| !batches[b].range.is_empty())
                .map(|&b| (b, batches[b].range.clone()))
                .collect();
            assert_eq!(joined, expected, "max {max}");
            let total: u64 = 31;
            assert_eq!(parts.len() as u64, total.div_ceil(max), "max {max}");
        }
    }

    #[test]
    fn nothing_to_draw_is_one_whole_pass() {
        let parts = split(&[], &[], 10);
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].position, PassPosition::WHOLE);
        assert!(parts[0].draws.is_empty());
    }

    /// Each layer cleared exactly once, by its first pass; at most `max`
    /// triangles between breaks; the draws of each layer in order and
    /// complete; no break without need.
    #[test]
    fn layer_parts_clear_once_and_stay_within_the_bound() {
        let layers: Vec<LayerDraws<u8>> = vec![
            (0, vec![(0..30, 0), (30..33, 1)]),
            (3, vec![]),
            (5, vec![(90..150, 2)]),
            (6, vec![(0..3, 0)]),
        ];
        for max in [1u64, 2, 7, 10, 11, 31, 1000] {
            let parts = split_layers(&layers, max);
            let mut since_break = 0u64;
            for (i, p) in parts.iter().enumerate() {
                if p.break_before {
                    assert!(i > 0, "max {max}: a break before the first part");
                    assert_eq!(since_break, max, "max {max}: a break with room left");
                    since_break = 0;
                }
                since_break += p.draws.iter().map(|(r, _)| r.len() as u64 / 3).sum::<u64>();
                assert!(since_break <= max, "max {max}: part {i} overflows");
                assert!(
                    p.draws
                        .iter()
                        .all(|(r, _)| r.len() % 3 == 0 && !r.is_empty())
                );
            }
            for (layer, draws) in &layers {
                let mine: Vec<_> = parts.iter().filter(|p| p.layer == *layer).collect();
                assert!(mine[0].clears, "max {max}: layer {layer} not cleared first");
                assert!(
                    mine[1..].iter().all(|p| !p.clears),
                    "max {max}: layer {layer}"
                );
                let mut joined: Vec<(Range<u32>, u8)> = Vec::new();
                for (r, t) in mine.iter().flat_map(|p| p.draws.iter().cloned()) {
                    match joined.last_mut() {
                        Some((lr, lt)) if *lt == t && lr.end == r.start => lr.end = r.end,
                        _ => joined.push((r, t)),
                    }
                }
                assert_eq!(&joined, draws, "max {max}: layer {layer}");
            }
        }
        // Without a bound: one pass per layer, no break.
        let whole = split_layers(&layers, u64::MAX);
        assert_eq!(whole.len(), layers.len());
        assert!(whole.iter().all(|p| p.clears && !p.break_before));
    }
}
