//! Exact contact between closed triangles and segments that may share vertices: do two of them
//! meet anywhere other than in what they share?
//!
//! Sharing is by identity, not by position: a triangle or segment carries its vertices' ids
//! beside their points, and two of them may meet exactly in the vertices (or the edge) whose ids
//! they share; the caller passes the same point for the same id. Any other contact counts,
//! including two distinct ids at one position. The tet mesher passes node indices and surface
//! validation canonical vertices (coincident vertices merged), so both judge by the same rules:
//! a shared edge counts only when the two triangles lie in one plane on the same side of it, a
//! shared vertex only when the triangles also meet elsewhere.
//!
//! Every decision is a sign of `orient3d` or `orient2d`: no epsilon, no constructed point.
//! Coplanar configurations are projected on an axis plane where a triangle keeps a non-zero area
//! (dropping a coordinate is exact), and collinear overlaps are settled by exact coordinate
//! comparisons. For non-degenerate triangles the answer does not depend on the arguments' order.

use crate::predicates::{Orientation, orient2d, orient3d_shortcut as orient3d};

type P = [f64; 3];
type P2 = [f64; 2];

/// How two triangles meet beyond what they share.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    None,
    /// They cross or touch beyond what they share, not in one plane.
    Crossing,
    /// They lie in one plane and overlap beyond what they share.
    CoplanarOverlap,
}

/// A triangle: its vertices' ids and points.
#[derive(Clone, Copy, Debug)]
pub struct Tri<'a> {
    pub ids: [u32; 3],
    pub pts: [&'a P; 3],
}

/// A segment: its ends' ids and points.
#[derive(Clone, Copy, Debug)]
pub struct Seg<'a> {
    pub ids: [u32; 2],
    pub pts: [&'a P; 2],
}

impl<'a> Tri<'a> {
    /// The triangle whose ids index `pts`.
    pub fn of(ids: [u32; 3], pts: &'a [P]) -> Self {
        Tri {
            ids,
            pts: ids.map(|i| &pts[i as usize]),
        }
    }

    fn has(&self, id: u32) -> bool {
        self.ids.contains(&id)
    }

    fn edge(&self, e: usize) -> Seg<'a> {
        let f = (e + 1) % 3;
        Seg {
            ids: [self.ids[e], self.ids[f]],
            pts: [self.pts[e], self.pts[f]],
        }
    }

    /// The exact sides of `other`'s vertices relative to this triangle's plane.
    pub fn sides_of(&self, other: &Tri) -> [Orientation; 3] {
        let [a, b, c] = self.pts;
        other.pts.map(|p| orient3d(a, b, c, p))
    }

    /// The points rotated so that vertex `id` (one of the triangle's) comes first.
    fn starting_at(&self, id: u32) -> [&'a P; 3] {
        let i = self.ids.iter().position(|&v| v == id).unwrap_or(0);
        [0, 1, 2].map(|k| self.pts[(i + k) % 3])
    }
}

impl<'a> Seg<'a> {
    /// The segment whose ids index `pts`.
    pub fn of(ids: [u32; 2], pts: &'a [P]) -> Self {
        Seg {
            ids,
            pts: ids.map(|i| &pts[i as usize]),
        }
    }

    /// The other end than `id`, which is one of the segment's ends.
    fn other_end(&self, id: u32) -> &'a P {
        if self.ids[0] == id {
            self.pts[1]
        } else {
            self.pts[0]
        }
    }
}

/// How triangles `t` and `u` meet beyond the vertices they share. Two triangles with the same
/// three ids do not meet (what a repeated face means is the caller's decision).
pub fn triangle_contact(t: &Tri, u: &Tri) -> Contact {
    triangle_contact_with(t, u, t.sides_of(u))
}

/// [`triangle_contact`] when the caller already knows `ou`, the sides of `u`'s vertices
/// relative to `t`'s plane (`t.sides_of(u)`).
pub fn triangle_contact_with(t: &Tri, u: &Tri, ou: [Orientation; 3]) -> Contact {
    let shared = t.ids.iter().filter(|&&i| u.has(i)).count();
    if shared == 3 || apart(&ou, u, t) || apart(&u.sides_of(t), t, u) {
        return Contact::None;
    }
    if ou.iter().all(|&o| o == Orientation::Zero) {
        return match coplanar_overlap(t, u) {
            true => Contact::CoplanarOverlap,
            false => Contact::None,
        };
    }
    // Triangles in two planes sharing an edge meet exactly in that edge.
    if shared == 2 || !edges_meet(t, u) {
        return Contact::None;
    }
    Contact::Crossing
}

/// All vertices of `x` off `other`'s plane are strictly on one side and those on it are shared
/// with `other`: `x` meets that plane only in shared vertices. `o` are the sides of `x`'s
/// vertices.
fn apart(o: &[Orientation; 3], x: &Tri, other: &Tri) -> bool {
    let mut side = Orientation::Zero;
    for (&s, &id) in o.iter().zip(&x.ids) {
        if s == Orientation::Zero {
            if !other.has(id) {
                return false;
            }
        } else if side == Orientation::Zero {
            side = s;
        } else if s != side {
            return false;
        }
    }
    side != Orientation::Zero
}

/// An edge of either triangle meets the other beyond a shared vertex.
fn edges_meet(t: &Tri, u: &Tri) -> bool {
    (0..3).any(|e| edge_meets(&t.edge(e), u) || edge_meets(&u.edge(e), t))
}

/// Segment `e` meets triangle `t` anywhere but in the vertices they share; a segment that is an
/// edge of `t` meets it along that edge.
pub fn segment_meets_triangle(e: &Seg, t: &Tri) -> bool {
    (t.has(e.ids[0]) && t.has(e.ids[1])) || edge_meets(e, t)
}

/// Segment `e` meets triangle `t` other than at a vertex they share (an edge of `t` does not).
fn edge_meets(e: &Seg, t: &Tri) -> bool {
    let [p, q] = e.pts;
    match [t.has(e.ids[0]), t.has(e.ids[1])] {
        [true, true] => false,
        [false, false] => segment_meets_closed_triangle(p, q, t.pts),
        [true, false] => leaves_vertex_into(t.starting_at(e.ids[0]), q),
        [false, true] => leaves_vertex_into(t.starting_at(e.ids[1]), p),
    }
}

/// The segment from `a` (the first of the triangle `[a, e, f]`) to `w` meets the triangle
/// beyond `a`: it lies in the triangle's plane, within the angle at `a`.
fn leaves_vertex_into([a, e, f]: [&P; 3], w: &P) -> bool {
    if orient3d(a, e, f, w) != Orientation::Zero {
        return false;
    }
    let Some(ax) = plane_axis(a, e, f) else {
        return false;
    };
    let [a2, e2, f2, w2] = [a, e, f, w].map(|p| project(p, ax));
    let s = s2(&a2, &e2, &f2);
    s2(&a2, &e2, &w2) * s >= 0 && s2(&a2, &f2, &w2) * s <= 0
}

/// Closed segment `pq` meets the closed triangle `abc` (any contact counts).
fn segment_meets_closed_triangle(p: &P, q: &P, [a, b, c]: [&P; 3]) -> bool {
    let op = orient3d(a, b, c, p);
    let oq = orient3d(a, b, c, q);
    if op == oq && op != Orientation::Zero {
        return false;
    }
    if op == Orientation::Zero && oq == Orientation::Zero {
        return coplanar_segment_meets_triangle(p, q, [a, b, c]);
    }
    let s = [(a, b), (b, c), (c, a)].map(|(x, y)| orient3d(p, q, x, y));
    !(s.contains(&Orientation::Positive) && s.contains(&Orientation::Negative))
}

/// Closed segment `pq` meets the closed triangle `abc`, all four in one plane.
fn coplanar_segment_meets_triangle(p: &P, q: &P, [a, b, c]: [&P; 3]) -> bool {
    let Some(ax) = plane_axis(a, b, c) else {
        return false;
    };
    let [p, q, a, b, c] = [p, q, a, b, c].map(|x| project(x, ax));
    point_in_triangle_2d(&p, &a, &b, &c)
        || point_in_triangle_2d(&q, &a, &b, &c)
        || [(a, b), (b, c), (c, a)]
            .iter()
            .any(|(x, y)| segments_meet_2d(&p, &q, x, y))
}

/// Two triangles in one plane overlap beyond what they share: a vertex of one not shared lies
/// in the other, or two edges meet other than at a shared end. A degenerate `t` overlaps.
fn coplanar_overlap(t: &Tri, u: &Tri) -> bool {
    let [a, b, c] = t.pts;
    let Some(ax) = plane_axis(a, b, c) else {
        return true;
    };
    let t2 = t.pts.map(|p| project(p, ax));
    let u2 = u.pts.map(|p| project(p, ax));
    vertex_inside(t, &t2, u, &u2)
        || vertex_inside(u, &u2, t, &t2)
        || (0..3).any(|i| (0..3).any(|j| edges_meet_2d(edge_2d(t, &t2, i), edge_2d(u, &u2, j))))
}

/// A vertex of `x` that `y` does not share lies in the closed `y` (both projected).
fn vertex_inside(x: &Tri, x2: &[P2; 3], y: &Tri, y2: &[P2; 3]) -> bool {
    (0..3).any(|i| !y.has(x.ids[i]) && point_in_triangle_2d(&x2[i], &y2[0], &y2[1], &y2[2]))
}

/// The projected edge `i` of `x`: its ends' ids and points.
fn edge_2d(x: &Tri, x2: &[P2; 3], i: usize) -> ([u32; 2], [P2; 2]) {
    let j = (i + 1) % 3;
    ([x.ids[i], x.ids[j]], [x2[i], x2[j]])
}

/// Two projected edges meet other than at a shared end.
fn edges_meet_2d((e, ep): ([u32; 2], [P2; 2]), (f, fp): ([u32; 2], [P2; 2])) -> bool {
    match [f.contains(&e[0]), f.contains(&e[1])] {
        [true, true] => false,
        [false, false] => segments_meet_2d(&ep[0], &ep[1], &fp[0], &fp[1]),
        common => {
            let (v, x) = if common[0] { (0, 1) } else { (1, 0) };
            let y = if f[0] == e[v] { fp[1] } else { fp[0] };
            same_ray_2d(&ep[v], &ep[x], &y)
        }
    }
}

/// Segments `e` and `f` meet anywhere but in an end they share (the same segment twice meets
/// itself everywhere).
pub fn segments_meet(e: &Seg, f: &Seg) -> bool {
    let shared: Vec<u32> = e
        .ids
        .iter()
        .copied()
        .filter(|v| f.ids.contains(v))
        .collect();
    match shared[..] {
        [] => closed_segments_meet(e.pts[0], e.pts[1], f.pts[0], f.pts[1]),
        [v] => {
            let at = if e.ids[0] == v { e.pts[0] } else { e.pts[1] };
            same_ray_3d(at, e.other_end(v), f.other_end(v))
        }
        _ => true,
    }
}

/// Segments `v x` and `v y` overlap beyond `v` (collinear, same direction), or an end of one
/// coincides with `v` or the other's end.
fn same_ray_3d(v: &P, x: &P, y: &P) -> bool {
    if x == v || y == v || x == y {
        return true;
    }
    if !collinear(v, x, y) {
        return false;
    }
    let k = (0..3).find(|&k| x[k] != v[k]).unwrap_or(0);
    (x[k] > v[k]) == (y[k] > v[k])
}

/// Closed segments `pq` and `rs` (each of two distinct points) meet: coplanar, then compared in
/// a coordinate projection that is one to one on their plane (or line).
fn closed_segments_meet(p: &P, q: &P, r: &P, s: &P) -> bool {
    if orient3d(p, q, r, s) != Orientation::Zero {
        return false;
    }
    let axis = [(p, q, r), (p, q, s), (r, s, p), (r, s, q)]
        .into_iter()
        .find_map(|(a, b, c)| plane_axis(a, b, c))
        // All four on one line: drop an axis along which it does not run.
        .or_else(|| (0..3).rev().find(|&k| project(p, k) != project(q, k)));
    let Some(ax) = axis else { return true };
    let [p, q, r, s] = [p, q, r, s].map(|x| project(x, ax));
    segments_meet_2d(&p, &q, &r, &s)
}

/// The coordinate axis to drop so that the triangle `abc` projects to a non-degenerate one, or
/// `None` for a degenerate triangle. The float normal suggests the axis; `orient2d` confirms it.
pub fn plane_axis(a: &P, b: &P, c: &P) -> Option<usize> {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        (u[1] * v[2] - u[2] * v[1]).abs(),
        (u[2] * v[0] - u[0] * v[2]).abs(),
        (u[0] * v[1] - u[1] * v[0]).abs(),
    ];
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| n[j].total_cmp(&n[i]).then(i.cmp(&j)));
    order
        .into_iter()
        .find(|&k| s2(&project(a, k), &project(b, k), &project(c, k)) != 0)
}

/// The triangle `abc` is degenerate: its points are collinear or coincide.
pub fn triangle_is_degenerate(a: &P, b: &P, c: &P) -> bool {
    plane_axis(a, b, c).is_none()
}

/// The three points lie on one line (or coincide): the three components of `(b-a)×(c-a)` are
/// the `orient2d` of the three coordinate projections.
pub fn collinear(a: &P, b: &P, c: &P) -> bool {
    (0..3).all(|k| s2(&project(a, k), &project(b, k), &project(c, k)) == 0)
}

/// `p` without its coordinate `axis`, the other two in cyclic order.
pub fn project(p: &P, axis: usize) -> P2 {
    [p[(axis + 1) % 3], p[(axis + 2) % 3]]
}

/// The sign of `orient2d`.
fn s2(a: &P2, b: &P2, c: &P2) -> i32 {
    orient2d(a, b, c).sign()
}

/// Closed segments meet in the plane (touching counts).
fn segments_meet_2d(p1: &P2, p2: &P2, q1: &P2, q2: &P2) -> bool {
    let d1 = s2(p1, p2, q1);
    let d2 = s2(p1, p2, q2);
    if d1 == 0 && d2 == 0 {
        return collinear_segments_overlap(p1, p2, q1, q2);
    }
    d1 * d2 <= 0 && s2(q1, q2, p1) * s2(q1, q2, p2) <= 0
}

/// Collinear segments overlap: their projections on an axis along which they vary do.
fn collinear_segments_overlap(p1: &P2, p2: &P2, q1: &P2, q2: &P2) -> bool {
    let ax = if p1[0] != p2[0] || q1[0] != q2[0] {
        0
    } else {
        1
    };
    let (pa, pb) = min_max(p1[ax], p2[ax]);
    let (qa, qb) = min_max(q1[ax], q2[ax]);
    pa <= qb && qa <= pb
}

fn min_max(a: f64, b: f64) -> (f64, f64) {
    if a <= b { (a, b) } else { (b, a) }
}

/// `p` lies in the closed non-degenerate triangle `abc`.
fn point_in_triangle_2d(p: &P2, a: &P2, b: &P2, c: &P2) -> bool {
    let s = s2(a, b, c);
    s2(a, b, p) * s >= 0 && s2(b, c, p) * s >= 0 && s2(c, a, p) * s >= 0
}

/// Segments `v x` and `v y` overlap beyond `v` (collinear, same direction).
fn same_ray_2d(v: &P2, x: &P2, y: &P2) -> bool {
    if s2(v, x, y) != 0 {
        return false;
    }
    let ax = if x[0] != v[0] { 0 } else { 1 };
    (x[ax] > v[ax]) == (y[ax] > v[ax]) && y[ax] != v[ax]
}

/// The closed segment `ab` meets the closed axis-aligned box `[lo, hi]` (separating axes: the
/// box's three, and in each coordinate projection the segment's line with the box's corners
/// strictly on one side).
pub fn segment_meets_box(a: &P, b: &P, lo: &P, hi: &P) -> bool {
    let apart_on_axis = |k: usize| {
        let (s0, s1) = min_max(a[k], b[k]);
        s1 < lo[k] || hi[k] < s0
    };
    !(0..3).any(apart_on_axis) && !(0..3).any(|ax| line_misses_rectangle(a, b, lo, hi, ax))
}

/// In the projection dropping `ax`, every corner of the box lies strictly on one side of the
/// line `ab`.
fn line_misses_rectangle(a: &P, b: &P, lo: &P, hi: &P, ax: usize) -> bool {
    let (a2, b2) = (project(a, ax), project(b, ax));
    let (l2, h2) = (project(lo, ax), project(hi, ax));
    let corners = [
        [l2[0], l2[1]],
        [h2[0], l2[1]],
        [l2[0], h2[1]],
        [h2[0], h2[1]],
    ];
    let sides = corners.map(|c| s2(&a2, &b2, &c));
    sides.iter().all(|&x| x > 0) || sides.iter().all(|&x| x < 0)
}

#[cfg(test)]
mod tests;
