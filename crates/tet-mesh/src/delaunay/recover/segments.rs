//! Recovering the embedded segments (well paths) as chains of edges, once the boundary and
//! embedded triangles are faces of the conforming mesh.
//!
//! Each segment is first divided to the size field (`place`): a FE mesh wants the well's line
//! elements at the local size, as the boundary's edges are, and short pieces are far more often
//! Delaunay edges than long ones. Then each piece, in segment and chain order, is made an edge:
//! if it is not one, by the flips that recover a boundary triangle's missing edge
//! (`flips::recover_edge`, which never removes a constraint face, an edge of one, or a piece
//! already recovered); if still missing, by inserting a node on it (`place::split_params`:
//! concentric shells round a vertex where segments meet, else the midpoint or a nearby fraction
//! that keeps clear of the vertices the piece passes) with the constrained Bowyer-Watson
//! insertion, whose cavities never cross a constraint face; its two halves are then recovered in
//! turn. A recovered piece is protected at once (`Tri::protect_edge`): no later insertion, here
//! or in refinement, removes it, and no flip here does. Nodes go only on the segments, never on a
//! boundary or embedded face (an insertion there is refused and another point is tried).
//!
//! Segment vertices inside the region are inserted with the boundary vertices; one that a
//! recovery hole swallowed (the front filled the hole without it) is inserted again first.

mod place;

use super::super::super::lines::{main_axis, point_on};
use super::super::super::sizing::Background;
use super::super::super::{RegionInput, TetMeshError};
use super::super::tri::{Limits, NONE, Tri};
use super::flips::{Kept, recover_edge};
use super::{constraints, star, vertex_tets};
use place::{placement, split_params};

/// Nodes one segment may receive to recover its pieces, before recovery gives up.
const MAX_SPLITS: usize = 2048;

/// The segments as chains of vertices of `tri`, and what it took.
pub struct Recovered {
    /// Per input segment: its vertices from its first end to its second.
    pub chains: Vec<Vec<u32>>,
    /// Nodes placed on the segments to the size field.
    pub placed: usize,
    /// Nodes inserted on pieces that were not edges (after flips).
    pub split: usize,
    /// Pieces made edges by flips.
    pub flipped: usize,
}

/// One segment being recovered: its ends' coordinates and its chain with each node's parameter.
struct Chain {
    a: [f64; 3],
    b: [f64; 3],
    nodes: Vec<(u32, f64)>,
}

/// What recovery carries from piece to piece.
struct Work<'k> {
    tri: &'k mut Tri,
    vtet: Vec<u32>,
    kept: Kept<'k>,
    name: &'k str,
}

pub fn recover_segments(
    tri: &mut Tri,
    input: &RegionInput,
    bg: &Background,
) -> Result<Recovered, TetMeshError> {
    reinsert_lost(tri, input)?;
    let (all, cons_index) = constraints(input);
    let vtet = vertex_tets(tri);
    tri.record = true;
    let mut w = Work {
        tri,
        vtet,
        kept: Kept::new(&all, &cons_index),
        name: &input.name,
    };
    let mut out = Recovered {
        chains: Vec::with_capacity(input.lines.len()),
        placed: 0,
        split: 0,
        flipped: 0,
    };
    let mut chains: Vec<Chain> = Vec::with_capacity(input.lines.len());
    for &[u, v] in &input.lines {
        let (a, b) = (input.vertices[u as usize], input.vertices[v as usize]);
        let mut nodes = vec![(u, 0.0)];
        for t in placement(&a, &b, bg) {
            if let Some(x) = w.insert(point_on(&a, &b, t), nodes[nodes.len() - 1].0) {
                nodes.push((x, t));
                out.placed += 1;
            }
        }
        nodes.push((v, 1.0));
        chains.push(Chain { a, b, nodes });
    }
    let apexes = shared_ends(&input.lines);
    for (k, c) in chains.iter_mut().enumerate() {
        let ends = input.lines[k].map(|v| apexes.binary_search(&v).is_ok());
        w.recover_chain(c, ends, &mut out)?;
    }
    w.tri.record = false;
    w.tri.created.clear();
    out.chains = chains
        .into_iter()
        .map(|c| c.nodes.into_iter().map(|(v, _)| v).collect())
        .collect();
    Ok(out)
}

/// The vertices where two or more segments end, sorted.
fn shared_ends(lines: &[[u32; 2]]) -> Vec<u32> {
    let mut ends: Vec<u32> = lines.iter().flatten().copied().collect();
    ends.sort_unstable();
    let mut shared: Vec<u32> = ends
        .windows(2)
        .filter(|w| w[0] == w[1])
        .map(|w| w[0])
        .collect();
    shared.dedup();
    shared
}

/// Inserts again the segment vertices that are in no tet (taken by a recovery hole).
fn reinsert_lost(tri: &mut Tri, input: &RegionInput) -> Result<(), TetMeshError> {
    let mut present = vec![false; tri.pts.len()];
    for t in tri.live_tets() {
        for &v in &tri.t[t as usize].v {
            present[v as usize] = true;
        }
    }
    let mut lost: Vec<u32> = input.lines.iter().flatten().copied().collect();
    lost.sort_unstable();
    lost.dedup();
    lost.retain(|&v| !present[v as usize]);
    for v in lost {
        tri.insert_vertex(v, NONE, &Limits::default())
            .map_err(|r| {
                TetMeshError::new(
                    &input.name,
                    format!("segment vertex {v} could not be inserted ({r:?})"),
                    Some(input.vertices[v as usize]),
                )
            })?;
    }
    Ok(())
}

impl Work<'_> {
    /// Inserts `p` (walking from a tet of `near`), keeping `vtet` current; `None` if refused.
    fn insert(&mut self, p: [f64; 3], near: u32) -> Option<u32> {
        let start = self.vtet.get(near as usize).copied().unwrap_or(NONE);
        self.tri.created.clear();
        let x = self.tri.insert(p, start, &Limits::default()).ok()?;
        self.vtet.resize(self.tri.pts.len(), NONE);
        for &t in &self.tri.created {
            for &v in &self.tri.t[t as usize].v {
                self.vtet[v as usize] = t;
            }
        }
        Some(x)
    }

    fn is_edge(&self, u: u32, v: u32) -> bool {
        let t = self.vtet[u as usize];
        t != NONE && star(self.tri, u, t).any(|s| self.tri.t[s as usize].v.contains(&v))
    }

    fn protect(&mut self, u: u32, v: u32) {
        self.tri.protect_edge(u, v);
        self.kept.keep_edge(u, v);
    }

    /// Makes every piece of chain `c` an edge, in order. `apex`: whether each end of the
    /// segment is shared with another segment (shells are split round it).
    fn recover_chain(
        &mut self,
        c: &mut Chain,
        apex: [bool; 2],
        out: &mut Recovered,
    ) -> Result<(), TetMeshError> {
        let mut splits = 0;
        let mut i = 0;
        while i + 1 < c.nodes.len() {
            let ((u, t0), (v, t1)) = (c.nodes[i], c.nodes[i + 1]);
            if !self.is_edge(u, v) {
                recover_edge(self.tri, u, v, &self.kept, &mut self.vtet);
                if self.is_edge(u, v) {
                    out.flipped += 1;
                }
            }
            if self.is_edge(u, v) {
                self.protect(u, v);
                i += 1;
                continue;
            }
            splits += 1;
            let node = (splits <= MAX_SPLITS)
                .then(|| self.split(c, i, apex))
                .flatten();
            let Some(node) = node else {
                let p = point_on(&c.a, &c.b, 0.5 * (t0 + t1));
                let msg = format!(
                    "the well segment from {:?} to {:?} could not be recovered as tet edges \
                     (a piece near here stays missing)",
                    c.a, c.b
                );
                return Err(TetMeshError::new(self.name, msg, Some(p)));
            };
            c.nodes.insert(i + 1, node);
            out.split += 1;
        }
        Ok(())
    }

    /// Inserts a node on the missing piece `i` of chain `c`: the first of `split_params` that
    /// the kernel takes and that keeps the chain's order strictly.
    fn split(&mut self, c: &Chain, i: usize, apex: [bool; 2]) -> Option<(u32, f64)> {
        let ((u, t0), (v, t1)) = (c.nodes[i], c.nodes[i + 1]);
        let (pu, pv) = (self.tri.pts[u as usize], self.tri.pts[v as usize]);
        let at_a = apex[0] && i == 0;
        let at_b = apex[1] && i + 2 == c.nodes.len();
        let axis = main_axis(&c.a, &c.b);
        for t in split_params(
            self.tri,
            &self.vtet,
            (u, t0),
            (v, t1),
            (c.a, c.b),
            (at_a, at_b),
        ) {
            let p = point_on(&c.a, &c.b, t);
            // Strictly between the piece's ends along the segment's main axis (rounding may
            // merge close parameters).
            if p[axis] == pu[axis] || p[axis] == pv[axis] {
                continue;
            }
            if let Some(x) = self.insert(p, u) {
                return Some((x, t));
            }
        }
        None
    }
}
