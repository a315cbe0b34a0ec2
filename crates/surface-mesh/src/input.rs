//! The given nodes of a patch: loop and constraint nodes numbered once each, in the documented
//! output order (loop nodes in the order given, loop after loop, then constraint nodes not
//! already met). A constraint node bit-identical to an earlier node (a dangling trace that starts
//! on the boundary, two constraints sharing an end) is the same node. Checks the shapes of the
//! input: finite coordinates, loops of at least 3 distinct nodes, constraints of at least 2, no
//! node repeated within a loop, no zero-length segment.

use super::{PatchInput, SurfaceMeshError};
use std::collections::BTreeMap;

pub struct GivenNodes {
    pub nodes: Vec<[f64; 3]>,
    pub loops: Vec<Vec<u32>>,
    pub constraints: Vec<Vec<u32>>,
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
        let mut ids = Vec::with_capacity(l.len());
        for (k, p) in l.iter().enumerate() {
            if p.iter().any(|c| !c.is_finite()) {
                return Err(fail(format!("loop {li} node {k} is not finite"), None));
            }
            if index.contains_key(&key(p)) {
                return Err(fail(
                    format!(
                        "loop {li} node {k} repeats an earlier loop node (loops touch or the closing node is repeated)"
                    ),
                    Some(*p),
                ));
            }
            let id = nodes.len() as u32;
            index.insert(key(p), id);
            nodes.push(*p);
            ids.push(id);
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
    Ok(GivenNodes {
        nodes,
        loops,
        constraints,
    })
}
