//! Constraint edges: the recovered pieces of embedded segments, which no insertion may remove.
//! A cavity removes an edge exactly when it takes every tet round it; then a tet of that ring
//! (not the one holding the point) leaves the cavity, and the shrinking goes on as for faces the
//! point does not see. Only regions with segments have constraint edges; without any, nothing
//! here runs and the kernel behaves as before.

use std::collections::HashSet;
use std::hash::BuildHasherDefault;

use geom::predicates::{dot, sub};

use super::super::super::front::WordHasher;
use super::{P, Tri};

/// Sorted edges as `lo << 32 | hi`, looked up only (never iterated).
pub type EdgeSet = HashSet<u64, BuildHasherDefault<WordHasher>>;

/// The six edges of a tet, as vertex slots.
const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

#[inline]
fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

impl Tri {
    /// From now on no insertion removes the edge `ab`.
    pub fn protect_edge(&mut self, a: u32, b: u32) {
        self.cons_edges.insert(key(a, b));
    }

    /// The constraint edges of the cavity's tets, as vertex pairs, each once.
    fn cavity_constraint_edges(&self) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        for &t in &self.cavity {
            let tv = self.t[t as usize].v;
            for (i, j) in EDGES {
                if self.cons_edges.contains(&key(tv[i], tv[j])) {
                    out.push([tv[i].min(tv[j]), tv[i].max(tv[j])]);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Tets to drop from the cavity so that it keeps every constraint edge: for each edge whose
    /// whole ring is in the cavity, the first tet of the ring that does not hold the point.
    pub(super) fn tets_freeing_edges(&self, root: u32) -> Vec<u32> {
        if self.cons_edges.is_empty() {
            return Vec::new();
        }
        let s = self.stamp;
        let mut out = Vec::new();
        for [a, b] in self.cavity_constraint_edges() {
            let Some(&start) = self.cavity.iter().find(|&&t| {
                let tv = self.t[t as usize].v;
                tv.contains(&a) && tv.contains(&b)
            }) else {
                continue;
            };
            // An open ring runs to the hull: the edge is on the cavity's boundary.
            let Some((ring, _)) = self.edge_ring(a, b, start) else {
                continue;
            };
            if ring.iter().all(|&t| self.t[t as usize].mark == s)
                && let Some(&t) = ring.iter().find(|&&t| t != root)
            {
                out.push(t);
            }
        }
        out
    }

    /// Whether `p` stands at least `min` off every constraint edge of the cavity (a size test
    /// in floating point, as the height over constraint faces).
    pub(super) fn clear_of_edges(&self, p: &P, min: f64) -> bool {
        if self.cons_edges.is_empty() {
            return true;
        }
        self.cavity_constraint_edges().iter().all(|&[a, b]| {
            let (x, y) = (&self.pts[a as usize], &self.pts[b as usize]);
            segment_distance(x, y, p) >= min
        })
    }
}

/// Distance from `p` to the segment `xy` (float).
fn segment_distance(x: &P, y: &P, p: &P) -> f64 {
    let d = sub(y, x);
    let l2 = dot(&d, &d);
    let t = if l2 > 0.0 {
        (dot(&sub(p, x), &d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [0, 1, 2].map(|k| x[k] + t * d[k]);
    let e = sub(p, &q);
    dot(&e, &e).sqrt()
}

#[cfg(test)]
mod tests {
    use super::super::{Limits, Tri};
    use crate::exact::orient3d;
    use geom::predicates::Orientation;

    /// A bipyramid over a triangle round the z axis (apexes 0.8 off it, closer than the
    /// triangle's circumsphere lets them be), inside a large enclosing tet: its Delaunay
    /// tetrahedralization holds the axis edge `ab` with three tets round it.
    fn bipyramid() -> (Tri, u32, u32) {
        let mut pts = vec![
            [100.0, 100.0, 100.0],
            [100.0, -100.0, -100.0],
            [-100.0, 100.0, -100.0],
            [-100.0, -100.0, 100.0],
        ];
        pts.extend([
            [0.0, 0.0, -0.8],
            [0.0, 0.0, 0.8],
            [1.0, 0.0, 0.0],
            [-0.5, 0.87, 0.0],
            [-0.5, -0.87, 0.0],
        ]);
        let mut st = [0, 1, 2, 3];
        if orient3d(&pts[0], &pts[1], &pts[2], &pts[3]) != Orientation::Positive {
            st.swap(0, 1);
        }
        let mut tri = Tri::new(pts, st);
        for v in 4..9 {
            tri.insert_vertex(v, super::super::NONE, &Limits::default())
                .expect("inserted");
        }
        (tri, 4, 5)
    }

    fn has_edge(tri: &Tri, a: u32, b: u32) -> bool {
        tri.live_tets()
            .any(|t| tri.t[t as usize].v.contains(&a) && tri.t[t as usize].v.contains(&b))
    }

    #[test]
    fn a_point_next_to_a_protected_edge_is_inserted_without_removing_it() {
        let (mut plain, a, b) = bipyramid();
        assert!(has_edge(&plain, a, b));
        let p = [0.05, 0.02, 0.1];
        // Unprotected, the point's cavity takes every tet round the edge.
        plain
            .insert(p, super::super::NONE, &Limits::default())
            .unwrap();
        assert!(!has_edge(&plain, a, b));
        let (mut tri, a, b) = bipyramid();
        tri.protect_edge(a, b);
        tri.insert(p, super::super::NONE, &Limits::default())
            .unwrap();
        assert!(has_edge(&tri, a, b));
        for t in tri.live_tets() {
            let [x, y, z, w] = tri.t[t as usize].v.map(|v| tri.pts[v as usize]);
            assert_eq!(orient3d(&x, &y, &z, &w), Orientation::Positive);
        }
        // A point too close to the protected edge for the limits is refused.
        let lim = Limits {
            min_dist: 0.0,
            min_height: 0.2,
        };
        assert!(
            tri.insert([-0.05, 0.05, -0.3], super::super::NONE, &lim)
                .is_err()
        );
    }
}
