//! The tetrahedral complex the quality optimizer edits: tets with a free list, node→tets
//! incidence, and what must never change — the protected faces (boundary and embedded
//! triangles), their edges, the pieces of embedded segments, and the fixed nodes (every input
//! vertex and every node on a segment). Adjacency is derived from
//! the incidence lists (a face's other tet is the one sharing its three nodes), which stay short,
//! so no face table has to be kept consistent through flips and insertions.
//!
//! Every local operation (`flips`, `slivers`) replaces a set of tets by another with the same
//! boundary; it is accepted only when every new tet is positive by the exact `orient3d`. Positive
//! tets over an unchanged boundary cover the old set exactly once (the cone/degree argument), so
//! exact positivity is the whole validity test.

use geom::predicates::{Orientation, orient3d};

use super::front::WordSet;
use super::quality::{shape, shape_above, shape_and_mean_ratio};

/// The most tets [`Complex::edge_ring`] gathers round one edge.
pub const RING_CAP: usize = 16;

pub type P = [f64; 3];

pub struct Complex {
    pub nodes: Vec<P>,
    pub tets: Vec<[u32; 4]>,
    pub alive: Vec<bool>,
    /// `quality` (shape) and mean ratio of each live tet, kept current through every change.
    pub shape: Vec<f64>,
    pub mean_ratio: Vec<f64>,
    free: Vec<u32>,
    pub node_tets: Vec<Vec<u32>>,
    /// Nodes below this index never move and never disappear.
    pub n_fixed: usize,
    /// Per node, a counter bumped whenever a tet with the node is added or removed, the node
    /// moves or a neighbour of it moves: a tet's [`Complex::stamp_of`] changes whenever anything
    /// a local operation on it could depend on changes, so failed attempts are not repeated.
    stamp: Vec<u64>,
    protected_faces: WordSet<[u32; 3]>,
    protected_edges: WordSet<[u32; 2]>,
    /// Whether some protected edge is a piece of a segment: one that no protected face holds,
    /// which a cavity could swallow without swallowing a protected face (see `slivers`).
    pub line_edges: bool,
}

#[inline]
pub fn sorted3(f: [u32; 3]) -> [u32; 3] {
    let mut k = f;
    k.sort_unstable();
    k
}

#[inline]
fn sorted2(a: u32, b: u32) -> [u32; 2] {
    if a <= b { [a, b] } else { [b, a] }
}

impl Complex {
    pub fn new(
        nodes: Vec<P>,
        tets: Vec<[u32; 4]>,
        n_fixed: usize,
        protected: impl Iterator<Item = [u32; 3]>,
    ) -> Self {
        // Each list sized to its node's degree (and a little room for flips) before it is
        // filled, instead of growing by doubling.
        let mut degree = vec![0u32; nodes.len()];
        for t in &tets {
            for &v in t {
                degree[v as usize] += 1;
            }
        }
        let mut node_tets: Vec<Vec<u32>> = degree
            .iter()
            .map(|&d| Vec::with_capacity(d as usize + 4))
            .collect();
        drop(degree);
        for (i, t) in tets.iter().enumerate() {
            for &v in t {
                node_tets[v as usize].push(i as u32);
            }
        }
        let mut protected_faces = WordSet::default();
        let mut protected_edges = WordSet::default();
        for f in protected {
            protected_faces.insert(sorted3(f));
            for k in 0..3 {
                protected_edges.insert(sorted2(f[k], f[(k + 1) % 3]));
            }
        }
        let n_nodes = node_tets.len();
        let (shape, mean_ratio) = tets
            .iter()
            .map(|t| {
                let [a, b, c, d] = t.map(|i| nodes[i as usize]);
                shape_and_mean_ratio(&a, &b, &c, &d)
            })
            .unzip();
        Complex {
            alive: vec![true; tets.len()],
            shape,
            mean_ratio,
            nodes,
            tets,
            free: Vec::new(),
            node_tets,
            n_fixed,
            stamp: vec![0; n_nodes],
            protected_faces,
            protected_edges,
            line_edges: false,
        }
    }

    /// Protect the pieces of embedded segments too (their nodes must be fixed).
    pub fn protect_edges(&mut self, edges: impl Iterator<Item = [u32; 2]>) {
        for [a, b] in edges {
            self.protected_edges.insert(sorted2(a, b));
            self.line_edges = true;
        }
    }

    /// The live tets, in slot order.
    #[cfg(test)]
    pub fn into_parts(self) -> (Vec<P>, Vec<[u32; 4]>) {
        let (nodes, tets, _) = self.into_measured_parts();
        (nodes, tets)
    }

    /// The live tets in slot order and their mean ratios (kept current, so the statistics need
    /// not measure every tet again).
    pub fn into_measured_parts(self) -> (Vec<P>, Vec<[u32; 4]>, Vec<f64>) {
        let live = || (0..self.tets.len()).filter(|&i| self.alive[i]);
        let tets = live().map(|i| self.tets[i]).collect();
        let mean_ratio = live().map(|i| self.mean_ratio[i]).collect();
        (self.nodes, tets, mean_ratio)
    }

    #[inline]
    pub fn face_protected(&self, f: [u32; 3]) -> bool {
        self.protected_faces.contains(&sorted3(f))
    }

    #[inline]
    pub fn edge_protected(&self, a: u32, b: u32) -> bool {
        self.protected_edges.contains(&sorted2(a, b))
    }

    /// The optimizer's measure of a tet (`quality::shape`: mean ratio capped by the dihedral
    /// sines).
    #[inline]
    pub fn quality(&self, t: [u32; 4]) -> f64 {
        let [a, b, c, d] = t.map(|i| self.nodes[i as usize]);
        shape(&a, &b, &c, &d)
    }

    /// [`Complex::quality`] when the mean ratio of `t` exceeds `floor`, else `-∞`
    /// (`quality::shape_above`).
    #[inline]
    pub fn quality_above(&self, t: [u32; 4], floor: f64) -> f64 {
        let [a, b, c, d] = t.map(|i| self.nodes[i as usize]);
        shape_above(&a, &b, &c, &d, floor)
    }

    /// Shape and mean ratio of `t`.
    #[inline]
    pub fn measures(&self, t: [u32; 4]) -> (f64, f64) {
        let [a, b, c, d] = t.map(|i| self.nodes[i as usize]);
        shape_and_mean_ratio(&a, &b, &c, &d)
    }

    #[inline]
    pub fn positive(&self, t: [u32; 4]) -> bool {
        let [a, b, c, d] = t.map(|i| self.nodes[i as usize]);
        orient3d(&a, &b, &c, &d) == Orientation::Positive
    }

    pub fn add_tet(&mut self, t: [u32; 4]) -> u32 {
        let (q, m) = self.measures(t);
        let id = match self.free.pop() {
            Some(id) => {
                self.tets[id as usize] = t;
                self.alive[id as usize] = true;
                self.shape[id as usize] = q;
                self.mean_ratio[id as usize] = m;
                id
            }
            None => {
                self.tets.push(t);
                self.alive.push(true);
                self.shape.push(q);
                self.mean_ratio.push(m);
                (self.tets.len() - 1) as u32
            }
        };
        for v in t {
            self.node_tets[v as usize].push(id);
            self.stamp[v as usize] += 1;
        }
        id
    }

    pub fn remove_tet(&mut self, id: u32) {
        if !self.alive[id as usize] {
            return;
        }
        self.alive[id as usize] = false;
        for v in self.tets[id as usize] {
            self.node_tets[v as usize].retain(|&x| x != id);
            self.stamp[v as usize] += 1;
        }
        self.free.push(id);
    }

    pub fn add_node(&mut self, p: P) -> u32 {
        self.nodes.push(p);
        self.node_tets.push(Vec::new());
        self.stamp.push(0);
        (self.nodes.len() - 1) as u32
    }

    /// Remove the last node, which no tet may use any more (an undone insertion).
    pub fn pop_node(&mut self) {
        if self.node_tets.last().is_some_and(|b| b.is_empty()) {
            self.nodes.pop();
            self.node_tets.pop();
            self.stamp.pop();
        }
    }

    /// Move the node `v` to `p` (the caller has checked its ball stays positive).
    pub fn move_node(&mut self, v: u32, p: P) {
        self.nodes[v as usize] = p;
        let measures: Vec<(f64, f64)> = self.node_tets[v as usize]
            .iter()
            .map(|&t| self.measures(self.tets[t as usize]))
            .collect();
        self.move_node_measured(v, p, &measures);
    }

    /// [`Complex::move_node`] with the ball's (shape, mean ratio) at `p` already computed, in
    /// `node_tets[v]` order.
    pub fn move_node_measured(&mut self, v: u32, p: P, measures: &[(f64, f64)]) {
        self.nodes[v as usize] = p;
        self.stamp[v as usize] += 1;
        for (i, &m) in measures.iter().enumerate() {
            let id = self.node_tets[v as usize][i] as usize;
            (self.shape[id], self.mean_ratio[id]) = m;
            for w in self.tets[id] {
                self.stamp[w as usize] += 1;
            }
        }
    }

    /// The stamps of `nodes`, to restore after an undone change.
    pub fn stamps(&self, nodes: &[u32]) -> Vec<u64> {
        nodes.iter().map(|&v| self.stamp[v as usize]).collect()
    }

    /// Put back stamps saved by [`Complex::stamps`] once the complex is exactly as it was.
    pub fn restore_stamps(&mut self, nodes: &[u32], saved: &[u64]) {
        for (&v, &s) in nodes.iter().zip(saved) {
            self.stamp[v as usize] = s;
        }
    }

    /// Sum of the stamps of the nodes of `t`: unchanged exactly while nothing near `t` changed.
    pub fn stamp_of(&self, t: [u32; 4]) -> u64 {
        t.iter().map(|&v| self.stamp[v as usize]).sum()
    }

    /// The live tet other than `not` that has the three nodes of `f`.
    pub fn across(&self, f: [u32; 3], not: u32) -> Option<u32> {
        let [a, b, c] = f;
        self.node_tets[a as usize].iter().copied().find(|&t| {
            t != not && {
                let tv = &self.tets[t as usize];
                tv.contains(&b) && tv.contains(&c)
            }
        })
    }

    /// Tets around the edge `ab` as a closed ring `r_0..r_{n-1}` such that every
    /// `[a, b, r_i, r_{i+1}]` is a (positive) tet of the complex. None when the ring is open (a
    /// boundary edge), not a single cycle, or of more than [`RING_CAP`] tets (no caller takes
    /// rings that large: the pairs are gathered on the stack, with no allocation per edge).
    pub fn edge_ring(&self, a: u32, b: u32, ring: &mut Vec<u32>, ring_tets: &mut Vec<u32>) -> bool {
        ring.clear();
        ring_tets.clear();
        let mut buf = [(0u32, 0u32, 0u32); RING_CAP];
        let mut n = 0;
        for &t in &self.node_tets[a as usize] {
            let tv = self.tets[t as usize];
            if !tv.contains(&b) {
                continue;
            }
            let Some((c, d)) = ordered_rest(tv, a, b) else {
                return false;
            };
            if n == RING_CAP {
                return false;
            }
            buf[n] = (c, d, t);
            n += 1;
        }
        let pairs = &buf[..n];
        if n < 3 {
            return false;
        }
        let (start, mut next, t0) = pairs[0];
        ring.push(start);
        ring_tets.push(t0);
        while next != start {
            if ring.len() > n {
                return false;
            }
            let Some(&(c, d, t)) = pairs.iter().find(|p| p.0 == next) else {
                return false;
            };
            ring.push(c);
            ring_tets.push(t);
            next = d;
        }
        ring.len() == n
    }

    /// The faces of the tet set `set` that no other tet of the set shares, oriented outward (the
    /// reference the sliver removal's incrementally grown hull is tested against).
    #[cfg(test)]
    pub fn hull_of(&self, set: &[u32]) -> Vec<[u32; 3]> {
        let mut faces: Vec<([u32; 3], [u32; 3])> = Vec::with_capacity(set.len() * 4);
        for &t in set {
            for f in super::verify::outward_faces(self.tets[t as usize]) {
                faces.push((sorted3(f), f));
            }
        }
        faces.sort_unstable();
        let mut out = Vec::new();
        let mut i = 0;
        while i < faces.len() {
            let mut j = i + 1;
            while j < faces.len() && faces[j].0 == faces[i].0 {
                j += 1;
            }
            if j - i == 1 {
                out.push(faces[i].1);
            }
            i = j;
        }
        out
    }
}

/// For a positive tet `t` with nodes `a` and `b`, the other two nodes `(c, d)` ordered so that
/// `[a, b, c, d]` is an even permutation of `t` (hence positive too).
pub fn ordered_rest(t: [u32; 4], a: u32, b: u32) -> Option<(u32, u32)> {
    let i = t.iter().position(|&v| v == a)?;
    let j = t.iter().position(|&v| v == b)?;
    let mut rest = [0usize; 2];
    let mut n = 0;
    for k in 0..4 {
        if k != i && k != j {
            rest[n] = k;
            n += 1;
        }
    }
    let perm = [i, j, rest[0], rest[1]];
    let mut inv = 0;
    for x in 0..4 {
        for y in x + 1..4 {
            if perm[x] > perm[y] {
                inv += 1;
            }
        }
    }
    let (c, d) = (t[rest[0]], t[rest[1]]);
    Some(if inv % 2 == 0 { (c, d) } else { (d, c) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rest_of_a_tet_keeps_its_orientation() {
        let t = [0, 1, 2, 3];
        assert_eq!(ordered_rest(t, 0, 1), Some((2, 3)));
        assert_eq!(ordered_rest(t, 1, 0), Some((3, 2)));
        assert_eq!(ordered_rest(t, 2, 3), Some((0, 1)));
        assert_eq!(ordered_rest(t, 0, 2), Some((3, 1)));
    }
}
