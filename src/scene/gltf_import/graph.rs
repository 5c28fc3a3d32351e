//! The node graph: checked to be a forest before anything walks it, then
//! the nodes of the scene to draw, and what drawing them will cost.
//!
//! Everything here is iterative and linear in the number of nodes and
//! child references, so neither a chain of a million nodes (which would
//! overflow the call stack of a recursive walk) nor a hierarchy that
//! reaches a node along exponentially many paths (which would make a walk
//! without a visited set run for ever) can hurt.

use crate::scene::limits::{Limits, exceeded};
use gltf::mesh::Mode;

/// No parent: a root.
const NO_PARENT: usize = usize::MAX;

/// Checks that the nodes form a forest: every child reference names an
/// existing node, no node has two parents, and there are no cycles. The
/// whole node list is checked, not only the nodes a scene reaches: a cycle
/// among unreachable nodes is as malformed, and other tools will walk it.
///
/// Returns each node's parent (`None` for roots).
pub(super) fn check_forest(document: &gltf::Document) -> Result<Vec<Option<usize>>, String> {
    let json = document.as_json();
    let parent = parents(json)?;
    if let Some(start) = first_unrooted(json, &parent) {
        return Err(describe_cycle(&parent, start));
    }
    Ok(parent
        .into_iter()
        .map(|p| (p != NO_PARENT).then_some(p))
        .collect())
}

/// Each node's parent ([`NO_PARENT`] for none), refusing a node with two.
fn parents(json: &gltf::json::Root) -> Result<Vec<usize>, String> {
    let count = json.nodes.len();
    let mut parent = vec![NO_PARENT; count];
    for (index, node) in json.nodes.iter().enumerate() {
        for child in node.children.iter().flatten() {
            let child = child.value();
            if child >= count {
                return Err(format!(
                    "node {index} has child {child}, which does not exist (there are {count} nodes)"
                ));
            }
            if child == index {
                return Err(format!("node {index} is its own child (a cycle)"));
            }
            if parent[child] == index {
                return Err(format!("node {index} lists child {child} twice"));
            }
            if parent[child] != NO_PARENT {
                return Err(format!(
                    "node {child} has two parents, nodes {} and {index}; glTF nodes must form trees (one parent per node)",
                    parent[child]
                ));
            }
            parent[child] = index;
        }
    }
    Ok(parent)
}

/// The first node that no parentless node reaches, if any. With at most
/// one parent each, such a node is on a cycle or hangs below one. Each
/// node is pushed at most once (it has one parent), so this is linear.
fn first_unrooted(json: &gltf::json::Root, parent: &[usize]) -> Option<usize> {
    let mut reached = vec![false; parent.len()];
    let mut stack: Vec<usize> = (0..parent.len())
        .filter(|&n| parent[n] == NO_PARENT)
        .collect();
    while let Some(n) = stack.pop() {
        reached[n] = true;
        let children = json.nodes[n].children.as_deref().unwrap_or_default();
        stack.extend(children.iter().map(|c| c.value()));
    }
    reached.iter().position(|&r| !r)
}

/// Names the nodes of the cycle above `start`, a node no root reaches:
/// following parents from it must enter a cycle within `count` steps.
fn describe_cycle(parent: &[usize], start: usize) -> String {
    const SHOWN: usize = 6;
    let mut on_cycle = start;
    for _ in 0..parent.len() {
        on_cycle = parent[on_cycle];
    }
    // Walk the cycle once, child to parent, keeping its first members.
    let mut members = vec![on_cycle];
    let mut length = 1;
    let mut next = parent[on_cycle];
    while next != on_cycle {
        if members.len() < SHOWN {
            members.push(next);
        }
        length += 1;
        next = parent[next];
    }
    // Parent to child, from the lowest index, back to where it started.
    members.reverse();
    if length <= SHOWN {
        let lowest = (0..members.len()).min_by_key(|&i| members[i]).unwrap_or(0);
        members.rotate_left(lowest);
        members.push(members[0]);
    }
    let mut shown: Vec<String> = members.iter().map(|n| format!("node {n}")).collect();
    if length > SHOWN {
        shown.push(format!("… ({length} nodes)"));
    }
    format!(
        "the node hierarchy has a cycle, {} (each the parent of the next); glTF nodes must form trees",
        shown.join(" → ")
    )
}

/// The roots of the scene to draw: the default scene's, scene 0's if none
/// is the default, or every parentless node if the file has no scenes.
/// A scene's roots must be distinct and have no parent, or nodes would be
/// drawn twice.
pub(super) fn scene_roots(
    document: &gltf::Document,
    parent: &[Option<usize>],
) -> Result<Vec<usize>, String> {
    let json = document.as_json();
    let scene = json
        .scene
        .map(|s| s.value())
        .or((!json.scenes.is_empty()).then_some(0));
    let Some(scene) = scene else {
        return Ok((0..parent.len()).filter(|&n| parent[n].is_none()).collect());
    };
    let nodes = &json
        .scenes
        .get(scene)
        .ok_or_else(|| format!("scene {scene} does not exist"))?
        .nodes;
    let mut listed = vec![false; parent.len()];
    nodes
        .iter()
        .map(|node| {
            let n = node.value();
            let slot = listed
                .get_mut(n)
                .ok_or_else(|| format!("scene {scene} lists node {n}, which does not exist"))?;
            if std::mem::replace(slot, true) {
                return Err(format!("scene {scene} lists node {n} twice"));
            }
            if let Some(p) = parent[n] {
                return Err(format!(
                    "scene {scene} lists node {n} as a root, but it is a child of node {p}"
                ));
            }
            Ok(n)
        })
        .collect()
}

/// Every node below `roots`, depth first, parents before children. Runs
/// on a forest (see [`check_forest`]), so each node appears once.
pub(super) fn descendants(document: &gltf::Document, roots: &[usize]) -> Vec<usize> {
    let json = document.as_json();
    let mut order = Vec::new();
    let mut stack: Vec<usize> = roots.iter().rev().copied().collect();
    while let Some(n) = stack.pop() {
        order.push(n);
        if let Some(children) = &json.nodes[n].children {
            stack.extend(children.iter().rev().map(|c| c.value()));
        }
    }
    order
}

/// What drawing the given nodes will produce, from declared counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Cost {
    pub vertices: u64,
    pub triangles: u64,
    pub lights: u64,
}

/// Adds up the declared vertex and triangle counts of every mesh instance
/// and the lights among `nodes`, and checks them against `limits` before
/// any vertex is read. A mesh shared by many nodes counts once per node,
/// as it is drawn once per node.
pub(super) fn check_cost(
    document: &gltf::Document,
    nodes: &[usize],
    limits: &Limits,
) -> Result<Cost, String> {
    let json = document.as_json();
    let mesh_costs: Vec<Cost> = json.meshes.iter().map(|m| mesh_cost(json, m)).collect();
    let mut total = Cost::default();
    for &n in nodes {
        let node = &json.nodes[n];
        if let Some(mesh) = node.mesh {
            let cost = mesh_costs
                .get(mesh.value())
                .ok_or_else(|| format!("node {n}: mesh {} does not exist", mesh.value()))?;
            total.vertices = total.vertices.saturating_add(cost.vertices);
            total.triangles = total.triangles.saturating_add(cost.triangles);
        }
        if node
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .is_some()
        {
            total.lights += 1;
        }
    }
    let over = |what: &str, amount: u64, key: &str, limit: u64| {
        (amount > limit).then(|| exceeded(what, amount, key, limit))
    };
    let problem = over(
        "the number of vertices to draw",
        total.vertices,
        "vertices",
        limits.vertices,
    )
    .or_else(|| {
        over(
            "the number of triangles to draw",
            total.triangles,
            "triangles",
            limits.triangles,
        )
    })
    .or_else(|| {
        over(
            "the number of lights",
            total.lights,
            "lights",
            limits.lights,
        )
    });
    match problem {
        Some(p) => Err(p),
        None => Ok(total),
    }
}

/// The declared cost of one mesh: what its triangle primitives read.
fn mesh_cost(json: &gltf::json::Root, mesh: &gltf::json::Mesh) -> Cost {
    let count = |accessor: gltf::json::Index<gltf::json::Accessor>| {
        json.accessors
            .get(accessor.value())
            .map_or(0, |a| a.count.0)
    };
    let mut cost = Cost::default();
    for primitive in &mesh.primitives {
        let mode = match primitive.mode {
            gltf::json::validation::Checked::Valid(mode) => mode,
            gltf::json::validation::Checked::Invalid => continue,
        };
        let Some(&positions) = primitive
            .attributes
            .get(&gltf::json::validation::Checked::Valid(
                gltf::Semantic::Positions,
            ))
        else {
            continue;
        };
        let vertices = count(positions);
        let corners = primitive.indices.map_or(vertices, count);
        let triangles = match mode {
            Mode::Triangles => corners / 3,
            Mode::TriangleStrip | Mode::TriangleFan => corners.saturating_sub(2),
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => continue,
        };
        cost.vertices = cost.vertices.saturating_add(vertices);
        cost.triangles = cost.triangles.saturating_add(triangles);
    }
    cost
}
