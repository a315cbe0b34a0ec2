//! Boundary loops of patches. A boundary half-edge is one whose edge does not join two triangles
//! of the same patch. From one, the next is found by turning around its end vertex through the
//! patch's triangles (crossing only interior edges) until another boundary side is met; this works
//! whatever the triangles' orientation and at vertices where several loops touch.
//!
//! Outer vs inner: a patch's outer loop is the one whose bounding box has the largest diagonal (a
//! loop that encloses others has a box at least as large); ties go to the lowest loop. This is a
//! measure, not a predicate: it names loops and never decides geometry.

use super::{NONE, SurfaceTopology};
use geom::{BBox, TriMesh};
use serde::{Deserialize, Serialize};

/// A closed chain of boundary half-edges of one patch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BoundaryLoop {
    pub patch: u32,
    /// Boundary half-edges in walking order.
    pub half_edges: Vec<u32>,
    /// Vertex at the start of each half-edge step, in walking order (`vertices[i]` → `vertices[i+1]`).
    pub vertices: Vec<u32>,
    /// `false` only when the walk could not come back to its start (a defect upstream).
    pub closed: bool,
    pub outer: bool,
}

impl SurfaceTopology {
    fn is_boundary_half_edge(&self, h: u32) -> bool {
        self.he_edge[h as usize] != NONE && self.across(h).is_none()
    }

    /// The next boundary half-edge after arriving at `b` along `cur`.
    fn next_boundary(&self, cur: u32, b: u32) -> Option<u32> {
        let mut t = cur / 3;
        let mut entered = self.edge_of(cur);
        let budget = 2 * self.edges_around_vertex(b).len() + 4;
        for _ in 0..budget {
            let g = (0..3).map(|k| t * 3 + k).find(|&g| {
                self.edge_of(g) != entered && (self.origin(g) == b || self.target(g) == b)
            })?;
            match self.across(g) {
                None => return Some(g),
                Some(o) => {
                    t = o / 3;
                    entered = self.edge_of(o);
                }
            }
        }
        None
    }

    pub(super) fn build_loops(&mut self, mesh: &TriMesh) {
        let mut visited = vec![false; self.he_edge.len()];
        let mut loops = Vec::new();
        let mut patch_loops = vec![Vec::new(); self.patch_count()];
        for p in 0..self.patch_count() as u32 {
            for &t in self.patch_triangles(p) {
                for k in 0..3 {
                    let start = t * 3 + k;
                    if visited[start as usize] || !self.is_boundary_half_edge(start) {
                        continue;
                    }
                    visited[start as usize] = true;
                    let mut hes = vec![start];
                    let mut verts = vec![self.origin(start)];
                    let mut cur = start;
                    let mut b = self.target(start);
                    let closed = loop {
                        let Some(g) = self.next_boundary(cur, b) else {
                            break false;
                        };
                        if g == start {
                            break true;
                        }
                        if visited[g as usize] {
                            break false;
                        }
                        visited[g as usize] = true;
                        hes.push(g);
                        verts.push(b);
                        b = if self.origin(g) == b {
                            self.target(g)
                        } else {
                            self.origin(g)
                        };
                        cur = g;
                    };
                    patch_loops[p as usize].push(loops.len() as u32);
                    loops.push(BoundaryLoop {
                        patch: p,
                        half_edges: hes,
                        vertices: verts,
                        closed,
                        outer: false,
                    });
                }
            }
        }
        for ls in &mut patch_loops {
            let diag = |l: u32| {
                let b = BBox::from_points(
                    loops[l as usize]
                        .vertices
                        .iter()
                        .filter_map(|&v| mesh.vertices.get(v as usize)),
                );
                let e = b.extent();
                e[0] * e[0] + e[1] * e[1] + e[2] * e[2]
            };
            let mut best: Option<(u32, f64)> = None;
            for &l in ls.iter() {
                let d = diag(l);
                if best.is_none_or(|(_, bd)| d > bd) {
                    best = Some((l, d));
                }
            }
            if let Some((outer, _)) = best {
                loops[outer as usize].outer = true;
                ls.retain(|&l| l != outer);
                ls.insert(0, outer);
            }
        }
        self.loops = loops;
        self.patch_loops = patch_loops;
    }
}
