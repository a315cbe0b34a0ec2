//! Recovering a missing constraint triangle by flips, before any hole is cut.
//!
//! A boundary triangle that is not a Delaunay face either misses an edge (the segment crosses
//! faces of the tetrahedralization) or is pierced by edges. A missing edge is recovered by 2-3
//! flips of the faces it crosses (or removal of their edges where no 2-3 flip is valid); each
//! piercing edge is then removed: 2-3 flips round it while one is valid, then the edge removal
//! that replaces its ring of `n` tets by `2n - 4` (a triangulation of the ring polygon, each
//! triangle joined to both ends; `n = 3` is the 3-2 flip), the triangulation whose worst tet is
//! best, by dynamic programming over the polygon's chains as in Shewchuk's edge removal. No node
//! is added, so the invariant holds. The holes that remain are few and small; a hole around a
//! needle triangle between the huge tets of the boundary points alone is neither, and the front
//! got stuck in such holes by the rim of a lens and the folds of a box.
//!
//! Decisions and why:
//! - Every flip is checked exactly (`orient3d`): a 2-3 flip only where the new edge crosses the
//!   shared face's interior, an edge removal only where every new tet is positive. Flips never
//!   remove a constraint triangle that is already a face nor an edge of any constraint triangle
//!   or a recovered piece of an embedded segment, so what is recovered stays recovered. The
//!   segments' recovery (`segments`) makes their missing pieces edges with the same flips.
//! - Greedy and bounded (`MAX_PASSES` over the missing triangles, `MAX_ROUNDS` per triangle,
//!   `MAX_EDGE_STEPS` per missing edge, rings of at most `MAX_RING` tets); what is left goes to
//!   the holes as before. Triangles pierced only through an edge or a vertex of theirs are left
//!   to the holes.
//! - The order is the triangles' input order and the edges' sorted order: the same mesh on every
//!   machine and thread count.

use std::collections::HashSet;

use geom::predicates::Orientation;

use super::super::super::exact::orient3d;
use super::super::super::front::FaceMap;
use super::super::tri::{NONE, Tri};
use super::{meets, sorted, star};

/// Passes over the missing triangles (flips for one may free another).
const MAX_PASSES: usize = 4;
/// Passes over one triangle's piercing edges.
const MAX_ROUNDS: usize = 6;
/// Flips tried on one missing edge of a triangle.
const MAX_EDGE_STEPS: usize = 32;
/// Longest walk along a missing edge.
const MAX_CROSSED: usize = 256;
/// Longest edge ring a removal works on (each 2-3 flip shortens it by one).
const MAX_RING: usize = 12;

/// What flips must keep: the constraint triangles (as faces), their edges, and the recovered
/// pieces of embedded segments.
pub(super) struct Kept<'a> {
    faces: &'a FaceMap<u32>,
    edges: HashSet<[u32; 2]>,
}

impl<'a> Kept<'a> {
    pub(super) fn new(all: &[([u32; 3], bool)], faces: &'a FaceMap<u32>) -> Self {
        let edges = all
            .iter()
            .flat_map(|(t, _)| (0..3).map(move |i| pair(t[i], t[(i + 1) % 3])))
            .collect();
        Kept { faces, edges }
    }

    /// From now on flips keep the edge `ab` too (a recovered piece of a segment).
    pub(super) fn keep_edge(&mut self, a: u32, b: u32) {
        self.edges.insert(pair(a, b));
    }

    fn face(&self, f: [u32; 3]) -> bool {
        self.faces.contains_key(&sorted(f))
    }
}

fn pair(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// Tries to make each `missing` triangle (indices into `all`) a face by flips; returns the
/// number of flips made. `vtet` is kept current.
pub(super) fn recover_by_flips(
    tri: &mut Tri,
    all: &[([u32; 3], bool)],
    missing: &[usize],
    kept: &Kept,
    vtet: &mut [u32],
) -> usize {
    let mut left: Vec<usize> = missing.to_vec();
    let mut flips = 0;
    for _ in 0..MAX_PASSES {
        let made: usize = left
            .iter()
            .map(|&k| recover_one(tri, all[k].0, kept, vtet))
            .sum();
        flips += made;
        left.retain(|&k| !holds_face(tri, all[k].0, vtet));
        if made == 0 || left.is_empty() {
            break;
        }
    }
    flips
}

fn recover_one(tri: &mut Tri, f: [u32; 3], kept: &Kept, vtet: &mut [u32]) -> usize {
    let mut flips = 0;
    for e in 0..3 {
        flips += recover_edge(tri, f[e], f[(e + 1) % 3], kept, vtet);
    }
    for _ in 0..MAX_ROUNDS {
        if holds_face(tri, f, vtet) {
            break;
        }
        let piercing = piercing_edges(tri, f, vtet);
        let mut progress = false;
        for [p, q] in piercing {
            if kept.edges.contains(&[p, q]) {
                continue;
            }
            if let Some(n) = remove_edge(tri, p, q, kept, vtet) {
                flips += n;
                progress = true;
            }
        }
        if !progress {
            break;
        }
    }
    flips
}

/// Makes the segment `uv` an edge by flips: 2-3 flips of the faces it crosses, or removals of
/// their edges where no 2-3 flip is valid; the number of flips (the edge may still be missing).
pub(super) fn recover_edge(tri: &mut Tri, u: u32, v: u32, kept: &Kept, vtet: &mut [u32]) -> usize {
    let mut flips = 0;
    for _ in 0..MAX_EDGE_STEPS {
        if tet_with_edge(tri, u, v, vtet).is_some() {
            break;
        }
        let crossed = crossed_faces(tri, u, v, vtet);
        let by_face = crossed.iter().find_map(|&(t, i)| {
            let f = tri.face(t, i);
            let a = tri.t[t as usize].adj[i];
            if kept.face(f) || a == NONE {
                return None;
            }
            flip23(tri, t, a >> 2, f, vtet)
        });
        if by_face.is_some() {
            flips += 1;
            continue;
        }
        let edges: Vec<[u32; 2]> = crossed
            .iter()
            .flat_map(|&(t, i)| {
                let f = tri.face(t, i);
                [pair(f[0], f[1]), pair(f[1], f[2]), pair(f[2], f[0])]
            })
            .filter(|e| !kept.edges.contains(e))
            .collect();
        let Some(n) = edges
            .iter()
            .find_map(|&[p, q]| remove_edge(tri, p, q, kept, vtet))
        else {
            break;
        };
        flips += n;
    }
    flips
}

/// The faces the open segment `uv` crosses strictly (through their open interior), in order
/// from `u`, as (tet, face) with the tet on `u`'s side; the walk stops early where the segment
/// goes through an edge or a vertex.
pub(super) fn crossed_faces(tri: &Tri, u: u32, v: u32, vtet: &[u32]) -> Vec<(u32, usize)> {
    let crosses = |f: [u32; 3]| {
        let p = |x: u32| &tri.pts[x as usize];
        let o = |a: u32, b: u32, c: u32, d: u32| orient3d(p(a), p(b), p(c), p(d)).sign();
        if f.contains(&u) || f.contains(&v) {
            return false;
        }
        let (su, sv) = (o(f[0], f[1], f[2], u), o(f[0], f[1], f[2], v));
        if su * sv >= 0 {
            return false;
        }
        let s = [
            o(u, v, f[0], f[1]),
            o(u, v, f[1], f[2]),
            o(u, v, f[2], f[0]),
        ];
        s[0] != 0 && s.iter().all(|&x| x == s[0])
    };
    let mut out = Vec::new();
    if vtet[u as usize] == NONE {
        return out;
    }
    let first = star(tri, u, vtet[u as usize]).into_iter().find_map(|t| {
        let i = tri.t[t as usize].v.iter().position(|&x| x == u)?;
        crosses(tri.face(t, i)).then_some((t, i))
    });
    let Some((mut t, mut i)) = first else {
        return out;
    };
    loop {
        out.push((t, i));
        let a = tri.t[t as usize].adj[i];
        if a == NONE || out.len() > MAX_CROSSED {
            return out;
        }
        let (next, entry) = (a >> 2, (a & 3) as usize);
        if tri.t[next as usize].v.contains(&v) {
            return out;
        }
        let Some(j) = (0..4).find(|&j| j != entry && crosses(tri.face(next, j))) else {
            return out;
        };
        t = next;
        i = j;
    }
}

/// A tet holding both `p` and `q`, found round `p`.
fn tet_with_edge(tri: &Tri, p: u32, q: u32, vtet: &[u32]) -> Option<u32> {
    if vtet[p as usize] == NONE {
        return None;
    }
    star(tri, p, vtet[p as usize]).find(|&t| tri.t[t as usize].v.contains(&q))
}

fn holds_face(tri: &Tri, f: [u32; 3], vtet: &[u32]) -> bool {
    if vtet[f[0] as usize] == NONE {
        return false;
    }
    star(tri, f[0], vtet[f[0] as usize]).any(|t| f.iter().all(|v| tri.t[t as usize].v.contains(v)))
}

/// The edges (sorted pairs, ascending) of the tets meeting `f` that cross its open interior
/// strictly: ends strictly on both sides of its plane, the crossing point strictly inside it.
fn piercing_edges(tri: &Tri, f: [u32; 3], vtet: &[u32]) -> Vec<[u32; 2]> {
    let o = |a: u32, b: u32, c: u32, d: u32| {
        let p = |v: u32| &tri.pts[v as usize];
        orient3d(p(a), p(b), p(c), p(d)).sign()
    };
    let mut out = Vec::new();
    for t in tets_meeting(tri, f, vtet) {
        let tv = tri.t[t as usize].v;
        for i in 0..4 {
            for j in i + 1..4 {
                let (p, q) = (tv[i], tv[j]);
                if f.contains(&p) || f.contains(&q) {
                    continue;
                }
                let (sp, sq) = (o(f[0], f[1], f[2], p), o(f[0], f[1], f[2], q));
                if sp * sq >= 0 {
                    continue;
                }
                let s = [
                    o(p, q, f[0], f[1]),
                    o(p, q, f[1], f[2]),
                    o(p, q, f[2], f[0]),
                ];
                if s.iter().all(|&x| x == s[0]) && s[0] != 0 {
                    out.push(pair(p, q));
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The tets meeting `f`, reached from its vertices through tets meeting it.
fn tets_meeting(tri: &Tri, f: [u32; 3], vtet: &[u32]) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::new();
    let mut seen: HashSet<u32> = HashSet::new();
    for &v in &f {
        if vtet[v as usize] == NONE {
            continue;
        }
        for t in star(tri, v, vtet[v as usize]) {
            if seen.insert(t) && meets(tri, t, f) {
                out.push(t);
            }
        }
    }
    let mut k = 0;
    while k < out.len() {
        let t = out[k];
        k += 1;
        for a in tri.t[t as usize].adj {
            if a != NONE && seen.insert(a >> 2) && meets(tri, a >> 2, f) {
                out.push(a >> 2);
            }
        }
    }
    out
}

/// Removes edge `pq`: 2-3 flips of the faces round it while one is valid, then
/// [`remove_by_ring`]. The number of flips, or `None` when the edge stays (the mesh may then
/// hold the 2-3 flips made on the way, each valid on its own).
fn remove_edge(tri: &mut Tri, p: u32, q: u32, kept: &Kept, vtet: &mut [u32]) -> Option<usize> {
    let mut flips = 0;
    loop {
        let start = tet_with_edge(tri, p, q, vtet)?;
        let (tets, ring) = tri.edge_ring(p, q, start)?;
        if tets.len() > MAX_RING {
            return None;
        }
        let n = tets.len();
        let flipped = (n > 3)
            .then(|| {
                (0..n).find_map(|i| {
                    let s = ring[i];
                    if kept.face([p, q, s]) {
                        return None;
                    }
                    flip23(tri, tets[i], tets[(i + 1) % n], [p, q, s], vtet)
                })
            })
            .flatten();
        if flipped.is_none() {
            return remove_by_ring(tri, [p, q], (&tets, &ring), kept, vtet).map(|n| n + flips);
        }
        flips += 1;
    }
}

/// Removes edge `pq` by the n-to-(2n-4) flip: its ring of `n` tets is replaced by two tets
/// (one towards `p`, one towards `q`) per triangle of the best triangulation of the ring polygon;
/// `Some(1)`, or `None` when no triangulation gives only positive tets or a kept face would go.
/// `tets` and `ring` are the edge's ring as `Tri::edge_ring` gives it.
fn remove_by_ring(
    tri: &mut Tri,
    [p, q]: [u32; 2],
    (tets, ring): (&[u32], &[u32]),
    kept: &Kept,
    vtet: &mut [u32],
) -> Option<usize> {
    if ring.iter().any(|&r| kept.face([p, q, r])) {
        return None;
    }
    let new = [Orientation::Positive, Orientation::Negative]
        .into_iter()
        .find_map(|side| ring_tets(tri, p, q, ring, side))?;
    commit(tri, tets, &new, vtet);
    Some(1)
}

/// The best triangulation of the polygon `ring` round edge `pq` whose triangles see `p` on
/// `side` and `q` strictly on the other, as tets; `None` when there is none.
fn ring_tets(tri: &Tri, p: u32, q: u32, ring: &[u32], side: Orientation) -> Option<Vec<[u32; 4]>> {
    let n = ring.len();
    let pt = |v: u32| &tri.pts[v as usize];
    // The worst of the two tets on triangle (i, j, k), or `None` when one is not positive.
    let score = |i: usize, j: usize, k: usize| -> Option<f64> {
        let [a, b, c] = [ring[i], ring[j], ring[k]];
        let (op, oq) = (
            orient3d(pt(a), pt(b), pt(c), pt(p)),
            orient3d(pt(a), pt(b), pt(c), pt(q)),
        );
        if op != side || oq != side.flip() {
            return None;
        }
        Some(shape(tri, [a, b, c, p]).min(shape(tri, [a, b, c, q])))
    };
    // best[i][k]: the best worst score triangulating the chain i..=k, and its middle vertex.
    let mut best = vec![vec![(f64::NEG_INFINITY, usize::MAX); n]; n];
    for i in 0..n - 1 {
        best[i][i + 1] = (f64::INFINITY, usize::MAX);
    }
    for len in 2..n {
        for i in 0..n - len {
            let k = i + len;
            for j in i + 1..k {
                let (l, r) = (best[i][j].0, best[j][k].0);
                if l == f64::NEG_INFINITY || r == f64::NEG_INFINITY {
                    continue;
                }
                if let Some(s) = score(i, j, k) {
                    let v = s.min(l).min(r);
                    if v > best[i][k].0 {
                        best[i][k] = (v, j);
                    }
                }
            }
        }
    }
    if best[0][n - 1].0 == f64::NEG_INFINITY {
        return None;
    }
    let mut out = Vec::with_capacity(2 * (n - 2));
    let mut stack = vec![(0, n - 1)];
    while let Some((i, k)) = stack.pop() {
        if k - i < 2 {
            continue;
        }
        let j = best[i][k].1;
        let [a, b, c] = [ring[i], ring[j], ring[k]];
        let (tp, tq) = if side == Orientation::Positive {
            ([a, b, c, p], [a, c, b, q])
        } else {
            ([a, c, b, p], [a, b, c, q])
        };
        out.push(tp);
        out.push(tq);
        stack.push((i, j));
        stack.push((j, k));
    }
    Some(out)
}

/// A scale-free shape measure of a positive tet: its volume over the cube of its longest edge.
fn shape(tri: &Tri, t: [u32; 4]) -> f64 {
    let [a, b, c, d] = t.map(|v| tri.pts[v as usize]);
    let vol = geom::predicates::signed_volume(&a, &b, &c, &d).abs();
    let l2 = [(a, b), (a, c), (a, d), (b, c), (b, d), (c, d)]
        .iter()
        .map(|(x, y)| (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>())
        .fold(0.0, f64::max);
    vol / (l2 * l2.sqrt())
}

/// The 2-3 flip of the face `f` shared by tets `t` and `u`, if its apexes' edge crosses the
/// face's open interior.
fn flip23(tri: &mut Tri, t: u32, u: u32, f: [u32; 3], vtet: &mut [u32]) -> Option<()> {
    let apex = |t: u32| tri.t[t as usize].v.into_iter().find(|v| !f.contains(v));
    let (d, e) = (apex(t)?, apex(u)?);
    let o = |a: u32, b: u32, c: u32, x: u32| {
        let p = |v: u32| &tri.pts[v as usize];
        orient3d(p(a), p(b), p(c), p(x))
    };
    let s = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| o(d, e, f[i], f[j]));
    if s[0] == Orientation::Zero || s.iter().any(|&x| x != s[0]) {
        return None;
    }
    let (d, e) = if s[0] == Orientation::Positive {
        (d, e)
    } else {
        (e, d)
    };
    let new = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| [d, e, f[i], f[j]]);
    commit(tri, &[t, u], &new, vtet);
    Some(())
}

fn commit(tri: &mut Tri, old: &[u32], new: &[[u32; 4]], vtet: &mut [u32]) {
    let ids = tri.replace(old, new);
    for (&id, tv) in ids.iter().zip(new) {
        for &v in tv {
            vtet[v as usize] = id;
        }
    }
}
