//! Corners and curves. A boundary vertex is a corner (topological vertex) when it is a BSTONE,
//! when the boundary turns there by more than `Tolerances::kink_angle_deg` (between its two edges
//! and over the longer edge's reach, as `crate::kinks` measures a kink), when it
//! does not have exactly two boundary edges (branching, fin ends, touching loops), or when the
//! boundary changes kind there (border edge meets non-manifold edge or part seam). Corners split
//! each loop into curves; a loop without corners is one closed curve. A curve shared by several
//! loops (a non-manifold edge chain, a seam) is stored once, in a canonical direction.

use super::SurfaceTopology;
use crate::kinks::is_kink;
use geom::{Tolerances, TriMesh};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A polyline between topological vertices (or a closed loop without any).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Curve {
    /// Vertices in order; for a closed curve the first vertex is not repeated at the end.
    pub vertices: Vec<u32>,
    pub closed: bool,
}

/// Canonical form of a curve: open curves read from the smaller end; closed ones start at their
/// smallest vertex and run towards the smaller neighbour. Returns the form and whether it reverses.
fn canonical(vs: &[u32], closed: bool) -> (Vec<u32>, bool) {
    if !closed {
        let rev: Vec<u32> = vs.iter().rev().copied().collect();
        return if rev.as_slice() < vs {
            (rev, true)
        } else {
            (vs.to_vec(), false)
        };
    }
    let n = vs.len();
    let Some(m) = (0..n).min_by_key(|&i| (vs[i], i)) else {
        return (Vec::new(), false);
    };
    let fwd: Vec<u32> = (0..n).map(|i| vs[(m + i) % n]).collect();
    let bwd: Vec<u32> = (0..n).map(|i| vs[(m + n - i) % n]).collect();
    if bwd < fwd { (bwd, true) } else { (fwd, false) }
}

impl SurfaceTopology {
    fn edge_kind(&self, e: u32) -> (usize, bool) {
        let hs = self.edge_half_edges(e);
        let seam = hs.len() == 2 && self.across(hs[0]).is_none();
        (hs.len(), seam)
    }

    pub(super) fn build_corners_and_curves(
        &mut self,
        mesh: &TriMesh,
        bstones: &[u32],
        tol: &Tolerances,
    ) {
        let nv = self.vertex_count;
        let mut corner = vec![false; nv];
        for &b in bstones {
            if let Some(c) = corner.get_mut(b as usize) {
                *c = true;
            }
        }
        let mut degree = vec![0u32; nv];
        for e in 0..self.edges.len() as u32 {
            if self
                .edge_half_edges(e)
                .iter()
                .any(|&h| self.across(h).is_none())
            {
                for v in self.edges[e as usize] {
                    degree[v as usize] += 1;
                }
            }
        }
        for v in 0..nv {
            if degree[v] != 0 && degree[v] != 2 {
                corner[v] = true;
            }
        }
        let p = |v: u32| mesh.vertices.get(v as usize);
        for l in &self.loops {
            let n = l.vertices.len();
            if !l.closed {
                if let Some(&f) = l.vertices.first() {
                    corner[f as usize] = true;
                }
                continue;
            }
            for i in 0..n {
                let v = l.vertices[i];
                let ein = self.edge_of(l.half_edges[(i + n - 1) % n]);
                let eout = self.edge_of(l.half_edges[i]);
                if self.edge_kind(ein) != self.edge_kind(eout) {
                    corner[v as usize] = true;
                }
                let back = (1..n).filter_map(|k| p(l.vertices[(i + n - k) % n]).copied());
                let fwd = (1..n).filter_map(|k| p(l.vertices[(i + k) % n]).copied());
                if let Some(b) = p(v)
                    && is_kink(b, back, fwd, tol.kink_angle_deg)
                {
                    corner[v as usize] = true;
                }
            }
        }
        self.corners = (0..nv as u32).filter(|&v| corner[v as usize]).collect();

        let mut index: BTreeMap<(Vec<u32>, bool), u32> = BTreeMap::new();
        let mut curves = Vec::new();
        let mut loop_curves = Vec::with_capacity(self.loops.len());
        for l in &self.loops {
            let n = l.vertices.len();
            let mut pieces: Vec<(Vec<u32>, bool)> = Vec::new();
            match (0..n).find(|&i| corner[l.vertices[i] as usize]) {
                _ if !l.closed => {
                    let mut vs = l.vertices.clone();
                    if let Some(&h) = l.half_edges.last() {
                        let last = *vs.last().unwrap_or(&0);
                        let end = if self.origin(h) == last {
                            self.target(h)
                        } else {
                            self.origin(h)
                        };
                        vs.push(end);
                    }
                    pieces.push((vs, false));
                }
                None => pieces.push((l.vertices.clone(), true)),
                Some(s) => {
                    let mut cur = vec![l.vertices[s]];
                    for i in 1..=n {
                        let v = l.vertices[(s + i) % n];
                        cur.push(v);
                        if corner[v as usize] {
                            pieces.push((std::mem::replace(&mut cur, vec![v]), false));
                        }
                    }
                }
            }
            let mut refs = Vec::with_capacity(pieces.len());
            for (vs, closed) in pieces {
                let (key, reversed) = canonical(&vs, closed);
                let id = *index.entry((key.clone(), closed)).or_insert_with(|| {
                    curves.push(Curve {
                        vertices: key,
                        closed,
                    });
                    (curves.len() - 1) as u32
                });
                refs.push((id, reversed));
            }
            loop_curves.push(refs);
        }
        self.curves = curves;
        self.loop_curves = loop_curves;
    }
}
