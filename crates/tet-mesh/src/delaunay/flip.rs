//! The 4-4 flip that recovers a boundary diagonal. Where four coplanar boundary vertices form a
//! quad whose two boundary triangles use one diagonal and the tetrahedralization the other, the
//! four points are cocircular (a tie, as on every square of a structured grid on a box side), so
//! the Delaunay choice was arbitrary: the four tets round the wrong diagonal are replaced by the
//! four round the right one, if all four are positive (exact). The result is as Delaunay as before
//! (each new tet's circumsphere is that of the old tets with the same apex), and recovery needs no
//! hole there.

use geom::predicates::Orientation;

use super::super::exact::orient3d;
use super::tri::{NONE, Tri};

/// Longest edge ring followed before giving up.
const MAX_RING: usize = 64;

impl Tri {
    /// The tets round edge `pq` in cyclic order and, for each, the ring vertex it shares with the
    /// next one; `None` when the ring is open (the hull) or longer than `MAX_RING`.
    pub fn edge_ring(&self, p: u32, q: u32, start: u32) -> Option<(Vec<u32>, Vec<u32>)> {
        let (mut tets, mut ring) = (Vec::new(), Vec::new());
        let mut t = start;
        // The vertex of `t` whose opposite face leads to the next tet round the edge.
        let others = |t: u32| -> [u32; 2] {
            let tv = self.t[t as usize].v;
            let mut o = [NONE; 2];
            let mut k = 0;
            for &v in &tv {
                if v != p && v != q && k < 2 {
                    o[k] = v;
                    k += 1;
                }
            }
            o
        };
        let [mut r, _] = others(t);
        loop {
            let tv = self.t[t as usize].v;
            let [x, y] = others(t);
            let s = if x == r { y } else { x };
            tets.push(t);
            ring.push(s);
            // Cross the face opposite `r` (it holds p, q and s).
            let i = tv.iter().position(|&v| v == r)?;
            let a = self.t[t as usize].adj[i];
            if a == NONE || tets.len() > MAX_RING {
                return None;
            }
            t = a >> 2;
            r = s;
            if t == start {
                return Some((tets, ring));
            }
        }
    }

    /// Replace the tets `old` by the positive tets `new` covering the same region: faces are
    /// linked to each other and to what bordered `old`, constraint marks kept.
    pub(super) fn replace(&mut self, old: &[u32], new: &[[u32; 4]]) -> Vec<u32> {
        let mut outer: Vec<([u32; 3], u32, bool)> = Vec::new();
        for &t in old {
            for i in 0..4 {
                let a = self.t[t as usize].adj[i];
                if a != NONE && old.contains(&(a >> 2)) {
                    continue;
                }
                let mut k = self.face(t, i);
                k.sort_unstable();
                outer.push((k, a, self.t[t as usize].cons & (1 << i) != 0));
            }
        }
        for &t in old {
            self.kill(t);
        }
        let mut inner: Vec<([u32; 3], u32)> = Vec::new();
        let mut ids = Vec::with_capacity(new.len());
        for &tv in new {
            let id = self.alloc(tv);
            for i in 0..4 {
                let mut k = self.face(id, i);
                k.sort_unstable();
                let me = 4 * id + i as u32;
                if let Some(&(_, a, con)) = outer.iter().find(|o| o.0 == k) {
                    if a != NONE {
                        self.t[id as usize].adj[i] = a;
                        self.t[(a >> 2) as usize].adj[(a & 3) as usize] = me;
                    }
                    if con {
                        self.t[id as usize].cons |= 1 << i;
                    }
                } else if let Some(pos) = inner.iter().position(|o| o.0 == k) {
                    let (_, o) = inner.swap_remove(pos);
                    self.t[id as usize].adj[i] = o;
                    self.t[(o >> 2) as usize].adj[(o & 3) as usize] = me;
                } else {
                    inner.push((k, me));
                }
            }
            ids.push(id);
        }
        self.hint = ids[0];
        ids
    }

    /// Flip the edge `pq` (held by tet `start`) to the edge `ac`, if `pq` has exactly four tets
    /// round it, `a` and `c` are opposite on its ring and the four new tets are positive. Returns
    /// the new tets.
    pub fn flip44(&mut self, p: u32, q: u32, start: u32, a: u32, c: u32) -> Option<Vec<u32>> {
        let (tets, ring) = self.edge_ring(p, q, start)?;
        if tets.len() != 4 {
            return None;
        }
        let ia = ring.iter().position(|&v| v == a)?;
        if ring[(ia + 2) % 4] != c {
            return None;
        }
        let (x, y) = (ring[(ia + 1) % 4], ring[(ia + 3) % 4]);
        let mut new = Vec::with_capacity(4);
        for [u, w] in [[p, x], [x, q], [q, y], [y, p]] {
            let mut t = [a, c, u, w];
            let [pa, pc, pu, pw] = t.map(|v| &self.pts[v as usize]);
            match orient3d(pa, pc, pu, pw) {
                Orientation::Positive => {}
                Orientation::Negative => t.swap(2, 3),
                Orientation::Zero => return None,
            }
            new.push(t);
        }
        Some(self.replace(&tets, &new))
    }
}

/// Whether the four vertices lie in one plane (exact).
pub fn coplanar(tri: &Tri, v: [u32; 4]) -> bool {
    let [a, b, c, d] = v.map(|i| &tri.pts[i as usize]);
    orient3d(a, b, c, d) == Orientation::Zero
}
