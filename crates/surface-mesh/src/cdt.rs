//! A 2D constrained Delaunay triangulation in the patch's parameter plane, with exact
//! `orient2d`/`incircle` decisions: incremental Bowyer–Watson insertion (cavities never cross a
//! fixed edge, so the triangulation stays constrained-Delaunay), segment recovery by Sloan's edge
//! flips followed by Lawson flips, and an inside/outside labelling by crossing parity of loop
//! edges. Three far "super" vertices (indices 0, 1, 2) enclose everything, so every real vertex is
//! interior to the triangulation and has a closed fan.
//!
//! Storage: triangle `t` has counter-clockwise vertices `tri[t]`; `nbr[t][i]` is the triangle
//! across the edge opposite vertex `i` (or `NONE` on the super hull) and `fix[t][i]` what that
//! edge is (`FREE`, `LOOP`, `CONSTRAINT`). Dead triangle slots are recycled from a free list in
//! LIFO order, so everything is deterministic. Nothing here recurses.

use geom::predicates::incircle;
use geom::{Orientation, orient2d};

pub const NONE: u32 = u32::MAX;
pub const FREE: u8 = 0;
pub const LOOP: u8 = 1;
pub const CONSTRAINT: u8 = 2;

/// Why an operation on the triangulation failed, with the 2D place.
#[derive(Debug, Clone, PartialEq)]
pub enum CdtError {
    /// A point coincides with the existing vertex.
    Duplicate(u32),
    /// The vertex lies exactly on the segment being recovered.
    VertexOnSegment { vertex: u32, a: u32, b: u32 },
    /// The segment `a b` crosses the fixed edge `c d`.
    Crossing { a: u32, b: u32, c: u32, d: u32 },
    /// A point lies on a fixed edge, or a walk or cavity failed.
    Rejected([f64; 2]),
}

/// A cavity boundary edge `(a, b, kind)`: the new triangle is `a b p`.
pub type CavityEdge = (u32, u32, u8);
/// A veto on an insertion, shown the cavity's boundary edges.
pub type Veto<'a> = dyn FnMut(&Cdt, &[CavityEdge]) -> bool + 'a;

pub struct Cdt {
    pub pts: Vec<[f64; 2]>,
    pub tri: Vec<[u32; 3]>,
    pub nbr: Vec<[u32; 3]>,
    pub fix: Vec<[u8; 3]>,
    pub inside: Vec<bool>,
    pub alive: Vec<bool>,
    /// One live triangle incident to each vertex.
    pub vtri: Vec<u32>,
    free: Vec<u32>,
    last: u32,
    rng: u64,
    // scratch
    cavity: Vec<u32>,
    mark: Vec<u32>,
    stamp: u32,
    /// Triangles every successful insertion removed (the work the insertion order decides).
    #[cfg(test)]
    pub removed: u64,
}

#[inline]
pub fn next(i: usize) -> usize {
    if i == 2 { 0 } else { i + 1 }
}
#[inline]
pub fn prev(i: usize) -> usize {
    if i == 0 { 2 } else { i - 1 }
}

impl Cdt {
    /// An empty triangulation whose super triangle encloses `[min, max]` with a wide margin.
    pub fn new(min: [f64; 2], max: [f64; 2]) -> Cdt {
        let c = [(min[0] + max[0]) * 0.5, (min[1] + max[1]) * 0.5];
        let r = ((max[0] - min[0]).max(max[1] - min[1])).max(1.0) * 100.0;
        let pts = vec![
            [c[0] - 2.0 * r, c[1] - r],
            [c[0] + 2.0 * r, c[1] - r],
            [c[0], c[1] + 2.0 * r],
        ];
        Cdt {
            pts,
            tri: vec![[0, 1, 2]],
            nbr: vec![[NONE; 3]],
            fix: vec![[FREE; 3]],
            inside: vec![false],
            alive: vec![true],
            vtri: vec![0, 0, 0],
            free: Vec::new(),
            last: 0,
            rng: 0x9E37_79B9_7F4A_7C15,
            cavity: Vec::new(),
            mark: vec![0],
            stamp: 0,
            #[cfg(test)]
            removed: 0,
        }
    }

    fn new_tri(&mut self, v: [u32; 3], n: [u32; 3], f: [u8; 3], inside: bool) -> u32 {
        let t = if let Some(t) = self.free.pop() {
            let k = t as usize;
            self.tri[k] = v;
            self.nbr[k] = n;
            self.fix[k] = f;
            self.inside[k] = inside;
            self.alive[k] = true;
            t
        } else {
            self.tri.push(v);
            self.nbr.push(n);
            self.fix.push(f);
            self.inside.push(inside);
            self.alive.push(true);
            self.mark.push(0);
            (self.tri.len() - 1) as u32
        };
        for &x in &v {
            self.vtri[x as usize] = t;
        }
        t
    }

    /// Which slot of `t` points at neighbour `n`.
    #[inline]
    pub fn slot_of(&self, t: u32, n: u32) -> Option<usize> {
        self.nbr[t as usize].iter().position(|&x| x == n)
    }
    #[inline]
    pub fn index_in(&self, t: u32, v: u32) -> Option<usize> {
        self.tri[t as usize].iter().position(|&x| x == v)
    }

    fn rand3(&mut self) -> usize {
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 7;
        self.rng ^= self.rng << 17;
        (self.rng % 3) as usize
    }

    /// The live triangle containing `p` (closed), by a remembering stochastic walk (seeded, so
    /// deterministic) with a linear scan as the fallback.
    pub fn locate(&mut self, p: &[f64; 2], start: u32) -> Option<u32> {
        let mut t =
            if start != NONE && (start as usize) < self.alive.len() && self.alive[start as usize] {
                start
            } else if self.alive.get(self.last as usize).copied().unwrap_or(false) {
                self.last
            } else {
                match self.alive.iter().position(|&a| a) {
                    Some(k) => k as u32,
                    None => return None,
                }
            };
        let mut prev_t = NONE;
        let limit = 4 * self.tri.len() + 100;
        'walk: for _ in 0..limit {
            let r = self.rand3();
            for k in 0..3 {
                let i = (r + k) % 3;
                let n = self.nbr[t as usize][i];
                if n == prev_t && n != NONE {
                    continue;
                }
                let v = self.tri[t as usize];
                let a = &self.pts[v[next(i)] as usize];
                let b = &self.pts[v[prev(i)] as usize];
                if orient2d(a, b, p) == Orientation::Negative {
                    if n == NONE {
                        return None;
                    }
                    prev_t = t;
                    t = n;
                    continue 'walk;
                }
            }
            self.last = t;
            return Some(t);
        }
        // Fallback: exhaustive scan (deterministic order).
        for k in 0..self.tri.len() {
            if self.alive[k] && self.contains(k as u32, p) {
                self.last = k as u32;
                return Some(k as u32);
            }
        }
        None
    }

    pub fn contains(&self, t: u32, p: &[f64; 2]) -> bool {
        let v = self.tri[t as usize];
        (0..3).all(|i| {
            orient2d(&self.pts[v[i] as usize], &self.pts[v[next(i)] as usize], p)
                != Orientation::Negative
        })
    }

    /// Inserts `p` (Bowyer–Watson, constrained). Returns the new vertex, or why not. Nothing is
    /// modified when it fails. `accept` may veto the insertion after seeing the cavity's boundary
    /// edges and their kinds (each new triangle is such an edge plus the new point).
    pub fn insert(&mut self, p: [f64; 2], start: u32, accept: &mut Veto) -> Result<u32, CdtError> {
        let pv = self.pts.len() as u32;
        self.pts.push(p);
        self.vtri.push(NONE);
        let inserted = self.insert_vertex(pv, start, accept);
        if inserted.is_err() {
            self.pts.pop();
            self.vtri.pop();
        }
        inserted.map(|()| pv)
    }

    /// Stores `points` as vertices not yet in the triangulation, so that they keep their order's
    /// numbers (the first is returned) whatever order [`Cdt::insert_stored`] then inserts them in.
    pub fn store(&mut self, points: &[[f64; 2]]) -> u32 {
        let first = self.pts.len() as u32;
        self.pts.extend_from_slice(points);
        self.vtri.resize(self.pts.len(), NONE);
        first
    }

    /// Inserts the stored vertex `v`, as [`Cdt::insert`] inserts a new point.
    pub fn insert_stored(&mut self, v: u32, accept: &mut Veto) -> Result<(), CdtError> {
        self.insert_vertex(v, NONE, accept)
    }

    /// Bowyer–Watson insertion of vertex `pv`, whose point is stored and which no triangle has.
    fn insert_vertex(&mut self, pv: u32, start: u32, accept: &mut Veto) -> Result<(), CdtError> {
        let p = self.pts[pv as usize];
        let t0 = self.locate(&p, start).ok_or(CdtError::Rejected(p))?;
        for &v in &self.tri[t0 as usize] {
            if self.pts[v as usize] == p {
                return Err(CdtError::Duplicate(v));
            }
        }
        // Grow the cavity.
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        let stamp = self.stamp;
        let mut cavity = std::mem::take(&mut self.cavity);
        cavity.clear();
        cavity.push(t0);
        self.mark[t0 as usize] = stamp;
        let mut head = 0;
        let mut boundary: Vec<(u32, u32, u32, u8)> = Vec::new(); // (a, b, outer tri, fix)
        while head < cavity.len() {
            let t = cavity[head];
            head += 1;
            let v = self.tri[t as usize];
            for i in 0..3 {
                let n = self.nbr[t as usize][i];
                let f = self.fix[t as usize][i];
                let a = v[next(i)];
                let b = v[prev(i)];
                if n != NONE && self.mark[n as usize] == stamp {
                    continue;
                }
                let grow = n != NONE && f == FREE && {
                    let w = self.tri[n as usize];
                    incircle(
                        &self.pts[w[0] as usize],
                        &self.pts[w[1] as usize],
                        &self.pts[w[2] as usize],
                        &p,
                    ) == Orientation::Positive
                };
                if grow {
                    self.mark[n as usize] = stamp;
                    cavity.push(n);
                } else {
                    boundary.push((a, b, n, f));
                }
            }
        }
        // A boundary edge can be recorded before its outer triangle joined the cavity: drop those.
        // A fixed edge with the cavity on both sides would be lost: refuse such a point.
        let swallowed = boundary
            .iter()
            .any(|&(_, _, n, f)| f != FREE && n != NONE && self.mark[n as usize] == stamp);
        boundary.retain(|&(_, _, n, _)| n == NONE || self.mark[n as usize] != stamp);
        // Star-shapedness: every new triangle must be strictly counter-clockwise.
        let ok = boundary.iter().all(|&(a, b, _, _)| {
            orient2d(&self.pts[a as usize], &self.pts[b as usize], &p) == Orientation::Positive
        });
        let mut verts: Vec<(u32, u32, u8)> = boundary.iter().map(|e| (e.0, e.1, e.3)).collect();
        if swallowed || !ok || !accept(self, &verts) {
            self.cavity = cavity;
            return Err(CdtError::Rejected(p));
        }
        let inside = self.inside[t0 as usize];
        #[cfg(test)]
        {
            self.removed += cavity.len() as u64;
        }
        for &t in &cavity {
            self.alive[t as usize] = false;
        }
        // Recycle slots in reverse so the order of reuse is deterministic.
        for &t in cavity.iter().rev() {
            self.free.push(t);
        }
        let mut made: Vec<(u32, u32)> = Vec::with_capacity(boundary.len()); // (first vertex, tri)
        for &(a, b, n, f) in &boundary {
            let t = self.new_tri([a, b, pv], [NONE, NONE, n], [FREE, FREE, f], inside);
            if n != NONE {
                let w = self.tri[n as usize];
                // The outer triangle's slot facing the cavity is the edge (b, a).
                if let Some(k) = (0..3).find(|&k| w[next(k)] == b && w[prev(k)] == a) {
                    self.nbr[n as usize][k] = t;
                }
            }
            made.push((a, t));
        }
        made.sort_unstable();
        for &(_, t) in &made {
            let [a, b, _] = self.tri[t as usize];
            // Edge (b, p) is opposite a (slot 0): shared with the new triangle starting at b.
            if let Ok(k) = made.binary_search_by_key(&b, |m| m.0) {
                let u = made[k].1;
                self.nbr[t as usize][0] = u;
                self.nbr[u as usize][1] = t;
            }
            let _ = a;
        }
        self.last = made.first().map(|m| m.1).unwrap_or(self.last);
        verts.clear();
        self.cavity = cavity;
        Ok(())
    }

    /// Flips the edge opposite vertex `i` of `t`. The caller checks convexity.
    /// Returns the two new triangles (`t` keeps the first).
    pub fn flip(&mut self, t: u32, i: usize) -> (u32, u32) {
        let n = self.nbr[t as usize][i];
        let v = self.tri[t as usize];
        let (p0, p1, p2) = (v[i], v[next(i)], v[prev(i)]);
        let w = self.tri[n as usize];
        let j = (0..3).find(|&k| w[k] != p1 && w[k] != p2).unwrap_or(0);
        let q = w[j];
        let jp1 = (0..3).find(|&k| w[k] == p1).unwrap_or(0);
        let jp2 = (0..3).find(|&k| w[k] == p2).unwrap_or(0);
        // Outer neighbours and their kinds.
        let n_p1q = (self.nbr[n as usize][jp2], self.fix[n as usize][jp2]); // edge (p1,q) opposite p2 in n
        let n_qp2 = (self.nbr[n as usize][jp1], self.fix[n as usize][jp1]); // edge (q,p2) opposite p1 in n
        let t_p0p1 = (self.nbr[t as usize][prev(i)], self.fix[t as usize][prev(i)]);
        let t_p2p0 = (self.nbr[t as usize][next(i)], self.fix[t as usize][next(i)]);
        let inside = self.inside[t as usize];
        // t' = [p0, p1, q], n' = [q, p2, p0]
        self.tri[t as usize] = [p0, p1, q];
        self.nbr[t as usize] = [n_p1q.0, n, t_p0p1.0];
        self.fix[t as usize] = [n_p1q.1, FREE, t_p0p1.1];
        self.tri[n as usize] = [q, p2, p0];
        self.nbr[n as usize] = [t_p2p0.0, t, n_qp2.0];
        self.fix[n as usize] = [t_p2p0.1, FREE, n_qp2.1];
        self.inside[n as usize] = inside;
        if n_p1q.0 != NONE
            && let Some(k) = self.slot_of(n_p1q.0, n)
        {
            self.nbr[n_p1q.0 as usize][k] = t;
        }
        if t_p2p0.0 != NONE
            && let Some(k) = self.slot_of(t_p2p0.0, t)
        {
            self.nbr[t_p2p0.0 as usize][k] = n;
        }
        self.vtri[p0 as usize] = t;
        self.vtri[p1 as usize] = t;
        self.vtri[q as usize] = t;
        self.vtri[p2 as usize] = n;
        (t, n)
    }

    /// Whether flipping the edge opposite `i` in `t` gives two strictly convex triangles.
    pub fn flippable(&self, t: u32, i: usize) -> bool {
        let n = self.nbr[t as usize][i];
        if n == NONE {
            return false;
        }
        let v = self.tri[t as usize];
        let (p0, p1, p2) = (v[i], v[next(i)], v[prev(i)]);
        let w = self.tri[n as usize];
        let Some(q) = w.iter().copied().find(|&x| x != p1 && x != p2) else {
            return false;
        };
        let pp = |x: u32| &self.pts[x as usize];
        orient2d(pp(p0), pp(p1), pp(q)) == Orientation::Positive
            && orient2d(pp(q), pp(p2), pp(p0)) == Orientation::Positive
    }

    /// The triangles around vertex `v`, counter-clockwise, starting at `vtri[v]`.
    pub fn fan(&self, v: u32, out: &mut Vec<u32>) {
        out.clear();
        let t0 = self.vtri[v as usize];
        if t0 == NONE {
            return;
        }
        let mut t = t0;
        for _ in 0..self.tri.len() {
            out.push(t);
            let Some(k) = self.index_in(t, v) else { return };
            // CCW around v: cross the edge (v, v[k+2]), opposite v[k+1].
            let n = self.nbr[t as usize][next(k)];
            if n == NONE || n == t0 {
                return;
            }
            t = n;
        }
    }

    /// The triangle and slot of edge `a b` (the slot opposite the third vertex), if present.
    pub fn find_edge(&self, a: u32, b: u32, scratch: &mut Vec<u32>) -> Option<(u32, usize)> {
        self.fan(a, scratch);
        for &t in scratch.iter() {
            let v = self.tri[t as usize];
            for i in 0..3 {
                if (v[next(i)] == a && v[prev(i)] == b) || (v[next(i)] == b && v[prev(i)] == a) {
                    return Some((t, i));
                }
            }
        }
        None
    }

    fn set_fix(&mut self, t: u32, i: usize, kind: u8) {
        self.fix[t as usize][i] = kind;
        let n = self.nbr[t as usize][i];
        if n != NONE
            && let Some(k) = self.slot_of(n, t)
        {
            self.fix[n as usize][k] = kind;
        }
    }

    /// Makes `a b` an edge of kind `kind` (Sloan's flips, then Lawson flips to restore the
    /// constrained Delaunay property).
    pub fn insert_segment(&mut self, a: u32, b: u32, kind: u8) -> Result<(), CdtError> {
        let mut scratch = Vec::new();
        if let Some((t, i)) = self.find_edge(a, b, &mut scratch) {
            self.set_fix(t, i, kind);
            return Ok(());
        }
        let pa = self.pts[a as usize];
        let pb = self.pts[b as usize];
        // Find the first crossed edge around a.
        self.fan(a, &mut scratch);
        let mut start: Option<(u32, usize)> = None;
        for &t in scratch.iter() {
            let k = self.index_in(t, a).unwrap_or(0);
            let v = self.tri[t as usize];
            let (l, r) = (v[next(k)], v[prev(k)]);
            let ol = orient2d(&pa, &pb, &self.pts[l as usize]);
            let or = orient2d(&pa, &pb, &self.pts[r as usize]);
            if ol == Orientation::Zero && dot_pos(&pa, &pb, &self.pts[l as usize]) {
                return Err(CdtError::VertexOnSegment { vertex: l, a, b });
            }
            if ol == Orientation::Negative && or == Orientation::Positive {
                start = Some((t, k));
                break;
            }
        }
        let Some((mut t, k)) = start else {
            return Err(CdtError::Rejected(pa));
        };
        // Walk from a to b collecting crossed edges (as vertex pairs).
        let mut crossed: Vec<(u32, u32)> = Vec::new();
        let mut slot = k; // crossing the edge opposite `slot` in t
        for _ in 0..self.tri.len() + 3 {
            let v = self.tri[t as usize];
            let (u, w) = (v[next(slot)], v[prev(slot)]);
            if self.fix[t as usize][slot] != FREE {
                return Err(CdtError::Crossing { a, b, c: u, d: w });
            }
            crossed.push((u, w));
            let n = self.nbr[t as usize][slot];
            if n == NONE {
                return Err(CdtError::Rejected(pa));
            }
            let nv = self.tri[n as usize];
            let Some(j) = (0..3).find(|&x| nv[x] != u && nv[x] != w) else {
                return Err(CdtError::Rejected(pa));
            };
            let o = nv[j];
            if o == b {
                break;
            }
            match orient2d(&pa, &pb, &self.pts[o as usize]) {
                Orientation::Zero => return Err(CdtError::VertexOnSegment { vertex: o, a, b }),
                s => {
                    // The next crossed edge is (o, u) or (w, o), whichever spans the line.
                    let su = orient2d(&pa, &pb, &self.pts[u as usize]);
                    let ju = (0..3).find(|&x| nv[x] == u).unwrap_or(0);
                    let jw = (0..3).find(|&x| nv[x] == w).unwrap_or(0);
                    // edge (o,u) is opposite w; edge (o,w) is opposite u
                    slot = if s == su { ju } else { jw };
                    t = n;
                }
            }
        }
        // Sloan: flip crossing edges until none remain.
        let mut queue: std::collections::VecDeque<(u32, u32)> = crossed.into();
        let mut created: Vec<(u32, u32)> = Vec::new();
        let mut guard = 0usize;
        let limit = 100 * (queue.len() + 10) * (queue.len() + 10);
        while let Some((u, w)) = queue.pop_front() {
            guard += 1;
            if guard > limit {
                return Err(CdtError::Rejected(pa));
            }
            let Some((t, i)) = self.find_edge(u, w, &mut scratch) else {
                continue;
            };
            if !self.flippable(t, i) {
                queue.push_back((u, w));
                continue;
            }
            let (t1, _) = self.flip(t, i);
            // The new diagonal is (p0, q): in t1 = [p0, p1, q] it is opposite p1 (slot 1).
            let nv = self.tri[t1 as usize];
            let (c, d) = (nv[0], nv[2]);
            let sc = orient2d(&pa, &pb, &self.pts[c as usize]);
            let sd = orient2d(&pa, &pb, &self.pts[d as usize]);
            let ends = c == a || c == b || d == a || d == b;
            if !ends && sc != Orientation::Zero && sd != Orientation::Zero && sc != sd {
                queue.push_back((c, d));
            } else {
                created.push((c, d));
            }
        }
        let Some((t, i)) = self.find_edge(a, b, &mut scratch) else {
            return Err(CdtError::Rejected(pa));
        };
        self.set_fix(t, i, kind);
        // Lawson flips on the new edges.
        let mut stack = created;
        let mut guard = 0usize;
        while let Some((u, w)) = stack.pop() {
            guard += 1;
            if guard > 1_000_000 + 100 * self.tri.len() {
                break;
            }
            let Some((t, i)) = self.find_edge(u, w, &mut scratch) else {
                continue;
            };
            if self.fix[t as usize][i] != FREE || !self.should_flip(t, i) {
                continue;
            }
            let (t1, t2) = self.flip(t, i);
            for tt in [t1, t2] {
                let v = self.tri[tt as usize];
                for s in 0..3 {
                    stack.push((v[next(s)], v[prev(s)]));
                }
            }
        }
        Ok(())
    }

    /// Delaunay test across the free edge opposite `i` of `t`.
    pub fn should_flip(&self, t: u32, i: usize) -> bool {
        let n = self.nbr[t as usize][i];
        if n == NONE {
            return false;
        }
        let v = self.tri[t as usize];
        let w = self.tri[n as usize];
        let Some(q) = w
            .iter()
            .copied()
            .find(|&x| x != v[next(i)] && x != v[prev(i)])
        else {
            return false;
        };
        incircle(
            &self.pts[v[0] as usize],
            &self.pts[v[1] as usize],
            &self.pts[v[2] as usize],
            &self.pts[q as usize],
        ) == Orientation::Positive
            && self.flippable(t, i)
    }

    /// Labels triangles inside the loops by crossing parity from the super hull.
    pub fn label_inside(&mut self) {
        let n = self.tri.len();
        let mut seen = vec![false; n];
        let mut queue = std::collections::VecDeque::new();
        for t in 0..n {
            if self.alive[t] && self.tri[t].iter().any(|&v| v < 3) {
                seen[t] = true;
                self.inside[t] = false;
                queue.push_back(t as u32);
            }
        }
        while let Some(t) = queue.pop_front() {
            for i in 0..3 {
                let m = self.nbr[t as usize][i];
                if m == NONE || seen[m as usize] {
                    continue;
                }
                seen[m as usize] = true;
                let flipp = self.fix[t as usize][i] == LOOP;
                self.inside[m as usize] = self.inside[t as usize] ^ flipp;
                queue.push_back(m);
            }
        }
    }

    pub fn live_triangles(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.tri.len() as u32).filter(|&t| self.alive[t as usize])
    }
}

/// Whether `c` (collinear with `a b`) lies strictly between them.
fn dot_pos(a: &[f64; 2], b: &[f64; 2], c: &[f64; 2]) -> bool {
    let d1 = (c[0] - a[0]) * (b[0] - a[0]) + (c[1] - a[1]) * (b[1] - a[1]);
    let d2 = (c[0] - b[0]) * (a[0] - b[0]) + (c[1] - b[1]) * (a[1] - b[1]);
    d1 > 0.0 && d2 > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn build(points: &[[f64; 2]]) -> (Cdt, Vec<u32>) {
        let mut c = Cdt::new([0.0, 0.0], [10.0, 10.0]);
        let ids = points
            .iter()
            .map(|p| {
                c.insert(*p, NONE, &mut |_: &Cdt, _: &[(u32, u32, u8)]| true)
                    .unwrap()
            })
            .collect();
        (c, ids)
    }

    fn check_delaunay_and_links(c: &Cdt) {
        for t in c.live_triangles() {
            let v = c.tri[t as usize];
            assert_eq!(
                orient2d(
                    &c.pts[v[0] as usize],
                    &c.pts[v[1] as usize],
                    &c.pts[v[2] as usize]
                ),
                Orientation::Positive
            );
            for i in 0..3 {
                let n = c.nbr[t as usize][i];
                if n != NONE {
                    assert!(c.alive[n as usize]);
                    assert!(c.slot_of(n, t).is_some(), "asymmetric link");
                    if c.fix[t as usize][i] == FREE {
                        assert!(!c.should_flip(t, i) || !c.flippable(t, i));
                    }
                }
            }
        }
    }

    #[test]
    fn a_grid_of_points_triangulates_into_consistent_counter_clockwise_triangles() {
        let mut pts = Vec::new();
        for i in 0..7 {
            for j in 0..6 {
                pts.push([i as f64 * 1.5, j as f64 * 1.7 + 0.01 * i as f64]);
            }
        }
        let (c, _) = build(&pts);
        check_delaunay_and_links(&c);
        // Euler: 2n + 1 live triangles for n points inside a super triangle.
        assert_eq!(c.live_triangles().count(), 2 * pts.len() + 1);
    }

    #[test]
    fn a_recovered_segment_becomes_an_edge_and_crossing_segments_are_reported() {
        let pts = [
            [0.0, 0.0],
            [10.0, 0.3],
            [5.0, -3.0],
            [5.0, 3.0],
            [3.0, 1.0],
            [7.0, -1.0],
            [5.2, 5.0],
            [4.8, -5.0],
        ];
        let (mut c, id) = build(&pts);
        c.insert_segment(id[0], id[1], LOOP).unwrap();
        let mut s = Vec::new();
        assert!(c.find_edge(id[0], id[1], &mut s).is_some());
        check_delaunay_and_links(&c);
        let err = c.insert_segment(id[6], id[7], LOOP).unwrap_err();
        assert!(matches!(err, CdtError::Crossing { .. }), "{err:?}");
        // A segment through a vertex names that vertex.
        let err = c.insert_segment(id[2], id[3], LOOP).unwrap_err();
        assert!(
            matches!(
                err,
                CdtError::VertexOnSegment { .. } | CdtError::Crossing { .. }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn a_duplicate_point_is_reported_with_the_existing_vertex() {
        let (mut c, id) = build(&[[1.0, 1.0], [2.0, 1.0], [1.0, 2.0]]);
        let e = c
            .insert([2.0, 1.0], NONE, &mut |_: &Cdt, _: &[(u32, u32, u8)]| true)
            .unwrap_err();
        assert_eq!(e, CdtError::Duplicate(id[1]));
    }
}
