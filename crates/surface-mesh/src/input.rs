//! The given nodes of a patch: loop and constraint nodes and points numbered once each, in the
//! documented output order (loop nodes in the order given, loop after loop, then constraint nodes
//! not already met, then points not already met). A node bit-identical to an earlier node is the
//! same node: a constraint that starts on the boundary (a dangling trace), two constraints sharing
//! an end, loops that touch at a vertex (a patch pinched there, where two faults meet its border
//! at one point or a hole touches the outer border), a point given twice or given where a loop or
//! constraint already has a node. Such a pinch node is recorded: its triangles form one fan per
//! visit. Checks the shapes of the input: finite coordinates, loops of at least 3 distinct nodes,
//! constraints of at least 2, no zero-length segment. Where the points may lie is checked once
//! they are flattened (`points`).

use super::{PatchInput, SurfaceMeshError};
use std::collections::BTreeMap;

pub struct GivenNodes {
    pub nodes: Vec<[f64; 3]>,
    pub loops: Vec<Vec<u32>>,
    pub constraints: Vec<Vec<u32>>,
    /// Per node, how many times the loops pass through it (0 for constraint nodes and points).
    pub loop_visits: Vec<u32>,
    /// The number of loop and constraint nodes: the nodes from this index on are points that no
    /// loop or constraint passes through.
    pub first_point: usize,
    /// Per node from `first_point` on, the first given point that is it.
    point_index: Vec<usize>,
}

impl GivenNodes {
    /// Loop segments (closing segment included), in loop order.
    pub fn loop_segments(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.loops
            .iter()
            .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
    }
    pub fn constraint_segments(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.constraints
            .iter()
            .flat_map(|c| c.windows(2).map(|w| (w[0], w[1])))
    }

    /// The first given point that is node `v`, if `v` is a node of its own (not a loop or
    /// constraint node): its index in `PatchInput::points`.
    pub fn point_of(&self, v: usize) -> Option<usize> {
        v.checked_sub(self.first_point)
            .and_then(|k| self.point_index.get(k).copied())
    }

    /// Segment `k` of `loop_segments` then `constraint_segments`, named for messages: "segment
    /// 3 of loop 0" (segment `s` of a loop runs from its node `s` to its node `s + 1`).
    pub fn segment_name(&self, k: usize) -> String {
        let mut k = k;
        for (li, l) in self.loops.iter().enumerate() {
            if k < l.len() {
                return format!("segment {k} of loop {li}");
            }
            k -= l.len();
        }
        for (ci, c) in self.constraints.iter().enumerate() {
            let n = c.len().saturating_sub(1);
            if k < n {
                return format!("segment {k} of constraint {ci}");
            }
            k -= n;
        }
        format!("segment {k} past the last constraint")
    }
}

fn key(p: &[f64; 3]) -> [u64; 3] {
    p.map(f64::to_bits)
}

pub fn given_nodes(input: &PatchInput) -> Result<GivenNodes, SurfaceMeshError> {
    let fail = |message: String, at: Option<[f64; 3]>| SurfaceMeshError {
        patch: input.name.clone(),
        message,
        at,
    };
    if input.loops.is_empty() {
        return Err(fail("the patch has no boundary loop".into(), None));
    }
    let mut index: BTreeMap<[u64; 3], u32> = BTreeMap::new();
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut loops = Vec::new();
    for (li, l) in input.loops.iter().enumerate() {
        if l.len() < 3 {
            return Err(fail(
                format!("loop {li} has {} nodes; a loop needs at least 3", l.len()),
                l.first().copied(),
            ));
        }
        let mut ids: Vec<u32> = Vec::with_capacity(l.len());
        for (k, p) in l.iter().enumerate() {
            if p.iter().any(|c| !c.is_finite()) {
                return Err(fail(format!("loop {li} node {k} is not finite"), None));
            }
            let id = *index.entry(key(p)).or_insert_with(|| {
                nodes.push(*p);
                nodes.len() as u32 - 1
            });
            let closing = k + 1 == l.len() && ids.first() == Some(&id);
            if ids.last() == Some(&id) || closing {
                return Err(fail(
                    format!(
                        "loop {li} has a zero-length segment at node {k} (a node repeated next to itself, or the closing node repeated)"
                    ),
                    Some(*p),
                ));
            }
            ids.push(id);
        }
        let mut distinct = ids.clone();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() < 3 {
            return Err(fail(
                format!(
                    "loop {li} has {} distinct nodes; a loop needs at least 3",
                    distinct.len()
                ),
                l.first().copied(),
            ));
        }
        loops.push(ids);
    }
    let mut constraints = Vec::new();
    for (ci, c) in input.constraints.iter().enumerate() {
        if c.len() < 2 {
            return Err(fail(
                format!("constraint {ci} has {} nodes; it needs at least 2", c.len()),
                c.first().copied(),
            ));
        }
        let mut ids: Vec<u32> = Vec::with_capacity(c.len());
        for (k, p) in c.iter().enumerate() {
            if p.iter().any(|x| !x.is_finite()) {
                return Err(fail(
                    format!("constraint {ci} node {k} is not finite"),
                    None,
                ));
            }
            let id = match index.get(&key(p)) {
                Some(&id) => id,
                None => {
                    let id = nodes.len() as u32;
                    index.insert(key(p), id);
                    nodes.push(*p);
                    id
                }
            };
            if ids.last() == Some(&id) {
                return Err(fail(
                    format!("constraint {ci} has a zero-length segment at node {k}"),
                    Some(*p),
                ));
            }
            ids.push(id);
        }
        constraints.push(ids);
    }
    let first_point = nodes.len();
    let mut point_index = Vec::new();
    for (k, p) in input.points.iter().enumerate() {
        if p.iter().any(|x| !x.is_finite()) {
            return Err(fail(format!("point {k} is not finite"), None));
        }
        index.entry(key(p)).or_insert_with(|| {
            nodes.push(*p);
            point_index.push(k);
            nodes.len() as u32 - 1
        });
    }
    let mut loop_visits = vec![0u32; nodes.len()];
    for &v in loops.iter().flatten() {
        loop_visits[v as usize] += 1;
    }
    Ok(GivenNodes {
        nodes,
        loops,
        constraints,
        loop_visits,
        first_point,
        point_index,
    })
}
