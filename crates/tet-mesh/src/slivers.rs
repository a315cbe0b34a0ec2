//! Removal of bad tets that flips and smoothing cannot fix — typically a flat tet whose four nodes
//! are all boundary nodes (nothing can move) in a thin layer — by inserting one interior node.
//!
//! A point `p` near the bad tet is chosen; the cavity starts as the bad tet and its neighbours
//! across unprotected faces and grows across every hull face that `p` does not see strictly from
//! inside (exact `orient3d`) until `p` sees the whole hull: the cavity is then star-shaped from
//! `p` and is replaced by the cone from `p` over its hull. The cavity never grows across a
//! protected (boundary or embedded) face and never swallows a fixed node or a piece of an
//! embedded segment, so those faces stay faces and those edges edges. The new node is then smoothed, and the whole change is undone unless the worst quality
//! of the new tets beats that of the cavity.

use geom::predicates::{Orientation, dist, orient3d};

use super::complex::{Complex, P, sorted3};
use super::quality::shape;
use super::smooth::smooth_node;
use super::verify::outward_faces;

/// Largest cavity (tets) an insertion may replace.
const MAX_CAVITY: usize = 48;
/// Cone tets below this quality make the cavity grow across their (unprotected) face...
const ROOMY_BELOW: f64 = 0.3;
/// ... while the cavity is smaller than this.
const ROOMY_CAVITY: usize = 24;
/// The worst quality must rise by at least this much.
const GAIN: f64 = 1e-6;

/// Try to replace the tet in slot `t` (and a cavity around it) by the cone from a new node.
pub fn insert_node_for(cx: &mut Complex, t: u32) -> bool {
    if !cx.alive[t as usize] {
        return false;
    }
    let tv = cx.tets[t as usize];
    let seed = seed_of(cx, t);
    let mut ids: Vec<u32> = seed.iter().flat_map(|&s| cx.tets[s as usize]).collect();
    ids.sort_unstable();
    ids.dedup();
    let mean = centroid(ids.iter().map(|&i| cx.nodes[i as usize]));
    let ct = centroid(tv.iter().map(|&i| cx.nodes[i as usize]));
    let mid = [0, 1, 2].map(|m| 0.5 * (mean[m] + ct[m]));
    let scale = {
        let [a, b, c, d] = tv.map(|i| cx.nodes[i as usize]);
        (dist(&a, &b) + dist(&a, &c) + dist(&a, &d) + dist(&b, &c) + dist(&b, &d) + dist(&c, &d))
            / 6.0
    };
    // Over each protected face of the tet, a point at a good apex height: there a new node can
    // take the face over from an apex that other tets hold in a poor place.
    let mut starts = vec![mean, mid, ct];
    for f in outward_faces(tv) {
        if cx.face_protected(f) {
            let fc = centroid(f.iter().map(|&i| cx.nodes[i as usize]));
            let [a, b, c] = f.map(|i| cx.nodes[i as usize]);
            let h = APEX_HEIGHT * (dist(&a, &b) + dist(&b, &c) + dist(&c, &a)) / 3.0;
            starts.extend(push_inside(cx, f, fc, h));
            // Half-way to the apex's level: in a thin layer the apex sits on the other side,
            // often beside the face rather than over it.
            if let Some(&apex) = tv.iter().find(|v| !f.contains(v))
                && let Some(on) = push_inside(cx, f, cx.nodes[apex as usize], 0.0)
            {
                let depth = dist(&on, &cx.nodes[apex as usize]);
                starts.extend(push_inside(cx, f, fc, 0.5 * depth));
            }
        }
    }
    for p0 in starts {
        let mut p = p0;
        // Each push goes half as deep as the one before, so that between two close protected
        // faces (a thin layer's top and bottom) the point settles between them.
        let mut push = PUSH * scale;
        for _ in 0..MAX_PUSHES {
            // An undone attempt re-creates the tets in other slots: find the bad one again.
            let Some(t) = cx.node_tets[tv[0] as usize]
                .iter()
                .copied()
                .find(|&u| cx.tets[u as usize] == tv)
            else {
                return false;
            };
            match try_insert(cx, &seed_of(cx, t), p) {
                Attempt::Done => return true,
                Attempt::Failed => break,
                Attempt::Behind(f) => match push_inside(cx, f, p, push) {
                    Some(q) => {
                        p = q;
                        push *= 0.5;
                    }
                    None => break,
                },
            }
        }
    }
    false
}

/// Height of the start point over a protected face, in mean edge lengths of the face.
const APEX_HEIGHT: f64 = 0.4;
/// Insertion attempts per starting point (the point is pushed off a protected face between).
const MAX_PUSHES: usize = 6;
/// How far inside a protected face a point is first pushed, in mean edge lengths of the bad
/// tet.
const PUSH: f64 = 0.2;

enum Attempt {
    Done,
    Failed,
    /// The point does not see this protected hull face from inside.
    Behind([u32; 3]),
}

/// `p` moved to `offset` inside the plane of the (outward) hull face `f`.
fn push_inside(cx: &Complex, f: [u32; 3], p: P, offset: f64) -> Option<P> {
    let [a, b, c] = f.map(|i| cx.nodes[i as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let nl = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    // Written so that a NaN length is refused too.
    if nl.is_nan() || nl <= 0.0 || !nl.is_finite() {
        return None;
    }
    let n = n.map(|x| x / nl);
    let out = (p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2];
    let q = [0, 1, 2].map(|m| p[m] - n[m] * (out + offset));
    q.iter().all(|x| x.is_finite()).then_some(q)
}

/// The tet `t` and its neighbours across unprotected faces.
fn seed_of(cx: &Complex, t: u32) -> Vec<u32> {
    let mut seed = vec![t];
    for f in outward_faces(cx.tets[t as usize]) {
        if !cx.face_protected(f)
            && let Some(u) = cx.across(f, t)
        {
            seed.push(u);
        }
    }
    seed
}

fn centroid(it: impl Iterator<Item = P>) -> P {
    let mut s = [0.0; 3];
    let mut n = 0.0;
    for p in it {
        for m in 0..3 {
            s[m] += p[m];
        }
        n += 1.0;
    }
    s.map(|x| x / n)
}

/// Grow the cavity from `seed` until `p` sees its hull, insert, smooth; undo if not better.
fn try_insert(cx: &mut Complex, seed: &[u32], p: P) -> Attempt {
    if !p.iter().all(|x| x.is_finite()) {
        return Attempt::Failed;
    }
    let mut cavity = seed.to_vec();
    let mut hull = Hull::of(cx, &cavity);
    let hull = loop {
        let blocked = hull.faces().find(|f| {
            let [a, b, c] = f.map(|i| cx.nodes[i as usize]);
            orient3d(&a, &c, &b, &p) != Orientation::Positive
        });
        // Once `p` sees the hull, unprotected faces that would make a poor cone tet are
        // opened too, to give the new node room.
        let poor = || {
            hull.faces().find(|f| {
                let [a, b, c] = f.map(|i| cx.nodes[i as usize]);
                !cx.face_protected(**f)
                    && cavity.len() < ROOMY_CAVITY
                    && shape(&a, &c, &b, &p) < ROOMY_BELOW
            })
        };
        let Some(&f) = blocked.or_else(poor) else {
            break hull.into_faces();
        };
        if cx.face_protected(f) {
            return Attempt::Behind(f);
        }
        if cavity.len() >= MAX_CAVITY {
            return Attempt::Failed;
        }
        let Some(u) = cx.node_tets[f[0] as usize].iter().copied().find(|&u| {
            let uv = cx.tets[u as usize];
            uv.contains(&f[1]) && uv.contains(&f[2]) && !cavity.contains(&u)
        }) else {
            return Attempt::Failed;
        };
        cavity.push(u);
        hull.add(cx, u);
    };
    // No protected face inside the cavity, no fixed node swallowed.
    let mut faces: Vec<[u32; 3]> = cavity
        .iter()
        .flat_map(|&c| outward_faces(cx.tets[c as usize]).map(sorted3))
        .collect();
    faces.sort_unstable();
    for w in faces.windows(2) {
        if w[0] == w[1] && cx.face_protected(w[0]) {
            return Attempt::Failed;
        }
    }
    if cx.line_edges && swallows_protected_edge(cx, &cavity, &hull) {
        return Attempt::Failed;
    }
    let mut on_hull: Vec<u32> = hull.iter().flatten().copied().collect();
    on_hull.sort_unstable();
    on_hull.dedup();
    for &c in &cavity {
        for v in cx.tets[c as usize] {
            if on_hull.binary_search(&v).is_err() && (v as usize) < cx.n_fixed {
                return Attempt::Failed;
            }
        }
    }
    let old_tets: Vec<[u32; 4]> = cavity.iter().map(|&c| cx.tets[c as usize]).collect();
    let old_q = old_tets
        .iter()
        .map(|&t| cx.quality(t))
        .fold(f64::INFINITY, f64::min);
    let mut touched: Vec<u32> = old_tets.iter().flatten().copied().collect();
    touched.sort_unstable();
    touched.dedup();
    let saved = cx.stamps(&touched);
    for &c in &cavity {
        cx.remove_tet(c);
    }
    let v = cx.add_node(p);
    let mut new_ids = Vec::with_capacity(hull.len());
    for f in &hull {
        new_ids.push(cx.add_tet([f[0], f[2], f[1], v]));
    }
    smooth_node(cx, v);
    smooth_node(cx, v);
    let new_q = cx.node_tets[v as usize]
        .iter()
        .map(|&t| cx.shape[t as usize])
        .fold(f64::INFINITY, f64::min);
    if new_q > old_q + GAIN {
        return Attempt::Done;
    }
    for id in new_ids {
        cx.remove_tet(id);
    }
    cx.pop_node();
    for t in old_tets {
        cx.add_tet(t);
    }
    // Nothing changed: a later round may skip what was tried here.
    cx.restore_stamps(&touched, &saved);
    Attempt::Failed
}

/// The hull of a growing cavity, kept as [`Complex::hull_of`] makes it (outward faces ordered by
/// their sorted nodes): a tet added toggles its faces, since in a tet complex a face belongs to
/// at most two tets. Recomputing the hull after each added tet sorted every face again.
struct Hull {
    /// (sorted nodes, outward face), ordered by the first.
    faces: Vec<([u32; 3], [u32; 3])>,
}

impl Hull {
    fn of(cx: &Complex, set: &[u32]) -> Hull {
        let mut hull = Hull { faces: Vec::new() };
        for &t in set {
            hull.add(cx, t);
        }
        hull
    }

    fn add(&mut self, cx: &Complex, t: u32) {
        for f in outward_faces(cx.tets[t as usize]) {
            let key = sorted3(f);
            match self.faces.binary_search_by(|(k, _)| k.cmp(&key)) {
                Ok(i) => {
                    self.faces.remove(i);
                }
                Err(i) => self.faces.insert(i, (key, f)),
            }
        }
    }

    fn faces(&self) -> impl Iterator<Item = &[u32; 3]> {
        self.faces.iter().map(|(_, f)| f)
    }

    fn into_faces(self) -> Vec<[u32; 3]> {
        self.faces.into_iter().map(|(_, f)| f).collect()
    }
}

/// Whether a protected edge of the cavity's tets is not an edge of its hull: the cone would
/// remove it (a piece of a segment, which no protected face holds and keeps).
fn swallows_protected_edge(cx: &Complex, cavity: &[u32], hull: &[[u32; 3]]) -> bool {
    let pair = |a: u32, b: u32| [a.min(b), a.max(b)];
    let mut kept: Vec<[u32; 2]> = hull
        .iter()
        .flat_map(|f| [pair(f[0], f[1]), pair(f[1], f[2]), pair(f[2], f[0])])
        .collect();
    kept.sort_unstable();
    kept.dedup();
    cavity.iter().any(|&c| {
        let t = cx.tets[c as usize];
        [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
            .into_iter()
            .any(|(i, j)| {
                cx.edge_protected(t[i], t[j]) && kept.binary_search(&pair(t[i], t[j])).is_err()
            })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cavity's hull grown tet by tet is the hull `Complex::hull_of` computes, in its order.
    #[test]
    fn a_hull_grown_tet_by_tet_is_the_complexs_hull_of_the_same_tets() {
        // A 3 × 3 × 3 grid of cubes, each cut into six tets round its main diagonal.
        let n = 3usize;
        let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
        let mut nodes = Vec::new();
        for k in 0..=n {
            for j in 0..=n {
                for i in 0..=n {
                    nodes.push([i as f64, j as f64, k as f64 * 1.1]);
                }
            }
        }
        let cx0 = Complex::new(nodes.clone(), vec![], 0, std::iter::empty());
        let mut tets = Vec::new();
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let c = |d: [usize; 3]| id(i + d[0], j + d[1], k + d[2]);
                    let (a, h) = (c([0, 0, 0]), c([1, 1, 1]));
                    let ring = [
                        [1, 0, 0],
                        [1, 1, 0],
                        [0, 1, 0],
                        [0, 1, 1],
                        [0, 0, 1],
                        [1, 0, 1],
                    ];
                    for r in 0..6 {
                        let (b, d) = (c(ring[r]), c(ring[(r + 1) % 6]));
                        let t = if cx0.positive([a, b, d, h]) {
                            [a, b, d, h]
                        } else {
                            [a, d, b, h]
                        };
                        tets.push(t);
                    }
                }
            }
        }
        let cx = Complex::new(nodes, tets.clone(), 0, std::iter::empty());
        // Growing sets in a scattered order, checked after every tet.
        let order: Vec<u32> = (0..tets.len() as u32)
            .map(|i| (i * 37) % tets.len() as u32)
            .collect();
        let mut hull = Hull::of(&cx, &order[..1]);
        for m in 2..=order.len() {
            hull.add(&cx, order[m - 1]);
            let faces: Vec<[u32; 3]> = hull.faces().copied().collect();
            assert_eq!(faces, cx.hull_of(&order[..m]), "after {m} tets");
        }
        assert_eq!(hull.into_faces().len(), 2 * 6 * n * n);
    }

    /// A flat tet of four fixed nodes inside a box of fixed nodes: only a new node can fix it.
    #[test]
    fn a_flat_tet_of_fixed_nodes_is_replaced_by_a_cone_from_a_new_node() {
        // Octahedron-like: a flat quad 0,1,2,3 (slightly non-planar) split into two tets by
        // the edge 0-2 ... realised as one flat tet [0,1,2,3] with caps 4 (above) and 5 (below).
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.003],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.003],
            [0.5, 0.5, 0.7],
            [0.5, 0.5, -0.7],
        ];
        let cx0 = Complex::new(nodes.clone(), vec![], 0, std::iter::empty());
        // Flat tet with edges 0-2 (low) and 1-3 (high): [0,2,1,3] or [0,2,3,1], whichever is
        // positive; then the four faces are capped by 4 and 5.
        let flat = if cx0.positive([0, 2, 1, 3]) {
            [0, 2, 1, 3]
        } else {
            [0, 2, 3, 1]
        };
        let mut tets = vec![flat];
        for f in outward_faces(flat) {
            // Cap each face with the apex on its outer side.
            for apex in [4u32, 5] {
                let t = [f[0], f[1], f[2], apex];
                if cx0.positive(t) {
                    tets.push(t);
                    break;
                }
            }
        }
        assert_eq!(tets.len(), 5);
        let hull: Vec<[u32; 3]> = {
            let cx = Complex::new(nodes.clone(), tets.clone(), 6, std::iter::empty());
            cx.hull_of(&(0..5).collect::<Vec<u32>>())
        };
        let mut cx = Complex::new(nodes, tets, 6, hull.clone().into_iter());
        let before = cx.quality(cx.tets[0]);
        assert!(before < 0.05);
        assert!(insert_node_for(&mut cx, 0));
        let (nodes, tets) = cx.into_parts();
        assert_eq!(nodes.len(), 7);
        let cx = Complex::new(nodes, tets.clone(), 6, std::iter::empty());
        assert!(tets.iter().all(|&t| cx.positive(t)));
        let worst = tets.iter().map(|&t| cx.quality(t)).fold(1.0, f64::min);
        assert!(worst > before + 0.1, "{before} -> {worst}");
        // The hull is unchanged.
        let mut h0: Vec<[u32; 3]> = hull.iter().map(|&f| sorted3(f)).collect();
        let mut h1: Vec<[u32; 3]> = cx
            .hull_of(&(0..tets.len() as u32).collect::<Vec<u32>>())
            .into_iter()
            .map(sorted3)
            .collect();
        h0.sort_unstable();
        h1.sort_unstable();
        assert_eq!(h0, h1);
    }
}
